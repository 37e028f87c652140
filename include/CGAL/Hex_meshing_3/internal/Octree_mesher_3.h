// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_INTERNAL_OCTREE_MESHER_3_H
#define CGAL_HEX_MESHING_3_INTERNAL_OCTREE_MESHER_3_H

// The overlay grid: an initial Cartesian grid of n_x x n_y x n_z cells over the meshing box, each
// refined as an octree.
//
// Lattice addresses: a node at level l has integer coordinates (x, y, z) with x in [0, n_x 2^l);
// its children are at level l+1 with coordinates (2x + dx, 2y + dy, 2z + dz), stored contiguously
// at `child + octant`, octant = dx + 2 dy + 4 dz. Corner positions are functions of an integer key
// at a fixed finest level D: key k on axis a maps to lo_a (1 - t) + hi_a t, t = k / (n_a 2^D), so a
// corner shared by several cells gets bit-identical coordinates, and the box is honoured exactly.
//
// Per-axis levels are carried in the public `Cell_3` so that directional refinement fits the same
// address later; this mesher refines isotropically (1 -> 8).
//
// Pipeline: refine (criteria, level by level) -> balance (2:1 across faces and edges) ->
// classify (components of uncut cells; inside test or seed; trimming) -> extract (vertices, hexahedra,
// hanging nodes, boundary faces with patches).

#include <CGAL/Hex_mesh_criteria_3.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/Status.h>
#include <CGAL/Hex_meshing_3/internal/Boundary_capture_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal {


// Open-addressing hash map from 63-bit keys to 32-bit values (deterministic, no allocation per entry).
class Key_map
{
public:
  static constexpr std::uint64_t EMPTY = ~std::uint64_t(0);
  void reserve(std::size_t n)
  {
    std::size_t cap = 16;
    while(cap < 2 * n + 16) cap <<= 1;
    m_keys.assign(cap, EMPTY); m_values.assign(cap, 0); m_mask = cap - 1; m_size = 0;
  }
  // returns the value stored for `key`, inserting `value` if absent; `inserted` tells which
  std::uint32_t insert(std::uint64_t key, std::uint32_t value, bool& inserted)
  {
    if(2 * (m_size + 1) > m_keys.size()) grow();
    std::size_t h = hash(key) & m_mask;
    while(m_keys[h] != EMPTY) {
      if(m_keys[h] == key) { inserted = false; return m_values[h]; }
      h = (h + 1) & m_mask;
    }
    m_keys[h] = key; m_values[h] = value; ++m_size; inserted = true;
    return value;
  }
  bool find(std::uint64_t key, std::uint32_t& value) const
  {
    if(m_keys.empty()) return false;
    std::size_t h = hash(key) & m_mask;
    while(m_keys[h] != EMPTY) {
      if(m_keys[h] == key) { value = m_values[h]; return true; }
      h = (h + 1) & m_mask;
    }
    return false;
  }
private:
  static std::size_t hash(std::uint64_t k)
  {
    k ^= k >> 33; k *= 0xff51afd7ed558ccdULL; k ^= k >> 33; k *= 0xc4ceb9fe1a85ec53ULL; k ^= k >> 33;
    return std::size_t(k);
  }
  void grow()
  {
    std::vector<std::uint64_t> keys; std::vector<std::uint32_t> values;
    keys.swap(m_keys); values.swap(m_values);
    reserve(keys.size());
    bool ins;
    for(std::size_t i = 0; i < keys.size(); ++i) if(keys[i] != EMPTY) insert(keys[i], values[i], ins);
  }
  std::vector<std::uint64_t> m_keys;
  std::vector<std::uint32_t> m_values;
  std::size_t m_mask = 0, m_size = 0;
};

template <typename MeshDomain, typename Criteria>
class Octree_mesher_3
{
public:
  typedef typename MeshDomain::Geom_traits GT;
  typedef typename GT::FT                  FT;
  typedef typename GT::Point_3             Point_3;
  typedef Cell_3<GT>                       Cell;

  static constexpr std::uint32_t NONE = ~std::uint32_t(0);
  static constexpr int KEY_BITS = 21;

  struct Node
  {
    std::uint32_t x, y, z;
    std::uint32_t child = 0;     // first of 8 children; 0: leaf (no root is anyone's child)
    std::uint32_t list = 0;      // index into m_lists of the triangles meeting the cell; 0: none
    std::uint8_t level = 0;
    std::uint8_t flags = 0;
    bool is_leaf() const { return child == 0; }
  };
  enum Flags : std::uint8_t { CUT = 1, KEPT = 2, LEAK = 4, FEATURE = 8, LINE = 16 };

  /// statistics of the last run
  typedef Meshing_statistics Statistics;

  Octree_mesher_3(const MeshDomain& domain, const Criteria& criteria, const Bbox_3& box)
    : m_domain(domain), m_criteria(criteria), m_box(box)
  {}

  const Statistics& statistics() const { return m_stats; }
  /// frees the octree (its nodes, their triangle lists): after `run()`, only the statistics and
  /// the leaks are read (the body-fitted capture runs on the extracted mesh)
  void release()
  {
    std::vector<Node>().swap(m_nodes);
    std::vector<std::vector<std::uint32_t>>().swap(m_lists);
    std::vector<std::uint32_t>().swap(m_free_list);
    std::vector<std::vector<std::uint32_t>>().swap(m_by_level);
    std::vector<int>().swap(m_component);
  }
  /// leaks of the seeded region found by the last run, largest first
  const std::vector<Region_leak>& leaks() const { return m_leaks; }

  template <typename Visitor, typename HexMesh>
  Status run(HexMesh& out, std::size_t max_cells, const std::optional<Point_3>& seed, Visitor& visitor,
             double buffer_gap = 0)
  {
    out.clear();
    Status status = Status::SUCCESS;
    m_near_layers = buffer_gap > 0 ? 1 : 0;
    m_keep_plates = bool(seed) && buffer_gap > 0;
    init_box();                                     // throws Input_error on an unusable box/size
    if(seed) locate_seed(*seed);                    // throws before any work on a bad seed
    visitor.on_phase_begin("refine", std::size_t(m_n[0]) * m_n[1] * m_n[2]);
    init_grid();
    status = refine(max_cells, visitor);
    visitor.on_phase_end("refine");
    visitor.on_phase_begin("balance", leaf_count());
    balance();
    visitor.on_phase_end("balance");
    visitor.on_phase_begin("classify", leaf_count());
    classify(seed);
    visitor.on_phase_end("classify");
    if(buffer_gap > 0) {
      visitor.on_phase_begin("prepare", m_stats.kept_cells);
      prepare_staircase(seed, buffer_gap);
      visitor.on_phase_end("prepare");
    }
    visitor.on_phase_begin("extract", m_stats.kept_cells);
    extract(out);
    visitor.on_phase_end("extract");
    return status;
  }

