// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// libFuzzer target: the script loader. The bytes are a Lua script run the
// way `dda run` runs one (the dda module loaded, text only, a traceback
// handler); it must succeed or fail with a Lua error. A crash, a sanitizer
// report or a hang is a finding.
//
// The script runs sandboxed so that fuzzing cannot touch the machine: no io
// library, no os.execute / exit / remove / rename, print silenced, outputs
// (monitors, frames, VTU) in a private temporary folder, one thread. Lua code
// is stopped after 5 million instructions, stepping after 3 s (the Ctrl-C
// path: a watchdog raises SIGINT, the step loop stops at the next step
// boundary) and Lua's memory is capped at 512 MB ("not enough memory", an
// ordinary Lua error), so endless loops, long runs (the paper scripts of the
// seed corpus) and string.rep bombs are script errors, not findings. One
// step cannot be stopped part way, so m:generate refuses models of more than
// 3000 blocks (a mutated paper script made 20 000, whose single step under
// the sanitizers outlasted libFuzzer's timeout): size limits are the memory
// estimate's business (docs/robustness.md), not the fuzzer's.
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

#include "scripting.hpp"

namespace {

constexpr int kInstructionBatch = 10000;
constexpr long kInstructionLimit = 5'000'000;
constexpr long long kMemoryLimit = 512LL << 20;

struct Budget {
  long instructions = 0;
  long long bytes = 0;  // since the allocator was set (blocks from before are freed through it too)
};
Budget g_budget;

void count_hook(lua_State* L, lua_Debug*) {
  g_budget.instructions += kInstructionBatch;
  if (g_budget.instructions > kInstructionLimit) luaL_error(L, "fuzz: instruction limit reached");
}

void* capped_alloc(void*, void* ptr, std::size_t old_size, std::size_t new_size) {
  if (!ptr) old_size = 0;
  if (new_size == 0) {
    std::free(ptr);
    g_budget.bytes -= static_cast<long long>(old_size);
    return nullptr;
  }
  if (new_size > old_size && g_budget.bytes + static_cast<long long>(new_size - old_size) > kMemoryLimit)
    return nullptr;
  void* p = std::realloc(ptr, new_size);
  if (p) g_budget.bytes += static_cast<long long>(new_size) - static_cast<long long>(old_size);
  return p;
}

int no_print(lua_State*) { return 0; }

constexpr lua_Integer kMaxBlocks = 3000;

// m:generate(...) as the module's, then the block count checked.
int capped_generate(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  if (lua_gettop(L) >= 1 && !lua_isnil(L, 1) && luaL_len(L, 1) > kMaxBlocks)
    return luaL_error(L, "fuzz: more than %d blocks", static_cast<int>(kMaxBlocks));
  return lua_gettop(L);
}

// Raises SIGINT (as a Ctrl-C) once the input has run for kWallBudget.
class Watchdog {
 public:
  static constexpr auto kWallBudget = std::chrono::seconds(3);
  Watchdog()
      : thread_([this] {
          std::unique_lock lock(mutex_);
          if (!done_.wait_for(lock, kWallBudget, [this] { return finished_; })) std::raise(SIGINT);
        }) {}
  ~Watchdog() {
    {
      std::lock_guard lock(mutex_);
      finished_ = true;
    }
    done_.notify_one();
    thread_.join();
  }

 private:
  std::mutex mutex_;
  std::condition_variable done_;
  bool finished_ = false;
  std::thread thread_;
};

const std::filesystem::path& out_dir() {
  static const std::filesystem::path dir = [] {
    char tmpl[] = "/tmp/dda-fuzz-script-XXXXXX";
    return std::filesystem::path(mkdtemp(tmpl));
  }();
  return dir;
}

void sandbox(lua_State* L) {
  lua_pushnil(L);
  lua_setglobal(L, "io");
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "loaded");
  lua_pushnil(L);
  lua_setfield(L, -2, "io");
  lua_pop(L, 2);
  lua_getglobal(L, "os");
  for (const char* f : {"execute", "exit", "remove", "rename", "tmpname", "setlocale"}) {
    lua_pushnil(L);
    lua_setfield(L, -2, f);
  }
  lua_pop(L, 1);
  lua_pushcfunction(L, no_print);
  lua_setglobal(L, "print");
  luaL_getmetatable(L, "dda.Model");
  lua_getfield(L, -1, "__methods");
  lua_getfield(L, -1, "generate");
  lua_pushcclosure(L, capped_generate, 1);
  lua_setfield(L, -2, "generate");
  lua_pop(L, 2);
  lua_sethook(L, count_hook, LUA_MASKCOUNT, kInstructionBatch);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  dda::script::Session s;
  s.out_dir = out_dir();
  s.quiet = true;
  s.threads = 1;
  lua_State* L = dda::script::new_state(std::move(s));
  g_budget = {};
  lua_setallocf(L, capped_alloc, nullptr);  // Lua's default allocator is realloc/free too
  sandbox(L);
  dda::script::clear_interrupt();
  dda::script::install_interrupt_handler(L);
  std::string error;
  {
    Watchdog watchdog;
    dda::script::run_string(L, std::string(reinterpret_cast<const char*>(data), size), "fuzz", error);
  }
  dda::script::remove_interrupt_handler();
  dda::script::clear_interrupt();
  lua_close(L);
  return 0;
}
