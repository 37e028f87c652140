// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESH_CRITERIA_3_H
#define CGAL_HEX_MESH_CRITERIA_3_H

// Sizes are lengths in the input's unit. A cell's size is its longest edge. Refinement is
// isotropic here (1 -> 8); a size s is realised as (initial edge) / 2^k <= s.

#include <CGAL/Bbox_3.h>
#include <CGAL/assertions.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {

/*!
 * \ingroup PkgHexMeshing3Criteria
 * \brief what a refinement criterion sees of a cell: its lattice address, its 8 corners
 * (VTK order) and whether the surface cuts it.
 *
 * Lattice address: on each axis a the initial grid has `n_a` cells; a cell at level `level[a]`
 * has index `index[a]` in [0, n_a 2^level[a]).
 */
template <typename GeomTraits>
struct Cell_3
{
  typedef typename GeomTraits::FT      FT;
  typedef typename GeomTraits::Point_3 Point_3;
  std::array<std::uint32_t, 3> index;
  std::array<std::uint8_t, 3> level;
  std::array<Point_3, 8> corners;
  bool is_cut = false;          ///< the cell's hull meets the surface (exact test)
  bool meets_feature = false;   ///< the cell meets a feature edge of the domain (exact test; only
                                ///< computed when the criteria have a feature size)
  /// how much the surface bends inside the cell: an estimate, in degrees, of the largest angle
  /// between the normals of the input triangles that meet it (exact test for "meet"), at least
  /// half the true largest angle and never more; 0 for an uncut cell. Only computed when the
  /// criteria have a curvature size and the cell is larger than it.
  double normal_spread = 0;
  /// how thin the part or the gap is where the surface crosses the cell: the shortest distance,
  /// along the normal of an input triangle meeting the cell (both ways, from a point of the
  /// triangle near the cell's centre), to an opposite-facing part of the surface (normals more
  /// than 120 degrees apart); infinite if none. Only computed when the criteria refine thin parts
  /// and the cell is cut and larger than their smallest size.
  double thickness = std::numeric_limits<double>::infinity();
  /// the smallest surface size asked by the patches (`Hex_mesh_criteria_3::set_patch_size()`) of
  /// the input triangles meeting the cell (exact test); infinite if none asks. Only computed when
  /// the criteria have patch sizes and the cell is cut and larger than the smallest of them.
  double patch_size = std::numeric_limits<double>::infinity();
  /// the same for the patches' sizes where the surface bends (`normal_spread` beyond the
  /// curvature angle); infinite if none asks
  double patch_curvature_size = std::numeric_limits<double>::infinity();

  /// length of the longest of the 12 edges
  FT size() const
  {
    FT m2 = 0;
    for(const auto& ed : hex_local_edges()) m2 = (std::max)(m2, CGAL::squared_distance(corners[ed[0]], corners[ed[1]]));
    return CGAL::approximate_sqrt(m2);
  }
  /// the average of the corners
  Point_3 center() const
  {
    FT x = 0, y = 0, z = 0;
    for(const Point_3& p : corners) { x += p.x(); y += p.y(); z += p.z(); }
    return Point_3(x / 8, y / 8, z / 8);
  }
  Bbox_3 bbox() const
  {
    Bbox_3 b = corners[0].bbox();
    for(int k = 1; k < 8; ++k) b += corners[k].bbox();
    return b;
  }
};

} // namespace Hex_meshing_3

/*!
 * \ingroup PkgHexMeshing3Criteria
 * \brief the refinement criteria of `make_hex_mesh_3()`: an aggregate of elementary criteria, each
 * saying "this cell is bad, split it with this priority" or nothing, as `Mesh_criteria_3` does.
 *
 * Model of `HexMeshCriteria_3`. Elementary criteria, in order:
 * - cell size: every cell's size is at most `cell_size` (a number or a field of the position);
 * - surface size: every cell cut by the surface has size at most `surface_size`;
 * - feature size: every cell meeting a feature edge of the domain has size at most `feature_size`;
 * - curvature size: every cut cell in which the surface normals differ by more than
 *   `curvature_angle` degrees has size at most `curvature_size` (snappyHexMesh's second surface
 *   level with its `resolveFeatureAngle`): curved parts, sharp edges and corners get finer cells;
 * - thin parts: every cut cell where the part or the gap is thinner than `thin_part_cells` x the
 *   cell's size is split, down to `thin_part_min_size` (snappyHexMesh's gap refinement): a plate
 *   or a slot gets that many cells across, as far as that size allows;
 * - refinement boxes: every cell overlapping a box (with positive volume) has size at most the
 *   box's size;
 * - user criteria added by `add_criterion()`.
 * No cell is split beyond `max_level` levels below the initial grid.
 *
 * After refinement the grid is balanced: by default 2:1 across faces and edges. With
 * `set_cells_between_levels(n)`, n >= 2, every region of one level is surrounded by at least n
 * cells of the next coarser level before a coarser one (snappyHexMesh's `nCellsBetweenLevels`):
 * the size grows more slowly away from the surface, at the price of more cells.
 *
 * \tparam GeomTraits a model of `Kernel`
 */
