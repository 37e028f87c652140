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
#include <CGAL/Hex_meshing_3/internal/Min_union_find.h>
#include <CGAL/Hex_meshing_3/internal/hole_fill.h>
#include <CGAL/Hex_meshing_3/internal/sealed_border_edges.h>

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
  /// (SEAM: no input edge, it joins two curve ends across a seam or a crack, see `Options::open_edges`;
  /// SOFT: a crease below the feature angle, see `Options::soft_angle`)
  enum Kind : std::uint8_t { SHARP = 1, OPEN = 2, NON_MANIFOLD = 4, PATCH_BORDER = 8, SEAM = 16, SOFT = 32 };

  struct Options
  {
    double feature_angle = 30;     ///< degrees; an edge whose face normals differ by at least this is sharp
    /// open edges are features, but for those that are one side of a seam or a crack (another
    /// border edge within a thousandth of the input's diagonal) across which the two faces are
    /// not sharp: those are no features. Two curve ends that close, whose curves run on in
    /// opposite directions (a crease crossing a crack), are joined by a `SEAM` edge: one curve.
    /// A closed loop of open edges at least half of whose length has its faces within the feature
    /// angle of the surface that would close it is the rim of a hole in a smooth surface: no
    /// feature either (two-sided sheets keep their borders). The rim of a hole the domain filled
    /// (`Surface_domain_3::is_fill()`) is judged the same way against its fill: a feature all
    /// along (sharp edges) unless it is smooth; the edges inside a fill are never features.
    bool open_edges = true;
    bool non_manifold_edges = true;
    bool patch_borders = true;
    /// a length; 0 (the default) keeps every sharp edge. Otherwise sharp edges are judged at this
    /// scale too: the normals of the input faces within `scale` on either side of an edge,
    /// averaged by area, must still differ by at least the feature angle, and a curve of sharp
    /// edges is kept only if at least half its length passes. The creases of a coarse
    /// triangulation of a smooth shape fail (the averages meet around a short crease's ends, or
    /// across many shallow ones); a CAD edge between faces wider than `scale` passes. Open,
    /// non-manifold and part-border edges are always kept. `make_hex_mesh_3()` uses half the
    /// surface size when it builds the curves itself.
    double scale = 0;
    /// a ratio; 0 (the default) keeps every sharp edge. Otherwise a sharp edge must also stand
    /// out from the input around it: its dihedral angle must be at least `contrast` times the
    /// mean angle of the non-sharp edges of the faces around it (its two faces and their
    /// neighbours), unless it is at least twice the feature angle; a curve of sharp edges is kept
    /// only if at least half its length passes.
    /// A coarse triangulation of a smooth shape has 30 degree edges among 10-15 degree ones (the
    /// test data's eight, bunny, elephant: median ratio 2.7-3.5); a CAD edge between flat or
    /// finely triangulated faces has a ratio of 20 or more. `make_hex_mesh_3()` uses 3 when it
    /// builds the curves itself.
    double contrast = 0;
    /// degrees; 0 (the default) or at least the feature angle: none. Otherwise an edge whose face
    /// normals differ by at least this but less than the feature angle is a soft crease (`SOFT`):
    /// the creases between the flat facets of a faceted blend or fillet (fandisk's blends: 17 to
    /// 22 degrees), which a mesh boundary following them keeps as close to the input as the
    /// facets are (crossing them, its faces cut under the creases). Soft creases need the
    /// judgement of `scale` or `contrast` (without both, no edge is soft), at this angle: sharp
    /// at the scale, and standing out 3 x `contrast` times from the mean angle of the edges
    /// around below this angle, with no pass at twice the angle as sharp edges have (a faceted
    /// blend's creases run between flat facets; the coarse triangulation of a smooth shape
    /// creases by 20 to 30 degrees among creases of 5 to 15: the elephant keeps 2 of 1,132).
    /// They are judged on their own curves, chained apart from the sharp edges (whose judgement
    /// they leave as it was): at least half of a curve's length passing, the curve at least 4 x
    /// `scale` long (twice the finest size when `make_hex_mesh_3()` builds the curves). An edge
    /// that is a feature of another kind (a part border) is no soft crease. Not counted by
    /// `feature_fidelity()` as input features.
    double soft_angle = 0;
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
  /// the sharp edges left out because they are not sharp at `Options::scale` or do not stand out
  /// by `Options::contrast`
  std::size_t number_of_smooth_edges() const { return m_smooth_edges; }
  /// the soft creases left out likewise (at `Options::soft_angle`), or on a curve of them shorter
  /// than 4 x `Options::scale`
  std::size_t number_of_smooth_soft_edges() const { return m_smooth_soft_edges; }
  /// the open edges left out because they are one side of a seam or a crack across which the
  /// surface is smooth (see `Options::open_edges`)
  std::size_t number_of_smooth_seam_edges() const { return m_smooth_seam_edges; }
  /// the open edges left out because they are the rim of a hole in a smooth surface (see
  /// `Options::open_edges`)
  std::size_t number_of_smooth_hole_rim_edges() const { return m_hole_rim_edges; }
  /// the rim edges of the holes the domain filled (`Surface_domain_3::is_fill()`) left out
  /// likewise: the rims of holes in a smooth surface
  std::size_t number_of_smooth_filled_rim_edges() const { return m_filled_rim_edges; }
  /// the `SEAM` edges that join curve ends across a seam or a crack
  std::size_t number_of_seam_bridges() const { return m_seam_bridges; }

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
    const bool judge = o.scale > 0 || o.contrast > 0;
    const bool judge_soft = judge && o.soft_angle > 0 && o.soft_angle < o.feature_angle;
    const double cos_soft = judge_soft ? std::cos(o.soft_angle * CGAL_PI / 180.0) : cos_max;
    std::vector<Edge> soft;   // the soft creases, with their faces, until judged
    std::vector<std::array<Index, 2>> soft_faces;
    std::vector<char> soft_consistent;
    std::vector<V> normal(tris.size());
    for(std::size_t f = 0; f < tris.size(); ++f) {
      const V a = vec(m_points[tris[f][0]]), b = vec(m_points[tris[f][1]]), c = vec(m_points[tris[f][2]]);
      normal[f] = unit(cross(sub(b, a), sub(c, a)));
    }
    // (edge, face, direction) sorted by edge
    struct Half { std::uint64_t key; Index face; bool forward; std::uint8_t slot; };
    std::vector<Open_edge> open_edges;
    std::vector<Half> half;
    half.reserve(3 * tris.size());
    for(std::size_t f = 0; f < tris.size(); ++f)
      for(int k = 0; k < 3; ++k) {
        const Index u = tris[f][std::size_t(k)], v = tris[f][std::size_t((k + 1) % 3)];
        half.push_back({u < v ? (std::uint64_t(u) << 32 | v) : (std::uint64_t(v) << 32 | u), Index(f), u < v,
                        std::uint8_t(k)});
      }
    // for the judgement at a scale: the face across each side (none at open and non-manifold
    // edges), whether it is oriented the same way, and the feature edge on each side
    const Index none = Index(-1);
    std::vector<Index> across;
    std::vector<char> same_way;
    std::vector<float> slot_angle;   // degrees, at manifold edges
    std::vector<std::array<Index, 2>> edge_faces;   // per feature edge, its two faces (or none)
    std::vector<char> edge_consistent;
    if(judge) {
      across.assign(3 * tris.size(), none);
      same_way.assign(3 * tris.size(), 1);
      slot_angle.assign(3 * tris.size(), -1.f);
    }
    std::sort(half.begin(), half.end(), [](const Half& a, const Half& b) {
      return a.key != b.key ? a.key < b.key : a.face < b.face;
    });
    // the rims of the holes the domain filled: per hole (from 1), its rim's length and the length
    // whose input face meets the fill within the feature angle; per rim edge, its hole
    std::vector<double> rim_length, rim_smooth;
    std::vector<std::pair<std::size_t, std::size_t>> rim_edges;   // (index in m_edges, hole)
    for(std::size_t i = 0; i < half.size();) {
      std::size_t j = i;
      while(j < half.size() && half[j].key == half[i].key) ++j;
      std::uint8_t kind = 0;
      bool soft_here = false;   // a soft crease (set aside: judged after the sharp edges)
      const std::size_t deg = j - i;
      if(deg == 1 && o.open_edges) kind |= OPEN;
      if(deg > 2 && o.non_manifold_edges) kind |= NON_MANIFOLD;
      if(deg == 2) {
        const Half& h = half[i];
        const Half& g = half[i + 1];
        double c = dot(normal[h.face], normal[g.face]);
        if(d.is_two_sided(h.face) || d.is_two_sided(g.face)) c = std::abs(c);   // sheets: unsigned
        else if(h.forward == g.forward) c = -c;   // inconsistent orientation across the edge
        const std::size_t hole = (std::max)(d.filled_hole(h.face), d.filled_hole(g.face));
        if(d.is_fill(h.face) && d.is_fill(g.face)) {
          // inside a fill: never a feature
        } else if(hole > 0 && !o.open_edges) {
          if(c <= cos_max) kind |= SHARP;   // (rims not judged as such: an edge like any other)
        } else if(hole > 0) {
          // a filled hole's rim: judged with the whole rim below (provisionally a feature)
          if(rim_length.size() <= hole) { rim_length.resize(hole + 1, 0.0); rim_smooth.resize(hole + 1, 0.0); }
          const V p = vec(m_points[Index(h.key >> 32)]), q = vec(m_points[Index(h.key & 0xffffffffu)]);
          const double len = std::sqrt(dot(sub(q, p), sub(q, p)));
          rim_length[hole] += len;
          if(c > cos_max) rim_smooth[hole] += len;
          rim_edges.push_back({m_edges.size(), hole});
          kind |= SHARP;
        } else if(c <= cos_max) kind |= SHARP;
        else if(c <= cos_soft) soft_here = true;
        if(judge)
          slot_angle[3 * h.face + h.slot] = slot_angle[3 * g.face + g.slot] =
            float(std::acos((std::max)(-1.0, (std::min)(1.0, c))) * 180.0 / CGAL_PI);
        if(o.patch_borders && !d.same_part(h.face, g.face, h.forward != g.forward)) kind |= PATCH_BORDER;
      }
      if(judge && deg == 2) {
        const Half& h = half[i];
        const Half& g = half[i + 1];
        across[3 * h.face + h.slot] = g.face;
        across[3 * g.face + g.slot] = h.face;
        same_way[3 * h.face + h.slot] = same_way[3 * g.face + g.slot] = char(h.forward != g.forward);
      }
      if(soft_here && !kind) {
        soft.push_back({{Index(half[i].key >> 32), Index(half[i].key & 0xffffffffu)}, SOFT});
        soft_faces.push_back({{half[i].face, half[i + 1].face}});
        soft_consistent.push_back(char(half[i].forward != half[i + 1].forward));
      }
      if(kind) {
        if(kind & OPEN) open_edges.push_back({Index(m_edges.size()), half[i].face, half[i].forward});
        m_edges.push_back({{Index(half[i].key >> 32), Index(half[i].key & 0xffffffffu)}, kind});
        if(judge) {
          edge_faces.push_back(deg == 2 ? std::array<Index, 2>{{half[i].face, half[i + 1].face}}
                                        : std::array<Index, 2>{{none, none}});
          edge_consistent.push_back(char(deg == 2 && half[i].forward != half[i + 1].forward));
        }
      }
      i = j;
    }
    // a filled hole's rim at least half of whose length meets the fill within the feature angle
    // is the rim of a hole in a smooth surface: no feature, the capture closes the hole smoothly;
    // other rims (the fill meets them at an angle: an open box's rim) are features all along
    // (as `mark_smooth_hole_rims()` judges the holes left open)
    bool dropped = false;
    for(const auto& re : rim_edges)
      if(rim_smooth[re.second] >= 0.5 * rim_length[re.second]) {
        Edge& e = m_edges[re.first];
        e.kind = std::uint8_t(e.kind & ~SHARP);
        if(e.kind == 0) { ++m_filled_rim_edges; dropped = true; }
      }
    if(dropped && open_edges.empty()) remove_dropped_edges(edge_faces, edge_consistent);
    if(!open_edges.empty()) {
      mark_smooth_seams(d, cos_max, normal, open_edges);
      mark_smooth_hole_rims(d, cos_max, normal, open_edges);
      remove_dropped_edges(edge_faces, edge_consistent);
      bridge_seams(internal::seam_tolerance(d.bbox()), cos_max, judge, edge_faces, edge_consistent);
    }
    if(judge) m_smooth_edges = judge_sharp_edges(d, o, cos_max, cos_max, false, across, same_way, slot_angle, edge_faces, edge_consistent);
    if(!soft.empty()) {
      // the soft creases judged on their own curves (the sharp edges' judgement as without them),
      // then merged with the features kept
      m_edges.swap(soft);
      m_smooth_soft_edges = judge_sharp_edges(d, o, cos_max, cos_soft, true, across, same_way, slot_angle, soft_faces, soft_consistent);
      m_edges.swap(soft);
      // (both sorted by vertices; an edge in both - a seam bridge along an input edge - once, as
      // the feature it already was)
      auto by_vertices = [](const Edge& a, const Edge& b) { return a.vertices < b.vertices; };
      CGAL_assertion(std::is_sorted(m_edges.begin(), m_edges.end(), by_vertices) &&
                     std::is_sorted(soft.begin(), soft.end(), by_vertices));
      std::vector<Edge> all;
      all.reserve(m_edges.size() + soft.size());
      std::set_union(m_edges.begin(), m_edges.end(), soft.begin(), soft.end(), std::back_inserter(all), by_vertices);
      m_edges.swap(all);
    }
    chain(cos_max);
  }

  // an open edge, its face, and whether the face runs along it from its smaller vertex index
  struct Open_edge { Index edge; Index face; bool forward; };

  // Open edges that are one side of a seam or a crack (`internal::sealed_border_edges()`: another
  // border edge passes within the seam tolerance, a thousandth of the input's diagonal): the
  // faces meet there as across an ordinary edge, so such an edge is no feature if the surface is
  // smooth across the seam (the angle test of a shared edge, with the face of any border edge
  // that seals it). A crack through a smooth surface (fandisk_crack) leaves no curve; a border
  // between two parts along a crease keeps it.
  void mark_smooth_seams(const Surface_domain_3<GeomTraits>& d, double cos_max, const std::vector<V>& normal,
                         const std::vector<Open_edge>& open)
  {
    std::vector<typename GeomTraits::Segment_3> segments;
    std::vector<std::array<std::uint32_t, 2>> ends;
    for(const Open_edge& oe : open) {
      const auto& e = m_edges[oe.edge].vertices;
      segments.push_back(typename GeomTraits::Segment_3(m_points[e[0]], m_points[e[1]]));
      ends.push_back({{e[0], e[1]}});
    }
    // the edge's direction as its face runs along it
    auto along = [&](const Open_edge& oe) {
      const auto& e = m_edges[oe.edge].vertices;
      const V a = vec(m_points[e[0]]), b = vec(m_points[e[1]]);
      return oe.forward ? sub(b, a) : sub(a, b);
    };
    // whether the faces of open edges i and j meet at an angle below the feature angle
    auto smooth = [&](std::size_t i, std::size_t j) {
      const Open_edge& a = open[i];
      const Open_edge& b = open[j];
      double c = dot(normal[a.face], normal[b.face]);
      if(d.is_two_sided(a.face) || d.is_two_sided(b.face)) c = std::abs(c);
      else if(dot(along(a), along(b)) > 0) c = -c;   // the faces run the same way along the seam: inconsistent
      return c > cos_max;
    };
    const std::vector<std::vector<std::size_t>> sealing =
      internal::sealing_border_edges<GeomTraits>(segments, ends, internal::seam_tolerance(d.bbox()));
    std::vector<char> smooth_seam(open.size(), 0);
    for(std::size_t i = 0; i < open.size(); ++i)
      for(std::size_t j : sealing[i]) if(smooth(i, j)) { smooth_seam[i] = 1; break; }
    // a crease along a seam is the border of both sides: one side's edges are enough (those
    // sealed by no kept edge of the other side, in index order)
    std::vector<char> second(open.size(), 0);
    for(std::size_t i = 0; i < open.size(); ++i) {
      if(smooth_seam[i]) continue;
      for(std::size_t j : sealing[i])
        if(j < i && !smooth_seam[j] && !second[j]) { second[i] = 1; break; }
    }
    for(std::size_t i = 0; i < open.size(); ++i) {
      if(!smooth_seam[i] && !second[i]) continue;
      Edge& e = m_edges[open[i].edge];
      e.kind = std::uint8_t(e.kind & ~OPEN);
      if(e.kind == 0) ++m_smooth_seam_edges;
    }
  }

  // Hole rims: the open edges left (not along a seam, not of a two-sided sheet), grouped into
  // connected chains; a closed one (every vertex on an even number of its edges) bounds holes,
  // which are filled (`fill_hole_rims()`). A chain at least half of whose length has its faces
  // within the feature angle of the fill's triangles on its edges is the rim of a hole in a
  // smooth surface (elephant-with-holes): no feature, the capture closes it smoothly. Rims the
  // fill meets at an angle (a spout's end, a body's rim under its lid: teapot) stay features.
  // A chain with no fill is compared with the plane of its vector area instead (as its faces
  // run along it, about its centroid; unsigned).
  void mark_smooth_hole_rims(const Surface_domain_3<GeomTraits>& d, double cos_max, const std::vector<V>& normal,
                             const std::vector<Open_edge>& open)
  {
    std::vector<std::size_t> rim;   // indices into `open` of the open edges still features
    for(std::size_t i = 0; i < open.size(); ++i)
      if((m_edges[open[i].edge].kind & OPEN) && !d.is_two_sided(open[i].face)) rim.push_back(i);
    if(rim.empty()) return;
    // chains: union of the edges sharing a vertex
    std::vector<std::pair<Index, std::size_t>> at;   // (vertex, position in rim)
    for(std::size_t r = 0; r < rim.size(); ++r)
      for(Index v : m_edges[open[rim[r]].edge].vertices) at.push_back({v, r});
    std::sort(at.begin(), at.end());
    internal::Min_union_find<std::size_t> uf(rim.size());
    for(std::size_t i = 1; i < at.size(); ++i) if(at[i].first == at[i - 1].first) uf.unite(at[i].second, at[i - 1].second);
    // only closed loops bound a hole: every vertex of the chain on an even number of its edges
    // (two, or four where two holes touch)
    std::vector<char> closed(rim.size(), 1);
    for(std::size_t i = 0; i < at.size();) {
      std::size_t j = i;
      while(j < at.size() && at[j].first == at[i].first) ++j;
      if((j - i) % 2 != 0) closed[uf.find(at[i].second)] = 0;
      i = j;
    }
    // per chain (at its root): the centroid of its edges' midpoints, its edge count and length
    std::vector<V> centre(rim.size(), V{{0, 0, 0}}), area(rim.size(), V{{0, 0, 0}});
    std::vector<double> count(rim.size(), 0), length(rim.size(), 0), smooth_length(rim.size(), 0), edge_length(rim.size());
    for(std::size_t r = 0; r < rim.size(); ++r) {
      const auto& e = m_edges[open[rim[r]].edge].vertices;
      const V p = vec(m_points[e[0]]), q = vec(m_points[e[1]]);
      const std::size_t root = uf.find(r);
      for(std::size_t k = 0; k < 3; ++k) centre[root][k] += 0.5 * (p[k] + q[k]);
      count[root] += 1;
      edge_length[r] = std::sqrt(dot(sub(q, p), sub(q, p)));
      length[root] += edge_length[r];
    }
    for(std::size_t r = 0; r < rim.size(); ++r)
      if(count[r] > 0) for(double& x : centre[r]) x /= count[r];
    // the vector area, its edges taken as their faces run along them
    for(std::size_t r = 0; r < rim.size(); ++r) {
      const Open_edge& oe = open[rim[r]];
      const auto& e = m_edges[oe.edge].vertices;
      const Index a = oe.forward ? e[0] : e[1], b = oe.forward ? e[1] : e[0];
      const std::size_t root = uf.find(r);
      const V w = cross(sub(vec(m_points[a]), centre[root]), sub(vec(m_points[b]), centre[root]));
      for(std::size_t k = 0; k < 3; ++k) area[root][k] += w[k];
    }
    // the loop's length whose faces lie within the feature angle of the closing surface: the
    // hole filled by CGAL's `triangulate_hole_polyline()` (the triangulation minimising its worst
    // dihedral angle, the rim's faces counted), each edge's face against the fill's triangle on
    // it; where there is no fill (a chain of more than 400 edges, inconsistent orientations, no
    // triangulation found), the plane of the chain's vector area
    std::vector<char> filled(rim.size(), 0);
    fill_hole_rims(d, rim, open, uf, closed, cos_max, normal, edge_length, smooth_length, filled);
    for(std::size_t r = 0; r < rim.size(); ++r) {
      const std::size_t root = uf.find(r);
      if(filled[root]) continue;
      if(std::abs(dot(unit(area[root]), normal[open[rim[r]].face])) > cos_max) smooth_length[root] += edge_length[r];
    }
    // a loop mostly smooth with its closing surface is a hole's rim: all of it goes (a rim in
    // pieces would leave curve ends and corners all along it)
    for(std::size_t r = 0; r < rim.size(); ++r) {
      const std::size_t root = uf.find(r);
      if(!closed[root] || count[root] < 3) continue;   // a chain that closes nothing
      // (a loop folded flat has no closing surface)
      if(!internal::spans_an_area(dot(area[root], area[root]) / 4, length[root])) continue;   // (the vector area is half the sum)
      if(smooth_length[root] < 0.5 * length[root]) continue;   // the closing surface meets it at an angle
      Edge& ed = m_edges[open[rim[r]].edge];
      ed.kind = std::uint8_t(ed.kind & ~OPEN);
      if(ed.kind == 0) ++m_hole_rim_edges;
    }
  }

  // The hole-rim test with the hole filled (see `mark_smooth_hole_rims()`): each closed chain of
  // at most `max_fill` edges is split into simple loops (its edges as their faces run along
  // them: `internal::split_into_loops()`, as the domain's own fill), each loop is filled, and
  // `smooth_length[root]` gets the length of the edges whose face meets the fill's triangle on
  // the edge within the feature angle; `filled[root]` is set if every loop of the chain was filled.
  template <typename Union_find>
  void fill_hole_rims(const Surface_domain_3<GeomTraits>& d, const std::vector<std::size_t>& rim,
                      const std::vector<Open_edge>& open, Union_find& uf, const std::vector<char>& closed,
                      double cos_max, const std::vector<V>& normal, const std::vector<double>& edge_length,
                      std::vector<double>& smooth_length, std::vector<char>& filled)
  {
    const auto& tris = d.triangle_indices();
    const std::size_t max_fill = 400;   // (the search is cubic in a loop's length at worst)
    std::vector<std::vector<std::size_t>> chain_edges(rim.size());
    for(std::size_t r = 0; r < rim.size(); ++r) {
      const std::size_t root = uf.find(r);
      if(closed[root]) chain_edges[root].push_back(r);
    }
    // an edge's ends as its face runs along it: tail -> head
    auto tail = [&](std::size_t r) { const Open_edge& oe = open[rim[r]]; const auto& e = m_edges[oe.edge].vertices; return oe.forward ? e[0] : e[1]; };
    auto head = [&](std::size_t r) { const Open_edge& oe = open[rim[r]]; const auto& e = m_edges[oe.edge].vertices; return oe.forward ? e[1] : e[0]; };
    std::vector<std::vector<std::size_t>> loops;
    std::vector<Point_3> points, third;
    std::vector<CGAL::Triple<int, int, int>> triangles;
    std::vector<int> apex;
    // fills one loop (edges in order); false if no fill was found
    auto fill = [&](const std::vector<std::size_t>& lp, double& smooth) {
      points.clear();
      third.clear();
      for(std::size_t q : lp) {
        points.push_back(m_points[tail(q)]);
        Index o = Index(-1);
        for(Index w : tris[open[rim[q]].face]) if(w != tail(q) && w != head(q)) o = w;
        CGAL_assertion(o != Index(-1));   // (the domain's triangles are not degenerate)
        third.push_back(m_points[o]);
      }
      triangles.clear();
      internal::triangulate_loop(points, third, std::back_inserter(triangles));
      // per loop edge (k, k + 1), the third vertex of the fill's triangle on it
      const int n = int(lp.size());
      apex.assign(lp.size(), -1);
      for(const auto& tr : triangles) {
        const int ix[3] = {tr.first, tr.second, tr.third};
        for(int i = 0; i < 3; ++i)
          for(int j = 0; j < 3; ++j)
            if(i != j && ix[j] == (ix[i] + 1) % n) apex[std::size_t(ix[i])] = ix[3 - i - j];
      }
      if(std::find(apex.begin(), apex.end(), -1) != apex.end()) return false;
      for(int k = 0; k < n; ++k) {
        const V a = vec(points[std::size_t(k)]), b = vec(points[std::size_t((k + 1) % n)]);
        const V t = vec(points[std::size_t(apex[std::size_t(k)])]);
        // the fill runs along the edge b -> a (consistently with the face, which runs a -> b)
        const V nf = unit(cross(sub(a, b), sub(t, b)));
        const std::size_t q = lp[std::size_t(k)];
        if(dot(nf, normal[open[rim[q]].face]) > cos_max) smooth += edge_length[q];
      }
      return true;
    };
    for(std::size_t root = 0; root < rim.size(); ++root) {
      const std::vector<std::size_t>& es = chain_edges[root];
      if(es.size() < 3 || es.size() > max_fill) continue;
      if(!internal::split_into_loops(es.size(), [&](std::size_t i) { return tail(es[i]); },
                                     [&](std::size_t i) { return head(es[i]); }, loops))
        continue;   // (a dead end: inconsistent orientations)
      bool ok = true;
      double smooth = 0;
      for(auto& lp : loops) {
        for(std::size_t& i : lp) i = es[i];
        if(lp.size() < 3 || !fill(lp, smooth)) { ok = false; break; }
      }
      if(!ok) continue;
      filled[root] = 1;
      smooth_length[root] = smooth;
    }
  }

  // the edges no longer features of any kind (after the seams and the hole rims) are removed
  void remove_dropped_edges(std::vector<std::array<Index, 2>>& edge_faces, std::vector<char>& edge_consistent)
  {
    std::size_t k = 0;
    for(std::size_t e = 0; e < m_edges.size(); ++e) {
      if(m_edges[e].kind == 0) continue;
      m_edges[k] = m_edges[e];
      if(!edge_faces.empty()) { edge_faces[k] = edge_faces[e]; edge_consistent[k] = edge_consistent[e]; }
      ++k;
    }
    m_edges.resize(k);
    if(!edge_faces.empty()) { edge_faces.resize(k); edge_consistent.resize(k); }
  }

  // Curve ends across a seam or a crack: two vertices with one feature edge each, closer than
  // `tol`, whose edges run on in opposite directions (within the feature angle), are joined by a
  // `SEAM` edge; nearest pairs first. A crease crossing a crack is then one curve, not two with a
  // pair of corners a hair apart. Deterministic: candidates ordered by (distance, indices).
  void bridge_seams(double tol, double cos_max, bool judge, std::vector<std::array<Index, 2>>& edge_faces,
                    std::vector<char>& edge_consistent)
  {
    const Index none = Index(-1);
    std::vector<Index> degree(m_points.size(), 0), edge_at(m_points.size(), none);
    for(std::size_t e = 0; e < m_edges.size(); ++e)
      for(Index v : m_edges[e].vertices) { ++degree[v]; edge_at[v] = Index(e); }
    std::vector<Index> ends;
    for(Index v = 0; v < m_points.size(); ++v) if(degree[v] == 1) ends.push_back(v);
    if(ends.size() < 2) return;
    std::sort(ends.begin(), ends.end(), [&](Index a, Index b) {
      const double xa = CGAL::to_double(m_points[a].x()), xb = CGAL::to_double(m_points[b].x());
      return xa != xb ? xa < xb : a < b;
    });
    auto direction = [&](Index v) {   // along its edge, away from v
      const auto& e = m_edges[edge_at[v]].vertices;
      return unit(sub(vec(m_points[e[0] == v ? e[1] : e[0]]), vec(m_points[v])));
    };
    struct Candidate { double d2; Index a, b; };
    std::vector<Candidate> cand;
    for(std::size_t i = 0; i < ends.size(); ++i) {
      const V p = vec(m_points[ends[i]]);
      for(std::size_t j = i + 1; j < ends.size(); ++j) {
        const V q = vec(m_points[ends[j]]);
        if(q[0] - p[0] > tol) break;
        const V pq = sub(q, p);
        const double d2 = dot(pq, pq);
        if(d2 > tol * tol || d2 == 0) continue;
        if(dot(direction(ends[i]), direction(ends[j])) > -cos_max) continue;   // not running on
        cand.push_back({d2, (std::min)(ends[i], ends[j]), (std::max)(ends[i], ends[j])});
      }
    }
    std::sort(cand.begin(), cand.end(), [](const Candidate& x, const Candidate& y) {
      return x.d2 != y.d2 ? x.d2 < y.d2 : x.a != y.a ? x.a < y.a : x.b < y.b;
    });
    std::vector<char> joined(m_points.size(), 0);
    std::size_t added = 0;
    for(const Candidate& c : cand) {
      if(joined[c.a] || joined[c.b]) continue;
      joined[c.a] = joined[c.b] = 1;
      m_edges.push_back({{c.a, c.b}, SEAM});
      if(judge) { edge_faces.push_back({{none, none}}); edge_consistent.push_back(0); }
      ++added;
    }
    if(added == 0) return;
    // sorted by vertices again, the judgement's per-edge data alike
    std::vector<Index> order(m_edges.size());
    for(Index e = 0; e < order.size(); ++e) order[e] = e;
    std::sort(order.begin(), order.end(), [&](Index x, Index y) { return m_edges[x].vertices < m_edges[y].vertices; });
    std::vector<Edge> edges;
    std::vector<std::array<Index, 2>> faces;
    std::vector<char> consistent;
    for(Index e : order) {
      edges.push_back(m_edges[e]);
      if(judge) { faces.push_back(edge_faces[e]); consistent.push_back(edge_consistent[e]); }
    }
    m_edges.swap(edges);
    if(judge) { edge_faces.swap(faces); edge_consistent.swap(consistent); }
    m_seam_bridges = added;
  }

  // leaves out the curves of sharp edges that are not sharp at `o.scale` or do not stand out by
  // `o.contrast` (see `Options::scale` and `Options::contrast`); with `soft`, the edges are the
  // soft creases (alone: their own curves), judged at the soft angle (`cos_limit`), by 3 x the
  // contrast, and their curves at least 4 x the scale long. Returns how many edges it left out.
  std::size_t judge_sharp_edges(const Surface_domain_3<GeomTraits>& d, const Options& o, double cos_max, double cos_limit, bool soft,
                      const std::vector<Index>& across, const std::vector<char>& same_way,
                      const std::vector<float>& slot_angle, const std::vector<std::array<Index, 2>>& edge_faces, const std::vector<char>& edge_consistent)
  {
    const auto& tris = d.triangle_indices();
    const Index none = Index(-1);
    const double r2 = o.scale * o.scale;
    std::vector<Index> seen(tris.size(), none);
    Index stamp = 0;
    std::vector<std::pair<Index, double>> queue;
    auto centroid = [&](Index f) {
      const V a = vec(m_points[tris[f][0]]), b = vec(m_points[tris[f][1]]), c = vec(m_points[tris[f][2]]);
      return V{{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3}};
    };
    auto near = [&](Index f, const V& m) {
      for(int k = 0; k < 3; ++k) {
        const V dp = sub(vec(m_points[tris[f][std::size_t(k)]]), m);
        if(dot(dp, dp) <= r2) return true;
      }
      const V dc = sub(centroid(f), m);
      return dot(dc, dc) <= r2;
    };
    // the direction, in face f's plane and across edge (p, q), that points into f
    auto inward = [&](Index f, const V& p, const V& q) {
      const V a = vec(m_points[tris[f][0]]), b = vec(m_points[tris[f][1]]), c = vec(m_points[tris[f][2]]);
      const V n = cross(sub(b, a), sub(c, a));
      V t = unit(cross(n, sub(q, p)));
      if(dot(t, sub(centroid(f), p)) < 0) for(double& x : t) x = -x;
      return t;
    };
    // the input faces within the scale of an edge's midpoint, reached across manifold edges
    // from its first face, split in two by the plane through the edge that bisects its two
    // faces; the area-weighted normals of the two sides (oriented as each side's edge face)
    const std::size_t max_faces = 4096;
    auto sides = [&](Index e, std::array<V, 2>& n) {
      const std::array<Index, 2>& fs = edge_faces[e];
      const V p = vec(m_points[m_edges[e].vertices[0]]), q = vec(m_points[m_edges[e].vertices[1]]);
      const V m = {{(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2}};
      const V t0 = inward(fs[0], p, q), t1 = inward(fs[1], p, q);
      V split = unit(sub(t0, t1));   // side 0 is where it points
      if(dot(split, split) == 0) split = t0;
      ++stamp;
      queue.clear();
      queue.push_back({fs[0], 1.0});
      seen[fs[0]] = stamp;
      n[0] = n[1] = V{{0, 0, 0}};
      double sign1 = edge_consistent[e] ? 1.0 : -1.0;   // the second face's orientation, as seen from the first
      for(std::size_t i = 0; i < queue.size() && i < max_faces; ++i) {
        const Index f = queue[i].first;
        const double sg = queue[i].second;
        const V a = vec(m_points[tris[f][0]]), b = vec(m_points[tris[f][1]]), c = vec(m_points[tris[f][2]]);
        const V w = cross(sub(b, a), sub(c, a));
        const int side = f == fs[0] ? 0 : f == fs[1] ? 1 : (dot(sub(centroid(f), m), split) >= 0 ? 0 : 1);
        const double s1 = side == 1 ? sg * sign1 : sg;   // side 1 oriented as the second face
        for(std::size_t k = 0; k < 3; ++k) n[std::size_t(side)][k] += s1 * w[k];
        for(std::size_t k = 0; k < 3; ++k) {
          const Index g = across[3 * f + k];
          if(g == none || seen[g] == stamp || !near(g, m)) continue;
          seen[g] = stamp;
          queue.push_back({g, same_way[3 * f + k] ? sg : -sg});
        }
      }
      if(seen[fs[1]] != stamp)   // not reached (a thin sliver): its own normal
        n[1] = cross(sub(vec(m_points[tris[fs[1]][1]]), vec(m_points[tris[fs[1]][0]])),
                     sub(vec(m_points[tris[fs[1]][2]]), vec(m_points[tris[fs[1]][0]])));
      n[0] = unit(n[0]);
      n[1] = unit(n[1]);
    };
    // the edge's angle against the mean angle of the non-sharp edges of the faces around it (for
    // a soft crease, 3 times as much against the edges below the soft angle: a faceted blend's
    // creases run side by side between flat facets)
    const double limit_angle = std::acos(cos_limit) * 180.0 / CGAL_PI;
    std::vector<Index> ring;
    auto stands_out = [&](Index e) {
      const std::array<Index, 2>& fs = edge_faces[e];
      ring.assign(fs.begin(), fs.end());
      for(Index f : fs)
        for(std::size_t k = 0; k < 3; ++k) if(across[3 * f + k] != none) ring.push_back(across[3 * f + k]);
      std::sort(ring.begin(), ring.end());
      ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      double sum = 0, own = 0;
      std::size_t n = 0;
      for(Index f : ring)
        for(std::size_t k = 0; k < 3; ++k) {
          const float a = slot_angle[3 * f + k];
          if(a < 0) continue;
          const Index g = across[3 * f + k];
          if((f == fs[0] && g == fs[1]) || (f == fs[1] && g == fs[0])) { own = a; continue; }
          if(a < limit_angle) { sum += a; ++n; }   // (each inner edge counts from both faces)
        }
      return n == 0 || (!soft && own >= 2 * limit_angle) || own >= (soft ? 3.0 : 1.0) * o.contrast * sum / double(n);
    };
    std::vector<char> kept(m_edges.size(), 1);
    m_corners.clear();
    m_curves.clear();
    chain(cos_max);
    auto edge_index = [&](Index u, Index v) {
      const std::uint64_t key = u < v ? (std::uint64_t(u) << 32 | v) : (std::uint64_t(v) << 32 | u);
      const auto it = std::lower_bound(m_edges.begin(), m_edges.end(), key, [](const Edge& x, std::uint64_t k) {
        return (std::uint64_t(x.vertices[0]) << 32 | x.vertices[1]) < k;
      });
      return Index(it - m_edges.begin());
    };
    for(const Curve& cv : m_curves) {
      const std::size_t nv = cv.vertices.size();
      std::vector<Index> es;
      for(std::size_t k = 0; k + 1 < nv + (cv.closed ? 1 : 0); ++k)
        es.push_back(edge_index(cv.vertices[k], cv.vertices[(k + 1) % nv]));
      bool only_sharp = !es.empty();
      for(Index e : es) only_sharp = only_sharp && (m_edges[e].kind == SHARP || m_edges[e].kind == SOFT || m_edges[e].kind == SEAM);
      if(!only_sharp) continue;
      double len = 0, sharp = 0;
      for(Index e : es) {
        if(m_edges[e].kind == SEAM) continue;   // (no faces: a hair across a crack)
        const V p = vec(m_points[m_edges[e].vertices[0]]), q = vec(m_points[m_edges[e].vertices[1]]);
        const double l = std::sqrt(dot(sub(q, p), sub(q, p)));
        len += l;
        if(o.scale > 0) {
          std::array<V, 2> n;
          sides(e, n);
          double c = dot(n[0], n[1]);
          if(d.is_two_sided(edge_faces[e][0]) || d.is_two_sided(edge_faces[e][1])) c = std::abs(c);
          else if(!edge_consistent[e]) c = -c;
          if(c > cos_limit) continue;
        }
        if(o.contrast > 0 && !stands_out(e)) continue;
        sharp += l;
      }
      if(sharp < 0.5 * len || (soft && len < 4 * o.scale))
        for(Index e : es) kept[e] = 0;
    }
    m_corners.clear();
    m_curves.clear();
    std::vector<Edge> cur;
    for(std::size_t e = 0; e < m_edges.size(); ++e)
      if(kept[e]) cur.push_back(m_edges[e]);
    const std::size_t left = m_edges.size() - cur.size();
    m_edges.swap(cur);
    return left;
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
    // the other end of edge e, or across a `SEAM` edge (a hair long, in any direction) the other
    // end of the curve's edge beyond it
    auto beyond = [&](Index e, Index v) {
      const Index w = other(e, v);
      if(m_edges[e].kind != SEAM) return w;
      const auto r = edges_at(w);
      for(auto it = r.first; it != r.second; ++it) if(it->second != e) return other(it->second, w);
      return w;
    };
    for(std::size_t i = 0; i < inc.size();) {
      std::size_t j = i;
      while(j < inc.size() && inc[j].first == inc[i].first) ++j;
      const Index v = inc[i].first;
      bool corner = (j - i) != 2;
      if(!corner) {   // a turn of at least the feature angle
        const V p = vec(m_points[v]);
        const V a = unit(sub(vec(m_points[beyond(inc[i].second, v)]), p));
        const V b = unit(sub(vec(m_points[beyond(inc[i + 1].second, v)]), p));
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
  std::size_t m_smooth_seam_edges = 0;
  std::size_t m_seam_bridges = 0;
  std::size_t m_hole_rim_edges = 0;
  std::size_t m_filled_rim_edges = 0;
  std::size_t m_smooth_edges = 0;
  std::size_t m_smooth_soft_edges = 0;
};

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_FEATURE_CURVES_3_H
