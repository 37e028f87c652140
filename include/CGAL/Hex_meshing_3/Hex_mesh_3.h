// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_HEX_MESH_3_H
#define CGAL_HEX_MESHING_3_HEX_MESH_3_H

// Conventions used throughout the package
// ---------------------------------------
// Hexahedron corner order is VTK's (VTK_HEXAHEDRON = 12): with (i,j,k) in {0,1}^3 the local
// lattice offsets of a corner along x, y, z,
//     0:(0,0,0) 1:(1,0,0) 2:(1,1,0) 3:(0,1,0) 4:(0,0,1) 5:(1,0,1) 6:(1,1,1) 7:(0,1,1)
// so that 0-1-2-3 is the bottom face, counter-clockwise seen from above, and corner c+4 lies
// above corner c. A valid cell has a positive Jacobian at every corner in this order.
// Local faces (each listed counter-clockwise seen from outside the cell):
//     0: x-  (0,4,7,3)   1: x+ (1,2,6,5)   2: y- (0,1,5,4)
//     3: y+  (3,7,6,2)   4: z- (0,3,2,1)   5: z+ (4,5,6,7)
// Hanging nodes are vertices lying inside an edge (2 masters, the edge's end points) or inside a
// face (4 masters, the face's corners) of a cell of the mesh; their position is the average of
// their masters' (for a 2:1 balanced grid). Masters may themselves be hanging (chains); see
// `Hex_mesh_3::independent_masters()`.

