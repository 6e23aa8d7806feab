#pragma once
// Private: the root of x in a disjoint-set forest `parent` (parent[r] == r at a root), with path
// halving. Connected components of a mesh (clean.cpp: by faces; surface.cpp: by boundary edges).
#include <cstddef>
#include <vector>

namespace emoface::retarget::detail {

inline int find_root(std::vector<int>& parent, int x) {
  while (parent[static_cast<std::size_t>(x)] != x) {
    parent[static_cast<std::size_t>(x)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    x = parent[static_cast<std::size_t>(x)];
  }
  return x;
}

}  // namespace emoface::retarget::detail
