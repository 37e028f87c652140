// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_WRITE_VTU_H
#define CGAL_HEX_MESHING_3_IO_WRITE_VTU_H

// VTK XML unstructured grid (.vtu), raw binary appended data (header_type UInt64, little endian),
// readable by ParaView and meshio. Cells are VTK_HEXAHEDRON (12), corners in VTK order.

#include <CGAL/Hex_meshing_3/quality.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief writes `mesh` to `filename` as a binary VTU file with cell data `level` (Int32, the
 * largest per-axis level) and `scaled_jacobian` (Float64; computed here when `sj` is empty) and
 * point data `hanging` (UInt8: 1 for a hanging node).
 * \return `false` if the file cannot be written
 */
template <typename HexMesh>
bool write_VTU(const std::string& filename, const HexMesh& mesh, std::vector<double> sj = {})
{
  static_assert(sizeof(double) == 8, "IEEE doubles expected");
  const std::uint64_t np = mesh.points.size(), nc = mesh.hexahedra.size();
  if(sj.size() != nc) {
    sj.resize(nc);
    for(std::size_t c = 0; c < nc; ++c) {
      std::array<typename HexMesh::Point_3, 8> p;
      for(int k = 0; k < 8; ++k) p[k] = mesh.points[mesh.hexahedra[c][k]];
      sj[c] = scaled_jacobian(p);
    }
  }
  std::ofstream os(filename, std::ios::binary);
  if(!os) return false;
  struct Block { std::string type, name, extra; std::uint64_t bytes; };
  const std::vector<Block> blocks = {
    {"Float64", "Points", " NumberOfComponents=\"3\"", np * 24},
    {"Int64", "connectivity", "", nc * 64},
    {"Int64", "offsets", "", nc * 8},
    {"UInt8", "types", "", nc},
    {"Float64", "scaled_jacobian", "", nc * 8},
    {"Int32", "level", "", nc * 4},
    {"UInt8", "hanging", "", np}};
  std::vector<std::uint64_t> offset(blocks.size());
  std::uint64_t off = 0;
  for(std::size_t b = 0; b < blocks.size(); ++b) { offset[b] = off; off += 8 + blocks[b].bytes; }
  auto decl = [&](std::size_t b) {
    os << "<DataArray type=\"" << blocks[b].type << "\" Name=\"" << blocks[b].name << "\""
       << blocks[b].extra << " format=\"appended\" offset=\"" << offset[b] << "\"/>\n";
  };
  os << "<?xml version=\"1.0\"?>\n"
     << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
     << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n"
     << "<PointData>\n"; decl(6);
  os << "</PointData>\n<CellData Scalars=\"scaled_jacobian\">\n"; decl(4); decl(5);
  os << "</CellData>\n<Points>\n"; decl(0);
  os << "</Points>\n<Cells>\n"; decl(1); decl(2); decl(3);
  os << "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  auto raw = [&](const void* data, std::uint64_t bytes) { os.write(static_cast<const char*>(data), std::streamsize(bytes)); };
  auto header = [&](std::size_t b) { raw(&blocks[b].bytes, 8); };
  {
    header(0);
    std::vector<double> buf; buf.reserve(3 * np);
    for(const auto& p : mesh.points) {
      buf.push_back(CGAL::to_double(p.x())); buf.push_back(CGAL::to_double(p.y())); buf.push_back(CGAL::to_double(p.z()));
    }
    raw(buf.data(), blocks[0].bytes);
  }
  {
    header(1);
    std::vector<std::int64_t> buf; buf.reserve(8 * nc);
    for(const auto& h : mesh.hexahedra) for(auto v : h) buf.push_back(std::int64_t(v));
    raw(buf.data(), blocks[1].bytes);
    header(2);
    for(std::uint64_t c = 0; c < nc; ++c) buf[c] = std::int64_t(8 * (c + 1));
    raw(buf.data(), blocks[2].bytes);
    header(3);
    std::vector<std::uint8_t> types(nc, 12);
    raw(types.data(), nc);
  }
  header(4); raw(sj.data(), blocks[4].bytes);
  {
    header(5);
    std::vector<std::int32_t> lv(nc);
    for(std::size_t c = 0; c < nc; ++c) {
      const auto& l = mesh.cell_levels[c];
      lv[c] = (std::max)({int(l[0]), int(l[1]), int(l[2])});
    }
    raw(lv.data(), blocks[5].bytes);
  }
  {
    header(6);
    std::vector<std::uint8_t> hg(np, 0);
    for(const auto& h : mesh.hanging_nodes) hg[h.vertex] = 1;
    raw(hg.data(), np);
  }
  os << "\n</AppendedData>\n</VTKFile>\n";
  return bool(os);
}

} // namespace IO
} // namespace Hex_meshing_3
} // namespace CGAL

#endif
