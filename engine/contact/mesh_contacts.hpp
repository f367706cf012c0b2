// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Contacts of meshed blocks stay on their outlines (block/mesh.hpp): the
// elements of one mesh share nodes and never contact each other, an edge
// inside a mesh carries no contact, and a node makes contacts only through
// an element that has an outline edge at it (an element meeting the outline
// at a corner alone would add a second spring to the node).
#include <utility>
#include <vector>

#include "block/blocks.hpp"
#include "contact/contact.hpp"

namespace dda {

// Drops the candidate pairs of two elements of one mesh (no-op without meshes).
void drop_pairs_inside_meshes(const Blocks& blocks, std::vector<std::pair<int, int>>& pairs);

// Drops the contacts on an edge inside a mesh, and those of a vertex neither
// of whose edges in its element lies on the mesh's outline (no-op without
// meshes), and the second contacts of an outline node (mesh_contacts.cpp).
// Keeps the order of the rest.
void drop_contacts_inside_meshes(const Blocks& blocks, std::vector<Contact>& contacts);

}  // namespace dda
