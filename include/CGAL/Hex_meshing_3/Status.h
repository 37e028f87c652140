// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_STATUS_H
#define CGAL_HEX_MESHING_3_STATUS_H

#include <CGAL/Bbox_3.h>

#include <array>
#include <vector>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

namespace CGAL {
namespace Hex_meshing_3 {

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief what `make_hex_mesh_3()` returns.
 */
enum class Status
{
  SUCCESS = 0,          ///< every criterion is met; the mesh is complete
  CANCELED,             ///< the visitor asked to stop: the mesh is valid but coarser
  CELL_LIMIT_REACHED,   ///< refinement stopped before exceeding `max_cells`: valid, coarser mesh
  INVALID_INPUT         ///< the domain, criteria or options are unusable; see `Input_error`
};

/// \brief a short English name of a status (`"SUCCESS"`, `"CANCELED"`, ...).
inline const char* status_name(Status s)
{
  switch(s) {
    case Status::SUCCESS: return "SUCCESS";
    case Status::CANCELED: return "CANCELED";
    case Status::CELL_LIMIT_REACHED: return "CELL_LIMIT_REACHED";
    case Status::INVALID_INPUT: return "INVALID_INPUT";
  }
  return "UNKNOWN";
}

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief why an `Input_error` was thrown.
 */
enum class Input_error_cause
{
  MALFORMED,       ///< the file does not follow its format (garbage, a bad keyword or number)
  UNREADABLE,      ///< the file cannot be opened or read
  EMPTY,           ///< the file is empty
  TRUNCATED,       ///< the file ends before its content does (or a gzip stream is cut)
  NON_FINITE,      ///< a coordinate is NaN or infinite
  BAD_INDEX,       ///< a face refers to a vertex that does not exist
  UNSUPPORTED,     ///< a format or variant the readers do not support
  NO_SURFACE,      ///< no usable triangle (no face, only degenerate ones, or all inside the volume)
  BAD_SEED,        ///< the region seed is outside the box, inside a body, or in a cut cell
  BAD_PARAMETER    ///< a size, box, level or scale that cannot be used
};

/// \brief a short name of a cause (`"truncated"`, `"bad_seed"`, ...)
inline const char* cause_name(Input_error_cause c)
{
  switch(c) {
    case Input_error_cause::MALFORMED: return "malformed";
    case Input_error_cause::UNREADABLE: return "unreadable";
    case Input_error_cause::EMPTY: return "empty";
    case Input_error_cause::TRUNCATED: return "truncated";
    case Input_error_cause::NON_FINITE: return "non_finite";
    case Input_error_cause::BAD_INDEX: return "bad_index";
    case Input_error_cause::UNSUPPORTED: return "unsupported";
    case Input_error_cause::NO_SURFACE: return "no_surface";
    case Input_error_cause::BAD_SEED: return "bad_seed";
    case Input_error_cause::BAD_PARAMETER: return "bad_parameter";
  }
  return "unknown";
}

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief thrown for input the package cannot use: an unreadable, empty, truncated or malformed
 * surface file, a non-finite coordinate, a region seed outside the box or inside a body, a box
 * that cannot hold the requested sizes. `what()` is a one-line message naming the file (when there
 * is one) and the cause; `cause()` says which kind of problem it is.
 */
class Input_error : public std::runtime_error
{
public:
  explicit Input_error(const std::string& what, Input_error_cause cause = Input_error_cause::MALFORMED)
    : std::runtime_error(what), m_cause(cause) {}
  Input_error_cause cause() const { return m_cause; }

private:
  Input_error_cause m_cause;
};

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief one boundary capture run by `make_hex_mesh_3()` (`Meshing_statistics::captures`): its
 * staircase, its settings, what it cost and, where the retries may run, what it left.
 */
struct Capture_record
{
  double staircase_gap = 0.4;        ///< the staircase's distance from the surface, in cell sizes
  std::size_t choice = 0;            ///< its place in the sequence of captures (as `Meshing_statistics::capture_choice`)
  bool feature_pillows = false;      ///< asked for pillows along convex feature curves
  double paths_ratio = 0;            ///< the feature paths' ratio of turn penalty to snap weight
  bool rerun = false;                ///< the kept retry made again with the removal of its OpenFOAM faults
  bool ran_ahead = false;            ///< run on another thread while the one before it ran
  double seconds = 0;                ///< wall seconds of the capture (on its own thread)
  std::size_t cells = 0;             ///< cells of the mesh it gave
  bool evaluated = false;            ///< the counts below were computed (where retries may follow)
  std::size_t openfoam_faults_found = 0;   ///< cells concave for OpenFOAM, faces failing its tet decomposition, cells of small determinant, before any removal
  std::size_t openfoam_faults_left = 0;    ///< the same, left in the mesh (the first capture removes its faults, retries do not)
  std::size_t cells_below_0_3 = 0;   ///< cells below a scaled Jacobian of 0.3
  double min_scaled_jacobian = 0;    ///< the minimum scaled Jacobian
  std::size_t far_faces = 0;         ///< boundary faces farther than a quarter of the surface size from the input
  bool kept = false;                 ///< the capture kept for its staircase (`rerun` replaces it where there is one)
};

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief one mesh made by `make_hex_mesh_3()` with its staircase at a given distance from the
 * surface (`Meshing_statistics::staircases`), as the staircase retries compared them.
 */
struct Staircase_record
{
  double gap = 0.4;                  ///< the staircase's distance from the surface, in cell sizes
  std::size_t captures = 0;          ///< the captures run for it (reruns included)
  bool evaluated = false;            ///< the counts below were computed (where staircase retries may follow)
  std::size_t far_faces = 0;         ///< boundary faces farther than a quarter of the surface size from the input
  std::size_t openfoam_faults = 0;   ///< the faults OpenFOAM's checks would find, as for `Capture_record` (not counted, 0, where none of the others is found)
  std::size_t cells_below_0_3 = 0;   ///< cells below a scaled Jacobian of 0.3
  double min_scaled_jacobian = 0;    ///< the minimum scaled Jacobian
  double seconds = 0;                ///< wall seconds from its grid to its kept capture
  bool kept = false;                 ///< the mesh returned
  bool weights_deferred = false;     ///< its captures with other path weights were left until the closer staircases were made (its captures so far left boundary faces beyond a quarter surface size, which those weights do not reach)
  bool pillow_free_deferred = false; ///< so was its capture without the feature pillows (the capture with them left cells below 0.3 as well as those far faces)
  bool deferred_weights = false;     ///< this mesh is those captures (with the one without pillows where it was deferred), made after the closer staircases on this staircase's grid
};

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief what `make_hex_mesh_3()` did, for reports (named parameter `statistics`).
 */
struct Meshing_statistics
{
  std::array<std::uint32_t, 3> initial_cells = {{0, 0, 0}};   ///< cells of the initial grid per axis
  std::size_t leaves = 0;              ///< leaf cells of the balanced grid
  std::size_t cut_leaves = 0;          ///< of which cut by the surface
  std::size_t balance_splits = 0;      ///< cells split by the 2:1 balance
  std::size_t components = 0;          ///< connected components of uncut leaves
  std::size_t trimmed_cells = 0;       ///< kept cells removed by trimming (one cell thick; in a seeded region body-fitted, plates stay)
  std::size_t disconnected_cells = 0;  ///< seeded region: cells cut off from the seed by trimming
  std::size_t kept_cells = 0;          ///< cells of the mesh
  int max_level_reached = 0;           ///< the finest level of the grid
  // body-fitted boundary (see `make_hex_mesh_3()`, named parameter `body_fitted`)
  std::size_t staircase_removed_cells = 0;  ///< cells removed to make room for the buffer layer or a manifold staircase
  std::size_t too_close_vertices = 0;       ///< staircase vertices found too close to the surface (all rounds)
  std::size_t non_manifold_vertices = 0;    ///< staircase vertices found non-manifold (all rounds)
  std::size_t buffer_cells = 0;             ///< hexahedra of the buffer layer (pillows included)
  std::size_t pillow_cells = 0;             ///< of which in the pillows along convex feature curves (one per chain edge, one per corner of three)
  std::size_t surface_vertices = 0;         ///< buffer vertices placed on the surface
  std::size_t curve_vertices = 0;           ///< of which on feature curves
  std::size_t corner_vertices = 0;          ///< of which on corners
  std::size_t cap_vertices = 0;             ///< buffer vertices over holes of the input (not projected; those at a two-sided sheet's border that reached it are not counted)
  std::size_t curves_captured = 0;          ///< feature curves followed by a chain of mesh edges
  std::size_t curves_missed = 0;            ///< feature curves no chain was found for
  std::size_t curve_gaps = 0;               ///< ends of captured curves left 1.5 cells short (walled in by other curves at a corner, even when the curves left short or missed are searched first)
  std::size_t corner_edge_searches = 0;     ///< captures whose feature paths were searched again with the corners' edges kept for the curves leaving along them (a chain had taken another curve's edge), and kept
  std::size_t optimisation_passes = 0;      ///< sweeps of the untangling / smoothing
  std::size_t removed_buffer_cells = 0;     ///< buffer cells that stayed invalid, removed (the staircase face is the boundary there)
  std::size_t unsnapped_vertices = 0;       ///< curve/corner vertices returned to the surface, or released into the volume, to untangle cells (they are brought back towards their feature afterwards, as far as their cells allow)
  std::size_t feature_joint_moves = 0;      ///< of the `unsnapped_vertices`, those put back on their curve or corner in a joint move (their neighbours making room, no cell below min(its quality, 0.35)); not counted in `unsnapped_vertices` any more
  std::size_t face_split_repairs = 0;       ///< vertex moves of the repairs of faces none of whose diagonal splits was valid for OpenFOAM (the face-split repair and the unfolding after the repairs and after the polish)
  std::size_t non_orthogonality_repairs = 0;   ///< vertex moves that lowered the non-orthogonality of faces beyond 50 degrees
  std::size_t polish_moves = 0;   ///< vertex moves of the final polish that raised the worst cells (below 0.35)
  std::size_t fidelity_moves = 0; ///< vertex moves after the polish (within its guards) that lowered by 2 % the largest distance to the surface of the centres of the vertex's boundary faces (relative to their local sizes; the faces of the hanging nodes it moves included), where it was beyond 0.2 (other faces of the vertex may get farther, not beyond that largest)
  std::size_t turn_moves = 0;     ///< moves of the vertices where a feature chain turns inside a face towards their curve, within the polish's guards (`Boundary_capture_3::turn_polish()`)
  std::size_t turn_far_moves = 0; ///< of which made after the others, for a top face standing more than a quarter of the local size off the surface, with the guards' floor at 0.32 instead of 0.35
  std::size_t polish_patches = 0; ///< the polish's joint moves kept: patches around a cell below 0.3 whose worst cell got better
  std::size_t loosened_vertices = 0;   ///< curve/corner vertices of a cell below 0.3 that left their feature in a joint move kept (surface vertices since, within 0.2 / 0.1 local sizes of their curve / corner); `curve_vertices` and `corner_vertices` still count them
  std::size_t capture_tries = 0;            ///< boundary captures run (see `make_hex_mesh_3()`: more than one where the first left cells below a scaled Jacobian of 0.3, a cell concave for OpenFOAM or a face failing its tet decomposition)
  std::size_t capture_choice = 0;           ///< the one kept, in the sequence of captures: with feature pillows if asked (the default), then without, the feature paths' ratio of turn penalty to snap weight 5, then 2.5, 3.75, 1.67 (0: the first capture; where it had pillows, 1 is the default weights without them, else the captures without pillows are not run twice and 1 is the ratio 2.5)
  std::size_t staircase_tries = 1;          ///< meshes made with the staircase at another distance from the surface (see `make_hex_mesh_3()`, `capture_retry_cells`: more than one where the first had a boundary face farther than a quarter of the surface size from the input or a cell below 0.3); `capture_tries` counts the captures of the one kept
  double staircase_gap = 0.4;               ///< the kept mesh's staircase distance from the surface, in cell sizes (0.4, then 0.25, 0.2)
  bool far_faces_over_thin_parts = false;   ///< the first mesh's only faults were boundary faces beyond a quarter surface size, all over parts or gaps of the input thinner than two surface sizes: the closer staircases were not made
  std::size_t split_warp_repairs = 0;       ///< vertex moves of the repair of warped faces split in four (concave for OpenFOAM)
  std::size_t concave_repairs = 0;          ///< vertex moves of the repair of cells at or near OpenFOAM's concave test, last in the polish
  std::size_t skewed_faces = 0;             ///< faces skewed beyond 3.5 found (the buffer cells at them removed)
  std::size_t non_orthogonal_faces = 0;     ///< faces non-orthogonal beyond 70 degrees found after the repairs (the buffer cells at them removed)
  std::size_t foam_fault_cells = 0;         ///< buffer cells found concave, or at a face failing the tet decomposition, as checkMesh -allGeometry finds them on the OpenFOAM export (removed; `make_hex_mesh_3()`)
  /// surface vertices released into the volume to keep every cell valid (they miss the surface)
  std::vector<std::array<double, 3>> unreached_vertices;
  /// where the `unsnapped_vertices` are at the end of the optimisation: curve and corner vertices
  /// that did not get back onto their feature (the feature is lost there)
  std::vector<std::array<double, 3>> unsnapped_at;
  /// the centres (vertex averages) of the `removed_buffer_cells`, where the staircase face is the
  /// boundary (its corners stand off the surface)
  std::vector<std::array<double, 3>> removed_buffer_cell_centres;
  /// where a feature chain turns inside a face (two of its edges in a row): the middle vertex is
  /// left off the curve, which crosses that face along its diagonal (final positions)
  std::vector<std::array<double, 3>> curve_turns;
  /// a point (the middle vertex) of each feature curve no chain was found for
  std::vector<std::array<double, 3>> missed_curves;
  /// wall seconds of each step of the boundary capture, in order (`"buffer"`, `"twins"`,
  /// `"features"`, `"regions"`, `"optimise"`, `"repairs"`, `"polish"`, `"cleanup"`)
  std::vector<std::pair<std::string, double>> capture_seconds;
  /// wall seconds of the parts of the longer steps, in order, named `"step.part"`: the
  /// optimisation's `"sweeps"`, `"untangle"` (the unsnapping and releases), `"final_sweeps"`,
  /// `"reattach"` (the rounds back to the surface), `"joint_moves"`; the polish's `"sweeps"`,
  /// `"patches"`, `"second_sweeps"`, `"second_patches"`, `"fidelity"`, `"turns"`, `"unfold"`; the
  /// cleanup's `"removal"` (of the invalid buffer cells) and `"checks"` (the rounds checking the
  /// faces and cells as OpenFOAM will). A part that did not run is missing; the parts of a step
  /// sum to at most its time.
  std::vector<std::pair<std::string, double>> capture_substep_seconds;
  /// every boundary capture run, in order (the retries' search: which settings ran, what each
  /// cost and left; see `make_hex_mesh_3()`); the statistics above are the kept capture's
  std::vector<Capture_record> captures;
  /// every mesh made with its staircase at a distance from the surface, in order
  std::vector<Staircase_record> staircases;
};

/*!
 * \ingroup PkgHexMeshing3Functions
 * \brief a leak of a seeded region: cells the flood fill from the seed reached (through a hole or
 * a crack of the surface wider than the cells) but that the winding number puts inside a body.
 *
 * The winding number decides: these cells are not meshed. `passage` bounds the grid faces across
 * which the flood entered the leak (the faces between the leak and the cells that stay), which is
 * where the hole is.
 */
struct Region_leak
{
  std::size_t cells = 0;            ///< cells of the leak
  double volume = 0;                ///< their volume
  Bbox_3 bbox;                      ///< bounding box of the leak's cells
  Bbox_3 passage;                   ///< bounding box of the faces between the leak and the region
  std::size_t passage_faces = 0;    ///< number of those faces
  double passage_area = 0;          ///< their area
  double max_winding_number = 0;    ///< the largest winding number at a leak cell's centre
  std::size_t cut_off_cells = 0;    ///< region cells reachable from the seed only through this leak (removed too)
  double cut_off_volume = 0;        ///< their volume
};

} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_STATUS_H
