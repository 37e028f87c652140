// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_QUALITY_H
#define CGAL_HEX_MESHING_3_QUALITY_H

// Quality measures, with the definitions of the tools people check meshes with:
// - scaled Jacobian of a hexahedron: Verdict's (Knupp 2000): at each corner the determinant of the
//   three normalised edge vectors leaving it (right-handed in VTK order), and at the centre the
//   determinant of the normalised principal axes; the minimum of the 9 values, in [-1, 1].
// - non-orthogonality, skewness and aspect ratio: OpenFOAM's (primitiveMeshTools, v1912), computed
//   on the polyhedral form of the mesh with OpenFOAM's face and cell centres, so that they agree
//   with what `checkMesh` prints.
// - face warpage: ours (no tool prints it under this name), see `face_warpage()`.
// Also: histograms with fixed ranges per measure (`histogram()`, `quality_histograms()`) and the
// worst elements with their locations (`worst_cells()`).

#include <CGAL/assertions.h>
#include <CGAL/number_utils.h>
#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {

namespace internal {
typedef std::array<double, 3> Vec3;
inline Vec3 sub(const Vec3& a, const Vec3& b) { return {{a[0]-b[0], a[1]-b[1], a[2]-b[2]}}; }
inline Vec3 add(const Vec3& a, const Vec3& b) { return {{a[0]+b[0], a[1]+b[1], a[2]+b[2]}}; }
inline Vec3 mul(const Vec3& a, double s) { return {{a[0]*s, a[1]*s, a[2]*s}}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0]*b[0] + a[1]*b[1] + a[2]*b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{ return {{a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]}}; }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
template <typename P> Vec3 vec(const P& p)
{ return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}}; }
inline Vec3 vec(const Vec3& p) { return p; }
} // namespace internal

namespace internal {
// The nine scaled Jacobians of a hexahedron given as 8 corner vectors (VTK order), unclamped:
// its corners' (j[0..7], the three edges at corner i, normalised) and its centre's (j[8], the
// three principal axes). Verdict's scaled Jacobian is their minimum, clamped to [-1, 1].
// With `stop`, the values stop at the first one below it: returns how many were written (9 if
// none is below `stop`).
inline int hex_scaled_jacobians(const Vec3* x, double* j, double stop = -std::numeric_limits<double>::infinity())
{
  static constexpr int nb[8][3] = {{1,3,4},{2,0,5},{3,1,6},{0,2,7},{7,5,0},{4,6,1},{5,7,2},{6,4,3}};
  // the squared lengths of the 12 edges (`hex_local_edges()`), and which three meet at each corner
  // (in the order of `nb`)
  static constexpr int ce[8][3] = {{0,4,8},{5,0,9},{1,5,10},{4,1,11},{6,2,8},{2,7,9},{7,3,10},{3,6,11}};
  double ll[12];
  for(int k = 0; k < 12; ++k) {
    const auto& e = hex_local_edges()[std::size_t(k)];
    const Vec3 d = sub(x[e[1]], x[e[0]]);
    ll[k] = dot(d, d);
  }
  auto det = [](const Vec3& a, const Vec3& b, const Vec3& c, double l) {
    l = std::sqrt(l);
    if(!(l > 0)) return 0.0;
    return dot(a, cross(b, c)) / l;
  };
  for(int i = 0; i < 8; ++i) {
    j[i] = det(sub(x[nb[i][0]], x[i]), sub(x[nb[i][1]], x[i]), sub(x[nb[i][2]], x[i]),
               ll[ce[i][0]] * ll[ce[i][1]] * ll[ce[i][2]]);
    if(j[i] < stop) return i + 1;
  }
  const Vec3 X1 = add(add(sub(x[1], x[0]), sub(x[2], x[3])), add(sub(x[5], x[4]), sub(x[6], x[7])));
  const Vec3 X2 = add(add(sub(x[3], x[0]), sub(x[2], x[1])), add(sub(x[7], x[4]), sub(x[6], x[5])));
  const Vec3 X3 = add(add(sub(x[4], x[0]), sub(x[5], x[1])), add(sub(x[6], x[2]), sub(x[7], x[3])));
  j[8] = det(X1, X2, X3, dot(X1, X1) * dot(X2, X2) * dot(X3, X3));
  return 9;
}

// the smallest of n values
inline double min_of(const double* v, std::size_t n)
{
  double m = std::numeric_limits<double>::max();
  for(std::size_t i = 0; i < n; ++i) m = (std::min)(m, v[i]);
  return m;
}

// Verdict's scaled Jacobian of a hexahedron given as 8 corner vectors (VTK order)
inline double hex_scaled_jacobian(const Vec3* x)
{
  double j[9];
  hex_scaled_jacobians(x, j);
  return (std::max)(-1.0, (std::min)(1.0, min_of(j, 9)));
}
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief Verdict's scaled Jacobian of the hexahedron with corners `p` in VTK order: 1 for a cube,
 * <= 0 for an inverted or degenerate cell.
 */
template <typename Point_3>
double scaled_jacobian(const std::array<Point_3, 8>& p)
{
  internal::Vec3 x[8];
  for(int i = 0; i < 8; ++i) x[i] = internal::vec(p[i]);
  return internal::hex_scaled_jacobian(x);
}

namespace internal {
// OpenFOAM's centre and area vector of a polygon of `n` vertices, `at(i)` the i-th
// (`primitiveMesh::makeFaceCentresAndAreas()`: a triangle as it is, else the fan of triangles
// around the vertex average, their centroids weighted by their areas)
template <typename At>
void foam_face_centre_and_area(std::size_t n, At at, Vec3& centre, Vec3& area)
{
  if(n == 3) {
    const Vec3 a = at(0), b = at(1), c = at(2);
    centre = mul(add(add(a, b), c), 1.0 / 3.0);
    area = mul(cross(sub(b, a), sub(c, a)), 0.5);
    return;
  }
  Vec3 avg{{0, 0, 0}};
  for(std::size_t i = 0; i < n; ++i) avg = add(avg, at(i));
  avg = mul(avg, 1.0 / double(n));
  Vec3 sumN{{0, 0, 0}}, sumAc{{0, 0, 0}};
  double sumA = 0;
  for(std::size_t i = 0; i < n; ++i) {
    const Vec3 p = at(i), q = at((i + 1) % n);
    const Vec3 c = add(add(p, q), avg);
    const Vec3 N = cross(sub(q, p), sub(avg, p));
    const double a = norm(N);
    sumN = add(sumN, N); sumA += a; sumAc = add(sumAc, mul(c, a));
  }
  centre = sumA < 1e-300 ? avg : mul(sumAc, 1.0 / (3.0 * sumA));
  area = mul(sumN, 0.5);
}
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief OpenFOAM's geometry of a polyhedral mesh: face centres and area vectors, cell centres and
 * volumes, computed as OpenFOAM's primitiveMesh does (faces: triangle fan around the vertex
 * average; cells: pyramids on the faces around the average of the face centres).
 */
struct OpenFOAM_geometry
{
  typedef internal::Vec3 Vec3;
  std::vector<Vec3> face_centres, face_areas, cell_centres;
  std::vector<double> cell_volumes;

