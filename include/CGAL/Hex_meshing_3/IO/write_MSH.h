// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_WRITE_MSH_H
#define CGAL_HEX_MESHING_3_IO_WRITE_MSH_H

// Gmsh MSH 4.1 ASCII (.msh), readable by Gmsh (4.2 and later) and meshio.
//
// Layout of the file:
//  - $PhysicalNames: one 2-D physical group per patch p of `mesh.patch_names` (tag p + 1, name =
//    the patch name) and one 3-D physical group "volume" (tag = number of patches + 1; renamed
//    "volume_", "volume__", ... should a patch already be called "volume").
//    Patches that have no boundary face are listed as well, so that the physical tag of a patch
//    is always its index + 1 and no name is lost. Gmsh (4.8) and meshio (5.0) both read such
//    names without complaint: Gmsh keeps the name with no entity attached, meshio puts it in
//    `field_data` with an empty `cell_sets` entry.
//  - $Comments: one line per patch "tag name type" (the type from `mesh.patch_types` when set,
//    else "patch" for the six box faces and "wall" for the others) and the number of hanging
//    nodes. Gmsh and meshio skip sections they do not know.
//  - $Entities: one surface entity per patch that has faces (entity tag = patch index + 1, the
//    bounding box of its faces, physical tag = entity tag) and one volume entity (tag 1, the
//    bounding box of all points, physical tag = number of patches + 1, bounded by all surfaces).
//  - $Nodes: a single block in the volume entity, node tag = point index + 1, coordinates with
//    17 significant digits.
//  - $Elements: for each surface entity (increasing patch index) a block of 4-node quadrangles
//    (type 3), in the order of `mesh.boundary_faces`; then one block of 8-node hexahedra (type 5)
//    in the order of `mesh.hexahedra`. Element tags are consecutive from 1: the hexahedron c has
//    tag (number of quadrangles written) + c + 1.
//  An empty mesh gives a valid file that Gmsh reads, but meshio 5.0 fails on a file without nodes.
//
// Corner order: Gmsh's 8-node hexahedron (reference element [-1,1]^3, nodes 0..3 on w = -1 in
// the order (-1,-1), (1,-1), (1,1), (-1,1) of (u,v), nodes 4..7 above them on w = +1; see the
// "Node ordering" section of the Gmsh reference manual and the MHexahedron.h header of the Gmsh
// sources) is VTK's order, which the package uses, so hexahedra are written unchanged and a cell
// with positive Jacobians in VTK order also has positive Jacobians in Gmsh (checked with Gmsh 4.8's
// AnalyseMeshQuality plugin). meshio maps Gmsh's 8-node hexahedron to its VTK-ordered "hexahedron"
// without permutation (it permutes only higher-order cells).
// Boundary quadrangles keep their orientation: counter-clockwise seen from outside the mesh.

#include <CGAL/Hex_meshing_3/IO/internal/patch_names.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {


/*!
 * \ingroup PkgHexMeshing3IO
 * \brief writes `mesh` to `filename` as a Gmsh MSH 4.1 ASCII file: the points, the hexahedra
 * (one volume, physical group "volume") and the boundary quadrangles (one surface and one physical
 * group per patch, named after `mesh.patch_names`).
 *
 * The mesh may be non-conformal: where a coarse cell meets finer ones, a face of the coarse
 * hexahedron is covered by 4 faces of finer hexahedra, whose extra vertices (hanging nodes) lie
 * inside the coarse face or on its edges. Likewise a boundary quadrilateral may be a quarter of a
 * face of its (coarser) hexahedron, so that some boundary nodes belong to no hexahedron (Gmsh's
 * `-check` reports them as "not connected to any 3D elements"). MSH has no notion of such
 * constraints: the mesh is stored as is, hanging nodes being ordinary nodes (their count is noted in
 * the `$Comments` section); a solver reading the file must either accept non-conformal meshes or
 * constrain those nodes itself (see `mesh.hanging_nodes`, which this file does not store).
 *
 * Patch names have `"`, `\` and control characters replaced by `_` (Gmsh and meshio could not
 * read them back otherwise). Boundary faces with a negative patch index are not written.
 *
 * \tparam HexMesh a `Hex_mesh_3` (or a type with the same public members `points`, `hexahedra`,
 * `boundary_faces`, `patch_names`, `hanging_nodes` and `patch_type()`)
 * \return `false` if the file cannot be written
 */
