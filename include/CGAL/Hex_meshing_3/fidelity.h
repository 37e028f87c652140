// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_FIDELITY_H
#define CGAL_HEX_MESHING_3_FIDELITY_H

// Geometric fidelity of a mesh boundary to the input surface, both ways:
// - mesh -> input: for every boundary face on a surface patch, the largest distance from its
//   corners and centre to the input (exact closest points through the domain's AABB tree,
//   distances rounded to double);
// - input -> mesh: the distance from points sampled uniformly on the input (by area, from a fixed
//   seed) to the mesh boundary (its quads split into two triangles each).
// Their maxima estimate the two one-sided Hausdorff distances.
// Fidelity to the feature curves, both ways (`feature_fidelity()`): points sampled along the
// input's feature edges against the feature edges of the mesh boundary, and back; input corners
// against the mesh's boundary vertices.

#include <CGAL/Hex_meshing_3/quality.h>
#include <CGAL/Hex_meshing_3/internal/boundary_polygons.h>
#include <CGAL/Hex_meshing_3/internal/sealed_border_edges.h>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Random.h>
#include <CGAL/Search_traits_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <memory>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief distances between a mesh boundary and the input surface (see `boundary_fidelity()`).
 */
struct Boundary_fidelity
{
  std::size_t surface_faces = 0;     ///< boundary faces on surface patches (not on the box)
  double max_face_distance = 0;      ///< mesh -> input: the largest distance of a face point
  double mean_face_distance = 0;     ///< mesh -> input: mean over faces of their largest distance
  std::size_t samples = 0;           ///< points sampled on the input
  double max_sample_distance = 0;    ///< input -> mesh: the largest distance of a sample
  double mean_sample_distance = 0;
  std::array<double, 3> worst_face_location = {{0, 0, 0}};     ///< where the mesh is farthest
  std::array<double, 3> worst_sample_location = {{0, 0, 0}};   ///< where the input is farthest
  std::size_t cap_faces = 0;         ///< faces capping holes of the input (not counted in the face distances): whose centre's nearest point of the domain is on a triangle filling a hole (`Surface_domain_3::is_fill()`) or on a border edge, not counting the border edges that run along another one (a seam or crack, `make_hex_mesh_3()`)
  double cap_area = 0;               ///< their area
  /// mesh -> input, per surface face (caps left out, in the order of `mesh.boundary_faces`): the
  /// largest distance of its corners and centre, and the point where it is reached
  std::vector<std::pair<double, std::array<double, 3>>> face_distances;
  /// per entry of `face_distances`: the face's index in `mesh.boundary_faces`
  std::vector<std::size_t> face_indices;
  /// per entry of `face_distances`: which point of the face is the farthest, 0..3 its corner
  /// `vertices[k]`, 4 its centre (the vertex average)
  std::vector<std::uint8_t> face_worst_points;
  /// per entry of `face_distances`: 1 if the farthest point is a corner whose nearest input point
  /// lies on a border edge of the input (a vertex of a cap over a hole, or next to one), else 0
  std::vector<std::uint8_t> face_worst_on_border;
};

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief measures how far the boundary of `mesh` is from the surface of `domain`, both ways.
 * Boundary faces on the six box patches (0..5) are not counted. `samples` points are drawn on the
 * input (uniformly by area, seed `seed`, deterministic); triangles marked two-sided and pieces
 * inside the volume are sampled like any other.
 */
