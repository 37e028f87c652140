// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_INTERNAL_BOUNDARY_POLYGONS_H
#define CGAL_HEX_MESHING_3_INTERNAL_BOUNDARY_POLYGONS_H

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal {

// The boundary faces of a hexahedral mesh as polygons: each quad with the hanging midpoints of its
// edges inserted (recursively, for chains), so that a coarse face and the finer faces along its
// edges share polygon edges.
template <typename HexMesh>
std::vector<std::vector<std::uint32_t>> boundary_polygons(const HexMesh& mesh)
{
  auto pair_key = [](std::uint64_t a, std::uint64_t b) { return a < b ? (a << 32 | b) : (b << 32 | a); };
  std::unordered_map<std::uint64_t, std::uint32_t> edge_mid;
  for(const auto& h : mesh.hanging_nodes)
    if(h.number_of_masters == 2) edge_mid[pair_key(h.masters[0], h.masters[1])] = std::uint32_t(h.vertex);
  std::vector<std::vector<std::uint32_t>> polys;
  polys.reserve(mesh.boundary_faces.size());
  // appends the vertices strictly inside a -> b, in order
  auto inside = [&](auto&& self, std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out, int depth) -> void {
    if(depth > 64) return;
    auto it = edge_mid.find(pair_key(a, b));
    if(it == edge_mid.end()) return;
    const std::uint32_t m = it->second;
    self(self, a, m, out, depth + 1);
    out.push_back(m);
    self(self, m, b, out, depth + 1);
  };
  for(const auto& f : mesh.boundary_faces) {
    std::vector<std::uint32_t> p;
    p.reserve(8);
    for(int i = 0; i < 4; ++i) {
      p.push_back(std::uint32_t(f.vertices[std::size_t(i)]));
      inside(inside, std::uint32_t(f.vertices[std::size_t(i)]), std::uint32_t(f.vertices[std::size_t((i + 1) % 4)]), p, 0);
    }
    polys.push_back(std::move(p));
  }
  return polys;
}

} // namespace internal
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_INTERNAL_BOUNDARY_POLYGONS_H