template <typename GeomTraits>
class Hex_mesh_criteria_3
{
public:
  typedef GeomTraits                          Geom_traits;
  typedef typename GeomTraits::FT             FT;
  typedef typename GeomTraits::Point_3        Point_3;
  typedef Hex_meshing_3::Cell_3<GeomTraits>   Cell;
  typedef std::optional<FT>                   Is_cell_bad;   ///< empty: keep; value: split priority
  typedef std::function<FT(const Point_3&)>   Size_field;    ///< a size as a function of position

  /// \name Creation
  /// @{
  /// constant sizes; `surface_size` <= 0 means "same as `cell_size`"
  Hex_mesh_criteria_3(FT cell_size, FT surface_size, int max_level = 12)
    : m_cell_size_value(cell_size), m_surface_size_value(surface_size > 0 ? surface_size : cell_size),
      m_max_level(max_level)
  {}
  /// sizes as fields evaluated at a cell's centre; `cell_size_bound` is the largest value the cell
  /// field takes (it sets the initial grid)
  Hex_mesh_criteria_3(Size_field cell_size, FT cell_size_bound, Size_field surface_size, int max_level = 12)
    : m_cell_size_value(cell_size_bound), m_surface_size_value(cell_size_bound),
      m_cell_size_field(std::move(cell_size)), m_surface_size_field(std::move(surface_size)),
      m_max_level(max_level)
  {}
  /// @}

  /// \name Settings
  /// @{
  /// cells overlapping `box` get size at most `size`
  void add_refinement_box(const Bbox_3& box, FT size) { m_boxes.emplace_back(box, size); }
  /// an extra elementary criterion, tested after the built-in ones
  void add_criterion(std::function<Is_cell_bad(const Cell&)> extra) { m_extra.push_back(std::move(extra)); }
  void set_max_level(int l) { m_max_level = l; }
  /// cells meeting a feature edge of the domain get size at most `size` (0: no such criterion);
  /// the domain's feature edges are set by `Surface_domain_3::set_feature_edges()`
  void set_feature_size(FT size) { m_feature_size = size; }
  /// cut cells in which the surface normals differ by more than `angle` degrees get size at most
  /// `size` (0: no such criterion); the angle is estimated (`Cell_3::normal_spread`): a cell is
  /// sure to be refined when its normals differ by more than twice `angle`
  void set_curvature_size(FT size, double angle = 30)
  {
    m_curvature_size = size;
    m_curvature_angle = angle;
  }
  /// cut cells where the part or the gap is thinner than `cells` x their size are split, down to
  /// size `min_size` (0 cells: no such criterion)
  /// \pre `cells == 0 || min_size > 0`
  void set_thin_part_refinement(int cells, FT min_size)
  {
    CGAL_precondition(cells == 0 || min_size > 0);
    m_thin_cells = cells;
    m_thin_min_size = min_size;
  }
  /// cut cells meeting an input triangle of patch `patch` (`Surface_domain_3::patch()`) get size
  /// at most `size`, and at most `curvature_size` where the surface normals in the cell differ by
  /// more than the curvature angle (0: no such size) - snappyHexMesh's per-surface `level (L1 L2)`
  /// \pre `patch >= 0 && size > 0 && curvature_size >= 0`
  void set_patch_size(int patch, FT size, FT curvature_size = 0)
  {
    CGAL_precondition(patch >= 0 && size > 0 && curvature_size >= 0);
    if(m_patch_sizes.size() <= std::size_t(patch)) m_patch_sizes.resize(std::size_t(patch) + 1, {FT(0), FT(0)});
    m_patch_sizes[std::size_t(patch)] = {size, curvature_size};
  }
  /// the angle (degrees) beyond which the curvature sizes apply (the global one and the patches')
  void set_curvature_angle(double angle) { m_curvature_angle = angle; }
  /// every region of one level gets at least `n` cells of the next coarser level around it
  /// before a coarser one (1: the plain 2:1 balance across faces and edges)
  /// \pre `n >= 1 && n <= 16`
  void set_cells_between_levels(int n)
  {
    CGAL_precondition(n >= 1 && n <= 16);
    m_cells_between_levels = n;
  }
  /// @}