template <typename HexMesh, typename Domain>
Boundary_fidelity boundary_fidelity(const HexMesh& mesh, const Domain& domain, std::size_t samples = 10000,
                                    unsigned seed = 20261122u)
{
  typedef typename Domain::Geom_traits GT;
  typedef typename GT::Point_3 Point_3;
  typedef typename GT::Triangle_3 Triangle_3;
  typedef typename GT::Segment_3 Segment_3;
  Boundary_fidelity r;
  // the border edges of the input (one triangle): a face whose centre is nearest to one of them
  // caps a hole, and is counted apart; border edges along another border edge (a seam between
  // parts, a crack: `internal::sealed_border_edges()`, as the capture judges them) border no hole
  std::vector<Segment_3> border;
  std::vector<std::array<std::uint32_t, 2>> border_ends;
  {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for(const auto& t : domain.triangle_indices())
      for(int k = 0; k < 3; ++k) {
        std::uint32_t u = t[std::size_t(k)], v = t[std::size_t((k + 1) % 3)];
        if(u > v) std::swap(u, v);
        edges.push_back({u, v});
      }
    std::sort(edges.begin(), edges.end());
    for(std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while(j < edges.size() && edges[j] == edges[i]) ++j;
      if(j - i == 1) {
        border.emplace_back(domain.points()[edges[i].first], domain.points()[edges[i].second]);
        border_ends.push_back({{edges[i].first, edges[i].second}});
      }
      i = j;
    }
    internal::remove_sealed_border_edges<GT>(border, border_ends, internal::seam_tolerance(domain.bbox()));
  }
  typedef typename std::vector<Segment_3>::const_iterator Seg_it;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GT, CGAL::AABB_segment_primitive<GT, Seg_it>>> Segment_tree;
  std::unique_ptr<Segment_tree> border_tree;
  if(!border.empty()) {
    border_tree = std::make_unique<Segment_tree>(border.begin(), border.end());
    border_tree->accelerate_distance_queries();
  }
  const Bbox_3 bb = domain.bbox();
  const double tiny = 1e-9 * std::sqrt(CGAL::square(bb.xmax() - bb.xmin()) + CGAL::square(bb.ymax() - bb.ymin()) +
                                       CGAL::square(bb.zmax() - bb.zmin()));
  // mesh -> input
  // (each input query once: a vertex's closest point is kept for the faces around it, and a
  // face centre's serves its cap test and its distance; the domain's `squared_distance()` is the
  // squared distance to its `closest_point()`, so the values are the same as querying each time)
  double sum = 0;
  std::vector<Triangle_3> boundary;
  // (and the triangle it lies on: a vertex nearest a hole's fill is a cap's)
  std::vector<std::pair<Point_3, std::size_t>> vclosest(mesh.points.size());
  std::vector<char> vknown(mesh.points.size(), 0);
  auto closest_of_vertex = [&](std::size_t v) -> const std::pair<Point_3, std::size_t>& {
    if(!vknown[v]) { vclosest[v] = domain.closest_point_and_triangle(mesh.points[v]); vknown[v] = 1; }
    return vclosest[v];
  };
  // a point of the domain that caps a hole: on a fill, or on a border edge (not along a seam)
  auto caps_hole = [&](const std::pair<Point_3, std::size_t>& near) {
    return domain.is_fill(near.second) || (border_tree && CGAL::to_double(border_tree->squared_distance(near.first)) <= tiny * tiny);
  };
  for(const auto& f : mesh.boundary_faces) {
    if(f.patch < 6) continue;
    const Point_3 &a = mesh.points[f.vertices[0]], &b = mesh.points[f.vertices[1]], &c = mesh.points[f.vertices[2]],
                  &d = mesh.points[f.vertices[3]];
    boundary.emplace_back(a, b, c);
    boundary.emplace_back(a, c, d);
    const Point_3 centre((a.x() + b.x() + c.x() + d.x()) / 4, (a.y() + b.y() + c.y() + d.y()) / 4,
                         (a.z() + b.z() + c.z() + d.z()) / 4);
    const auto centre_near = domain.closest_point_and_triangle(centre);
    const Point_3& centre_closest = centre_near.first;
    if(caps_hole(centre_near)) {
      ++r.cap_faces;
      r.cap_area += 0.5 * std::sqrt(CGAL::to_double(CGAL::cross_product(c - a, d - b).squared_length()));
      continue;
    }
    ++r.surface_faces;
    double worst = 0;
    std::uint8_t at = 4;
    const Point_3* pts[5] = {&a, &b, &c, &d, &centre};
    for(std::uint8_t k = 0; k < 5; ++k) {
      const Point_3& q = k < 4 ? closest_of_vertex(std::size_t(f.vertices[k])).first : centre_closest;
      const double dist = std::sqrt(CGAL::to_double(GT().compute_squared_distance_3_object()(*pts[k], q)));
      if(dist > worst) { worst = dist; at = k; }
    }
    const std::array<double, 3> where = {{CGAL::to_double(pts[at]->x()), CGAL::to_double(pts[at]->y()), CGAL::to_double(pts[at]->z())}};
    if(worst > r.max_face_distance) { r.max_face_distance = worst; r.worst_face_location = where; }
    r.face_distances.push_back({worst, where});
    r.face_indices.push_back(std::size_t(&f - mesh.boundary_faces.data()));
    r.face_worst_points.push_back(at);
    r.face_worst_on_border.push_back(at < 4 && worst > 0 && caps_hole(closest_of_vertex(std::size_t(f.vertices[at]))));
    sum += worst;
  }
  if(r.surface_faces) r.mean_face_distance = sum / double(r.surface_faces);
  if(boundary.empty() || samples == 0) return r;
  // input -> mesh
  typedef typename std::vector<Triangle_3>::const_iterator It;
  typedef CGAL::AABB_triangle_primitive<GT, It> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GT, Primitive>> Tree;
  Tree tree(boundary.begin(), boundary.end());
  tree.accelerate_distance_queries();
  const std::size_t nt = domain.number_of_triangles();
  std::vector<double> cumulative(nt);
  double total = 0;
  std::size_t last_input = 0;   // (a draw that rounds up to the total falls on it, not on a fill)
  for(std::size_t i = 0; i < nt; ++i) {   // (the input's triangles: not the fills of its holes)
    if(!domain.is_fill(i)) { total += std::sqrt(CGAL::to_double(domain.triangle(i).squared_area())); last_input = i; }
    cumulative[i] = total;
  }
  if(!(total > 0)) return r;
  CGAL::Random rng(seed);
  sum = 0;
  for(std::size_t s = 0; s < samples; ++s) {
    const double u = rng.get_double(0, total);
    const std::size_t i = std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
    const Triangle_3& t = domain.triangle(i < nt && !domain.is_fill(i) ? i : last_input);
    double a = rng.get_double(0, 1), b = rng.get_double(0, 1);
    if(a + b > 1) { a = 1 - a; b = 1 - b; }
    const Point_3 p(t[0].x() + a * (t[1].x() - t[0].x()) + b * (t[2].x() - t[0].x()),
                    t[0].y() + a * (t[1].y() - t[0].y()) + b * (t[2].y() - t[0].y()),
                    t[0].z() + a * (t[1].z() - t[0].z()) + b * (t[2].z() - t[0].z()));
    const double dist = std::sqrt(CGAL::to_double(tree.squared_distance(p)));
    sum += dist;
    if(dist > r.max_sample_distance) {
      r.max_sample_distance = dist;
      r.worst_sample_location = {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
    }
  }
  r.samples = samples;
  r.mean_sample_distance = sum / double(samples);
  return r;
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief why a boundary face stands off the input (see `far_faces()`), from the point of it that is
 * farthest from the input.
 */
enum class Far_face_cause
{
  HANGING_CORNER,   ///< a corner that is a hanging node: the midpoint of a coarser face's edge, a chord of the surface
  CAP_CORNER,       ///< another corner, whose nearest input point is on a border edge: a vertex of a cap over a hole of the input
  CORNER,           ///< another corner: a vertex that did not reach the surface (released, in a wedge, ...)
  FOLDED,           ///< the centre, the face folded along a diagonal beyond the fold angle (a feature curve or a crease across it)
  BENT              ///< the centre, the face not so folded: a face too large for the surface's curvature under it
};

/// the name of a `Far_face_cause` in reports: `hanging_corner`, `cap_corner`, `corner`, `folded`, `bent`
inline const char* far_face_cause_name(Far_face_cause c)
{
  switch(c) {
  case Far_face_cause::HANGING_CORNER: return "hanging_corner";
  case Far_face_cause::CAP_CORNER: return "cap_corner";
  case Far_face_cause::CORNER: return "corner";
  case Far_face_cause::FOLDED: return "folded";
  default: return "bent";
  }
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief a boundary face farther than a threshold from the input (see `far_faces()`).
 */
struct Far_face
{
  std::size_t face = 0;                  ///< its index in `mesh.boundary_faces`
  double distance = 0;                   ///< the largest distance of its corners and centre to the input
  std::array<double, 3> at = {{0, 0, 0}};   ///< the point where it is reached
  Far_face_cause cause = Far_face_cause::BENT;
  double fold = 0;   ///< degrees: the larger, over its two diagonals, of the angle between the normals of the two triangles the diagonal splits it into
  double size = 0;   ///< its longer diagonal / sqrt(2) (the side of a square with that diagonal)
};

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the boundary faces of `fid` (`boundary_fidelity()` of `mesh`) farther than `threshold`
 * from the input, farthest first (ties in face order), each with its cause:
 * - the farthest point a corner: `HANGING_CORNER` if that vertex is a hanging node of `mesh`, else
 *   `CAP_CORNER` if its nearest input point lies on a border edge of the input
 *   (`Boundary_fidelity::face_worst_on_border`), else `CORNER`;
 * - the farthest point the centre: `FOLDED` if the face's fold (see `Far_face::fold`) exceeds
 *   `fold_angle` degrees, else `BENT`.
 */
template <typename HexMesh>
std::vector<Far_face> far_faces(const HexMesh& mesh, const Boundary_fidelity& fid, double threshold, double fold_angle = 30)
{
  using internal::Vec3; using internal::sub; using internal::cross; using internal::dot;
  std::vector<char> hanging(mesh.points.size(), 0);
  for(const auto& h : mesh.hanging_nodes) hanging[h.vertex] = 1;
  auto angle = [](const Vec3& u, const Vec3& w) {   // degrees; 0 if either is degenerate
    const double l = std::sqrt(dot(u, u) * dot(w, w));
    return l > 0 ? std::acos((std::max)(-1.0, (std::min)(1.0, dot(u, w) / l))) * 180.0 / CGAL_PI : 0.0;
  };
  std::vector<Far_face> out;
  for(std::size_t i = 0; i < fid.face_distances.size() && i < fid.face_indices.size() && i < fid.face_worst_points.size(); ++i) {
    if(!(fid.face_distances[i].first > threshold)) continue;
    Far_face ff;
    ff.face = fid.face_indices[i];
    ff.distance = fid.face_distances[i].first;
    ff.at = fid.face_distances[i].second;
    const auto& q = mesh.boundary_faces[ff.face].vertices;
    const Vec3 a = internal::vec(mesh.points[q[0]]), b = internal::vec(mesh.points[q[1]]), c = internal::vec(mesh.points[q[2]]),
               d = internal::vec(mesh.points[q[3]]);
    ff.fold = (std::max)(angle(cross(sub(b, a), sub(c, a)), cross(sub(c, a), sub(d, a))),    // along a-c
                         angle(cross(sub(b, a), sub(d, a)), cross(sub(c, b), sub(d, b))));   // along b-d
    ff.size = std::sqrt((std::max)(dot(sub(c, a), sub(c, a)), dot(sub(d, b), sub(d, b))) / 2);
    const std::uint8_t k = fid.face_worst_points[i];
    if(k < 4)
      ff.cause = hanging[q[k]] ? Far_face_cause::HANGING_CORNER
               : i < fid.face_worst_on_border.size() && fid.face_worst_on_border[i] ? Far_face_cause::CAP_CORNER
               : Far_face_cause::CORNER;
    else ff.cause = ff.fold > fold_angle ? Far_face_cause::FOLDED : Far_face_cause::BENT;
    out.push_back(ff);
  }
  std::stable_sort(out.begin(), out.end(), [](const Far_face& x, const Far_face& y) { return x.distance > y.distance; });
  return out;
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the topology of a closed polygonal surface: edge-connected components and the Euler
 * characteristic V - E + F (2 for a sphere, 2 - 2g for a closed surface of genus g, summed over
 * components).
 */
struct Surface_topology
{
  std::size_t components = 0;
  long long euler_characteristic = 0;
  std::size_t vertices = 0, edges = 0, faces = 0;
  std::size_t boundary_edges = 0;   ///< edges of one face (0 on a closed surface)
};

namespace internal {
template <typename PolygonRange>
Surface_topology polygon_topology(const PolygonRange& polygons)
{
  Surface_topology t;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
  std::vector<std::uint32_t> verts;
  std::uint32_t f = 0;
  for(const auto& poly : polygons) {
    const std::size_t n = poly.size();
    for(std::size_t i = 0; i < n; ++i) {
      const std::uint64_t a = poly[i], b = poly[(i + 1) % n];
      edges.push_back({a < b ? (a << 32 | b) : (b << 32 | a), f});
      verts.push_back(std::uint32_t(a));
    }
    ++f;
  }
  t.faces = f;
  std::sort(verts.begin(), verts.end());
  t.vertices = std::size_t(std::unique(verts.begin(), verts.end()) - verts.begin());
  std::sort(edges.begin(), edges.end());
  std::vector<std::uint32_t> uf(f);
  for(std::uint32_t i = 0; i < f; ++i) uf[i] = i;
  auto find = [&](std::uint32_t x) { while(uf[x] != x) { uf[x] = uf[uf[x]]; x = uf[x]; } return x; };
  for(std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while(j < edges.size() && edges[j].first == edges[i].first) ++j;
    ++t.edges;
    if(j - i == 1) ++t.boundary_edges;
    for(std::size_t k = i + 1; k < j; ++k) {
      const std::uint32_t a = find(edges[i].second), b = find(edges[k].second);
      if(a != b) uf[(std::max)(a, b)] = (std::min)(a, b);
    }
    i = j;
  }
  for(std::uint32_t i = 0; i < f; ++i) if(find(i) == i) ++t.components;
  t.euler_characteristic = (long long)t.vertices - (long long)t.edges + (long long)t.faces;
  return t;
}
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the topology of the mesh boundary on the surface patches (patches 6 and up), from its
 * polyhedral form `pm` (`Polyhedral_mesh_3::build()`), whose boundary faces list the hanging nodes
 * on their edges, so that the boundary is a conforming polygonal surface.
 */
template <typename PolyhedralMesh>
Surface_topology boundary_topology(const PolyhedralMesh& pm)
{
  std::vector<std::vector<std::uint32_t>> polys;
  for(std::size_t p = 6; p < pm.patches.size(); ++p)
    for(std::size_t f = pm.patches[p].start; f < pm.patches[p].start + pm.patches[p].size; ++f)
      polys.emplace_back(pm.faces[f].begin(), pm.faces[f].end());
  return internal::polygon_topology(polys);
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the topology of the domain's (repaired) input triangles: without the triangles that
 * fill its holes (`Surface_domain_3::is_fill()`), so that a hole counts as one.
 */
template <typename Domain>
Surface_topology surface_topology(const Domain& domain)
{
  std::vector<typename Domain::Triangle_indices> input;
  const auto& all = domain.triangle_indices();
  for(std::size_t i = 0; i < all.size(); ++i) if(!domain.is_fill(i)) input.push_back(all[i]);
  return internal::polygon_topology(input);
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief how well a mesh boundary follows the feature curves of the input (see `feature_fidelity()`).
 *
 * A distance over an empty set of samples is 0; a distance to an empty set is infinite
 * (`std::numeric_limits<double>::infinity()`). So if both sides have no feature edge, both
 * distances are 0; if only one side has some, the distance from that side is infinite (and the
 * Hausdorff distance, the larger of the two, is infinite).
 */
struct Feature_fidelity
{
  std::size_t input_feature_edges = 0;   ///< input edges of kind `SHARP`, `OPEN` or `NON_MANIFOLD`
  std::size_t mesh_feature_edges = 0;    ///< feature edges of the boundary polygons (hanging nodes split edges)
  double input_to_mesh = 0;   ///< the largest distance of a point sampled on the input's feature edges to the mesh's
  double mesh_to_input = 0;   ///< the largest distance of a point sampled on the mesh's feature edges to the input's
  std::array<double, 3> worst_input_location = {{0, 0, 0}};   ///< the input sample farthest from the mesh's edges
  std::array<double, 3> worst_mesh_location = {{0, 0, 0}};    ///< the mesh sample farthest from the input's edges
  std::size_t corners = 0;          ///< input corners (`features.corners()`)
  double max_corner_distance = 0;   ///< the largest distance of an input corner to its nearest boundary vertex
  std::array<double, 3> worst_corner_location = {{0, 0, 0}};   ///< the input corner farthest from the boundary
  double sample_spacing = 0;        ///< the spacing of the samples along the edges (as given, or automatic)
};

namespace internal {

// the input's feature edges of kind SHARP, OPEN or NON_MANIFOLD, as segments
template <typename Segment_3, typename FeatureCurves>
std::vector<Segment_3> input_feature_segments(const FeatureCurves& features)
{
  std::vector<Segment_3> input;
  const unsigned wanted = unsigned(FeatureCurves::SHARP) | unsigned(FeatureCurves::OPEN) | unsigned(FeatureCurves::NON_MANIFOLD);
  for(const auto& e : features.edges())
    if(unsigned(e.kind) & wanted) input.emplace_back(features.point(e.vertices[0]), features.point(e.vertices[1]));
  return input;
}

// the feature edges of the mesh boundary's polygons (`boundary_polygons(mesh)`) at
// `feature_angle` degrees (see `feature_fidelity()`), as segments
template <typename Segment_3, typename HexMesh>
std::vector<Segment_3> mesh_feature_segments(const HexMesh& mesh, const std::vector<std::vector<std::uint32_t>>& polys,
                                             double feature_angle)
{
  typedef std::array<double, 3> V;
  auto vec = [](const auto& p) -> V { return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}}; };
  std::vector<V> normal(polys.size());
  for(std::size_t f = 0; f < polys.size(); ++f) {
    const auto& q = mesh.boundary_faces[f].vertices;
    const V a = vec(mesh.points[q[0]]), b = vec(mesh.points[q[1]]), c = vec(mesh.points[q[2]]), d = vec(mesh.points[q[3]]);
    const V u = {{c[0] - a[0], c[1] - a[1], c[2] - a[2]}}, w = {{d[0] - b[0], d[1] - b[1], d[2] - b[2]}};
    normal[f] = {{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]}};
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> half;   // (edge key, face)
  for(std::size_t f = 0; f < polys.size(); ++f) {
    const std::size_t n = polys[f].size();
    for(std::size_t i = 0; i < n; ++i) {
      const std::uint64_t a = polys[f][i], b = polys[f][(i + 1) % n];
      half.push_back({a < b ? (a << 32 | b) : (b << 32 | a), std::uint32_t(f)});
    }
  }
  std::sort(half.begin(), half.end());
  const double cos_max = std::cos(feature_angle * CGAL_PI / 180.0);
  std::vector<Segment_3> meshed;
  for(std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    std::size_t on_surface = 0, on_box = 0;
    std::uint32_t s[2] = {0, 0};
    for(; j < half.size() && half[j].first == half[i].first; ++j) {
      if(mesh.boundary_faces[half[j].second].patch >= 6) {
        if(on_surface < 2) s[on_surface] = half[j].second;
        ++on_surface;
      } else
        ++on_box;
    }
    bool feature = false;
    if(on_surface > 0) {
      if(on_box > 0 || on_surface != 2) feature = true;
      else {
        const V& n0 = normal[s[0]];
        const V& n1 = normal[s[1]];
        const double l = std::sqrt((n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2]) * (n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]));
        if(l > 0) feature = (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2]) / l <= cos_max;
      }
    }
    if(feature) {
      const std::uint32_t a = std::uint32_t(half[i].first >> 32), b = std::uint32_t(half[i].first & 0xffffffffu);
      meshed.emplace_back(mesh.points[a], mesh.points[b]);
    }
    i = j;
  }
  return meshed;
}

} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief measures how well the boundary of `mesh` captures the feature curves of the input, both
 * ways (within an angle tolerance), and how close its boundary vertices come to the input's corners.
 *
 * - Input feature edges: the edges of `features` whose kind includes `SHARP`, `OPEN` or
 *   `NON_MANIFOLD` (not those that are only `PATCH_BORDER`s: the mesh side has no counterpart).
 *   Which edges are sharp was decided when `features` was built (its own feature angle).
 * - Mesh feature edges: the boundary faces are first made polygons by inserting the hanging nodes
 *   that lie inside their edges (`Polyhedral_mesh_3`'s view), so that a coarse face's edge pairs
 *   with its finer neighbours' halves. An edge of these polygons that belongs to at least one face
 *   on a surface patch (patch >= 6) is a feature edge if it also belongs to a face on a box patch
 *   (0..5), or to only one face (open), or to more than two faces (non-manifold), or to exactly two
 *   faces whose normals make an angle of at least `feature_angle` degrees. A quad's normal is its
 *   vector area (its diagonals' cross product), as faces may be slightly non-planar; a degenerate
 *   normal makes no feature. Edges between faces of two different surface patches are not
 *   features by themselves.
 * - Distances: every edge of each set is sampled at `sample_spacing` (or finer: the edge is cut
 *   into equal parts, its end points included), and the distance from each sample to the nearest
 *   edge of the other set is found through an AABB tree of segments. The maxima are lower bounds of
 *   the two one-sided Hausdorff distances between the edge sets, below them by at most half the
 *   spacing. With `sample_spacing` <= 0 the spacing is 1/20 of the mean length of the input
 *   feature edges or of the mesh feature edges, whichever is smaller.
 * - Corners: each of `features.corners()` against the nearest vertex of a boundary face on a surface
 *   patch (hanging nodes included); infinite if there is none.
 * - Tolerance: with `tolerance` > 0 degrees, each side is compared with the other side's edges at
 *   a lower angle: the input's feature edges (of `features`) against the mesh edges of at least
 *   `feature_angle - tolerance` degrees, and the mesh edges of at least `feature_angle` against
 *   the feature edges of `loose_features` (the same input's curves built at `feature_angle -
 *   tolerance`). A crease of the input at the angle (30.0 degrees) that the mesh reproduces at
 *   29, or a crease of the mesh at 32 degrees across the facets of a faceted blend (22.5 each),
 *   then counts as followed. With `tolerance` <= 0, `loose_features` is not used (the strict
 *   form, `feature_fidelity()`).
 *
 * The result is deterministic: edges are visited in a fixed order and ties keep the first sample.
 * See `Feature_fidelity` for empty sets.
 *
 * \tparam HexMesh a `Hex_mesh_3`
 * \tparam Domain a `Surface_domain_3` (its kernel is used)
 * \tparam FeatureCurves a `Feature_curves_3` built from `domain`
 */
template <typename HexMesh, typename Domain, typename FeatureCurves>
Feature_fidelity feature_fidelity_with_tolerance(const HexMesh& mesh, const Domain& domain, const FeatureCurves& features,
                                                 const FeatureCurves& loose_features, double feature_angle,
                                                 double tolerance, double sample_spacing = 0)
{
  (void)domain;
  typedef typename Domain::Geom_traits GT;
  typedef typename GT::FT FT;
  typedef typename GT::Point_3 Point_3;
  typedef typename GT::Segment_3 Segment_3;
  const double inf = std::numeric_limits<double>::infinity();
  auto vec = [](const Point_3& p) -> std::array<double, 3> { return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}}; };
  Feature_fidelity r;
  const std::vector<Segment_3> input = internal::input_feature_segments<Segment_3>(features);
  r.input_feature_edges = input.size();
  const std::vector<std::vector<std::uint32_t>> polys = internal::boundary_polygons(mesh);
  const std::vector<Segment_3> meshed = internal::mesh_feature_segments<Segment_3>(mesh, polys, feature_angle);
  r.mesh_feature_edges = meshed.size();
  // the other sides' sets, at the lower angle (the same sets without a tolerance)
  const bool loose = tolerance > 0;
  const std::vector<Segment_3> loose_input = loose ? internal::input_feature_segments<Segment_3>(loose_features) : std::vector<Segment_3>();
  const std::vector<Segment_3> loose_meshed = loose ? internal::mesh_feature_segments<Segment_3>(mesh, polys, feature_angle - tolerance) : std::vector<Segment_3>();

  // sample spacing
  auto mean_length = [](const std::vector<Segment_3>& segs) {
    double sum = 0;
    for(const Segment_3& g : segs) sum += std::sqrt(CGAL::to_double(g.squared_length()));
    return segs.empty() ? 0.0 : sum / double(segs.size());
  };
  if(sample_spacing > 0) r.sample_spacing = sample_spacing;
  else {
    double m = inf;
    if(!input.empty()) m = (std::min)(m, mean_length(input));
    if(!meshed.empty()) m = (std::min)(m, mean_length(meshed));
    r.sample_spacing = m < inf ? m / 20 : 0;
  }

  // the largest distance from the samples of `from` to the segments of `to`
  typedef typename std::vector<Segment_3>::const_iterator It;
  typedef CGAL::AABB_segment_primitive<GT, It> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GT, Primitive>> Tree;
  auto one_way = [&](const std::vector<Segment_3>& from, const std::vector<Segment_3>& to, double& worst,
                     std::array<double, 3>& where) {
    worst = 0;
    if(from.empty()) return;
    if(to.empty()) { worst = inf; where = vec(from.front().source()); return; }
    Tree tree(to.begin(), to.end());
    tree.accelerate_distance_queries();
    for(const Segment_3& g : from) {
      const double len = std::sqrt(CGAL::to_double(g.squared_length()));
      std::size_t parts = 1;
      if(r.sample_spacing > 0 && len > r.sample_spacing)
        parts = std::size_t((std::min)(std::ceil(len / r.sample_spacing), double(1 << 20)));
      for(std::size_t k = 0; k <= parts; ++k) {
        const Point_3 p = k == 0 ? g.source()
                        : k == parts ? g.target()
                        : g.source() + (g.target() - g.source()) * FT(double(k) / double(parts));
        const double dist = std::sqrt(CGAL::to_double(tree.squared_distance(p)));
        if(dist > worst) { worst = dist; where = vec(p); }
      }
    }
  };
  one_way(input, loose ? loose_meshed : meshed, r.input_to_mesh, r.worst_input_location);
  one_way(meshed, loose ? loose_input : input, r.mesh_to_input, r.worst_mesh_location);

  // corners -> nearest boundary vertex on a surface patch
  const auto& corners = features.corners();
  r.corners = corners.size();
  if(corners.empty()) return r;
  std::vector<Point_3> bv;
  {
    std::vector<std::uint32_t> ids;
    for(std::size_t f = 0; f < polys.size(); ++f)
      if(mesh.boundary_faces[f].patch >= 6) ids.insert(ids.end(), polys[f].begin(), polys[f].end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for(std::uint32_t v : ids) bv.push_back(mesh.points[v]);
  }
  if(bv.empty()) {
    r.max_corner_distance = inf;
    r.worst_corner_location = vec(features.point(corners.front()));
    return r;
  }
  typedef CGAL::Search_traits_3<GT> Search_traits;
  typedef CGAL::Orthogonal_k_neighbor_search<Search_traits> Search;
  typename Search::Tree kd(bv.begin(), bv.end());
  for(const auto c : corners) {
    const Point_3& p = features.point(c);
    Search search(kd, p, 1);
    const double dist = std::sqrt(CGAL::to_double(CGAL::squared_distance(p, search.begin()->first)));
    if(dist > r.max_corner_distance) { r.max_corner_distance = dist; r.worst_corner_location = vec(p); }
  }
  return r;
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief `feature_fidelity_with_tolerance()` with no tolerance: the input's feature edges against
 * the mesh's at `feature_angle`, both ways.
 */
template <typename HexMesh, typename Domain, typename FeatureCurves>
Feature_fidelity feature_fidelity(const HexMesh& mesh, const Domain& domain, const FeatureCurves& features,
                                  double feature_angle = 30, double sample_spacing = 0)
{
  return feature_fidelity_with_tolerance(mesh, domain, features, features, feature_angle, 0.0, sample_spacing);
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief where the mesh leaves a face of the meshing box uncovered: a body touching or crossing
 * the box face (the motorBike's tyres dip 4e-5 below the ground), see `box_contacts()`.
 */
struct Box_contact
{
  int patch = 0;                 ///< the box face: 0..5 (xmin, xmax, ymin, ymax, zmin, zmax)
  double area = 0;               ///< area of the box face left out of the mesh there (a hole of the face's patch)
  double body_area = 0;          ///< of it, the part inside the input (its section by the face; sampled, `Domain::is_inside()`)
  double filled_area = 0;        ///< `area - body_area`: the thin wedge between the input and the face, filled
  double max_gap = 0;            ///< the largest distance to the input of a filled sample (the wedge's thickness there)
  std::size_t samples = 0;       ///< samples drawn in the hole (a square grid over its box)
  std::array<double, 3> centre = {{0, 0, 0}};   ///< the hole's area centroid
  Bbox_3 bbox;                   ///< the hole's box
};

/// \ingroup PkgHexMeshing3Quality
/// \brief the six box faces' coverage and the holes in it (see `box_contacts()`)
struct Box_contacts
{
  std::array<double, 6> face_area = {{0, 0, 0, 0, 0, 0}};       ///< the box faces' areas
  std::array<double, 6> meshed_area = {{0, 0, 0, 0, 0, 0}};     ///< the area of the mesh faces on each
  std::array<double, 6> unmeshed_area = {{0, 0, 0, 0, 0, 0}};   ///< `face_area - meshed_area`
  std::array<double, 6> border_area = {{0, 0, 0, 0, 0, 0}};     ///< of it, in holes that reach the face's border (not in `contacts`)
  std::vector<Box_contact> contacts;                             ///< the holes inside the faces, largest first
  double filled_area = 0;                                        ///< summed over `contacts`
};

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief measures, on each face of `mesh.box`, the area that the faces of the box patches lying on
 * it cover (`box_patch[p]`: is patch `p` a box patch; empty: the patches 0..5), and finds the holes
 * in it: loops of patch edges (hanging nodes included, from the polyhedral form `pm`) inside
 * the face. Each hole is sampled on a square grid of about `samples_per_hole` points: a sample
 * inside the input (`domain.is_inside()`, a winding-number estimate on open input) is in the body's
 * section, any other one is filled (the mesh left out a wedge between the input and the face,
 * thinner there than the local cells); `max_gap` is the largest distance from a filled sample to the
 * input. A hole that reaches the face's border (a body crossing the box's edge) is not a contact:
 * its area is counted in `border_area`.
 *
 * Known limits: where a hole's boundary and a chain reaching the border share a vertex, the loop
 * walk may follow the chain, and that hole's area then goes to `border_area`; a meshed island
 * inside a hole is subtracted from every hole around it (nested holes and islands are not told
 * apart), and the centroid ignores islands. `hexmesh` tells the box patches by name after
 * `--patch-name`: an input part named like a box face's patch, whose faces lie on that plane,
 * would count as coverage.
 */
template <typename HexMesh, typename PolyhedralMesh, typename Domain>
Box_contacts box_contacts(const HexMesh& mesh, const PolyhedralMesh& pm, const Domain& domain,
                          std::vector<char> box_patch = {}, std::size_t samples_per_hole = 20000)
{
  if(box_patch.empty()) {   // the meshing's own numbering: the box faces are the patches 0..5
    box_patch.assign(pm.patches.size(), 0);
    for(std::size_t p = 0; p < 6 && p < box_patch.size(); ++p) box_patch[p] = 1;
  }
  typedef typename Domain::Point_3 Point_3;
  Box_contacts r;
  const Bbox_3& B = mesh.box;
  const double lo[3] = {B.xmin(), B.ymin(), B.zmin()}, hi[3] = {B.xmax(), B.ymax(), B.zmax()};
  // the faces on each box plane, from the box patches (after renaming, several planes may share a patch)
  std::array<std::vector<std::size_t>, 6> on_plane;
  for(std::size_t q = 0; q < pm.patches.size() && q < box_patch.size(); ++q) {
    if(!box_patch[q]) continue;
    for(std::size_t f = pm.patches[q].start; f < pm.patches[q].start + pm.patches[q].size; ++f)
      for(int p = 0; p < 6; ++p) {
        const int axis = p / 2;
        const double plane = p % 2 ? hi[axis] : lo[axis];
        bool all = true;
        for(auto v : pm.faces[f]) {
          const auto& x = mesh.points[v];
          const double c = CGAL::to_double(axis == 0 ? x.x() : axis == 1 ? x.y() : x.z());
          if(c != plane) { all = false; break; }
        }
        if(all) { on_plane[std::size_t(p)].push_back(f); break; }
      }
  }
  for(int p = 0; p < 6; ++p) {
    const int axis = p / 2, ua = (axis + 1) % 3, va = (axis + 2) % 3;
    const double plane = p % 2 ? hi[axis] : lo[axis];
    r.face_area[std::size_t(p)] = (hi[ua] - lo[ua]) * (hi[va] - lo[va]);
    auto uv = [&](std::uint32_t i) {
      const auto& q = mesh.points[i];
      const double c[3] = {CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())};
      return std::array<double, 2>{{c[ua], c[va]}};
    };
    typedef std::array<double, 2> P2;
    auto twice_area = [](const std::vector<P2>& L) {   // shoelace, signed by the polygon's turn
      double a = 0;
      for(std::size_t k = 0; k < L.size(); ++k) a += L[k][0] * L[(k + 1) % L.size()][1] - L[k][1] * L[(k + 1) % L.size()][0];
      return a;
    };
    // meshed area (in the face's plane), the patch's orientation there (its first face's turn),
    // and the directed edges of the patch
    std::vector<std::uint64_t> directed;
    double meshed = 0, face_sign = 0;
    const auto& faces = on_plane[std::size_t(p)];
    std::vector<P2> poly;
    for(std::size_t f : faces) {
      const auto& F = pm.faces[f];
      poly.clear();
      for(std::size_t k = 0; k < F.size(); ++k) {
        poly.push_back(uv(F[k]));
        directed.push_back(std::uint64_t(F[k]) << 32 | F[(k + 1) % F.size()]);
      }
      const double a = twice_area(poly);
      if(f == faces.front()) face_sign = a;
      meshed += std::abs(a) / 2;
    }
    std::sort(directed.begin(), directed.end());   // deterministic loops
    directed.erase(std::unique(directed.begin(), directed.end()), directed.end());
    r.meshed_area[std::size_t(p)] = meshed;
    r.unmeshed_area[std::size_t(p)] = (std::max)(0.0, r.face_area[std::size_t(p)] - meshed);
    // boundary edges of the patch away from the face's border, chained into loops
    auto on_border = [&](const std::array<double, 2>& x) {
      return x[0] == lo[ua] || x[0] == hi[ua] || x[1] == lo[va] || x[1] == hi[va];
    };
    std::multimap<std::uint32_t, std::uint32_t> next;
    for(std::uint64_t k : directed) {
      const std::uint32_t a = std::uint32_t(k >> 32), b = std::uint32_t(k & 0xffffffffu);
      if(std::binary_search(directed.begin(), directed.end(), std::uint64_t(b) << 32 | a)) continue;
      const auto xa = uv(a), xb = uv(b);
      if(on_border(xa) && on_border(xb) && (xa[0] == xb[0] || xa[1] == xb[1])) continue;   // along the border
      next.emplace(a, b);
    }
    // loops: area (signed: holes run against the patch's faces), box; chains ending on the border
    // belong to holes that reach it
    struct Loop { std::vector<P2> pts; double area; };
    std::vector<Loop> holes, islands;
    while(!next.empty()) {
      auto it = next.begin();
      const std::uint32_t start = it->first;
      Loop L;
      std::uint32_t v = start;
      bool closed = false;
      while(true) {
        auto e = next.find(v);
        if(e == next.end()) break;
        L.pts.push_back(uv(v));
        v = e->second;
        next.erase(e);
        if(v == start) { closed = true; break; }
      }
      if(!closed) continue;   // a chain from the border to the border: a hole reaching it
      L.area = twice_area(L.pts) / 2;
      ((L.area > 0) == (face_sign > 0) ? islands : holes).push_back(std::move(L));
    }
    auto inside = [](const Loop& L, const P2& x) {   // even-odd rule
      bool in = false;
      for(std::size_t i = 0, j = L.pts.size() - 1; i < L.pts.size(); j = i++) {
        const auto& a = L.pts[i];
        const auto& b = L.pts[j];
        if((a[1] > x[1]) != (b[1] > x[1]) && x[0] < (b[0] - a[0]) * (x[1] - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
      }
      return in;
    };
    for(Loop& H : holes) {
      Box_contact c;
      c.patch = p;
      double ulo = H.pts[0][0], uhi = ulo, vlo = H.pts[0][1], vhi = vlo, cu = 0, cv = 0;
      for(std::size_t k = 0; k < H.pts.size(); ++k) {
        const auto& x = H.pts[k];
        const auto& y = H.pts[(k + 1) % H.pts.size()];
        ulo = (std::min)(ulo, x[0]); uhi = (std::max)(uhi, x[0]); vlo = (std::min)(vlo, x[1]); vhi = (std::max)(vhi, x[1]);
        const double w = x[0] * y[1] - x[1] * y[0];
        cu += (x[0] + y[0]) * w; cv += (x[1] + y[1]) * w;
      }
      const double a2 = 2 * H.area;
      c.area = std::abs(H.area);
      // the islands (meshed parts) inside this hole
      std::vector<const Loop*> inner;
      for(const Loop& I : islands)
        if(inside(H, I.pts[0])) { inner.push_back(&I); c.area -= std::abs(I.area); }
      double pt[3];
      pt[axis] = plane;
      pt[ua] = a2 != 0 ? cu / (3 * a2) : ulo; pt[va] = a2 != 0 ? cv / (3 * a2) : vlo;
      c.centre = {{pt[0], pt[1], pt[2]}};
      double blo[3], bhi[3];
      blo[axis] = bhi[axis] = plane; blo[ua] = ulo; bhi[ua] = uhi; blo[va] = vlo; bhi[va] = vhi;
      c.bbox = Bbox_3(blo[0], blo[1], blo[2], bhi[0], bhi[1], bhi[2]);
      // samples on a square grid over the hole's box, at the cells' centres
      const double box_area = (uhi - ulo) * (vhi - vlo);
      std::size_t inside_hole = 0, in_body = 0;
      if(box_area > 0 && samples_per_hole > 0) {
        const double step = std::sqrt(box_area / double(samples_per_hole));
        const std::size_t nu = (std::max)(std::size_t(1), std::size_t(std::ceil((uhi - ulo) / step)));
        const std::size_t nv = (std::max)(std::size_t(1), std::size_t(std::ceil((vhi - vlo) / step)));
        for(std::size_t i = 0; i < nu; ++i)
          for(std::size_t j = 0; j < nv; ++j) {
            const P2 x{{ulo + (double(i) + 0.5) * (uhi - ulo) / double(nu), vlo + (double(j) + 0.5) * (vhi - vlo) / double(nv)}};
            bool in = inside(H, x);
            for(const Loop* I : inner) if(in && inside(*I, x)) in = false;
            if(!in) continue;
            ++inside_hole;
            double q[3];
            q[axis] = plane; q[ua] = x[0]; q[va] = x[1];
            const Point_3 s(q[0], q[1], q[2]);
            if(domain.is_inside(s)) { ++in_body; continue; }
            c.max_gap = (std::max)(c.max_gap, std::sqrt(CGAL::to_double(domain.squared_distance(s))));
          }
      }
      c.samples = inside_hole;
      c.body_area = inside_hole ? c.area * double(in_body) / double(inside_hole) : 0.0;
      c.filled_area = c.area - c.body_area;
      r.filled_area += c.filled_area;
      r.contacts.push_back(c);
    }
    double in_contacts = 0;
    for(const Box_contact& c : r.contacts) if(c.patch == p) in_contacts += c.area;
    r.border_area[std::size_t(p)] = (std::max)(0.0, r.unmeshed_area[std::size_t(p)] - in_contacts);
  }
  std::stable_sort(r.contacts.begin(), r.contacts.end(), [](const Box_contact& a, const Box_contact& b) { return a.area > b.area; });
  return r;
}

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_FIDELITY_H