template <typename HexMesh>
bool write_MSH(const std::string& filename, const HexMesh& mesh)
{
  const std::size_t np = mesh.points.size(), nh = mesh.hexahedra.size();
  const std::size_t npatch = internal::number_of_patches(mesh);

  std::vector<std::vector<std::size_t>> faces_of(npatch);   // boundary faces of each patch
  std::size_t nq = 0;
  for(std::size_t f = 0; f < mesh.boundary_faces.size(); ++f) {
    const int p = mesh.boundary_faces[f].patch;
    if(p < 0) continue;
    faces_of[std::size_t(p)].push_back(f);
    ++nq;
  }
  std::size_t nsurf = 0;
  for(const auto& v : faces_of) if(!v.empty()) ++nsurf;

  std::vector<std::array<double, 3>> xyz(np);
  for(std::size_t i = 0; i < np; ++i) {
    const auto& p = mesh.points[i];
    xyz[i] = {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  }

  std::vector<std::string> names(npatch);
  for(std::size_t p = 0; p < npatch; ++p)
    names[p] = internal::replace_chars(internal::patch_name(mesh, p), "\"\\", '_');
  std::string volume_name = "volume";
  while(std::find(names.begin(), names.end(), volume_name) != names.end()) volume_name += '_';

  std::ofstream os(filename);
  if(!os) return false;
  char buf[160];
  struct Box {   // bounding box, empty when lo > hi
    std::array<double, 3> lo{{ std::numeric_limits<double>::infinity(),  std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::infinity()}};
    std::array<double, 3> hi{{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity()}};
    void add(const std::array<double, 3>& q)
    {
      for(int k = 0; k < 3; ++k) { lo[k] = (std::min)(lo[k], q[k]); hi[k] = (std::max)(hi[k], q[k]); }
    }
  };
  auto write_box = [&](Box b) {
    if(!(b.lo[0] <= b.hi[0])) b.lo = b.hi = {{0., 0., 0.}};
    std::snprintf(buf, sizeof buf, " %.17g %.17g %.17g %.17g %.17g %.17g", b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1],
                  b.hi[2]);
    os << buf;
  };

  os << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";

  os << "$PhysicalNames\n" << npatch + 1 << "\n";
  for(std::size_t p = 0; p < npatch; ++p) os << "2 " << p + 1 << " \"" << names[p] << "\"\n";
  os << "3 " << npatch + 1 << " \"" << volume_name << "\"\n$EndPhysicalNames\n";

  os << "$Comments\nWritten by Hex_meshing_3. Patches (physical tag, name, type):\n";
  for(std::size_t p = 0; p < npatch; ++p)
    os << p + 1 << " " << names[p] << " " << internal::replace_chars(mesh.patch_type(p), "", '_') << "\n";
  os << "Hanging nodes: " << mesh.hanging_nodes.size()
     << (mesh.hanging_nodes.empty() ? " (conformal mesh)\n" : " (non-conformal mesh, constraints not stored)\n")
     << "$EndComments\n";

  os << "$Entities\n0 0 " << nsurf << " 1\n";
  for(std::size_t p = 0; p < npatch; ++p) {
    if(faces_of[p].empty()) continue;
    Box b;
    for(std::size_t f : faces_of[p])
      for(auto v : mesh.boundary_faces[f].vertices) b.add(xyz[v]);
    os << p + 1;
    write_box(b);
    os << " 1 " << p + 1 << " 0\n";
  }
  {
    Box b;
    for(const auto& q : xyz) b.add(q);
    os << 1;
    write_box(b);
    os << " 1 " << npatch + 1 << " " << nsurf;
    for(std::size_t p = 0; p < npatch; ++p) if(!faces_of[p].empty()) os << " " << p + 1;
    os << "\n$EndEntities\n";
  }

  os << "$Nodes\n";
  if(np == 0) os << "0 0 0 0\n";
  else {
    os << "1 " << np << " 1 " << np << "\n3 1 0 " << np << "\n";
    for(std::size_t i = 0; i < np; ++i) os << i + 1 << "\n";
    for(const auto& q : xyz) {
      std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g\n", q[0], q[1], q[2]);
      os << buf;
    }
  }
  os << "$EndNodes\n";

  const std::size_t ne = nq + nh;
  os << "$Elements\n" << nsurf + (nh > 0 ? 1 : 0) << " " << ne << " " << (ne > 0 ? 1 : 0) << " " << ne << "\n";
  std::size_t tag = 1;
  for(std::size_t p = 0; p < npatch; ++p) {
    if(faces_of[p].empty()) continue;
    os << "2 " << p + 1 << " 3 " << faces_of[p].size() << "\n";
    for(std::size_t f : faces_of[p]) {
      const auto& v = mesh.boundary_faces[f].vertices;
      os << tag++ << " " << v[0] + 1 << " " << v[1] + 1 << " " << v[2] + 1 << " " << v[3] + 1 << "\n";
    }
  }
  if(nh > 0) {
    os << "3 1 5 " << nh << "\n";
    for(const auto& h : mesh.hexahedra) {   // VTK order == Gmsh order
      os << tag++;
      for(auto v : h) os << " " << v + 1;
      os << "\n";
    }
  }
  os << "$EndElements\n";
  return bool(os);
}

} // namespace IO
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_IO_WRITE_MSH_H