  /// OpenFOAM's centre and area vector of the face with vertices `F` (one face of `compute()`)
  template <typename Point_3, typename Polygon>
  static void face_centre_and_area(const std::vector<Point_3>& points, const Polygon& F,
                                   Vec3& centre, Vec3& area)
  {
    internal::foam_face_centre_and_area(F.size(), [&](std::size_t i) { return internal::vec(points[F[i]]); }, centre, area);
  }

  /// the centre and area vector of face `f`: the stored ones after `compute()`, computed from
  /// `points` after `compute_cells()`
  template <typename Point_3>
  void face(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm, std::size_t f, Vec3& centre, Vec3& area) const
  {
    if(face_centres.empty()) face_centre_and_area(points, pm.faces[f], centre, area);
    else { centre = face_centres[f]; area = face_areas[f]; }
  }

  template <typename Point_3>
  void compute(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm)
  {
    const std::size_t nf = pm.faces.size();
    face_centres.assign(nf, Vec3{{0, 0, 0}});
    face_areas.assign(nf, Vec3{{0, 0, 0}});
    for(std::size_t f = 0; f < nf; ++f) face_centre_and_area(points, pm.faces[f], face_centres[f], face_areas[f]);
    cells_from_faces(pm, [&](std::size_t f, Vec3& c, Vec3& a) { c = face_centres[f]; a = face_areas[f]; });
  }

