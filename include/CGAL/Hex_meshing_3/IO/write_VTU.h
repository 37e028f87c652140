// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_WRITE_VTU_H
#define CGAL_HEX_MESHING_3_IO_WRITE_VTU_H

// VTK XML unstructured grid (.vtu), raw binary appended data (header_type UInt64, little endian),
// readable by ParaView and meshio. Cells are VTK_HEXAHEDRON (12), corners in VTK order, followed by
// the boundary faces as VTK_QUAD (9) with their patch.

#include <CGAL/Hex_meshing_3/quality.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief writes `mesh` to `filename` as a binary VTU file (ParaView, meshio).
 *
 * Cells: the hexahedra (`VTK_HEXAHEDRON`), then, when `with_boundary` is true, the boundary faces
 * (`VTK_QUAD`, outward). Cell data: `scaled_jacobian` (Float64; computed here when `sj` is empty;
 * NaN for a boundary face), `level` (Int32, the largest per-axis level; a face has its cell's),
 * `patch` (Int32: -1 for a hexahedron, the patch index for a boundary face). Point data: `hanging`
 * (UInt8: 1 for a hanging node). Field data: one Int32 array per patch, named `patch:<name>`,
 * holding the patch index, so that the names travel with the file (ParaView: threshold `patch`).
 * \return `false` if the file cannot be written
 */
template <typename HexMesh>
bool write_VTU(const std::string& filename, const HexMesh& mesh, std::vector<double> sj = {},
               bool with_boundary = true)
{
  static_assert(sizeof(double) == 8, "IEEE doubles expected");
  const std::uint64_t np = mesh.points.size(), nh = mesh.hexahedra.size();
  const std::uint64_t nq = with_boundary ? mesh.boundary_faces.size() : 0, nc = nh + nq;
  if(sj.size() != nh) sj = cell_scaled_jacobians(mesh);
  std::ofstream os(filename, std::ios::binary);
  if(!os) return false;
  struct Block { std::string type, name, extra; std::uint64_t bytes; };
  const std::vector<Block> blocks = {
    {"Float64", "Points", " NumberOfComponents=\"3\"", np * 24},
    {"Int64", "connectivity", "", (8 * nh + 4 * nq) * 8},
    {"Int64", "offsets", "", nc * 8},
    {"UInt8", "types", "", nc},
    {"Float64", "scaled_jacobian", "", nc * 8},
    {"Int32", "level", "", nc * 4},
    {"UInt8", "hanging", "", np},
    {"Int32", "patch", "", nc * 4}};
  std::vector<std::uint64_t> offset(blocks.size());
  std::uint64_t off = 0;
  for(std::size_t b = 0; b < blocks.size(); ++b) { offset[b] = off; off += 8 + blocks[b].bytes; }
  auto decl = [&](std::size_t b) {
    os << "<DataArray type=\"" << blocks[b].type << "\" Name=\"" << blocks[b].name << "\""
       << blocks[b].extra << " format=\"appended\" offset=\"" << offset[b] << "\"/>\n";
  };
  auto xml = [](const std::string& t) {
    std::string r;
    for(char c : t) {
      if(c == '&') r += "&amp;"; else if(c == '<') r += "&lt;"; else if(c == '>') r += "&gt;";
      else if(c == '"') r += "&quot;"; else if(static_cast<unsigned char>(c) < 0x20) r += '_'; else r += c;
    }
    return r;
  };
  os << "<?xml version=\"1.0\"?>\n"
     << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
     << "<UnstructuredGrid>\n<FieldData>\n";
  for(std::size_t p = 0; p < mesh.patch_names.size(); ++p)
    os << "<DataArray type=\"Int32\" Name=\"patch:" << xml(mesh.patch_names[p]) << "\" NumberOfTuples=\"1\" format=\"ascii\">"
       << p << "</DataArray>\n";
  os << "</FieldData>\n<Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n"
     << "<PointData>\n"; decl(6);
  os << "</PointData>\n<CellData Scalars=\"scaled_jacobian\">\n"; decl(4); decl(5); decl(7);
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
    std::vector<std::int64_t> buf; buf.reserve(8 * nh + 4 * nq);
    for(const auto& h : mesh.hexahedra) for(auto v : h) buf.push_back(std::int64_t(v));
    for(std::uint64_t q = 0; q < nq; ++q) for(auto v : mesh.boundary_faces[q].vertices) buf.push_back(std::int64_t(v));
    raw(buf.data(), blocks[1].bytes);
    header(2);
    buf.resize(nc);
    for(std::uint64_t c = 0; c < nc; ++c) buf[c] = std::int64_t(c < nh ? 8 * (c + 1) : 8 * nh + 4 * (c - nh + 1));
    raw(buf.data(), blocks[2].bytes);
    header(3);
    std::vector<std::uint8_t> types(nc, 12);
    for(std::uint64_t c = nh; c < nc; ++c) types[c] = 9;
    raw(types.data(), nc);
  }
  header(4);
  sj.resize(nc, std::numeric_limits<double>::quiet_NaN());
  raw(sj.data(), blocks[4].bytes);
  auto level_of = [&](std::size_t c) {
    const auto& l = mesh.cell_levels[c];
    return std::int32_t((std::max)({int(l[0]), int(l[1]), int(l[2])}));
  };
  {
    header(5);
    std::vector<std::int32_t> lv(nc);
    for(std::size_t c = 0; c < nh; ++c) lv[c] = level_of(c);
    for(std::uint64_t q = 0; q < nq; ++q) lv[nh + q] = level_of(mesh.boundary_faces[q].cell);
    raw(lv.data(), blocks[5].bytes);
  }
  {
    header(6);
    std::vector<std::uint8_t> hg(np, 0);
    for(const auto& h : mesh.hanging_nodes) hg[h.vertex] = 1;
    raw(hg.data(), np);
  }
  {
    header(7);
    std::vector<std::int32_t> pt(nc, -1);
    for(std::uint64_t q = 0; q < nq; ++q) pt[nh + q] = std::int32_t(mesh.boundary_faces[q].patch);
    raw(pt.data(), blocks[7].bytes);
  }
  os << "\n</AppendedData>\n</VTKFile>\n";
  return bool(os);
}

} // namespace IO
} // namespace Hex_meshing_3
} // namespace CGAL

#endif
