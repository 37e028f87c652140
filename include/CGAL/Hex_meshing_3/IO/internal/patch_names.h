// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_INTERNAL_PATCH_NAMES_H
#define CGAL_HEX_MESHING_3_IO_INTERNAL_PATCH_NAMES_H

// Patch helpers shared by the Gmsh and Medit writers.

#include <algorithm>
#include <cstddef>
#include <string>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {
namespace internal {

/// number of patches: the size of `patch_names`, or more if a boundary face refers to a larger index
template <typename HexMesh>
std::size_t number_of_patches(const HexMesh& mesh)
{
  std::size_t n = mesh.patch_names.size();
  for(const auto& f : mesh.boundary_faces)
    if(f.patch >= 0) n = (std::max)(n, std::size_t(f.patch) + 1);
  return n;
}

/// the name of patch `p` (`"patch_<p>"` when `patch_names` has none)
template <typename HexMesh>
std::string patch_name(const HexMesh& mesh, std::size_t p)
{
  if(p < mesh.patch_names.size() && !mesh.patch_names[p].empty()) return mesh.patch_names[p];
  return "patch_" + std::to_string(p);
}

/// `s` with every character in `bad` and every control character replaced by `by`
inline std::string replace_chars(const std::string& s, const char* bad, char by)
{
  std::string r = s;
  for(char& c : r)
    if(static_cast<unsigned char>(c) < 32 || c == 127 || std::string(bad).find(c) != std::string::npos)
      c = by;
  return r;
}

} // namespace internal
} // namespace IO
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_IO_INTERNAL_PATCH_NAMES_H
