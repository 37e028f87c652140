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

#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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
} // namespace internal

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief Verdict's scaled Jacobian of the hexahedron with corners `p` in VTK order: 1 for a cube,
 * <= 0 for an inverted or degenerate cell.
 */
template <typename Point_3>
double scaled_jacobian(const std::array<Point_3, 8>& p)
{
  using namespace internal;
  static const int nb[8][3] = {{1,3,4},{2,0,5},{3,1,6},{0,2,7},{7,5,0},{4,6,1},{5,7,2},{6,4,3}};
  Vec3 x[8];
  for(int i = 0; i < 8; ++i) x[i] = vec(p[i]);
  double sj = std::numeric_limits<double>::max();
  auto det = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    const double la = norm(a), lb = norm(b), lc = norm(c);
    if(la == 0 || lb == 0 || lc == 0) return 0.0;
    return dot(a, cross(b, c)) / (la * lb * lc);
  };
  for(int i = 0; i < 8; ++i)
    sj = (std::min)(sj, det(sub(x[nb[i][0]], x[i]), sub(x[nb[i][1]], x[i]), sub(x[nb[i][2]], x[i])));
  const Vec3 X1 = add(add(sub(x[1], x[0]), sub(x[2], x[3])), add(sub(x[5], x[4]), sub(x[6], x[7])));
  const Vec3 X2 = add(add(sub(x[3], x[0]), sub(x[2], x[1])), add(sub(x[7], x[4]), sub(x[6], x[5])));
  const Vec3 X3 = add(add(sub(x[4], x[0]), sub(x[5], x[1])), add(sub(x[6], x[2]), sub(x[7], x[3])));
  sj = (std::min)(sj, det(X1, X2, X3));
  return (std::max)(-1.0, (std::min)(1.0, sj));
}

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

  template <typename Point_3>
  void compute(const std::vector<Point_3>& points, const Polyhedral_mesh_3& pm)
  {
    using namespace internal;
    const std::size_t nf = pm.faces.size();
    face_centres.assign(nf, Vec3{{0, 0, 0}});
    face_areas.assign(nf, Vec3{{0, 0, 0}});
    for(std::size_t f = 0; f < nf; ++f) {
      const auto& F = pm.faces[f];
      const std::size_t n = F.size();
      if(n == 3) {
        const Vec3 a = vec(points[F[0]]), b = vec(points[F[1]]), c = vec(points[F[2]]);
        face_centres[f] = mul(add(add(a, b), c), 1.0 / 3.0);
        face_areas[f] = mul(cross(sub(b, a), sub(c, a)), 0.5);
        continue;
      }
      Vec3 avg{{0, 0, 0}};
      for(auto v : F) avg = add(avg, vec(points[v]));
      avg = mul(avg, 1.0 / double(n));
      Vec3 sumN{{0, 0, 0}}, sumAc{{0, 0, 0}};
      double sumA = 0;
      for(std::size_t i = 0; i < n; ++i) {
        const Vec3 p = vec(points[F[i]]), q = vec(points[F[(i + 1) % n]]);
        const Vec3 c = add(add(p, q), avg);
        const Vec3 N = cross(sub(q, p), sub(avg, p));
        const double a = norm(N);
        sumN = add(sumN, N); sumA += a; sumAc = add(sumAc, mul(c, a));
      }
      face_centres[f] = sumA < 1e-300 ? avg : mul(sumAc, 1.0 / (3.0 * sumA));
      face_areas[f] = mul(sumN, 0.5);
    }
    const std::size_t nc = pm.number_of_cells;
    std::vector<Vec3> est(nc, Vec3{{0, 0, 0}});
    std::vector<int> nfaces(nc, 0);
    for(std::size_t f = 0; f < nf; ++f) {
      est[pm.owner[f]] = add(est[pm.owner[f]], face_centres[f]); ++nfaces[pm.owner[f]];
      if(f < pm.neighbour.size()) { est[pm.neighbour[f]] = add(est[pm.neighbour[f]], face_centres[f]); ++nfaces[pm.neighbour[f]]; }
    }
    for(std::size_t c = 0; c < nc; ++c) est[c] = mul(est[c], 1.0 / (std::max)(1, nfaces[c]));
    cell_centres.assign(nc, Vec3{{0, 0, 0}});
    cell_volumes.assign(nc, 0.0);
    auto add_pyramid = [&](std::size_t c, std::size_t f, double sign) {
      const double pyr3Vol = sign * dot(face_areas[f], sub(face_centres[f], est[c]));
      const Vec3 pc = add(mul(face_centres[f], 3.0 / 4.0), mul(est[c], 1.0 / 4.0));
      cell_centres[c] = add(cell_centres[c], mul(pc, pyr3Vol));
      cell_volumes[c] += pyr3Vol;
    };
    for(std::size_t f = 0; f < nf; ++f) {
      add_pyramid(pm.owner[f], f, 1.0);
      if(f < pm.neighbour.size()) add_pyramid(pm.neighbour[f], f, -1.0);
    }
    for(std::size_t c = 0; c < nc; ++c) {
      if(std::abs(cell_volumes[c]) > 1e-300) cell_centres[c] = mul(cell_centres[c], 1.0 / cell_volumes[c]);
      else cell_centres[c] = est[c];
      cell_volumes[c] /= 3.0;
    }
  }
};

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
};

