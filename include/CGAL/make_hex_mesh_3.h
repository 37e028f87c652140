// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_MAKE_HEX_MESH_3_H
#define CGAL_MAKE_HEX_MESH_3_H

#include <CGAL/Hex_mesh_criteria_3.h>
#include <CGAL/Hex_meshing_3/Default_visitor.h>
#include <CGAL/Hex_meshing_3/Feature_curves_3.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/IO/write_OpenFOAM.h>
#include <CGAL/Hex_meshing_3/Status.h>
#include <CGAL/Hex_meshing_3/fidelity.h>
#include <CGAL/Hex_meshing_3/parameters.h>
#include <CGAL/Hex_meshing_3/internal/Octree_mesher_3.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <iterator>
#include <memory>
#include <optional>
#include <tuple>
#include <type_traits>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>
#endif

namespace CGAL {

namespace Hex_meshing_3 {
/*!
 * \ingroup PkgHexMeshing3Domains
 * \brief the options `make_hex_mesh_3()` builds its `Feature_curves_3` with when it is given none:
 * 30 degrees, sharp edges judged at half the smallest of the criteria's surface, curvature and
 * feature sizes (`Options::scale`) and by a contrast of 3 (`Options::contrast`)
 */
template <typename GeomTraits, typename Criteria>
typename Feature_curves_3<GeomTraits>::Options default_feature_curve_options(const Criteria& criteria)
{
  double finest = CGAL::to_double(criteria.surface_size());
  if(criteria.curvature_size() > 0) finest = (std::min)(finest, CGAL::to_double(criteria.curvature_size()));
  if(criteria.feature_size() > 0) finest = (std::min)(finest, CGAL::to_double(criteria.feature_size()));
  typename Feature_curves_3<GeomTraits>::Options o;
  o.scale = finest / 2;
  o.contrast = 3;
  return o;
}

namespace internal {
// The visitor of a capture run ahead on another thread (`make_hex_mesh_3()` with a parallel
// tag): it reports nothing and stops the capture once `stop` is set.
struct Ahead_visitor
{
  const std::atomic<bool>* stop;
  void on_phase_begin(const char*, std::size_t) {}
  void on_phase_end(const char*) {}
  bool go_further(double) { return !stop->load(std::memory_order_relaxed); }
};
// where the captures run ahead: TBB's tasks, or (sequential) none; and how many threads TBB
// would run them on (its arena, within `tbb::global_control`'s limit: `hexmesh --threads`)
#ifdef CGAL_LINKED_WITH_TBB
typedef tbb::task_group Ahead_group;
inline std::size_t available_threads()
{
  return (std::min)(std::size_t(tbb::this_task_arena::max_concurrency()),
                    tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}
#else
struct Ahead_group
{
  template <typename F> void run(F&& f) { f(); }
  void wait() {}
};
inline std::size_t available_threads() { return 1; }
#endif
} // namespace internal
} // namespace Hex_meshing_3

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief fills `out` with the hexahedra of an overlay grid refined by `criteria` over the region
 * of `domain` asked for: the inside of the surface (default), or the region reached from a seed
 * point without crossing the surface.
 *
 * Steps: an initial Cartesian grid over the meshing box (n_a = ceil(L_a / size) cells per axis,
 * so the box is honoured exactly); refinement of the cells the criteria call bad, level by level;
 * 2:1 balance across every face and edge; classification of the cells not cut by the surface;
 * extraction of the kept cells with their hanging nodes and boundary faces; then, unless
 * `body_fitted(false)` is given, the boundary is fitted to the surface (HEXPRESS-style):
 * - refinement splits, with every cut cell, the cells of its level around it (so the staircase
 *   next to the surface has the surface size); the staircase keeps its surface vertices at least
 *   0.4 x their cell size away from the surface (the cells at a closer vertex removed, then
 *   trimmed; 0.25 or 0.2 in the retries of `capture_retry_cells`) and is made manifold: at a non-manifold vertex the fewest cells that make its 2x2x2
 *   block well-composed are removed, those nearest to the surface first;
 * - a buffer layer of hexahedra joins each staircase face on the surface to its image on the
 *   surface (closest point, or the point along the staircase normal where the closest point lies
 *   behind a staircase face; kept in the box planes it touches); a hanging midpoint of a staircase
 *   face's edge has a hanging image, so coarse and fine buffer cells meet 1:2; an image whose
 *   surface point lies on a border edge of the input (a hole) caps the hole instead: it stays
 *   half a cell out from the staircase and is not projected - unless that border edge runs along
 *   another border edge within a thousandth of the input's diagonal (and a quarter of its
 *   length): a seam between parts that have their own copies of the vertices, or a crack, which
 *   borders no hole (`Boundary_fidelity::cap_faces` follows the same rule, and also counts the
 *   faces on the triangles that fill holes: `Surface_domain_3` fills the holes it can, and the
 *   images on a fill are projected onto it like any other surface point); the cap vertices at
 *   the border of a two-sided sheet (a baffle, round which the buffer wraps) are moved onto it
 *   after the optimisation, as far as no cell of theirs falls below min(its quality, 0.35); a
 *   surface vertex within two cells of a hole's border (a simple closed loop of open edges, not
 *   on a two-sided sheet) is never moved onto that border (its cells towards the cap would
 *   collapse there);
 * - feature curves (named parameter `feature_curves`) are followed by chains of mesh edges
 *   (shortest paths on the buffer's outer surface) snapped onto them, corners onto corners; the
 *   outer faces between chains are projected onto the input faces between the same curves;
 * - the vertices near the boundary are moved to raise the minimum scaled Jacobian (and face
 *   pyramid quality) of their cells, never making a valid cell invalid; curve vertices of cells
 *   still inverted return to the surface, then surface vertices are released into the volume
 *   (reported in the statistics as unreached); both go back as far as their cells allow, alone
 *   or with their neighbours making room (`Meshing_statistics::feature_joint_moves`), and buffer
 *   cells still below 0.02 are removed
 *   (their staircase face is the boundary there), as are those at a face OpenFOAM would find
 *   skewed beyond 3.5 or non-orthogonal beyond 70 degrees; before that removal, the cells of faces that cannot be cut
 *   into positive tetrahedra with both cell centres (OpenFOAM's "face tets") are moved until
 *   they can, where their scaled Jacobian and non-orthogonality allow. Then the buffer cells that
 *   `checkMesh -allGeometry` would still find concave, or at a face failing the tet decomposition,
 *   on the points an OpenFOAM case gets (`IO::write_OpenFOAM()` with its default bulge of the
 *   hanging nodes) are removed too (`Meshing_statistics::foam_fault_cells`; where the capture may
 *   be retried, see `capture_retry_cells`, the retries do not remove them, and a retry kept that
 *   has such faults runs once more, the same, with the removal). Every cell of the result has a
 *   positive scaled Jacobian.
 * - after the polish, the corners of the outer faces whose centre stands more than 0.2 local sizes off the
 *   surface (a chain turning inside a face, a stretched face over a convex region) slide on their
 *   surface or curve to bring the centre closer, as far as the polish's guards allow (no cell
 *   below min(its quality, 0.35)); `Meshing_statistics::fidelity_moves` counts the moves.
 *   Then the vertices where a feature chain turns inside a face (left off their curve) are
 *   pulled towards it, to no closer than 0.1 local sizes, within the same guards: the face no
 *   longer folds along its diagonal (`Meshing_statistics::turn_moves`); no face of the vertex may
 *   stand farther off the surface than before (or than 0.2 local sizes). Where its step alone
 *   fails the guards, it is tried with the other vertices of its cells improved once after it, the
 *   guards then holding on all their cells.
 *
 * Retries run ahead with `ConcurrencyTag` `CGAL::Parallel_tag` (or `CGAL::Parallel_if_available_tag`
 * where TBB is linked) and more than one thread in TBB's arena: while a capture runs, the one the
 * retries of `capture_retry_cells` would run after it is started on another thread, and used only
 * if they do run it. The captures and the rules that choose among them are the same, so the
 * mesh is the same whatever the number of threads (a cancellation aside: a capture run ahead is
 * not polled by the visitor, and one that is not used is stopped). Two captures run at once
 * then, and the domain's search tree is kept until they end. Nothing runs ahead on meshes beyond
 * the retries' budget (the motorBike).
 *
 * \tparam ConcurrencyTag `CGAL::Sequential_tag` (default) or `CGAL::Parallel_tag`
 * \tparam MeshDomain model of `HexMeshDomain_3` (e.g. `Hex_meshing_3::Surface_domain_3<K>`)
 * \tparam Criteria   model of `HexMeshCriteria_3` (e.g. `Hex_mesh_criteria_3<K>`)
 * \tparam HexMesh    model of `HexMesh_3` (e.g. `Hex_meshing_3::Hex_mesh_3<K>`)
 * \param domain   the surface and its inside test (input; its search tree, which the surface
 *                 queries build when first needed, is freed at the end of the body-fitted capture to
 *                 lower the memory peak, and built again by the next query: one domain must not be
 *                 meshed or queried from several threads at once)
 * \param criteria says which cells to split (input)
 * \param out      receives the mesh; cleared first (output)
 * \param np optional sequence of named parameters among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{meshing_box}
 *     \cgalParamDescription{the box to mesh, honoured exactly}
 *     \cgalParamType{`CGAL::Bbox_3`}
 *     \cgalParamDefault{the domain's bounding box grown by the criteria's initial size on every side}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{region_seed}
 *     \cgalParamDescription{mesh the cells reached from this point without crossing a cut cell
 *       (the fluid around bodies, as OpenFOAM's `locationInMesh`), instead of the inside}
 *     \cgalParamType{`Geom_traits::Point_3`}
 *     \cgalParamDefault{none: the inside of the surface is meshed}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{leaks}
 *     \cgalParamDescription{receives the leaks of a seeded region: groups of cells the flood fill
 *       from the seed reached through holes of an open surface but that the winding number puts
 *       inside a body; the winding number decides (they are not meshed). Only open or
 *       inconsistent surfaces can leak.}
 *     \cgalParamType{an output iterator with value type `Hex_meshing_3::Region_leak`}
 *     \cgalParamDefault{leaks are removed silently}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{statistics}
 *     \cgalParamDescription{receives the counts of the run (grid leaves, cut leaves, balance splits,
 *       trimmed cells, cells cut off from the seed, ...)}
 *     \cgalParamType{`Hex_meshing_3::Meshing_statistics*`}
 *     \cgalParamDefault{not reported}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{max_cells}
 *     \cgalParamDescription{stop refining before a level would take the grid beyond this many
 *       leaf cells (balance may add a few more); the status is then `CELL_LIMIT_REACHED`}
 *     \cgalParamType{`std::size_t`}
 *     \cgalParamDefault{unlimited}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{body_fitted}
 *     \cgalParamDescription{`false` keeps the staircase of grid faces as the boundary}
 *     \cgalParamType{`bool`}
 *     \cgalParamDefault{`true`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{feature_curves}
 *     \cgalParamDescription{the curves and corners the boundary must follow}
 *     \cgalParamType{`const Hex_meshing_3::Feature_curves_3<Geom_traits>*`}
 *     \cgalParamDefault{`Feature_curves_3` of the domain at 30 degrees, its sharp edges judged at the scale of half
 *       the smallest of the criteria's surface, curvature and feature sizes (`Feature_curves_3::Options::scale`)
 *       and against the edges around them (`Feature_curves_3::Options::contrast` 3)}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{feature_pillows}
 *     \cgalParamDescription{`true`: along each convex sharp curve whose chain allows it (and runs within
 *       half a cell of the curve on average), the buffer is
 *       cut and each side gets its own copies of the chain's vertices; one hexahedron per chain edge
 *       fills the cut, with two boundary faces meeting at the curve, and one cell closes three such
 *       pillows at a corner. A face then never has three corners on a curve where the chain turns
 *       inside it (the cube's worst cell: 0.57 without, 0.88 with; anchor's input sharp edges are
 *       within 0.35 surface sizes of the mesh's, 0.64 without). Where the capture with pillows
 *       leaves a cell below a scaled Jacobian of 0.3, a checkMesh -allGeometry fault or a
 *       boundary face farther than a quarter of the surface size from the input, the retries of
 *       `capture_retry_cells` run without them (cube_nonmanifold and fandisk_crack at the test
 *       sizes; cylinder at 0.7 to 0.9 times its default surface size, where some pillow vertices
 *       stop short of the surface), and the better mesh is kept}
 *     \cgalParamType{`bool`}
 *     \cgalParamDefault{`true`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{polish_worst_cells}
 *     \cgalParamDescription{`true`: the capture ends by moving the vertices of the cells whose scaled Jacobian
 *       (or face-pyramid or split-face warp quality) is below 0.35 with the max-min step alone, no
 *       cell falling below min(its own, 0.35), no cell's worst face split below min(its own, 0.05)
 *       and the worst non-orthogonality around the moved vertex (whole faces, vertex averages) not
 *       above max(its value, 50 degrees); then by joint moves around each cell still below 0.3
 *       (the vertices of the cells around it move together, down the gradient of a soft minimum
 *       of their cells' qualities, under the same guards but that a cell below 0.35 may fall to
 *       the patch's current minimum; a patch is kept if its worst cell got better and its count
 *       of cells whose scaled Jacobian is below 0.3 did not grow): neither the minimum below 0.35
 *       nor the count of cells under 0.35 can get worse (OpenFOAM's non-orthogonality may rise a
 *       little)}
 *     \cgalParamType{`bool`}
 *     \cgalParamDefault{`true`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{all_capture_retries}
 *     \cgalParamDescription{every retry of `capture_retry_cells` is run, whatever its budget and
 *       however good the captures before it: every capture of the sequence (five, or four where
 *       the first made no pillow) at each of the three staircase distances, the best kept by the
 *       same rules: at up to 18 captures' time, a better mesh than the default rules give on 30
 *       of 75 meshes measured and a worse one on 4 (one or two more boundary faces beyond a
 *       quarter surface size; see the manual); `Meshing_statistics::captures` logs them.}
 *     \cgalParamType{`bool`}
 *     \cgalParamDefault{`false`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{capture_retry_cells}
 *     \cgalParamDescription{the retries' budget, in cells: where the capture leaves a cell whose
 *       scaled Jacobian is below 0.3, a cell concave for OpenFOAM or a face failing its tet
 *       decomposition and there are feature curves, the capture runs again from the same grid
 *       (without pillows if the first had them, see `feature_pillows`, then with other ratios of
 *       the feature paths' turn penalty to snap weight, 2.5, 3.75, 1.67 after the default 5) until
 *       one leaves no cell below 0.3 and no fault that checkMesh -allGeometry reports (cells
 *       concave for OpenFOAM, faces failing its tet decomposition, on the points an OpenFOAM case
 *       gets); where the capture with pillows leaves only boundary faces farther than a quarter of
 *       the surface size from the input, the one without pillows runs too. Then, where the mesh
 *       kept has a boundary face farther than a quarter of the criteria's surface size from the
 *       input (`Hex_meshing_3::boundary_fidelity()`), such a fault or a cell below 0.3 (however
 *       many), the whole mesh is made again, its captures
 *       retried as above, with the staircase's surface vertices 0.25 cell sizes from the surface,
 *       then 0.2, instead of 0.4, until one has none of them (not where the first mesh's only
 *       faults are such faces and every one stands over a part or a gap of the input thinner than
 *       two surface sizes, which no staircase resolves: `Meshing_statistics::
 *       far_faces_over_thin_parts`). Where a staircase's captures so far leave such far faces,
 *       which the other ratios do not reach, its captures with those ratios wait until the closer
 *       staircases are made, and so does its capture without pillows where the one with them
 *       also leaves a cell below 0.3; they run (on its grid, kept for them; the staircase kept
 *       first; a capture that ran ahead before it waited is not run again) only while the best
 *       mesh has a cell below 0.3 or a fault (`Hex_meshing_3::Staircase_record::
 *       weights_deferred`, `pillow_free_deferred`; not where the budget lacks room for two
 *       captures of each closer staircase and one more). Every retry counts the cells of the first capture's mesh
 *       against this budget, and runs only if they fit in what is left: a mesh of N cells gets at
 *       most budget / N retries (none above the budget), so small meshes get every retry and
 *       large ones few (elephant at diagonal / 80 with `--size 4h
 *       --thin-cells 5`, 89,500 cells: 2 retries, 29 s, against 8 and 80 s without a budget, for
 *       a minimum scaled Jacobian of 0.253 instead of 0.255). The captures of one grid are ranked
 *       by the faults left (after the first capture's removal of the buffer cells at its faults;
 *       a retry kept that has faults runs once more with the removal, outside the budget), then
 *       the cells below 0.3, the worst of them, the faces beyond a quarter surface size, the
 *       faults the removal found (each removed cell leaves a staircase face), the minimum; the
 *       meshes of the staircases by the faults left,
 *       the cells below 0.3, the faces beyond a quarter surface size, the minimum; the best is
 *       kept (deterministic). No retry with `polish_worst_cells(false)`; no retry of a grid's
 *       capture where the first leaves more than 10 cells below 0.3 (other paths do not lift that
 *       many; the closer staircases still run, and lift them on anchor and elephant at diagonal /
 *       80). 0: never. A cancellation during a retry keeps the best
 *       mesh so far. `Meshing_statistics::capture_tries`, `capture_choice`, `staircase_tries` and
 *       `staircase_gap` say what was done. A thinner buffer reaches some corners and concave
 *       curves that a thicker one does not, and loses others: on the 15 test surfaces at their
 *       test sizes, the files with no face beyond a quarter surface size go from 8 to 10
 *       (fandisk, fandisk_crack), for 1.8 times the time summed over the 15 (each of the 7 files
 *       with far faces is made two or three times); the budget changes none of them}
 *     \cgalParamType{`std::size_t`}
 *     \cgalParamDefault{200,000}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{smoothing_sweeps}
 *     \cgalParamDescription{the capture's main optimisation sweeps over the buffer's vertices at
 *       most (untangling and smoothing, before the vertices that could not stay valid are released
 *       and brought back; fewer if a sweep moves no vertex). More sweeps cost time and do not
 *       always help: on the motorBike 12 sweeps leave 471 cells below 0.3 against 405 at 8, for
 *       0.7 to 4.8 s more (two machines); on the 15 test surfaces both reach 0.3 everywhere.
 *       Values below 1 count as 1}
 *     \cgalParamType{`int`}
 *     \cgalParamDefault{8}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{visitor}
 *     \cgalParamDescription{progress and cancellation hooks (model of `HexMeshingVisitor`)}
 *     \cgalParamType{a class, or `std::reference_wrapper` of one}
 *     \cgalParamDefault{`Hex_meshing_3::Default_visitor`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 *
 * \return `Hex_meshing_3::Status::SUCCESS`, or why refinement stopped early (the mesh is valid).
 * \throws Hex_meshing_3::Input_error when the box, sizes or seed are unusable: a seed outside the
 *         box, inside a body, or in a cell cut by the surface; an empty box; sizes too small.
 */
template <typename ConcurrencyTag = Sequential_tag, typename MeshDomain, typename Criteria, typename HexMesh,
          typename CGAL_NP_TEMPLATE_PARAMETERS>
Hex_meshing_3::Status
make_hex_mesh_3(const MeshDomain& domain, const Criteria& criteria, HexMesh& out,
                const CGAL_NP_CLASS& np = parameters::default_values())
{
#ifndef CGAL_LINKED_WITH_TBB
  static_assert(!std::is_convertible<ConcurrencyTag, Parallel_tag>::value,
                "make_hex_mesh_3: Parallel_tag needs TBB (CGAL_LINKED_WITH_TBB); use Parallel_if_available_tag");
#endif
  const bool parallel = std::is_convertible<ConcurrencyTag, Parallel_tag>::value && Hex_meshing_3::internal::available_threads() > 1;
  using parameters::choose_parameter;
  using parameters::get_parameter;
  using parameters::get_parameter_reference;
  using parameters::is_default_parameter;
  namespace HNP = Hex_meshing_3::internal_np;
  typedef typename MeshDomain::Geom_traits GT;
  typedef typename GT::Point_3 Point_3;

  const std::size_t max_cells = choose_parameter(get_parameter(np, HNP::max_cells), std::size_t(-1));

  Bbox_3 box = domain.bbox();
  const double margin = CGAL::to_double(criteria.initial_size());
  box = Bbox_3(box.xmin() - margin, box.ymin() - margin, box.zmin() - margin,
               box.xmax() + margin, box.ymax() + margin, box.zmax() + margin);
  box = choose_parameter(get_parameter(np, HNP::meshing_box), box);

  std::optional<Point_3> seed;
  if constexpr(!is_default_parameter<CGAL_NP_CLASS, HNP::region_seed_t>::value)
    seed = Point_3(get_parameter(np, HNP::region_seed));

  typedef typename internal_np::Lookup_named_param_def<
      internal_np::visitor_t, CGAL_NP_CLASS, Hex_meshing_3::Default_visitor>::reference Visitor;
  Hex_meshing_3::Default_visitor default_visitor;
  Visitor visitor = choose_parameter(get_parameter_reference(np, internal_np::visitor), default_visitor);

  const bool body_fitted = choose_parameter(get_parameter(np, HNP::body_fitted), true);
  const bool polish = choose_parameter(get_parameter(np, HNP::polish_worst_cells), true);
  const std::size_t retry_cells = choose_parameter(get_parameter(np, HNP::capture_retry_cells), std::size_t(200000));
  // every retry, whatever the budget and the captures before it (the best by the same rules)
  const bool all_retries = choose_parameter(get_parameter(np, HNP::all_capture_retries), false);
  // The retries' budget: the cells of the meshes they make, together, each counted as the first
  // capture's mesh (`capture_cost`; a capture's time grows with them). A retry runs only if it fits
  // in what is left, so small meshes may run every retry and large ones fewer (elephant at
  // diagonal / 80, 89,500 cells, ran 9 captures in 80 s for a minimum scaled Jacobian of 0.253 ->
  // 0.255). The rerun of a kept retry with the removal of its OpenFOAM faults is not counted: the
  // mesh kept needs it.
  std::size_t retry_left = retry_cells, capture_cost = 0;
  // the cells below 0.3 and the minimum scaled Jacobian (a NaN counts as -1)
  auto low_cells = [](const HexMesh& mesh) {
    std::size_t below = 0;
    double worst = 1;
    std::array<typename HexMesh::Point_3, 8> p;
    for(const auto& c : mesh.hexahedra) {
      for(std::size_t k = 0; k < 8; ++k) p[k] = mesh.points[c[k]];
      double q = Hex_meshing_3::scaled_jacobian(p);
      if(!(q == q)) q = -1;
      if(q < 0.3) ++below;
      worst = (std::min)(worst, q);
    }
    return std::make_pair(below, worst);
  };
  // the boundary faces farther than a quarter of the surface size from the input: the farthest
  // point of each, and their count
  const double far_bound = 0.25 * CGAL::to_double(criteria.surface_size());
  auto far_points = [&](const HexMesh& mesh) {
    const Hex_meshing_3::Boundary_fidelity fid = Hex_meshing_3::boundary_fidelity(mesh, domain, 0);
    std::vector<std::array<double, 3>> far;
    for(const auto& d : fid.face_distances)
      if(d.first > far_bound) far.push_back(d.second);
    return far;
  };
  auto far_faces = [&](const HexMesh& mesh) { return far_points(mesh).size(); };
  // whether the input is thinner than `limit` (a part or a gap between two of its sides facing
  // each other) at the point nearest to `x`: rays both ways along the normal of its nearest
  // triangle, up to the first triangle facing it (normals within 60 degrees of opposite)
  auto thin_at = [&](const Point_3& x, double limit) {
    typedef typename GT::Vector_3 Vector_3;
    const std::size_t t = domain.closest_triangle(x);
    const auto& tr = domain.triangle(t);
    const Point_3 q = GT().construct_projected_point_3_object()(tr, x);   // (on its triangle: no second search)
    auto unit = [](const auto& tri, Vector_3& n) {
      n = CGAL::cross_product(tri[1] - tri[0], tri[2] - tri[0]);
      const double l = std::sqrt(CGAL::to_double(n.squared_length()));
      if(!(l > 0)) return false;
      n = n / l;
      return true;
    };
    Vector_3 n;
    if(!unit(tr, n)) return false;
    const double eps = 1e-7 * limit;
    for(double side : {-1.0, 1.0}) {
      const Vector_3 dir = n * side;
      Point_3 from = q + dir * eps;
      for(int k = 0; k < 8; ++k) {
        Point_3 hit;
        std::size_t ht = 0;
        if(!domain.first_ray_hit(from, dir, hit, &ht)) break;
        const double dist = std::sqrt(CGAL::to_double(CGAL::squared_distance(q, hit)));
        if(dist >= limit) break;
        Vector_3 m;
        if(ht != t && dist > 2 * eps && unit(domain.triangle(ht), m) && CGAL::to_double(n * m) < -0.5) return true;
        from = hit + dir * eps;   // (not facing it: on past it)
      }
    }
    return false;
  };
  // ... at the point nearest to `x` or to one of the six points half `limit` from it along the axes
  // (a face bridging a slot's end stands over the solid below it: the slot's walls are beside it)
  auto thin_near = [&](const std::array<double, 3>& x, double limit) {
    if(thin_at(Point_3(x[0], x[1], x[2]), limit)) return true;
    for(int a = 0; a < 3; ++a)
      for(double side : {-0.5, 0.5}) {
        std::array<double, 3> y = x;
        y[a] += side * limit;
        if(thin_at(Point_3(y[0], y[1], y[2]), limit)) return true;
      }
    return false;
  };
  // a mesh's faults, compared in order: cells concave for OpenFOAM and faces failing its tet
  // decomposition (as `checkMesh -allGeometry` counts them on the points an OpenFOAM case gets,
  // before the writer's node-by-node step, as the capture's removal sees them),
  // cells below 0.3, the minimum scaled Jacobian (negated)
  auto faults = [&](const HexMesh& mesh) {
    Hex_meshing_3::Polyhedral_mesh_3 pm;
    pm.build(mesh);
    std::size_t concave = 0;
    const auto x = Hex_meshing_3::IO::internal::foam_points(mesh, Hex_meshing_3::IO::default_hanging_bulge, &pm,
                                                            Hex_meshing_3::IO::default_max_hanging_bulge, &concave, false);
    Hex_meshing_3::OpenFOAM_geometry g;
    g.compute_cells(x, pm);
    const std::vector<char> ft = Hex_meshing_3::face_tet_errors(x, pm, g);
    const std::vector<double> det = Hex_meshing_3::cell_determinants(x, pm);
    const std::size_t small = std::size_t(std::count_if(det.begin(), det.end(), [](double d) {
      return d < Hex_meshing_3::openfoam_min_cell_determinant; }));
    const auto low = low_cells(mesh);
    return std::make_tuple(concave + small + std::size_t(std::count(ft.begin(), ft.end(), char(1))), low.first,
                           -low.second);
  };
  // The captures of one staircase are compared by (in this order) the faults left in the mesh
  // (`residual`: after the first capture's removal; none for a retry, whose faults the removal
  // takes if it is kept), the cells below 0.3, the worst of them, the boundary faces beyond a
  // quarter surface size from the input (`far`, as the staircases below count them), the faults
  // found (`found`: the buffer cells the removal takes, each leaves a staircase face at the
  // boundary), the minimum.
  // Before, the faults found came first: at t20_part at diagonal / 80 (`--size 4h --thin-cells 5`)
  // a retry with no fault and a cell at 0.024 beat the first capture with one buffer cell removed
  // and its worst cell at 0.278 (once the retries had a budget, below, and did not reach the
  // capture with one fault and no cell below 0.3); and the first capture's removal may leave a
  // fault (anchor at diagonal / 40: a concave cell).
  auto rank = [](std::size_t residual, std::size_t found, const auto& f, std::size_t far) {
    const std::size_t low = std::get<1>(f);
    return std::make_tuple(residual, low, low > 0 ? std::get<2>(f) : 0.0, far, found, std::get<2>(f));
  };
  // Other paths lift a few cells below 0.3, not many: where the first capture leaves more than
  // `max_low_cells` of them, the retries of that grid's capture are not run (the staircase
  // retries below still are: a closer staircase may lift them) (anchor at diagonal / 40: 87 cells below 0.3, four more captures took 1.5 s to 7.6 s for
  // a minimum of 0.032 -> 0.035; elephant, diagonal / 40 at the surface, --thin-cells 5: 47
  // cells, 5.7 s -> 26 s for 0.176 -> 0.192). Where they helped, the first capture left 1 to 8
  // (bunny 8: 0.176 -> 0.304; fandisk_crack 2, anchor 1 at 0.75 times the test sizes). Its
  // faults are still removed (by the first capture itself).
  const std::size_t max_low_cells = 10;
  typedef Hex_meshing_3::Feature_curves_3<GT> Features;
  std::unique_ptr<Features> own;
  const Features* features = choose_parameter(get_parameter(np, HNP::feature_curves), static_cast<const Features*>(nullptr));
  if(body_fitted && !features) {
    own = std::make_unique<Features>(domain, Hex_meshing_3::default_feature_curve_options<GT>(criteria));
    features = own.get();
  }

  // every capture and every staircase mesh, in order (`Meshing_statistics::captures`, `staircases`)
  std::vector<Hex_meshing_3::Capture_record> capture_log;
  std::vector<Hex_meshing_3::Staircase_record> staircase_log;
  auto seconds_since = [](std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  // One mesh: the grid, its staircase kept `gap` cell sizes off the surface, and its capture (with
  // the retries of `capture_retry_cells`; with a parallel tag, one of them at a time runs ahead,
  // see above).
  // the faults and far faces of the mesh `mesh_once()` kept, where its retries measured them on
  // that very mesh (the staircase retries below measure the same, and need not again)
  typedef decltype(faults(std::declval<const HexMesh&>())) Faults;
  std::optional<Faults> kept_faults;
  std::optional<std::vector<std::array<double, 3>>> kept_far;
  // which captures `mesh_once()` runs (`capture_part`): 0 all of its sequence; 1 all but those with
  // other path weights once the captures before them leave far faces, and but the one without
  // pillows too where the one with them leaves far faces and cells below 0.3 (`weights_deferred`,
  // `pillow_free_deferred` are then set: see the staircase retries below); 2 only those deferred
  // (with the one without pillows if `run_pillow_free`)
  int capture_part = 0;
  bool weights_deferred = false;
  // (with them the capture without pillows: `Staircase_record::pillow_free_deferred`; in part 2,
  // whether it runs)
  bool pillow_free_deferred = false, run_pillow_free = false;
  // A capture's choice in the sequence of `mesh_once()`: feature pillows or not, and the factors
  // of the feature paths' turn penalty and snap weight.
  struct Choice
  {
    bool pillows;
    double turn, snap;
    bool operator==(const Choice& o) const { return pillows == o.pillows && turn == o.turn && snap == o.snap; }
  };
  // A capture deferred while it ran ahead (with a parallel tag) is kept, to serve as the first of
  // the deferred captures if they are made (the same capture: the same grid, the same options), not
  // run again (`stashed`: its staircase's gap, its choice, its mesh, ...); used only where its
  // choice is the first of the deferred captures (a deferral at the weights 3.75 while they ran
  // ahead would otherwise hand them over as the weights 2.5)
  struct Stashed_capture { double gap; Choice choice; HexMesh mesh; Hex_meshing_3::Meshing_statistics stats; bool ran; double seconds; };
  std::vector<Stashed_capture> stashed;
  // the grids of the staircases whose captures were deferred, kept for them (not made again): at
  // most two, of at most a fifth and a third of the retries' budget in cells
  struct Kept_grid { double gap; HexMesh grid; Hex_meshing_3::Meshing_statistics stats; std::vector<Hex_meshing_3::Region_leak> leaks; Hex_meshing_3::Status status; };
  std::vector<Kept_grid> kept_grids;
  std::size_t closer_staircases = 0;   // (the staircases after the one `mesh_once()` makes)
  auto mesh_once = [&](double gap, HexMesh& out, Hex_meshing_3::Meshing_statistics& stats,
                       std::vector<Hex_meshing_3::Region_leak>& leaks) {
    kept_faults.reset();
    kept_far.reset();
    weights_deferred = false;
    pillow_free_deferred = false;
    Hex_meshing_3::internal::Ahead_group workers;
    std::atomic<bool> stop_ahead{false};
    Hex_meshing_3::Status status;
    const auto kept_grid = std::find_if(kept_grids.begin(), kept_grids.end(), [&](const Kept_grid& g) {
      return capture_part == 2 && g.gap == gap; });
    if(kept_grid != kept_grids.end()) {   // (the grid of a staircase whose captures were deferred)
      out = std::move(kept_grid->grid);
      stats = std::move(kept_grid->stats);
      leaks = std::move(kept_grid->leaks);
      status = kept_grid->status;
      kept_grids.erase(kept_grid);
    } else {
      Hex_meshing_3::internal::Octree_mesher_3<MeshDomain, Criteria> mesher(domain, criteria, box);
      status = mesher.run(out, max_cells, seed, visitor, body_fitted ? gap : 0.0);
      stats = mesher.statistics();
      leaks = mesher.leaks();
      mesher.release();   // the capture's memory peak need not hold the octree too
    }
    const Hex_meshing_3::Status grid_status = status;
    if(body_fitted && status != Hex_meshing_3::Status::CANCELED && out.number_of_cells() > 0) {
      visitor.on_phase_begin("capture", out.number_of_cells());
      typedef Hex_meshing_3::internal::Boundary_capture_3<HexMesh, MeshDomain, Features> Capture;
      typename Capture::Options copt;
      copt.feature_pillows = choose_parameter(get_parameter(np, HNP::feature_pillows), true);
      if(!polish) copt.polish_passes = copt.patch_iterations = 0;
      copt.passes = (std::max)(1, int(choose_parameter(get_parameter(np, HNP::smoothing_sweeps), copt.passes)));
      // The chains of grid edges that become the feature curves are shortest paths whose costs
      // weigh the distance to the curve (`snap_weight`) and turns inside a face (`turn_penalty`).
      // Where curves are dense (dirty or detailed CAD), the worst cells depend on which paths these
      // weights pick, and no one setting suits every input: on the 15 test surfaces the default
      // leaves cells below a scaled Jacobian of 0.3 in 2 files, other ratios of the weights in 2 to
      // 6 (fandisk falls to 0.03 at some). So where the first capture leaves a cell below 0.3 or a
      // fault that checkMesh -allGeometry reports (a concave cell, a face failing the tet
      // decomposition: `faults` below), the mesh is small enough (`retry_cells`) and has feature
      // curves, the capture runs again from the same grid with other ratios in turn, until one
      // leaves neither, and the mesh with the fewest faults is kept (the first capture's faults are
      // measured on every such mesh; no retry if it leaves more than 10 cells below 0.3, see
      // `max_low_cells`):
      // deterministic, at most four captures, on such meshes only (the report gives `capture_tries`
      // and `capture_choice`). (Not with `polish_worst_cells(false)`: the retries look for the
      // best polished mesh.)
      const bool may_retry = (all_retries || (out.number_of_cells() <= retry_left && retry_cells > 0)) &&
                             copt.patch_iterations > 0 && !features->curves().empty();
      // The buffer cells that checkMesh -allGeometry would still find concave or at a face failing
      // the tet decomposition are removed at the end of the capture (`Meshing_statistics::
      // foam_fault_cells`; their staircase faces become the boundary there). The first capture
      // removes them; the retries do not (another choice of paths may leave no such fault, with no
      // cell removed), and a retry kept runs once more with the removal if it has faults.
      // (`copt.remove_foam_faults`: true by default)
      //
      // The sequence of captures: with pillows (if asked), then without, with the paths' weights in
      // the ratio 5 by default, then 2.5, 3.75, 1.67. Pillows lift the worst cells along convex
      // curves (the cube 0.57 -> 0.88, anchor 0.317 -> 0.334) but leave cells below 0.3 at some
      // (cube_nonmanifold's fin, fandisk_crack): there the captures without them are kept.
      std::vector<Choice> sequence;
      if(copt.feature_pillows) sequence.push_back({true, 1, 1});
      for(const Choice& c : {Choice{false, 1, 1}, Choice{false, 1, 2}, Choice{false, 0.75, 1}, Choice{false, 1, 3}})
        sequence.push_back(c);
      if(capture_part == 2) sequence.erase(sequence.begin(), sequence.begin() + (copt.feature_pillows ? (run_pillow_free ? 1 : 2) : 1));
      // (a capture with other path weights than the first's)
      auto other_weights = [&](std::size_t choice) { return !sequence[choice].pillows && !(sequence[choice] == Choice{false, 1, 1}); };
      auto options_of = [&](std::size_t choice) {
        typename Capture::Options o = copt;
        o.feature_pillows = sequence[choice].pillows;
        o.turn_penalty *= sequence[choice].turn;
        o.snap_weight *= sequence[choice].snap;
        return o;
      };
      // a capture's record in `capture_log` (the counts: `evaluate()`)
      auto log_capture = [&](std::size_t choice, const HexMesh& mesh, double seconds, bool ahead_run) {
        Hex_meshing_3::Capture_record r;
        r.staircase_gap = gap;
        r.choice = choice;
        r.feature_pillows = sequence[choice].pillows;
        const typename Capture::Options o = options_of(choice);
        r.paths_ratio = o.snap_weight > 0 ? o.turn_penalty / o.snap_weight : 0.0;
        r.ran_ahead = ahead_run;
        r.seconds = seconds;
        r.cells = mesh.number_of_cells();
        capture_log.push_back(r);
        return capture_log.size() - 1;
      };
      auto evaluate = [&](std::size_t i, std::size_t found, const auto& f, std::size_t far) {
        Hex_meshing_3::Capture_record& r = capture_log[i];
        r.evaluated = true;
        r.far_faces = far;
        r.openfoam_faults_found = found;
        r.openfoam_faults_left = std::get<0>(f);
        r.cells_below_0_3 = std::get<1>(f);
        r.min_scaled_jacobian = -std::get<2>(f);
      };
      std::unique_ptr<HexMesh> grid;
      if(may_retry) grid = std::make_unique<HexMesh>(out);
      const Hex_meshing_3::Meshing_statistics stats0 = stats;
      // Retries run ahead (with a parallel tag, see above): while a capture runs here, the next
      // retry of the sequence runs on another thread (`ahead`); the loop below takes it if it
      // reaches that retry, else it is stopped. The domain's search tree is built before and
      // kept until they end (a capture frees it at its end).
      const bool run_ahead = parallel && may_retry;
      if(run_ahead) {
        copt.release_search_tree = false;
        domain.closest_point(Point_3(0, 0, 0));
      }
      auto retry_options = [&](std::size_t choice) {
        typename Capture::Options o = options_of(choice);
        o.remove_foam_faults = false;
        return o;
      };
      struct Ahead { Choice choice; HexMesh mesh; Hex_meshing_3::Meshing_statistics stats; bool ran; double seconds; };
      std::unique_ptr<Ahead> ahead;
      auto launch = [&](std::size_t choice) {
        if(!run_ahead || choice >= sequence.size()) return;
        ahead.reset(new Ahead{sequence[choice], *grid, stats0, false, 0.0});
        Ahead* a = ahead.get();
        const typename Capture::Options o = retry_options(choice);
        workers.run([a, o, &domain, features, &stop_ahead, seconds_since]() {
          Hex_meshing_3::internal::Ahead_visitor av{&stop_ahead};
          const auto t0 = std::chrono::steady_clock::now();
          a->ran = Capture(a->mesh, domain, features, a->stats, o).run(av);
          a->seconds = seconds_since(t0);
        });
      };
      // (what it threw, if anything, is dropped with it: the captures run here do not throw it)
      auto drop_ahead = [&]() {
        if(!ahead) return;
        stop_ahead = true;
        try { workers.wait(); } catch(...) {}
        stop_ahead = false;
        ahead.reset();
      };
      // (an exception leaving here stops it too)
      struct Ahead_guard
      {
        decltype(drop_ahead)& drop;
        ~Ahead_guard() { drop(); }
      } ahead_guard{drop_ahead};
      // (the deferred captures' first is a retry like the others: no removal of its faults, made
      // again with it if kept with faults)
      const bool first_as_retry = capture_part == 2 && may_retry;
      const auto stash = std::find_if(stashed.begin(), stashed.end(), [&](const Stashed_capture& c) {
        return first_as_retry && c.gap == gap && c.choice == sequence[0]; });
      // (none runs ahead of a capture kept from before: the loop below launches the one after
      // the next if the next runs)
      if(may_retry && stash == stashed.end()) launch(1);
      Capture first_capture(out, domain, features, stats, first_as_retry ? retry_options(0) : options_of(0));
      const auto first_t0 = std::chrono::steady_clock::now();
      bool ran;
      std::size_t kept_log;
      if(stash != stashed.end()) {   // (it ran ahead before it was deferred)
        out = std::move(stash->mesh);
        stats = std::move(stash->stats);
        ran = stash->ran;
        kept_log = log_capture(0, out, stash->seconds, true);
        stashed.erase(stash);
      } else {
        ran = first_capture.run(visitor);
        kept_log = log_capture(0, out, seconds_since(first_t0), false);
      }
      stats.capture_tries = 1;
      if(capture_cost == 0) capture_cost = (std::max)(out.number_of_cells(), std::size_t(1));
      if(ran && may_retry) {
        // the first capture's faults: those left after its removal, and those its removal found
        // (as `faults()` counts them on the same capture without the removal); its cells below
        // 0.3 and minimum after the removal
        const auto f0 = faults(out);
        std::vector<std::array<double, 3>> far_pts0 = far_points(out);
        const std::size_t far0 = far_pts0.size();
        kept_faults = f0;
        kept_far = std::move(far_pts0);
        const std::size_t found0 = first_as_retry ? std::get<0>(f0) : first_capture.foam_faults_found;
        evaluate(kept_log, found0, f0, far0);
        auto best = first_as_retry ? rank(0, found0, f0, far0) : rank(std::get<0>(f0), found0, f0, far0);
        // Where the first capture made no pillow it was the capture without them, which is not run
        // again; after one with pillows, the one without runs whatever the count of cells below 0.3,
        // and its own count decides whether the other weights are tried. It also runs where the
        // capture with pillows leaves nothing but boundary faces beyond a quarter surface size
        // (`far_faces()`): a pillow's vertices may stop short of the surface where the chain's cells
        // are small (cylinder at 0.9 times its default surface size: 46 vertices unreached along its
        // rims, 68 far faces, against none without the pillows); the other weights are not tried
        // for far faces alone (the staircase retries below are).
        const bool first_had_pillows = sequence[0].pillows && stats.pillow_cells > 0;
        if(sequence[0].pillows && !first_had_pillows) sequence.erase(sequence.begin() + 1);
        bool hopeless = std::get<1>(best) > max_low_cells && !first_had_pillows;
        for(std::size_t choice = 1; choice < sequence.size() && (all_retries || (!hopeless &&
                                    (std::get<0>(best) > 0 || std::get<1>(best) > 0 || std::get<4>(best) > 0 ||
                                     (choice == 1 && first_had_pillows && std::get<3>(best) > 0)))); ++choice) {
          // (the closer staircases first, where the budget has room for two captures of each and
          // one of these after them: elephant at 0.75 times its test size, 178,667 cells, has
          // room for one retry; the weights 2.5 lift its first capture's 3 cells below 0.3, the
          // staircase 0.25 leaves 10)
          // The capture without pillows waits too where the one with them leaves cells below 0.3
          // as well as far faces (where it leaves far faces only, they may be a pillow's vertices
          // short of the surface, which it reaches: it runs). fandisk at diagonal / 80: 39 far
          // faces and 12 cells below 0.3 with pillows at 0.4, 38 and 10 without; 36 and 15 at
          // 0.25; the mesh kept, 0.2 without pillows, the same in 4 captures instead of 6, 9.0 ->
          // 6.2 s; anchor / 80 9 -> 8 captures, 15.5 -> 13.1 s; the same meshes on the 15 test
          // files at their test sizes and 0.75 times them and on 12 at diagonal / 80. A capture
          // deferred while it ran ahead is kept for the deferred ones (`stashed`): teapot at
          // 0.75 times its test size on 2 threads 11.3 s, 13.4 s if run again, 10.4 s kept.
          if(capture_part == 1 && !all_retries && std::get<3>(best) > 0 &&
             (other_weights(choice) || (choice == 1 && first_had_pillows && std::get<1>(best) > 0)) &&
             (2 * closer_staircases + 1) * capture_cost <= retry_left) {
            weights_deferred = true;
            pillow_free_deferred = !other_weights(choice);
            if(ahead && ahead->choice == sequence[choice]) {
              try {
                workers.wait();
                stashed.push_back({gap, sequence[choice], std::move(ahead->mesh), std::move(ahead->stats), ahead->ran, ahead->seconds});
              } catch(...) {}   // (run again if the deferred captures are made: there it throws)
              ahead.reset();
            }
            break;
          }
          if(!all_retries) {
            if(capture_cost > retry_left) break;   // (the budget is spent)
            retry_left -= capture_cost;
          }
          HexMesh trial;
          Hex_meshing_3::Meshing_statistics st;
          bool ok;
          std::size_t log_i;
          if(ahead && ahead->choice == sequence[choice]) {
            workers.wait();
            trial = std::move(ahead->mesh);
            st = std::move(ahead->stats);
            ok = ahead->ran;
            log_i = log_capture(choice, trial, ahead->seconds, true);
            ahead.reset();
          } else {
            drop_ahead();
            if(all_retries || capture_cost <= retry_left) launch(choice + 1);   // (if the budget has room for it)
            trial = *grid;
            st = stats0;
            const auto t0 = std::chrono::steady_clock::now();
            ok = Capture(trial, domain, features, st, retry_options(choice)).run(visitor);
            log_i = log_capture(choice, trial, seconds_since(t0), false);
          }
          ++stats.capture_tries;
          if(!ok) { status = Hex_meshing_3::Status::CANCELED; break; }   // (the best mesh so far stays)
          const auto f = faults(trial);
          std::vector<std::array<double, 3>> far_pts = far_points(trial);
          const std::size_t far = far_pts.size();
          evaluate(log_i, std::get<0>(f), f, far);
          const auto r = rank(0, std::get<0>(f), f, far);
          if(choice == 1 && first_had_pillows) hopeless = std::get<1>(f) > max_low_cells;
          if(r < best) {
            const std::size_t tries = stats.capture_tries;
            kept_log = log_i;
            kept_faults = f;
            kept_far = std::move(far_pts);
            best = r;
            out = std::move(trial);
            stats = st;
            stats.capture_tries = tries;
            stats.capture_choice = choice;
          }
        }
        drop_ahead();
        if(status != Hex_meshing_3::Status::CANCELED && (stats.capture_choice != 0 || first_as_retry) && std::get<4>(best) > 0) {
          typename Capture::Options o = options_of(stats.capture_choice);
          o.remove_foam_faults = true;
          HexMesh trial(*grid);
          Hex_meshing_3::Meshing_statistics st = stats0;
          const std::size_t tries = stats.capture_tries + 1, choice = stats.capture_choice;
          const auto t0 = std::chrono::steady_clock::now();
          const bool rerun_ok = Capture(trial, domain, features, st, o).run(visitor);
          const std::size_t rerun_log = log_capture(choice, trial, seconds_since(t0), false);
          capture_log[rerun_log].rerun = true;
          kept_faults.reset();   // (another mesh: its buffer cells at faults removed)
          kept_far.reset();
          if(rerun_ok) {
            kept_log = rerun_log;
            out = std::move(trial);
            stats = st;
            stats.capture_choice = choice;
          } else
            status = Hex_meshing_3::Status::CANCELED;   // (the best mesh so far stays)
          stats.capture_tries = tries;
        }
      }
      drop_ahead();
      if(weights_deferred && grid) kept_grids.push_back({gap, std::move(*grid), stats0, leaks, grid_status});
      if(ran) capture_log[kept_log].kept = true;
      if(run_ahead) domain.release_search_tree();
      if(!ran) status = Hex_meshing_3::Status::CANCELED;
      visitor.on_phase_end("capture");
      stats.kept_cells = out.number_of_cells();
    }
    return status;
  };

  // The staircase keeps its surface vertices `gaps[0]` cell sizes off the surface. Where the mesh
  // that gives is small enough for the retries (`capture_retry_cells`) and has a boundary face
  // farther than a quarter of the surface size from the input (`far_faces()`) or a cell below 0.3
  // (however many: `max_low_cells` stops the weight retries of one grid, not these), the whole
  // mesh is made again with the staircase closer to the surface, `gaps[1]` then `gaps[2]`, until
  // one has none of them nor an OpenFOAM fault; the mesh with the fewest faults, then cells below
  // 0.3, then far faces, then the highest minimum is kept. A
  // thinner buffer layer reaches some corners and concave curves a thicker one does not, and
  // loses others: on the 15 test surfaces no one gap leaves the fewest far faces on all of them
  // (fandisk 6 / 0 / 0 far faces at 0.4 / 0.25 / 0.2, fandisk_crack 4 / 1 / 0, elephant 46 / 42 /
  // 49, teapot 75 / 96 / 135 with 23 cells below 0.3 at 0.25). Until stop 54 a mesh with more
  // than `max_low_cells` cells below 0.3 was not made again: on the suite's inputs at diagonal /
  // 40 and / 80 that kept anchor at 0.036 (/40) and 0.124 (/80), elephant at 0.090 (/80) and
  // fandisk_crack at 0.203 (/80), where the closer staircases give 0.096, 0.350 (and a boundary
  // fidelity 6 times better), 0.282 and 0.251, for 3 to 15 s more each (the suite's hexmesh
  // seconds 625 -> 785 summed).
  static constexpr double gaps[] = {0.4, 0.25, 0.2};
  std::vector<Hex_meshing_3::Region_leak> leaks;
  Hex_meshing_3::Meshing_statistics stats;
  // (a staircase mesh's record: its gap, its captures, its time)
  auto log_staircase = [&](double gap, std::size_t captures_before, std::chrono::steady_clock::time_point t0) {
    Hex_meshing_3::Staircase_record r;
    r.gap = gap;
    r.captures = capture_log.size() - captures_before;
    r.seconds = seconds_since(t0);
    staircase_log.push_back(r);
  };
  const auto first_t0 = std::chrono::steady_clock::now();
  capture_part = 1;
  closer_staircases = std::size(gaps) - 1;
  Hex_meshing_3::Status status = mesh_once(gaps[0], out, stats, leaks);
  if(body_fitted) {
    log_staircase(gaps[0], 0, first_t0);
    staircase_log.back().weights_deferred = weights_deferred;
    staircase_log.back().pillow_free_deferred = pillow_free_deferred;
  }
  std::size_t kept_staircase = 0;
  stats.staircase_tries = 1;
  stats.staircase_gap = gaps[0];
  // (`capture_cost` is 0 where no capture ran; where the budget left has no room for another
  // mesh, its far faces and faults are not counted)
  if(body_fitted && polish && capture_cost > 0 && (all_retries || (retry_cells > 0 && capture_cost <= retry_left)) &&
     status != Hex_meshing_3::Status::CANCELED && out.number_of_cells() > 0) {
    // faults, cells below 0.3, far faces (`far`), minimum scaled Jacobian (negated)
    // (the faults `mesh_once()` measured on the mesh it kept, if it did)
    auto score = [&](const HexMesh& mesh, std::size_t far) {
      const auto f = kept_faults ? *kept_faults : faults(mesh);
      return std::make_tuple(std::get<0>(f), std::get<1>(f), far, std::get<2>(f));
    };
    auto kept_far_points = [&](const HexMesh& mesh) { return kept_far ? *kept_far : far_points(mesh); };
    // (the cheap counts first: a mesh with no cell below 0.3 and no far face is kept without
    // counting its OpenFOAM faults, which its capture removed: anchor at its test size 5.25 ->
    // 5.05 s, against 4.8 s without the staircase retries)
    const std::vector<std::array<double, 3>> far_pts0 = kept_far_points(out);
    const std::size_t far0 = far_pts0.size();
    const auto low0 = kept_faults ? std::make_pair(std::get<1>(*kept_faults), -std::get<2>(*kept_faults)) : low_cells(out);
    const bool clean = far0 == 0 && low0.first == 0;
    auto best = clean ? std::make_tuple(std::size_t(0), std::size_t(0), std::size_t(0), -low0.second) : score(out, far0);
    auto evaluate = [&](Hex_meshing_3::Staircase_record& r, const decltype(best)& sc) {
      r.evaluated = true;
      r.openfoam_faults = std::get<0>(sc);
      r.cells_below_0_3 = std::get<1>(sc);
      r.far_faces = std::get<2>(sc);
      r.min_scaled_jacobian = -std::get<3>(sc);
    };
    evaluate(staircase_log.front(), best);
    // Where the mesh's only fault is far faces and every one of them stands over a part or a gap
    // of the input thinner than two surface sizes (`thin_near()`), the closer staircases are not
    // made: no staircase resolves such a part (that is the job of `thin_part_cells`). fin_slot at
    // diagonal / 80 (its slot and fin 0.01 wide, cells of 0.0197): 4 far faces at the slot's end
    // whatever the staircase, 8.7 s -> 3.1 s; at / 40 one of its 61 far faces is not over the slot
    // and the closer staircases run (48 far faces at 0.2).
    const double thin_limit = 2 * CGAL::to_double(criteria.surface_size());
    const bool thin_only = !clean && std::get<0>(best) == 0 && std::get<1>(best) == 0 && far0 > 0 && !all_retries &&
                           std::all_of(far_pts0.begin(), far_pts0.end(), [&](const auto& x) { return thin_near(x, thin_limit); });
    stats.far_faces_over_thin_parts = thin_only;
    std::size_t tries = 1, choice = 0;
    // another mesh, with the staircase `gaps[k]` and the captures `part` of `mesh_once()`, the
    // best kept; false if it was cancelled (the best mesh so far stays)
    auto another_mesh = [&](std::size_t k, int part) {
      HexMesh trial;
      Hex_meshing_3::Meshing_statistics st;
      std::vector<Hex_meshing_3::Region_leak> lk;
      const std::size_t before = capture_log.size();
      const auto t0 = std::chrono::steady_clock::now();
      capture_part = part;
      closer_staircases = std::size(gaps) - 1 - k;
      const Hex_meshing_3::Status s = mesh_once(gaps[k], trial, st, lk);
      log_staircase(gaps[k], before, t0);
      staircase_log.back().weights_deferred = weights_deferred;
      staircase_log.back().pillow_free_deferred = pillow_free_deferred;
      staircase_log.back().deferred_weights = part == 2;
      ++tries;
      if(s == Hex_meshing_3::Status::CANCELED) { status = s; return false; }
      if(trial.number_of_cells() == 0) return true;
      const auto sc = score(trial, kept_far_points(trial).size());
      evaluate(staircase_log.back(), sc);
      if(sc < best) {
        best = sc; out = std::move(trial); stats = st; leaks = std::move(lk); status = s; choice = k;
        kept_staircase = staircase_log.size() - 1;
      }
      return true;
    };
    for(std::size_t k = 1; k < std::size(gaps) && !thin_only && (all_retries ||
                           (std::get<0>(best) > 0 || std::get<1>(best) > 0 || std::get<2>(best) > 0)); ++k) {
      // (the budget: its first capture is counted here, its retries in `mesh_once()`)
      if(!all_retries) {
        if(capture_cost > retry_left) break;
        retry_left -= capture_cost;
      }
      // (the closest staircase's weights are not deferred)
      if(!another_mesh(k, k + 1 < std::size(gaps) ? 1 : 0)) break;
    }
    // The captures with other path weights lift cells below 0.3 and OpenFOAM faults, not far
    // faces: a staircase whose captures left far faces made the closer staircases before them
    // (`capture_part` 1; so did the capture without pillows, where the one with them left cells
    // below 0.3 too). If the mesh kept has cells below 0.3 or faults, they are made now on the
    // grids of those staircases (`kept_grids`), the one kept first, then the others in order,
    // while the best mesh has such cells and the budget has room. (fandisk at diagonal / 80: its
    // 38 far faces at 0.4 are there whatever the weights, which took 4 captures before the
    // closer staircases; the mesh kept, at 0.2, the same, 12.6 -> 8.7 s.) (Only after the three
    // staircases: the loop above stops early only where the mesh has neither, or the budget is
    // spent.)
    std::vector<std::pair<std::size_t, bool>> deferred;   // (their places in `gaps`, and whether without pillows too)
    for(std::size_t i = 0; i < staircase_log.size(); ++i)
      if(staircase_log[i].weights_deferred)
        deferred.push_back({std::size_t(std::find(std::begin(gaps), std::end(gaps), staircase_log[i].gap) - std::begin(gaps)),
                            staircase_log[i].pillow_free_deferred});
    std::stable_partition(deferred.begin(), deferred.end(), [&](const auto& d) { return d.first == choice; });
    for(const auto& [k, pillow_free] : deferred) {
      if(status == Hex_meshing_3::Status::CANCELED || all_retries || !(std::get<0>(best) > 0 || std::get<1>(best) > 0) ||
         capture_cost > retry_left)
        break;
      retry_left -= capture_cost;
      run_pillow_free = pillow_free;
      const bool ok = another_mesh(k, 2);
      run_pillow_free = false;
      if(!ok) break;
    }
    stats.staircase_tries = tries;
    stats.staircase_gap = gaps[choice];
  }
  if(!staircase_log.empty()) staircase_log[kept_staircase].kept = true;
  stats.captures = std::move(capture_log);
  stats.staircases = std::move(staircase_log);
  if constexpr(!is_default_parameter<CGAL_NP_CLASS, HNP::leaks_t>::value) {
    auto it = get_parameter(np, HNP::leaks);
    for(const Hex_meshing_3::Region_leak& l : leaks) *it++ = l;
  }
  if constexpr(!is_default_parameter<CGAL_NP_CLASS, HNP::statistics_t>::value)
    *get_parameter(np, HNP::statistics) = stats;
  return status;
}

} // namespace CGAL

#endif // CGAL_MAKE_HEX_MESH_3_H
