// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_INTERNAL_HOLE_FILL_H
#define CGAL_HEX_MESHING_3_INTERNAL_HOLE_FILL_H

#include <CGAL/Hex_meshing_3/internal/sealed_border_edges.h>

#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Bbox_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal {

// Splits a chain of `n` directed edges (edge i runs tail(i) -> head(i)) into simple loops: from
// each edge not yet used, a walk follows an unused edge out of each head (the first in order of
// (tail, index)); where it comes back to a vertex it passed, the edges since then form a loop
// (holes touching at a vertex are two loops). `loops` gets the loops, each as its edges' indices
// in order; false if a walk reaches a vertex with no unused edge out (more edges in than out:
// inconsistent orientations, or a chain that does not close), `loops` then incomplete. Each step
// scans the walk so far: quadratic in a loop's length. Deterministic.
template <typename Tail, typename Head>
bool split_into_loops(std::size_t n, const Tail& tail, const Head& head, std::vector<std::vector<std::size_t>>& loops)
{
  typedef decltype(tail(std::size_t(0))) Vertex;
  loops.clear();
  std::vector<std::pair<Vertex, std::size_t>> from;   // (tail, edge), sorted
  from.reserve(n);
  for(std::size_t i = 0; i < n; ++i) from.push_back({tail(i), i});
  std::sort(from.begin(), from.end());
  std::vector<char> used(n, 0);   // (indexed by position in `from`)
  auto next_edge = [&](Vertex v) -> std::size_t {   // an unused edge leaving v (its position in `from`), or none
    for(auto it = std::lower_bound(from.begin(), from.end(), std::make_pair(v, std::size_t(0)));
        it != from.end() && it->first == v; ++it)
      if(!used[std::size_t(it - from.begin())]) return std::size_t(it - from.begin());
    return std::size_t(-1);
  };
  std::vector<std::size_t> walk;
  std::vector<std::pair<Vertex, std::size_t>> on_walk;   // (vertex, position in the walk)
  for(std::size_t s0 = 0; s0 < n; ++s0) {
    if(used[s0]) continue;
    walk.clear();
    on_walk.clear();
    std::size_t e = s0;
    on_walk.push_back({tail(from[e].second), 0});
    while(true) {
      used[e] = 1;
      walk.push_back(from[e].second);
      const Vertex h = head(from[e].second);
      std::size_t back = std::size_t(-1);
      for(const auto& ow : on_walk) if(ow.first == h) back = ow.second;
      if(back != std::size_t(-1)) {   // back at a vertex of the walk: the edges since it form a loop
        loops.emplace_back(walk.begin() + std::ptrdiff_t(back), walk.end());
        walk.resize(back);
        while(!on_walk.empty() && on_walk.back().second > back) on_walk.pop_back();
        if(walk.empty()) break;
      } else on_walk.push_back({h, walk.size()});
      e = next_edge(h);
      if(e == std::size_t(-1)) return false;   // (walk not empty: a dead end)
    }
  }
  return true;
}

// Whether a loop whose vector area has the squared norm `area2` and whose perimeter is `length`
// may bound a hole: not folded flat (the two sides of a slit), its area at least 1/484 of the
// square of its perimeter (a rectangle 119 times longer than wide is at the limit)
inline bool spans_an_area(double area2, double length)
{
  return area2 * 484.0 * 484.0 >= length * length * length * length;
}

// CGAL's `triangulate_hole_polyline()` on a loop (its points `pts`, and per edge k -> k + 1 the
// third point of the face on it, `third`) as the hole fills call it: the triangulation minimising
// its worst dihedral angle, the rim's faces counted, over the 3D search space (the cubic search up
// to 100 edges, Delaunay-restricted beyond); no new vertex
template <typename Point_3, typename OutputIterator>
void triangulate_loop(const std::vector<Point_3>& pts, const std::vector<Point_3>& third, OutputIterator out)
{
  CGAL::Polygon_mesh_processing::triangulate_hole_polyline(
    pts, third, out, CGAL::parameters::use_2d_constrained_delaunay_triangulation(false).do_not_use_cubic_algorithm(pts.size() > 100));
}

