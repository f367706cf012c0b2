#include "core/error.hpp"

#include <cstdio>
#include <cstdlib>

namespace dda {

void assertion_failed(const char* expr, const char* file, int line, const std::string& what) {
  std::fprintf(stderr, "internal error: %s:%d: assertion '%s' failed: %s\n", file, line, expr, what.c_str());
  std::abort();
}

}  // namespace dda
