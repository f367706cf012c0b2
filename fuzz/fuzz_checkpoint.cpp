// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// libFuzzer target: the checkpoint loader (dda.load, dda run --restart). The
// bytes are a checkpoint file; it must load and step, or be refused with a
// dda::Error (or a script error). A crash, a sanitizer report, another
// exception or a hang is a finding.
//
// A checkpoint's checksums catch accidents only: anyone who edits a file can
// recompute them. So the custom mutator below mutates the payload with
// libFuzzer's own mutations and then seals it again (its size and both
// CRCs, checkpoint_file), and the loader sees crafted contents, not just
// checksum failures; one mutation in 16 is left unsealed (the header's own
// checks). Seeds: real checkpoints (first-order, meshed, CHOLMOD,
// earthquake; fuzz/make_checkpoint_seeds.lua writes them).
//
// A model that loads takes up to three steps on one thread. The controls
// that set a step's effort are capped first (6 open-close iterations, 3 step
// cuts, 300 CG iterations), so that one input does not outlast libFuzzer's
// timeout on a shared machine: a mutated model whose CG never converges runs
// every solve to the cap (a multigrid wall took over a minute at a cap of
// 5000 and 15 s at 1000 under the sanitizers). Size and effort limits are the
// controls' own business, not the loader's. Memory is capped at 1 GB through
// the estimates' own limit (set_own_memory_limit), under libFuzzer's RSS limit.
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "lua_support.hpp"
#include "model.hpp"
#include "scripting.hpp"
#include "world/checkpoint.hpp"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

namespace {

constexpr int kSteps = 3;

void cap_step_effort(dda::Controls& c) {
  c.threads = 1;
  c.open_close_limit = std::min(c.open_close_limit, 6);
  c.max_step_cuts = std::min(c.max_step_cuts, 3);
  if (c.cg_max_iterations == 0 || c.cg_max_iterations > 300) c.cg_max_iterations = 300;
}

lua_State* state() {
  static lua_State* L = [] {
    dda::script::Session s;
    s.quiet = true;
    s.threads = 1;
    return dda::script::new_state(std::move(s));
  }();
  return L;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  dda::set_own_memory_limit(1e9);
  return 0;
}

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  constexpr std::size_t header = dda::kCheckpointHeaderBytes;
  std::minstd_rand random(seed);
  if (size < header || max_size <= header || random() % 16 == 0) return LLVMFuzzerMutate(data, size, max_size);
  const std::size_t payload = LLVMFuzzerMutate(data + header, size - header, max_size - header);
  const std::string sealed = dda::checkpoint_file(std::string_view(reinterpret_cast<char*>(data) + header, payload));
  std::memcpy(data, sealed.data(), sealed.size());
  return sealed.size();
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  lua_State* L = state();
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    std::vector<std::string> warnings;
    auto m = dda::script::ScriptModel::from_checkpoint(dda::checkpoint_from_bytes(bytes, "fuzz checkpoint"),
                                                       "fuzz checkpoint", warnings);
    cap_step_effort(m->world().controls());
    for (int k = 0; k < kSteps; ++k) m->step(L);
  } catch (const dda::Error&) {
  } catch (const dda::script::ScriptError&) {}
  return 0;
}