  /// \name Access
  /// @{
  /// the size that sets the initial grid (the cell size, or the bound of the cell size field)
  FT initial_size() const { return m_cell_size_value; }
  FT surface_size() const { return m_surface_size_value; }
  int max_level() const { return m_max_level; }
  /// the size asked along feature edges (0: none)
  FT feature_size() const { return m_feature_size; }
  /// the size asked where the surface bends by more than `curvature_angle()` in a cell (0: none)
  FT curvature_size() const { return m_curvature_size; }
  double curvature_angle() const { return m_curvature_angle; }
  /// the cells asked across thin parts and gaps (0: none), and the smallest size that asks for
  int thin_part_cells() const { return m_thin_cells; }
  FT thin_part_min_size() const { return m_thin_min_size; }
  /// the cells of each level between two transitions of the balanced grid (1: plain 2:1)
  int cells_between_levels() const { return m_cells_between_levels; }
  const std::vector<std::pair<Bbox_3, FT>>& refinement_boxes() const { return m_boxes; }
  /// per patch index: (surface size, curvature size) asked, (0, 0) where none is
  const std::vector<std::pair<FT, FT>>& patch_sizes() const { return m_patch_sizes; }
  /// @}

  /// is `c` bad? The first failing elementary criterion wins; the priority is the ratio of the
  /// cell's size to the size asked (larger: split first).
  Is_cell_bad operator()(const Cell& c) const
  {
    const int lvl = (std::max)({int(c.level[0]), int(c.level[1]), int(c.level[2])});
    if(lvl >= m_max_level) return Is_cell_bad();
    const FT s = c.size();
    const FT cs = m_cell_size_field ? m_cell_size_field(c.center()) : m_cell_size_value;
    if(exceeds(s, cs)) return Is_cell_bad(s / cs);
    if(c.is_cut) {
      const FT ss = m_surface_size_field ? m_surface_size_field(c.center()) : m_surface_size_value;
      if(exceeds(s, ss)) return Is_cell_bad(s / ss);
    }
    if(c.is_cut && c.patch_size < std::numeric_limits<double>::infinity() && exceeds(s, FT(c.patch_size)))
      return Is_cell_bad(s / FT(c.patch_size));
    if(c.is_cut && c.patch_curvature_size < std::numeric_limits<double>::infinity() && c.normal_spread > m_curvature_angle &&
       exceeds(s, FT(c.patch_curvature_size)))
      return Is_cell_bad(s / FT(c.patch_curvature_size));
    if(c.meets_feature && m_feature_size > 0 && exceeds(s, m_feature_size)) return Is_cell_bad(s / m_feature_size);
    if(c.is_cut && m_curvature_size > 0 && c.normal_spread > m_curvature_angle && exceeds(s, m_curvature_size))
      return Is_cell_bad(s / m_curvature_size);
    if(c.is_cut && m_thin_cells > 0 && c.thickness > 0 && exceeds(s, m_thin_min_size) &&
       CGAL::to_double(s) * m_thin_cells > c.thickness)
      return Is_cell_bad(s * m_thin_cells / FT(c.thickness));
    if(!m_boxes.empty()) {
      const Bbox_3 b = c.bbox();
      for(const auto& rb : m_boxes)
        if(exceeds(s, rb.second) && overlaps_with_volume(b, rb.first)) return Is_cell_bad(s / rb.second);
    }
    for(const auto& f : m_extra) {
      Is_cell_bad r = f(c);
      if(r) return r;
    }
    return Is_cell_bad();
  }

private:
  // sizes are realised as (initial edge) / 2^k: a relative slack of 1e-9 keeps round-off in the
  // corner coordinates from asking for one more level (a size comparison, not a geometric predicate)
  static bool exceeds(FT s, FT target) { return s > target * FT(1 + 1e-9); }
  static bool overlaps_with_volume(const Bbox_3& a, const Bbox_3& b)
  {
    for(int d = 0; d < 3; ++d)
      if(!(a.min(d) < b.max(d) && b.min(d) < a.max(d))) return false;
    return true;
  }

  FT m_cell_size_value, m_surface_size_value;
  std::vector<std::pair<FT, FT>> m_patch_sizes;
  Size_field m_cell_size_field, m_surface_size_field;
  int m_max_level;
  FT m_feature_size = 0;
  FT m_curvature_size = 0;
  double m_curvature_angle = 30;
  int m_thin_cells = 0;
  FT m_thin_min_size = 0;
  int m_cells_between_levels = 1;
  std::vector<std::pair<Bbox_3, FT>> m_boxes;
  std::vector<std::function<Is_cell_bad(const Cell&)>> m_extra;
};

} // namespace CGAL

#endif // CGAL_HEX_MESH_CRITERIA_3_H
