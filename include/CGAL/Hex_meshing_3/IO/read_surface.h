// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_IO_READ_SURFACE_H
#define CGAL_HEX_MESHING_3_IO_READ_SURFACE_H

#include <CGAL/Hex_meshing_3/Status.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace IO {

/*!
 * \ingroup PkgHexMeshing3IO
 * \brief reads a triangulated surface (OFF, OBJ, STL ASCII or binary, PLY, by the file's extension)
 * as a triangle soup: polygons with more than three corners are split into fans.
 *
 * \throws Input_error with a one-line message naming the file and the cause when the file cannot
 * be opened, has an unknown extension, cannot be parsed, has no triangle, or has a coordinate
 * that is not finite.
 */
template <typename Point_3>
void read_surface(const std::string& filename,
                  std::vector<Point_3>& points,
                  std::vector<std::array<std::uint32_t, 3>>& triangles)
{
  const std::string::size_type dot = filename.find_last_of('.');
  std::string ext = dot == std::string::npos ? std::string() : filename.substr(dot + 1);
  for(char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if(ext != "off" && ext != "obj" && ext != "stl" && ext != "ply")
    throw Input_error(filename + ": unknown surface format '" + ext + "' (expected .off, .obj, .stl or .ply)");

  {
    std::ifstream probe(filename, std::ios::binary);
    if(!probe)
      throw Input_error(filename + ": cannot open the file for reading");
    probe.seekg(0, std::ios::end);
    if(probe.tellg() <= 0)
      throw Input_error(filename + ": the file is empty");
  }
  std::vector<Point_3> pts;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(filename, pts, polygons);
  } catch(const std::exception& e) {
    throw Input_error(filename + ": cannot parse the file as " + ext + " (" + e.what() + ")");
  }
  if(!ok)
    throw Input_error(filename + ": cannot parse the file as " + ext);
  for(const Point_3& p : pts)
    if(!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
       !std::isfinite(CGAL::to_double(p.z())))
      throw Input_error(filename + ": a vertex has a coordinate that is not a finite number");

  points = std::move(pts);
  triangles.clear();
  triangles.reserve(polygons.size());
  for(const auto& poly : polygons) {
    for(std::size_t id : poly)
      if(id >= points.size())
        throw Input_error(filename + ": a face refers to vertex " + std::to_string(id) +
                          " but the file has " + std::to_string(points.size()) + " vertices");
    for(std::size_t i = 2; i < poly.size(); ++i)
      triangles.push_back({{std::uint32_t(poly[0]), std::uint32_t(poly[i - 1]), std::uint32_t(poly[i])}});
  }
  if(triangles.empty())
    throw Input_error(filename + ": the surface has no triangle");
}

} // namespace IO
} // namespace Hex_meshing_3
} // namespace CGAL

#endif
