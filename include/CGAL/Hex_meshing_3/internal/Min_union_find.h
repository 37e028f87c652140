// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_INTERNAL_MIN_UNION_FIND_H
#define CGAL_HEX_MESHING_3_INTERNAL_MIN_UNION_FIND_H

#include <algorithm>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal {

// Disjoint sets of 0..n-1 whose representative is the set's smallest element (so the roots, and
// what is ordered by them, do not depend on the order of the unions); path halving.
template <typename I>
struct Min_union_find
{
  std::vector<I> parent;
  explicit Min_union_find(std::size_t n) : parent(n) { for(std::size_t i = 0; i < n; ++i) parent[i] = I(i); }
  I find(I x) { while(parent[x] != x) { parent[x] = parent[parent[x]]; x = parent[x]; } return x; }
  void unite(I a, I b)
  {
    a = find(a);
    b = find(b);
    if(a != b) parent[(std::max)(a, b)] = (std::min)(a, b);
  }
};

} // namespace internal
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_INTERNAL_MIN_UNION_FIND_H
