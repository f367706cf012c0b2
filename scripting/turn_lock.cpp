// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "turn_lock.hpp"

namespace dda::script {

void TurnLock::lock() {
  std::unique_lock g(m_);
  if (depth_ > 0 && owner_ == std::this_thread::get_id()) {
    ++depth_;
    return;
  }
  const std::uint64_t ticket = next_++;
  cv_.wait(g, [&] { return serving_ == ticket; });
  owner_ = std::this_thread::get_id();
  depth_ = 1;
}

void TurnLock::unlock() {
  std::lock_guard g(m_);
  if (--depth_ > 0) return;
  owner_ = std::thread::id();
  ++serving_;
  cv_.notify_all();
}

bool TurnLock::held_by_this_thread() const {
  std::lock_guard g(m_);
  return depth_ > 0 && owner_ == std::this_thread::get_id();
}

void TurnLock::yield() {
  {
    std::lock_guard g(m_);
    if (next_ == serving_ + 1) return;  // only our own ticket is out
  }
  take_back(release_all());
}

int TurnLock::release_all() {
  std::lock_guard g(m_);
  if (depth_ == 0 || owner_ != std::this_thread::get_id()) return 0;
  const int depth = depth_;
  depth_ = 0;
  owner_ = std::thread::id();
  ++serving_;
  cv_.notify_all();
  return depth;
}

void TurnLock::take_back(int depth) {
  if (depth <= 0) return;
  lock();
  std::lock_guard g(m_);
  depth_ = depth;
}

}  // namespace dda::script
