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
#include <CGAL/Hex_meshing_3/internal/hole_fill.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Bbox_3.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <functional>
#include <map>
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
 * Holes: unless told not to (`fill_holes = false`), the holes of the surface are closed by
 * triangles that are not the input's (`is_fill()`): each loop of border edges (of one-sided
 * triangles, not along another border edge - a seam or a crack) is filled by CGAL's
 * `Polygon_mesh_processing::triangulate_hole_polyline()`, without new vertices (see
 * `internal::fill_holes()` for the loops left open). The fill bounds the volume like the input
 * (the grid stops there, the mesh boundary lies on it, the inside test counts it) and has the part
 * of the faces round its rim; the boundary's faces on a fill are caps (`Boundary_fidelity`), and
 * the feature curves judge each rim as a whole (`Feature_curves_3`). A surface closed by its fills
 * (and free of self-intersections) gets the exact inside test.
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

  /// what happened to the soup when the domain was built: the repairs, and what the surface is
  struct Input_summary
  {
    std::size_t input_points = 0, input_triangles = 0;
    std::size_t merged_points = 0;          ///< exactly coincident points merged
    std::size_t degenerate_triangles = 0;   ///< removed: two equal corners, or collinear (exact)
    std::size_t duplicate_triangles = 0;    ///< removed: same corners, same orientation as a kept face
    std::size_t reversed_duplicates = 0;    ///< removed: same corners, opposite orientation to a kept face
    std::size_t sheet_triangles = 0;        ///< kept faces of zero-thickness sheets (a face and its reversed copy), two-sided
    std::size_t sheet_reoriented = 0;       ///< sheet faces flipped (with their two sides' parts) so that each sheet's sides are consistent
    std::size_t sheet_back_parts = 0;       ///< parts added for the back side of sheets whose two copies were in one part (`NAME_back`)
    std::size_t reoriented_triangles = 0;   ///< flipped to agree with their neighbours or to face outward
    std::size_t internal_triangles = 0;     ///< left out of the boundary, wholly or partly: inside the volume on both sides (overlapping parts)
    std::size_t split_triangles = 0;        ///< pieces kept of the partly inside triangles (split at edge midpoints)
    std::size_t components = 0;             ///< edge-connected components (sheets excluded)
    std::size_t boundary_edges = 0;         ///< edges of one face: holes, cracks, open rims (after repair, before the holes are filled)
    std::size_t filled_holes = 0;           ///< holes closed by fill triangles (see `Surface_domain_3`)
    std::size_t fill_triangles = 0;         ///< the triangles added to fill them
    std::size_t filled_rim_edges = 0;       ///< the boundary edges on their rims
    std::size_t non_manifold_edges = 0;     ///< edges of more than two faces (after repair)
    bool closed = false;                    ///< a closed, manifold, consistently oriented mesh (its holes filled)
    bool self_intersecting = false;         ///< tested only when `closed`
    bool reoriented = false;                ///< some faces were reoriented
    bool exact_inside_test = false;         ///< `Side_of_triangle_mesh` is used
  };

  /// \name Creation
  /// @{

  /*!
   * builds the domain from a triangle soup. `patch_of_triangle` (empty: all 0) gives each triangle
   * a part index into `patch_names` (empty: one part named `"surface"`). `fill_holes`: whether the
   * holes are closed (see the class description).
   * \throws Input_error if no non-degenerate triangle remains or a coordinate is not finite.
   */
  Surface_domain_3(std::vector<Point_3> points,
                   std::vector<Triangle_indices> triangles,
                   std::vector<int> patch_of_triangle = {},
                   std::vector<std::string> patch_names = {},
                   bool fill_holes = true)
  {
    init(std::move(points), std::move(triangles), std::move(patch_of_triangle), std::move(patch_names), fill_holes);
  }

  /*!
   * builds the domain from a soup read by `IO::read_surface()`; its parts become the domain's parts.
   * \throws Input_error
   */
  explicit Surface_domain_3(const IO::Surface_soup<Point_3>& soup, bool fill_holes = true)
  {
    init(soup.points, soup.triangles, soup.part_of_triangle, soup.part_names, fill_holes);
  }

  /*!
   * reads the surface from a file (see `IO::read_surface()`): OBJ groups and STL solids are parts,
   * otherwise the file is one part named after its base name.
   * \throws Input_error
   */
  explicit Surface_domain_3(const std::string& filename, double scale = 1.0, bool fill_holes = true)
  {
    IO::Surface_soup<Point_3> soup;
    IO::read_surface(filename, soup, scale);
    init(std::move(soup.points), std::move(soup.triangles), std::move(soup.part_of_triangle),
         std::move(soup.part_names), fill_holes);
  }
  /// @}

  /// \name Access
  /// @{
  const Bbox_3& bbox() const { return m_bbox; }
  std::size_t number_of_triangles() const { return m_triangles.size(); }
  const Triangle_3& triangle(std::size_t i) const { return m_triangles[i]; }
  /// (computed: storing them took 48 bytes a triangle, 13 MB on motorBike, through the whole run)
  Bbox_3 triangle_bbox(std::size_t i) const { return m_triangles[i].bbox(); }
  /// the part of triangle `i` (of a sheet: the part of its front side, where its normal points)
  int patch(std::size_t i) const { return m_patch[i]; }
  /// the part of the back side of triangle `i`: of a sheet, the part its reversed copy had (or the
  /// added part `NAME_back` when both copies were in part `NAME`); of any other triangle, `patch(i)`
  int back_patch(std::size_t i) const { return m_back_patch[i]; }
  /*!
   * the part of the side of triangle `i` that faces `p`: `patch(i)`, or for a sheet whose back side
   * faces `p` (`p` strictly below the triangle's oriented plane, exact test), `back_patch(i)`.
   * A mesh face bounding the air on one side of a sheet gets this part, so the two sides of a sheet
   * are two patches (OpenFOAM's baffles).
   */
  int patch_facing(std::size_t i, const Point_3& p) const
  {
    if(!m_two_sided[i]) return m_patch[i];
    const Triangle_indices& t = m_indices[i];
    return CGAL::orientation(m_points[t[0]], m_points[t[1]], m_points[t[2]], p) == CGAL::NEGATIVE ? m_back_patch[i] : m_patch[i];
  }
  /*!
   * are triangles `i` and `j`, which share an edge, in the same part? `consistent`: they run the
   * edge in opposite directions (oriented alike). Two sheet faces are when both their sides are:
   * front with front and back with back if oriented alike, front with back otherwise. Any other
   * pair compares its (front) parts.
   */
  bool same_part(std::size_t i, std::size_t j, bool consistent = true) const
  {
    if(m_two_sided[i] && m_two_sided[j])
      return consistent ? m_patch[i] == m_patch[j] && m_back_patch[i] == m_back_patch[j]
                        : m_patch[i] == m_back_patch[j] && m_back_patch[i] == m_patch[j];
    return m_patch[i] == m_patch[j];
  }
  const std::vector<std::string>& patch_names() const { return m_patch_names; }
  const std::vector<Point_3>& points() const { return m_points; }
  const std::vector<Triangle_indices>& triangle_indices() const { return m_indices; }
  const Input_summary& input_summary() const { return m_summary; }
  /*!
   * sets the feature edges (pairs of point indices, e.g. `Feature_curves_3::edges()`): cells they
   * meet can be refined to the criteria's feature size. Pairs that are not an edge of a triangle
   * are ignored.
   */
  template <typename EdgeRange>
  void set_feature_edges(const EdgeRange& edges)
  {
    std::vector<std::uint64_t> keys;
    for(const auto& e : edges) {
      const std::uint32_t a = std::uint32_t(e[0]), b = std::uint32_t(e[1]);
      keys.push_back(edge_key(a, b));
    }
    std::sort(keys.begin(), keys.end());
    m_feature_mask.assign(m_indices.size(), 0);
    m_has_features = !m_feature_segments.empty();
    for(std::size_t t = 0; t < m_indices.size(); ++t)
      for(int k = 0; k < 3; ++k)
        if(std::binary_search(keys.begin(), keys.end(), edge_key(m_indices[t][std::size_t(k)], m_indices[t][std::size_t((k + 1) % 3)]))) {
          m_feature_mask[t] |= std::uint8_t(1u << k);
          m_has_features = true;
        }
  }
  /*!
   * adds user feature lines (polylines given as point sequences, anywhere in space, e.g. read by
   * `IO::read_polylines()`): cells they meet are refined to the criteria's feature size like the
   * cells meeting feature edges.
   */
  void add_feature_polylines(const std::vector<std::vector<Point_3>>& polylines)
  {
    for(const auto& pl : polylines)
      for(std::size_t i = 1; i < pl.size(); ++i)
        if(pl[i - 1] != pl[i]) m_feature_segments.emplace_back(pl[i - 1], pl[i]);
    m_segment_tree.reset();
    if(!m_feature_segments.empty()) {
      m_segment_tree = std::make_unique<Segment_tree>(m_feature_segments.begin(), m_feature_segments.end());
      m_has_features = true;
      if(m_feature_mask.size() != m_indices.size()) m_feature_mask.assign(m_indices.size(), 0);
    }
  }
  /// the segments of the user feature lines
  const std::vector<typename GeomTraits::Segment_3>& feature_segments() const { return m_feature_segments; }
  /// are there feature edges or user feature lines?
  bool has_feature_edges() const { return m_has_features; }
  /// exact: does the closed box `b` meet a user feature line?
  bool do_intersect_feature_lines(const Bbox_3& b) const
  {
    if(!m_segment_tree) return false;
    return m_segment_tree->do_intersect(typename GeomTraits::Iso_cuboid_3(b));
  }
  /// exact: does the closed box `b` meet a feature edge of triangle `i`?
  bool do_intersect_feature(const Bbox_3& b, std::size_t i) const
  {
    if(!m_has_features || i >= m_feature_mask.size() || m_feature_mask[i] == 0) return false;
    for(int k = 0; k < 3; ++k)
      if(m_feature_mask[i] & (1u << k)) {
        const typename GeomTraits::Segment_3 s(m_points[m_indices[i][std::size_t(k)]], m_points[m_indices[i][std::size_t((k + 1) % 3)]]);
        if(CGAL::do_overlap(b, s.bbox()) && CGAL::do_intersect(b, s)) return true;
      }
    return false;
  }

  /// is triangle `i` part of a zero-thickness sheet (two-sided: it bounds no volume)?
  bool is_two_sided(std::size_t i) const { return m_two_sided[i]; }
  /// was triangle `i` added to fill a hole (not the input's)?
  bool is_fill(std::size_t i) const { return m_fill[i] != 0; }
  /// the hole that triangle `i` fills, from 1 (0: an input triangle)
  std::size_t filled_hole(std::size_t i) const { return m_fill[i]; }
  /// `true` if `is_inside()` is exact (closed, consistently oriented, not self-intersecting input)
  bool has_exact_inside_test() const { return bool(m_side); }
  /// @}

  /// \name Queries
  /// @{

  /// exact: does the closed axis-aligned box `b` meet triangle `i`?
  bool do_intersect(const Bbox_3& b, std::size_t i) const
  {
    if(!CGAL::do_overlap(b, triangle_bbox(i))) return false;
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
    if(!CGAL::do_overlap(b, triangle_bbox(i))) return false;
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

  /// frees the search tree of the distance and ray queries (built by the first such query; the
  /// next one builds it again): for a step that makes no query and needs the memory
  void release_search_tree() const { m_tree.reset(); }

  /// the point of the surface nearest to `p`
  Point_3 closest_point(const Point_3& p) const { return tree().closest_point(p); }
  /// the index of a triangle nearest to `p`
  std::size_t closest_triangle(const Point_3& p) const
  {
    return std::size_t(tree().closest_point_and_primitive(p).second - m_triangles.begin());
  }
  /// the point of the surface nearest to `p` and the index of a triangle it lies on
  std::pair<Point_3, std::size_t> closest_point_and_triangle(const Point_3& p) const
  {
    const auto r = tree().closest_point_and_primitive(p);
    return {r.first, std::size_t(r.second - m_triangles.begin())};
  }
  /// squared distance from `p` to the surface
  FT squared_distance(const Point_3& p) const { return tree().squared_distance(p); }
  /// the first point where the ray from `p` in direction `d` meets the surface, if any (the
  /// intersection point is constructed in floating point; a ray along a triangle gives the
  /// segment's first end)
  /// (and, if `triangle` is given, the index of the triangle met there)
  bool first_ray_hit(const Point_3& p, const typename GeomTraits::Vector_3& d, Point_3& hit,
                     std::size_t* triangle = nullptr) const
  {
    const typename GeomTraits::Ray_3 ray(p, d);
    const auto r = tree().first_intersection(ray);
    if(!r) return false;
    if(triangle) *triangle = std::size_t(r->second - m_triangles.begin());
    if(const Point_3* q = boost::get<Point_3>(&r->first)) { hit = *q; return true; }
    if(const typename GeomTraits::Segment_3* s = boost::get<typename GeomTraits::Segment_3>(&r->first)) {
      hit = CGAL::squared_distance(p, s->source()) < CGAL::squared_distance(p, s->target()) ? s->source() : s->target();
      return true;
    }
    return false;
  }
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
            std::vector<int> patch_of_triangle, std::vector<std::string> patch_names, bool fill_holes)
  {
    namespace PMP = CGAL::Polygon_mesh_processing;
    m_summary.input_points = points.size();
    m_summary.input_triangles = triangles.size();
    if(patch_names.empty()) patch_names.push_back("surface");
    if(patch_of_triangle.size() != triangles.size()) patch_of_triangle.assign(triangles.size(), 0);
    for(int p : patch_of_triangle)
      if(p < 0 || std::size_t(p) >= patch_names.size())
        throw Input_error("surface: a triangle's part index " + std::to_string(p) + " is not among the " +
                          std::to_string(patch_names.size()) + " part names", Input_error_cause::MALFORMED);
    for(const Point_3& p : points)
      if(!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
         !std::isfinite(CGAL::to_double(p.z())))
        throw Input_error("surface: a vertex has a coordinate that is not a finite number", Input_error_cause::NON_FINITE);
    for(const Triangle_indices& t : triangles)
      for(std::uint32_t v : t)
        if(v >= points.size()) throw Input_error("surface: a triangle refers to a missing vertex", Input_error_cause::BAD_INDEX);

    // merge exactly coincident points (soups from STL have one point per triangle corner)
    std::vector<std::vector<std::size_t>> polys(triangles.size());
    for(std::size_t i = 0; i < triangles.size(); ++i)
      polys[i].assign(triangles[i].begin(), triangles[i].end());
    m_summary.merged_points = PMP::merge_duplicate_points_in_polygon_soup(points, polys);

    // remove degenerate triangles (exact collinearity), keep patch ids aligned
    m_points = std::move(points);
    std::vector<Triangle_indices> tris;
    std::vector<int> parts;
    tris.reserve(polys.size());
    for(std::size_t i = 0; i < polys.size(); ++i) {
      const auto& q = polys[i];
      if(q[0] == q[1] || q[1] == q[2] || q[0] == q[2] ||
         CGAL::collinear(m_points[q[0]], m_points[q[1]], m_points[q[2]])) {
        ++m_summary.degenerate_triangles;
        continue;
      }
      tris.push_back({{std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])}});
      parts.push_back(patch_of_triangle[i]);
    }
    polys.clear();
    polys.shrink_to_fit();
    if(tris.empty())
      throw Input_error("surface: no non-degenerate triangle", Input_error_cause::NO_SURFACE);
    m_patch_names = std::move(patch_names);
    repair(tris, parts);
    m_fill.assign(m_indices.size(), 0);
    if(fill_holes && m_summary.boundary_edges > 0) fill_input_holes();

    // closed, consistently oriented, no self-intersection: exact inside test
    if(m_summary.sheet_triangles == 0 && m_summary.boundary_edges == m_summary.filled_rim_edges && m_summary.non_manifold_edges == 0) {
      // (on the points the triangles use: an unused point would be an isolated vertex, which
      // makes the mesh invalid for the orientation test)
      std::vector<std::size_t> compact(m_points.size(), std::size_t(-1));
      std::vector<Point_3> used;
      std::vector<std::vector<std::size_t>> tri_polys(m_indices.size());
      for(std::size_t i = 0; i < m_indices.size(); ++i)
        for(std::uint32_t v : m_indices[i]) {
          if(compact[v] == std::size_t(-1)) { compact[v] = used.size(); used.push_back(m_points[v]); }
          tri_polys[i].push_back(compact[v]);
        }
      if(PMP::is_polygon_soup_a_polygon_mesh(tri_polys)) {
        m_mesh = std::make_unique<Mesh>();
        PMP::polygon_soup_to_polygon_mesh(used, tri_polys, *m_mesh);
        if(CGAL::is_closed(*m_mesh) && CGAL::is_triangle_mesh(*m_mesh)) {
          m_summary.self_intersecting = PMP::does_self_intersect(*m_mesh);
          if(!m_summary.self_intersecting) {
            m_summary.closed = true;
            if(!PMP::is_outward_oriented(*m_mesh)) {   // e.g. several nested shells
              m_summary.reoriented = true;
              m_summary.reoriented_triangles += m_indices.size();
              for(Triangle_indices& t : m_indices) std::swap(t[1], t[2]);
              PMP::reverse_face_orientations(*m_mesh);
            }
            m_side = std::make_unique<Side>(*m_mesh);
            m_summary.exact_inside_test = true;
          }
        }
        if(!m_side) m_mesh.reset();
      }
    }

    m_triangles.reserve(m_indices.size());
    std::vector<double> coords;
    coords.reserve(3 * m_points.size());
    for(const Point_3& p : m_points)
      for(int d = 0; d < 3; ++d) coords.push_back(CGAL::to_double(p[d]));
    std::vector<std::uint32_t> wn_triangles;
    wn_triangles.reserve(3 * m_indices.size());
    m_bbox = Bbox_3();
    for(const Triangle_indices& t : m_indices) {
      m_triangles.emplace_back(m_points[t[0]], m_points[t[1]], m_points[t[2]]);
      m_bbox += m_triangles.back().bbox();
      if(m_two_sided[m_triangles.size() - 1]) continue;   // a sheet and its reversed copy cancel out
      wn_triangles.insert(wn_triangles.end(), t.begin(), t.end());
    }
    m_wn.build(std::move(coords), std::move(wn_triangles), 2.0);
    if(!m_side) remove_internal_triangles();
  }

  // Overlapping parts (a spout pushed into a body, parts exported with overlaps): the part of a
  // triangle that has the inside (winding number >= 0.5) on both of its sides bounds nothing and
  // would only stop the grid inside the volume; it is left out of the boundary (the winding number
  // keeps every triangle). Only triangles overlapping the bounding box of another edge-connected
  // component are examined. A triangle is sampled (1e-6 of the bounding box diagonal off it, on both
  // sides) at its centroid, near its corners and at its edge midpoints: all samples inside on both
  // sides -> left out; none -> kept; some -> split into 4 at its edge midpoints, recursively (at most
  // 6 times), so that the part outside the other body stays (a sub-triangle is kept at the last
  // level unless all its samples are inside). Sub-triangle corners are rounded midpoints.
  void remove_internal_triangles()
  {
    const std::size_t n = m_indices.size();
    const double diag = std::sqrt(CGAL::square(m_bbox.xmax() - m_bbox.xmin()) + CGAL::square(m_bbox.ymax() - m_bbox.ymin()) +
                                  CGAL::square(m_bbox.zmax() - m_bbox.zmin()));
    const double eps = 1e-6 * diag;
    // edge-connected components and their boxes
    std::vector<std::uint32_t> uf(n);
    for(std::size_t i = 0; i < n; ++i) uf[i] = std::uint32_t(i);
    auto find = [&](std::uint32_t x) { while(uf[x] != x) { uf[x] = uf[uf[x]]; x = uf[x]; } return x; };
    {
      std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
      edges.reserve(3 * n);
      for(std::size_t f = 0; f < n; ++f)
        for(int k = 0; k < 3; ++k) edges.push_back({edge_key(m_indices[f][k], m_indices[f][(k + 1) % 3]), std::uint32_t(f)});
      std::sort(edges.begin(), edges.end());
      for(std::size_t e = 1; e < edges.size(); ++e)
        if(edges[e].first == edges[e - 1].first) {
          const std::uint32_t x = find(edges[e].second), y = find(edges[e - 1].second);
          if(x != y) uf[(std::max)(x, y)] = (std::min)(x, y);
        }
    }
    std::vector<std::uint32_t> roots;
    std::vector<int> comp(n);
    std::vector<Bbox_3> comp_box;
    {
      std::vector<int> id(n, -1);
      for(std::size_t f = 0; f < n; ++f) {
        const std::uint32_t r = find(std::uint32_t(f));
        if(id[r] < 0) { id[r] = int(comp_box.size()); comp_box.push_back(Bbox_3()); }
        comp[f] = id[r];
        comp_box[std::size_t(id[r])] += triangle_bbox(f);
      }
    }
    if(comp_box.size() < 2) return;   // a single component cannot overlap another one

    typedef std::array<double, 3> V;
    auto both_sides_inside = [&](const V& p, const V& nrm) {
      V x, y;
      for(int k = 0; k < 3; ++k) { x[std::size_t(k)] = p[std::size_t(k)] + eps * nrm[std::size_t(k)]; y[std::size_t(k)] = p[std::size_t(k)] - eps * nrm[std::size_t(k)]; }
      return m_wn(x) >= 0.5 && m_wn(y) >= 0.5;
    };
    // 0: no sample inside on both sides, 1: some, 2: all
    auto classify = [&](const V& a, const V& b, const V& c) {
      const V u{{b[0] - a[0], b[1] - a[1], b[2] - a[2]}}, v{{c[0] - a[0], c[1] - a[1], c[2] - a[2]}};
      V nrm{{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]}};
      const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
      if(!(len > 0)) return 0;
      for(double& x : nrm) x /= len;
      static const double w[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.98, 0.01, 0.01}, {0.01, 0.98, 0.01}, {0.01, 0.01, 0.98},
                                     {0.495, 0.495, 0.01}, {0.01, 0.495, 0.495}, {0.495, 0.01, 0.495}};
      int inside = 0;
      for(const auto& wk : w) {
        V p;
        for(int k = 0; k < 3; ++k) p[std::size_t(k)] = wk[0] * a[std::size_t(k)] + wk[1] * b[std::size_t(k)] + wk[2] * c[std::size_t(k)];
        inside += both_sides_inside(p, nrm);
        if(inside > 0 && inside <= (&wk - w)) return 1;   // mixed already
      }
      return inside == 0 ? 0 : (inside == 7 ? 2 : 1);
    };
    std::map<V, std::uint32_t> point_index;   // corners of the pieces
    std::vector<Triangle_indices> out_idx;
    std::vector<int> out_patch, out_back;
    std::vector<bool> out_sided;
    std::vector<std::uint32_t> out_fill;
    std::vector<char> changed(n, 0);
    std::size_t left_out = 0;
    std::function<void(const V&, const V&, const V&, int, std::size_t)> split =
        [&](const V& a, const V& b, const V& c, int depth, std::size_t f) {
      const int k = classify(a, b, c);
      if(k == 2) return;
      if(k == 0 || depth == 6) {
        Triangle_indices t;
        const V* v[3] = {&a, &b, &c};
        for(int i = 0; i < 3; ++i) {   // pieces share their corners (midpoints are computed alike)
          const auto ins = point_index.emplace(*v[i], std::uint32_t(m_points.size()));
          if(ins.second) m_points.push_back(Point_3((*v[i])[0], (*v[i])[1], (*v[i])[2]));
          t[std::size_t(i)] = ins.first->second;
        }
        out_idx.push_back(t); out_patch.push_back(m_patch[f]); out_back.push_back(m_back_patch[f]); out_sided.push_back(m_two_sided[f]);
        out_fill.push_back(m_fill[f]);
        return;
      }
      auto mid = [](const V& p, const V& q) { return V{{(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2}}; };
      const V ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      split(a, ab, ca, depth + 1, f); split(ab, b, bc, depth + 1, f);
      split(ca, bc, c, depth + 1, f); split(ab, bc, ca, depth + 1, f);
    };
    // candidates: triangles whose box meets the box of another component (box intersection, not n x C)
    std::vector<char> candidate(n, 0);
    {
      typedef CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t> Box;
      std::vector<Box> tb, cb;
      tb.reserve(n);
      for(std::size_t f = 0; f < n; ++f) tb.push_back(Box(triangle_bbox(f), f));
      for(std::size_t c = 0; c < comp_box.size(); ++c) cb.push_back(Box(comp_box[c], c));
      CGAL::box_intersection_d(tb.begin(), tb.end(), cb.begin(), cb.end(), [&](const Box& t, const Box& c) {
        if(int(c.info()) != comp[t.info()]) candidate[t.info()] = 1;
      });
    }
    for(std::size_t f = 0; f < n; ++f) {
      if(!candidate[f]) continue;
      const V a = internal_vec(m_points[m_indices[f][0]]), b = internal_vec(m_points[m_indices[f][1]]),
              c = internal_vec(m_points[m_indices[f][2]]);
      const int k = classify(a, b, c);
      if(k == 0) continue;
      changed[f] = 1;
      ++left_out;
      if(k == 1) {   // the parts outside the other body are appended
        for(int i = 0; i < 3; ++i) point_index.emplace(internal_vec(m_points[m_indices[f][std::size_t(i)]]), m_indices[f][std::size_t(i)]);
        split(a, b, c, 1, f);
      }
    }
    if(left_out == 0) return;
    // keep the unchanged triangles in order, then the kept pieces of the split ones
    std::size_t j = 0;
    for(std::size_t i = 0; i < n; ++i) {
      if(changed[i]) continue;
      m_indices[j] = m_indices[i]; m_triangles[j] = m_triangles[i];
      m_patch[j] = m_patch[i]; m_back_patch[j] = m_back_patch[i]; m_two_sided[j] = m_two_sided[i]; m_fill[j] = m_fill[i];
      ++j;
    }
    m_summary.internal_triangles = left_out;
    m_summary.split_triangles = out_idx.size();
    m_indices.resize(j); m_triangles.resize(j); m_patch.resize(j); m_back_patch.resize(j); m_two_sided.resize(j); m_fill.resize(j);
    for(std::size_t i = 0; i < out_idx.size(); ++i) {
      const Triangle_indices& t = out_idx[i];
      Triangle_3 tri(m_points[t[0]], m_points[t[1]], m_points[t[2]]);
      if(tri.is_degenerate()) continue;
      m_indices.push_back(t); m_triangles.push_back(tri);
      m_patch.push_back(out_patch[i]); m_back_patch.push_back(out_back[i]); m_two_sided.push_back(out_sided[i]);
      m_fill.push_back(out_fill[i]);
    }
    if(m_indices.empty()) throw Input_error("surface: every triangle lies inside the volume (nothing bounds it)", Input_error_cause::NO_SURFACE);
    m_bbox = Bbox_3();
    for(const Triangle_3& t : m_triangles) m_bbox += t.bbox();
  }

  // The holes filled (`internal::fill_holes()`, the seam tolerance of the capture): the fill
  // triangles are appended, with the part of their rim's first face on both sides.
  void fill_input_holes()
  {
    Bbox_3 b;
    for(const Triangle_indices& t : m_indices) for(std::uint32_t v : t) b += m_points[v].bbox();
    const internal::Hole_fill f = internal::fill_holes<GeomTraits>(m_points, m_indices, m_two_sided, internal::seam_tolerance(b));
    for(std::size_t i = 0; i < f.triangles.size(); ++i) {
      const int part = m_patch[f.loop_face[f.loop_of[i]]];
      m_indices.push_back(f.triangles[i]);
      m_patch.push_back(part);
      m_back_patch.push_back(part);
      m_two_sided.push_back(false);
      m_fill.push_back(f.loop_of[i] + 1);
    }
    m_summary.filled_holes = f.loop_face.size();
    m_summary.fill_triangles = f.triangles.size();
    m_summary.filled_rim_edges = f.rim_edges;
  }

  static std::uint64_t edge_key(std::uint32_t a, std::uint32_t b)
  {
    return a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
  }

  /*
   * The two sides of the sheets: `m_back_patch[f]` comes in as the part of face `f`'s reversed
   * copy (or its own part), and goes out equal to `m_patch[f]` off the sheets. Each sheet is
   * oriented consistently across the edges it shares with exactly one other sheet face (breadth
   * first from its lowest face; a flipped face swaps its two parts), so that its front and back are
   * two coherent patches. A sheet whose copies were all in one part `NAME` gets the part
   * `NAME_back` for its back side.
   */
  void orient_sheets(const std::vector<std::pair<std::uint64_t, std::uint32_t>>& edges,
                     const std::vector<std::size_t>& edge_begin)
  {
    const std::size_t m = m_indices.size();
    for(std::size_t f = 0; f < m; ++f) if(!m_two_sided[f]) m_back_patch[f] = m_patch[f];
    if(m_summary.sheet_triangles == 0) return;
    // sheet faces across each edge met by exactly two sheet faces
    std::vector<std::vector<std::uint32_t>> nbr(m);
    for(std::size_t e = 0; e + 1 < edge_begin.size(); ++e) {
      std::uint32_t f0 = UINT32_MAX, f1 = UINT32_MAX;
      std::size_t cnt = 0;
      for(std::size_t i = edge_begin[e]; i < edge_begin[e + 1]; ++i)
        if(m_two_sided[edges[i].second]) { ++cnt; (f0 == UINT32_MAX ? f0 : f1) = edges[i].second; }
      if(cnt == 2 && f0 != f1) { nbr[f0].push_back(f1); nbr[f1].push_back(f0); }
    }
    // does face g run edge (a, b) in the same direction as face f?
    auto same_direction = [&](std::uint32_t f, std::uint32_t g) {
      const Triangle_indices& tf = m_indices[f];
      const Triangle_indices& tg = m_indices[g];
      for(int i = 0; i < 3; ++i)
        for(int j = 0; j < 3; ++j)
          if(tf[std::size_t(i)] == tg[std::size_t(j)] && tf[std::size_t((i + 1) % 3)] == tg[std::size_t((j + 1) % 3)]) return true;
      return false;
    };
    std::vector<char> seen(m, 0);
    std::vector<std::uint32_t> queue;
    for(std::size_t s = 0; s < m; ++s) {
      if(!m_two_sided[s] || seen[s]) continue;
      seen[s] = 1;
      queue.assign(1, std::uint32_t(s));
      for(std::size_t qi = 0; qi < queue.size(); ++qi) {
        const std::uint32_t f = queue[qi];
        for(std::uint32_t g : nbr[f]) {
          if(seen[g]) continue;
          seen[g] = 1;
          if(same_direction(f, g)) {   // g is the other way round: flip it, its sides swap parts
            std::swap(m_indices[g][1], m_indices[g][2]);
            std::swap(m_patch[g], m_back_patch[g]);
            ++m_summary.sheet_reoriented;
          }
          queue.push_back(g);
        }
      }
    }
    std::map<int, int> added;   // part -> its added back part
    for(std::size_t f = 0; f < m; ++f) {
      if(!m_two_sided[f]) continue;
      if(m_back_patch[f] != m_patch[f]) continue;
      auto it = added.find(m_patch[f]);
      if(it == added.end()) {
        std::string name = m_patch_names[std::size_t(m_patch[f])] + "_back";
        for(int k = 2; std::find(m_patch_names.begin(), m_patch_names.end(), name) != m_patch_names.end(); ++k)
          name = m_patch_names[std::size_t(m_patch[f])] + "_back" + std::to_string(k);
        m_patch_names.push_back(name);
        ++m_summary.sheet_back_parts;
        it = added.emplace(m_patch[f], int(m_patch_names.size() - 1)).first;
      }
      m_back_patch[f] = it->second;
    }
  }

  /*
   * Repairs, in order, each counted in the summary:
   * 1. faces with the same three corners are kept once; a copy with the same orientation is a
   *    duplicate, a copy with the opposite orientation a reversed duplicate;
   * 2. faces that came with a reversed copy are grouped by shared edges. A group whose free edges
   *    each meet exactly one other face is a patch of a larger surface (the reversed copies were
   *    spurious), and a group without free edge is a closed surface exported double-sided (a
   *    solid): their faces stay one-sided and are oriented in step 3. Any other group (it has an
   *    edge of no other face, or meets a non-manifold edge) is a zero-thickness sheet, as the
   *    windshield of the motorBike: kept, two-sided, excluded from the winding number (it bounds
   *    no volume) but still cut by and blocking the grid;
   * 3. the one-sided faces are oriented consistently (CGAL's orient_polygon_soup); then each
   *    edge-connected component that is closed is oriented by its nesting depth among the closed
   *    components (outward, positive signed volume, at even depth; inward at odd depth: the wall
   *    of a cavity), and each open one keeps the orientation most of its input faces had.
   */
  void repair(std::vector<Triangle_indices>& tris, std::vector<int>& parts)
  {
    namespace PMP = CGAL::Polygon_mesh_processing;
    const std::size_t n = tris.size();
    // 1. duplicates: sort by the sorted corner triple (stable: the first face of a group is kept)
    std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> keyed(n);
    for(std::size_t i = 0; i < n; ++i) {
      std::array<std::uint32_t, 3> k = tris[i];
      std::sort(k.begin(), k.end());
      keyed[i] = {k, std::uint32_t(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    auto parity = [](const Triangle_indices& t) {   // even permutation of the sorted triple?
      return (t[0] < t[1]) + (t[1] < t[2]) + (t[2] < t[0]) == 2;
    };
    std::vector<std::uint32_t> kept;
    std::vector<char> had_reversed;
    std::vector<int> reversed_part;   // the part of the first reversed copy
    kept.reserve(n);
    for(std::size_t i = 0; i < n;) {
      std::size_t j = i;
      while(j < n && keyed[j].first == keyed[i].first) ++j;
      const std::uint32_t rep = keyed[i].second;   // lowest index of the group
      bool reversed = false;
      int rpart = parts[rep];
      for(std::size_t k = i + 1; k < j; ++k) {   // the group is sorted by index: the first copy first
        if(parity(tris[keyed[k].second]) == parity(tris[rep])) ++m_summary.duplicate_triangles;
        else {
          ++m_summary.reversed_duplicates;
          if(!reversed) rpart = parts[keyed[k].second];
          reversed = true;
        }
      }
      kept.push_back(rep);
      had_reversed.push_back(reversed);
      reversed_part.push_back(rpart);
      i = j;
    }
    // back to input order (deterministic, and parts of a file stay together)
    std::vector<std::size_t> order(kept.size());
    for(std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return kept[a] < kept[b]; });
    const std::size_t m = kept.size();
    m_indices.resize(m);
    m_patch.resize(m);
    m_back_patch.resize(m);
    m_two_sided.assign(m, false);
    std::vector<char> candidate(m);
    for(std::size_t i = 0; i < m; ++i) {
      m_indices[i] = tris[kept[order[i]]];
      m_patch[i] = parts[kept[order[i]]];
      candidate[i] = had_reversed[order[i]];
      m_back_patch[i] = reversed_part[order[i]];
    }
    tris.clear(); tris.shrink_to_fit();

    // edges -> faces
    std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
    edges.reserve(3 * m);
    for(std::size_t f = 0; f < m; ++f)
      for(int k = 0; k < 3; ++k)
        edges.push_back({edge_key(m_indices[f][k], m_indices[f][(k + 1) % 3]), std::uint32_t(f)});
    std::sort(edges.begin(), edges.end());
    std::vector<std::size_t> edge_begin;   // start of each distinct edge's run in `edges`
    for(std::size_t i = 0; i < edges.size(); ++i)
      if(i == 0 || edges[i].first != edges[i - 1].first) edge_begin.push_back(i);
    edge_begin.push_back(edges.size());
    for(std::size_t e = 0; e + 1 < edge_begin.size(); ++e) {
      const std::size_t deg = edge_begin[e + 1] - edge_begin[e];
      if(deg == 1) ++m_summary.boundary_edges;
      else if(deg > 2) ++m_summary.non_manifold_edges;
    }

    // union-find
    std::vector<std::uint32_t> uf(m);
    for(std::size_t i = 0; i < m; ++i) uf[i] = std::uint32_t(i);
    auto find = [&](std::uint32_t x) {
      while(uf[x] != x) { uf[x] = uf[uf[x]]; x = uf[x]; }
      return x;
    };
    auto unite = [&](std::uint32_t a, std::uint32_t b) {
      a = find(a); b = find(b);
      if(a != b) uf[(std::max)(a, b)] = (std::min)(a, b);
    };

    // 2. groups of faces that had a reversed copy: sheets or patches of a surface
    if(m_summary.reversed_duplicates > 0) {
      for(std::size_t e = 0; e + 1 < edge_begin.size(); ++e) {
        std::uint32_t first = UINT32_MAX;
        for(std::size_t i = edge_begin[e]; i < edge_begin[e + 1]; ++i) {
          const std::uint32_t f = edges[i].second;
          if(!candidate[f]) continue;
          if(first == UINT32_MAX) first = f; else unite(first, f);
        }
      }
      std::vector<char> is_patch(m, 1);   // per group root
      for(std::size_t e = 0; e + 1 < edge_begin.size(); ++e) {
        std::size_t in = 0, out = 0;
        std::uint32_t root = UINT32_MAX;
        bool several_groups = false;
        for(std::size_t i = edge_begin[e]; i < edge_begin[e + 1]; ++i) {
          const std::uint32_t f = edges[i].second;
          if(candidate[f]) {
            ++in;
            const std::uint32_t r = find(f);
            if(root != UINT32_MAX && r != root) several_groups = true;
            root = r;
          } else ++out;
        }
        if(in == 0) continue;
        if(several_groups || in > 2) { is_patch[root] = 0; continue; }
        if(in == 1) {   // a free edge of the group
          if(out != 1) is_patch[root] = 0;
        } else if(out != 0) is_patch[root] = 0;   // non-manifold inside the group
      }
      for(std::size_t f = 0; f < m; ++f)
        if(candidate[f]) {
          const std::uint32_t r = find(f);
          if(!is_patch[r]) { m_two_sided[f] = true; ++m_summary.sheet_triangles; }
        }
      for(std::size_t i = 0; i < m; ++i) uf[i] = std::uint32_t(i);
    }
    orient_sheets(edges, edge_begin);

    // 3. orientation of the one-sided faces
    std::vector<std::uint32_t> one_sided;
    for(std::size_t f = 0; f < m; ++f) if(!m_two_sided[f]) one_sided.push_back(std::uint32_t(f));
    if(one_sided.empty()) return;
    std::vector<Point_3> pts = m_points;
    std::vector<std::vector<std::size_t>> polys(one_sided.size());
    for(std::size_t i = 0; i < one_sided.size(); ++i)
      polys[i].assign(m_indices[one_sided[i]].begin(), m_indices[one_sided[i]].end());
    PMP::orient_polygon_soup(pts, polys);
    std::map<Point_3, std::size_t> original;   // only needed when points were duplicated
    if(pts.size() > m_points.size())
      for(std::size_t i = 0; i < m_points.size(); ++i) original.emplace(m_points[i], i);
    std::vector<char> flipped(m, 0);
    for(std::size_t i = 0; i < one_sided.size(); ++i) {
      Triangle_indices t;
      for(int k = 0; k < 3; ++k) {
        const std::size_t v = polys[i][std::size_t(k)];
        t[std::size_t(k)] = std::uint32_t(v < m_points.size() ? v : original.at(pts[v]));
      }
      const Triangle_indices& o = m_indices[one_sided[i]];
      const bool same = (t[0] == o[0] && t[1] == o[1]) || (t[0] == o[1] && t[1] == o[2]) || (t[0] == o[2] && t[1] == o[0]);
      if(!same) flipped[one_sided[i]] = 1;
    }
    polys.clear(); pts.clear();
    // components of one-sided faces through manifold edges
    for(std::size_t e = 0; e + 1 < edge_begin.size(); ++e) {
      std::uint32_t f0 = UINT32_MAX, f1 = UINT32_MAX;
      std::size_t cnt = 0;
      for(std::size_t i = edge_begin[e]; i < edge_begin[e + 1]; ++i) {
        const std::uint32_t f = edges[i].second;
        if(m_two_sided[f]) continue;
        ++cnt;
        if(f0 == UINT32_MAX) f0 = f; else f1 = f;
      }
      if(cnt == 2) unite(f0, f1);
    }
    std::vector<char> comp_closed(m, 1);
    for(std::size_t e = 0; e + 1 < edge_begin.size(); ++e) {
      std::size_t cnt = 0;
      std::uint32_t f0 = UINT32_MAX;
      for(std::size_t i = edge_begin[e]; i < edge_begin[e + 1]; ++i)
        if(!m_two_sided[edges[i].second]) { ++cnt; f0 = edges[i].second; }
      if(cnt != 0 && cnt != 2) {
        for(std::size_t i = edge_begin[e]; i < edge_begin[e + 1]; ++i)
          if(!m_two_sided[edges[i].second]) comp_closed[find(edges[i].second)] = 0;
      }
      (void)f0;
    }
    std::vector<double> volume(m, 0.0);
    std::vector<std::size_t> size(m, 0), nflipped(m, 0);
    for(std::uint32_t f : one_sided) {
      const std::uint32_t r = find(f);
      ++size[r];
      nflipped[r] += flipped[f];
      const Triangle_indices& t = m_indices[f];
      const auto o = internal_vec(m_points[m_indices[one_sided[0]][0]]);   // origin near the data
      auto a = internal_vec(m_points[t[0]]), b = internal_vec(m_points[t[1]]), c = internal_vec(m_points[t[2]]);
      for(int k = 0; k < 3; ++k) { a[k] -= o[k]; b[k] -= o[k]; c[k] -= o[k]; }
      const double v = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
      volume[r] += flipped[f] ? -v : v;   // oriented as orient_polygon_soup left it
    }
    // nesting depth of the closed components: how many other closed components contain a point of it
    std::vector<std::uint32_t> closed_roots;
    for(std::uint32_t f : one_sided) if(find(f) == f && comp_closed[f]) closed_roots.push_back(f);
    std::vector<int> depth(m, 0);
    if(closed_roots.size() > 1) {
      std::vector<Bbox_3> cbox(m);
      std::vector<std::vector<std::uint32_t>> members(m);
      for(std::uint32_t f : one_sided) {
        const std::uint32_t r = find(f);
        if(!comp_closed[r]) continue;
        members[r].push_back(f);
        cbox[r] += m_points[m_indices[f][0]].bbox() + m_points[m_indices[f][1]].bbox() + m_points[m_indices[f][2]].bbox();
      }
      typedef CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t> Box;
      std::vector<Box> boxes;
      for(std::uint32_t r : closed_roots) boxes.push_back(Box(cbox[r], r));
      auto contains = [](const Bbox_3& a, const Bbox_3& b) { return a + b == a; };
      // |winding number| of component r (as oriented now) at p, by direct summation
      auto winding = [&](std::uint32_t r, const std::array<double, 3>& p) {
        double w = 0;
        for(std::uint32_t f : members[r]) {
          double t[9];
          for(int k = 0; k < 3; ++k) {
            const auto v = internal_vec(m_points[m_indices[f][std::size_t(flipped[f] && k ? 3 - k : k)]]);
            std::copy(v.begin(), v.end(), t + 3 * k);
          }
          w += internal::Fast_winding_number_3::solid_angle(p, t);
        }
        return std::abs(w) / (4 * CGAL_PI);
      };
      CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
        for(int pass = 0; pass < 2; ++pass) {
          const Box& outer = pass ? b : a;
          const Box& inner = pass ? a : b;
          if(!contains(cbox[outer.info()], cbox[inner.info()])) continue;
          const std::uint32_t f = members[inner.info()].front();
          std::array<double, 3> c{{0, 0, 0}};
          for(int k = 0; k < 3; ++k) {
            const auto v = internal_vec(m_points[m_indices[f][std::size_t(k)]]);
            for(int d = 0; d < 3; ++d) c[std::size_t(d)] += v[std::size_t(d)] / 3;
          }
          if(winding(outer.info(), c) > 0.5) ++depth[inner.info()];
        }
      });
    }
    std::vector<char> flip_comp(m, 0);
    for(std::uint32_t f : one_sided) {
      const std::uint32_t r = find(f);
      if(r != f) continue;
      ++m_summary.components;
      if(comp_closed[r]) flip_comp[r] = (volume[r] < 0) != (depth[r] % 2 == 1);
      else flip_comp[r] = 2 * nflipped[r] > size[r];   // keep the input's majority orientation
    }
    for(std::uint32_t f : one_sided) {
      const bool flip = flipped[f] != flip_comp[find(f)];
      if(flip) { std::swap(m_indices[f][1], m_indices[f][2]); ++m_summary.reoriented_triangles; }
    }
    if(m_summary.reoriented_triangles) m_summary.reoriented = true;
  }

  static std::array<double, 3> internal_vec(const Point_3& p)
  {
    return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  }

  std::vector<Point_3> m_points;
  std::vector<Triangle_indices> m_indices;
  std::vector<Triangle_3> m_triangles;
  std::vector<int> m_patch, m_back_patch;
  std::vector<bool> m_two_sided;
  std::vector<std::uint32_t> m_fill;   // per triangle: 0 (the input's), or the hole it fills, from 1
  std::vector<std::uint8_t> m_feature_mask;   // bit k: edge (k, k+1) of the triangle is a feature
  bool m_has_features = false;
  typedef typename std::vector<typename GeomTraits::Segment_3>::const_iterator Segment_iterator;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GeomTraits, CGAL::AABB_segment_primitive<GeomTraits, Segment_iterator>>> Segment_tree;
  std::vector<typename GeomTraits::Segment_3> m_feature_segments;
  std::unique_ptr<Segment_tree> m_segment_tree;
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