/*!
 * \ingroup PkgHexMeshing3Quality
 * \brief computes the quality of `mesh`; `pm` is its polyhedral form (`Polyhedral_mesh_3::build()`).
 */
template <typename HexMesh>
Mesh_quality compute_quality(const HexMesh& mesh, const Polyhedral_mesh_3& pm)
{
  using namespace internal;
  Mesh_quality q;
  q.scaled_jacobian.resize(mesh.hexahedra.size());
  for(std::size_t c = 0; c < mesh.hexahedra.size(); ++c) {
    std::array<typename HexMesh::Point_3, 8> p;
    for(int k = 0; k < 8; ++k) p[k] = mesh.points[mesh.hexahedra[c][k]];
    q.scaled_jacobian[c] = scaled_jacobian(p);
  }
  OpenFOAM_geometry g;
  g.compute(mesh.points, pm);
  q.cell_volume = g.cell_volumes;
  const std::size_t ni = pm.neighbour.size();
  const double ROOTVSMALL = 1.0e-150, VSMALL = 1.0e-300;
  q.non_orthogonality.resize(ni);
  q.skewness.resize(pm.faces.size());
  for(std::size_t f = 0; f < pm.faces.size(); ++f) {
    const Vec3& S = g.face_areas[f];
    const Vec3& Cf = g.face_centres[f];
    const Vec3& Co = g.cell_centres[pm.owner[f]];
    const Vec3 Cpf = sub(Cf, Co);
    Vec3 d; double fd0;
    if(f < ni) {
      d = sub(g.cell_centres[pm.neighbour[f]], Co);
      const double c = dot(d, S) / (norm(d) * norm(S) + VSMALL);
      q.non_orthogonality[f] = std::acos((std::min)(1.0, (std::max)(-1.0, c))) * 180.0 / M_PI;
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
    for(auto v : pm.faces[f]) fd = (std::max)(fd, std::abs(dot(svHat, sub(vec(mesh.points[v]), Cf))));
    q.skewness[f] = msv / fd;
  }
  // aspect ratio (primitiveMeshTools::cellClosedness)
  std::vector<Vec3> sumMag(pm.number_of_cells, Vec3{{0, 0, 0}});
  for(std::size_t f = 0; f < pm.faces.size(); ++f) {
    const Vec3 m{{std::abs(g.face_areas[f][0]), std::abs(g.face_areas[f][1]), std::abs(g.face_areas[f][2])}};
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
  return q;
}

} // namespace Hex_meshing_3
} // namespace CGAL

#endif
