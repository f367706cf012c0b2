#pragma once
// Memory limits stated up front: what this process may still allocate, and
// a refusal, with the estimate, of work that would need more. The callers
// estimate their own needs (block cutting from the joint crossings, the
// first step from the blocks and vertices; docs/robustness.md).
#include <string>

namespace dda {

// Bytes this process may still allocate: the least headroom of the
// machine's physical memory (MemTotal less this process's resident size),
// the address-space limit (ulimit -v, less the mapped size), the data
// limit, and the cgroup limit (memory.max less memory.current). +inf when
// none is known.
double memory_headroom_bytes();

// Throws dda::Error "<what> needs about X GB of memory (<detail>); this
// process can have about Y GB (<limit>): <cure>" when needed > headroom.
void check_memory_need(double needed_bytes, double headroom_bytes, const std::string& what, const std::string& detail,
                       const std::string& cure);

}  // namespace dda
