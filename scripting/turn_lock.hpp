// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A lock taken in turns: whoever asks first holds it next (a ticket lock),
// so a stepping loop that takes it for every step cannot starve a reader
// that waits between two steps, nor a reader the loop. The thread that holds
// it may take it again (each take needs its release). Used for "who may
// touch this model now" (RunControl::lock) and "who may run Lua now"
// (lua_gate()).
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

namespace dda::script {

class TurnLock {
 public:
  void lock();
  void unlock();
  bool held_by_this_thread() const;
  // Lets whoever waits take a turn, then takes the lock back with the same
  // depth (the caller holds it). A no-op when nobody waits.
  void yield();
  // Gives up every take of the calling thread; returns how many there were
  // (0 when it held none). take_back(n) restores them.
  int release_all();
  void take_back(int depth);

 private:
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::uint64_t next_ = 0;     // the next ticket handed out
  std::uint64_t serving_ = 0;  // the ticket that may hold the lock
  std::thread::id owner_;
  int depth_ = 0;
};

}  // namespace dda::script
