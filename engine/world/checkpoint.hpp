// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Checkpoint and restart: a World's whole state in one file, so that a run
// continues from it bit for bit as if it had never stopped (the same state
// hash at every later step, for any thread count), or branches from it.
//
// What it holds: the WorldState (controls, materials, blocks with their
// velocities, last displacements and stresses, loads and boundaries with
// their histories and state, tracked points, contacts with their states and
// shear references, the clock, the last step's figures) and what the Stepper
// carries from one step to the next (the contact search's range and what the
// list's staleness is measured from; the linear solver's preconditioner
// choice and kept inverses; the contact law's own per-contact history). Each
// type lists its fields once, beside their declarations (core/archive.hpp);
// the Stepper's list says what is left out and why.
//
// The file: a 32-byte header, then the payload.
//   magic "DDA-CKPT" | u32 format | u32 byte-order mark 0x01020304 |
//   u64 payload bytes | u32 CRC-32 of the payload | u32 CRC-32 of the 28
//   header bytes before it
// A file of another format is refused (there is no conversion: a state that
// lacks a field cannot continue exactly). Raise kCheckpointFormat with any
// change of what is written. Writes are atomic (FILE.part, every write
// checked, fsync, rename): a crash or a full disk leaves the previous file
// whole.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "world/world.hpp"

namespace dda {

// 1: the first format. 2: the contact search's watched aligned edges. 3: the
// contacts' lagged friction normal force (friction_lag). 4: the meshed
// solver's kept factors. 5: the energy budget's impact term (the landing
// law). 6: the age of the contacts' lagged friction. 7: whether a contact
// was a bonded joint when first found. 8: the contact law's part, with its
// per-contact history (the lagged friction's memory, out of the contacts).
// 9: the automatic solver choice's trial (its work against PCG's, and a
// trial given up in the step). 10: the wave model (its decision, the
// in-place meshing's map, the joints' lengths, the boundaries' edges and
// the edge targets). 11: the automatic solver choice judges one trial step
// (the PCG steps made, and whether one measures for the trial).
inline constexpr std::uint32_t kCheckpointFormat = 11;

// The World's state and `extra` (bytes its owner keeps beside it: the Lua
// layer's loads and monitors), as a checkpoint file's bytes.
std::string checkpoint_bytes(const World& world, std::string_view extra = {});

// A checkpoint file's parts: the header (with the payload's size and both
// checksums) and the payload. checkpoint_file() seals a payload into a file
// as checkpoint_bytes does: for the tests and the fuzz target, which craft
// payloads the checksums cannot catch (anyone can recompute them).
inline constexpr std::size_t kCheckpointHeaderBytes = 32;
std::string checkpoint_file(std::string_view payload);

struct Checkpoint {
  World world;
  std::string extra;
};
// Throws dda::Error naming `what` (e.g. "checkpoint 'run.ckpt'") and the
// cause: not a checkpoint, another format, truncated, damaged.
Checkpoint checkpoint_from_bytes(std::string_view bytes, const std::string& what);

// The same through a file. Throws dda::Error naming the file and the cause.
void save_checkpoint(const World& world, const std::filesystem::path& path, std::string_view extra = {});
Checkpoint load_checkpoint(const std::filesystem::path& path);

}  // namespace dda