  // ---------------------------------------------------------------------------------------------
  // grid set-up
  void init_box()
  {
    m_use_features = m_domain.has_feature_edges() && m_criteria.feature_size() > 0;
    m_curvature_size = CGAL::to_double(m_criteria.curvature_size());
    m_patch_sizes.clear();
    for(const auto& ps : m_criteria.patch_sizes()) m_patch_sizes.push_back({CGAL::to_double(ps.first), CGAL::to_double(ps.second)});
    m_min_patch_size = m_min_patch_fine = std::numeric_limits<double>::infinity();
    for(const auto& ps : m_patch_sizes) {
      if(ps.first > 0) m_min_patch_size = (std::min)(m_min_patch_size, ps.first);
      if(ps.second > 0) m_min_patch_fine = (std::min)(m_min_patch_fine, ps.second);
    }
    m_min_patch_size = (std::min)(m_min_patch_size, m_min_patch_fine);
    m_thin_cells = m_criteria.thin_part_cells();
    m_thin_min_size = CGAL::to_double(m_criteria.thin_part_min_size());
    m_use_lines = m_use_features && !m_domain.feature_segments().empty();
    const FT size = m_criteria.initial_size();
    if(!(size > 0) || !std::isfinite(CGAL::to_double(size)))
      throw Input_error("the cell size must be a positive number", Input_error_cause::BAD_PARAMETER);
    m_D = m_criteria.max_level();
    if(m_D < 0 || m_D > 20) throw Input_error("the maximum level must be in [0, 20]", Input_error_cause::BAD_PARAMETER);
    for(int a = 0; a < 3; ++a) {
      m_lo[a] = m_box.min(a); m_hi[a] = m_box.max(a);
      const double L = m_hi[a] - m_lo[a];
      if(!(L > 0) || !std::isfinite(L)) throw Input_error("the meshing box is empty or not finite", Input_error_cause::BAD_PARAMETER);
      const double n = std::ceil(L / CGAL::to_double(size) * (1 - 1e-12));
      if(n > double(1u << 20)) throw Input_error("the cell size is too small for the box (more than 2^20 cells per axis)", Input_error_cause::BAD_PARAMETER);
      m_n[a] = std::uint32_t((std::max)(1.0, n));
    }
    // coordinates at the finest level must fit in KEY_BITS bits (with one spare for neighbours)
    while(m_D > 0 && (std::uint64_t((std::max)({m_n[0], m_n[1], m_n[2]})) << m_D) >= (std::uint64_t(1) << KEY_BITS))
      --m_D;
    m_stats = Statistics();
    m_stats.initial_cells = m_n;
  }

  void init_grid()
  {
    const std::size_t roots = std::size_t(m_n[0]) * m_n[1] * m_n[2];
    if(roots > 200000000u) throw Input_error("the initial grid would have more than 2e8 cells; increase the cell size", Input_error_cause::BAD_PARAMETER);
    m_nodes.clear(); m_nodes.resize(roots);
    m_lists.clear(); m_lists.emplace_back();   // slot 0 = no list
    m_by_level.assign(m_D + 2, {});
    m_by_level[0].reserve(roots);
    for(std::uint32_t z = 0; z < m_n[2]; ++z)
      for(std::uint32_t y = 0; y < m_n[1]; ++y)
        for(std::uint32_t x = 0; x < m_n[0]; ++x) {
          const std::uint32_t id = root_index(x, y, z);
          Node& nd = m_nodes[id];
          nd.x = x; nd.y = y; nd.z = z; nd.level = 0;
          m_by_level[0].push_back(id);
        }
    // distribute the triangles to the root cells they meet (exact test)
    const double h[3] = {(m_hi[0]-m_lo[0]) / m_n[0], (m_hi[1]-m_lo[1]) / m_n[1], (m_hi[2]-m_lo[2]) / m_n[2]};
    for(std::size_t t = 0; t < m_domain.number_of_triangles(); ++t) {
      const Bbox_3 tb = m_domain.triangle_bbox(t);
      std::int64_t r0[3], r1[3];
      bool outside = false;
      for(int a = 0; a < 3; ++a) {
        // candidate cells, widened by 1e-6 cell for round-off; the exact test decides. Clamped
        // as doubles first: huge coordinates must not overflow the integer conversion.
        const double u0 = std::floor((tb.min(a) - m_lo[a]) / h[a] - 1e-6);
        const double u1 = std::floor((tb.max(a) - m_lo[a]) / h[a] + 1e-6);
        r0[a] = std::int64_t((std::min)((std::max)(u0, 0.0), double(m_n[a])));
        r1[a] = std::int64_t((std::min)((std::max)(u1, -1.0), double(m_n[a]) - 1));
        if(r0[a] > r1[a]) outside = true;
      }
      if(outside) continue;
      for(std::int64_t z = r0[2]; z <= r1[2]; ++z)
        for(std::int64_t y = r0[1]; y <= r1[1]; ++y)
          for(std::int64_t x = r0[0]; x <= r1[0]; ++x) {
            const std::uint32_t id = root_index(std::uint32_t(x), std::uint32_t(y), std::uint32_t(z));
            if(CGAL::do_overlap(node_bbox(m_nodes[id]), tb)) {
              Node& nd = m_nodes[id];
              if(nd.list == 0) { nd.list = std::uint32_t(m_lists.size()); m_lists.emplace_back(); }
              m_lists[nd.list].push_back(std::uint32_t(t));
            }
          }
    }
    for(std::uint32_t id = 0; id < roots; ++id) decide_cut(id);
    if(m_use_lines)   // user feature lines may lie anywhere, cut cells or not
      for(std::uint32_t id = 0; id < roots; ++id)
        if(m_domain.do_intersect_feature_lines(node_bbox(m_nodes[id]))) m_nodes[id].flags |= LINE | FEATURE;
    m_leaves = roots;
  }

  // Candidate lists hold the triangles whose bounding boxes overlap the cell's (a superset of the
  // triangles meeting it, cheap to pass down to children); whether the cell is cut is decided by
  // the exact test, stopping at the first triangle that meets it. Uncut cells drop their list:
  // their children cannot be cut.
  void decide_cut(std::uint32_t id)
  {
    Node& nd = m_nodes[id];
    if(nd.list == 0) return;
    const Bbox_3 b = node_bbox(nd);
    std::vector<std::uint32_t>& l = m_lists[nd.list];
    for(std::size_t i = 0; i < l.size(); ++i)
      if(m_domain.do_intersect(b, l[i])) {
        std::swap(l[0], l[i]);   // the first hit is tested first in the children (likely to hit again)
        nd.flags |= CUT;
        if(m_use_features)   // a cell meets a feature edge only if it meets a triangle of it
          for(std::uint32_t t : l)
            if(m_domain.do_intersect_feature(b, t)) { nd.flags |= FEATURE; break; }
        return;
      }
    l.clear();
    m_free_list.push_back(nd.list);
    nd.list = 0;
  }

  std::size_t leaf_count() const { return m_leaves; }

  // ---------------------------------------------------------------------------------------------
  // geometry of lattice keys
  double coord(int a, std::uint64_t key, int level) const
  {
    const double t = double(key) / double(std::uint64_t(m_n[a]) << level);
    if(key == 0) return m_lo[a];
    if(key == (std::uint64_t(m_n[a]) << level)) return m_hi[a];
    return m_lo[a] * (1 - t) + m_hi[a] * t;
  }
  // positions depend on the key scaled to the finest level D only
  double coord_at(int a, std::uint64_t key, int level) const { return coord(a, key << (m_D - level), m_D); }

  Bbox_3 node_bbox(const Node& nd) const
  {
    const std::uint32_t c[3] = {nd.x, nd.y, nd.z};
    return Bbox_3(coord_at(0, c[0], nd.level), coord_at(1, c[1], nd.level), coord_at(2, c[2], nd.level),
                  coord_at(0, c[0] + 1, nd.level), coord_at(1, c[1] + 1, nd.level), coord_at(2, c[2] + 1, nd.level));
  }

  Cell make_cell(const Node& nd) const
  {
    Cell c;
    c.index = {{nd.x, nd.y, nd.z}};
    c.level = {{nd.level, nd.level, nd.level}};
    const std::uint32_t v[3] = {nd.x, nd.y, nd.z};
    double lo[3], hi[3];
    for(int a = 0; a < 3; ++a) { lo[a] = coord_at(a, v[a], nd.level); hi[a] = coord_at(a, v[a] + 1, nd.level); }
    for(int k = 0; k < 8; ++k)
      c.corners[k] = Point_3(hex_corner_offsets()[k][0] ? hi[0] : lo[0], hex_corner_offsets()[k][1] ? hi[1] : lo[1],
                             hex_corner_offsets()[k][2] ? hi[2] : lo[2]);
    c.is_cut = (nd.flags & CUT) != 0;
    c.meets_feature = (nd.flags & FEATURE) != 0;
    return c;
  }

