/*!
\ingroup PkgHexMeshing3Concepts
\cgalConcept

The concept `HexMesh_3` describes the output of `CGAL::make_hex_mesh_3()`: an unstructured,
possibly non-conformal, all-hexahedral mesh stored in plain arrays that the mesher fills and that
the writers (`CGAL::Hex_meshing_3::IO::write_VTU()`, `CGAL::Hex_meshing_3::Polyhedral_mesh_3`,
`CGAL::Hex_meshing_3::IO::write_OpenFOAM()`) and `CGAL::Hex_meshing_3::compute_quality()` read.

Conventions:
- the 8 corners of a hexahedron are in VTK order (`VTK_HEXAHEDRON`): with \f$ (i,j,k) \in \{0,1\}^3 \f$
  the offsets of a corner along x, y and z, the corners are
  0:(0,0,0) 1:(1,0,0) 2:(1,1,0) 3:(0,1,0) 4:(0,0,1) 5:(1,0,1) 6:(1,1,1) 7:(0,1,1);
  see `CGAL::Hex_meshing_3::hex_local_faces()` and `CGAL::Hex_meshing_3::hex_local_edges()`;
- a hanging node lies at the middle of an edge (2 masters, the edge's ends) or at the centre of a
  face (4 masters, the face's corners) of a hexahedron of the mesh, without being one of its corners;
- boundary faces are quads, counter-clockwise seen from outside the mesh;
- patches 0 to 5 are the faces of the meshing box, named `xmin`, `xmax`, `ymin`, `ymax`, `zmin`,
  `zmax`; the parts of the surface (`HexMeshDomain_3::patch_names()`) follow.

A model is copy constructible and move assignable: `CGAL::make_hex_mesh_3()` keeps a copy of the
grid to run the boundary capture again (its named parameter `capture_retry_cells`).

\cgalHasModelsBegin
\cgalHasModels{`CGAL::Hex_meshing_3::Hex_mesh_3<GeomTraits>`}
\cgalHasModelsEnd

\sa `CGAL::make_hex_mesh_3()`
*/
class HexMesh_3
{
public:
  /// \name Types
  /// @{

  /// the point type, constructible from three `double`s
  typedef unspecified_type Point_3;

  /// an unsigned integer type indexing `points` (e.g. `std::uint32_t`)
  typedef unspecified_type Index;

  /// `std::array<Index, 8>`: the corners of a hexahedron in VTK order
  typedef unspecified_type Hexahedron;

  /// a hanging node, an aggregate initialisable as `{vertex, masters, number_of_masters}` with
  /// the members `Index vertex`, `std::array<Index, 4> masters` and `int number_of_masters`
  /// (2 or 4); `vertex` is the average of the first `number_of_masters` masters
  typedef unspecified_type Hanging_node;

  /// a boundary quad, an aggregate initialisable as `{vertices, cell, patch}` with the members
  /// `std::array<Index, 4> vertices` (counter-clockwise seen from outside), `Index cell` (the
  /// hexahedron it bounds) and `int patch` (an index into `patch_names`)
  typedef unspecified_type Boundary_face;

  /// @}

  /// \name Data
  /// @{

  /// the vertices
  std::vector<Point_3> points;

  /// the hexahedra
  std::vector<Hexahedron> hexahedra;

  /// per hexahedron, its refinement level along x, y and z below the initial grid
  std::vector<std::array<std::uint8_t, 3>> cell_levels;

  /// the hanging nodes
  std::vector<Hanging_node> hanging_nodes;

  /// the boundary faces
  std::vector<Boundary_face> boundary_faces;

  /// the names of the patches: the six box faces, then the parts of the surface
  std::vector<std::string> patch_names;

  /// the OpenFOAM type of each patch (`patch`, `wall`, `symmetryPlane`, ...)
  std::vector<std::string> patch_types;

  /// the meshing box
  CGAL::Bbox_3 box;

  /// @}

  /// \name Operations
  /// @{

  /// empties the mesh
  void clear();

  /// the type of patch `p`: `patch_types[p]`, or `patch` for the box faces and `wall` otherwise
  std::string patch_type(std::size_t p) const;

  /// @}
};
