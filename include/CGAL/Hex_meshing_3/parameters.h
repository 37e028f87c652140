// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_PARAMETERS_H
#define CGAL_HEX_MESHING_3_PARAMETERS_H

// The package's own named parameters. In CGAL 5.5 the names that chain with `.` are CGAL's fixed
// list; ours are declared here through a pack class that *is* a CGAL pack, so that our entry
// points read them with CGAL's `get_parameter()` and forward CGAL's own names unchanged.
//
//   namespace HP = CGAL::Hex_meshing_3::parameters;
//   CGAL::make_hex_mesh_3(domain, criteria, mesh, HP::max_cells(2000000).region_seed(p));
//   auto np = HP::combine(CGAL::parameters::visitor(std::ref(v)), HP::max_cells(500000));

#include <CGAL/Named_function_parameters.h>

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal_np {
enum max_cells_t { max_cells };
enum region_seed_t { region_seed };
enum meshing_box_t { meshing_box };
enum leaks_t { leaks };
enum statistics_t { statistics };
enum body_fitted_t { body_fitted };
enum feature_curves_t { feature_curves };
enum feature_pillows_t { feature_pillows };
enum polish_worst_cells_t { polish_worst_cells };
enum capture_retry_cells_t { capture_retry_cells };
enum all_capture_retries_t { all_capture_retries };
enum smoothing_sweeps_t { smoothing_sweeps };
} // namespace internal_np

/// \cond SKIP_IN_MANUAL
template <typename T, typename Tag, typename Base = CGAL::internal_np::No_property>
struct Named_parameters : CGAL::Named_function_parameters<T, Tag, Base>
{
  using CGAL::Named_function_parameters<T, Tag, Base>::Named_function_parameters;

  template <typename V>
  Named_parameters<V, internal_np::max_cells_t, Named_parameters>
  max_cells(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::region_seed_t, Named_parameters>
  region_seed(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::meshing_box_t, Named_parameters>
  meshing_box(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::leaks_t, Named_parameters>
  leaks(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::statistics_t, Named_parameters>
  statistics(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::body_fitted_t, Named_parameters>
  body_fitted(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::feature_curves_t, Named_parameters>
  feature_curves(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::feature_pillows_t, Named_parameters>
  feature_pillows(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::polish_worst_cells_t, Named_parameters>
  polish_worst_cells(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::capture_retry_cells_t, Named_parameters>
  capture_retry_cells(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::all_capture_retries_t, Named_parameters>
  all_capture_retries(const V& v) const { return { v, *this }; }

  template <typename V>
  Named_parameters<V, internal_np::smoothing_sweeps_t, Named_parameters>
  smoothing_sweeps(const V& v) const { return { v, *this }; }
};
/// \endcond

namespace parameters {

/// stop refining before the mesh would exceed this many cells (`std::size_t`)
template <typename V>
Named_parameters<V, internal_np::max_cells_t> max_cells(const V& v) { return { v }; }

/// mesh the region reached from this point without crossing the surface (a `Point_3`),
/// instead of the inside of the surface
template <typename V>
Named_parameters<V, internal_np::region_seed_t> region_seed(const V& v) { return { v }; }

/// the box to mesh (a `CGAL::Bbox_3`), honoured exactly, instead of the domain's bounding box
/// grown by one cell size on every side
template <typename V>
Named_parameters<V, internal_np::meshing_box_t> meshing_box(const V& v) { return { v }; }

/// an output iterator receiving the `Region_leak`s of a seeded region (largest first)
template <typename V>
Named_parameters<V, internal_np::leaks_t> leaks(const V& v) { return { v }; }

/// a pointer to a `Meshing_statistics` that receives the counts of the run
template <typename V>
Named_parameters<V, internal_np::statistics_t> statistics(const V& v) { return { v }; }

/// `false`: keep the staircase of grid faces as the boundary (no buffer layer, no projection)
template <typename V>
Named_parameters<V, internal_np::body_fitted_t> body_fitted(const V& v) { return { v }; }

/// the feature curves the boundary must follow (a pointer to a `Feature_curves_3`), instead of the
/// ones `Feature_curves_3` finds with its default options (30 degrees)
template <typename V>
Named_parameters<V, internal_np::feature_curves_t> feature_curves(const V& v) { return { v }; }

/// `true`: the chains of convex sharp curves get a sheet of hexahedra along them (see
/// `make_hex_mesh_3()`); experimental, off by default
template <typename V>
Named_parameters<V, internal_np::feature_pillows_t> feature_pillows(const V& v) { return { v }; }

/// `false` skips the capture's last step, the polish of the cells below 0.35 (see
/// `make_hex_mesh_3()`); on by default
template <typename V>
Named_parameters<V, internal_np::polish_worst_cells_t> polish_worst_cells(const V& v) { return { v }; }

/// the capture runs again with other weights of the feature paths where it leaves a cell below
/// 0.3, a cell concave for OpenFOAM or a face failing its tet decomposition, on meshes of at most
/// this many cells (`std::size_t`; see `make_hex_mesh_3()`); 0: never;
/// 200,000 by default
template <typename V>
Named_parameters<V, internal_np::capture_retry_cells_t> capture_retry_cells(const V& v) { return { v }; }

/// every retry of `capture_retry_cells` is run, whatever the budget and however good the captures
/// before it: every capture of the sequence at each of the three staircases (up to 18 captures),
/// the best kept by the same rules (`bool`; see `make_hex_mesh_3()`); false by default
template <typename V>
Named_parameters<V, internal_np::all_capture_retries_t> all_capture_retries(const V& v) { return { v }; }

/// the capture's main optimisation sweeps over the buffer's vertices at most (`int`, >= 1; see
/// `make_hex_mesh_3()`); 8 by default
template <typename V>
Named_parameters<V, internal_np::smoothing_sweeps_t> smoothing_sweeps(const V& v) { return { v }; }

/// \cond SKIP_IN_MANUAL
template <typename NP> NP combine(const NP& np) { return np; }

template <typename NP, typename V, typename Tag, typename Base, typename... Rest>
auto combine(const NP& np, const CGAL::Named_function_parameters<V, Tag, Base>& head,
             const Rest&... rest)
{
  return combine(CGAL::Named_function_parameters<V, Tag, NP>(
                   CGAL::parameters::get_parameter_reference(head, Tag{}), np),
                 rest...);
}
/// \endcond

} // namespace parameters
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_PARAMETERS_H
