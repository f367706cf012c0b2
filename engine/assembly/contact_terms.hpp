#pragma once
// The Assemble stage of each open-close iteration: each block row's diagonal
// block and right-hand side, its own terms (block_terms.hpp) plus the
// springs and friction of its contacts in their current states; the
// couplings between blocks stay with the matrix-free operator
// (contact_operator.hpp).
#include <span>
#include <vector>

#include "assembly/block_terms.hpp"
#include "assembly/contact_operator.hpp"
#include "contact/open_close.hpp"

namespace dda {

// Sets every contact's springs in `system` (normal on a closed contact, shear
// too on a locked one), then gathers the rows: all of them, or (all_rows
// false) only those with a contact whose state changed in the last check or
// a sliding contact (whose friction follows the latest normal force); the
// others would come out the same to the bit. Writes rhs and, per row,
// whether it was rewritten (row_reassembled).
void assemble_contact_rows(std::span<const Contact> contacts, const ContactLinearisation& lin,
                           const OpenCloseState& open_close, const ContactParameters& p, const BlockTerms& own,
                           bool all_rows, ContactOperator& system, VecX& rhs, std::vector<char>& row_reassembled);

}  // namespace dda