  /// the cells' centres and volumes only, as `compute()` finds them; `face_centres` and
  /// `face_areas` stay empty (each face's are computed where needed: they are two thirds of the
  /// memory, 53 MB on motorBike)
  template <typename Point_3>
  void compute_cells(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm)
  {
    face_centres.clear(); face_centres.shrink_to_fit();
    face_areas.clear(); face_areas.shrink_to_fit();
    cells_from_faces(pm, [&](std::size_t f, Vec3& c, Vec3& a) { face_centre_and_area(points, pm.faces[f], c, a); });
  }

private:
  // `face(f, centre, area)`: the centre and area vector of face f
  template <typename Face>
  void cells_from_faces(const Polyhedral_mesh_3& pm, const Face& face)
  {
    using namespace internal;
    const std::size_t nf = pm.faces.size();
    const std::size_t nc = pm.number_of_cells;
    std::vector<Vec3> est(nc, Vec3{{0, 0, 0}});
    std::vector<int> nfaces(nc, 0);
    Vec3 fc, fa;
    for(std::size_t f = 0; f < nf; ++f) {
      face(f, fc, fa);
      est[pm.owner[f]] = add(est[pm.owner[f]], fc); ++nfaces[pm.owner[f]];
      if(f < pm.neighbour.size()) { est[pm.neighbour[f]] = add(est[pm.neighbour[f]], fc); ++nfaces[pm.neighbour[f]]; }
    }
    for(std::size_t c = 0; c < nc; ++c) est[c] = mul(est[c], 1.0 / (std::max)(1, nfaces[c]));
    std::vector<int>().swap(nfaces);
    cell_centres.assign(nc, Vec3{{0, 0, 0}});
    cell_volumes.assign(nc, 0.0);
    auto add_pyramid = [&](std::size_t c, double sign) {
      const double pyr3Vol = sign * dot(fa, sub(fc, est[c]));
      const Vec3 pc = add(mul(fc, 3.0 / 4.0), mul(est[c], 1.0 / 4.0));
      cell_centres[c] = add(cell_centres[c], mul(pc, pyr3Vol));
      cell_volumes[c] += pyr3Vol;
    };
    for(std::size_t f = 0; f < nf; ++f) {
      face(f, fc, fa);
      add_pyramid(pm.owner[f], 1.0);
      if(f < pm.neighbour.size()) add_pyramid(pm.neighbour[f], -1.0);
    }
    for(std::size_t c = 0; c < nc; ++c) {
      if(std::abs(cell_volumes[c]) > 1e-300) cell_centres[c] = mul(cell_centres[c], 1.0 / cell_volumes[c]);
      else cell_centres[c] = est[c];
      cell_volumes[c] /= 3.0;
    }
  }
};

namespace internal {
// OpenFOAM's concave test of one cell from the centres and the outward area vectors of its faces
// (see `concave_cells()`)
template <typename Vec3s>
bool concave_cell(const Vec3s& centres, const Vec3s& outward_areas)
{
  const double planar_cos_angle = 1.0e-6, VSMALL = 1.0e-300;
  for(std::size_t i = 0; i < centres.size(); ++i) {
    const Vec3 n = mul(outward_areas[i], 1.0 / (std::max)(norm(outward_areas[i]), VSMALL));
    for(std::size_t j = 0; j < centres.size(); ++j) {
      if(j == i) continue;
      const Vec3 d = sub(centres[j], centres[i]);
      if(dot(d, n) / (std::max)(norm(d), VSMALL) > -planar_cos_angle) return true;
    }
  }
  return false;
}

// the faces of each cell of `pm`: cell c's are faces[start[c] .. start[c + 1]) (32 bits: a memory peak)
inline void cell_faces(const Polyhedral_mesh_3& pm, std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& faces)
{
  const std::size_t nc = pm.number_of_cells, nf = pm.faces.size(), ni = pm.neighbour.size();
  CGAL_precondition(nf + ni <= std::numeric_limits<std::uint32_t>::max());
  start.assign(nc + 1, 0);
  for(std::size_t f = 0; f < nf; ++f) { ++start[pm.owner[f] + 1]; if(f < ni) ++start[pm.neighbour[f] + 1]; }
  for(std::size_t c = 0; c < nc; ++c) start[c + 1] += start[c];
  faces.resize(start[nc]);
  std::vector<std::uint32_t> pos(start.begin(), start.end() - 1);
  for(std::size_t f = 0; f < nf; ++f) {
    faces[pos[pm.owner[f]]++] = std::uint32_t(f);
    if(f < ni) faces[pos[pm.neighbour[f]]++] = std::uint32_t(f);
  }
}

// OpenFOAM's concave test of cell c of `pm`, from its faces (`cell_faces()`) and their centres
// and area vectors, which `face(f, centre, area)` gives (`centres`, `areas`: work space)
template <typename Face>
bool concave_cell(const Polyhedral_mesh_3& pm, std::size_t c, const std::vector<std::uint32_t>& start,
                  const std::vector<std::uint32_t>& faces, const Face& face, std::vector<Vec3>& centres,
                  std::vector<Vec3>& areas)
{
  centres.clear(); areas.clear();
  for(std::size_t i = start[c]; i < start[c + 1]; ++i) {
    const std::size_t f = faces[i];
    Vec3 fc, fa;
    face(f, fc, fa);
    centres.push_back(fc);
    areas.push_back(mul(fa, pm.owner[f] == c ? 1.0 : -1.0));
  }
  return concave_cell(centres, areas);
}

// `concave_cells()`, the faces' centres and areas from `face(f, centre, area)`
template <typename Face>
std::vector<char> concave_cells_of(const Polyhedral_mesh_3& pm, const Face& face)
{
  std::vector<std::uint32_t> start, faces;
  cell_faces(pm, start, faces);
  std::vector<char> concave(pm.number_of_cells, 0);
  std::vector<Vec3> centres, areas;
  for(std::size_t c = 0; c < pm.number_of_cells; ++c)
    concave[c] = concave_cell(pm, c, start, faces, face, centres, areas) ? 1 : 0;
  return concave;
}
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the cells of `pm` that OpenFOAM's `checkMesh -allGeometry` calls concave ("Concave cells
 * (using face planes)", `primitiveMesh::checkConcaveCells`): 1 for a cell with a face whose plane
 * has the centre of another face of the cell on it or on its outer side. For a face with centre c
 * and outward unit normal n, and another face's centre p, the cell is concave when
 * (p - c) / |p - c| . n > -1e-6 (OpenFOAM's `planarCosAngle`). A face split into coplanar pieces by
 * hanging nodes makes its cell concave in this sense (see `IO::write_OpenFOAM()`'s bulge).
 *
 * `g` is the geometry computed by `OpenFOAM_geometry::compute(points, pm)`.
 */
inline std::vector<char> concave_cells(const Polyhedral_mesh_3& pm, const OpenFOAM_geometry& g)
{
  CGAL_precondition(g.face_areas.size() == pm.faces.size() && g.face_centres.size() == pm.faces.size());   // `compute()`, not `compute_cells()`
  return internal::concave_cells_of(pm, [&](std::size_t f, internal::Vec3& c, internal::Vec3& a) {
    c = g.face_centres[f]; a = g.face_areas[f]; });
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief `concave_cells()` where `g` may also be the cells-only geometry of
 * `OpenFOAM_geometry::compute_cells(points, pm)`: the faces' centres and areas are then computed
 * from `points` where needed (the same values; no array of them, two thirds of the geometry's memory).
 */
template <typename Point_3>
std::vector<char> concave_cells(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm, const OpenFOAM_geometry& g)
{
  return internal::concave_cells_of(pm, [&](std::size_t f, internal::Vec3& c, internal::Vec3& a) {
    g.face(points, pm, f, c, a); });
}

namespace internal {
// OpenFOAM's tetrahedron quality (`tetrahedron::quality()`): the signed volume of (a, b, c, d)
// over that of the regular tetrahedron with the same circumradius; about 1 for a regular one,
// negative when inverted
inline double foam_tet_quality(const Vec3& a_, const Vec3& b_, const Vec3& c_, const Vec3& d_)
{
  const double GREAT = 1.0e15, ROOTVSMALL = 1.0e-150;
  const Vec3 a = sub(b_, a_), b = sub(c_, a_), c = sub(d_, a_);
  const double volume = dot(cross(a, b), c) / 6.0;
  const double lambda = dot(c, c) - dot(a, c), mu = dot(b, b) - dot(a, b);
  const Vec3 ba = cross(b, a), ca = cross(c, a);
  const Vec3 num = sub(mul(ba, lambda), mul(ca, mu));
  const double denom = dot(c, ba);
  double radius = GREAT;
  if(std::abs(denom) >= ROOTVSMALL) radius = norm(add(mul(a, 0.5), mul(num, 0.5 / denom)));
  radius = (std::min)(radius, GREAT);
  return volume / (8.0 / (9.0 * std::sqrt(3.0)) * radius * radius * radius + ROOTVSMALL);
}
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the faces of `pm` that OpenFOAM's `checkMesh -allGeometry` reports in "Error in face tets"
 * (`polyMeshTetDecomposition::checkFaceTets()` with its `minTetQuality` 1e-30): 1 for a face whose
 * fan of triangles around its centre forms, with the owner's or the neighbour's cell centre, a
 * tetrahedron of quality at most 1e-30 (`internal::foam_tet_quality()`), or that has no vertex
 * from which the fan of triangles forms tetrahedra of quality above 1e-30 with both cell centres
 * (`findSharedBasePoint()`; a boundary face: with its owner's, `findBasePoint()`).
 *
 * `g` is the geometry computed by `OpenFOAM_geometry::compute(points, pm)` or `compute_cells(points, pm)`.
 */
template <typename Point_3>
std::vector<char> face_tet_errors(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm,
                                  const OpenFOAM_geometry& g)
{
  using namespace internal;
  const double tol = 1.0e-30;   // OpenFOAM's minTetQuality, sqr(SMALL)
  const std::size_t ni = pm.neighbour.size();
  std::vector<char> bad(pm.faces.size(), 0);
  for(std::size_t f = 0; f < pm.faces.size(); ++f) {
    const auto& F = pm.faces[f];
    const std::size_t n = F.size();
    Vec3 fc, fa;
    if(g.face_centres.empty()) OpenFOAM_geometry::face_centre_and_area(points, F, fc, fa);   // (`compute_cells()`)
    else fc = g.face_centres[f];
    const Vec3& co = g.cell_centres[pm.owner[f]];
    const bool internal_face = f < ni;
    for(std::size_t i = 0; i < n && !bad[f]; ++i)
      if(foam_tet_quality(vec(points[F[i]]), vec(points[F[(i + 1) % n]]), fc, co) > -tol) bad[f] = 1;
    if(internal_face) {
      const Vec3& cn = g.cell_centres[pm.neighbour[f]];
      for(std::size_t i = 0; i < n && !bad[f]; ++i)
        if(foam_tet_quality(vec(points[F[i]]), vec(points[F[(i + 1) % n]]), fc, cn) < tol) bad[f] = 1;
    }
    if(bad[f]) continue;
    // a base point shared by both cells (a boundary face: good for its owner, `findBasePoint()`)
    const Vec3 cn = internal_face ? g.cell_centres[pm.neighbour[f]] : co;
    bool found = false;
    for(std::size_t base = 0; base < n && !found; ++base) {
      double worst = std::numeric_limits<double>::max();
      const Vec3 b = vec(points[F[base]]);
      for(std::size_t t = 1; t + 1 < n; ++t) {
        const std::size_t i = (t + base) % n, j = (i + 1) % n;
        const Vec3 pa = vec(points[F[i]]), pb = vec(points[F[j]]);
        worst = (std::min)(worst, foam_tet_quality(co, b, pa, pb));
        if(internal_face) worst = (std::min)(worst, foam_tet_quality(cn, b, pb, pa));
      }
      found = worst > tol;
    }
    if(!found) bad[f] = 1;
  }
  return bad;
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief per-element quality of a hexahedral mesh and its summary.
 */
struct Mesh_quality
{
  std::vector<double> scaled_jacobian;    ///< per cell
  std::vector<double> aspect_ratio;       ///< per cell, OpenFOAM's definition
  std::vector<double> non_orthogonality;  ///< per internal face, degrees
  std::vector<double> skewness;           ///< per face (internal and boundary), OpenFOAM's
  std::vector<double> cell_volume;        ///< per cell
  std::vector<double> face_warpage;       ///< per face (internal and boundary), degrees, see `face_warpage()`
  std::vector<char> concave;              ///< per cell: 1 if concave for OpenFOAM, see `concave_cells()`

  struct Range { double min = 0, mean = 0, max = 0; std::size_t count = 0; };
  static Range range(const std::vector<double>& v)
  {
    Range r;
    if(v.empty()) return r;
    r.min = *std::min_element(v.begin(), v.end());
    r.max = *std::max_element(v.begin(), v.end());
    double s = 0; for(double x : v) s += x;
    r.mean = s / double(v.size()); r.count = v.size();
    return r;
  }
  /// number of cells with a scaled Jacobian <= 0 (inverted or degenerate)
  std::size_t number_of_inverted_cells() const
  { return std::size_t(std::count_if(scaled_jacobian.begin(), scaled_jacobian.end(), [](double x) { return x <= 0; })); }
  /// number of cells OpenFOAM's `checkMesh -allGeometry` calls concave
  std::size_t number_of_concave_cells() const { return std::size_t(std::count(concave.begin(), concave.end(), char(1))); }
};

namespace internal {
// OpenFOAM's cell determinant (`cellDeterminant()` of OpenCFD's primitiveMeshTools, as
// `checkMesh -allGeometry` prints it, "wellposedness"): over the cell's internal faces only, the
// tensor sum of (A/a)(A/a)^T, A a face's area vector, a the mean of |A| over those faces; the
// determinant of that sum / 8 (1 for a cube with six internal faces; 0 for a cell with none).
// The sums over a cell's internal faces: of A A^T (xx xy xz yy yz zz), of |A| and of 1
typedef std::array<double, 8> Area_tensor_sum;
inline void add_face_area(Area_tensor_sum& s, const Vec3& a)
{
  s[0] += a[0] * a[0]; s[1] += a[0] * a[1]; s[2] += a[0] * a[2];
  s[3] += a[1] * a[1]; s[4] += a[1] * a[2]; s[5] += a[2] * a[2];
  s[6] += std::sqrt(dot(a, a)); s[7] += 1;
}
// ... and the cell's determinant from them
inline double area_tensor_determinant(Area_tensor_sum t)
{
  if(t[7] == 0 || !(t[6] > 0)) return 0;
  const double avg = t[6] / t[7], s2 = 1.0 / (avg * avg);
  for(int i = 0; i < 6; ++i) t[std::size_t(i)] *= s2;
  const double d = t[0] * (t[3] * t[5] - t[4] * t[4]) - t[1] * (t[1] * t[5] - t[4] * t[2]) +
                   t[2] * (t[1] * t[4] - t[3] * t[2]);
  return std::abs(d) / 8.0;
}
// ... of every cell of `pm`, `area(f)` giving face f's area vector
template <typename FaceArea>
std::vector<double> cell_determinants(const Polyhedral_mesh_3& pm, const FaceArea& area)
{
  std::vector<std::uint32_t> start, faces;
  cell_faces(pm, start, faces);
  const std::size_t ni = pm.neighbour.size();
  std::vector<double> det(pm.number_of_cells, 0.0);
  for(std::size_t c = 0; c < pm.number_of_cells; ++c) {
    Area_tensor_sum t{{0, 0, 0, 0, 0, 0, 0, 0}};
    for(std::uint32_t k = start[c]; k < start[c + 1]; ++k)
      if(faces[k] < ni) add_face_area(t, area(faces[k]));
    det[c] = area_tensor_determinant(t);
  }
  return det;
}
} // namespace internal

/// checkMesh -allGeometry's threshold on the cell determinant ("Cells with small determinant")
constexpr double openfoam_min_cell_determinant = 0.001;

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief OpenFOAM's cell determinant of each cell of `pm` (`checkMesh -allGeometry`'s
 * "wellposedness"): over the cell's internal faces only, the determinant of the sum of
 * (A/a)(A/a)^T, A a face's area vector and a the mean of their lengths, divided by 8: 1 for a
 * cube with six internal faces, 0 for a cell with no internal face or with all of them parallel.
 * checkMesh flags the cells below `openfoam_min_cell_determinant` (0.001). The face areas are
 * computed on `points` as OpenFOAM does.
 */
template <typename Point_3>
std::vector<double> cell_determinants(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm)
{
  return internal::cell_determinants(pm, [&](std::size_t f) {
    internal::Vec3 c, a;
    OpenFOAM_geometry::face_centre_and_area(points, pm.faces[f], c, a);
    return a;
  });
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the warpage of each face of `pm`, in degrees: 0 for a planar convex face.
 *
 * Our definition (no checking tool prints this measure under this name): the face of n vertices
 * p_0 .. p_{n-1} is cut into the n fan triangles (p_i, p_{i+1}, c) around its centre c as OpenFOAM
 * computes it (`OpenFOAM_geometry::face_centres`); the warpage is the largest angle between the
 * normal of a fan triangle and the face's area vector S (`OpenFOAM_geometry::face_areas`), in
 * [0, 180] degrees. A fan triangle that is degenerate (its two edges at p_i make an angle whose
 * sine is below 1e-10, e.g. c on the line through p_i p_{i+1}) has no normal and is skipped; a face
 * whose area vector vanishes gets 0. A fan triangle folded over (a badly warped face, or a planar
 * face that is not star-shaped around its centre) gives an angle above 90 degrees, 180 if planar.
 * The faces of this package's meshes (rectangles, with hanging nodes on their edges) are convex.
 *
 * OpenFOAM's `checkMesh -allGeometry` "face flatness" (`primitiveMeshTools::faceFlatness()`) is
 * related but different: it is the ratio |S| / sum |N_i| of the area vector's magnitude to the sum
 * of the fan triangles' areas around the same centre (1 for a planar face; checkMesh warns below
 * 0.8), a ratio rather than an angle.
 *
 * `g` is the geometry computed by `OpenFOAM_geometry::compute(points, pm)` or `compute_cells(points, pm)`.
 */
template <typename Point_3>
std::vector<double> face_warpage(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm,
                                 const OpenFOAM_geometry& g)
{
  using namespace internal;
  const double rad_to_deg = 180.0 / 3.14159265358979323846;
  std::vector<double> w(pm.faces.size(), 0.0);
  for(std::size_t f = 0; f < pm.faces.size(); ++f) {
    const auto& F = pm.faces[f];
    Vec3 S, c;
    g.face(points, pm, f, c, S);
    const double mS = norm(S);
    if(!(mS > 0) || F.size() < 3) continue;
    const std::size_t n = F.size();
    double worst = 1.0;   // smallest cosine
    for(std::size_t i = 0; i < n; ++i) {
      const Vec3 p = vec(points[F[i]]), q = vec(points[F[(i + 1) % n]]);
      const Vec3 e1 = sub(q, p), e2 = sub(c, p);
      const Vec3 N = cross(e1, e2);
      const double mN = norm(N);
      if(!(mN > 1e-10 * norm(e1) * norm(e2))) continue;
      worst = (std::min)(worst, dot(N, S) / (mN * mS));
    }
    w[f] = std::acos((std::max)(-1.0, (std::min)(1.0, worst))) * rad_to_deg;
  }
  return w;
}

namespace internal {
// `sink(f, non_orthogonality, skewness)` for each face f: OpenFOAM's non-orthogonality (degrees;
// NaN for a boundary face) and skewness; `g` from `compute()` or `compute_cells()` (then the
// faces' centres and areas are computed from `points`)
template <typename Point_3, typename Sink>
void for_each_face_non_orthogonality_and_skewness(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm,
                                                  const OpenFOAM_geometry& g, const Sink& sink)
{
  const std::size_t ni = pm.neighbour.size();
  const double ROOTVSMALL = 1.0e-150, VSMALL = 1.0e-300;
  for(std::size_t f = 0; f < pm.faces.size(); ++f) {
    Vec3 S, Cf;
    g.face(points, pm, f, Cf, S);
    const Vec3& Co = g.cell_centres[pm.owner[f]];
    const Vec3 Cpf = sub(Cf, Co);
    Vec3 d;
    double fd0, non_orthogonality = std::numeric_limits<double>::quiet_NaN();
    if(f < ni) {
      d = sub(g.cell_centres[pm.neighbour[f]], Co);
      const double c = dot(d, S) / (norm(d) * norm(S) + VSMALL);
      non_orthogonality = std::acos((std::min)(1.0, (std::max)(-1.0, c))) * 180.0 / M_PI;
      fd0 = 0.2 * norm(d);
    } else {
      const double ms = norm(S);
      const Vec3 n = ms > VSMALL ? mul(S, 1.0 / ms) : Vec3{{0, 0, 0}};
      d = mul(n, dot(n, Cpf));
      fd0 = 0.4 * norm(d);
    }
    const Vec3 sv = sub(Cpf, mul(d, dot(S, Cpf) / (dot(S, d) + ROOTVSMALL)));
    const double msv = norm(sv);
    const Vec3 svHat = mul(sv, 1.0 / (msv + ROOTVSMALL));
    double fd = fd0 + ROOTVSMALL;
    for(auto v : pm.faces[f]) fd = (std::max)(fd, std::abs(dot(svHat, sub(vec(points[v]), Cf))));
    sink(f, non_orthogonality, msv / fd);
  }
}

// OpenFOAM's face non-orthogonality (degrees, internal faces; skipped if `non_orthogonality` is
// null) and skewness (all faces), from the geometry `g` of the mesh with points `points`
template <typename Point_3>
void face_non_orthogonality_and_skewness(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm, const OpenFOAM_geometry& g,
                                         std::vector<double>* non_orthogonality, std::vector<double>& skewness)
{
  const std::size_t ni = pm.neighbour.size();
  if(non_orthogonality) non_orthogonality->resize(ni);
  skewness.resize(pm.faces.size());
  for_each_face_non_orthogonality_and_skewness(points, pm, g, [&](std::size_t f, double no, double sk) {
    if(non_orthogonality && f < ni) (*non_orthogonality)[f] = no;
    skewness[f] = sk;
  });
}
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the scaled Jacobian of each hexahedron of `mesh` (`scaled_jacobian()`), in cell order.
 */
template <typename HexMesh>
std::vector<double> cell_scaled_jacobians(const HexMesh& mesh)
{
  std::vector<double> sj(mesh.hexahedra.size());
  for(std::size_t c = 0; c < sj.size(); ++c) {
    std::array<typename HexMesh::Point_3, 8> p;
    for(int k = 0; k < 8; ++k) p[std::size_t(k)] = mesh.points[mesh.hexahedra[c][std::size_t(k)]];
    sj[c] = scaled_jacobian(p);
  }
  return sj;
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief computes the quality of `mesh`; `pm` is its polyhedral form (`Polyhedral_mesh_3::build()`).
 */
template <typename HexMesh>
Mesh_quality compute_quality(const HexMesh& mesh, const Polyhedral_mesh_3& pm)
{
  using namespace internal;
  Mesh_quality q;
  q.scaled_jacobian = cell_scaled_jacobians(mesh);
  // (the cells' geometry only: the faces' centres and areas, two thirds of its memory, are
  // computed where needed)
  OpenFOAM_geometry g;
  g.compute_cells(mesh.points, pm);
  const std::size_t ni = pm.neighbour.size();
  const double ROOTVSMALL = 1.0e-150;
  face_non_orthogonality_and_skewness(mesh.points, pm, g, &q.non_orthogonality, q.skewness);
  // aspect ratio (primitiveMeshTools::cellClosedness)
  {
  std::vector<Vec3> sumMag(pm.number_of_cells, Vec3{{0, 0, 0}});
  for(std::size_t f = 0; f < pm.faces.size(); ++f) {
    Vec3 fc, fa;
    g.face(mesh.points, pm, f, fc, fa);
    const Vec3 m{{std::abs(fa[0]), std::abs(fa[1]), std::abs(fa[2])}};
    sumMag[pm.owner[f]] = add(sumMag[pm.owner[f]], m);
    if(f < ni) sumMag[pm.neighbour[f]] = add(sumMag[pm.neighbour[f]], m);
  }
  q.aspect_ratio.resize(pm.number_of_cells);
  for(std::size_t c = 0; c < pm.number_of_cells; ++c) {
    const Vec3& s = sumMag[c];
    const double mn = (std::min)({s[0], s[1], s[2]}), mx = (std::max)({s[0], s[1], s[2]});
    double ar = mx / (mn + ROOTVSMALL);
    const double v = (std::max)(ROOTVSMALL, g.cell_volumes[c]);
    ar = (std::max)(ar, (s[0] + s[1] + s[2]) / 6.0 / std::pow(v, 2.0 / 3.0));
    q.aspect_ratio[c] = ar;
  }
  }   // (`sumMag` freed: the memory peak comes next)
  q.face_warpage = face_warpage(mesh.points, pm, g);
  q.concave = concave_cells(mesh.points, pm, g);
  q.cell_volume = std::move(g.cell_volumes);
  return q;
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief a histogram of `counts.size()` equal bins over [`lo`, `hi`]; bin i covers
 * [lo + i w, lo + (i+1) w) with w = (hi - lo) / counts.size(), the last bin includes `hi`, and the
 * values outside the range are counted in the end bins.
 */
struct Histogram
{
  double lo = 0, hi = 1;
  std::vector<std::size_t> counts;

  /// number of values counted (NaN excluded)
  std::size_t total() const { std::size_t t = 0; for(std::size_t c : counts) t += c; return t; }
};

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the histogram of `values` with `bins` equal bins over [`lo`, `hi`] (`hi` > `lo` expected;
 * otherwise every value goes to the first bin): values below `lo` are counted in the first bin,
 * values above `hi` (and +infinity) in the last one; NaN values are ignored. One linear pass.
 */
inline Histogram histogram(const std::vector<double>& values, double lo, double hi, std::size_t bins)
{
  Histogram h;
  h.lo = lo; h.hi = hi;
  h.counts.assign(bins, 0);
  if(bins == 0) return h;
  const bool ok = hi > lo;   // false for NaN bounds too
  const double scale = ok ? double(bins) / (hi - lo) : 0.0;
  const double last = double(bins - 1);
  for(double v : values) {
    if(std::isnan(v)) continue;
    if(!ok || !(v > lo)) { ++h.counts[0]; continue; }
    const double x = (v - lo) * scale;   // > 0, may be +inf
    h.counts[x >= last ? bins - 1 : std::size_t(x)] += 1;
  }
  return h;
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the histograms of the measures of `q`, named as the members of `Mesh_quality`, over fixed
 * ranges so that histograms of different meshes compare bin by bin:
 * - `scaled_jacobian`: [-1, 1] (its whole range), 20 bins of 0.1;
 * - `non_orthogonality`: [0, 90] degrees, 18 bins of 5 (OpenFOAM's checkMesh warns above 70);
 * - `skewness`: [0, max(4, largest value)], 20 bins (checkMesh warns above 4);
 * - `aspect_ratio`: [1, max(10, largest value)], 18 bins (1 is its least value);
 * - `face_warpage`: [0, 90] degrees, 18 bins of 5 (angles above 90 fall in the last bin).
 *
 * `bins` > 0 replaces these numbers of bins. Empty measures give empty histograms (all counts 0).
 */
inline std::vector<std::pair<std::string, Histogram>> quality_histograms(const Mesh_quality& q, std::size_t bins = 0)
{
  auto largest = [](const std::vector<double>& v) {
    double m = -std::numeric_limits<double>::infinity();
    for(double x : v) if(x > m) m = x;   // NaN never compares greater
    return m;
  };
  auto nb = [bins](std::size_t d) { return bins > 0 ? bins : d; };
  double sk_hi = (std::max)(4.0, largest(q.skewness));
  double ar_hi = (std::max)(10.0, largest(q.aspect_ratio));
  if(!std::isfinite(sk_hi)) sk_hi = 4.0;   // +inf: everything above 4 in the last bin
  if(!std::isfinite(ar_hi)) ar_hi = 10.0;
  std::vector<std::pair<std::string, Histogram>> h;
  h.emplace_back("scaled_jacobian", histogram(q.scaled_jacobian, -1.0, 1.0, nb(20)));
  h.emplace_back("non_orthogonality", histogram(q.non_orthogonality, 0.0, 90.0, nb(18)));
  h.emplace_back("skewness", histogram(q.skewness, 0.0, sk_hi, nb(20)));
  h.emplace_back("aspect_ratio", histogram(q.aspect_ratio, 1.0, ar_hi, nb(18)));
  h.emplace_back("face_warpage", histogram(q.face_warpage, 0.0, 90.0, nb(18)));
  return h;
}

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief one of the worst elements of a measure: its index (cell index in `Hex_mesh_3::hexahedra`,
 * which is also the cell label of the `Polyhedral_mesh_3`, or face index in
 * `Polyhedral_mesh_3::faces`, which is OpenFOAM's face label), its value and where it is.
 */
struct Worst_element
{
  std::size_t index = 0;
  double value = 0;
  std::array<double, 3> location{{0, 0, 0}};   ///< cell: average of its 8 corners; face: OpenFOAM's face centre
};

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the worst elements of each measure of a `Mesh_quality`, worst first (see `worst_cells()`).
 */
struct Worst_cells
{
  std::vector<Worst_element> scaled_jacobian;    ///< cells, smallest values
  std::vector<Worst_element> aspect_ratio;       ///< cells, largest values
  std::vector<Worst_element> non_orthogonality;  ///< internal faces, largest values
  std::vector<Worst_element> skewness;           ///< faces, largest values
  std::vector<Worst_element> face_warpage;       ///< faces, largest values
};

namespace internal {
/// the indices of the (at most) k worst values, worst first: the smallest ones if `!largest`, the
/// largest ones otherwise; NaN counts as worse than any number; ties go to the smaller index.
/// One pass with a heap of k elements: O(n log k) time, O(k) memory.
inline std::vector<std::size_t> worst_indices(const std::vector<double>& v, std::size_t k, bool largest)
{
  struct Item { double value; std::size_t index; };
  auto worse = [largest](const Item& a, const Item& b) {
    const bool na = std::isnan(a.value), nb = std::isnan(b.value);
    if(na != nb) return na;
    if(!na && a.value != b.value) return largest ? a.value > b.value : a.value < b.value;
    return a.index < b.index;
  };
  std::vector<Item> heap;   // the best of the kept items on top (worse is the heap's "less")
  k = (std::min)(k, v.size());
  if(k == 0) return {};
  heap.reserve(k);
  for(std::size_t i = 0; i < v.size(); ++i) {
    const Item it{v[i], i};
    if(heap.size() < k) { heap.push_back(it); std::push_heap(heap.begin(), heap.end(), worse); }
    else if(worse(it, heap.front())) {
      std::pop_heap(heap.begin(), heap.end(), worse);
      heap.back() = it;
      std::push_heap(heap.begin(), heap.end(), worse);
    }
  }
  std::sort(heap.begin(), heap.end(), worse);
  std::vector<std::size_t> r;
  r.reserve(heap.size());
  for(const Item& it : heap) r.push_back(it.index);
  return r;
}
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief the `k` worst cells and faces of `q` (computed by `compute_quality(mesh, pm)`), worst first:
 * the cells with the smallest scaled Jacobian and the largest aspect ratio, the faces with the
 * largest non-orthogonality, skewness and warpage. Deterministic: ties go to the smaller index, and
 * NaN values count as the worst. A cell is located by the average of its 8 corners, a face by
 * OpenFOAM's face centre. One linear pass per measure, O(k) memory.
 */
template <typename HexMesh>
Worst_cells worst_cells(const HexMesh& mesh, const Polyhedral_mesh_3& pm, const Mesh_quality& q, std::size_t k = 10)
{
  using namespace internal;
  auto cells = [&](const std::vector<double>& v, bool largest) {
    std::vector<Worst_element> r;
    for(std::size_t c : worst_indices(v, k, largest)) {
      Worst_element e;
      e.index = c; e.value = v[c];
      if(c < mesh.hexahedra.size()) {
        Vec3 s{{0, 0, 0}};
        for(int i = 0; i < 8; ++i) s = add(s, vec(mesh.points[mesh.hexahedra[c][i]]));
        e.location = mul(s, 1.0 / 8.0);
      }
      r.push_back(e);
    }
    return r;
  };
  auto faces = [&](const std::vector<double>& v) {
    std::vector<Worst_element> r;
    for(std::size_t f : worst_indices(v, k, true)) {
      Worst_element e;
      e.index = f; e.value = v[f];
      if(f < pm.faces.size()) {
        Vec3 area;
        OpenFOAM_geometry::face_centre_and_area(mesh.points, pm.faces[f], e.location, area);
      }
      r.push_back(e);
    }
    return r;
  };
  Worst_cells w;
  w.scaled_jacobian = cells(q.scaled_jacobian, false);
  w.aspect_ratio = cells(q.aspect_ratio, true);
  w.non_orthogonality = faces(q.non_orthogonality);
  w.skewness = faces(q.skewness);
  w.face_warpage = faces(q.face_warpage);
  return w;
}

} // namespace Hex_meshing_3
} // namespace CGAL

#endif
