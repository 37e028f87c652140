/*!
\ingroup PkgHexMeshing3Concepts
\cgalConcept

The concept `HexMeshingVisitor` describes the progress and cancellation hooks of
`CGAL::make_hex_mesh_3()`, passed with the named parameter `visitor` (as
`CGAL::parameters::visitor(std::ref(v))` to keep the visitor's state).

The mesher runs these phases, in order: `"refine"`, `"balance"`, `"classify"`, `"prepare"` (room
for the buffer layer), `"extract"` and `"capture"` (buffer layer, projection, feature snapping,
optimisation); the body-fitted ones only with `body_fitted(true)`, the default.
It polls `go_further()` during refinement once per batch of cells (never once per cell) and after
each level, and after each optimisation sweep of the capture. When `go_further()` returns
`false` during refinement, refinement stops at the next safe point; the mesher still balances,
classifies and extracts (the boundary is then the staircase), so the mesh it returns is valid,
only coarser. During the capture, the optimisation sweeps stop, and the steps that make every
cell valid still run. The status is `CGAL::Hex_meshing_3::Status::CANCELED` in both cases.

The hooks are called from the thread that called `CGAL::make_hex_mesh_3()`.

\cgalHasModelsBegin
\cgalHasModels{`CGAL::Hex_meshing_3::Default_visitor`}
\cgalHasModelsEnd

\sa `CGAL::make_hex_mesh_3()`
*/
class HexMeshingVisitor
{
public:
  /// \name Operations
  /// @{

  /// a phase starts; `work` is an estimate of the number of cells it will visit (0 if unknown)
  void on_phase_begin(const char* name, std::size_t work);

  /// the phase `name` ended
  void on_phase_end(const char* name);

  /// `fraction_done`, in [0,1], is the progress of the current phase; returns `false` to cancel
  bool go_further(double fraction_done);

  /// @}
};