  // what the curvature and thin-part criteria need of a cut cell larger than their sizes (the
  // refinement asks; other uses of `make_cell()` do not pay for it)
  void measure(const Node& nd, Cell& c) const
  {
    if(!c.is_cut || nd.list == 0 || (m_curvature_size <= 0 && m_thin_cells <= 0 && m_patch_sizes.empty())) return;
    const Bbox_3 b = node_bbox(nd);
    const double h = (std::max)({b.xmax() - b.xmin(), b.ymax() - b.ymin(), b.zmax() - b.zmin()});
    const bool spread = (m_curvature_size > 0 && h > m_curvature_size * (1 + 1e-9)) || h > m_min_patch_fine * (1 + 1e-9);
    const bool thin = m_thin_cells > 0 && h > m_thin_min_size * (1 + 1e-9);
    const bool patch = h > m_min_patch_size * (1 + 1e-9);
    if(!spread && !thin && !patch) return;
    // the triangles meeting the cell (exact test) and their unit normals, in list order, once
    std::vector<std::pair<std::uint32_t, Vec3>> meets;
    for(std::uint32_t t : m_lists[nd.list]) {
      Vec3 u;
      if(m_domain.do_intersect(b, t) && unit_normal(t, u)) meets.push_back({t, u});
    }
    if(spread) c.normal_spread = normal_spread(meets);
    if(thin) c.thickness = thickness(b, meets);
    if(patch)
      for(const auto& mt : meets)
        for(const int p : {m_domain.patch(mt.first), m_domain.back_patch(mt.first)}) {   // a sheet: both sides
          if(p < 0 || std::size_t(p) >= m_patch_sizes.size()) continue;
          const auto& ps = m_patch_sizes[std::size_t(p)];
          if(ps.first > 0) c.patch_size = (std::min)(c.patch_size, ps.first);
          if(ps.second > 0) c.patch_curvature_size = (std::min)(c.patch_curvature_size, ps.second);
        }
  }

  // the unit normal of triangle t (false if it is degenerate in double precision)
  bool unit_normal(std::size_t t, Vec3& n) const
  {
    const auto& tr = m_domain.triangle(t);
    const Vec3 a = vec(tr[0]);
    n = cross(sub(vec(tr[1]), a), sub(vec(tr[2]), a));
    const double l = norm(n);
    if(!(l > 0)) return false;
    n = mul(n, 1.0 / l);
    return true;
  }

  // An estimate of the largest angle (degrees) between the unit normals of the triangles meeting
  // the cell (exact test): the largest angle to the first normal, then to the normal farthest
  // from it; by the triangle inequality on the sphere, at least half the true largest angle and
  // never more.
  static double normal_spread(const std::vector<std::pair<std::uint32_t, Vec3>>& n)
  {
    if(n.size() < 2) return 0;
    double worst = 1;
    std::size_t far = 0;
    for(int pass = 0; pass < 2; ++pass) {
      const Vec3 r = n[far].second;
      for(std::size_t i = 0; i < n.size(); ++i) {
        const double c = dot(r, n[i].second);
        if(c < worst) { worst = c; far = i; }
      }
    }
    return std::acos((std::max)(-1.0, (std::min)(1.0, worst))) * 180.0 / CGAL_PI;
  }

  // The shortest distance, along the normals of (at most 4 of) the triangles meeting the cell,
  // both ways, to an opposite-facing part of the surface (normals more than 120 degrees apart):
  // the thickness of a plate or the width of a gap there. Each ray starts from the triangle's
  // point closest to the cell's centre, pulled 1 % towards the triangle's centroid (strictly
  // inside it), a hair off the triangle; hits on parts that do not face it (a side wall) are
  // passed through, up to 8 of them.
  double thickness(const Bbox_3& b, const std::vector<std::pair<std::uint32_t, Vec3>>& meets) const
  {
    const double inf = std::numeric_limits<double>::infinity();
    const Vec3 centre = {{0.5 * (b.xmin() + b.xmax()), 0.5 * (b.ymin() + b.ymax()), 0.5 * (b.zmin() + b.zmax())}};
    const double h = (std::max)({b.xmax() - b.xmin(), b.ymax() - b.ymin(), b.zmax() - b.zmin()});
    const double eps = 1e-7 * h;
    double best = inf;
    for(std::size_t i = 0; i < meets.size() && i < 4; ++i) {
      const std::uint32_t t = meets[i].first;
      const Vec3& n = meets[i].second;
      const auto& tr = m_domain.triangle(t);
      const Vec3 g = mul(add(add(vec(tr[0]), vec(tr[1])), vec(tr[2])), 1.0 / 3);
      const Vec3 q = vec(GT().construct_projected_point_3_object()(tr, Point_3(centre[0], centre[1], centre[2])));
      const Vec3 o = add(q, mul(sub(g, q), 0.01));
      for(double side : {-1.0, 1.0}) {
        const Vec3 dir = mul(n, side);
        Vec3 from = add(o, mul(dir, eps));
        for(int k = 0; k < 8; ++k) {
          Point_3 hit;
          std::size_t ht = 0;
          if(!m_domain.first_ray_hit(Point_3(from[0], from[1], from[2]), typename GT::Vector_3(dir[0], dir[1], dir[2]), hit, &ht))
            break;
          const Vec3 x = vec(hit);
          const double dist = dot(sub(x, o), dir);
          if(dist >= best) break;
          Vec3 m;
          if(ht != t && dist > 2 * eps && unit_normal(ht, m) && dot(n, m) < -0.5) { best = dist; break; }
          from = add(x, mul(dir, eps));   // not facing this triangle: go on past it
        }
      }
    }
    return best;
  }

  std::uint32_t root_index(std::uint32_t x, std::uint32_t y, std::uint32_t z) const
  {
    return x + m_n[0] * (y + m_n[1] * z);
  }

  // the deepest node of level <= l containing lattice cell (l, x, y, z); NONE outside the grid
  std::uint32_t find(int l, std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    if(x < 0 || y < 0 || z < 0) return NONE;
    const std::int64_t rx = x >> l, ry = y >> l, rz = z >> l;
    if(rx >= m_n[0] || ry >= m_n[1] || rz >= m_n[2]) return NONE;
    std::uint32_t id = root_index(std::uint32_t(rx), std::uint32_t(ry), std::uint32_t(rz));
    int lev = 0;
    while(m_nodes[id].child != 0 && lev < l) {
      ++lev;
      const int s = l - lev;
      const std::uint32_t oct = std::uint32_t(((x >> s) & 1) | (((y >> s) & 1) << 1) | (((z >> s) & 1) << 2));
      id = m_nodes[id].child + oct;
    }
    return id;
  }

