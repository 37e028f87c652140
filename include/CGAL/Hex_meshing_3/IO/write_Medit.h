// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_WRITE_MEDIT_H
#define CGAL_HEX_MESHING_3_IO_WRITE_MEDIT_H

// INRIA Medit / Gamma Mesh Format ASCII (.mesh), readable by libMeshb, Medit, Gmsh and meshio.
//
//     MeshVersionFormatted 2        (double precision)
//     Dimension 3
//     # patch 1 = xmin (patch)      one comment line per patch: ref = name (type)
//     ...
//     Vertices / Quadrilaterals / Hexahedra / End
//
// Vertices have reference 0; boundary quadrilaterals (in the order of `mesh.boundary_faces`,
// counter-clockwise seen from outside the mesh) have reference patch index + 1; hexahedra have
// reference 1. Indices are one-based. Sections without entries are left out.
// Patch names cannot be stored in the format, hence the comment lines: a line whose first token
// starts with '#' is a comment for libMeshb (its ASCII keyword scanner skips the rest of the line),
// for Mmg's documented format, for meshio's reader and for Gmsh's. They come after the
// MeshVersionFormatted and Dimension lines, as the format asks the file to begin with
// MeshVersionFormatted.
//
// Corner order: the libMeshb documentation only says "8 vertex indices and a reference"; in
// practice the order is bottom face 1-2-3-4 then top face 5-6-7-8, vertex 4+i above vertex i, with
// the same handedness as VTK's order, which the package uses. Readers agree: meshio maps Medit
// "Hexahedra" to its VTK-ordered "hexahedron" without permutation; Gmsh's Medit reader builds its
// MHexahedron (same order as VTK) from the file order, and Gmsh 4.8 finds positive Jacobians for
// the cells written here (negative ones once top and bottom faces are swapped); libMeshb-based
// converters pass the 8 indices straight to VTK_HEXAHEDRON; ultimaille's Medit reader permutes
// them with {0,1,3,2,4,5,7,6} into its lexicographic order, i.e. reads them in VTK order. So the
// hexahedra are written unchanged, and a cell with positive Jacobians in VTK order stays positive.

#include <CGAL/Hex_meshing_3/IO/internal/patch_names.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {


/*!
 * \ingroup PkgHexMeshing3IO
 * \brief writes `mesh` to `filename` as an INRIA Medit (Gamma Mesh Format) ASCII file, version 2
 * (double precision): vertices, boundary quadrilaterals with reference patch index + 1, and
 * hexahedra with reference 1. The patch names and types, which the format cannot hold, are written
 * as comment lines `# patch <ref> = <name> (<type>)` after the header.
 *
 * The mesh may be non-conformal: where a coarse cell meets finer ones, a face of the coarse
 * hexahedron is covered by 4 faces of finer hexahedra, whose extra vertices (hanging nodes) lie
 * inside the coarse face or on its edges. Likewise a boundary quadrilateral may be a quarter of a
 * face of its (coarser) hexahedron, so that some boundary vertices belong to no hexahedron. The
 * format has no notion of such constraints: the mesh is stored as is, hanging nodes being ordinary
 * vertices (their count is given in a comment line); a solver reading the file must either accept
 * non-conformal meshes or constrain those vertices itself (see `mesh.hanging_nodes`, which this
 * file does not store).
 *
 * Boundary faces with a negative patch index are not written.
 *
 * \tparam HexMesh a `Hex_mesh_3` (or a type with the same public members `points`, `hexahedra`,
 * `boundary_faces`, `patch_names`, `hanging_nodes` and `patch_type()`)
 * \return `false` if the file cannot be written
 */
template <typename HexMesh>
bool write_Medit(const std::string& filename, const HexMesh& mesh)
{
  const std::size_t npatch = internal::number_of_patches(mesh);
  std::size_t nq = 0;
  for(const auto& f : mesh.boundary_faces) if(f.patch >= 0) ++nq;

  std::ofstream os(filename);
  if(!os) return false;
  char buf[96];

  os << "MeshVersionFormatted 2\n\nDimension 3\n\n";
  os << "# Written by Hex_meshing_3. Quadrilateral references are patches:\n";
  for(std::size_t p = 0; p < npatch; ++p)
    os << "# patch " << p + 1 << " = " << internal::replace_chars(internal::patch_name(mesh, p), "", ' ')
       << " (" << internal::replace_chars(mesh.patch_type(p), "", ' ') << ")\n";
  os << "# hanging nodes: " << mesh.hanging_nodes.size()
     << (mesh.hanging_nodes.empty() ? " (conformal mesh)\n\n" : " (non-conformal mesh, constraints not stored)\n\n");

  os << "Vertices\n" << mesh.points.size() << "\n";
  for(const auto& p : mesh.points) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g 0\n", CGAL::to_double(p.x()), CGAL::to_double(p.y()),
                  CGAL::to_double(p.z()));
    os << buf;
  }

  if(nq > 0) {
    os << "\nQuadrilaterals\n" << nq << "\n";
    for(const auto& f : mesh.boundary_faces) {
      if(f.patch < 0) continue;
      for(auto v : f.vertices) os << v + 1 << " ";
      os << f.patch + 1 << "\n";
    }
  }

  if(!mesh.hexahedra.empty()) {
    os << "\nHexahedra\n" << mesh.hexahedra.size() << "\n";
    for(const auto& h : mesh.hexahedra) {   // VTK order == Gamma Mesh Format order
      for(auto v : h) os << v + 1 << " ";
      os << "1\n";
    }
  }

  os << "\nEnd\n";
  return bool(os);
}

} // namespace IO
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_IO_WRITE_MEDIT_H
