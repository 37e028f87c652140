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

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Random.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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
  Boundary_fidelity r;
  // mesh -> input
  double sum = 0;
  std::vector<Triangle_3> boundary;
  for(const auto& f : mesh.boundary_faces) {
    if(f.patch < 6) continue;
    ++r.surface_faces;
    const Point_3 &a = mesh.points[f.vertices[0]], &b = mesh.points[f.vertices[1]], &c = mesh.points[f.vertices[2]],
                  &d = mesh.points[f.vertices[3]];
    boundary.emplace_back(a, b, c);
    boundary.emplace_back(a, c, d);
    const Point_3 centre((a.x() + b.x() + c.x() + d.x()) / 4, (a.y() + b.y() + c.y() + d.y()) / 4,
                         (a.z() + b.z() + c.z() + d.z()) / 4);
    double worst = 0;
    const Point_3* pts[5] = {&a, &b, &c, &d, &centre};
    for(const Point_3* p : pts) {
      const double dist = std::sqrt(CGAL::to_double(domain.squared_distance(*p)));
      if(dist > worst) worst = dist;
      if(dist > r.max_face_distance) {
        r.max_face_distance = dist;
        r.worst_face_location = {{CGAL::to_double(p->x()), CGAL::to_double(p->y()), CGAL::to_double(p->z())}};
      }
    }
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
  for(std::size_t i = 0; i < nt; ++i) {
    total += std::sqrt(CGAL::to_double(domain.triangle(i).squared_area()));
    cumulative[i] = total;
  }
  if(!(total > 0)) return r;
  CGAL::Random rng(seed);
  sum = 0;
  for(std::size_t s = 0; s < samples; ++s) {
    const double u = rng.get_double(0, total);
    const std::size_t i = std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
    const Triangle_3& t = domain.triangle((std::min)(i, nt - 1));
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
 * \brief the topology of the domain's (repaired) triangles.
 */
template <typename Domain>
Surface_topology surface_topology(const Domain& domain)
{
  return internal::polygon_topology(domain.triangle_indices());
}

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_FIDELITY_H
