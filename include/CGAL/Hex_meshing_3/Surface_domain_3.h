// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_SURFACE_DOMAIN_3_H
#define CGAL_HEX_MESHING_3_SURFACE_DOMAIN_3_H

// A triangulated surface seen as a meshing domain. Cells are given as the 8 corners of a
// hexahedron in VTK order (see Hex_mesh_3.h); a cell is the convex hull of its corners, so the
// queries stay right once the grid is deformed.

#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/Status.h>
#include <CGAL/Hex_meshing_3/IO/read_surface.h>
#include <CGAL/Hex_meshing_3/internal/Fast_winding_number_3.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Bbox_3.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {

/*!
 * \ingroup PkgHexMeshing3Domains
 * \brief a triangulated surface (a soup, possibly open, overlapping or several parts) as a
 * meshing domain: exact cell/triangle intersection tests, closest points, and an inside test.
 *
 * Model of `HexMeshDomain_3`.
 *
 * Inside test: when the soup is a closed, consistently oriented, self-intersection-free
 * triangle mesh, `is_inside()` uses `CGAL::Side_of_triangle_mesh` (exact); otherwise it thresholds
 * the generalised winding number at 0.5, a floating-point estimate (the one documented exception
 * to exact predicates), computed hierarchically (far field by a second-order dipole expansion).
 *
 * \tparam GeomTraits a model of `Kernel` with exact predicates
 */
template <typename GeomTraits>
class Surface_domain_3
{
public:
  typedef GeomTraits                          Geom_traits;
  typedef typename GeomTraits::FT             FT;
  typedef typename GeomTraits::Point_3        Point_3;
  typedef typename GeomTraits::Triangle_3     Triangle_3;
  typedef typename GeomTraits::Tetrahedron_3  Tetrahedron_3;
  typedef std::array<std::uint32_t, 3>        Triangle_indices;

  /// what happened to the soup when the domain was built
  struct Input_summary
  {
    std::size_t input_points = 0, input_triangles = 0;
    std::size_t merged_points = 0;          ///< exactly coincident points merged
    std::size_t degenerate_triangles = 0;   ///< removed: two equal corners, or collinear
    bool closed = false;                    ///< a closed, manifold, consistently oriented mesh
    bool self_intersecting = false;         ///< tested only when `closed`
    bool reoriented = false;                ///< a closed inward-oriented mesh was flipped
    bool exact_inside_test = false;         ///< `Side_of_triangle_mesh` is used
  };

  /// \name Creation
  /// @{

  /*!
   * builds the domain from a triangle soup. `patch_of_triangle` (empty: all 0) gives each triangle
   * a part index into `patch_names` (empty: one part named `"surface"`).
   * \throws Input_error if no non-degenerate triangle remains or a coordinate is not finite.
   */
  Surface_domain_3(std::vector<Point_3> points,
                   std::vector<Triangle_indices> triangles,
                   std::vector<int> patch_of_triangle = {},
                   std::vector<std::string> patch_names = {})
  {
    init(std::move(points), std::move(triangles), std::move(patch_of_triangle), std::move(patch_names));
  }

  /*!
   * reads the surface from a file (see `IO::read_surface()`); the part is named after the file's
   * base name.
   * \throws Input_error
   */
  explicit Surface_domain_3(const std::string& filename)
  {
    std::vector<Point_3> pts;
    std::vector<Triangle_indices> tris;
    IO::read_surface(filename, pts, tris);
    std::string base = filename.substr(filename.find_last_of("/\\") + 1);
    base = base.substr(0, base.find('.'));
    if(base.empty()) base = "surface";
    init(std::move(pts), std::move(tris), {}, {base});
  }
  /// @}

  /// \name Access
  /// @{
  const Bbox_3& bbox() const { return m_bbox; }
  std::size_t number_of_triangles() const { return m_triangles.size(); }
  const Triangle_3& triangle(std::size_t i) const { return m_triangles[i]; }
  const Bbox_3& triangle_bbox(std::size_t i) const { return m_tri_bboxes[i]; }
  int patch(std::size_t i) const { return m_patch[i]; }
  const std::vector<std::string>& patch_names() const { return m_patch_names; }
  const std::vector<Point_3>& points() const { return m_points; }
  const std::vector<Triangle_indices>& triangle_indices() const { return m_indices; }
  const Input_summary& input_summary() const { return m_summary; }
  /// `true` if `is_inside()` is exact (closed, consistently oriented, not self-intersecting input)
  bool has_exact_inside_test() const { return bool(m_side); }
  /// @}

