// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_INTERNAL_SEALED_BORDER_EDGES_H
#define CGAL_HEX_MESHING_3_INTERNAL_SEALED_BORDER_EDGES_H

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Bbox_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal {

// The border edges of a triangle soup (edges of a single triangle) that seal each one: those,
// sharing no vertex index with it, that pass within min(`tolerance`, a quarter of its length) of
// its midpoint (in index order). An edge sealed by another is one side of a seam or a crack - two
// parts meeting along a line with their own copies of the vertices (the motorBike's parts;
// fandisk_crack), or a border lying along another part's border - not the border of a hole.
// `segments[i]` runs between the points of indices `ends[i]`. The answer depends only on the
// input (deterministic).
template <typename GT>
std::vector<std::vector<std::size_t>> sealing_border_edges(const std::vector<typename GT::Segment_3>& segments,
                                                           const std::vector<std::array<std::uint32_t, 2>>& ends,
                                                           double tolerance)
{
  typedef typename std::vector<typename GT::Segment_3>::const_iterator Seg_it;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GT, CGAL::AABB_segment_primitive<GT, Seg_it>>> Tree;
  std::vector<std::vector<std::size_t>> sealing(segments.size());
  if(segments.size() < 2 || !(tolerance > 0)) return sealing;
  const Tree tree(segments.begin(), segments.end());
  std::vector<typename Tree::Primitive_id> near;
  for(std::size_t i = 0; i < segments.size(); ++i) {
    const auto& s = segments[i];
    const double len = std::sqrt(CGAL::to_double(s.squared_length()));
    const double r = (std::min)(tolerance, 0.25 * len);
    if(!(r > 0)) continue;
    const auto m = CGAL::midpoint(s.source(), s.target());
    const double mx = CGAL::to_double(m.x()), my = CGAL::to_double(m.y()), mz = CGAL::to_double(m.z());
    near.clear();
    tree.all_intersected_primitives(Bbox_3(mx - r, my - r, mz - r, mx + r, my + r, mz + r), std::back_inserter(near));
    for(const auto& id : near) {
      const std::size_t j = std::size_t(id - segments.begin());
      if(j == i) continue;
      const auto& a = ends[i];
      const auto& b = ends[j];
      if(a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) continue;
      if(CGAL::to_double(CGAL::squared_distance(m, segments[j])) <= r * r) sealing[i].push_back(j);
    }
    std::sort(sealing[i].begin(), sealing[i].end());
  }
  return sealing;
}

// which border edges are sealed by another (`sealing_border_edges()`)
template <typename GT>
std::vector<char> sealed_border_edges(const std::vector<typename GT::Segment_3>& segments,
                                      const std::vector<std::array<std::uint32_t, 2>>& ends, double tolerance)
{
  const std::vector<std::vector<std::size_t>> sealing = sealing_border_edges<GT>(segments, ends, tolerance);
  std::vector<char> sealed(segments.size(), 0);
  for(std::size_t i = 0; i < segments.size(); ++i) sealed[i] = !sealing[i].empty();
  return sealed;
}

// removes the sealed border edges (`sealed_border_edges()`) from `segments` and `ends` alike
template <typename GT>
void remove_sealed_border_edges(std::vector<typename GT::Segment_3>& segments,
                                std::vector<std::array<std::uint32_t, 2>>& ends, double tolerance)
{
  const std::vector<char> sealed = sealed_border_edges<GT>(segments, ends, tolerance);
  std::size_t kept = 0;
  for(std::size_t i = 0; i < segments.size(); ++i)
    if(!sealed[i]) { segments[kept] = segments[i]; ends[kept] = ends[i]; ++kept; }
  segments.resize(kept);
  ends.resize(kept);
}

// the tolerance both the capture and `boundary_fidelity()` use: a thousandth of the diagonal of
// the input's bounding box
inline double seam_tolerance(const Bbox_3& b)
{
  return 1e-3 * std::sqrt((b.xmax() - b.xmin()) * (b.xmax() - b.xmin()) + (b.ymax() - b.ymin()) * (b.ymax() - b.ymin()) +
                          (b.zmax() - b.zmin()) * (b.zmax() - b.zmin()));
}

} // namespace internal
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_INTERNAL_SEALED_BORDER_EDGES_H
