/*!
\ingroup PkgHexMeshing3Concepts
\cgalConcept

The concept `HexMeshDomain_3` describes what `CGAL::make_hex_mesh_3()` asks of the region to mesh:
a triangulated surface given as indexed triangles, with exact box/triangle intersection tests, an
inside test, and surface parts (patches) that name the boundary faces of the mesh.

The mesher distributes the triangles to the cells of the grid with `do_intersect()` (a cell is
*cut* when it meets a triangle), decides which uncut cells lie inside with `is_inside()` when
`has_exact_inside_test()` is `true` and with `winding_number()` otherwise, and names each boundary
face after the part of the triangle closest to it (`closest_triangle()`, `patch()`). The
body-fitted boundary projects onto the surface with the queries of the last group.

\cgalHasModelsBegin
\cgalHasModels{`CGAL::Hex_meshing_3::Surface_domain_3<GeomTraits>`}
\cgalHasModelsEnd

\sa `CGAL::make_hex_mesh_3()`
\sa `HexMeshCriteria_3`
*/
class HexMeshDomain_3
{
public:
  /// \name Types
  /// @{

  /// a model of `Kernel` with exact predicates; its `FT` and `Point_3` are those of the mesher
  typedef unspecified_type Geom_traits;

  /// `Geom_traits::Point_3`
  typedef unspecified_type Point_3;

  /// @}

  /// \name Access
  /// @{

  /// the bounding box of the surface; the default meshing box is this box grown by the criteria's
  /// initial size on every side
  const CGAL::Bbox_3& bbox() const;

  /// the number of triangles; triangles are indexed from 0 to `number_of_triangles() - 1`
  std::size_t number_of_triangles() const;

  /// the bounding box of triangle `i` (by value: a model may compute it)
  CGAL::Bbox_3 triangle_bbox(std::size_t i) const;

  /// the names of the parts of the surface; boundary faces on the surface get the patch
  /// `6 + patch(i)` of the mesh, after the six faces of the meshing box
  const std::vector<std::string>& patch_names() const;

  /// the part of triangle `i`, an index into `patch_names()`
  int patch(std::size_t i) const;

  /// @}

  /// \name Queries
  /// @{

  /// does the closed box `b` meet triangle `i`? Must be exact: it decides which cells are cut.
  bool do_intersect(const CGAL::Bbox_3& b, std::size_t i) const;

  /// `true` if `is_inside()` is an exact test; the mesher then calls it once per connected
  /// component of uncut cells, and `winding_number()` once per cell otherwise
  bool has_exact_inside_test() const;

  /// is `p` inside the surface? Also used to reject a region seed that lies inside a body.
  bool is_inside(const Point_3& p) const;

  /// the generalised winding number of the surface at `p`; a cell whose centre has a winding
  /// number of at least 0.5 is inside
  double winding_number(const Point_3& p) const;

  /// the index of a triangle closest to `p`
  std::size_t closest_triangle(const Point_3& p) const;

  /// are there feature edges or feature lines (for the criteria's feature size)?
  bool has_feature_edges() const;

  /// does the closed box `b` meet a feature edge of triangle `i`? Must be exact.
  bool do_intersect_feature(const CGAL::Bbox_3& b, std::size_t i) const;

  /// the segments of the feature lines that need not lie on the surface (may be empty)
  const std::vector<Geom_traits::Segment_3>& feature_segments() const;

  /// does the closed box `b` meet one of `feature_segments()`? Must be exact.
  bool do_intersect_feature_lines(const CGAL::Bbox_3& b) const;

  /// @}

  /// \name Body-fitted boundary
  /// What the buffer layer, the projection and the feature snapping ask (named parameter
  /// `body_fitted`, on by default).
  /// @{

  /// the point of the surface closest to `p`
  Point_3 closest_point(const Point_3& p) const;

  /// frees whatever the surface queries built to answer fast (a search tree); the next query
  /// builds it again. The boundary capture calls it when it has made its last query, to lower
  /// the memory peak. (A model that keeps nothing does nothing.)
  void release_search_tree() const;

  /// the squared distance from `p` to the surface
  Geom_traits::FT squared_distance(const Point_3& p) const;

  /// the first point where the ray from `p` along `d` meets the surface; `false` if none; if
  /// `triangle` is given, it receives the index of the triangle met there (thin-part refinement)
  bool first_ray_hit(const Point_3& p, const Geom_traits::Vector_3& d, Point_3& hit, std::size_t* triangle = nullptr) const;

  /// triangle `i`, its corner indices into `points()`, and the points: the surface regions
  /// between feature curves are built from them
  const Geom_traits::Triangle_3& triangle(std::size_t i) const;
  const std::vector<std::array<std::uint32_t, 3>>& triangle_indices() const;
  const std::vector<Point_3>& points() const;

  /// was triangle `i` added to close a hole of the input (not the input's)? The boundary faces on
  /// such triangles are caps in the fidelity measures, and their input->mesh samples skip them.
  bool is_fill(std::size_t i) const;
  /// the hole triangle `i` fills, from 1 (0: an input triangle); the feature curves judge the rim
  /// of each hole as a whole
  std::size_t filled_hole(std::size_t i) const;
  /// the point of the surface closest to `p` and the index of a triangle it lies on
  std::pair<Point_3, std::size_t> closest_point_and_triangle(const Point_3& p) const;

  /// @}
};