  /// \name Queries
  /// @{

  /// exact: does the closed axis-aligned box `b` meet triangle `i`?
  bool do_intersect(const Bbox_3& b, std::size_t i) const
  {
    if(!CGAL::do_overlap(b, m_tri_bboxes[i])) return false;
    return CGAL::do_intersect(b, m_triangles[i]);
  }

  /*!
   * exact: does the convex hull of the 8 points `cell` meet triangle `i`? When the corners form an
   * axis-aligned box (tested exactly) the box test is used; otherwise, by Carathéodory's theorem the
   * hull is the union of the non-degenerate tetrahedra on 4 of its corners, each tested exactly.
   */
  bool do_intersect(const std::array<Point_3, 8>& cell, std::size_t i) const
  {
    Bbox_3 b = cell[0].bbox();
    for(int k = 1; k < 8; ++k) b += cell[k].bbox();
    if(!CGAL::do_overlap(b, m_tri_bboxes[i])) return false;
    if(is_axis_aligned_box(cell)) return CGAL::do_intersect(b, m_triangles[i]);
    for(int a = 0; a < 8; ++a)
      for(int c = a + 1; c < 8; ++c)
        for(int d = c + 1; d < 8; ++d)
          for(int e = d + 1; e < 8; ++e) {
            if(CGAL::orientation(cell[a], cell[c], cell[d], cell[e]) == CGAL::COPLANAR) continue;
            if(CGAL::do_intersect(Tetrahedron_3(cell[a], cell[c], cell[d], cell[e]), m_triangles[i]))
              return true;
          }
    return false;
  }

  /// exact: are the 8 corners (VTK order) those of an axis-aligned box?
  static bool is_axis_aligned_box(const std::array<Point_3, 8>& c)
  {
    // each corner's coordinates are corner 0's or corner 6's, by its lattice offsets (exact compare)
    const auto& o = hex_corner_offsets();
    for(int k = 1; k < 8; ++k) {
      if(c[k].x() != (o[k][0] ? c[6].x() : c[0].x())) return false;
      if(c[k].y() != (o[k][1] ? c[6].y() : c[0].y())) return false;
      if(c[k].z() != (o[k][2] ? c[6].z() : c[0].z())) return false;
    }
    return c[0].x() < c[6].x() && c[0].y() < c[6].y() && c[0].z() < c[6].z();
  }

  /// generalised winding number at `p` (floating point)
  double winding_number(const Point_3& p) const
  {
    return m_wn({{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}});
  }

  /// is `p` inside the surface? Exact for closed input (see the class description), winding
  /// number >= 0.5 otherwise. A point on the surface counts as inside.
  bool is_inside(const Point_3& p) const
  {
    if(m_side) return (*m_side)(p) != CGAL::ON_UNBOUNDED_SIDE;
    return winding_number(p) >= 0.5;
  }

  /// the point of the surface nearest to `p`
  Point_3 closest_point(const Point_3& p) const { return tree().closest_point(p); }
  /// the index of a triangle nearest to `p`
  std::size_t closest_triangle(const Point_3& p) const
  {
    return std::size_t(tree().closest_point_and_primitive(p).second - m_triangles.begin());
  }
  /// squared distance from `p` to the surface
  FT squared_distance(const Point_3& p) const { return tree().squared_distance(p); }
  /// @}

private:
  typedef typename std::vector<Triangle_3>::const_iterator Tri_iterator;
  typedef CGAL::AABB_triangle_primitive<GeomTraits, Tri_iterator> Primitive;
  typedef CGAL::AABB_traits<GeomTraits, Primitive> AABB_traits;
  typedef CGAL::AABB_tree<AABB_traits> Tree;
  typedef CGAL::Surface_mesh<Point_3> Mesh;
  typedef CGAL::Side_of_triangle_mesh<Mesh, GeomTraits> Side;

  const Tree& tree() const
  {
    if(!m_tree) {
      m_tree = std::make_unique<Tree>(m_triangles.begin(), m_triangles.end());
      m_tree->accelerate_distance_queries();
    }
    return *m_tree;
  }

