// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_FEATURE_CURVES_3_H
#define CGAL_HEX_MESHING_3_FEATURE_CURVES_3_H

// Feature curves of a (repaired) triangle soup: the edges the mesh boundary must follow, chained
// into polylines between corners. CGAL's PMP::detect_sharp_edges() needs a polygon mesh; our input
// is a soup that may be open, non-manifold and carry two-sided sheets (motorBike), so the edges
// are found here from the soup itself (the tests compare with detect_sharp_edges() where both
// apply).

#include <CGAL/Hex_meshing_3/Surface_domain_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {

/*!
 * \ingroup PkgHexMeshing3Domains
 * \brief the feature curves of a `Surface_domain_3`: sharp edges (the normals of the two faces
 * differ by at least the feature angle), open edges (one face: holes, rims, sheet borders),
 * non-manifold edges (more than two faces), and the borders between parts (patches), chained into
 * polylines that end at corners. A corner is a vertex where a curve ends, where three or more
 * feature edges meet, or where a curve turns by at least the feature angle.
 *
 * The angle test is a floating-point decision on normals (an angle threshold is a tolerance, not
 * a predicate). On a two-sided sheet, whose orientation is arbitrary, the unsigned angle between
 * the planes of the faces is used.
 */
template <typename GeomTraits>
class Feature_curves_3
{
public:
  typedef typename GeomTraits::Point_3 Point_3;
  typedef std::uint32_t Index;

  /// what makes an edge a feature (a bit set: an edge may be several)
  enum Kind : std::uint8_t { SHARP = 1, OPEN = 2, NON_MANIFOLD = 4, PATCH_BORDER = 8 };

  struct Options
  {
    double feature_angle = 30;     ///< degrees; an edge whose face normals differ by at least this is sharp
    bool open_edges = true;
    bool non_manifold_edges = true;
    bool patch_borders = true;
  };

  struct Edge { std::array<Index, 2> vertices; std::uint8_t kind; };
  /// a polyline of point indices of the domain; closed curves repeat no vertex
  struct Curve { std::vector<Index> vertices; bool closed; };

  Feature_curves_3(const Surface_domain_3<GeomTraits>& domain, const Options& options = Options())
    : m_points(domain.points())
  {
    build(domain, options);
  }

