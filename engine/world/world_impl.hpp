#pragma once
// Private to the World: scratch buffers that live from step to step (so the
// step loop does not allocate) and the reasons a step attempt is rejected.
#include <tbb/task_arena.h>

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "assembly/contact_operator.hpp"
#include "contact/contact_law.hpp"
#include "core/symmetric6.hpp"
#include "solver/linear_solver.hpp"
#include "world/world.hpp"

namespace dda {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Why a step attempt was rejected (the step is then redone with a smaller Δt).
enum class Rejection : int {
  None,
  OpenCloseUnsettled,
  DisplacementTooLarge,
  PenetrationTooDeep,
  SolverNotConverged,
  BlockInverted,
  BeyondContactRange
};

inline const char* describe(Rejection r) {
  switch (r) {
    case Rejection::None:
      return "accepted";
    case Rejection::OpenCloseUnsettled:
      return "the open-close iteration did not settle";
    case Rejection::DisplacementTooLarge:
      return "a vertex moved more than the g2 bound in one step";
    case Rejection::PenetrationTooDeep:
      return "a contact penetrated deeper than the g2 bound";
    case Rejection::SolverNotConverged:
      return "the linear solver did not converge";
    case Rejection::BlockInverted:
      return "a block would turn inside out (its area would become zero or negative)";
    case Rejection::BeyondContactRange:
      return "a vertex moved more than the contact range allows in one step (range / 2.5)";
  }
  return "?";
}

// Scratch that lives from step to step so the loop does not allocate.
struct World::Impl {
  // Resolved controls (auto values filled in).
  double g0 = 0, g1 = 0;
  std::unique_ptr<tbb::task_arena> arena;
  int arena_threads = -1;

  ContactOperator system;                // the matrix of the step, matrix-free off the diagonal
  std::unique_ptr<LinearSolver> solver;  // made on the first step (make_linear_solver)
  VecX rhs, solution;
  std::vector<Symmetric6> own_k;     // block terms of the diagonal (elastic, inertia, fixed points)
  std::vector<Vec6> own_f;           // block terms of the right-hand side
  std::vector<Mat3> elastic;         // per rock material
  std::vector<double> tan_friction;  // tan φ per joint material (the contact law needs it per contact)

  // Per contact, parallel to World::contacts_.
  std::vector<ContactGradients> gradients;  // the contacts' linearisation (contact_law.hpp), in two parts
  std::vector<ContactOffsets> offsets;
  std::vector<ContactIterate> iterate;
  std::vector<char> contact_changed;  // by the last open-close check (its rows are reassembled)
  std::vector<char> row_reassembled;  // per block row: rewritten by the last assembly (matrix or right-hand side)
  std::vector<ContactIterationState> saved_states;  // at the start of the step (for a redo)

  bool first_detection = true;  // contacts found before the first step are intact joints
  // The contact list's search state (see detect_contacts).
  std::vector<Vec2> detected_vertices;
  std::vector<double> rotation_since_detection;
  double detected_range = 0;
  long detections = 0;
  double largest_displacement =
      0;  // of the last solve's vertices (the step's g2 ratio; widens the automatic contact range)
  BlockId inverted_block = -1;  // the first block the last rejected attempt would have turned inside out
  // check_block_motion's: per block, whether its outline turned inside out;
  // per vertex, its motion in the solve (what update() adds once the step is
  // accepted).
  std::vector<char> block_inverted;
  std::vector<Vec2> vertex_motion;

  int open_close_iterations = 0, cg_iterations = 0, patch_iterations = 0;
  double t_assemble = 0, t_solve = 0, t_check = 0;
};

}  // namespace dda
