// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "core/error.hpp"

#include <cstdio>
#include <cstdlib>

namespace dda {

namespace {
// The length of the UTF-8 sequence at the start of s (2 to 4 bytes, no
// overlong form, no surrogate, at most U+10FFFF, and not one of the C1
// controls U+0080 to U+009F, which terminals may obey), or 0 if there is none.
std::size_t utf8_sequence(std::string_view s) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char c = byte(0);
  const std::size_t n = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
  if (n == 0 || s.size() < n) return 0;
  for (std::size_t i = 1; i < n; ++i)
    if ((byte(i) & 0xC0) != 0x80) return 0;
  if ((c == 0xC2 && byte(1) < 0xA0) || (c == 0xE0 && byte(1) < 0xA0) || (c == 0xED && byte(1) > 0x9F) ||
      (c == 0xF0 && byte(1) < 0x90) || (c == 0xF4 && byte(1) > 0x8F))
    return 0;
  return n;
}
}  // namespace

std::string printable(std::string_view bytes, std::size_t limit) {
  std::string out;
  const std::string_view shown = bytes.substr(0, limit);
  for (std::size_t i = 0; i < shown.size();) {
    const auto c = static_cast<unsigned char>(shown[i]);
    if (c >= 0x20 && c < 0x7F && c != '\\') {
      out += static_cast<char>(c), ++i;
    } else if (const std::size_t n = c >= 0x80 ? utf8_sequence(shown.substr(i)) : 0; n > 0) {
      out.append(shown.substr(i, n)), i += n;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, c == '\\' ? "\\\\" : "\\x%02x", c);
      out += hex, ++i;
    }
  }
  if (bytes.size() > limit) out += "...";
  return out;
}

void assertion_failed(const char* expr, const char* file, int line, const std::string& what) {
  std::fprintf(stderr, "internal error: %s:%d: assertion '%s' failed: %s\n", file, line, expr, what.c_str());
  std::abort();
}

}  // namespace dda
