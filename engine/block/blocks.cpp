#include "block/blocks.hpp"

#include "core/error.hpp"

namespace dda {

void check_edges(const Blocks& blocks, const std::vector<EdgeRef>& edges, const std::string& what) {
  if (edges.empty()) throw Error(msg(what, ": no edges given"));
  for (const EdgeRef& e : edges) {
    if (e.block < 0 || static_cast<std::size_t>(e.block) >= blocks.count())
      throw Error(msg(what, ": no block ", e.block));
    const int n = blocks.vertex_count(e.block);
    if (e.edge < 0 || e.edge >= n)
      throw Error(msg(what, ": block ", e.block, " has no edge ", e.edge, " (it has ", n, ")"));
  }
}

}  // namespace dda
