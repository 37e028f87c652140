// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_WRITE_OPENFOAM_H
#define CGAL_HEX_MESHING_3_IO_WRITE_OPENFOAM_H

// OpenFOAM polyMesh (ASCII, points with 17 significant digits) in <case>/constant/polyMesh, and a
// minimal <case>/system/{controlDict,fvSchemes,fvSolution} when there are none, so that checkMesh and the solvers can run.
// Patch types come from the mesh (box faces `patch`, surface parts `wall` unless changed).

#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>
#include <CGAL/Hex_meshing_3/quality.h>
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
/// the largest bulge `write_OpenFOAM()` raises a hanging node to where its cell is still concave
constexpr double default_max_hanging_bulge = 0.2;

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
//
// Given the polyhedral form `pm`, the bulge adapts: while cells are still concave (the pieces of
// the warped faces of moved cells need a steeper roof), the bulge of the hanging nodes inside the
// mesh rises by half, round after round, up to `max_bulge`; nodes on the boundary keep `bulge`
// (the boundary stays on the surface). The face nodes rise first, all alike, and then, from the
// best points so far, the edge nodes: a face split into quarters gets a convex roof from its
// centre alone, while raised edge nodes tilt the pieces of the faces around the edge (raising
// face and edge nodes together leaves eight at --thin-cells 5 with 41 concave cells, face nodes
// first with 4). Raising only the nodes of the concave cells tilts the pieces of their
// neighbours' faces and makes more cells concave than it cures (anchor 491 -> 337 -> 636 over
// four rounds, against 491 -> 130 uniformly). A node stops rising where a cell it is a corner of
// would fall below min(its scaled Jacobian at `bulge`, max(0.3, the mesh's minimum)): the mesh's
// minimum scaled Jacobian never falls. With `node_by_node`, the hanging nodes of the cells still
// concave then try every level one at a time (below). The points with the fewest concave cells
// are returned; `concave`, if given, receives their count. Without `pm`: the uniform `bulge`, no
// count.
template <typename HexMesh>
std::vector<std::array<double, 3>> foam_points(const HexMesh& mesh, double bulge, const Polyhedral_mesh_3* pm = nullptr,
                                               double max_bulge = default_max_hanging_bulge, std::size_t* concave = nullptr,
                                               bool node_by_node = true)
{
  typedef std::array<double, 3> P3;
  std::vector<P3> x(mesh.points.size());
  for(std::size_t v = 0; v < x.size(); ++v)
    x[v] = {{CGAL::to_double(mesh.points[v].x()), CGAL::to_double(mesh.points[v].y()), CGAL::to_double(mesh.points[v].z())}};
  // The count of concave cells as `concave_cells()` finds it, kept up to date where points move:
  // the rounds below move the hanging nodes only, so only the faces with a moved node get their
  // centre and area again, and only their cells their flag (the same values, to the bit, as a
  // count from scratch; a full count per round took most of the export's time on motorBike).
  typedef CGAL::Hex_meshing_3::internal::Vec3 Vec3;
  // (the centres and areas are kept for the faces with a hanging node only, which the rounds
  // move; the others' are computed where needed: all faces' took 53 MB at the capture's memory
  // peak on motorBike)
  std::vector<Vec3> fcentre, farea, cc, ca;
  std::vector<std::uint32_t> fslot;                            // face -> its entry in fcentre, farea (or -1)
  std::vector<std::uint32_t> cstart, cfaces, hstart, hfaces;   // cell -> faces, hanging node -> faces
  std::vector<std::uint32_t> hanging_index;                    // vertex -> its hanging node (or -1)
  std::vector<char> cflag, fmark, cmark;
  std::size_t nconcave = 0;
  const std::uint32_t no_slot = std::uint32_t(-1);
  auto face_geometry = [&](const std::vector<P3>& y, std::size_t f) {
    CGAL::Hex_meshing_3::OpenFOAM_geometry::face_centre_and_area(y, pm->faces[f], fcentre[fslot[f]], farea[fslot[f]]);
  };
  auto cell_flag = [&](const std::vector<P3>& y, std::size_t c) {
    auto face = [&](std::size_t f, Vec3& fc, Vec3& fa) {
      if(fslot[f] != no_slot) { fc = fcentre[fslot[f]]; fa = farea[fslot[f]]; }
      else CGAL::Hex_meshing_3::OpenFOAM_geometry::face_centre_and_area(y, pm->faces[f], fc, fa);
    };
    return char(CGAL::Hex_meshing_3::internal::concave_cell(*pm, c, cstart, cfaces, face, cc, ca) ? 1 : 0);
  };
  auto count_from_scratch = [&](const std::vector<P3>& y) {
    const std::size_t nf = pm->faces.size(), nc = pm->number_of_cells;
    if(cstart.empty()) {
      CGAL::Hex_meshing_3::internal::cell_faces(*pm, cstart, cfaces);
      hanging_index.assign(x.size(), std::uint32_t(-1));
      for(std::size_t i = 0; i < mesh.hanging_nodes.size(); ++i) hanging_index[mesh.hanging_nodes[i].vertex] = std::uint32_t(i);
      hstart.assign(mesh.hanging_nodes.size() + 1, 0);
      for(std::size_t f = 0; f < nf; ++f) for(auto v : pm->faces[f]) if(hanging_index[v] != std::uint32_t(-1)) ++hstart[hanging_index[v] + 1];
      for(std::size_t i = 0; i + 1 < hstart.size(); ++i) hstart[i + 1] += hstart[i];
      hfaces.resize(hstart.back());
      std::vector<std::uint32_t> hpos(hstart.begin(), hstart.end() - 1);
      for(std::size_t f = 0; f < nf; ++f) for(auto v : pm->faces[f]) if(hanging_index[v] != std::uint32_t(-1)) hfaces[hpos[hanging_index[v]]++] = std::uint32_t(f);
      fslot.assign(nf, no_slot);
      std::uint32_t slots = 0;
      for(std::size_t f = 0; f < nf; ++f)
        for(auto v : pm->faces[f]) if(hanging_index[v] != std::uint32_t(-1)) { fslot[f] = slots++; break; }
      fcentre.resize(slots); farea.resize(slots); cflag.resize(nc); fmark.assign(nf, 0); cmark.assign(nc, 0);
    }
    for(std::size_t f = 0; f < nf; ++f) if(fslot[f] != no_slot) face_geometry(y, f);
    nconcave = 0;
    for(std::size_t c = 0; c < nc; ++c) nconcave += std::size_t(cflag[c] = cell_flag(y, c));
    return nconcave;
  };
  if(!(bulge > 0) || mesh.hanging_nodes.empty()) {
    if(concave && pm) *concave = count_from_scratch(x);
    return x;
  }
  std::vector<std::uint32_t> touched_faces, touched_cells;
  // after the hanging nodes `moved` (indices into mesh.hanging_nodes) moved, from the last count
  auto count_after = [&](const std::vector<P3>& y, const std::vector<std::size_t>& moved) {
    touched_faces.clear(); touched_cells.clear();
    for(std::size_t i : moved)
      for(std::size_t k = hstart[i]; k < hstart[i + 1]; ++k)
        if(!fmark[hfaces[k]]) { fmark[hfaces[k]] = 1; touched_faces.push_back(hfaces[k]); }
    for(std::uint32_t f : touched_faces) {
      fmark[f] = 0;
      face_geometry(y, f);
      const std::uint32_t o = std::uint32_t(pm->owner[f]);
      if(!cmark[o]) { cmark[o] = 1; touched_cells.push_back(o); }
      if(f < pm->neighbour.size()) {
        const std::uint32_t n = std::uint32_t(pm->neighbour[f]);
        if(!cmark[n]) { cmark[n] = 1; touched_cells.push_back(n); }
      }
    }
    for(std::uint32_t c : touched_cells) {
      cmark[c] = 0;
      const char fl = cell_flag(y, c);
      nconcave = nconcave - std::size_t(cflag[c]) + std::size_t(fl);
      cflag[c] = fl;
    }
    return nconcave;
  };
  std::vector<std::uint32_t> start, cells;   // the cells at each vertex
  CGAL::Hex_meshing_3::internal::vertex_cells(mesh, x.size(), start, cells);
  const double lo[3] = {mesh.box.xmin(), mesh.box.ymin(), mesh.box.zmin()};
  const double hi[3] = {mesh.box.xmax(), mesh.box.ymax(), mesh.box.zmax()};
  // per hanging node: its displacement for a bulge of 1 (edge length x unit direction), or zero
  const std::size_t nh = mesh.hanging_nodes.size();
  std::vector<P3> unit(nh, P3{{0, 0, 0}});
  for(std::size_t i = 0; i < nh; ++i) {
    const auto& h = mesh.hanging_nodes[i];
    const std::size_t hv = std::size_t(h.vertex), m0 = std::size_t(h.masters[0]);
    P3 d = {{0, 0, 0}};
    for(std::size_t k = start[m0]; k < start[m0 + 1]; ++k) {
      const auto& H = mesh.hexahedra[cells[k]];
      bool coarse = true;   // the masters are corners of the cell: the node is on its edge or face
      for(int j = 1; j < h.number_of_masters && coarse; ++j) coarse = std::find(H.begin(), H.end(), h.masters[std::size_t(j)]) != H.end();
      if(!coarse) continue;
      P3 u = x[hv];
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
    for(int a = 0; a < 3; ++a) unit[i][std::size_t(a)] = e * d[std::size_t(a)] / l;
  }
  std::vector<double> b(nh, bulge);
  std::vector<P3> y = x;
  auto place = [&](std::size_t i) {
    const std::size_t hv = mesh.hanging_nodes[i].vertex;
    for(int a = 0; a < 3; ++a) y[hv][std::size_t(a)] = x[hv][std::size_t(a)] + b[i] * unit[i][std::size_t(a)];
  };
  for(std::size_t i = 0; i < nh; ++i) place(i);
  if(!pm) return y;

  // the nodes that rise: not on a boundary face, and displaced at all
  std::vector<char> rises(nh, 0);
  {
    std::vector<char> on_boundary(x.size(), 0);
    for(std::size_t f = pm->neighbour.size(); f < pm->faces.size(); ++f) for(auto v : pm->faces[f]) on_boundary[v] = 1;
    for(std::size_t i = 0; i < nh; ++i)
      rises[i] = !on_boundary[mesh.hanging_nodes[i].vertex] && (unit[i][0] != 0 || unit[i][1] != 0 || unit[i][2] != 0);
  }
  auto sj = [&](std::size_t c) {
    CGAL::Hex_meshing_3::internal::Vec3 p[8];
    for(int k = 0; k < 8; ++k) p[k] = y[mesh.hexahedra[c][std::size_t(k)]];
    return CGAL::Hex_meshing_3::internal::hex_scaled_jacobian(p);
  };
  std::vector<double> floor_sj(mesh.hexahedra.size());
  double mesh_min = 1;
  for(std::size_t c = 0; c < floor_sj.size(); ++c) { floor_sj[c] = sj(c); mesh_min = (std::min)(mesh_min, floor_sj[c]); }
  for(double& f : floor_sj) f = (std::min)(f, (std::max)(0.3, mesh_min));

  std::vector<P3> best = y;
  std::vector<double> best_b = b;
  std::size_t best_count = count_from_scratch(y);
  std::vector<std::size_t> raised;
  // first the face nodes (a face split into quarters gets its roof from its centre alone), then
  // the edge nodes (the halves of a face split 1:2 have no centre node), each from the best so far
  for(const int masters : {4, 2}) {
    if(best_count == 0) break;
    std::vector<std::size_t> reset;   // the nodes the best points so far have elsewhere
    for(std::size_t i = 0; i < nh; ++i) if(b[i] != best_b[i]) reset.push_back(i);
    b = best_b;
    for(std::size_t i = 0; i < nh; ++i) place(i);
    if(!reset.empty()) count_after(y, reset);
    double level = bulge;
    while(best_count > 0 && level * 1.5 <= max_bulge * (1 + 1e-12)) {
      const double previous = level;
      level *= 1.5;
      raised.clear();
      for(std::size_t i = 0; i < nh; ++i)
        if(rises[i] && mesh.hanging_nodes[i].number_of_masters == masters && b[i] == previous) { b[i] = level; place(i); raised.push_back(i); }
      if(raised.empty()) break;
      // a node whose cells would fall below their floor goes back and rises no more (until no
      // cell falls: each pass freezes at least one node, and the previous points were valid)
      for(bool again = true; again;) {
        again = false;
        for(std::size_t i : raised) {
          if(b[i] != level) continue;
          const std::size_t hv = mesh.hanging_nodes[i].vertex;
          bool ok = true;
          for(std::size_t k = start[hv]; k < start[hv + 1] && ok; ++k) ok = sj(cells[k]) >= floor_sj[cells[k]];
          if(!ok) { b[i] = previous; place(i); rises[i] = 0; again = true; }
        }
      }
      const std::size_t n = count_after(y, raised);
      if(n < best_count) { best_count = n; best = y; best_b = b; }
    }
  }
  // What is left: each concave cell's own hanging nodes, those on a boundary face too, try the
  // other levels one at a time (none, and up to 2.5 x max_bulge), a change kept if it lowers the
  // count and no cell at the node falls below min(its floor, max(0.2, the mesh's minimum)):
  // validity for OpenFOAM before quality, and still no new minimum. (motorBike: a grid cell's face
  // split in four, its centre node on the boundary where a buffer cell was removed, whose fine
  // cells fell below 0.3 for any rise; the capture cannot remove a grid cell.)
  if(best_count > 0 && node_by_node) {
    y = best;
    b = best_b;
    count_from_scratch(y);
    std::vector<double> levels{0.0};
    for(double l = bulge; l <= 2.5 * max_bulge * (1 + 1e-12); l *= 1.5) levels.push_back(l);
    std::vector<std::size_t> nodes, one(1);
    for(int round = 0; round < 4 && nconcave > 0; ++round) {
      const std::size_t before = nconcave;
      nodes.clear();
      for(std::size_t c = 0; c < cflag.size(); ++c)
        if(cflag[c])
          for(std::size_t k = cstart[c]; k < cstart[c + 1]; ++k)
            for(auto v : pm->faces[cfaces[k]])
              if(hanging_index[v] != std::uint32_t(-1)) nodes.push_back(hanging_index[v]);
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      for(std::size_t i : nodes) {
        if(unit[i][0] == 0 && unit[i][1] == 0 && unit[i][2] == 0) continue;
        one[0] = i;
        const std::size_t hv = mesh.hanging_nodes[i].vertex;
        for(double level : levels) {
          const double old = b[i];
          if(level == old) continue;
          const std::size_t n0 = nconcave;
          b[i] = level;
          place(i);
          bool ok = true;
          for(std::size_t k = start[hv]; k < start[hv + 1] && ok; ++k) ok = sj(cells[k]) >= (std::min)(floor_sj[cells[k]], (std::max)(0.2, mesh_min));
          if(ok && count_after(y, one) < n0) continue;   // kept (the next level starts from here)
          b[i] = old;
          place(i);
          if(ok) count_after(y, one);
        }
      }
      if(nconcave >= before) break;
    }
    if(nconcave < best_count) { best_count = nconcave; best = y; }
  }
  if(concave) *concave = best_count;
  return best;
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
 * non-orthogonality a little). Where cells are still concave (warped split faces of moved cells),
 * the bulge of the hanging nodes inside the mesh rises (face nodes first, then edge nodes, each
 * kind alike) up to `default_max_hanging_bulge`
 * (nodes on the boundary keep `hanging_bulge`; no cell's scaled Jacobian falls below
 * min(its own, max(0.3, the mesh's minimum))); then the hanging nodes of the cells still concave,
 * those on the boundary too, try each level one at a time (no cell below min(its own, max(0.2,
 * the mesh's minimum))): see `internal::foam_points()`. 0 writes the points as they are.
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
    for(const auto& p : internal::foam_points(mesh, hanging_bulge, &pm)) {
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