  // ---------------------------------------------------------------------------------------------
  // refinement
  void split(std::uint32_t id)
  {
    const std::uint32_t first = std::uint32_t(m_nodes.size());
    if(m_nodes.size() + 8 >= std::size_t(NONE)) throw Input_error("too many cells (more than 4e9 nodes)", Input_error_cause::BAD_PARAMETER);
    const Node parent = m_nodes[id];
    m_nodes[id].child = first;
    m_nodes.resize(m_nodes.size() + 8);
    const int l = parent.level + 1;
    for(int o = 0; o < 8; ++o) {
      Node& c = m_nodes[first + o];
      c.x = 2 * parent.x + (o & 1); c.y = 2 * parent.y + ((o >> 1) & 1); c.z = 2 * parent.z + ((o >> 2) & 1);
      c.level = std::uint8_t(l);
      m_by_level[l].push_back(first + o);
    }
    m_leaves += 7;
    if(parent.list != 0) {
      std::vector<std::uint32_t> tris;
      tris.swap(m_lists[parent.list]);
      m_nodes[id].list = 0;
      Bbox_3 cb[8];
      for(int o = 0; o < 8; ++o) cb[o] = node_bbox(m_nodes[first + o]);
      m_free_list.push_back(parent.list);
      for(std::uint32_t t : tris) {
        const Bbox_3 tb = m_domain.triangle_bbox(t);
        for(int o = 0; o < 8; ++o) {
          if(!CGAL::do_overlap(cb[o], tb)) continue;
          Node& c = m_nodes[first + o];
          if(c.list == 0) {
            if(m_free_list.empty()) { c.list = std::uint32_t(m_lists.size()); m_lists.emplace_back(); }
            else { c.list = m_free_list.back(); m_free_list.pop_back(); }
          }
          m_lists[c.list].push_back(t);
        }
      }
      for(int o = 0; o < 8; ++o) decide_cut(first + o);
    }
    if(parent.flags & LINE)   // only the children of a cell meeting a user line can meet it
      for(int o = 0; o < 8; ++o)
        if(m_domain.do_intersect_feature_lines(node_bbox(m_nodes[first + o]))) m_nodes[first + o].flags |= LINE | FEATURE;
  }

  template <typename Visitor>
  Status refine(std::size_t max_cells, Visitor& visitor)
  {
    const int max_level = (std::min)(m_criteria.max_level(), m_D);
    for(int l = 0; l < max_level; ++l) {
      std::vector<std::uint32_t> bad;
      const std::vector<std::uint32_t>& nodes = m_by_level[l];
      for(std::size_t i = 0; i < nodes.size(); ++i) {
        const Node& nd = m_nodes[nodes[i]];
        if(!nd.is_leaf()) continue;
        Cell c = make_cell(nd);
        measure(nd, c);
        if(m_criteria(c)) bad.push_back(nodes[i]);
        if((i & 0xFFFF) == 0xFFFF && !visitor.go_further(double(l) / max_level)) return Status::CANCELED;
      }
      if(bad.empty()) break;
      if(m_near_layers > 0) add_near_cells(l, bad);
      if(m_leaves + 7 * bad.size() > max_cells) return Status::CELL_LIMIT_REACHED;
      for(std::size_t i = 0; i < bad.size(); ++i) {
        split(bad[i]);
        if((i & 0x3FFF) == 0x3FFF && !visitor.go_further((l + double(i) / bad.size()) / max_level))
          return Status::CANCELED;
      }
      if(!visitor.go_further(double(l + 1) / max_level)) return Status::CANCELED;
    }
    return Status::SUCCESS;
  }

  // Surface layers: when a cut cell of level l is split, the leaves of level l within
  // `m_near_layers` cells of it are split too, so that the cells next to the surface (where the
  // buffer layer starts) have the size asked for the surface, not the balance's coarser sizes.
  void add_near_cells(int l, std::vector<std::uint32_t>& bad)
  {
    std::vector<char> mark(m_nodes.size(), 0);
    for(std::uint32_t id : bad) mark[id] = 1;
    const std::size_t n = bad.size();
    const int r = m_near_layers;
    for(std::size_t i = 0; i < n; ++i) {
      const Node nd = m_nodes[bad[i]];
      if(!(nd.flags & CUT)) continue;
      for(int dz = -r; dz <= r; ++dz)
        for(int dy = -r; dy <= r; ++dy)
          for(int dx = -r; dx <= r; ++dx) {
            const std::uint32_t j = find(l, std::int64_t(nd.x) + dx, std::int64_t(nd.y) + dy, std::int64_t(nd.z) + dz);
            if(j == NONE || mark[j] || !m_nodes[j].is_leaf() || m_nodes[j].level != l) continue;
            mark[j] = 1;
            bad.push_back(j);
          }
    }
    std::sort(bad.begin(), bad.end());
  }

  // 2:1 balance across every face and edge: processing levels from the finest down, a leaf at
  // level l forces the leaves containing its face and edge neighbours to level >= l-1. Splits
  // only create leaves of levels < l, which are visited later in the same sweep.
  //
  // With n = `cells_between_levels()` >= 2 the rule is wider: the leaves containing the lattice
  // cells of level l-1 within n cells (in each axis) of a leaf's parent are split to level >= l-1,
  // so every region of level l has at least n cells of level l-1 around it before level l-2
  // (which implies the 2:1 balance across faces and edges).
  void balance()
  {
    int top = 0;
    for(int l = 0; l < int(m_by_level.size()); ++l) if(!m_by_level[l].empty()) top = l;
    const int n = m_criteria.cells_between_levels();
    if(n >= 2) {
      for(int l = top; l >= 2; --l) {
        std::vector<std::uint64_t> parents;   // the parents of the leaves of level l, once
        for(std::uint32_t id : m_by_level[l]) {
          const Node& nd = m_nodes[id];
          if(nd.is_leaf())
            parents.push_back(pack(nd.x >> 1, nd.y >> 1, nd.z >> 1));
        }
        std::sort(parents.begin(), parents.end());
        parents.erase(std::unique(parents.begin(), parents.end()), parents.end());
        const std::uint64_t mask = (std::uint64_t(1) << KEY_BITS) - 1;
        for(std::uint64_t k : parents) {
          const std::int64_t px = std::int64_t(k & mask), py = std::int64_t((k >> KEY_BITS) & mask), pz = std::int64_t(k >> (2 * KEY_BITS));
          for(int dz = -n; dz <= n; ++dz)
            for(int dy = -n; dy <= n; ++dy)
              for(int dx = -n; dx <= n; ++dx)
                for(;;) {
                  const std::uint32_t j = find(l - 1, px + dx, py + dy, pz + dz);
                  if(j == NONE || !m_nodes[j].is_leaf() || m_nodes[j].level >= l - 1) break;
                  split(j);
                  ++m_stats.balance_splits;
                }
        }
      }
      return;
    }
    for(int l = top; l >= 2; --l) {
      for(std::size_t i = 0; i < m_by_level[l].size(); ++i) {
        const Node nd = m_nodes[m_by_level[l][i]];
        if(!nd.is_leaf()) continue;
        for(int dz = -1; dz <= 1; ++dz)
          for(int dy = -1; dy <= 1; ++dy)
            for(int dx = -1; dx <= 1; ++dx) {
              const int nz = (dx != 0) + (dy != 0) + (dz != 0);
              if(nz == 0 || nz == 3) continue;   // faces and edges only
              for(;;) {
                const std::uint32_t j = find(l, std::int64_t(nd.x) + dx, std::int64_t(nd.y) + dy, std::int64_t(nd.z) + dz);
                if(j == NONE || !m_nodes[j].is_leaf() || m_nodes[j].level >= l - 1) break;
                split(j);
                ++m_stats.balance_splits;
              }
            }
      }
    }
  }

  // ---------------------------------------------------------------------------------------------
  // face neighbours: the leaves across face f (axis f/2, side f%2) of leaf `id`
  template <typename F>
  void for_each_face_neighbour(std::uint32_t id, int f, F&& fn) const
  {
    const Node& nd = m_nodes[id];
    const int a = f / 2, side = f % 2;
    std::int64_t c[3] = {nd.x, nd.y, nd.z};
    c[a] += side ? 1 : -1;
    const std::uint32_t j = find(nd.level, c[0], c[1], c[2]);
    if(j == NONE) return;
    collect_face_leaves(j, a, side ? 0 : 1, fn);
  }
  template <typename F>
  void collect_face_leaves(std::uint32_t j, int a, int offset, F& fn) const
  {
    const Node& nd = m_nodes[j];
    if(nd.is_leaf()) { fn(j); return; }
    for(int o = 0; o < 8; ++o)
      if(((o >> a) & 1) == offset) collect_face_leaves(nd.child + o, a, offset, fn);
  }

