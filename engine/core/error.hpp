// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Errors in two tiers:
//  - dda::Error: anything a user can cause (bad geometry, bad material, a step
//    that diverges). The message names the object and the cause; callers catch
//    it and carry on (the console stays up, batch runs exit non-zero).
//  - DDA_ASSERT: internal invariants. On in every build type; a failure is a bug.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace dda {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
// A number in a message: NaN as "nan" whatever its sign bit (a stream
// writes "-nan" for the NaN most arithmetic makes).
struct MessageNumber {
  double value;
  friend std::ostream& operator<<(std::ostream& out, MessageNumber n) {
    return std::isnan(n.value) ? out << "nan" : out << n.value;
  }
};
template <typename T>
decltype(auto) message_part(const T& part) {
  if constexpr (std::is_floating_point_v<T>)
    return MessageNumber{static_cast<double>(part)};
  else
    return (part);
}
}  // namespace detail

// Builds a message from streamable parts: throw Error(msg("block ", id, ": ...")).
template <typename... Parts>
std::string msg(const Parts&... parts) {
  std::ostringstream out;
  out.precision(12);
  (out << ... << detail::message_part(parts));
  return out.str();
}

// Bytes from a file (a checkpoint's text, a record's header) made safe to
// quote in a message: control characters, DEL and bytes that are not UTF-8
// become \xNN and a backslash \\, so no terminal escape sequence gets
// through; longer than `limit` bytes, the rest becomes "...".
std::string printable(std::string_view bytes, std::size_t limit = 80);

[[noreturn]] void assertion_failed(const char* expr, const char* file, int line, const std::string& what);

}  // namespace dda

#define DDA_ASSERT(cond, what)                                               \
  do {                                                                       \
    if (!(cond)) ::dda::assertion_failed(#cond, __FILE__, __LINE__, (what)); \
  } while (0)