#include <CGAL/Bbox_3.h>

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {

/// \ingroup PkgHexMeshing3Mesh
/// \brief the names of the meshing box's faces, patches 0..5 of a mesh: xmin, xmax, ymin, ymax,
/// zmin, zmax (face `p` is normal to axis `p / 2`, at its low end for even `p`)
inline const std::array<const char*, 6>& box_face_names()
{
  static const std::array<const char*, 6> n = {{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"}};
  return n;
}

/// \ingroup PkgHexMeshing3Mesh
/// \brief lattice offsets (x, y, z) of the 8 corners of a hexahedron in VTK order
inline const std::array<std::array<int, 3>, 8>& hex_corner_offsets()
{
  static const std::array<std::array<int, 3>, 8> o = {{
      {{0, 0, 0}}, {{1, 0, 0}}, {{1, 1, 0}}, {{0, 1, 0}}, {{0, 0, 1}}, {{1, 0, 1}}, {{1, 1, 1}}, {{0, 1, 1}}}};
  return o;
}

/// \ingroup PkgHexMeshing3Mesh
/// \brief local faces of a hexahedron in VTK corner order, each counter-clockwise seen from outside
inline const std::array<std::array<int, 4>, 6>& hex_local_faces()
{
  static const std::array<std::array<int, 4>, 6> f = {{
      {{0, 4, 7, 3}}, {{1, 2, 6, 5}}, {{0, 1, 5, 4}}, {{3, 7, 6, 2}}, {{0, 3, 2, 1}}, {{4, 5, 6, 7}}}};
  return f;
}

/// \ingroup PkgHexMeshing3Mesh
/// \brief local edges of a hexahedron in VTK corner order (x edges, then y, then z)
inline const std::array<std::array<int, 2>, 12>& hex_local_edges()
{
  static const std::array<std::array<int, 2>, 12> e = {{
      {{0, 1}}, {{3, 2}}, {{4, 5}}, {{7, 6}},   // along x
      {{0, 3}}, {{1, 2}}, {{4, 7}}, {{5, 6}},   // along y
      {{0, 4}}, {{1, 5}}, {{2, 6}}, {{3, 7}}}}; // along z
  return e;
}

/*!
 * \ingroup PkgHexMeshing3Mesh
 * \brief the result of `make_hex_mesh_3()`: an unstructured, possibly non-conformal
 * all-hexahedral mesh.
 *
 * Model of `HexMesh_3`. Points and connectivity are plain arrays so that any writer or solver can
 * read them: `points`, `hexahedra` (8 point indices in VTK order), `hanging_nodes` (constrained
 * vertices with their masters), `boundary_faces` (outward quads with a patch index into
 * `patch_names`). Per-cell data: `cell_levels` (refinement level per axis).
 *
 * The six faces of the meshing box are the patches 0..5, named `xmin, xmax, ymin, ymax, zmin,
 * zmax`; the input surface parts follow.
 *
 * \tparam GeomTraits a model of `Kernel` (e.g. `CGAL::Exact_predicates_inexact_constructions_kernel`)
 */
template <typename GeomTraits>
class Hex_mesh_3
{
public:
  typedef GeomTraits                      Geom_traits;
  typedef typename GeomTraits::FT         FT;
  typedef typename GeomTraits::Point_3    Point_3;
  typedef std::uint32_t                   Index;
  typedef std::array<Index, 8>            Hexahedron;

  /// a constrained (hanging) vertex: `vertex` = average of `masters[0 .. number_of_masters-1]`
  struct Hanging_node
  {
    Index vertex;
    std::array<Index, 4> masters;
    int number_of_masters;   ///< 2 (on an edge) or 4 (on a face)
  };

  /// a boundary quad, counter-clockwise seen from outside the mesh
  struct Boundary_face
  {
    std::array<Index, 4> vertices;
    Index cell;     ///< the hexahedron it bounds
    int patch;      ///< index into `patch_names`
  };

  std::vector<Point_3> points;
  std::vector<Hexahedron> hexahedra;
  std::vector<std::array<std::uint8_t, 3>> cell_levels;  ///< refinement level per axis
  std::vector<Hanging_node> hanging_nodes;
  std::vector<Boundary_face> boundary_faces;
  std::vector<std::string> patch_names;
  /// the type of each patch, in OpenFOAM's words: `patch` (default for the box faces), `wall`
  /// (default for the surface parts), `symmetryPlane`, ...; writers that know no types ignore it
  std::vector<std::string> patch_types;
  Bbox_3 box;   ///< the meshing box

  void clear()
  {
    points.clear(); hexahedra.clear(); cell_levels.clear(); hanging_nodes.clear();
    boundary_faces.clear(); patch_names.clear(); patch_types.clear(); box = Bbox_3();
  }

  /// the type of patch `p` (`patch_types[p]`; when absent, `patch` for 0..5 and `wall` otherwise)
  std::string patch_type(std::size_t p) const
  {
    if(p < patch_types.size() && !patch_types[p].empty()) return patch_types[p];
    return p < 6 ? "patch" : "wall";
  }

  /// the number of boundary faces of each patch
  std::vector<std::size_t> patch_sizes() const
  {
    std::vector<std::size_t> n(patch_names.size(), 0);
    for(const Boundary_face& f : boundary_faces) ++n[std::size_t(f.patch)];
    return n;
  }

  /*!
   * renames every patch `p` to `rename(patch_names[p])`; patches that end up with the same name are
   * merged into one, which keeps the type of the first of them and the position of the first.
   */
  template <typename Rename>
  void rename_patches(const Rename& rename)
  {
    std::vector<std::string> names, types;
    std::vector<int> to(patch_names.size());
    for(std::size_t p = 0; p < patch_names.size(); ++p) {
      const std::string n = rename(patch_names[p]);
      std::size_t q = 0;
      while(q < names.size() && names[q] != n) ++q;
      if(q == names.size()) { names.push_back(n); types.push_back(patch_type(p)); }
      to[p] = int(q);
    }
    for(Boundary_face& f : boundary_faces) f.patch = to[std::size_t(f.patch)];
    patch_names = std::move(names);
    patch_types = std::move(types);
  }

  std::size_t number_of_vertices() const { return points.size(); }
  std::size_t number_of_cells() const { return hexahedra.size(); }
  bool has_hanging_nodes() const { return !hanging_nodes.empty(); }

  /// the masters of hanging vertex `v` after substituting hanging masters recursively, with
  /// their weights (summing to one); a vertex that is not hanging is its own single master
  std::map<Index, double> independent_masters(Index v) const
  {
    if(m_hanging_index.size() != points.size()) build_hanging_index();
    std::map<Index, double> result;
    add_masters(v, 1.0, result, 0);
    return result;
  }

private:
  mutable std::vector<std::int64_t> m_hanging_index;
  void build_hanging_index() const
  {
    m_hanging_index.assign(points.size(), -1);
    for(std::size_t i = 0; i < hanging_nodes.size(); ++i)
      m_hanging_index[hanging_nodes[i].vertex] = std::int64_t(i);
  }
  void add_masters(Index v, double w, std::map<Index, double>& out, int depth) const
  {
    const std::int64_t h = m_hanging_index[v];
    if(h < 0 || depth > 64) { out[v] += w; return; }
    const Hanging_node& n = hanging_nodes[std::size_t(h)];
    for(int i = 0; i < n.number_of_masters; ++i)
      add_masters(n.masters[i], w / n.number_of_masters, out, depth + 1);
  }
};

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_HEX_MESH_3_H