  void locate_seed(const Point_3& p)
  {
    const double s[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    for(int a = 0; a < 3; ++a)
      if(!(s[a] > m_lo[a] && s[a] < m_hi[a])) {
        std::ostringstream os;
        os << "the region seed (" << s[0] << ", " << s[1] << ", " << s[2] << ") is outside the meshing box ("
           << m_lo[0] << ", " << m_lo[1] << ", " << m_lo[2] << ") - (" << m_hi[0] << ", " << m_hi[1] << ", " << m_hi[2] << ")";
        throw Input_error(os.str(), Input_error_cause::BAD_SEED);
      }
    if(m_domain.is_inside(p)) {
      std::ostringstream os;
      os << "the region seed (" << s[0] << ", " << s[1] << ", " << s[2] << ") is inside a body of the surface; "
         << "it must lie in the region to mesh (the fluid around the bodies)";
      throw Input_error(os.str(), Input_error_cause::BAD_SEED);
    }
  }

  std::uint32_t leaf_containing(const Point_3& p) const
  {
    const double s[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    std::int64_t k[3];
    for(int a = 0; a < 3; ++a) {
      const double K = double(std::uint64_t(m_n[a]) << m_D);
      k[a] = std::int64_t(std::floor((s[a] - m_lo[a]) / (m_hi[a] - m_lo[a]) * K));
      k[a] = (std::min<std::int64_t>)((std::max<std::int64_t>)(k[a], 0), std::int64_t(K) - 1);
    }
    return find(m_D, k[0], k[1], k[2]);
  }

  // ---------------------------------------------------------------------------------------------
  // classification: components of uncut leaves (face adjacency), then the region
  void classify(const std::optional<Point_3>& seed)
  {
    m_component.assign(m_nodes.size(), -1);
    std::vector<std::uint32_t> first_of_component;
    std::vector<std::uint32_t> queue;
    for(std::uint32_t id = 0; id < m_nodes.size(); ++id) {
      const Node& nd = m_nodes[id];
      if(!nd.is_leaf()) continue;
      ++m_stats.leaves;
      if(nd.flags & CUT) { ++m_stats.cut_leaves; continue; }
      if(m_component[id] >= 0) continue;
      const int comp = int(first_of_component.size());
      first_of_component.push_back(id);
      m_component[id] = comp;
      queue.clear(); queue.push_back(id);
      for(std::size_t q = 0; q < queue.size(); ++q) {
        const std::uint32_t cur = queue[q];
        for(int f = 0; f < 6; ++f)
          for_each_face_neighbour(cur, f, [&](std::uint32_t j) {
            if(m_component[j] < 0 && !(m_nodes[j].flags & CUT)) { m_component[j] = comp; queue.push_back(j); }
          });
      }
    }
    m_stats.components = first_of_component.size();
    for(const Node& nd : m_nodes) if(nd.is_leaf()) m_stats.max_level_reached = (std::max)(m_stats.max_level_reached, int(nd.level));

    if(seed) {
      const std::uint32_t s = leaf_containing(*seed);
      if(m_nodes[s].flags & CUT) {
        const double h = CGAL::to_double(make_cell(m_nodes[s]).size());
        std::ostringstream os;
        os << "the region seed (" << CGAL::to_double(seed->x()) << ", " << CGAL::to_double(seed->y()) << ", "
           << CGAL::to_double(seed->z()) << ") lies in a cell cut by the surface; move it farther than " << h
           << " from the surface";
        throw Input_error(os.str(), Input_error_cause::BAD_SEED);
      }
      const int comp = m_component[s];
      for(std::uint32_t id = 0; id < m_nodes.size(); ++id)
        if(m_nodes[id].is_leaf() && m_component[id] == comp) m_nodes[id].flags |= KEPT;
      // open or inconsistent surfaces: the flood may have leaked through a hole into a body
      if(!m_domain.has_exact_inside_test()) find_leaks(s);
    } else if(m_domain.has_exact_inside_test()) {
      // closed input: a component of uncut cells lies on one side, one exact test decides it
      std::vector<char> inside(first_of_component.size());
      for(std::size_t c = 0; c < first_of_component.size(); ++c)
        inside[c] = m_domain.is_inside(make_cell(m_nodes[first_of_component[c]]).center());
      for(std::uint32_t id = 0; id < m_nodes.size(); ++id)
        if(m_nodes[id].is_leaf() && m_component[id] >= 0 && inside[m_component[id]]) m_nodes[id].flags |= KEPT;
    } else {
      for(std::uint32_t id = 0; id < m_nodes.size(); ++id)
        if(m_nodes[id].is_leaf() && m_component[id] >= 0 &&
           m_domain.winding_number(make_cell(m_nodes[id]).center()) >= 0.5)
          m_nodes[id].flags |= KEPT;
    }
    trim();
    if(seed) keep_seed_component(leaf_containing(*seed));
    for(const Node& nd : m_nodes) if(nd.is_leaf() && (nd.flags & KEPT)) ++m_stats.kept_cells;
  }

  // Room for a buffer layer: the cells of `staircase_cells_to_remove()` (too close to the surface,
  // or at a non-manifold vertex of the staircase) are removed, then trimming again, until none is
  // left. Each round extracts the staircase (cheap next to the rest).
  void prepare_staircase(const std::optional<Point_3>& seed, double gap)
  {
    const std::uint32_t seed_cell = seed ? leaf_containing(*seed) : NONE;
    for(int round = 0; round < 64; ++round) {
      Hex_mesh_3<GT> tmp;
      extract(tmp);
      std::size_t close = 0, nm = 0;
      std::vector<std::uint32_t> nm_vertices;
      const std::vector<std::uint32_t> bad = staircase_cells_to_remove(tmp, m_domain, gap, &close, &nm, &nm_vertices);
      m_stats.too_close_vertices += close;
      m_stats.non_manifold_vertices += nm;
      if(bad.empty() && nm_vertices.empty()) break;
      std::vector<std::uint32_t> kept;   // mesh cell i = the i-th kept leaf in node order
      for(std::uint32_t id = 0; id < m_nodes.size(); ++id)
        if(m_nodes[id].is_leaf() && (m_nodes[id].flags & KEPT)) kept.push_back(id);
      // which blocks were octant cases as extracted (removals below may repair a block first)
      std::vector<char> octant_case(nm_vertices.size());
      for(std::size_t i = 0; i < nm_vertices.size(); ++i) octant_case[i] = !well_composed(tmp.points[nm_vertices[i]]);
      for(std::uint32_t c : bad) m_nodes[kept[c]].flags &= std::uint8_t(~KEPT);
      m_stats.staircase_removed_cells += bad.size();
      for(std::size_t i = 0; i < nm_vertices.size(); ++i)
        m_stats.staircase_removed_cells += make_vertex_manifold(tmp.points[nm_vertices[i]], octant_case[i] != 0);
      trim();
      if(seed) keep_seed_component(seed_cell);
      m_stats.kept_cells = 0;
      for(const Node& nd : m_nodes) if(nd.is_leaf() && (nd.flags & KEPT)) ++m_stats.kept_cells;
      if(m_stats.kept_cells == 0) break;
    }
  }

  // the leaves holding the 8 octants around the grid point `p` (NONE outside the box)
  void octant_leaves(const Point_3& p, std::array<std::uint32_t, 8>& leaf) const
  {
    std::int64_t key[3];
    for(int a = 0; a < 3; ++a) {
      const double K = double(std::uint64_t(m_n[a]) << m_D);
      key[a] = std::llround((CGAL::to_double(p[a]) - m_lo[a]) / (m_hi[a] - m_lo[a]) * K);
    }
    for(int o = 0; o < 8; ++o)
      leaf[o] = find(m_D, key[0] - 1 + (o & 1), key[1] - 1 + ((o >> 1) & 1), key[2] - 1 + ((o >> 2) & 1));
  }

  // whether a set of octants (bit o: octant o) is face-connected
  static bool octants_connected(unsigned set)
  {
    if(set == 0) return true;
    unsigned reached = set & (~set + 1), grow = reached;   // from the lowest octant
    while(grow) {
      unsigned next = 0;
      for(int o = 0; o < 8; ++o)
        if((grow >> o) & 1) next |= (1u << (o ^ 1)) | (1u << (o ^ 2)) | (1u << (o ^ 4));
      next &= set & ~reached;
      reached |= next;
      grow = next;
    }
    return reached == set;
  }
  // whether the kept octants `set` and the others are each face-connected
  static bool well_composed(unsigned set) { return octants_connected(set) && octants_connected(~set & 0xffu); }
  // ... around the grid point `p`
  bool well_composed(const Point_3& p) const
  {
    std::array<std::uint32_t, 8> leaf;
    octant_leaves(p, leaf);
    unsigned set = 0;
    for(int o = 0; o < 8; ++o) if(leaf[o] != NONE && (m_nodes[leaf[o]].flags & KEPT)) set |= 1u << o;
    return well_composed(set);
  }

  // The kept cells around a grid vertex where the staircase is not manifold: the 8 octants
  // around it (each in one leaf, a coarse leaf may hold several) must form, kept and not kept, two
  // face-connected sets (a well-composed 2x2x2 block; the staircase is then a disk there). The
  // fewest kept leaves whose removal does it go, those nearest to the surface first, so the
  // staircase does not retreat into the part (removing every cell at the vertex, then at the new
  // ones, dug notches two or three cells deep). A block that an earlier removal of the round made
  // well-composed is left alone if it was not so as extracted (`octant_case`); one that was
  // (the polygons' test found another fault) loses all its kept leaves, the former rule.
  // Returns the number of leaves removed.
  std::size_t make_vertex_manifold(const Point_3& p, bool octant_case)
  {
    std::array<std::uint32_t, 8> leaf;
    octant_leaves(p, leaf);
    std::vector<std::uint32_t> cand;   // the kept leaves around the vertex, in octant order
    for(int o = 0; o < 8; ++o)
      if(leaf[o] != NONE && (m_nodes[leaf[o]].flags & KEPT) && std::find(cand.begin(), cand.end(), leaf[o]) == cand.end())
        cand.push_back(leaf[o]);
    auto octants = [&](unsigned removed) {   // the kept octants once the leaves in `removed` go
      unsigned set = 0;
      for(int o = 0; o < 8; ++o)
        for(std::size_t i = 0; i < cand.size(); ++i)
          if(leaf[o] == cand[i] && !((removed >> i) & 1)) set |= 1u << o;
      return set;
    };
    const unsigned all = (1u << cand.size()) - 1;
    unsigned best = all;   // well-composed now: repaired earlier this round, or the former rule
    if(well_composed(octants(0))) {
      if(octant_case) return 0;
    } else {
      std::vector<double> dist(cand.size());
      for(std::size_t i = 0; i < cand.size(); ++i)
        dist[i] = std::sqrt(CGAL::to_double(m_domain.squared_distance(make_cell(m_nodes[cand[i]]).center())));
      int best_count = int(cand.size()) + 1;
      double best_dist = 0;
      for(unsigned r = 1; r <= all; ++r) {
        if(!well_composed(octants(r))) continue;
        int count = 0;
        double d = 0;
        for(std::size_t i = 0; i < cand.size(); ++i) if((r >> i) & 1) { ++count; d += dist[i]; }
        if(count < best_count || (count == best_count && d < best_dist)) { best = r; best_count = count; best_dist = d; }
      }
    }
    std::size_t removed = 0;
    for(std::size_t i = 0; i < cand.size(); ++i)
      if((best >> i) & 1) { m_nodes[cand[i]].flags &= std::uint8_t(~KEPT); ++removed; }
    return removed;
  }

  // A seeded region is one connected region: trimming can cut pockets off it (behind a passage
  // one cell thick); they are removed. The flood starts at the seed's cell, or, if trimming removed
  // it, at the nearest kept cell of the seed's component.
  void keep_seed_component(std::uint32_t seed_cell)
  {
    std::vector<char> seen(m_nodes.size(), 0);
    std::vector<std::uint32_t> queue{seed_cell};
    seen[seed_cell] = 1;
    std::uint32_t start = NONE;
    for(std::size_t q = 0; q < queue.size() && start == NONE; ++q) {
      const std::uint32_t cur = queue[q];
      if(m_nodes[cur].flags & KEPT) { start = cur; break; }
      for(int f = 0; f < 6; ++f)
        for_each_face_neighbour(cur, f, [&](std::uint32_t j) {
          if(!seen[j] && m_component[j] == m_component[seed_cell]) { seen[j] = 1; queue.push_back(j); }
        });
    }
    std::fill(seen.begin(), seen.end(), 0);
    queue.clear();
    if(start != NONE) { seen[start] = 1; queue.push_back(start); }
    for(std::size_t q = 0; q < queue.size(); ++q)
      for(int f = 0; f < 6; ++f)
        for_each_face_neighbour(queue[q], f, [&](std::uint32_t j) {
          if(!seen[j] && (m_nodes[j].flags & KEPT)) { seen[j] = 1; queue.push_back(j); }
        });
    for(std::uint32_t id = 0; id < m_nodes.size(); ++id)
      if(m_nodes[id].is_leaf() && (m_nodes[id].flags & KEPT) && !seen[id]) {
        m_nodes[id].flags &= std::uint8_t(~KEPT);
        ++m_stats.disconnected_cells;
      }
  }

  // Leaks: the kept cells (the flood fill from the seed) that the winding number puts inside a body
  // are removed; connected groups of them are reported, with the faces across which the flood
  // entered them (the hole).
  void find_leaks(std::uint32_t seed_cell)
  {
    m_leaks.clear();
    std::vector<int> leak_of(m_nodes.size(), -1);
    std::vector<std::uint32_t> leak_cells;
    std::vector<double> wn(m_nodes.size(), 0.0);
    for(std::uint32_t id = 0; id < m_nodes.size(); ++id) {
      Node& nd = m_nodes[id];
      if(!nd.is_leaf() || !(nd.flags & KEPT)) continue;
      wn[id] = m_domain.winding_number(make_cell(nd).center());
      if(wn[id] >= 0.5) { nd.flags |= LEAK; leak_cells.push_back(id); }
    }
    std::vector<std::uint32_t> queue;
    for(std::uint32_t start : leak_cells) {
      if(!(m_nodes[start].flags & KEPT)) continue;   // already in a reported leak
      Region_leak leak;
      bool first_passage = true;
      queue.clear();
      queue.push_back(start);
      m_nodes[start].flags &= std::uint8_t(~KEPT);
      for(std::size_t q = 0; q < queue.size(); ++q) {
        const std::uint32_t cur = queue[q];
        const Bbox_3 cb = node_bbox(m_nodes[cur]);
        leak_of[cur] = int(m_leaks.size());
        ++leak.cells;
        leak.volume += (cb.xmax() - cb.xmin()) * (cb.ymax() - cb.ymin()) * (cb.zmax() - cb.zmin());
        leak.bbox += cb;
        leak.max_winding_number = (std::max)(leak.max_winding_number, wn[cur]);
        for(int f = 0; f < 6; ++f)
          for_each_face_neighbour(cur, f, [&](std::uint32_t j) {
            const Node& nj = m_nodes[j];
            if(nj.flags & LEAK) {
              if(nj.flags & KEPT) { m_nodes[j].flags &= std::uint8_t(~KEPT); queue.push_back(j); }
            } else if(nj.flags & KEPT) {
              // a face between the leak and the region: the smaller of the two cells' faces
              const Bbox_3 nb = node_bbox(nj);
              const int a = f / 2;
              double lo[3], hi[3];
              for(int k = 0; k < 3; ++k) {
                lo[k] = (std::max)(cb.min(k), nb.min(k));
                hi[k] = (std::min)(cb.max(k), nb.max(k));
              }
              lo[a] = hi[a] = (f % 2) ? cb.max(a) : cb.min(a);
              const Bbox_3 fb(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
              leak.passage = first_passage ? fb : leak.passage + fb;
              first_passage = false;
              ++leak.passage_faces;
              leak.passage_area += (hi[(a + 1) % 3] - lo[(a + 1) % 3]) * (hi[(a + 2) % 3] - lo[(a + 2) % 3]);
            }
          });
      }
      m_leaks.push_back(leak);
    }
    for(std::uint32_t id : leak_cells) m_nodes[id].flags &= std::uint8_t(~LEAK);
    if(m_leaks.empty()) return;
    // flood again from the seed: pockets reached only through a leak (a cavity inside a body,
    // with a winding number below 0.5) are cut off from the region; they go with their leak
    std::vector<char> reached(m_nodes.size(), 0);
    queue.clear();
    if(m_nodes[seed_cell].flags & KEPT) { reached[seed_cell] = 1; queue.push_back(seed_cell); }
    for(std::size_t q = 0; q < queue.size(); ++q)
      for(int f = 0; f < 6; ++f)
        for_each_face_neighbour(queue[q], f, [&](std::uint32_t j) {
          if((m_nodes[j].flags & KEPT) && !reached[j]) { reached[j] = 1; queue.push_back(j); }
        });
    for(std::uint32_t start = 0; start < m_nodes.size(); ++start) {
      if(!m_nodes[start].is_leaf() || !(m_nodes[start].flags & KEPT) || reached[start]) continue;
      queue.clear();
      queue.push_back(start);
      reached[start] = 1;
      int owner = -1;
      double volume = 0;
      for(std::size_t q = 0; q < queue.size(); ++q) {
        const std::uint32_t cur = queue[q];
        m_nodes[cur].flags &= std::uint8_t(~KEPT);
        const Bbox_3 cb = node_bbox(m_nodes[cur]);
        volume += (cb.xmax() - cb.xmin()) * (cb.ymax() - cb.ymin()) * (cb.zmax() - cb.zmin());
        for(int f = 0; f < 6; ++f)
          for_each_face_neighbour(cur, f, [&](std::uint32_t j) {
            if(leak_of[j] >= 0 && owner < 0) owner = leak_of[j];
            if((m_nodes[j].flags & KEPT) && !reached[j]) { reached[j] = 1; queue.push_back(j); }
          });
      }
      Region_leak& l = m_leaks[std::size_t(owner < 0 ? 0 : owner)];
      l.cut_off_cells += queue.size();
      l.cut_off_volume += volume;
    }
    std::stable_sort(m_leaks.begin(), m_leaks.end(),
                     [](const Region_leak& a, const Region_leak& b) { return a.volume > b.volume; });
  }

  // Trimming: a kept cell whose kept face neighbours do not span the three axes (a finger or a
  // plate of the staircase, one cell thick) would be an under-determined cell for a finite-volume
  // solver (OpenFOAM's cell determinant is 0) and cannot carry a boundary layer; such cells are
  // removed, repeatedly, until none is left. In a seeded region meshed body-fitted, a plate (kept
  // neighbours along two axes) with no finer leaf beside it stays: it is a gap between bodies two
  // and a half to four cells wide, whose buffer cells on both sides make it a channel of three
  // cells (motorBike: the passages between engine, frame and tank; the mean distance from the
  // input to the mesh 3.1 -> 2.1 mm for 2 % more cells). Inside a body (no seed) keeping them
  // lowered the worst cells of the organic test surfaces (elephant 0.31 -> 0.04), so there it
  // does not. (Only plates with no finer leaf beside them: fewer split faces for the buffer on
  // both sides to fold; on motorBike keeping all gave the same distances.)
  void trim()
  {
    std::vector<std::uint32_t> work;
    for(std::uint32_t id = 0; id < m_nodes.size(); ++id)
      if(m_nodes[id].is_leaf() && (m_nodes[id].flags & KEPT)) work.push_back(id);
    std::vector<std::uint32_t> next;
    while(!work.empty()) {
      next.clear();
      for(std::uint32_t id : work) {
        if(!(m_nodes[id].flags & KEPT)) continue;
        bool axis_ok[3] = {false, false, false};
        for(int f = 0; f < 6; ++f) {
          if(axis_ok[f / 2]) continue;
          for_each_face_neighbour(id, f, [&](std::uint32_t j) { if(m_nodes[j].flags & KEPT) axis_ok[f / 2] = true; });
        }
        const int axes = int(axis_ok[0]) + int(axis_ok[1]) + int(axis_ok[2]);
        if(axes == 3) continue;
        if(m_keep_plates && axes == 2) {   // a plate: kept if no finer leaf is beside it
          bool finer = false;
          for(int f = 0; f < 6 && !finer; ++f)
            for_each_face_neighbour(id, f, [&](std::uint32_t j) { if(m_nodes[j].level > m_nodes[id].level) finer = true; });
          if(!finer) continue;
        }
        m_nodes[id].flags &= std::uint8_t(~KEPT);
        ++m_stats.trimmed_cells;
        for(int f = 0; f < 6; ++f)
          for_each_face_neighbour(id, f, [&](std::uint32_t j) { if(m_nodes[j].flags & KEPT) next.push_back(j); });
      }
      std::sort(next.begin(), next.end());
      next.erase(std::unique(next.begin(), next.end()), next.end());
      work.swap(next);
    }
  }

  // ---------------------------------------------------------------------------------------------
  // extraction
  std::uint64_t pack(std::uint64_t x, std::uint64_t y, std::uint64_t z) const
  {
    return x | (y << KEY_BITS) | (z << (2 * KEY_BITS));
  }

  template <typename HexMesh>
  void extract(HexMesh& out)
  {
    typedef typename HexMesh::Index Index;
    out.clear();
    out.box = m_box;
    for(const char* n : box_face_names()) out.patch_names.push_back(n);
    for(const std::string& s : m_domain.patch_names()) {
      // a part named like a box face or another part gets a suffix: patch names are unique
      std::string n = s;
      for(int k = 2; std::find(out.patch_names.begin(), out.patch_names.end(), n) != out.patch_names.end(); ++k)
        n = s + "_" + std::to_string(k);
      out.patch_names.push_back(n);
    }
    out.patch_types.assign(out.patch_names.size(), "wall");
    for(int f = 0; f < 6; ++f) out.patch_types[std::size_t(f)] = "patch";

    const int D = m_stats.max_level_reached;   // keys at the finest level present
    std::vector<std::uint32_t> kept;
    kept.reserve(m_stats.kept_cells);
    for(std::uint32_t id = 0; id < m_nodes.size(); ++id)
      if(m_nodes[id].is_leaf() && (m_nodes[id].flags & KEPT)) kept.push_back(id);
    std::vector<std::uint32_t> cell_of_node(m_nodes.size(), NONE);
    for(std::size_t i = 0; i < kept.size(); ++i) cell_of_node[kept[i]] = std::uint32_t(i);

    Key_map vmap;
    vmap.reserve(kept.size() + kept.size() / 2 + 64);
    std::vector<std::array<std::uint32_t, 3>> vkeys;
    auto vertex = [&](std::uint64_t x, std::uint64_t y, std::uint64_t z) -> Index {
      bool inserted;
      const Index v = vmap.insert(pack(x, y, z), Index(vkeys.size()), inserted);
      if(inserted) vkeys.push_back({{std::uint32_t(x), std::uint32_t(y), std::uint32_t(z)}});
      return v;
    };
    auto corner_key = [&](const Node& nd, int k, std::uint64_t* c) {
      const int s = D - nd.level;
      c[0] = std::uint64_t(nd.x + hex_corner_offsets()[k][0]) << s;
      c[1] = std::uint64_t(nd.y + hex_corner_offsets()[k][1]) << s;
      c[2] = std::uint64_t(nd.z + hex_corner_offsets()[k][2]) << s;
    };

    out.hexahedra.resize(kept.size());
    out.cell_levels.resize(kept.size());
    for(std::size_t i = 0; i < kept.size(); ++i) {
      const Node& nd = m_nodes[kept[i]];
      for(int k = 0; k < 8; ++k) {
        std::uint64_t c[3]; corner_key(nd, k, c);
        out.hexahedra[i][k] = vertex(c[0], c[1], c[2]);
      }
      out.cell_levels[i] = {{nd.level, nd.level, nd.level}};
    }

    // boundary faces; a face of a kept cell next to finer leaves that are only partly kept is
    // split into the quarters facing them, creating the edge-midpoint / centre vertices it needs
    const auto& lf = hex_local_faces();
    std::vector<std::uint32_t> fine;
    for(std::size_t i = 0; i < kept.size(); ++i) {
      const Node& nd = m_nodes[kept[i]];
      for(int f = 0; f < 6; ++f) {
        const int a = f / 2, side = f % 2;
        std::int64_t c[3] = {nd.x, nd.y, nd.z};
        c[a] += side ? 1 : -1;
        const std::uint32_t j = find(nd.level, c[0], c[1], c[2]);
        std::array<Index, 4> quad;
        for(int q = 0; q < 4; ++q) quad[q] = out.hexahedra[i][lf[f][q]];
        if(j == NONE) { out.boundary_faces.push_back({quad, Index(i), f}); continue; }
        if(m_nodes[j].is_leaf()) {
          if(!(m_nodes[j].flags & KEPT)) out.boundary_faces.push_back({quad, Index(i), surface_patch(nd, f)});
          continue;
        }
        fine.clear();
        auto push_fine = [&](std::uint32_t x) { fine.push_back(x); };
        collect_face_leaves(j, a, side ? 0 : 1, push_fine);
        std::size_t nkept = 0;
        for(std::uint32_t x : fine) if(m_nodes[x].flags & KEPT) ++nkept;
        if(nkept == fine.size()) continue;                     // all internal
        if(nkept == 0) { out.boundary_faces.push_back({quad, Index(i), surface_patch(nd, f)}); continue; }
        CGAL_assertion(fine.size() == 4);
        for(std::uint32_t x : fine) {
          if(m_nodes[x].flags & KEPT) continue;
          // the quarter of face f facing fine leaf x: the fine leaf's opposite face, keys at D
          const Node& fx = m_nodes[x];
          const auto& of = lf[f ^ 1];   // the fine leaf's face towards us, seen from it
          std::array<Index, 4> sub;
          for(int q = 0; q < 4; ++q) {
            std::uint64_t k[3]; corner_key(fx, of[q], k);
            sub[q] = vertex(k[0], k[1], k[2]);
          }
          std::swap(sub[1], sub[3]);     // reverse: outward from our cell
          out.boundary_faces.push_back({sub, Index(i), surface_patch(nd, f)});
        }
      }
    }

    // hanging nodes: vertices at an edge midpoint or a face centre of a kept cell
    std::vector<char> is_hanging(vkeys.size(), 0);
    const auto& le = hex_local_edges();
    for(std::size_t i = 0; i < kept.size(); ++i) {
      const Node& nd = m_nodes[kept[i]];
      if(nd.level >= D) continue;
      std::uint64_t ck[8][3];
      for(int k = 0; k < 8; ++k) corner_key(nd, k, ck[k]);
      for(const auto& e : le) {
        std::uint32_t v;
        if(vmap.find(pack((ck[e[0]][0] + ck[e[1]][0]) / 2, (ck[e[0]][1] + ck[e[1]][1]) / 2,
                          (ck[e[0]][2] + ck[e[1]][2]) / 2), v) && !is_hanging[v]) {
          is_hanging[v] = 1;
          out.hanging_nodes.push_back({Index(v), {{out.hexahedra[i][e[0]], out.hexahedra[i][e[1]], 0, 0}}, 2});
        }
      }
      for(const auto& f : lf) {
        std::uint32_t v;
        if(vmap.find(pack((ck[f[0]][0] + ck[f[2]][0]) / 2, (ck[f[0]][1] + ck[f[2]][1]) / 2,
                          (ck[f[0]][2] + ck[f[2]][2]) / 2), v) && !is_hanging[v]) {
          is_hanging[v] = 1;
          out.hanging_nodes.push_back({Index(v), {{out.hexahedra[i][f[0]], out.hexahedra[i][f[1]],
                                                   out.hexahedra[i][f[2]], out.hexahedra[i][f[3]]}}, 4});
        }
      }
    }

    out.points.resize(vkeys.size());
    for(std::size_t v = 0; v < vkeys.size(); ++v)
      out.points[v] = Point_3(coord_at(0, vkeys[v][0], D), coord_at(1, vkeys[v][1], D), coord_at(2, vkeys[v][2], D));
  }

  int surface_patch(const Node& nd, int f) const
  {
    if(m_domain.patch_names().size() <= 1) return 6;
    // the part of the triangle nearest to the face centre (of a sheet: of its side facing the cell)
    const Cell c = make_cell(nd);
    const auto& q = hex_local_faces()[f];
    const Point_3 m = CGAL::centroid(c.corners[q[0]], c.corners[q[1]], c.corners[q[2]], c.corners[q[3]]);
    return 6 + m_domain.patch_facing(m_domain.closest_triangle(m), CGAL::midpoint(c.corners[0], c.corners[6]));
  }

private:
  const MeshDomain& m_domain;
  const Criteria& m_criteria;
  Bbox_3 m_box;
  double m_lo[3], m_hi[3];
  std::array<std::uint32_t, 3> m_n;
  int m_D = 0;
  std::vector<Node> m_nodes;
  std::vector<std::vector<std::uint32_t>> m_lists;
  std::vector<std::uint32_t> m_free_list;
  std::vector<std::vector<std::uint32_t>> m_by_level;
  std::vector<int> m_component;
  std::vector<Region_leak> m_leaks;
  bool m_use_features = false, m_use_lines = false;
  double m_curvature_size = 0;   // the criteria's curvature size (0: normal spreads not computed)
  std::vector<std::pair<double, double>> m_patch_sizes;   // the criteria's per-patch sizes
  double m_min_patch_size = std::numeric_limits<double>::infinity(), m_min_patch_fine = std::numeric_limits<double>::infinity();
  int m_thin_cells = 0;          // the criteria's cells across thin parts (0: thicknesses not computed)
  bool m_keep_plates = false;    // trimming keeps plates one cell thick (a seeded region's gaps)
  double m_thin_min_size = 0;
  int m_near_layers = 0;
  std::size_t m_leaves = 0;
  Statistics m_stats;
};

} // namespace internal
} // namespace Hex_meshing_3
} // namespace CGAL

#endif
