// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_WRITE_OPENFOAM_H
#define CGAL_HEX_MESHING_3_IO_WRITE_OPENFOAM_H

// OpenFOAM polyMesh (ASCII, points with 17 significant digits) in <case>/constant/polyMesh, and a
// minimal <case>/system/{controlDict,fvSchemes,fvSolution} when there are none, so that checkMesh and the solvers can run.
// Patch types come from the mesh (box faces `patch`, surface parts `wall` unless changed).

#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>
#include <CGAL/Hex_meshing_3/internal/vertex_cells.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {

/// the default of `write_OpenFOAM()`'s `hanging_bulge`
constexpr double default_hanging_bulge = 0.01;

namespace internal {
inline void foam_header(std::ostream& os, const char* cls, const char* location, const char* object,
                        const std::string& note = std::string())
{
  os << "/*--------------------------------*- C++ -*----------------------------------*\\\n"
     << "  Written by Hex_meshing_3\n"
     << "\\*---------------------------------------------------------------------------*/\n"
     << "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       " << cls << ";\n";
  if(!note.empty()) os << "    note        \"" << note << "\";\n";
  os << "    location    \"" << location << "\";\n    object      " << object << ";\n}\n\n";
}
// OpenFOAM's concave-cell check (checkMesh -allGeometry) calls a cell concave when the centre of
// one of its faces lies on (or beyond) the plane of another. A cell next to finer ones has its face
// split by hanging nodes into coplanar pieces, so every such cell would be "concave". The points
// written move each hanging node by `bulge` x its edge length (a face node: its face's diagonal /
// sqrt 2) away from the centres of its coarse cells, so the pieces form a slightly convex roof;
// a node on a plane of the meshing box stays in that plane.
template <typename HexMesh>
std::vector<std::array<double, 3>> foam_points(const HexMesh& mesh, double bulge)
{
  std::vector<std::array<double, 3>> x(mesh.points.size());
  for(std::size_t v = 0; v < x.size(); ++v)
    x[v] = {{CGAL::to_double(mesh.points[v].x()), CGAL::to_double(mesh.points[v].y()), CGAL::to_double(mesh.points[v].z())}};
  if(!(bulge > 0) || mesh.hanging_nodes.empty()) return x;
  std::vector<std::uint32_t> start, cells;   // the cells at each vertex
  CGAL::Hex_meshing_3::internal::vertex_cells(mesh, x.size(), start, cells);
  const double lo[3] = {mesh.box.xmin(), mesh.box.ymin(), mesh.box.zmin()};
  const double hi[3] = {mesh.box.xmax(), mesh.box.ymax(), mesh.box.zmax()};
  std::vector<std::array<double, 3>> moved = x;
  for(const auto& h : mesh.hanging_nodes) {
    const std::size_t hv = std::size_t(h.vertex), m0 = std::size_t(h.masters[0]);
    std::array<double, 3> d = {{0, 0, 0}};
    for(std::size_t k = start[m0]; k < start[m0 + 1]; ++k) {
      const auto& H = mesh.hexahedra[cells[k]];
      bool coarse = true;   // the masters are corners of the cell: the node is on its edge or face
      for(int i = 1; i < h.number_of_masters && coarse; ++i) coarse = std::find(H.begin(), H.end(), h.masters[std::size_t(i)]) != H.end();
      if(!coarse) continue;
      std::array<double, 3> u = x[hv];
      for(auto v : H) for(int a = 0; a < 3; ++a) u[std::size_t(a)] -= x[std::size_t(v)][std::size_t(a)] / 8;
      const double l = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      if(l > 0) for(int a = 0; a < 3; ++a) d[std::size_t(a)] += u[std::size_t(a)] / l;
    }
    for(int a = 0; a < 3; ++a)
      if(x[hv][std::size_t(a)] == lo[a] || x[hv][std::size_t(a)] == hi[a]) d[std::size_t(a)] = 0;
    const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if(!(l > 1e-6)) continue;
    const std::size_t m1 = std::size_t(h.masters[h.number_of_masters == 2 ? 1 : 2]);
    double e = 0;
    for(int a = 0; a < 3; ++a) e += (x[m1][std::size_t(a)] - x[m0][std::size_t(a)]) * (x[m1][std::size_t(a)] - x[m0][std::size_t(a)]);
    e = std::sqrt(e) / (h.number_of_masters == 2 ? 1.0 : std::sqrt(2.0));
    for(int a = 0; a < 3; ++a) moved[hv][std::size_t(a)] += bulge * e * d[std::size_t(a)] / l;
  }
  return moved;
}

/// an OpenFOAM `word`: letters, digits and _-.: only
inline std::string foam_word(const std::string& s)
{
  std::string w;
  for(char c : s) w += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') ? c : '_';
  if(w.empty() || std::isdigit(static_cast<unsigned char>(w[0]))) w = "p_" + w;
  return w;
}
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief writes `mesh` (with its polyhedral form `pm`) as an OpenFOAM case in directory
 * `case_dir`: `constant/polyMesh/{points,faces,owner,neighbour,boundary}`, and
 * `system/controlDict`, `system/fvSchemes`, `system/fvSolution` only if absent. Patch types are `mesh.patch_type(p)` (by default `patch` for
 * the box faces, `wall` for the surface parts).
 *
 * Hanging nodes are written `hanging_bulge` x their edge length away from the centres of their
 * coarse cells (nodes on the box's planes stay in them): a face split by hanging nodes into
 * coplanar pieces is what checkMesh's concave-cell check flags, and the slight roof makes the cell
 * convex (on the test surfaces 0.01 removes 80-100 % of the concave cells and lowers the
 * non-orthogonality a little). 0 writes the points as they are.
 * \return `false` if a file cannot be written
 */
template <typename HexMesh>
bool write_OpenFOAM(const std::string& case_dir, const HexMesh& mesh, const Polyhedral_mesh_3& pm,
                    double hanging_bulge = default_hanging_bulge)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path poly = fs::path(case_dir) / "constant" / "polyMesh";
  fs::create_directories(poly, ec);
  fs::create_directories(fs::path(case_dir) / "system", ec);
  if(!fs::is_directory(poly)) return false;
  const char* loc = "constant/polyMesh";
  char buf[96];
  {
    std::ofstream os(poly / "points");
    if(!os) return false;
    internal::foam_header(os, "vectorField", loc, "points");
    os << mesh.points.size() << "\n(\n";
    for(const auto& p : internal::foam_points(mesh, hanging_bulge)) {
      std::snprintf(buf, sizeof buf, "(%.17g %.17g %.17g)\n", p[0], p[1], p[2]);
      os << buf;
    }
    os << ")\n";
    if(!os) return false;
  }
  {
    std::ofstream os(poly / "faces");
    if(!os) return false;
    internal::foam_header(os, "faceList", loc, "faces");
    os << pm.faces.size() << "\n(\n";
    for(const auto& f : pm.faces) {
      os << f.size() << '(';
      for(std::size_t i = 0; i < f.size(); ++i) os << (i ? " " : "") << f[i];
      os << ")\n";
    }
    os << ")\n";
    if(!os) return false;
  }
  const std::string note = "nPoints:" + std::to_string(mesh.points.size()) + "  nCells:" +
                           std::to_string(pm.number_of_cells) + "  nFaces:" + std::to_string(pm.faces.size()) +
                           "  nInternalFaces:" + std::to_string(pm.neighbour.size());
  auto write_labels = [&](const char* name, const std::vector<Polyhedral_mesh_3::Index>& v) {
    std::ofstream os(poly / name);
    if(!os) return false;
    internal::foam_header(os, "labelList", loc, name, note);
    os << v.size() << "\n(\n";
    for(auto x : v) os << x << '\n';
    os << ")\n";
    return bool(os);
  };
  if(!write_labels("owner", pm.owner) || !write_labels("neighbour", pm.neighbour)) return false;
  {
    std::ofstream os(poly / "boundary");
    if(!os) return false;
    internal::foam_header(os, "polyBoundaryMesh", loc, "boundary");
    os << pm.patches.size() << "\n(\n";
    std::vector<std::string> words;   // OpenFOAM words, made unique ("a b" and "a_b" both give "a_b")
    for(std::size_t p = 0; p < pm.patches.size(); ++p) {
      const std::string w = internal::foam_word(pm.patches[p].name);
      std::string u = w;
      for(int k = 2; std::find(words.begin(), words.end(), u) != words.end(); ++k) u = w + "_" + std::to_string(k);
      words.push_back(u);
    }
    for(std::size_t p = 0; p < pm.patches.size(); ++p) {
      const std::string type = internal::foam_word(mesh.patch_type(p));
      os << "    " << words[p] << "\n    {\n"
         << "        type            " << type << ";\n"
         << (type == "patch" ? std::string() : "        inGroups        List<word> 1(" + type + ");\n")
         << "        nFaces          " << pm.patches[p].size << ";\n"
         << "        startFace       " << pm.patches[p].start << ";\n    }\n";
    }
    os << ")\n";
    if(!os) return false;
  }
  // fvSchemes and fvSolution: empty defaults, so that checkMesh and utilities can run; the user's
  // own files are never overwritten
  for(const char* name : {"fvSchemes", "fvSolution"}) {
    const fs::path f = fs::path(case_dir) / "system" / name;
    if(fs::exists(f)) continue;
    std::ofstream os(f);
    if(!os) return false;
    internal::foam_header(os, "dictionary", "system", name);
    if(std::string(name) == "fvSchemes")
      os << "ddtSchemes {}\ngradSchemes {}\ndivSchemes {}\nlaplacianSchemes {}\n"
         << "interpolationSchemes {}\nsnGradSchemes {}\n";
    else
      os << "solvers {}\n";
    if(!os) return false;
  }
  const fs::path cd = fs::path(case_dir) / "system" / "controlDict";
  if(!fs::exists(cd)) {
    std::ofstream os(cd);
    if(!os) return false;
    internal::foam_header(os, "dictionary", "system", "controlDict");
    os << "application     simpleFoam;\nstartFrom       startTime;\nstartTime       0;\n"
       << "stopAt          endTime;\nendTime         1;\ndeltaT          1;\n"
       << "writeControl    timeStep;\nwriteInterval   1;\npurgeWrite      0;\n"
       << "writeFormat     ascii;\nwritePrecision  12;\nwriteCompression off;\n"
       << "timeFormat      general;\ntimePrecision   6;\nrunTimeModifiable false;\n";
    if(!os) return false;
  }
  return true;
}

} // namespace IO
} // namespace Hex_meshing_3
} // namespace CGAL

#endif