  const std::vector<Edge>& edges() const { return m_edges; }
  /// the feature edges as pairs of point indices (for `Surface_domain_3::set_feature_edges()`)
  std::vector<std::array<Index, 2>> edge_vertices() const
  {
    std::vector<std::array<Index, 2>> v;
    v.reserve(m_edges.size());
    for(const Edge& e : m_edges) v.push_back(e.vertices);
    return v;
  }
  const std::vector<Curve>& curves() const { return m_curves; }
  /// the corners, sorted
  const std::vector<Index>& corners() const { return m_corners; }
  const Point_3& point(Index i) const { return m_points[i]; }
  /// the number of feature edges of kind `k` (an edge may count for several kinds)
  std::size_t number_of_edges(Kind k) const
  {
    return std::size_t(std::count_if(m_edges.begin(), m_edges.end(), [k](const Edge& e) { return (e.kind & k) != 0; }));
  }

private:
  typedef std::array<double, 3> V;
  static V vec(const Point_3& p) { return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}}; }
  static V sub(const V& a, const V& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
  static double dot(const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  static V cross(const V& a, const V& b)
  {
    return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
  }
  static V unit(V a)
  {
    const double l = std::sqrt(dot(a, a));
    if(l > 0) for(double& x : a) x /= l;
    return a;
  }

  void build(const Surface_domain_3<GeomTraits>& d, const Options& o)
  {
    const auto& tris = d.triangle_indices();
    const double cos_max = std::cos(o.feature_angle * CGAL_PI / 180.0);
    std::vector<V> normal(tris.size());
    for(std::size_t f = 0; f < tris.size(); ++f) {
      const V a = vec(m_points[tris[f][0]]), b = vec(m_points[tris[f][1]]), c = vec(m_points[tris[f][2]]);
      normal[f] = unit(cross(sub(b, a), sub(c, a)));
    }
    // (edge, face, direction) sorted by edge
    struct Half { std::uint64_t key; Index face; bool forward; };
    std::vector<Half> half;
    half.reserve(3 * tris.size());
    for(std::size_t f = 0; f < tris.size(); ++f)
      for(int k = 0; k < 3; ++k) {
        const Index u = tris[f][std::size_t(k)], v = tris[f][std::size_t((k + 1) % 3)];
        half.push_back({u < v ? (std::uint64_t(u) << 32 | v) : (std::uint64_t(v) << 32 | u), Index(f), u < v});
      }
    std::sort(half.begin(), half.end(), [](const Half& a, const Half& b) {
      return a.key != b.key ? a.key < b.key : a.face < b.face;
    });
    for(std::size_t i = 0; i < half.size();) {
      std::size_t j = i;
      while(j < half.size() && half[j].key == half[i].key) ++j;
      std::uint8_t kind = 0;
      const std::size_t deg = j - i;
      if(deg == 1 && o.open_edges) kind |= OPEN;
      if(deg > 2 && o.non_manifold_edges) kind |= NON_MANIFOLD;
      if(deg == 2) {
        const Half& h = half[i];
        const Half& g = half[i + 1];
        double c = dot(normal[h.face], normal[g.face]);
        if(d.is_two_sided(h.face) || d.is_two_sided(g.face)) c = std::abs(c);   // sheets: unsigned
        else if(h.forward == g.forward) c = -c;   // inconsistent orientation across the edge
        if(c <= cos_max) kind |= SHARP;
        if(o.patch_borders && d.patch(h.face) != d.patch(g.face)) kind |= PATCH_BORDER;
      }
      if(kind) m_edges.push_back({{Index(half[i].key >> 32), Index(half[i].key & 0xffffffffu)}, kind});
      i = j;
    }
    chain(cos_max);
  }

  // corners and polylines
  void chain(double cos_max)
  {
    std::vector<std::pair<Index, Index>> inc;   // (vertex, edge)
    for(std::size_t e = 0; e < m_edges.size(); ++e) {
      inc.push_back({m_edges[e].vertices[0], Index(e)});
      inc.push_back({m_edges[e].vertices[1], Index(e)});
    }
    std::sort(inc.begin(), inc.end());
    auto edges_at = [&](Index v) {
      auto lo = std::lower_bound(inc.begin(), inc.end(), std::make_pair(v, Index(0)));
      auto hi = std::lower_bound(inc.begin(), inc.end(), std::make_pair(v + 1, Index(0)));
      return std::make_pair(lo, hi);
    };
    auto other = [&](Index e, Index v) { return m_edges[e].vertices[0] == v ? m_edges[e].vertices[1] : m_edges[e].vertices[0]; };
    for(std::size_t i = 0; i < inc.size();) {
      std::size_t j = i;
      while(j < inc.size() && inc[j].first == inc[i].first) ++j;
      const Index v = inc[i].first;
      bool corner = (j - i) != 2;
      if(!corner) {   // a turn of at least the feature angle
        const V p = vec(m_points[v]);
        const V a = unit(sub(vec(m_points[other(inc[i].second, v)]), p));
        const V b = unit(sub(vec(m_points[other(inc[i + 1].second, v)]), p));
        corner = -dot(a, b) <= cos_max;   // straight: a = -b
      }
      if(corner) m_corners.push_back(v);
      i = j;
    }
    std::vector<char> used(m_edges.size(), 0), is_corner(m_points.size(), 0);
    for(Index c : m_corners) is_corner[c] = 1;
    auto walk = [&](Index start, Index e, Curve& curve) {
      Index v = start;
      curve.vertices.push_back(v);
      for(;;) {
        used[e] = 1;
        v = other(e, v);
        if(v == start) { curve.closed = true; return; }
        curve.vertices.push_back(v);
        if(is_corner[v]) return;
        const auto r = edges_at(v);
        Index next = Index(-1);
        for(auto it = r.first; it != r.second; ++it) if(!used[it->second]) { next = it->second; break; }
        if(next == Index(-1)) return;
        e = next;
      }
    };
    for(Index c : m_corners) {
      const auto r = edges_at(c);
      for(auto it = r.first; it != r.second; ++it)
        if(!used[it->second]) { Curve cv{{}, false}; walk(c, it->second, cv); m_curves.push_back(cv); }
    }
    for(std::size_t e = 0; e < m_edges.size(); ++e)   // closed loops without corner
      if(!used[e]) { Curve cv{{}, false}; walk(m_edges[e].vertices[0], Index(e), cv); m_curves.push_back(cv); }
  }

  const std::vector<Point_3>& m_points;
  std::vector<Edge> m_edges;
  std::vector<Curve> m_curves;
  std::vector<Index> m_corners;
};

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_FEATURE_CURVES_3_H
