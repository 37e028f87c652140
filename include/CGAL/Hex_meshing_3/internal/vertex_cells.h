// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_INTERNAL_VERTEX_CELLS_H
#define CGAL_HEX_MESHING_3_INTERNAL_VERTEX_CELLS_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal {

// The cells having each vertex as a corner: those of vertex v are cells[start[v] .. start[v+1])
template <typename HexMesh>
void vertex_cells(const HexMesh& m, std::size_t nv, std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& cells)
{
  start.assign(nv + 1, 0);
  for(const auto& h : m.hexahedra) for(std::uint32_t v : h) ++start[v + 1];
  for(std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  cells.resize(start[nv]);
  std::vector<std::uint32_t> pos(start.begin(), start.end() - 1);
  for(std::uint32_t c = 0; c < m.hexahedra.size(); ++c) for(std::uint32_t v : m.hexahedra[c]) cells[pos[v]++] = c;
}

} // namespace internal
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_INTERNAL_VERTEX_CELLS_H