  void init(std::vector<Point_3> points, std::vector<Triangle_indices> triangles,
            std::vector<int> patch_of_triangle, std::vector<std::string> patch_names)
  {
    namespace PMP = CGAL::Polygon_mesh_processing;
    m_summary.input_points = points.size();
    m_summary.input_triangles = triangles.size();
    if(patch_names.empty()) patch_names.push_back("surface");
    if(patch_of_triangle.size() != triangles.size()) patch_of_triangle.assign(triangles.size(), 0);
    for(int p : patch_of_triangle)
      if(p < 0 || std::size_t(p) >= patch_names.size())
        throw Input_error("surface: a triangle's part index " + std::to_string(p) + " is not among the " +
                          std::to_string(patch_names.size()) + " part names");
    for(const Point_3& p : points)
      if(!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
         !std::isfinite(CGAL::to_double(p.z())))
        throw Input_error("surface: a vertex has a coordinate that is not a finite number");
    for(const Triangle_indices& t : triangles)
      for(std::uint32_t v : t)
        if(v >= points.size()) throw Input_error("surface: a triangle refers to a missing vertex");

    // merge exactly coincident points (soups from STL have one point per triangle corner)
    std::vector<std::vector<std::size_t>> polys(triangles.size());
    for(std::size_t i = 0; i < triangles.size(); ++i)
      polys[i].assign(triangles[i].begin(), triangles[i].end());
    m_summary.merged_points = PMP::merge_duplicate_points_in_polygon_soup(points, polys);

    // remove degenerate triangles (exact collinearity), keep patch ids aligned
    m_points = std::move(points);
    for(std::size_t i = 0; i < polys.size(); ++i) {
      const auto& q = polys[i];
      if(q[0] == q[1] || q[1] == q[2] || q[0] == q[2] ||
         CGAL::collinear(m_points[q[0]], m_points[q[1]], m_points[q[2]])) {
        ++m_summary.degenerate_triangles;
        continue;
      }
      m_indices.push_back({{std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])}});
      m_patch.push_back(patch_of_triangle[i]);
    }
    if(m_indices.empty())
      throw Input_error("surface: no non-degenerate triangle");
    m_patch_names = std::move(patch_names);

    // closed, consistently oriented, no self-intersection: exact inside test
    std::vector<std::vector<std::size_t>> tri_polys(m_indices.size());
    for(std::size_t i = 0; i < m_indices.size(); ++i)
      tri_polys[i].assign(m_indices[i].begin(), m_indices[i].end());
    if(PMP::is_polygon_soup_a_polygon_mesh(tri_polys)) {
      m_mesh = std::make_unique<Mesh>();
      PMP::polygon_soup_to_polygon_mesh(m_points, tri_polys, *m_mesh);
      if(CGAL::is_closed(*m_mesh) && CGAL::is_triangle_mesh(*m_mesh)) {
        m_summary.self_intersecting = PMP::does_self_intersect(*m_mesh);
        if(!m_summary.self_intersecting) {
          m_summary.closed = true;
          if(!PMP::is_outward_oriented(*m_mesh)) {
            m_summary.reoriented = true;
            for(Triangle_indices& t : m_indices) std::swap(t[1], t[2]);
            PMP::reverse_face_orientations(*m_mesh);
          }
          m_side = std::make_unique<Side>(*m_mesh);
          m_summary.exact_inside_test = true;
        }
      }
      if(!m_side) m_mesh.reset();
    }

    m_triangles.reserve(m_indices.size());
    m_tri_bboxes.reserve(m_indices.size());
    std::vector<double> flat;
    flat.reserve(9 * m_indices.size());
    m_bbox = Bbox_3();
    for(const Triangle_indices& t : m_indices) {
      m_triangles.emplace_back(m_points[t[0]], m_points[t[1]], m_points[t[2]]);
      m_tri_bboxes.push_back(m_triangles.back().bbox());
      m_bbox += m_tri_bboxes.back();
      for(int k = 0; k < 3; ++k) {
        flat.push_back(CGAL::to_double(m_points[t[k]].x()));
        flat.push_back(CGAL::to_double(m_points[t[k]].y()));
        flat.push_back(CGAL::to_double(m_points[t[k]].z()));
      }
    }
    m_wn.build(flat, 2.0);
  }

  std::vector<Point_3> m_points;
  std::vector<Triangle_indices> m_indices;
  std::vector<Triangle_3> m_triangles;
  std::vector<Bbox_3> m_tri_bboxes;
  std::vector<int> m_patch;
  std::vector<std::string> m_patch_names;
  Bbox_3 m_bbox;
  Input_summary m_summary;
  internal::Fast_winding_number_3 m_wn;
  std::unique_ptr<Mesh> m_mesh;
  std::unique_ptr<Side> m_side;
  mutable std::unique_ptr<Tree> m_tree;
};

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_SURFACE_DOMAIN_3_H
