// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_WRITE_OPENFOAM_H
#define CGAL_HEX_MESHING_3_IO_WRITE_OPENFOAM_H

// OpenFOAM polyMesh (ASCII, points with 17 significant digits) in <case>/constant/polyMesh, and a
// minimal <case>/system/{controlDict,fvSchemes,fvSolution} when there are none, so that checkMesh and the solvers can run.
// Patch types come from the mesh (box faces `patch`, surface parts `wall` unless changed).

#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {

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
 * \return `false` if a file cannot be written
 */
template <typename HexMesh>
bool write_OpenFOAM(const std::string& case_dir, const HexMesh& mesh, const Polyhedral_mesh_3& pm)
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
    for(const auto& p : mesh.points) {
      std::snprintf(buf, sizeof buf, "(%.17g %.17g %.17g)\n", CGAL::to_double(p.x()), CGAL::to_double(p.y()),
                    CGAL::to_double(p.z()));
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