// What `fill_holes()` adds to a triangle soup.
struct Hole_fill
{
  std::vector<std::array<std::uint32_t, 3>> triangles;   // on the soup's points
  std::vector<std::uint32_t> loop_of;   // per triangle, its hole (0, 1, ...)
  std::vector<std::uint32_t> loop_face;   // per hole, a face of the soup on its rim (the one of its first edge)
  std::size_t rim_edges = 0;   // the border edges closed (their number, over all holes)
};

// Fills the holes of a triangle soup whose faces are consistently oriented across their shared
// edges. Border edges: edges of exactly one triangle, that triangle not skipped (`skip`: the
// two-sided sheets, whose borders are rims, not holes), not sealed by another border edge, a
// sheet's included, within `seam_tolerance` (a seam between parts or a crack:
// `sealing_border_edges()`). They are chained as their faces run along them; a chain of more than
// `max_edges` edges or with a dead end (a vertex with more edges in than out: inconsistent
// orientations) closes nothing. Each closed chain is walked into simple loops
// (`split_into_loops()`). A loop of at
// least 3 edges whose vector area is at least 1/484 of the square of its perimeter (a rectangle
// 119 times longer than wide; not folded flat: the two sides of a slit) is filled by CGAL's
// `triangulate_hole_polyline()` (the triangulation minimising its worst dihedral angle, the rim's
// faces counted; no new vertex), oriented so that each rim edge runs against its face; a loop
// whose fill misses a rim edge, runs along an edge the wrong way, has a degenerate triangle
// (exact collinearity) or a chord that is already an edge of the soup or of a fill before it (a
// non-manifold edge) is left open, and so is one whose fill has more than `max_area_ratio` times
// the area of the surface around it (the triangles edge-connected to its rim): that is the rim of
// an open surface (a roof, a plate given once), not a hole. Deterministic (the soup's order only).
template <typename GT>
Hole_fill fill_holes(const std::vector<typename GT::Point_3>& points,
                     const std::vector<std::array<std::uint32_t, 3>>& tris,
                     const std::vector<bool>& skip, double seam_tolerance, std::size_t max_edges = 400,
                     double max_area_ratio = 0.5)
{
  typedef typename GT::Point_3 Point_3;
  typedef std::array<double, 3> V;
  Hole_fill out;
  // half-edges (undirected key, face, tail, head as the face runs)
  struct Half { std::uint64_t key; std::uint32_t face, tail, head; };
  std::vector<Half> half;
  half.reserve(3 * tris.size());
  for(std::size_t f = 0; f < tris.size(); ++f)
    for(int k = 0; k < 3; ++k) {
      const std::uint32_t u = tris[f][std::size_t(k)], v = tris[f][std::size_t((k + 1) % 3)];
      half.push_back({u < v ? (std::uint64_t(u) << 32 | v) : (std::uint64_t(v) << 32 | u), std::uint32_t(f), u, v});
    }
  std::sort(half.begin(), half.end(), [](const Half& a, const Half& b) { return a.key != b.key ? a.key < b.key : a.face < b.face; });
  std::vector<Half> border;
  // the triangles' edge-connected components and their areas
  std::vector<std::uint32_t> comp(tris.size());
  for(std::size_t f = 0; f < tris.size(); ++f) comp[f] = std::uint32_t(f);
  auto find_comp = [&](std::uint32_t x) { while(comp[x] != x) { comp[x] = comp[comp[x]]; x = comp[x]; } return x; };
  for(std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    while(j < half.size() && half[j].key == half[i].key) ++j;
    if(j - i == 1) border.push_back(half[i]);   // (a sheet's too, for the seam test; dropped after it)
    for(std::size_t k = i + 1; k < j; ++k) {
      const std::uint32_t a = find_comp(half[k].face), b = find_comp(half[i].face);
      if(a != b) comp[(std::max)(a, b)] = (std::min)(a, b);
    }
    i = j;
  }
  if(border.size() < 3) return out;
  auto triangle_area = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return std::sqrt(CGAL::to_double(CGAL::squared_area(points[a], points[b], points[c])));
  };
  std::vector<double> comp_area(tris.size(), 0.0);
  for(std::size_t f = 0; f < tris.size(); ++f) comp_area[find_comp(std::uint32_t(f))] += triangle_area(tris[f][0], tris[f][1], tris[f][2]);
  {
    std::vector<typename GT::Segment_3> segments;
    std::vector<std::array<std::uint32_t, 2>> ends;
    for(const Half& h : border) {
      segments.emplace_back(points[h.tail], points[h.head]);
      ends.push_back({{h.tail, h.head}});
    }
    const std::vector<char> sealed = sealed_border_edges<GT>(segments, ends, seam_tolerance);
    std::size_t kept = 0;
    for(std::size_t i = 0; i < border.size(); ++i) if(!sealed[i] && !skip[border[i].face]) border[kept++] = border[i];
    border.resize(kept);
  }
  if(border.size() < 3) return out;
  // an edge already in the soup, or of a fill made before (a chord must be neither)
  std::vector<std::uint64_t> soup_edges;
  soup_edges.reserve(half.size());
  for(const Half& h : half) if(soup_edges.empty() || soup_edges.back() != h.key) soup_edges.push_back(h.key);
  std::vector<std::uint64_t> fill_edges;   // sorted
  auto key_of = [](std::uint32_t u, std::uint32_t v) { return u < v ? (std::uint64_t(u) << 32 | v) : (std::uint64_t(v) << 32 | u); };
  // chains: edges sharing a vertex
  const std::size_t nb = border.size();
  std::vector<std::size_t> uf(nb);
  for(std::size_t i = 0; i < nb; ++i) uf[i] = i;
  auto find = [&](std::size_t x) { while(uf[x] != x) { uf[x] = uf[uf[x]]; x = uf[x]; } return x; };
  std::vector<std::pair<std::uint32_t, std::size_t>> at;   // (vertex, edge)
  for(std::size_t i = 0; i < nb; ++i) { at.push_back({border[i].tail, i}); at.push_back({border[i].head, i}); }
  std::sort(at.begin(), at.end());
  for(std::size_t i = 1; i < at.size(); ++i)
    if(at[i].first == at[i - 1].first) {
      const std::size_t a = find(at[i].second), b = find(at[i - 1].second);
      if(a != b) uf[(std::max)(a, b)] = (std::min)(a, b);
    }
  std::vector<std::vector<std::size_t>> chains(nb);
  for(std::size_t i = 0; i < nb; ++i) chains[find(i)].push_back(i);
  auto vec = [&](std::uint32_t v) { return V{{CGAL::to_double(points[v].x()), CGAL::to_double(points[v].y()), CGAL::to_double(points[v].z())}}; };
  std::vector<Point_3> pts, third;
  std::vector<CGAL::Triple<int, int, int>> fill;
  std::vector<std::vector<std::size_t>> loops;
  // fills one loop (edges in order, each head the next one's tail)
  auto fill_loop = [&](const std::vector<std::size_t>& lp) {
    const std::size_t n = lp.size();
    if(n < 3) return;
    // not folded flat
    V c{{0, 0, 0}}, area{{0, 0, 0}};
    double length = 0;
    for(std::size_t e : lp) { const V p = vec(border[e].tail); for(int k = 0; k < 3; ++k) c[std::size_t(k)] += p[std::size_t(k)] / double(n); }
    for(std::size_t e : lp) {
      const V p = vec(border[e].tail), q = vec(border[e].head);
      const V a{{p[0] - c[0], p[1] - c[1], p[2] - c[2]}}, b{{q[0] - c[0], q[1] - c[1], q[2] - c[2]}};
      area[0] += 0.5 * (a[1] * b[2] - a[2] * b[1]);
      area[1] += 0.5 * (a[2] * b[0] - a[0] * b[2]);
      area[2] += 0.5 * (a[0] * b[1] - a[1] * b[0]);
      length += std::sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]));
    }
    const double a2 = area[0] * area[0] + area[1] * area[1] + area[2] * area[2];
    if(!spans_an_area(a2, length)) return;
    pts.clear();
    third.clear();
    for(std::size_t e : lp) {
      pts.push_back(points[border[e].tail]);
      std::uint32_t o = border[e].tail;
      for(std::uint32_t w : tris[border[e].face]) if(w != border[e].tail && w != border[e].head) o = w;
      third.push_back(points[o]);
    }
    fill.clear();
    triangulate_loop(pts, third, std::back_inserter(fill));
    if(fill.size() != n - 2) return;
    // orientation: the rim edge k -> k + 1 runs along its face, so the fill runs k + 1 -> k
    int flip = -1;
    std::vector<int> seen(n, 0);
    for(const auto& t : fill) {
      const int ix[3] = {t.first, t.second, t.third};
      for(int i = 0; i < 3; ++i) {
        const int a = ix[i], b = ix[(i + 1) % 3];
        if(a < 0 || b < 0 || std::size_t(a) >= n || std::size_t(b) >= n) return;
        const bool forward = std::size_t(b) == (std::size_t(a) + 1) % n, backward = std::size_t(a) == (std::size_t(b) + 1) % n;
        if(!forward && !backward) continue;
        const int f = forward ? 1 : 0;   // flip this triangle's orientation
        if(flip < 0) flip = f;
        else if(flip != f) return;   // inconsistent
        ++seen[forward ? std::size_t(a) : std::size_t(b)];
      }
    }
    for(int s : seen) if(s != 1) return;   // every rim edge once
    const std::uint32_t id = std::uint32_t(out.loop_face.size());
    std::vector<std::array<std::uint32_t, 3>> added;
    double fill_area = 0;
    for(const auto& t : fill) {
      const std::size_t ix[3] = {std::size_t(t.first), std::size_t(t.second), std::size_t(t.third)};
      std::array<std::uint32_t, 3> tri = {{border[lp[ix[0]]].tail, border[lp[ix[1]]].tail, border[lp[ix[2]]].tail}};
      if(flip == 1) std::swap(tri[1], tri[2]);
      if(CGAL::collinear(points[tri[0]], points[tri[1]], points[tri[2]])) return;
      added.push_back(tri);
      for(int k = 0; k < 3; ++k) {   // a chord (not a rim edge) already an edge: non-manifold
        const std::size_t a = ix[k], b = ix[(k + 1) % 3];
        const std::uint64_t key = key_of(border[lp[a]].tail, border[lp[b]].tail);
        if(std::binary_search(fill_edges.begin(), fill_edges.end(), key)) return;
        // (a loop's vertices are distinct: its rim edges are the consecutive positions)
        const bool rim = b == (a + 1) % n || a == (b + 1) % n;
        if(!rim && std::binary_search(soup_edges.begin(), soup_edges.end(), key)) return;
      }
      fill_area += triangle_area(tri[0], tri[1], tri[2]);
    }
    if(!(fill_area <= max_area_ratio * comp_area[find_comp(border[lp[0]].face)])) return;
    const std::size_t old_edges = fill_edges.size();
    for(const auto& tri : added)
      for(int k = 0; k < 3; ++k) fill_edges.push_back(key_of(tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)]));
    std::sort(fill_edges.begin() + std::ptrdiff_t(old_edges), fill_edges.end());
    std::inplace_merge(fill_edges.begin(), fill_edges.begin() + std::ptrdiff_t(old_edges), fill_edges.end());
    out.triangles.insert(out.triangles.end(), added.begin(), added.end());
    out.loop_of.insert(out.loop_of.end(), added.size(), id);
    out.loop_face.push_back(border[lp[0]].face);
    out.rim_edges += n;
  };
  for(std::size_t root = 0; root < nb; ++root) {
    const std::vector<std::size_t>& es = chains[root];
    if(es.size() < 3 || es.size() > max_edges) continue;   // (the walk is quadratic in a chain's length)
    // the chain's loops (all or none: a chain with a dead end closes nothing)
    if(!split_into_loops(es.size(), [&](std::size_t i) { return border[es[i]].tail; },
                         [&](std::size_t i) { return border[es[i]].head; }, loops))
      continue;
    for(auto& lp : loops) {
      for(std::size_t& i : lp) i = es[i];
      fill_loop(lp);
    }
  }
  return out;
}

} // namespace internal
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_INTERNAL_HOLE_FILL_H
