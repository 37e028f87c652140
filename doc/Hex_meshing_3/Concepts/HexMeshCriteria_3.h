/*!
\ingroup PkgHexMeshing3Concepts
\cgalConcept

The concept `HexMeshCriteria_3` describes the refinement criteria of `CGAL::make_hex_mesh_3()`:
the size that sets the initial grid, the deepest refinement level, and a test that says whether a
cell must be split.

The mesher builds an initial grid of \f$ n_a = \lceil L_a / s \rceil \f$ cells along each axis
\f$ a \f$ of the meshing box, where \f$ L_a \f$ is the box's length along \f$ a \f$ and
\f$ s \f$ is `initial_size()`. Then, level by level, it asks the criteria about every leaf cell of
the level and splits (1 into 8) every cell they call bad, never beyond `max_level()`.

\cgalHasModelsBegin
\cgalHasModels{`CGAL::Hex_mesh_criteria_3<GeomTraits>`}
\cgalHasModelsEnd

\sa `CGAL::make_hex_mesh_3()`
\sa `HexMeshDomain_3`
*/
class HexMeshCriteria_3
{
public:
  /// \name Types
  /// @{

  /// the number type of the domain's `Geom_traits`
  typedef unspecified_type FT;

  /// the cell the criteria judge: `CGAL::Hex_meshing_3::Cell_3<Geom_traits>`, where `Geom_traits`
  /// is the domain's (`HexMeshDomain_3::Geom_traits`)
  typedef unspecified_type Cell;

  /// the answer of `operator()`: contextually convertible to `bool`, `true` meaning "split this
  /// cell" (e.g. `std::optional<FT>` holding a priority)
  typedef unspecified_type Is_cell_bad;

  /// @}

  /// \name Access
  /// @{

  /// the largest cell edge of the initial grid; must be positive and finite
  FT initial_size() const;

  /// the deepest refinement level below the initial grid, in [0, 20]; the mesher may lower it so
  /// that lattice coordinates fit in 21 bits
  int max_level() const;

  /// the size asked for cells meeting feature edges or lines of the domain (0: none); when
  /// positive, the mesher sets `Cell::meets_feature`
  FT feature_size() const;

  /// the size asked for cut cells in which the surface bends (0: none); when positive, the mesher
  /// sets `Cell::normal_spread` for the cut cells larger than it
  FT curvature_size() const;

  /// the cells asked across thin parts and gaps (0: none) and the smallest size that asks for;
  /// when positive, the mesher sets `Cell::thickness` for the cut cells larger than that size
  int thin_part_cells() const;
  FT thin_part_min_size() const;

  /// the cells of each level that wrap a finer region before the next coarser level, in [1, 16]:
  /// 1 asks for the plain 2:1 balance across faces and edges (see the user manual, "Balance")
  int cells_between_levels() const;

  /// per patch index of the domain: the (surface size, curvature size) asked for the cut cells
  /// meeting that patch's triangles, (0, 0) where none is; the mesher sets `Cell::patch_size`
  /// and `Cell::patch_curvature_size` (and `Cell::normal_spread`) for the cut cells larger than
  /// the smallest of them
  const std::vector<std::pair<FT, FT>>& patch_sizes() const;

  /// @}

  /// \name Operations
  /// @{

  /// is `c` bad, that is, must it be split? The mesher asks only about cells of a level smaller than `max_level()`.
  Is_cell_bad operator()(const Cell& c) const;

  /// @}
};
