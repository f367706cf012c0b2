#pragma once
// Errors in two tiers:
//  - dda::Error: anything a user can cause (bad geometry, bad material, a step
//    that diverges). The message names the object and the cause; callers catch
//    it and carry on (the console stays up, batch runs exit non-zero).
//  - DDA_ASSERT: internal invariants. On in every build type; a failure is a bug.
#include <sstream>
#include <stdexcept>
#include <string>

namespace dda {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Builds a message from streamable parts: throw Error(msg("block ", id, ": ...")).
template <typename... Parts>
std::string msg(const Parts&... parts) {
  std::ostringstream out;
  out.precision(12);
  (out << ... << parts);
  return out.str();
}

[[noreturn]] void assertion_failed(const char* expr, const char* file, int line, const std::string& what);

}  // namespace dda

#define DDA_ASSERT(cond, what)                                               \
  do {                                                                       \
    if (!(cond)) ::dda::assertion_failed(#cond, __FILE__, __LINE__, (what)); \
  } while (0)
