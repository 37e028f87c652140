// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_INTERNAL_BOUNDARY_CAPTURE_3_H
#define CGAL_HEX_MESHING_3_INTERNAL_BOUNDARY_CAPTURE_3_H

// Body-fitted boundary, HEXPRESS-style (ALGORITHMS.md §9.1): the staircase of grid faces left by
// the overlay grid is joined to the input surface by a buffer layer of hexahedra.
//
// 1. The staircase is prepared on the grid (see `staircase_cells_to_remove()`): cells with a
//    corner on the surface side closer than `gap` x their size are removed (a buffer hex must have
//    room); at a non-manifold vertex or edge of the staircase (a buffer vertex needs one outward
//    side) the fewest cells that make it manifold go, the ones nearest to the surface first
//    (`Octree_mesher_3::make_vertex_manifold()`); both repeat with trimming until nothing changes.
// 2. Every vertex of a surface face of the staircase gets a twin, placed at its closest point on
//    the surface (on a box plane, kept in it); each surface face (a,b,c,d) becomes the bottom of a
//    buffer hex (a,b,c,d,a',b',c',d'), whose top is the new boundary face. The twin of a hanging
//    edge midpoint of a surface face's edge (a,b) hangs on (a',b'), so a coarse buffer hex meets
//    two fine ones 1:2 across its side face (Polyhedral_mesh_3 splits such faces).
// 3. Feature curves are captured by chains of top-face edges (shortest paths on the buffer's outer
//    surface between the vertices nearest to the curve's ends, biased towards the curve), whose
//    vertices are snapped onto the curve; corners are snapped onto the corners. The top faces
//    between chains form surface regions, each projected only onto the input faces between the
//    same curves, so a vertex near a sharp edge does not jump to the other side.
// 4. Optimisation: every free vertex (interior, inner buffer vertex, box-plane vertex in its
//    plane, surface vertex on its region, curve vertex on its curve; corners stay) moves, hanging
//    nodes following their masters. Sweeps alternate between a Gauss-Seidel step on a smooth
//    shape energy (Knupp's corner condition numbers with Escobar's regularised determinant, so it
//    also untangles) and a move to the best of a few candidates that raises the minimum quality
//    (min of the scaled Jacobian and OpenFOAM's face-pyramid quality) of the cells it affects. No
//    move takes a cell below min(its quality, keep_quality): validity first, then quality.
// 5. Cells still inverted: their curve vertices, then corners, go back to the surface; then their
//    surface vertices are released into the volume (restarting from the staircase's extrusion).
//    Fidelity before quality: afterwards each of them goes back to its surface, curve or corner
//    as far as its cells allow, alone, then with its neighbours making room (joint moves); those
//    still off the surface are reported ("unreached"). A buffer
//    cell that stays below min_valid_quality, or at a face OpenFOAM would find too skewed, is
//    removed (the staircase face under it is the boundary there), and so is one that checkMesh
//    -allGeometry would find concave or at a face failing its tet decomposition
//    (`Options::remove_foam_faults`).

#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/Status.h>
#include <CGAL/Hex_meshing_3/quality.h>
#include <CGAL/Hex_meshing_3/IO/write_OpenFOAM.h>
#include <CGAL/Hex_meshing_3/internal/boundary_polygons.h>
#include <CGAL/Hex_meshing_3/internal/Min_union_find.h>
#include <CGAL/Hex_meshing_3/internal/sealed_border_edges.h>
#include <CGAL/Hex_meshing_3/internal/vertex_cells.h>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <queue>
#include <set>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>   // malloc_trim
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal {

inline std::uint64_t capture_edge_key(std::uint32_t a, std::uint32_t b)
{
  return a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
}

// The face pyramids OpenFOAM checks: each face split into 4 triangles around its vertex average,
// each triangle with the cell's vertex average forms a tetrahedron that must have a positive
// volume. Their 24 scaled volumes (6V / product of the 3 edge lengths at the face centre)
// relative to a cube's, face by face: 1 for a cube, <= 0 when a pyramid is inverted.
// With `stop`, the values stop at the first one below it: returns how many were written (24 if
// none is below `stop`).
inline int hex_pyramid_qualities(const Vec3* x, double* out, double stop = -std::numeric_limits<double>::infinity())
{
  Vec3 cc{{0, 0, 0}};
  for(int k = 0; k < 8; ++k) cc = add(cc, x[k]);
  cc = mul(cc, 0.125);
  int n = 0;
  for(const auto& f : hex_local_faces()) {
    const Vec3 fc = mul(add(add(x[f[0]], x[f[1]]), add(x[f[2]], x[f[3]])), 0.25);
    const Vec3 u = sub(cc, fc);
    const double uu = dot(u, u);
#if defined(__SSE2__)
    // two triangles at a time (SSE2, in every x86-64): the same operations in the same order as
    // the scalar code below, so the same values to the bit; 1.4 times faster alone (its square
    // roots and divisions in pairs), fandisk at diagonal / 80 on one thread 20.4 -> 17.3 s (this
    // function had a fifth of its samples). (The scaled Jacobians the same way: 1.06 times, not kept.)
    double ax[4], ay[4], az[4], aa[4], v[4];
    for(int i = 0; i < 4; ++i) {
      const Vec3 a = sub(x[f[i]], fc);
      ax[i] = a[0];
      ay[i] = a[1];
      az[i] = a[2];
      aa[i] = dot(a, a);
    }
    const __m128d U0 = _mm_set1_pd(u[0]), U1 = _mm_set1_pd(u[1]), U2 = _mm_set1_pd(u[2]), UU = _mm_set1_pd(uu);
    for(int p = 0; p < 4; p += 2) {
      // lanes: the triangles at corners p and p + 1 (a = corner, b = next corner)
      const int q = (p + 2) & 3;
      const __m128d Ax = _mm_loadu_pd(ax + p), Ay = _mm_loadu_pd(ay + p), Az = _mm_loadu_pd(az + p);
      const __m128d Bx = _mm_set_pd(ax[q], ax[p + 1]), By = _mm_set_pd(ay[q], ay[p + 1]), Bz = _mm_set_pd(az[q], az[p + 1]);
      const __m128d Cx = _mm_sub_pd(_mm_mul_pd(Ay, Bz), _mm_mul_pd(Az, By));
      const __m128d Cy = _mm_sub_pd(_mm_mul_pd(Az, Bx), _mm_mul_pd(Ax, Bz));
      const __m128d Cz = _mm_sub_pd(_mm_mul_pd(Ax, By), _mm_mul_pd(Ay, Bx));
      const __m128d D = _mm_add_pd(_mm_add_pd(_mm_mul_pd(Cx, U0), _mm_mul_pd(Cy, U1)), _mm_mul_pd(Cz, U2));
      const __m128d L = _mm_sqrt_pd(_mm_mul_pd(_mm_mul_pd(_mm_loadu_pd(aa + p), _mm_set_pd(aa[q], aa[p + 1])), UU));
      const __m128d Q = _mm_div_pd(_mm_xor_pd(D, _mm_set1_pd(-0.0)), L);   // (-D / l)
      _mm_storeu_pd(v + p, _mm_and_pd(_mm_cmpgt_pd(L, _mm_setzero_pd()), Q));   // (0 unless l > 0)
    }
    for(int i = 0; i < 4; ++i) {
      out[n] = v[i];
      if(out[n++] < stop) return n;
    }
#else
    Vec3 a[4];
    double aa[4];
    for(int i = 0; i < 4; ++i) { a[i] = sub(x[f[i]], fc); aa[i] = dot(a[i], a[i]); }
    for(int i = 0; i < 4; ++i) {
      const int j = (i + 1) & 3;
      const double l = std::sqrt(aa[i] * aa[j] * uu);
      out[n] = l > 0 ? -dot(cross(a[i], a[j]), u) / l : 0.0;
      if(out[n++] < stop) return n;
    }
#endif
  }
  // a cube: a, b = half diagonals of a face (orthogonal, length sqrt(2)/2), u = half an edge,
  // normal to the face: |a x b| |u| / (|a| |b| |u|) = 1
  return n;
}
// the smallest of them
inline double hex_pyramid_quality(const Vec3* x)
{
  double v[24];
  hex_pyramid_qualities(x, v);
  return min_of(v, 24);
}

// The corner tetrahedron of a face at vertex p (its neighbours `next` and `prev` along the face,
// which runs counter-clockwise seen from outside the cell) with the cell's centre c: 6V / product
// of the 3 edge lengths at p, relative to a cube's; > 0 when c is inside. Swapping `next` and
// `prev` scores the face for the cell on its other side.
inline double face_corner_quality(const Vec3& p, const Vec3& next, const Vec3& prev, const Vec3& c)
{
  const double cube = 1.0 / std::sqrt(3.0);   // a cube's corner: (b x a).u / (|a| |b| |u|)
  const Vec3 a = sub(next, p), b = sub(prev, p), u = sub(c, p);
  const double l = std::sqrt(dot(a, a) * dot(b, b) * dot(u, u));
  return l > 0 ? dot(cross(b, a), u) / (l * cube) : 0.0;
}

inline Vec3 hex_centre(const Vec3* x)
{
  Vec3 cc{{0, 0, 0}};
  for(int k = 0; k < 8; ++k) cc = add(cc, x[k]);
  return mul(cc, 0.125);
}

// How far a hexahedron with whole faces is from OpenFOAM's concave test (`concave_cell()`, checkMesh
// -allGeometry): the smallest, over its faces i and the other faces j, of -cos of the angle between
// face i's outward normal and the line from its centre to face j's centre. The test calls the
// cell concave below 1e-6; a cube has 1/sqrt(2).
inline double hex_concavity_margin(const Vec3* x)
{
  Vec3 fc[6], fn[6];
  for(int k = 0; k < 6; ++k) {
    const auto& f = hex_local_faces()[std::size_t(k)];
    foam_face_centre_and_area(4, [&](std::size_t i) { return x[f[i]]; }, fc[k], fn[k]);
    fn[k] = mul(fn[k], 1.0 / (std::max)(norm(fn[k]), 1e-300));
  }
  double m = 1;
  for(int i = 0; i < 6; ++i)
    for(int j = 0; j < 6; ++j) {
      if(j == i) continue;
      const Vec3 d = sub(fc[j], fc[i]);
      m = (std::min)(m, -dot(d, fn[i]) / (std::max)(norm(d), 1e-300));
    }
  return m;
}

// OpenFOAM's cell centre of a hexahedron (`primitiveMesh::makeCellCentresAndVols()`, as
// `OpenFOAM_geometry::compute()`): the faces' centres and area vectors, then the pyramids on the
// faces from the average of the face centres, their centroids weighted by their volumes. A face
// split by hanging nodes is taken whole here. Not the vertex average: on the skewed cells of the
// buffer the two differ enough that a face split valid around one is flat around the other
// (teapot: a face between two buffer cells of scaled Jacobian 0.49).
inline Vec3 foam_hex_centre(const Vec3* x)
{
  Vec3 fc[6], fa[6], est{{0, 0, 0}};
  for(int k = 0; k < 6; ++k) {
    const auto& f = hex_local_faces()[std::size_t(k)];
    foam_face_centre_and_area(4, [&](std::size_t i) { return x[f[i]]; }, fc[k], fa[k]);
    est = add(est, fc[k]);
  }
  est = mul(est, 1.0 / 6.0);
  Vec3 sc{{0, 0, 0}};
  double sv = 0;
  for(int i = 0; i < 6; ++i) {
    const double v = dot(fa[i], sub(fc[i], est));   // the faces' area vectors point outwards
    sv += v;
    sc = add(sc, mul(add(mul(fc[i], 0.75), mul(est, 0.25)), v));
  }
  return std::abs(sv) > 1e-300 ? mul(sc, 1.0 / sv) : est;
}

// The face decompositions OpenFOAM checks (checkMesh -allGeometry's "face tets": a base vertex of
// each face whose fan of triangles forms tetrahedra of positive volume with the cell centres on
// both sides): a quad split along one of its diagonals gives two triangles, each the corner
// triangle of a vertex off that diagonal. The two cells of a face must agree on the diagonal, and
// each sees only its own side, so both splits must be valid. For each of the 24 corners of the
// six faces (face by face), the corner triangle's tetrahedron with the cell's centre
// (OpenFOAM's, `foam_hex_centre()`): 6V / product of the 3 edge lengths at the corner, relative
// to a cube's. 1 for a cube; <= 0 when a split of a face gives this cell a tetrahedron that is
// flat or inverted.
inline void hex_face_split_qualities(const Vec3* x, double* out)
{
  const Vec3 cc = foam_hex_centre(x);
  int n = 0;
  for(const auto& f : hex_local_faces())
    for(int i = 0; i < 4; ++i) out[n++] = face_corner_quality(x[f[i]], x[f[(i + 1) % 4]], x[f[(i + 3) % 4]], cc);
}
// the smallest of them
inline double hex_face_split_quality(const Vec3* x)
{
  double v[24];
  hex_face_split_qualities(x, v);
  return min_of(v, 24);
}

// OpenFOAM's tet decomposition of a face needs a diagonal split whose corner tetrahedra are
// positive with the centres of both its cells: the better diagonal of the quad q[0..3] (in the
// order of the cell whose centre is `cc`), scored by the worse of its corners' qualities with
// `cc` and, if `cd` is given, with the centre of the cell across
inline double face_shared_split(const Vec3* q, const Vec3& cc, const Vec3* cd)
{
  double corner[4];
  for(int i = 0; i < 4; ++i) {
    const Vec3& p = q[i];
    const Vec3& next = q[(i + 1) % 4];
    const Vec3& prev = q[(i + 3) % 4];
    corner[i] = face_corner_quality(p, next, prev, cc);
    if(cd) corner[i] = (std::min)(corner[i], face_corner_quality(p, prev, next, *cd));
  }
  return (std::max)((std::min)(corner[1], corner[3]), (std::min)(corner[0], corner[2]));
}

// `g` (n vectors) becomes minus the direction d closest to -g with a_k . d >= 0 for the `m` rows
// a_k of `ga` (each n vectors, row by row), so that a step along -g lowers none of the
// constrained values at first order. d = -g + sum_k lambda_k a_k with lambda >= 0 minimising
// |d|^2 (the dual problem, a non-negative least squares), by projected Gauss-Seidel sweeps on
// lambda (Hildreth's method), until a sweep changes d by at most 1e-12 |g| or after `sweeps`
// sweeps. Where rows are nearly dependent the convergence is slow, and a violation of 1e-5 to
// 1e-3 |a| |g| may remain: the caller's guards catch it.
inline void project_direction(std::vector<Vec3>& g, const std::vector<Vec3>& ga, std::size_t m, std::size_t n,
                              int sweeps = 200)
{
  if(m == 0) return;
  std::vector<Vec3> d(n);
  for(std::size_t i = 0; i < n; ++i) d[i] = mul(g[i], -1);
  std::vector<double> lambda(m, 0.0), aa(m, 0.0);
  double scale = 0;
  for(std::size_t k = 0; k < m; ++k) {
    for(std::size_t i = 0; i < n; ++i) aa[k] += dot(ga[k * n + i], ga[k * n + i]);
    scale = (std::max)(scale, aa[k]);
  }
  double gn = 0;
  for(std::size_t i = 0; i < n; ++i) gn += dot(g[i], g[i]);
  gn = std::sqrt(gn);
  for(int sweep = 0; sweep < sweeps; ++sweep) {
    double change = 0;
    for(std::size_t k = 0; k < m; ++k) {
      if(!(aa[k] > 1e-30 * scale)) continue;   // a value no vertex of the patch moves
      double r = 0;
      for(std::size_t i = 0; i < n; ++i) r += dot(ga[k * n + i], d[i]);
      const double l = (std::max)(0.0, lambda[k] - r / aa[k]);
      const double dl = l - lambda[k];
      if(dl == 0) continue;
      lambda[k] = l;
      for(std::size_t i = 0; i < n; ++i) d[i] = add(d[i], mul(ga[k * n + i], dl));
      change = (std::max)(change, std::abs(dl) * std::sqrt(aa[k]));
    }
    if(change <= 1e-12 * gn) break;
  }
  for(std::size_t i = 0; i < n; ++i) g[i] = mul(d[i], -1);
}

// Knupp's shape energy of a hexahedron: the mean over its 8 corners of the squared condition
// number of the corner's Jacobian matrix A (its three edges), |A|^2 |adj A|^2 / (9 det^2); 1 for a
// cube, growing without bound as a corner flattens. The determinant is Escobar et al.'s
// regularised one, (det + sqrt(det^2 + 4 delta^2)) / 2, so an inverted corner has a finite (very
// large) energy that decreases towards validity: one objective untangles and smooths.
// If `g` is given, the energy's gradient with respect to each corner is added to g[0..7].
inline double hex_shape_energy(const Vec3* x, double delta2, Vec3* g = nullptr)
{
  static const int nb[8][3] = {{1,3,4},{2,0,5},{3,1,6},{0,2,7},{7,5,0},{4,6,1},{5,7,2},{6,4,3}};
  double e = 0;
  for(int i = 0; i < 8; ++i) {
    const Vec3 a = sub(x[nb[i][0]], x[i]), b = sub(x[nb[i][1]], x[i]), c = sub(x[nb[i][2]], x[i]);
    const Vec3 bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
    const double det = dot(a, bc);
    const double sq = std::sqrt(det * det + 4 * delta2);
    const double hd = 0.5 * (det + sq);
    const double aa = dot(a, a), bb = dot(b, b), cc = dot(c, c);
    const double f2 = aa + bb + cc;
    const double g2 = dot(bc, bc) + dot(ca, ca) + dot(ab, ab);
    const double k = 1.0 / (72 * hd * hd);   // the mean over 8 corners of f2 g2 / (9 hd^2)
    e += f2 * g2 * k;
    if(!g || !(sq > 0)) continue;
    const double ab_ = dot(a, b), bc_ = dot(b, c), ca_ = dot(c, a);
    // d/dv [f2 g2 / hd^2] = (2 v g2 + f2 dg2/dv) / hd^2 - 2 f2 g2 / (hd^2 sq) ddet/dv
    const Vec3 dga = add(mul(a, 2 * (cc + bb)), add(mul(c, -2 * ca_), mul(b, -2 * ab_)));
    const Vec3 dgb = add(mul(b, 2 * (cc + aa)), add(mul(c, -2 * bc_), mul(a, -2 * ab_)));
    const Vec3 dgc = add(mul(c, 2 * (bb + aa)), add(mul(b, -2 * bc_), mul(a, -2 * ca_)));
    const double t = -2 * f2 * g2 / sq;
    const Vec3 da = mul(add(add(mul(a, 2 * g2), mul(dga, f2)), mul(bc, t)), k);
    const Vec3 db = mul(add(add(mul(b, 2 * g2), mul(dgb, f2)), mul(ca, t)), k);
    const Vec3 dc = mul(add(add(mul(c, 2 * g2), mul(dgc, f2)), mul(ab, t)), k);
    g[nb[i][0]] = add(g[nb[i][0]], da);
    g[nb[i][1]] = add(g[nb[i][1]], db);
    g[nb[i][2]] = add(g[nb[i][2]], dc);
    g[i] = sub(g[i], add(add(da, db), dc));
  }
  return e;
}

// Lists per vertex stored end to end (a `Polygon_list`; a vector per vertex costs a 24-byte header
// and an allocation each: tens of MB for the capture's lists on the motorBike): rows 0..n-1 from
// (row, item) pairs, each row's items in the order of the pairs, or sorted and without repeats
// if `unique`
inline Polygon_list lists_from_pairs(std::size_t n, std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs, bool unique)
{
  if(unique) {
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  } else {
    std::stable_sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  }
  Polygon_list L;
  L.reserve(n, pairs.size());
  std::vector<std::uint32_t> row;
  std::size_t i = 0;
  for(std::size_t r = 0; r < n; ++r) {
    row.clear();
    for(; i < pairs.size() && pairs[i].first == r; ++i) row.push_back(pairs[i].second);
    L.push_back(row.begin(), row.end());
  }
  return L;
}

// Lists of which few are not empty, one per item (vertex, cell): 4 bytes an item and the lists
// that have elements, where a vector per item would take 24 bytes each (10 MB on motorBike,
// at the capture's memory peak)
template <typename T>
class Sparse_lists
{
  static constexpr std::uint32_t none = std::uint32_t(-1);

public:
  void assign(std::size_t n) { slot.assign(n, none); lists.clear(); }
  std::size_t size() const { return slot.size(); }
  const std::vector<T>& operator[](std::size_t i) const
  {
    static const std::vector<T> empty;
    return slot[i] == none ? empty : lists[slot[i]];
  }
  // the list of `i`, to be changed (made if it had none)
  std::vector<T>& at(std::size_t i)
  {
    if(slot[i] == none) { slot[i] = std::uint32_t(lists.size()); lists.emplace_back(); }
    return lists[slot[i]];
  }
  // a new item, with list `l`
  void push_back(std::vector<T> l)
  {
    slot.push_back(none);
    if(!l.empty()) { slot.back() = std::uint32_t(lists.size()); lists.push_back(std::move(l)); }
  }
  void swap(Sparse_lists& o) { slot.swap(o.slot); lists.swap(o.lists); }
  void shrink_to_fit() { slot.shrink_to_fit(); lists.shrink_to_fit(); }

private:
  std::vector<std::uint32_t> slot;
  std::vector<std::vector<T>> lists;
};

template <typename HexMesh, typename Domain>
std::vector<std::uint32_t> staircase_cells_to_remove(const HexMesh& m, const Domain& domain, double gap,
                                                     std::size_t* too_close = nullptr,
                                                     std::size_t* non_manifold = nullptr,
                                                     std::vector<std::uint32_t>* non_manifold_vertices = nullptr)
{
  typedef std::uint32_t Index;
  const std::size_t nv = m.points.size();
  std::vector<Index> start, cells;   // vertex -> cells (corners)
  vertex_cells(m, nv, start, cells);
  auto cell_size = [&](Index c) {
    const auto& h = m.hexahedra[c];
    return CGAL::to_double(m.points[h[1]].x() - m.points[h[0]].x());
  };
  const auto polys = boundary_polygons(m);
  std::vector<char> bad_vertex(nv, 0);
  std::size_t n_close = 0, n_nm = 0;
  // too close
  std::vector<char> surf(nv, 0);
  for(std::size_t f = 0; f < m.boundary_faces.size(); ++f)
    if(m.boundary_faces[f].patch >= 6) for(Index v : polys[f]) surf[v] = 1;
  for(Index v = 0; v < nv; ++v) {
    if(!surf[v] || start[v] == start[v + 1]) continue;
    double h = std::numeric_limits<double>::max();
    for(Index k = start[v]; k < start[v + 1]; ++k) h = (std::min)(h, cell_size(cells[k]));
    const double d2 = CGAL::to_double(domain.squared_distance(m.points[v]));
    if(d2 < gap * gap * h * h) { bad_vertex[v] = 1; ++n_close; }
  }
  // manifoldness: around each vertex, the polygons must form one cycle (each in-edge w->v matched by
  // exactly one polygon with out-edge v->w)
  std::vector<Index> pstart(nv + 1, 0), pinc;
  for(const auto& p : polys) for(Index v : p) ++pstart[v + 1];
  for(std::size_t v = 0; v < nv; ++v) pstart[v + 1] += pstart[v];
  pinc.resize(pstart[nv]);
  {
    std::vector<Index> pos(pstart.begin(), pstart.end() - 1);
    for(Index f = 0; f < polys.size(); ++f) for(Index v : polys[f]) pinc[pos[v]++] = f;
  }
  auto next_prev = [&](Index f, Index v, Index& nx, Index& pv) {
    const auto& p = polys[f];
    for(std::size_t i = 0; i < p.size(); ++i)
      if(p[i] == v) { nx = p[(i + 1) % p.size()]; pv = p[(i + p.size() - 1) % p.size()]; return; }
  };
  std::vector<Index> nxt, prv;
  std::vector<char> seen;
  for(Index v = 0; v < nv; ++v) {
    const Index n = pstart[v + 1] - pstart[v];
    if(n == 0) continue;
    nxt.resize(n); prv.resize(n);
    for(Index k = 0; k < n; ++k) next_prev(pinc[pstart[v] + k], v, nxt[k], prv[k]);
    bool ok = true;
    seen.assign(n, 0);
    Index cur = 0, visited = 0;
    for(;;) {
      seen[cur] = 1; ++visited;
      // the polygon whose in-edge (w -> v) has w = our out-neighbour
      Index found = n, count = 0;
      for(Index k = 0; k < n; ++k) if(prv[k] == nxt[cur]) { found = k; ++count; }
      if(count != 1) { ok = false; break; }
      if(seen[found]) { ok = (found == 0); break; }
      cur = found;
    }
    if(ok && visited != n) ok = false;
    if(!ok) { if(!bad_vertex[v]) bad_vertex[v] = 2; ++n_nm; }
  }
  std::vector<char> bad_cell(m.hexahedra.size(), 0);
  for(Index v = 0; v < nv; ++v) {
    if(!bad_vertex[v]) continue;
    // a vertex only non-manifold goes to the caller, which removes as few cells as it can
    if(non_manifold_vertices && bad_vertex[v] == 2) { non_manifold_vertices->push_back(v); continue; }
    for(Index k = start[v]; k < start[v + 1]; ++k) bad_cell[cells[k]] = 1;
    for(Index k = pstart[v]; k < pstart[v + 1]; ++k) bad_cell[m.boundary_faces[pinc[k]].cell] = 1;
  }
  std::vector<Index> out;
  for(Index c = 0; c < bad_cell.size(); ++c) if(bad_cell[c]) out.push_back(c);
  if(too_close) *too_close = n_close;
  if(non_manifold) *non_manifold = n_nm;
  return out;
}

template <typename HexMesh, typename Domain, typename FeatureCurves>
class Boundary_capture_3
{
public:
  typedef std::uint32_t Index;
  static constexpr Index NONE = ~Index(0);
  // A cell whose quality is at most this is flat, as good as inverted: a corner whose three edges
  // are coplanar to round-off (a surface vertex whose closest point is the crease between two
  // curve vertices of its face, a curve vertex between two others on a straight curve) scores
  // 1e-14, not 0. The untangling and the release work on such cells too, and no joint move may
  // leave one (the cleanup would remove it, leaving a hole in the buffer).
  static constexpr double degenerate_quality = 1e-6;
  typedef typename Domain::Geom_traits GT;
  typedef typename GT::Point_3 Point_3;
  typedef typename GT::Segment_3 Segment_3;
  typedef typename GT::Triangle_3 Triangle_3;

  enum Kind : std::uint8_t { INTERIOR, SURFACE, CURVE, CORNER, CAP, HANGING, RELEASED };

  struct Options
  {
    double target_quality = 0.6;   ///< cells below this minimum scaled Jacobian are optimised
    int passes = 8;                ///< optimisation sweeps at most (`smoothing_sweeps`)
    int final_passes = 10;          ///< sweeps after vertices were released
    int reattach_rounds = 10;      ///< rounds moving released vertices back towards the surface
    double snap_weight = 4;        ///< bias of the feature paths towards their curve
    double turn_penalty = 20;      ///< extra cost (x edge length) of a path turning inside a top face
    double curve_corridor = 3;     ///< a feature path keeps its vertices this close to its curve (x local size) ...
    double wide_curve_corridor = 6;   ///< ... or, if no path does, this close
    double corner_edge_cosine = 0.5;  ///< at a corner where a chain took as its first edge the edge of the corner's vertex another curve leaves along (within this cosine of the curve's direction; 0: never), the paths are searched again with each curve's edge kept for it (`snap_features()`)
    double keep_quality = 0.2;     ///< a move may not take a cell below min(its quality, this)
    double min_valid_quality = 0.02;   ///< buffer cells below this after optimisation are removed
    double buffer_thickness = 0.5;     ///< the buffer's thickness the inner vertices aim at, x local size
    double max_skewness = 3.5;         ///< buffer cells at a face more skewed than this are removed (OpenFOAM fails > 4)
    double removal_non_orthogonality = 70;   ///< ... or more non-orthogonal than this after the repairs, in degrees (checkMesh: "severely non-orthogonal")
    double min_face_split_quality = 0.05;   ///< cells whose faces split worse than this are repaired last
    double min_fold = 0.02;                 ///< `unfold_faces()` works on the cells with a whole face whose better diagonal split (in both cells) scores below this
    int face_split_passes = 4;              ///< sweeps of that repair (and of the split-face warp's)
    double max_split_face_warp = 0.05;      ///< faces split in four warped beyond this (x edge) are repaired last
    double max_non_orthogonality = 50;      ///< degrees: the cells at faces beyond it are worked on after the repairs
    double concave_margin = 0.05;           ///< `repair_concave_cells()` works last on the cells with whole faces whose `hex_concavity_margin()` is below this
    double split_concave_margin = 0.5;      ///< ... and lets no cell with a hanging node on a face lose margin below min(its own, this)
    bool feature_pillows = false;           ///< convex sharp curves get a sheet of hexahedra along their chain (`pillow_chains()`)
    double pillow_max_offset = 0.5;         ///< ... if their chain's vertices lie this close to the curve on average (x local size) before snapping
    double pillow_max_offset_closed = 2.5;  ///< ... or, for a closed curve with no corner, if none of them lies farther than this
    double polish_quality = 0.35;           ///< the polish works on cells below this and keeps the others above it
    int polish_passes = 8;                  ///< sweeps of the polish at most
    double patch_target = 0.4;              ///< the polish's joint moves (`polish_patches()`) penalise qualities below this
    int patch_iterations = 40;              ///< gradient steps of a patch at most (0: no joint moves)
    int patch_stall = 8;                    ///< ... stopped after this many steps without raising the patch's worst cell
    int patch_rings = 1;                    ///< ... on the vertices of the cells around the cell's (1), of the cells around those (2), ...
    double patch_floor = 0.3;               ///< the joint moves work around the cells below this, and keep a patch only if its count of cells whose scaled Jacobian is below it did not grow
    double patch_sharpness = 30;            ///< ... their penalty exp(k (target - q)) - 1: its k
    double loosen_curve = 0.2;              ///< the patch around a cell below `patch_floor` with curve vertices is tried first with them free to leave their curve by at most this (x local size; 0: never)
    double loosen_corner = 0.1;             ///< ... and with its corner vertices free to leave their corner's point by at most this (x local size; 0: never)
    double second_polish_pyramid_weight = 2;   ///< the second polish counts the face pyramids at this many times their value (1: no second polish)
    int fidelity_passes = 3;                ///< sweeps of `fidelity_polish()` (0: none)
    int turn_passes = 6;                    ///< sweeps of `turn_polish()`, until one moves nothing (0: none)
    bool turn_joint = true;                 ///< ... where a turn vertex's step alone fails the guards, try it with the other vertices of its cells improved once (`joint_turn_move()`)
    double turn_joint_far = 0.3;            ///< ... after the first two sweeps, only for turn vertices still farther than this from their curve (x local size)
    double turn_far_offset = 0.25;          ///< then the turn vertices whose top faces stand farther than this off the surface (x local size) ...
    double turn_far_quality = 0.32;         ///< ... are tried again with the guards' floor at this instead of polish_quality (0: not)
    double turn_distance = 0.1;             ///< ... which brings the vertices where a chain turns inside a face no closer than this to their curve (x local size)
    int joint_passes = 10;                  ///< improve() passes over a released vertex's neighbours while it is held on the surface (0: no joint moves)
    int joint_hopeless_passes = 3;          ///< ... given up after this many passes if a cell is still `joint_hopeless_margin` below its floor (0: never)
    double joint_hopeless_margin = 0.3;     ///< (see `joint_hopeless_passes`)
    double turn_joint_offset_slack = 1.2;   ///< a joint turn move is not tried at a step whose top faces stand farther off the surface than this x their cap before the neighbours move (0: always tried)
    double joint_quality = 0.25;            ///< ... kept if no cell of theirs falls below min(its quality, this)
    double feature_joint_quality = 0.35;    ///< the same for an unsnapped curve or corner vertex held on its feature (a feature regained at the price of the cells' quality: not below min(its quality, this))
    double sheet_cap_quality = 0.2;         ///< a sheet's cap vertex goes onto the sheet's border if no cell falls below min(its quality, this) (and none turns concave, no face split worsens)
    double fidelity_distance = 0.2;         ///< ... over the top faces whose centre is farther than this (x the smallest local size of their corners) from the surface
    bool release_search_tree = true;        ///< the cleanup frees the domain's search tree (false where another capture of the same domain runs at the same time: `make_hex_mesh_3()` with a parallel tag)
    bool remove_foam_faults = true;         ///< the cleanup removes the buffer cells that checkMesh -allGeometry would find concave or at a face failing the tet decomposition (on the points of the OpenFOAM export)
  };

  /// with `remove_foam_faults`, after `run()`: the cells concave for OpenFOAM (all, not only the
  /// buffer's) and the faces failing its tet decomposition before the removal, as
  /// `checkMesh -allGeometry` would count them on the mesh the same capture gives without it
  std::size_t foam_faults_found = 0;

  /// `stats` receives the counts of the capture (its body-fitted fields)
  Boundary_capture_3(HexMesh& mesh, const Domain& domain, const FeatureCurves* features, Meshing_statistics& stats,
                     const Options& o = Options())
    : m(mesh), d(domain), fc(features), opt(o), rep(stats)
  {}

  template <typename Visitor>
  bool run(Visitor& visitor)
  {
    for(int a = 0; a < 3; ++a) { box_lo[a] = m.box.min(a); box_hi[a] = m.box.max(a); }
    auto t0 = std::chrono::steady_clock::now();
    auto lap = [&](const char* step) {
      const auto t = std::chrono::steady_clock::now();
      rep.capture_seconds.emplace_back(step, std::chrono::duration<double>(t - t0).count());
      t0 = sub_t0 = t;
    };
    sub_t0 = t0;
    P.resize(m.points.size());
    for(std::size_t v = 0; v < P.size(); ++v) P[v] = vec(m.points[v]);
    // the mesh's points are freed while `P` holds them (`build_adjacency()`): if an exception
    // leaves the capture before they are written back, they are written back here, so that the
    // mesh stays whole (its points as many as its cells use)
    struct Points_back
    {
      Boundary_capture_3& c;
      ~Points_back()
      {
        if(!c.m.points.empty() || c.P.empty()) return;   // not freed, or written back already
        c.m.points.resize(c.P.size());
        for(std::size_t v = 0; v < c.P.size(); ++v) c.m.points[v] = Point_3(c.P[v][0], c.P[v][1], c.P[v][2]);
      }
    } points_back{*this};
    insert_buffer();
    build_topology();
    lap("buffer");
    place_twins();
    lap("twins");
    if(fc) snap_features();
    lap("features");
    build_regions();
    for(Index v = 0; v < P.size(); ++v)   // after snapping: back onto the surface regions
      if(kind[v] == SURFACE) P[v] = constrain(v, P[v]);
    update_hanging();
    lap("regions");
    // a cancellation stops the smoothing sweeps only: the steps that make every cell valid run
    optimise(visitor);
    lap("optimise");
    repair_face_splits();
    repair_split_face_warp();
    reduce_non_orthogonality();
    unfold_faces();
    lap("repairs");
    if(!cancelled) polish();   // not needed for validity: a cancellation skips it
    substep("polish.sweeps");
    if(!cancelled && opt.patch_iterations > 0) rep.polish_patches += polish_patches(visitor);
    substep("polish.patches");
    // The second polish: next to a stretched top face the face pyramids bind before the scaled
    // Jacobian (bunny: a cell at 0.246 whose inner vertices, moved together, reach 0.35 with no
    // pyramid below 0.2). The goals are on the scaled Jacobian and OpenFOAM needs the pyramids
    // positive, so the polish and its joint moves run again with the pyramids counted at
    // `second_polish_pyramid_weight` times their value, the joint moves around the cells whose
    // scaled Jacobian is below `patch_floor`, and no move may make a cell concave
    // (`cell_concave()`). Counting them so in the first polish already loses elsewhere.
    if(!cancelled && opt.second_polish_pyramid_weight != 1) {
      second_polish = true;
      polish();
      substep("polish.second_sweeps");
      if(!cancelled && opt.patch_iterations > 0) rep.polish_patches += polish_patches(visitor);
      substep("polish.second_patches");
      second_polish = false;
    }
    if(!cancelled) fidelity_polish(visitor);
    substep("polish.fidelity");
    if(!cancelled) turn_polish(visitor);
    substep("polish.turns");
    if(!cancelled) unfold_faces();
    substep("polish.unfold");
    if(!cancelled) repair_concave_cells();
    substep("polish.concave");
    lap("polish");
    assign_patches();
    release_work_data();
    // no surface query follows: the domain's search tree (a fifth of the cleanup's memory peak on
    // motorBike) is rebuilt by the next query made of the domain
    if(opt.release_search_tree) d.release_search_tree();
    remove_invalid_buffer_cells({});
    substep("cleanup.removal");
    m.points.resize(P.size());
    for(std::size_t v = 0; v < P.size(); ++v) m.points[v] = Point_3(P[v][0], P[v][1], P[v][2]);
    // OpenFOAM rejects faces skewed beyond 4: the buffer cells at such a face go too, and those at
    // a face the repairs left beyond 70 degrees of non-orthogonality (checkMesh's "severely
    // non-orthogonal"; the goal is 65) (a few rounds: a removal changes the faces around it)
    for(int round = 0; round < 8; ++round) {
      Polyhedral_mesh_3 pm;
      pm.build(m);
      const std::size_t first = m.hexahedra.size() - rep.buffer_cells;
      std::vector<Index> extra;
      {
        // (the cells' geometry only, the faces' computed where needed, and no per-face array: a
        // part of the cleanup's memory peak)
        OpenFOAM_geometry g;
        g.compute_cells(m.points, pm);
        for_each_face_non_orthogonality_and_skewness(m.points, pm, g, [&](std::size_t f, double no, double sk) {
          const bool skewed = sk > opt.max_skewness;
          const bool non_orthogonal = f < pm.neighbour.size() && no > opt.removal_non_orthogonality;
          if(!skewed && !non_orthogonal) return;
          const bool own = pm.owner[f] >= first, nei = f < pm.neighbour.size() && pm.neighbour[f] >= first;
          if(skewed) ++rep.skewed_faces;
          else if(own || nei) ++rep.non_orthogonal_faces;   // (between grid cells: left to the report)
          if(own) extra.push_back(pm.owner[f]);
          if(nei) extra.push_back(pm.neighbour[f]);
        });
      }
      // then what checkMesh -allGeometry reports on the points an OpenFOAM case gets (hanging
      // nodes bulged, `IO::internal::foam_points()` with the writer's defaults): the buffer cells
      // that are concave, and those at a face failing the tet decomposition (the repairs guard
      // both; what they leave goes)
      if(extra.empty() && opt.remove_foam_faults) {
        std::vector<char> concave, tets;
        {
          // (the rounds only: the node-by-node step after them is the writer's, for what the
          // removal cannot reach, as grid cells)
          const auto x = IO::internal::foam_points(m, IO::default_hanging_bulge, &pm, IO::default_max_hanging_bulge, nullptr, false);
          OpenFOAM_geometry gx;
          gx.compute_cells(x, pm);
          concave = concave_cells(x, pm, gx);
          tets = face_tet_errors(x, pm, gx);
          // and the cells whose determinant checkMesh finds small (`cell_determinants()`: few
          // internal faces, or nearly parallel ones; motorBike: one buffer cell), the buffer's
          // only (sums per buffer cell over the internal faces: less memory than all cells' faces)
          std::vector<Area_tensor_sum> acc(concave.size() - (std::min)(concave.size(), std::size_t(first)),
                                           Area_tensor_sum{{0, 0, 0, 0, 0, 0, 0, 0}});
          for(std::size_t f = 0; f < pm.neighbour.size(); ++f) {
            if(pm.owner[f] < first && pm.neighbour[f] < first) continue;
            Vec3 fc, fa;
            gx.face(x, pm, f, fc, fa);
            for(const std::size_t c : {std::size_t(pm.owner[f]), std::size_t(pm.neighbour[f])})
              if(c >= first) add_face_area(acc[c - first], fa);
          }
          for(std::size_t i = 0; i < acc.size(); ++i)
            if(area_tensor_determinant(acc[i]) < openfoam_min_cell_determinant) concave[first + i] = 2;
        }
        if(!foam_checked) {   // what checkMesh -allGeometry would find without the removal
          foam_checked = true;
          foam_faults_found = std::size_t(std::count_if(concave.begin(), concave.end(), [](char x) { return x != 0; })) +
                              std::size_t(std::count(tets.begin(), tets.end(), char(1)));
        }
        for(std::size_t c = first; c < concave.size(); ++c) if(concave[c]) extra.push_back(Index(c));
        for(std::size_t f = 0; f < tets.size(); ++f) {
          if(!tets[f]) continue;
          if(pm.owner[f] >= first) extra.push_back(pm.owner[f]);
          if(f < pm.neighbour.size() && pm.neighbour[f] >= first) extra.push_back(pm.neighbour[f]);
        }
        std::sort(extra.begin(), extra.end());
        extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
        rep.foam_fault_cells += extra.size();
      }
      if(extra.empty()) break;
      remove_invalid_buffer_cells(extra);
    }
    if(rep.removed_buffer_cells > 0) drop_unused_vertices();
    substep("cleanup.checks");
    lap("cleanup");
    return !cancelled;
  }

private:
  // -----------------------------------------------------------------------------------------------
  // 2. the buffer layer
  int plane_mask(const Vec3& p) const
  {
    int mask = 0;
    for(int a = 0; a < 3; ++a) {
      if(p[a] == box_lo[a]) mask |= 1 << (2 * a);
      if(p[a] == box_hi[a]) mask |= 1 << (2 * a + 1);
    }
    return mask;
  }

  void insert_buffer()
  {
    const std::size_t nv0 = P.size();
    twin.assign(nv0, NONE);
    std::vector<char> surf(nv0, 0);
    std::unordered_set<std::uint64_t> surface_edges;
    for(const auto& f : m.boundary_faces)
      if(f.patch >= 6)
        for(int i = 0; i < 4; ++i) { surf[f.vertices[i]] = 1; surface_edges.insert(capture_edge_key(f.vertices[i], f.vertices[(i + 1) % 4])); }
    // midpoints hanging on an edge of a surface face are surface vertices too (they are corners of
    // the finer faces next to it)
    // (reserved: growing these by doubling kept a third of them unused, at the capture's peak)
    std::size_t nsurf = 0, nbuf = 0;
    for(Index v = 0; v < nv0; ++v) nsurf += std::size_t(surf[v]);
    for(const auto& f : m.boundary_faces) nbuf += std::size_t(f.patch >= 6);
    P.reserve(nv0 + nsurf);
    m.hexahedra.reserve(m.hexahedra.size() + nbuf);
    m.cell_levels.reserve(m.cell_levels.size() + nbuf);
    buffer_owner.reserve(buffer_owner.size() + nbuf);
    top_faces.reserve(top_faces.size() + nbuf);
    inner.clear();
    inner.reserve(nsurf);
    for(Index v = 0; v < nv0; ++v)
      if(surf[v]) { twin[v] = Index(P.size()); inner.push_back(v); P.push_back(P[v]); }
    inner_of.assign(P.size(), NONE);
    for(Index v = 0; v < nv0; ++v) if(twin[v] != NONE) inner_of[twin[v]] = v;
    const std::size_t nh = m.hanging_nodes.size();
    for(std::size_t i = 0; i < nh; ++i) {
      const auto h = m.hanging_nodes[i];
      if(h.number_of_masters != 2 || twin[h.vertex] == NONE) continue;
      const Index a = h.masters[0], b = h.masters[1];
      if(twin[a] == NONE || twin[b] == NONE || !surface_edges.count(capture_edge_key(a, b))) continue;
      m.hanging_nodes.push_back({twin[h.vertex], {{twin[a], twin[b], 0, 0}}, 2});
    }
    std::vector<typename HexMesh::Boundary_face> faces;
    faces.reserve(m.boundary_faces.size() * 2);
    for(const auto& f : m.boundary_faces) {
      if(f.patch < 6) { faces.push_back(f); continue; }
      const Index c = Index(m.hexahedra.size());
      typename HexMesh::Hexahedron hx;
      for(int i = 0; i < 4; ++i) { hx[i] = f.vertices[i]; hx[i + 4] = twin[f.vertices[i]]; }
      m.hexahedra.push_back(hx);
      m.cell_levels.push_back(m.cell_levels[f.cell]);
      buffer_owner.push_back(f.cell);
      faces.push_back({{{hx[4], hx[5], hx[6], hx[7]}}, c, f.patch});
      top_faces.push_back(faces.size() - 1);
      // a side face on a box plane (the quad's edge lies in a plane the quad is not in)
      for(int i = 0; i < 4; ++i) {
        const Index a = f.vertices[i], b = f.vertices[(i + 1) % 4];
        int common = plane_mask(P[a]) & plane_mask(P[b]);
        int all = 0x3f;
        for(int k = 0; k < 4; ++k) all &= plane_mask(P[f.vertices[k]]);
        common &= ~all;
        if(!common) continue;
        int bit = 0;
        while(!(common & (1 << bit))) ++bit;
        faces.push_back({{{a, b, twin[b], twin[a]}}, c, bit});
      }
      ++rep.buffer_cells;
    }
    m.boundary_faces.swap(faces);
  }

  // -----------------------------------------------------------------------------------------------
  void build_topology()
  {
    const std::size_t nv = P.size();
    kind.assign(nv, INTERIOR);
    planes.assign(nv, 0);
    for(Index v = 0; v < nv; ++v) planes[v] = std::uint8_t(plane_mask(P[v]));
    for(Index v : inner) kind[twin[v]] = SURFACE;
    build_adjacency();
    // local size: the shortest incident edge of the staircase
    hloc.assign(nv, std::numeric_limits<double>::max());
    for(const auto& h : m.hexahedra)
      for(const auto& e : hex_local_edges()) {
        const double l = norm(sub(P[h[e[0]]], P[h[e[1]]]));
        if(l > 0) for(int k = 0; k < 2; ++k) hloc[h[e[k]]] = (std::min)(hloc[h[e[k]]], l);
      }
    for(Index v : inner) hloc[twin[v]] = hloc[v];
  }

  // hanging nodes, vertex-cell incidences, neighbours and top faces at each vertex (again after
  // the pillows changed the buffer)
  void build_adjacency()
  {
    const std::size_t nv = P.size();
    // hanging nodes: independent masters with weights
    hang_of.assign(nv, NONE);
    for(std::size_t i = 0; i < m.hanging_nodes.size(); ++i) {
      hang_of[m.hanging_nodes[i].vertex] = Index(i);
      kind[m.hanging_nodes[i].vertex] = HANGING;
    }
    m.points.resize(nv);   // the twins' places are filled at the end; the count is what matters here
    hang_masters.assign(m.hanging_nodes.size(), {});
    for(std::size_t i = 0; i < m.hanging_nodes.size(); ++i)
      for(const auto& x : m.independent_masters(m.hanging_nodes[i].vertex)) hang_masters[i].push_back(x);
    // the places are in `P` until the end of the capture (the mesh's copy took 11 MB at its memory
    // peak on motorBike)
    std::vector<Point_3>().swap(m.points);
    vertex_cells(m, nv, cstart, cinc);
    // independent vertex -> dependent hanging nodes
    std::vector<std::pair<Index, Index>> pairs;
    for(std::size_t i = 0; i < hang_masters.size(); ++i)
      for(const auto& x : hang_masters[i]) pairs.push_back({x.first, m.hanging_nodes[i].vertex});
    deps = lists_from_pairs(nv, pairs, false);
    // neighbours: hex edges for volume vertices (gathered per vertex from its cells: pairs from
    // every cell's edges would take 24 per cell), top-face edges for surface vertices
    nbrs = Polygon_list();
    nbrs.reserve(nv, 0);
    std::vector<Index> buf;
    for(Index v = 0; v < nv; ++v) {
      buf.clear();
      for(Index k = cstart[v]; k < cstart[v + 1]; ++k) {
        const auto& h = m.hexahedra[cinc[k]];
        for(const auto& e : hex_local_edges()) {
          if(h[e[0]] == v) buf.push_back(h[e[1]]);
          else if(h[e[1]] == v) buf.push_back(h[e[0]]);
        }
      }
      std::sort(buf.begin(), buf.end());
      buf.erase(std::unique(buf.begin(), buf.end()), buf.end());
      nbrs.push_back(buf.begin(), buf.end());
    }
    nbrs.shrink_to_fit();
    pairs.clear();
    for(std::size_t f : top_faces) {
      const auto& q = m.boundary_faces[f].vertices;
      for(int i = 0; i < 4; ++i) { pairs.push_back({q[i], q[(i + 1) % 4]}); pairs.push_back({q[(i + 1) % 4], q[i]}); }
    }
    snbrs = lists_from_pairs(nv, pairs, true);
    pairs.clear();
    for(std::size_t i = 0; i < top_faces.size(); ++i)
      for(Index v : m.boundary_faces[top_faces[i]].vertices) pairs.push_back({v, Index(i)});
    vertex_top_faces = lists_from_pairs(nv, pairs, false);
  }

  void update_hanging()
  {
    for(std::size_t i = 0; i < hang_masters.size(); ++i) recompute_hanging(Index(i));
  }
  void recompute_hanging(Index i)
  {
    Vec3 p{{0, 0, 0}};
    for(const auto& x : hang_masters[i]) p = add(p, mul(P[x.first], x.second));
    P[m.hanging_nodes[i].vertex] = p;
  }

  // -----------------------------------------------------------------------------------------------
  // projection
  Vec3 clamp_planes(Index v, Vec3 x) const
  {
    for(int a = 0; a < 3; ++a) {
      if(planes[v] & (1 << (2 * a))) x[a] = box_lo[a];
      if(planes[v] & (1 << (2 * a + 1))) x[a] = box_hi[a];
    }
    return x;
  }
  // the closest point of the vertex's region (of the whole surface if it has none)
  Vec3 closest_on_surface(const Vec3& x, int region) const
  {
    const Point_3 p(x[0], x[1], x[2]);
    if(region >= 0 && std::size_t(region) < region_trees.size() && region_trees[std::size_t(region)])
      return vec(region_trees[std::size_t(region)]->closest_point(p));
    return vec(d.closest_point(p));
  }
  // the same for a surface vertex, the search starting from the last point found for it (a point
  // of its region: the search only prunes with it)
  Vec3 closest_on_surface_from(Index v, const Vec3& x) const
  {
    const int region = region_of_vertex(v);
    if(!(region >= 0 && std::size_t(region) < region_trees.size() && region_trees[std::size_t(region)]))
      return closest_on_surface(x, region);
    if(hint_region.size() != P.size()) { hint_region.assign(P.size(), -1); hint.resize(P.size()); }
    const Point_3 p(x[0], x[1], x[2]);
    const auto& tree = *region_trees[std::size_t(region)];
    const Point_3 c = hint_region[v] == region ? tree.closest_point(p, hint[v]) : tree.closest_point(p);
    hint[v] = c;
    hint_region[v] = region;
    return vec(c);
  }
  bool on_hint(Index v) const
  {
    return v < hint_region.size() && hint_region[v] == region_of_vertex(v) && hint_region[v] >= 0 &&
           clamp_planes(v, vec(hint[v])) == P[v];
  }
  // a surface vertex near a hole, at `x` on the hole's border: its smoothing target lies over the
  // hole, and the cells between it and the hole's cap vertices collapse there
  bool onto_hole_rim(Index v, const Vec3& x) const
  {
    return hole_tree && v < near_hole.size() && near_hole[v] && kind[v] == SURFACE &&
           CGAL::to_double(hole_tree->squared_distance(Point_3(x[0], x[1], x[2]))) <= tiny_length() * tiny_length();
  }
  // a length below which two points of the meshing box are one (a point on a segment)
  double tiny_length() const { return 1e-9 * (box_hi[0] - box_lo[0] + box_hi[1] - box_lo[1] + box_hi[2] - box_lo[2]); }
  Vec3 closest_on_curve(const Vec3& x, int curve) const
  {
    return vec(curve_trees[std::size_t(curve)]->closest_point(Point_3(x[0], x[1], x[2])));
  }
  Vec3 constrain(Index v, const Vec3& x) const
  {
    switch(kind[v]) {
    case SURFACE: {
      const Vec3 y = clamp_planes(v, closest_on_surface_from(v, clamp_planes(v, x)));
      return v < loose_of.size() && loose_of[v] != NO_LOOSE ? pull_to_feature(v, y) : y;
    }
    case CURVE: return clamp_planes(v, closest_on_curve(x, curve_of[v]));
    case CORNER: case HANGING: return P[v];
    default: return clamp_planes(v, x);
    }
  }
  // the local cell size at a vertex (1 where it has none)
  double local_size(Index v) const { return hloc[v] < 1e300 ? hloc[v] : 1.0; }
  // a curve or corner vertex the polish let off its feature (`polish_patches()`): its kind before,
  // its region before, where it was
  struct Loose { Index v; Kind kind; int region; Vec3 at; };
  static constexpr std::uint32_t NO_LOOSE = std::uint32_t(-1);
  // the point of the loosened vertex's feature nearest to y, and how far it may be from it
  Vec3 feature_point(const Loose& l, const Vec3& y) const { return l.kind == CORNER ? l.at : closest_on_curve(y, curve_of[l.v]); }
  double loose_tolerance(const Loose& l) const { return (l.kind == CORNER ? opt.loosen_corner : opt.loosen_curve) * local_size(l.v); }
  // a loosened vertex's constrained position `y` (on its surface region) pulled back to within
  // 0.95 x its tolerance of its feature: three rounds of pull and projection (what is still
  // beyond the tolerance fails the polish's guard)
  Vec3 pull_to_feature(Index v, Vec3 y) const
  {
    const Loose& l = loose[loose_of[v]];
    const double tol = 0.95 * (l.kind == CORNER ? opt.loosen_corner : opt.loosen_curve) * local_size(v);
    for(int it = 0; it < 3; ++it) {
      const Vec3 f = feature_point(l, y);
      const double d = norm(sub(y, f));
      if(d <= tol) break;
      y = clamp_planes(v, closest_on_surface_from(v, add(f, mul(sub(y, f), tol / d))));
    }
    return y;
  }
  int region_of_point(const Vec3& x) const
  {
    if(tri_region.empty()) return -1;
    return tri_region[d.closest_triangle(Point_3(x[0], x[1], x[2]))];
  }
  int region_of_vertex(Index v) const { return v < vregion.size() ? vregion[v] : -1; }

  void place_twins()
  {
    // a twin whose closest point lies on an open edge of the input (a hole) caps the hole: it
    // stays near its inner vertex, pushed out along the staircase normal, and is not projected.
    // Open edges along another open edge (a seam between parts with their own vertices, a crack:
    // `sealed_border_edges()`) border no hole: a twin nearest to them is projected.
    std::unique_ptr<Segment_tree> open_tree;
    std::vector<Segment_3> open_segments;
    std::vector<std::array<std::uint32_t, 2>> ends;
    if(fc) {
      for(const auto& e : fc->edges())
        if(e.kind & FeatureCurves::OPEN) {
          open_segments.emplace_back(fc->point(e.vertices[0]), fc->point(e.vertices[1]));
          ends.push_back({{std::uint32_t(e.vertices[0]), std::uint32_t(e.vertices[1])}});
        }
      remove_sealed_border_edges<GT>(open_segments, ends, seam_tolerance(d.bbox()));
    }
    if(!open_segments.empty()) {
      open_tree = std::make_unique<Segment_tree>(open_segments.begin(), open_segments.end());
      open_tree->accelerate_distance_queries();
    }
    // the borders of holes: simple closed loops of open edges (every vertex on two of them; not
    // a dangling fin's border, which ends at a non-manifold edge; holes touching at a vertex are
    // left out too), not on a two-sided sheet; no surface vertex may slide onto them later
    // (`onto_hole_rim()`)
    {
      std::vector<std::uint32_t> verts;
      for(const auto& e : ends) { verts.push_back(e[0]); verts.push_back(e[1]); }
      std::sort(verts.begin(), verts.end());
      verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
      auto index_of = [&](std::uint32_t v) { return std::size_t(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin()); };
      Min_union_find<std::size_t> uf(verts.size());
      std::vector<int> degree(verts.size(), 0);
      for(const auto& e : ends) {
        const std::size_t a = index_of(e[0]), b = index_of(e[1]);
        ++degree[a]; ++degree[b];
        uf.unite(a, b);
      }
      std::vector<char> loop(verts.size(), 1);
      for(std::size_t i = 0; i < verts.size(); ++i)
        if(degree[i] != 2) loop[uf.find(i)] = 0;
      for(std::size_t i = 0; i < open_segments.size(); ++i) {
        const Segment_3& sg = open_segments[i];
        if(loop[uf.find(index_of(ends[i][0]))] && !d.is_two_sided(d.closest_triangle(CGAL::midpoint(sg.source(), sg.target()))))
          hole_segments.push_back(sg);
      }
    }
    if(!hole_segments.empty()) {
      hole_tree = std::make_unique<Segment_tree>(hole_segments.begin(), hole_segments.end());
      hole_tree->accelerate_distance_queries();
      near_hole.assign(P.size(), 0);
    }
    const double tiny = tiny_length();
    // outward normal of the staircase at each surface vertex
    std::vector<Vec3> normal(P.size(), Vec3{{0, 0, 0}});
    for(std::size_t f : top_faces) {
      const auto& q = m.boundary_faces[f].vertices;
      Vec3 n = cross(sub(P[q[2]], P[q[0]]), sub(P[q[3]], P[q[1]]));
      const double l = norm(n);
      if(l > 0) n = mul(n, 1.0 / l);
      for(int i = 0; i < 4; ++i) normal[q[i]] = add(normal[q[i]], n);
    }
    // unit normals of the staircase faces at each surface vertex (at most a few distinct ones)
    fnormals.assign(P.size());
    for(std::size_t f : top_faces) {
      const auto& q = m.boundary_faces[f].vertices;
      Vec3 n = cross(sub(P[inner_of[q[2]]], P[inner_of[q[0]]]), sub(P[inner_of[q[3]]], P[inner_of[q[1]]]));
      const double l = norm(n);
      if(!(l > 0)) continue;
      n = mul(n, 1.0 / l);
      for(int i = 0; i < 4; ++i) {
        auto& L = fnormals.at(q[i]);
        if(std::none_of(L.begin(), L.end(), [&](const Vec3& x) { return dot(x, n) > 0.999; })) L.push_back(n);
      }
    }
    for(Index v : inner) {
      const Index t = twin[v];
      if(kind[t] == HANGING) continue;
      ++rep.surface_vertices;
      Vec3 c = clamp_planes(t, vec(d.closest_point(Point_3(P[v][0], P[v][1], P[v][2]))));
      // the twin must lie in front of every staircase face at v (else its buffer hexes are flat
      // or inverted: a closest point on the other side of a sharp edge); if the closest point does
      // not, the surface point along the mean face normal is taken
      bool visible = true;
      const double dist = norm(sub(c, P[v]));
      for(const Vec3& n : fnormals[t]) if(dot(sub(c, P[v]), n) < 0.2 * dist) visible = false;
      if(!visible && norm(normal[t]) > 0) {
        Point_3 hit;
        const Vec3 dir = mul(normal[t], 1.0 / norm(normal[t]));
        if(d.first_ray_hit(Point_3(P[v][0], P[v][1], P[v][2]), typename GT::Vector_3(dir[0], dir[1], dir[2]), hit) &&
           norm(sub(vec(hit), P[v])) < 4 * hloc[v])
          c = clamp_planes(t, vec(hit));
      }
      bool cap = false;
      if(open_tree && open_tree->squared_distance(Point_3(c[0], c[1], c[2])) <= tiny * tiny) cap = true;
      if(cap) {
        kind[t] = CAP;
        ++rep.cap_vertices;
        // the border of a two-sided sheet (a baffle) is no hole: the buffer wraps round it, and
        // its cap vertices go onto it later as far as their cells allow (`optimise()`)
        if(d.is_two_sided(d.closest_triangle(Point_3(c[0], c[1], c[2])))) sheet_caps.push_back(t);
        const double l = norm(normal[t]);
        P[t] = clamp_planes(t, l > 0 ? add(P[v], mul(normal[t], 0.5 * hloc[v] / l)) : P[v]);
      } else {
        P[t] = c;
        if(hole_tree && hole_tree->squared_distance(Point_3(c[0], c[1], c[2])) < 4 * hloc[v] * hloc[v]) near_hole[t] = 1;
      }
    }
    update_hanging();
  }

  // -----------------------------------------------------------------------------------------------
  // 3. features
  // the curves to follow: the feature curves, and the user's feature lines (the domain's feature
  // segments, chained into polylines); their ends are corners
  struct Snap_curve { std::vector<Vec3> pts; bool closed = false; int c0 = -1, c1 = -1; };
  // a path of top-face edges following a curve from arc length s0 to s1
  struct Piece { std::vector<Index> path; double s0, s1; };

  void snap_features()
  {
    std::vector<Snap_curve> curves;
    std::vector<Vec3> corner_pts;
    std::map<std::array<double, 3>, int> corner_id;
    auto corner_of = [&](const Vec3& p) {
      auto it = corner_id.find(p);
      if(it != corner_id.end()) return it->second;
      corner_id[p] = int(corner_pts.size());
      corner_pts.push_back(p);
      return int(corner_pts.size()) - 1;
    };
    for(Index k : fc->corners()) corner_of(vec(fc->point(k)));
    for(const auto& cv : fc->curves()) {
      Snap_curve sc;
      for(Index i : cv.vertices) sc.pts.push_back(vec(fc->point(i)));
      sc.closed = cv.closed;
      if(!sc.closed) { sc.c0 = corner_of(sc.pts.front()); sc.c1 = corner_of(sc.pts.back()); }
      curves.push_back(std::move(sc));
    }
    const auto& segs = d.feature_segments();
    for(std::size_t i = 0; i < segs.size();) {
      Snap_curve sc;
      sc.pts.push_back(vec(segs[i].source()));
      std::size_t j = i;
      while(j < segs.size() && (j == i || segs[j].source() == segs[j - 1].target())) { sc.pts.push_back(vec(segs[j].target())); ++j; }
      if(sc.pts.size() > 3 && sc.pts.front() == sc.pts.back()) { sc.pts.pop_back(); sc.closed = true; }
      else { sc.c0 = corner_of(sc.pts.front()); sc.c1 = corner_of(sc.pts.back()); }
      curves.push_back(std::move(sc));
      i = j;
    }
    curve_trees.clear();
    all_curves_tree.reset();
    all_curve_segments.clear();
    segment_curve.clear();
    curve_ends.clear();
    for(const auto& cv : curves) curve_ends.push_back(cv.closed ? std::make_pair(-1, -1) : std::make_pair(cv.c0, cv.c1));
    curve_of.assign(P.size(), -1);
    cnbrs.assign(P.size());
    curve_segments.assign(curves.size(), {});
    for(std::size_t c = 0; c < curves.size(); ++c) {
      const auto& cv = curves[c];
      auto& sg = curve_segments[c];
      for(std::size_t i = 0; i + 1 < cv.pts.size(); ++i) sg.emplace_back(Point_3(cv.pts[i][0], cv.pts[i][1], cv.pts[i][2]), Point_3(cv.pts[i + 1][0], cv.pts[i + 1][1], cv.pts[i + 1][2]));
      if(cv.closed && cv.pts.size() > 2) sg.emplace_back(Point_3(cv.pts.back()[0], cv.pts.back()[1], cv.pts.back()[2]), Point_3(cv.pts[0][0], cv.pts[0][1], cv.pts[0][2]));
      curve_trees.push_back(sg.empty() ? nullptr : std::make_unique<Segment_tree>(sg.begin(), sg.end()));
      if(curve_trees.back()) curve_trees.back()->accelerate_distance_queries();
      all_curve_segments.insert(all_curve_segments.end(), sg.begin(), sg.end());
      segment_curve.insert(segment_curve.end(), sg.size(), int(c));
    }
    if(!all_curve_segments.empty()) {
      all_curves_tree = std::make_unique<Segment_tree>(all_curve_segments.cbegin(), all_curve_segments.cend());
      all_curves_tree->accelerate_distance_queries();
    }
    nearest_curve.assign(P.size(), {NOT_YET, 0.0});
    // outer-surface vertices that may carry a feature: surface twins (not hanging, not caps)
    std::vector<Index> outer;
    for(Index v : inner) if(kind[twin[v]] == SURFACE) outer.push_back(twin[v]);
    if(outer.empty()) return;
    // the outer vertices in a hash grid of cells 3 x the largest local size: every query below
    // wants a vertex within 3 local sizes, found among the 27 cells around the point
    double hmax = 0;
    for(Index v : outer) hmax = (std::max)(hmax, hloc[v]);
    const double g = 3 * hmax;
    auto cell_key = [&](const Vec3& x, int dx, int dy, int dz) {
      const std::int64_t i = std::int64_t(std::floor(x[0] / g)) + dx, j = std::int64_t(std::floor(x[1] / g)) + dy,
                         k = std::int64_t(std::floor(x[2] / g)) + dz;
      return std::uint64_t((i & 0x1fffff) | ((j & 0x1fffff) << 21) | ((k & 0x1fffff) << 42));
    };
    std::unordered_map<std::uint64_t, std::vector<Index>> grid;
    for(Index v : outer) grid[cell_key(P[v], 0, 0, 0)].push_back(v);
    auto for_near = [&](const Vec3& x, auto&& fn) {
      for(int dz = -1; dz <= 1; ++dz)
        for(int dy = -1; dy <= 1; ++dy)
          for(int dx = -1; dx <= 1; ++dx) {
            auto it = grid.find(cell_key(x, dx, dy, dz));
            if(it != grid.end()) for(Index u : it->second) fn(u);
          }
    };
    // the nearest allowed outer vertex within 3 local sizes (NONE if none)
    auto nearest = [&](const Vec3& x, auto&& allowed) {
      Index best = NONE;
      double bd = std::numeric_limits<double>::max();
      for_near(x, [&](Index u) {
        if(!allowed(u)) return;
        const double dd = dot(sub(P[u], x), sub(P[u], x));
        if(dd <= 9 * hloc[u] * hloc[u] && (dd < bd || (dd == bd && u < best))) { bd = dd; best = u; }
      });
      return best;
    };
    std::vector<char> allowed(P.size(), 0);   // outer vertices not taken by a corner
    for(Index v : outer) allowed[v] = 1;
    auto is_allowed = [&](Index u) { return allowed[u] != 0; };
    // curves shorter than two cells are not followed (on a coarse organic mesh, a 30 degree
    // angle finds many tiny ones); the corners are those of the curves followed
    std::vector<char> follow(curves.size(), 0), wanted_corners(corner_pts.size(), 0);
    for(std::size_t c = 0; c < curves.size(); ++c) {
      double len = 0;
      for(const auto& sg : curve_segments[c]) len += std::sqrt(CGAL::to_double(sg.squared_length()));
      const Index v0 = nearest(curves[c].pts.front(), is_allowed);
      if(v0 == NONE || len < 2 * hloc[v0]) continue;
      follow[c] = 1;
      if(!curves[c].closed) { wanted_corners[std::size_t(curves[c].c0)] = 1; wanted_corners[std::size_t(curves[c].c1)] = 1; }
    }
    // corners first: the nearest twin whose inner vertex sees the corner in front of its faces
    std::vector<Index> corner_vertex(corner_pts.size(), NONE);
    for(std::size_t k = 0; k < corner_pts.size(); ++k) {
      if(!wanted_corners[k]) continue;
      const Vec3 c = corner_pts[k];
      Index v = NONE;
      double bd = std::numeric_limits<double>::max();
      for_near(c, [&](Index u) {
        if(!allowed[u]) return;
        const double dd = norm(sub(P[u], c));
        if(dd > bd || (dd == bd && u > v) || dd > 3 * hloc[u]) return;
        bool sees = true;
        for(const Vec3& n : fnormals[u]) if(dot(sub(c, P[inner_of[u]]), n) <= 0) sees = false;
        if(sees) { bd = dd; v = u; }
      });
      if(v == NONE) {   // none sees it: the nearest
        v = nearest(c, is_allowed);
        if(v != NONE && norm(sub(P[v], c)) > 3 * hloc[v]) v = NONE;
      }
      if(v == NONE) continue;
      corner_vertex[k] = v;
      allowed[v] = 0;
      kind[v] = CORNER;
      P[v] = clamp_planes(v, c);
      ++rep.corner_vertices;
    }
    // curves: shortest paths on the outer surface between their end vertices (all paths first:
    // whether a chain gets a pillow depends on the chains around it)
    // The search is greedy, curve after curve: a curve searched late can find its corner walled
    // in by the paths of the curves searched before it (anchor: the three curves of a corner whose
    // four edges all lead diagonally across faces, two of them taking the two edges the third
    // needed). When a search leaves gaps or misses curves, it is run again with those curves
    // first, and the better of the two kept (fewer missed curves, then fewer gaps).
    struct Search {
      std::vector<char> used;
      std::vector<std::pair<std::size_t, std::vector<Piece>>> captured;
      std::size_t gaps = 0;
      std::vector<Vec3> missed_at;        // the missed curves' middle points
      std::vector<std::size_t> trouble;   // the curves missed or left with a gap
    };
    // (`reserved`: per curve, the edges of its corners' vertices kept for it, by their far ends
    // at its first and last corner; NONE: none. The other paths do not pass there; its own
    // path need not, and leaves an end it did not take to the curves after it.)
    std::vector<std::array<Index, 2>> reserved;
    auto search = [&](const std::vector<std::size_t>& order) {
      Search out;
      std::vector<char>& used = out.used;
      used.assign(P.size(), 0);
      std::vector<std::uint8_t> keep_count;   // per vertex: the curves not searched yet that keep it
      if(!reserved.empty()) {
        keep_count.assign(P.size(), 0);
        for(std::size_t c : order) for(Index w : reserved[c]) if(w != NONE) { ++keep_count[w]; used[w] = 1; }
      }
      auto& captured = out.captured;
      for(std::size_t c : order) {
        if(!follow[c]) continue;
        // this curve's kept edges open to it alone; afterwards kept again for the curves still to
        // come (a path this curve took has them in `used` already; a failed search cleared its own)
        struct Kept
        {
          const std::array<Index, 2> ends;
          std::vector<std::uint8_t>& count;
          std::vector<char>& used;
          Kept(const std::array<Index, 2>& e, std::vector<std::uint8_t>& n, std::vector<char>& u) : ends(e), count(n), used(u)
          {
            for(Index w : ends) if(w != NONE) { --count[w]; used[w] = 0; }
          }
          ~Kept() { for(Index w : ends) if(w != NONE && count[w] > 0) used[w] = 1; }
        } kept(reserved.empty() ? std::array<Index, 2>{{NONE, NONE}} : reserved[c], keep_count, used);
        const auto& cv = curves[c];
        const std::vector<Vec3>& pts = cv.pts;
        // waypoints: the ends (corners), plus, for closed curves, three points around the loop
        std::vector<std::size_t> way;
        if(cv.closed) { const std::size_t n = pts.size(); way = {0, n / 3, 2 * n / 3, 0}; }
        else way = {0, pts.size() - 1};
        std::vector<Index> wv;
        bool ok = true;
        for(std::size_t k = 0; k < way.size(); ++k) {
          Index v = NONE;
          if(!cv.closed) v = corner_vertex[std::size_t(k == 0 ? cv.c0 : cv.c1)];
          else if(k + 1 == way.size()) v = wv.front();
          else {
            v = nearest(pts[way[k]], [&](Index u) { return kind[u] == SURFACE && !used[u]; });
            if(v != NONE && norm(sub(P[v], pts[way[k]])) > 2 * hloc[v]) v = NONE;
          }
          if(v == NONE) { ok = false; break; }
          wv.push_back(v);
        }
        auto miss = [&]() { out.missed_at.push_back(pts[pts.size() / 2]); out.trouble.push_back(c); };
        if(!ok || wv.size() < 2) { miss(); continue; }
        // arc length of the curve at its vertices
        const std::vector<double> arc = curve_arc(c);
        // a path that never turns inside a face if there is one, else one that turns as little as
        // it can; if none keeps within `curve_corridor` local sizes of the curve, one within
        // `wide_curve_corridor` (fine cells at a thin or acute part leave the buffer's vertices
        // several of their sizes short of a ridge: t20_part's two curved ridges were missed, and
        // the mesh cut across them 0.37 surface sizes off)
        auto find_path = [&](Index a, Index b) {
          std::vector<Index> p = shortest_path(a, b, int(c), used, true, opt.curve_corridor);
          if(p.empty()) p = shortest_path(a, b, int(c), used, false, opt.curve_corridor);
          if(p.empty()) p = shortest_path(a, b, int(c), used, false, opt.wide_curve_corridor);
          return p;
        };
        // a free surface vertex within one local size of the curve's point at arc length s
        auto free_near = [&](double s) {
          const Vec3 x = point_at(c, arc, s);
          Index v = nearest(x, [&](Index u) { return kind[u] == SURFACE && !used[u]; });
          if(v != NONE && norm(sub(P[v], x)) > hloc[v]) v = NONE;
          return v;
        };
        std::vector<Piece> pieces;
        std::vector<Index> marked;
        std::size_t gaps = 0;
        for(std::size_t k = 0; k + 1 < wv.size() && ok; ++k) {
          double s0 = arc[way[k]], s1 = (k + 2 == wv.size() && cv.closed) ? arc.back() : arc[way[k + 1]];
          std::vector<Index> p = find_path(wv[k], wv[k + 1]);
          if(p.empty()) {
            // an end walled in by the curves already followed (three or more meet at a corner that
            // has few edges): the piece starts or ends 1.5 local sizes along the curve instead,
            // leaving that much of the curve uncaptured
            const double step = 1.5 * hloc[wv[k]];
            if(s1 - s0 > 4 * step) {
              const Index a2 = free_near(s0 + step), b2 = free_near(s1 - step);
              const std::pair<Index, Index> tries[3] = {{a2, wv[k + 1]}, {wv[k], b2}, {a2, b2}};
              for(const auto& t : tries) {
                if(t.first == NONE || t.second == NONE || t.first == t.second) continue;
                p = find_path(t.first, t.second);
                if(p.empty()) continue;
                if(t.first != wv[k]) { s0 += step; used[t.first] = 1; marked.push_back(t.first); ++gaps; }
                if(t.second != wv[k + 1]) { s1 -= step; used[t.second] = 1; marked.push_back(t.second); ++gaps; }
                break;
              }
            }
          }
          if(p.empty()) { ok = false; break; }
          for(std::size_t i = 1; i + 1 < p.size(); ++i) { used[p[i]] = 1; marked.push_back(p[i]); }
          pieces.push_back({std::move(p), s0, s1});
        }
        if(!ok) {
          for(Index v : marked) used[v] = 0;
          miss();
          continue;
        }
        out.gaps += gaps;
        if(gaps > 0) out.trouble.push_back(c);
        for(const Piece& piece : pieces) for(Index v : piece.path) used[v] = 1;   // the ends too
        captured.push_back({c, std::move(pieces)});
      }
      return out;
    };
    std::vector<std::size_t> order(curves.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    Search found = search(order);
    std::vector<std::size_t> found_order = order;
    if(!found.trouble.empty()) {
      std::vector<char> first(curves.size(), 0);
      for(std::size_t c : found.trouble) first[c] = 1;
      std::stable_partition(order.begin(), order.end(), [&](std::size_t c) { return first[c] != 0; });
      Search again = search(order);
      const std::size_t missed = found.missed_at.size(), missed_again = again.missed_at.size();
      if(missed_again < missed || (missed_again == missed && again.gaps < found.gaps)) {
        // the chains in curve order, as the first search has them
        std::sort(again.captured.begin(), again.captured.end(),
                  [](const auto& x, const auto& y) { return x.first < y.first; });
        found = std::move(again);
        found_order = order;
      }
    }
    // A curve searched early can leave its corner along the edge another curve of that corner
    // leaves along: that curve then starts across a face (fandisk's corner (0.4603, 0.1544,
    // -0.0071), whose vertex has edges along -x, -y, +z and +y: the curve along -z took the -x
    // edge, and the -x curve's chain ran a row of faces off it, the mesh creased 0.92 surface
    // sizes from any sharp edge). At each corner the curves are given the edges of the corner's
    // vertex closest to their direction (the point one local size along the curve; greedy by
    // cosine, at least `corner_edge_cosine`); where a chain took another curve's edge, the search
    // runs again (in the order of the search kept) with the edges of those corners kept for their
    // curves, and is kept if it misses no more curves and leaves no more gaps.
    if(opt.corner_edge_cosine > 0) {
      std::vector<std::vector<std::pair<std::size_t, int>>> at(corner_pts.size());   // corner -> its curves' ends
      for(std::size_t c = 0; c < curves.size(); ++c)
        if(follow[c] && !curves[c].closed) {
          at[std::size_t(curves[c].c0)].push_back({c, 0});
          at[std::size_t(curves[c].c1)].push_back({c, 1});
        }
      // the chains' first edges at their corners (their far ends; NONE: none)
      std::vector<std::array<Index, 2>> first(curves.size(), {{NONE, NONE}});
      for(const auto& cp : found.captured) {
        const auto& cv = curves[cp.first];
        if(cv.closed || cp.second.empty()) continue;
        const auto& p0 = cp.second.front().path;
        const auto& p1 = cp.second.back().path;
        if(p0.size() > 1 && p0.front() == corner_vertex[std::size_t(cv.c0)]) first[cp.first][0] = p0[1];
        if(p1.size() > 1 && p1.back() == corner_vertex[std::size_t(cv.c1)]) first[cp.first][1] = p1[p1.size() - 2];
      }
      std::vector<std::array<Index, 2>> keep(curves.size(), {{NONE, NONE}});
      bool again = false;
      for(std::size_t k = 0; k < corner_pts.size(); ++k) {
        const Index v = corner_vertex[k];
        if(v == NONE || at[k].size() < 2) continue;
        struct Candidate { double cosine; std::size_t end; Index w; };
        std::vector<Candidate> cand;
        for(std::size_t e = 0; e < at[k].size(); ++e) {
          const std::size_t c = at[k][e].first;
          const std::vector<double> arc = curve_arc(c);
          const double s = (std::min)(hloc[v], 0.5 * arc.back());
          const Vec3 u = sub(point_at(c, arc, at[k][e].second == 0 ? s : arc.back() - s), P[v]);
          const double lu = norm(u);
          if(!(lu > 0)) continue;
          for(Index w : snbrs[v]) {
            if(kind[w] != SURFACE || !allowed[w]) continue;
            const Vec3 dw = sub(P[w], P[v]);
            const double ld = norm(dw);
            if(ld > 0 && dot(u, dw) >= opt.corner_edge_cosine * lu * ld) cand.push_back({dot(u, dw) / (lu * ld), e, w});
          }
        }
        std::sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) {
          return a.cosine > b.cosine || (a.cosine == b.cosine && (a.end < b.end || (a.end == b.end && a.w < b.w)));
        });
        std::vector<Index> given(at[k].size(), NONE);
        for(const Candidate& cd : cand)
          if(given[cd.end] == NONE && std::find(given.begin(), given.end(), cd.w) == given.end()) given[cd.end] = cd.w;
        // another curve's chain took an edge given to a curve here
        bool taken = false;
        for(std::size_t e = 0; e < at[k].size() && !taken; ++e)
          for(std::size_t o = 0; o < at[k].size() && given[e] != NONE && !taken; ++o)
            taken = o != e && first[at[k][o].first][std::size_t(at[k][o].second)] == given[e];
        if(!taken) continue;
        again = true;
        for(std::size_t e = 0; e < at[k].size(); ++e) keep[at[k][e].first][std::size_t(at[k][e].second)] = given[e];
      }
      if(again) {
        reserved = std::move(keep);
        Search kept_edges = search(found_order);
        reserved.clear();
        if(kept_edges.missed_at.size() <= found.missed_at.size() && kept_edges.gaps <= found.gaps) {
          std::sort(kept_edges.captured.begin(), kept_edges.captured.end(),
                    [](const auto& x, const auto& y) { return x.first < y.first; });
          found = std::move(kept_edges);
          ++rep.corner_edge_searches;
        }
      }
    }
    std::vector<char>& used = found.used;
    const auto& captured = found.captured;
    rep.curves_captured += captured.size();
    rep.curves_missed += found.missed_at.size();
    rep.missed_curves.insert(rep.missed_curves.end(), found.missed_at.begin(), found.missed_at.end());
    rep.curve_gaps += found.gaps;
    // the chains of convex sharp curves get a pillow (see `pillow_chains()`) where the chains
    // around them allow it
    std::vector<char> pillow(curves.size(), 0);
    if(opt.feature_pillows) choose_pillows(captured, pillow);
    for(const auto& cp : captured) {
      const std::size_t c = cp.first;
      const auto& pieces = cp.second;
      const std::vector<double> arc = curve_arc(c);
      // snap the path vertices onto the curve, spaced along it as they are along the path (a
      // closest-point snap could put two of them on one point)
      for(const Piece& piece : pieces) {
        const auto& pc = piece.path;
        // where the path turns inside a top face (two of its edges in a row), the middle vertex is
        // not snapped: three corners of one face on the curve would flatten it; the curve crosses
        // that face along its diagonal
        // (a pillowed chain has no such face once its pillow is in)
        std::vector<char> skip(pc.size(), 0);
        for(std::size_t i = 1; i + 1 < pc.size() && !pillow[c]; ++i)
          if(!skip[i - 1] && share_top_face(pc[i - 1], pc[i], pc[i + 1])) skip[i] = 1;
        std::vector<double> cum{0};
        Index last = pc[0];
        for(std::size_t i = 1; i < pc.size(); ++i) {
          cum.push_back(cum.back() + (skip[i] ? 0.0 : norm(sub(P[pc[i]], P[last]))));
          if(!skip[i]) last = pc[i];
        }
        for(std::size_t i = 0; i < pc.size(); ++i) {
          const Index v = pc[i];
          used[v] = 1;
          if(skip[i]) { turn_vertices.push_back(v); turn_curve.push_back(int(c)); }
          if(kind[v] != SURFACE || skip[i]) continue;   // corners stay; shared ends are placed once
          kind[v] = CURVE;
          curve_of[v] = int(c);
          const double t = cum.back() > 0 ? cum[i] / cum.back() : 0;
          P[v] = clamp_planes(v, point_at(c, arc, piece.s0 + t * (piece.s1 - piece.s0)));
          ++rep.curve_vertices;
        }
        for(std::size_t i = 0; i + 1 < pc.size(); ++i) {
          feature_edges.insert(capture_edge_key(pc[i], pc[i + 1]));
          cnbrs.at(pc[i]).push_back(pc[i + 1]);
          cnbrs.at(pc[i + 1]).push_back(pc[i]);
        }
      }
    }
    if(std::find(pillow.begin(), pillow.end(), 1) != pillow.end()) pillow_chains(captured, pillow);
    // a top face with a curve vertex between two other snapped corners of it is flat where the
    // three are collinear (a path back in a face it left, or two curves side by side): that
    // vertex goes back to the surface, the curve crosses the face (a turn: `turn_polish()`
    // brings it as close to its curve as the cells allow)
    auto snapped = [&](Index v) { return kind[v] == CURVE || kind[v] == CORNER; };
    for(std::size_t f : top_faces) {
      const auto& q = m.boundary_faces[f].vertices;
      for(int k = 0; k < 4; ++k)
        if(kind[q[k]] == CURVE && snapped(q[(k + 1) % 4]) && snapped(q[(k + 3) % 4])) {
          kind[q[k]] = SURFACE;
          --rep.curve_vertices;
          turn_vertices.push_back(q[k]);
          turn_curve.push_back(curve_of[q[k]]);
          break;
        }
    }
    // a corner with its two chain edges in one top face at more than 135 degrees, both ends
    // snapped: the face has three corners along the curves and is flat there (where two curves or
    // two pieces of a chain meet at the corner, which the turn test above does not see). The
    // corner stays; its curve neighbours in that face go back to the surface (turns: the curves
    // cross the face). (Not with pillows: a pillowed chain's corner cell has such faces.)
    const bool any_pillow = std::find(pillow.begin(), pillow.end(), 1) != pillow.end();
    if(!any_pillow) for(std::size_t f : top_faces) {
      const auto& q = m.boundary_faces[f].vertices;
      for(int k = 0; k < 4; ++k) {
        const Index v = q[std::size_t(k)], a = q[std::size_t((k + 1) % 4)], b = q[std::size_t((k + 3) % 4)];
        if(kind[v] != CORNER || !snapped(a) || !snapped(b) || !feature_edges.count(capture_edge_key(v, a)) ||
           !feature_edges.count(capture_edge_key(v, b)))
          continue;
        const Vec3 da = sub(P[a], P[v]), db = sub(P[b], P[v]);
        const double l = norm(da) * norm(db);
        if(!(l > 0) || dot(da, db) > -std::sqrt(0.5) * l) continue;
        for(const Index w : {a, b})
          if(kind[w] == CURVE) {
            kind[w] = SURFACE;
            --rep.curve_vertices;
            turn_vertices.push_back(w);
            turn_curve.push_back(curve_of[w]);
          }
        break;
      }
    }
    update_hanging();
  }

  bool share_top_face(Index a, Index b, Index c) const
  {
    for(std::size_t f : vertex_top_faces[b]) {
      const auto& q = m.boundary_faces[top_faces[f]].vertices;
      if(std::find(q.begin(), q.end(), a) != q.end() && std::find(q.begin(), q.end(), c) != q.end()) return true;
    }
    return false;
  }

  // -----------------------------------------------------------------------------------------------
  // 3b. pillows along convex feature chains
  //
  // A chain of top-face edges follows a curve on the staircase's grid, so it turns inside faces
  // where the curve is oblique to the grid, and a face with three corners on the curve is flat.
  // At a convex sharp curve the buffer is cut along the chain instead: each side of the chain
  // gets its own copies of the chain's vertices (on its own surface region), and one hexahedron per
  // chain edge fills the cut, its section (inner vertex, side-A copy, curve vertex, side-B copy)
  // a quadrilateral with two boundary faces meeting at the curve. Where three pillowed curves
  // meet at a corner, one hexahedron closes the three pillows (the cube-corner cell). Concave
  // curves keep one vertex for both sides (their section would have an angle beyond 180 degrees).

  // `x` seen from `t` along a top-face edge: the far end of the edge of which `x` is the hanging
  // midpoint, or `x` itself
  Index canonical_end(Index t, Index x) const
  {
    if(kind[x] != HANGING || hang_of[x] == NONE) return x;
    const auto& h = m.hanging_nodes[hang_of[x]];
    if(h.number_of_masters != 2) return x;
    if(h.masters[0] == t) return h.masters[1];
    if(h.masters[1] == t) return h.masters[0];
    return x;
  }

  // The fan of top faces at `t` (in the order of `vertex_top_faces[t]`): the ends of each face's
  // edges after and before `t`, and its sector once the fan is cut at the edges in `cut`. Returns
  // the number of sectors, -1 if the fan is not a closed disk.
  struct Fan { std::vector<Index> next, prev; std::vector<int> sector; };
  int fan_sectors(Index t, const std::unordered_set<std::uint64_t>& cut, Fan& fan) const
  {
    const auto& F = vertex_top_faces[t];
    const std::size_t n = F.size();
    fan.next.assign(n, NONE);
    fan.prev.assign(n, NONE);
    fan.sector.assign(n, -1);
    for(std::size_t i = 0; i < n; ++i) {
      const auto& q = m.boundary_faces[top_faces[F[i]]].vertices;
      int k = 0;
      while(k < 4 && q[std::size_t(k)] != t) ++k;
      if(k == 4) return -1;
      fan.next[i] = canonical_end(t, q[std::size_t((k + 1) % 4)]);
      fan.prev[i] = canonical_end(t, q[std::size_t((k + 3) % 4)]);
    }
    Min_union_find<std::size_t> uf(n);
    for(std::size_t i = 0; i < n; ++i) {
      std::size_t match = n, after = 0, before = 0;
      for(std::size_t j = 0; j < n; ++j) {
        if(fan.prev[j] == fan.next[i]) { match = j; ++before; }
        if(fan.next[j] == fan.next[i]) ++after;
      }
      if(before != 1 || after != 1) return -1;
      if(!cut.count(capture_edge_key(t, fan.next[i]))) uf.unite(i, match);
    }
    int ns = 0;
    std::vector<int> id(n, -1);
    for(std::size_t i = 0; i < n; ++i) {
      const std::size_t r = uf.find(i);
      if(id[r] < 0) id[r] = ns++;
      fan.sector[i] = id[r];
    }
    return ns;
  }

  // whether the mesh is convex at every edge of the input's curve `c` (a curve of `fc`): the far
  // vertex of each triangle lies behind the other's plane, the planes oriented out of the mesh
  // (exact orientation tests; which side of the input the mesh is on is voted by the buffer's
  // vertices next to the chain, against their closest triangles)
  bool convex_curve(std::size_t c, const std::vector<Piece>& pieces) const
  {
    const auto& tris = d.triangle_indices();
    const auto& X = d.points();
    typename GT::Orientation_3 orientation = GT().orientation_3_object();
    // which side: + if the mesh is behind the triangles' normals
    int vote = 0, voters = 0;
    std::set<Index> on_path;
    for(const Piece& pc : pieces) on_path.insert(pc.path.begin(), pc.path.end());
    std::set<Index> seen;
    for(Index v : on_path)
      for(Index w : snbrs[v]) {
        if(on_path.count(w) || kind[w] != SURFACE || inner_of[w] == NONE || !seen.insert(w).second) continue;
        const std::size_t T = d.closest_triangle(point(P[w]));
        if(d.is_two_sided(T)) return false;
        const auto& ti = tris[T];
        const Index iv = inner_of[w];
        const CGAL::Orientation o = orientation(X[ti[0]], X[ti[1]], X[ti[2]], point(P[iv]));
        if(o == CGAL::NEGATIVE) ++vote;
        else if(o == CGAL::POSITIVE) --vote;
        ++voters;
      }
    if(voters == 0 || 2 * std::abs(vote) < voters) return false;
    const CGAL::Orientation behind = vote > 0 ? CGAL::NEGATIVE : CGAL::POSITIVE;
    const auto& cv = fc->curves()[c].vertices;
    const std::size_t ne = fc->curves()[c].closed ? cv.size() : cv.size() - 1;
    for(std::size_t i = 0; i < ne; ++i) {
      const Index a = cv[i], b = cv[(i + 1) % cv.size()];
      auto it = curve_edge_triangles.find(capture_edge_key(a, b));
      if(it == curve_edge_triangles.end() || it->second.size() != 2) return false;
      const auto& t1 = tris[it->second[0]];
      const auto& t2 = tris[it->second[1]];
      if(d.is_two_sided(it->second[0]) || d.is_two_sided(it->second[1])) return false;
      auto far = [&](const auto& t) {
        for(int k = 0; k < 3; ++k) if(t[std::size_t(k)] != a && t[std::size_t(k)] != b) return t[std::size_t(k)];
        return t[0];
      };
      // consistently oriented across the edge: a -> b in one, b -> a in the other
      auto forward = [&](const auto& t) {
        for(int k = 0; k < 3; ++k) if(t[std::size_t(k)] == a) return t[std::size_t((k + 1) % 3)] == b;
        return false;
      };
      if(forward(t1) == forward(t2)) return false;
      if(orientation(X[t1[0]], X[t1[1]], X[t1[2]], X[far(t2)]) != behind) return false;
      if(orientation(X[t2[0]], X[t2[1]], X[t2[2]], X[far(t1)]) != behind) return false;
    }
    return true;
  }

  // the curves whose chains get a pillow: convex ones, whose chain vertices are off the box planes
  // and have fans that are closed disks cut into two sectors (three at a corner where three
  // pillowed chains meet); a curve failing at one vertex loses its pillow, until none fails
  void choose_pillows(const std::vector<std::pair<std::size_t, std::vector<Piece>>>& captured, std::vector<char>& pillow)
  {
    if(!fc) return;
    std::unordered_set<std::uint64_t> curve_edges;
    for(const auto& cp : captured) {
      if(cp.first >= fc->curves().size()) continue;
      const auto& cv = fc->curves()[cp.first].vertices;
      for(std::size_t i = 0; i + 1 < cv.size(); ++i) curve_edges.insert(capture_edge_key(cv[i], cv[i + 1]));
      if(fc->curves()[cp.first].closed && cv.size() > 2) curve_edges.insert(capture_edge_key(cv.back(), cv.front()));
    }
    curve_edge_triangles.clear();
    const auto& tris = d.triangle_indices();
    for(Index t = 0; t < tris.size(); ++t)
      for(int k = 0; k < 3; ++k) {
        const std::uint64_t key = capture_edge_key(tris[t][std::size_t(k)], tris[t][std::size_t((k + 1) % 3)]);
        if(curve_edges.count(key)) curve_edge_triangles[key].push_back(t);
      }
    // (and whose chain runs close to the curve: a chain a row of faces off it leaves that row to
    // cross the curve, which the pillow makes worse - measured on t20_part and fandisk. A closed
    // curve - a cylinder's rim, a hole's - has no corner where its pillow meets other chains:
    // its chain may run farther off, up to `pillow_max_offset_closed` local sizes at its farthest
    // vertex (1.5 on average, 2 at most on the rims of cylinder.off at its test size; unpillowed,
    // their chains turn inside 26 faces and the feature fidelity is 0.37 / 0.74 surface sizes,
    // pillowed 0.03 / 0.02, with a higher minimum scaled Jacobian). Open curves at 1 local size on
    // average: fandisk gets 16 far faces, t20_part's mesh-to-input feature distance 0.78 -> 1.01.)
    for(const auto& cp : captured) {
      if(!(cp.first < fc->curves().size() && convex_curve(cp.first, cp.second))) continue;
      double sum = 0, farthest = 0;
      std::size_t n = 0;
      for(const Piece& pc : cp.second)
        for(Index v : pc.path) {
          const double o = norm(sub(closest_on_curve(P[v], int(cp.first)), P[v])) / hloc[v];
          sum += o;
          farthest = (std::max)(farthest, o);
          ++n;
        }
      const auto& curve = fc->curves()[cp.first];
      const bool loop = curve.closed && !curve.vertices.empty() &&   // (a loop from a corner back to it has a corner)
                        std::find(fc->corners().begin(), fc->corners().end(), curve.vertices.front()) == fc->corners().end();
      const bool near = loop ? farthest <= opt.pillow_max_offset_closed : sum <= opt.pillow_max_offset * double(n);
      if(n > 0 && near) pillow[cp.first] = 1;
    }
    Fan fan;
    for(bool changed = true; changed;) {
      changed = false;
      std::unordered_set<std::uint64_t> cut;
      std::map<Index, std::vector<std::size_t>> at;   // chain vertex -> its pillowed curves, once per chain edge
      for(const auto& cp : captured) {
        if(!pillow[cp.first]) continue;
        for(const Piece& pc : cp.second)
          for(std::size_t i = 0; i + 1 < pc.path.size(); ++i) {
            cut.insert(capture_edge_key(pc.path[i], pc.path[i + 1]));
            at[pc.path[i]].push_back(cp.first);
            at[pc.path[i + 1]].push_back(cp.first);
          }
      }
      // the chain edges of the other curves at each vertex (they meet the pillows at corners)
      std::map<Index, std::vector<Index>> others;
      for(const auto& cp : captured) {
        if(pillow[cp.first]) continue;
        for(const Piece& pc : cp.second)
          for(std::size_t i = 0; i + 1 < pc.path.size(); ++i) {
            if(at.count(pc.path[i])) others[pc.path[i]].push_back(pc.path[i + 1]);
            if(at.count(pc.path[i + 1])) others[pc.path[i + 1]].push_back(pc.path[i]);
          }
      }
      std::vector<std::size_t> drop;
      for(const auto& a : at) {
        const Index t = a.first;
        const int k = int(a.second.size());
        const int ns = planes[t] == 0 && inner_of[t] != NONE ? fan_sectors(t, cut, fan) : -1;
        bool ok = ns == k && (k == 2 || (k == 3 && kind[t] == CORNER));
        // another curve's chain ending here runs inside one sector, whose copy of the vertex then
        // starts that chain (one per sector; none at a corner cell)
        auto o = others.find(t);
        if(ok && o != others.end()) {
          std::vector<char> taken(std::size_t(ns), 0);
          ok = k == 2;
          for(Index e : o->second) {
            std::size_t i = 0;
            while(i < fan.next.size() && fan.next[i] != e) ++i;
            if(!ok || i == fan.next.size() || taken[std::size_t(fan.sector[i])]) { ok = false; break; }
            taken[std::size_t(fan.sector[i])] = 1;
          }
        }
        if(ok) continue;
        drop.insert(drop.end(), a.second.begin(), a.second.end());
      }
      for(std::size_t c : drop) if(pillow[c]) { pillow[c] = 0; changed = true; }
    }
  }

  // a copy of vertex `t` for a pillow (same inner vertex, size, normals)
  Index pillow_vertex(Index t, Kind k)
  {
    const Index v = Index(P.size());
    P.push_back(P[t]);
    kind.push_back(k);
    planes.push_back(planes[t]);
    hloc.push_back(hloc[t]);
    inner_of.push_back(inner_of[t]);
    fnormals.push_back(fnormals[t]);
    curve_of.push_back(-1);
    cnbrs.push_back({});
    return v;
  }

  void pillow_chains(const std::vector<std::pair<std::size_t, std::vector<Piece>>>& captured, const std::vector<char>& pillow)
  {
    struct Chain_edge { Index t, u; int curve; };
    std::vector<Chain_edge> edges;
    std::unordered_set<std::uint64_t> cut;
    std::map<Index, int> count;
    for(const auto& cp : captured) {
      if(!pillow[cp.first]) continue;
      for(const Piece& pc : cp.second)
        for(std::size_t i = 0; i + 1 < pc.path.size(); ++i) {
          edges.push_back({pc.path[i], pc.path[i + 1], int(cp.first)});
          cut.insert(capture_edge_key(pc.path[i], pc.path[i + 1]));
          ++count[pc.path[i]];
          ++count[pc.path[i + 1]];
        }
    }
    // the fans and one new vertex per sector
    std::map<Index, Fan> fans;
    std::map<Index, std::vector<Index>>& sector_twin = pillow_twins;
    for(const auto& kc : count) {
      Fan& fan = fans[kc.first];
      const int ns = fan_sectors(kc.first, cut, fan);
      CGAL_assertion(ns == kc.second);
      std::vector<Index>& tw = sector_twin[kc.first];
      for(int s_ = 0; s_ < ns; ++s_) { tw.push_back(pillow_vertex(kc.first, SURFACE)); ++rep.surface_vertices; }
    }
    auto sector_vertex = [&](Index t, std::size_t i) { return sector_twin[t][std::size_t(fans[t].sector[i])]; };
    // the face of the fan at `t` whose edge after (before) `t` goes to `u`
    auto face_after = [&](Index t, Index u) {
      const Fan& f = fans[t];
      for(std::size_t i = 0; i < f.next.size(); ++i) if(f.next[i] == u) return i;
      CGAL_assertion(false);
      return std::size_t(0);
    };
    auto face_before = [&](Index t, Index u) {
      const Fan& f = fans[t];
      for(std::size_t i = 0; i < f.prev.size(); ++i) if(f.prev[i] == u) return i;
      CGAL_assertion(false);
      return std::size_t(0);
    };
    // hanging twins whose master is a chain vertex hang on that master's copy for the sector
    // of their faces
    for(auto& hn : m.hanging_nodes) {
      if(hn.number_of_masters != 2) continue;
      for(int j = 0; j < 2; ++j) {
        const Index p = hn.masters[std::size_t(j)];
        auto it = fans.find(p);
        if(it == fans.end()) continue;
        const auto& F = vertex_top_faces[p];
        for(std::size_t i = 0; i < F.size(); ++i) {
          const auto& q = m.boundary_faces[top_faces[F[i]]].vertices;
          if(std::find(q.begin(), q.end(), hn.vertex) != q.end()) { hn.masters[std::size_t(j)] = sector_vertex(p, i); break; }
        }
      }
    }
    // the buffer cells and top faces of each sector take its copy
    for(const auto& kf : fans) {
      const Index t = kf.first;
      const auto& F = vertex_top_faces[t];
      for(std::size_t i = 0; i < F.size(); ++i) {
        auto& bf = m.boundary_faces[top_faces[F[i]]];
        const Index tw = sector_vertex(t, i);
        for(Index& x : bf.vertices) if(x == t) x = tw;
        for(Index& x : m.hexahedra[bf.cell]) if(x == t) x = tw;
      }
    }
    // another curve's chain ending at a pillowed vertex starts from the copy of its sector
    std::set<Index> on_other;
    for(const auto& cp : captured) {
      if(pillow[cp.first]) continue;
      for(const Piece& pc : cp.second)
        for(std::size_t i = 0; i + 1 < pc.path.size(); ++i)
          for(int end = 0; end < 2; ++end) {
            const Index t = pc.path[i + std::size_t(end)], e = pc.path[i + std::size_t(1 - end)];
            if(!fans.count(t)) continue;
            const Index tw = sector_vertex(t, face_after(t, e));
            kind[tw] = CURVE;
            curve_of[tw] = int(cp.first);
            P[tw] = clamp_planes(tw, closest_on_curve(mul(add(P[t], P[e]), 0.5), int(cp.first)));
            --rep.surface_vertices;
            ++rep.curve_vertices;
            on_other.insert(tw);
            for(Index& x : cnbrs.at(e)) if(x == t) x = tw;
            auto& ct = cnbrs.at(t);
            ct.erase(std::remove(ct.begin(), ct.end(), e), ct.end());
            ct.push_back(tw);
            cnbrs.at(tw) = {t, e};
            feature_edges.erase(capture_edge_key(t, e));
            feature_edges.insert(capture_edge_key(t, tw));
            feature_edges.insert(capture_edge_key(tw, e));
          }
    }
    // corners where three pillows meet: each chain ends at a vertex of its own on its curve, near
    // the corner; the corner cell joins them
    struct End { Index other, q; int sa, sb; int curve; };
    std::map<Index, std::vector<End>> corner_ends;
    for(const auto& kc : count)
      if(kc.second == 3) corner_ends[kc.first];
    auto end_vertex = [&](Index c, Index e, int curve, int sa, int sb) {
      auto it = corner_ends.find(c);
      if(it == corner_ends.end()) return c;
      for(const End& en : it->second) if(en.other == e) return en.q;
      const Index q = pillow_vertex(c, CURVE);
      curve_of[q] = curve;
      P[q] = clamp_planes(q, closest_on_curve(mul(add(P[c], P[e]), 0.5), curve));
      ++rep.curve_vertices;
      for(Index& x : cnbrs.at(c)) if(x == e) x = q;
      for(Index& x : cnbrs.at(e)) if(x == c) x = q;
      cnbrs.at(q) = {c, e};
      feature_edges.erase(capture_edge_key(c, e));
      feature_edges.insert(capture_edge_key(c, q));
      feature_edges.insert(capture_edge_key(q, e));
      it->second.push_back({e, q, sa, sb, curve});
      return q;
    };
    std::map<Index, std::array<Index, 4>> corner_face;   // a chain cell's outward face at a corner, from the inner vertex
    auto add_cell = [&](const typename HexMesh::Hexahedron& hx, int level_cell) {
      const Index c = Index(m.hexahedra.size());
      m.hexahedra.push_back(hx);
      m.cell_levels.push_back(m.cell_levels[std::size_t(level_cell)]);
      buffer_owner.push_back(NONE);
      ++rep.buffer_cells;
      ++rep.pillow_cells;
      return c;
    };
    auto add_top = [&](const std::array<Index, 4>& q, Index cell, int patch) {
      m.boundary_faces.push_back({q, cell, patch});
      top_faces.push_back(m.boundary_faces.size() - 1);
    };
    for(const Chain_edge& e : edges) {
      const Index t = e.t, u = e.u;
      const std::size_t at_t = face_after(t, u), bt_t = face_before(t, u), au = face_before(u, t), bu = face_after(u, t);
      const auto& fa = m.boundary_faces[top_faces[vertex_top_faces[t][at_t]]];
      const auto& fb = m.boundary_faces[top_faces[vertex_top_faces[t][bt_t]]];
      const int patch_a = fa.patch, patch_b = fb.patch, level_cell = int(fa.cell);
      const int sa_t = fans[t].sector[at_t], sb_t = fans[t].sector[bt_t];
      const int sa_u = fans[u].sector[au], sb_u = fans[u].sector[bu];
      const Index tA = sector_twin[t][std::size_t(sa_t)], tB = sector_twin[t][std::size_t(sb_t)];
      const Index uA = sector_twin[u][std::size_t(sa_u)], uB = sector_twin[u][std::size_t(sb_u)];
      const Index t1 = end_vertex(t, u, e.curve, sa_t, sb_t), u1 = end_vertex(u, t, e.curve, sa_u, sb_u);
      const typename HexMesh::Hexahedron hx{{inner_of[t], tA, t1, tB, inner_of[u], uA, u1, uB}};
      const Index c = add_cell(hx, level_cell);
      add_top({{tA, t1, u1, uA}}, c, patch_a);
      add_top({{tB, uB, u1, t1}}, c, patch_b);
      feature_edges.insert(capture_edge_key(t1, u1));
      if(t1 != t) corner_face[t] = {{inner_of[t], tB, t1, tA}};   // local face 4 (0, 3, 2, 1)
      if(u1 != u) corner_face[u] = {{inner_of[u], uA, u1, uB}};   // local face 5 (4, 5, 6, 7)
    }
    for(const auto& ce : corner_ends) {
      const Index c = ce.first;
      const auto& ends = ce.second;
      CGAL_assertion(ends.size() == 3);
      const auto& f = corner_face[c];   // (inner, a, q, b) outward from its chain cell
      const auto& tw = sector_twin[c];
      auto sector_of_twin = [&](Index x) { return int(std::find(tw.begin(), tw.end(), x) - tw.begin()); };
      const int sa = sector_of_twin(f[1]), sb = sector_of_twin(f[3]);
      const int sz = 3 - sa - sb;
      auto q_between = [&](int s1, int s2) {
        for(const End& en : ends) if((en.sa == s1 && en.sb == s2) || (en.sa == s2 && en.sb == s1)) return en.q;
        CGAL_assertion(false);
        return NONE;
      };
      const Index z = tw[std::size_t(sz)], qaz = q_between(sa, sz), qbz = q_between(sb, sz);
      const typename HexMesh::Hexahedron hx{{f[0], f[1], f[2], f[3], z, qaz, c, qbz}};
      // the patches of the sectors' faces
      int patch[3] = {6, 6, 6};
      const auto& F = vertex_top_faces[c];
      for(std::size_t i = 0; i < F.size(); ++i) patch[fans[c].sector[i]] = m.boundary_faces[top_faces[F[i]]].patch;
      const Index cell = add_cell(hx, int(m.boundary_faces[top_faces[F[0]]].cell));
      add_top({{f[1], f[2], c, qaz}}, cell, patch[sa]);   // local face 1 (1, 2, 6, 5)
      add_top({{f[3], qbz, c, f[2]}}, cell, patch[sb]);   // local face 3 (3, 7, 6, 2)
      add_top({{z, qaz, c, qbz}}, cell, patch[sz]);       // local face 5 (4, 5, 6, 7)
    }
    // the copies start on their sector's side: at the mean centre of its faces, on the surface
    for(const auto& kf : fans) {
      const auto& F = vertex_top_faces[kf.first];
      for(std::size_t i = 0; i < F.size(); ++i) pillow_sector_faces[sector_vertex(kf.first, i)].push_back(F[i]);
    }
    std::vector<std::pair<Index, Vec3>> start;   // all from the positions before any copy moves
    for(const auto& ps : pillow_sector_faces)
      if(!on_other.count(ps.first)) start.push_back({ps.first, sector_centre(ps.first)});
    for(const auto& st : start) P[st.first] = clamp_planes(st.first, vec(d.closest_point(point(st.second))));
    // the arrays the pillows grew by doubling, back to their sizes (motorBike: its 22 pillow cells
    // doubled the capacity of the cells' and the vertices' arrays, 36 MiB allocated to the end of
    // the capture, 4 MiB of it resident at the memory peak)
    auto fit = [](auto& x) { x.shrink_to_fit(); };
    fit(P); fit(kind); fit(planes); fit(hloc); fit(inner_of); fit(fnormals); fit(curve_of); fit(cnbrs);
    fit(m.hexahedra); fit(m.cell_levels); fit(buffer_owner); fit(m.boundary_faces); fit(top_faces);
    build_adjacency();
  }

  // the mean of the centres of the faces of the sector of a pillow's copy `tw`
  Vec3 sector_centre(Index tw) const
  {
    Vec3 g{{0, 0, 0}};
    const auto& F = pillow_sector_faces.at(tw);
    for(std::size_t f : F) {
      Vec3 cc{{0, 0, 0}};
      for(Index x : m.boundary_faces[top_faces[f]].vertices) cc = add(cc, mul(P[x], 0.25));
      g = add(g, cc);
    }
    const double n = double(F.size());
    return Vec3{{g[0] / n, g[1] / n, g[2] / n}};
  }

  static Point_3 point(const Vec3& x) { return Point_3(x[0], x[1], x[2]); }

  // the distance tree of surface region `r` (`region_trees`), built at its first use
  void build_region_tree(std::size_t r)
  {
    if(region_trees[r]) return;
    region_trees[r] = std::make_unique<Tree>();
    for(const Triangle_3* t : region_triangles[r]) region_trees[r]->insert(typename Tree::Primitive(t));
    region_trees[r]->build();
    // no search tree of reference points for the distance queries (CGAL builds one at the first
    // query by default: 17 MiB of the motorBike's memory peak, 264,327 triangles in its regions):
    // the queries of surface vertices start from their last closest point
    // (`closest_on_surface_from()`), and the motorBike's capture takes as long without it
    region_trees[r]->do_not_accelerate_distance_queries();
  }

  // the arc length of curve c at its points (its segments' ends, from the first)
  std::vector<double> curve_arc(std::size_t c) const
  {
    std::vector<double> arc{0};
    for(const auto& sg : curve_segments[c]) arc.push_back(arc.back() + std::sqrt(CGAL::to_double(sg.squared_length())));
    return arc;
  }
  Vec3 point_at(std::size_t c, const std::vector<double>& arc, double s) const
  {
    const auto& segs = curve_segments[c];
    std::size_t i = std::size_t(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin());
    i = i == 0 ? 0 : (std::min)(i - 1, segs.size() - 1);
    const double l = arc[i + 1] - arc[i];
    const double t = l > 0 ? (std::min)(1.0, (std::max)(0.0, (s - arc[i]) / l)) : 0;
    const Vec3 a = vec(segs[i].source()), b = vec(segs[i].target());
    return add(a, mul(sub(b, a), t));
  }

  // Dijkstra on the top-face edges: cost = length x (1 + w (distance of both ends to the curve) / h)
  std::vector<Index> shortest_path(Index from, Index to, int curve, const std::vector<char>& used, bool strict,
                                   double corridor)
  {
    if(from == to) return {};
    std::unordered_map<Index, double> dist;
    std::unordered_map<Index, Index> pred;
    typedef std::pair<double, Index> QE;
    std::priority_queue<QE, std::vector<QE>, std::greater<QE>> q;
    dist[from] = 0;
    q.push({0, from});
    while(!q.empty()) {
      const auto [dv, v] = q.top();
      q.pop();
      if(dv > dist[v]) continue;
      if(v == to) break;
      auto pv = pred.find(v);
      const double dvc = norm(sub(closest_on_curve(P[v], curve), P[v]));
      for(Index w : snbrs[v]) {
        if(w != to && (used[w] || kind[w] == CAP || kind[w] == HANGING)) continue;
        // two edges of one top face in a row would put three of its corners on the curve (a flat
        // face): allowed only at a high price
        const bool turns = pv != pred.end() && share_top_face(pv->second, v, w);
        if(turns && strict) continue;
        const double turn = turns ? opt.turn_penalty : 0.0;
        // stay near the curve: at most `corridor` local sizes away
        const Vec3 cp = closest_on_curve(P[w], curve);
        const double dw = norm(sub(cp, P[w]));
        if(dw > corridor * hloc[w]) continue;
        // another curve's corner is passed only if it lies on this curve (a T-junction)
        if(w != to && kind[w] == CORNER && !(dw < 1e-3 * hloc[w])) continue;
        // a vertex whose inner vertex does not see its curve point in front of its staircase faces
        // would make flat buffer cells once snapped: allowed, at a price
        double penalty = 0;
        if(w != to)
          for(const Vec3& n : fnormals[w]) if(dot(sub(cp, P[inner_of[w]]), n) <= 0) penalty = 10;
        // a vertex that lies on another curve leaving a corner of this one (within 0.2 local
        // sizes of it, and less than a quarter as far from it as from this one) is that curve's:
        // taken only at a price (fandisk: the chain of its top edge reached the corner at x =
        // -0.46 over the first vertex of the end face's edge, which then found no path and was
        // missed; without the shared corner, or at half a local size, teapot's coarse facets
        // lost faces to it)
        if(w != to && penalty == 0 && all_curves_tree && dw > 0) {
          // (the curve nearest to w does not depend on the path's curve: asked once per vertex,
          // the vertices do not move while the paths are searched)
          auto& near = nearest_curve[w];
          if(near.first == NOT_YET) {
            const auto op = all_curves_tree->closest_point_and_primitive(point(P[w]));
            near = {segment_curve[std::size_t(op.second - all_curve_segments.cbegin())], norm(sub(vec(op.first), P[w]))};
          }
          const int other = near.first;
          const double dother = near.second;
          const auto& a = curve_ends[std::size_t(curve)];
          const auto& b = curve_ends[std::size_t(other)];
          auto meet = [](int x, int y) { return x >= 0 && x == y; };
          const bool share = other != curve && (meet(a.first, b.first) || meet(a.first, b.second) ||
                                                meet(a.second, b.first) || meet(a.second, b.second));
          if(share && dother < 0.2 * hloc[w] && dother < 0.25 * dw) penalty = 10;
        }
        const double l = norm(sub(P[w], P[v]));
        const double cost = dv + l * (1 + penalty + turn + opt.snap_weight * (dvc + dw) / hloc[w]);
        auto it = dist.find(w);
        if(it == dist.end() || cost < it->second) { dist[w] = cost; pred[w] = v; q.push({cost, w}); }
      }
    }
    if(!pred.count(to)) {
      return {};
    }
    std::vector<Index> path{to};
    while(path.back() != from) path.push_back(pred[path.back()]);
    std::reverse(path.begin(), path.end());
    return path;
  }

  // surface regions: input triangles between feature edges; top faces between feature paths
  void build_regions()
  {
    vregion.assign(P.size(), -1);
    if(!fc) return;
    const auto& tris = d.triangle_indices();
    // input: union-find over triangles across non-feature edges
    std::unordered_set<std::uint64_t> fe;
    for(const auto& e : fc->edges()) fe.insert(capture_edge_key(e.vertices[0], e.vertices[1]));
    Min_union_find<Index> uf(tris.size());
    std::unordered_map<std::uint64_t, Index> first_face;
    for(Index t = 0; t < tris.size(); ++t)
      for(int k = 0; k < 3; ++k) {
        const std::uint64_t key = capture_edge_key(tris[t][std::size_t(k)], tris[t][std::size_t((k + 1) % 3)]);
        if(fe.count(key)) continue;
        auto it = first_face.find(key);
        if(it == first_face.end()) first_face[key] = t;
        else uf.unite(t, it->second);
      }
    tri_region.assign(tris.size(), -1);
    int nreg = 0;
    std::vector<int> root_region(tris.size(), -1);
    for(Index t = 0; t < tris.size(); ++t) {
      const Index r = uf.find(t);
      if(root_region[r] < 0) root_region[r] = nreg++;
      tri_region[t] = root_region[r];
    }
    region_triangles.assign(std::size_t(nreg), {});
    for(Index t = 0; t < tris.size(); ++t) region_triangles[std::size_t(tri_region[t])].push_back(&d.triangle(t));
    region_trees.clear();
    region_trees.resize(std::size_t(nreg));
    // mesh: components of top faces across non-feature edges
    const std::size_t nf = top_faces.size();
    Min_union_find<Index> fuf(nf);
    std::unordered_map<std::uint64_t, Index> edge_face;
    for(Index i = 0; i < nf; ++i) {
      const auto& q = m.boundary_faces[top_faces[i]].vertices;
      for(int k = 0; k < 4; ++k) {
        const std::uint64_t key = capture_edge_key(q[k], q[(k + 1) % 4]);
        if(feature_edges.count(key)) continue;
        auto it = edge_face.find(key);
        if(it == edge_face.end()) edge_face[key] = i;
        else fuf.unite(i, it->second);
      }
    }
    // each component votes with the regions of its faces' centres' closest triangles; a component
    // that one region dominates (a feature chain was missed, or a face's centre is closest to
    // the other side of a sharp edge) takes it, otherwise each face keeps its own
    // (votes are counted on sorted (voter, region) pairs: a hash map per vertex took 80 bytes and
    // more a vertex, the peak of the capture on large meshes)
    std::vector<std::pair<Index, int>> votes;
    // the region most votes name, the smallest on a tie, for each voter of `votes` (sorted);
    // `total`: the voter's number of votes
    auto tally = [&](auto&& take) {
      std::sort(votes.begin(), votes.end());
      for(std::size_t i = 0; i < votes.size();) {
        int best = -1, bc = -1, total = 0;
        std::size_t j = i;
        while(j < votes.size() && votes[j].first == votes[i].first) {
          std::size_t k = j;
          while(k < votes.size() && votes[k] == votes[j]) ++k;
          const int n = int(k - j);
          total += n;
          if(n > bc) { bc = n; best = votes[j].second; }   // ascending regions: the smallest wins a tie
          j = k;
        }
        take(votes[i].first, best, bc, total);
        i = j;
      }
    };
    std::vector<int> own(nf);
    votes.reserve(4 * nf);
    for(Index i = 0; i < nf; ++i) {
      const auto& q = m.boundary_faces[top_faces[i]].vertices;
      Vec3 c{{0, 0, 0}};
      for(int k = 0; k < 4; ++k) c = add(c, mul(P[q[k]], 0.25));
      own[i] = tri_region[d.closest_triangle(Point_3(c[0], c[1], c[2]))];
      votes.push_back({fuf.find(i), own[i]});
    }
    std::unordered_map<Index, int> comp_region;
    tally([&](Index comp, int best, int bc, int total) { comp_region[comp] = 5 * bc >= 4 * total ? best : -1; });
    face_region.assign(nf, -1);
    votes.clear();
    for(Index i = 0; i < nf; ++i) {
      const int r = comp_region[fuf.find(i)];
      face_region[i] = r >= 0 ? r : own[i];
      for(Index v : m.boundary_faces[top_faces[i]].vertices) votes.push_back({v, face_region[i]});
    }
    tally([&](Index v, int best, int, int) { vregion[v] = best; });
    std::vector<std::pair<Index, int>>().swap(votes);
    std::vector<int>().swap(own);
    // a pillow's copy of a chain vertex lies on its sector's region: the one most of the sector's
    // faces have (the pillow's own faces, along the curve, are left out: their centres are
    // often closer to the other side)
    std::map<Index, int> twin_region;
    for(const auto& ps : pillow_sector_faces) {
      std::map<int, int> count;
      for(std::size_t f : ps.second) ++count[face_region[f]];
      int best = -1, bc = -1;
      for(const auto& x : count) if(x.second > bc) { bc = x.second; best = x.first; }
      twin_region[ps.first] = best;
    }
    // the two copies at a vertex of a pillowed curve take the two regions of the input's triangles
    // at the curve there (the chain may run a row of faces off the curve, both sectors' faces
    // then lying on one region): the copy whose sector lies more towards a triangle takes its region
    for(const auto& kt : pillow_twins) {
      const Index t = kt.first;
      if(kt.second.size() != 2 || kind[t] != CURVE || curve_of[t] < 0 || std::size_t(curve_of[t]) >= fc->curves().size()) continue;
      const std::size_t c = std::size_t(curve_of[t]);
      const auto cp = curve_trees[c]->closest_point_and_primitive(point(P[t]));
      const std::size_t i = std::size_t(cp.second - curve_segments[c].begin());
      const auto& cv = fc->curves()[c].vertices;
      auto et = curve_edge_triangles.find(capture_edge_key(cv[i], cv[(i + 1) % cv.size()]));
      if(et == curve_edge_triangles.end() || et->second.size() != 2) continue;
      const int r1 = tri_region[et->second[0]], r2 = tri_region[et->second[1]];
      if(r1 == r2) continue;
      auto centroid = [&](Index T) {
        const auto& tr = d.triangle(T);
        return mul(add(add(vec(tr[0]), vec(tr[1])), vec(tr[2])), 1.0 / 3.0);
      };
      const Vec3 e = sub(centroid(et->second[0]), centroid(et->second[1]));
      // (the mean of the sector's face corners, summed vertex by vertex: it rounds apart from
      // `sector_centre()`, and the copies' places depend on those bits)
      auto side = [&](Index tw) {
        Vec3 g{{0, 0, 0}};
        for(std::size_t f : pillow_sector_faces[tw])
          for(Index x : m.boundary_faces[top_faces[f]].vertices) g = add(g, mul(P[x], 0.25));
        return mul(g, 1.0 / double(pillow_sector_faces[tw].size()));
      };
      const bool a_first = dot(sub(side(kt.second[0]), side(kt.second[1])), e) >= 0;
      twin_region[kt.second[0]] = a_first ? r1 : r2;
      twin_region[kt.second[1]] = a_first ? r2 : r1;
      // each copy starts at its sector's centre projected onto its region; if that lands near
      // the curve (the sector's faces lie on the other side), half a cell into its triangle's
      // plane, square to the curve
      const Vec3 a = vec(fc->point(cv[i])), b = vec(fc->point(cv[(i + 1) % cv.size()]));
      const Vec3 dir = sub(b, a);
      const double dl = dot(dir, dir);
      for(int k = 0; k < 2; ++k) {
        const Index tw = kt.second[std::size_t(k)];
        const Index T = et->second[std::size_t((k == 0) == a_first ? 0 : 1)];
        Vec3 off = sub(centroid(T), a);
        if(dl > 0) off = sub(off, mul(dir, dot(off, dir) / dl));
        const double l = norm(off);
        const int r = twin_region[tw];
        if(r >= 0 && std::size_t(r) < region_triangles.size() && !region_triangles[std::size_t(r)].empty()) {
          build_region_tree(std::size_t(r));
          const Vec3 on = closest_on_surface(side(tw), r);
          if(norm(sub(on, P[t])) >= 0.3 * hloc[tw]) { P[tw] = clamp_planes(tw, on); continue; }
        }
        if(!(l > 0)) continue;
        P[tw] = clamp_planes(tw, add(P[t], mul(off, 0.5 * hloc[tw] / l)));
      }
    }
    for(const auto& ps : pillow_sector_faces) {
      const int best = twin_region[ps.first];
      if(best < 0) continue;
      vregion[ps.first] = best;
      for(std::size_t f : vertex_top_faces[ps.first])
        if(std::find(ps.second.begin(), ps.second.end(), f) == ps.second.end()) face_region[f] = best;
    }
    for(Index i = 0; i < nf; ++i)
      if(!region_triangles[std::size_t(face_region[i])].empty()) build_region_tree(std::size_t(face_region[i]));
  }

  // -----------------------------------------------------------------------------------------------
  // 4. optimisation
  void corners(Index c, Vec3* x) const { for(int k = 0; k < 8; ++k) x[k] = P[m.hexahedra[c][k]]; }
  double cell_sj(Index c) const { Vec3 x[8]; corners(c, x); return hex_scaled_jacobian(x); }
  double cell_split(Index c) const { Vec3 x[8]; corners(c, x); return hex_face_split_quality(x); }
  Vec3 cell_centre(Index c) const { Vec3 x[8]; corners(c, x); return hex_centre(x); }
  // OpenFOAM's concave test (`concave_cell()`) of the cell with its six faces whole
  bool cell_concave(Index c) const
  {
    Vec3 x[8];
    corners(c, x);
    std::array<Vec3, 6> fc, fa;
    for(int k = 0; k < 6; ++k) {
      const auto& f = hex_local_faces()[std::size_t(k)];
      foam_face_centre_and_area(4, [&](std::size_t i) { return x[f[i]]; }, fc[std::size_t(k)], fa[std::size_t(k)]);
    }
    return concave_cell(fc, fa);
  }
  // the face pyramids' weight in `cell_quality()` and `cell_values()`
  double pyramid_weight() const { return second_polish ? opt.second_polish_pyramid_weight : 1.0; }
  double cell_quality(Index c) const
  {
    Vec3 x[8];
    corners(c, x);
    return finish_quality(c, x, (std::min)(hex_scaled_jacobian(x), hex_pyramid_quality(x) * pyramid_weight()));
  }
  // `cell_quality(c)` if it is at least `floor`, else some value below `floor`: the scaled
  // Jacobians, then the face pyramids, are computed only until one falls below it (most trial
  // moves fail on one cell, at one value). `sj`, if given, receives the cell's scaled Jacobian
  // when the quality is at least `floor`. (The same values as `cell_quality()`, to the bit.)
  double cell_quality_above(Index c, double floor, double* sj = nullptr) const
  {
    const double inf = std::numeric_limits<double>::infinity();
    if(use_non_orthogonality && !(use_split_warp || use_polish)) {   // a quality not from these values
      const double q = cell_quality(c);
      if(sj && q >= floor) *sj = cell_sj(c);
      return q;
    }
    Vec3 x[8];
    corners(c, x);
    double v[24];
    const double stop = floor > -1 ? floor : -inf;   // (the scaled Jacobian is clamped to [-1, 1])
    const int nj = hex_scaled_jacobians(x, v, stop);
    if(v[nj - 1] < stop) return v[nj - 1];
    const double s = (std::max)(-1.0, (std::min)(1.0, min_of(v, 9)));
    if(sj) *sj = s;
    const double w = pyramid_weight();
    const int np = hex_pyramid_qualities(x, v, stop / w);
    if(v[np - 1] < stop / w) {
      if(v[np - 1] * w < floor) return v[np - 1] * w;
      hex_pyramid_qualities(x, v);   // (round-off at the boundary: all of them)
    }
    return finish_quality(c, x, (std::min)(s, min_of(v, 24) * w));
  }
  // the quality from q = min(scaled Jacobian, weighted face pyramids), in the current mode
  double finish_quality(Index c, const Vec3* x, double q) const
  {
    // the polish counts the warp too (its face splits are guarded apart, in `improve()`)
    if(use_split_warp || use_polish) return (std::min)(q, split_warp_quality(c, x));
    if(use_concavity) {   // that repair: the margin below its threshold
      const double mg = split_cell[c] ? 1.0 : hex_concavity_margin(x);
      return mg < opt.concave_margin ? (std::min)(q, mg / opt.concave_margin) : q;
    }
    if(use_non_orthogonality) {   // that repair: the worst face's angle only (the scaled Jacobian is guarded apart)
      const double a = cell_non_orthogonality(c);
      return q <= 0 ? q : a <= opt.max_non_orthogonality ? 1.0 : 1 - (a - opt.max_non_orthogonality) / (90 - opt.max_non_orthogonality);
    }
    if(use_folds) {   // in the unfolding only (`unfold_faces()`), where a face folds or nearly does
      const double fold = cell_fold(c);
      return fold < opt.min_fold ? (std::min)(q, fold) : q;
    }
    if(!use_face_splits) return q;
    // in the face-split repair only (see `repair_face_splits()`), and only where a split fails or
    // nearly does
    const double split = hex_face_split_quality(x);
    return split < opt.min_face_split_quality ? (std::min)(q, split) : q;
  }
  void affected_cells(Index v, std::vector<Index>& out) const
  {
    out.clear();
    for(Index k = cstart[v]; k < cstart[v + 1]; ++k) out.push_back(cinc[k]);
    for(Index h : deps[v]) for(Index k = cstart[h]; k < cstart[h + 1]; ++k) out.push_back(cinc[k]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
  double quality_of(const std::vector<Index>& cells) const
  {
    double q = 1;
    for(Index c : cells) q = (std::min)(q, cell_quality(c));
    return q;
  }
  void move(Index v, const Vec3& x)
  {
    P[v] = x;
    for(Index h : deps[v]) recompute_hanging(hang_of[h]);
  }
  bool movable(Index v) const { return kind[v] != CORNER && kind[v] != HANGING; }

  Vec3 smoothing_target(Index v) const
  {
    const Polygon_list::Polygon L = kind[v] == CURVE ? Polygon_list::Polygon{cnbrs[v].data(), cnbrs[v].data() + cnbrs[v].size()}
                                  : (kind[v] == SURFACE || kind[v] == CAP || kind[v] == RELEASED) ? snbrs[v] : nbrs[v];
    if(L.empty()) return P[v];
    Vec3 s{{0, 0, 0}};
    for(Index w : L) s = add(s, P[w]);
    return mul(s, 1.0 / double(L.size()));
  }

  // an inner vertex's ideal place: its twin minus `buffer_thickness` x local size along the mean
  // normal of the top faces around the twin
  Vec3 inner_target(Index v) const
  {
    const Index t = twin[v];
    Vec3 n{{0, 0, 0}};
    for(std::size_t f : vertex_top_faces[t]) {
      const auto& q = m.boundary_faces[top_faces[f]].vertices;
      const Vec3 a = cross(sub(P[q[2]], P[q[0]]), sub(P[q[3]], P[q[1]]));
      const double l = norm(a);
      if(l > 0) n = add(n, mul(a, 1.0 / l));
    }
    const double l = norm(n);
    if(!(l > 0)) return P[v];
    return sub(P[t], mul(n, opt.buffer_thickness * hloc[v] / l));
  }

  // `trial_order`: the positions in `q_old`, its lowest values first
  void order_worst_first()
  {
    trial_order.resize(q_old.size());
    for(std::size_t i = 0; i < q_old.size(); ++i) trial_order[i] = i;
    std::sort(trial_order.begin(), trial_order.end(), [&](std::size_t a, std::size_t b) { return q_old[a] < q_old[b] || (q_old[a] == q_old[b] && a < b); });
  }
  // the cell at `trial_order[k]`, which failed a trial, is looked at first in the next ones
  void fail_first(std::size_t k)
  {
    std::rotate(trial_order.begin(), trial_order.begin() + std::ptrdiff_t(k), trial_order.begin() + std::ptrdiff_t(k) + 1);
  }
  // a move of v (and of the hanging nodes that follow it) stamped, for the cache and the sweeps' skips
  void stamp_move(Index v)
  {
    moved_at[v] = next_stamp();
    for(Index h : deps[v]) moved_at[h] = clock;
  }
  // after improve() or relax() moved v (its cells `cells`): the move stamped, and the cells'
  // qualities at the new place (`moved_q`) in the cache of `current_quality()`
  void record_move(Index v, const std::vector<Index>& cells)
  {
    stamp_move(v);
    CGAL_assertion(moved_q.size() == cells.size());
    for(std::size_t i = 0; i < cells.size(); ++i) { quality_cache[cells[i]] = moved_q[i]; quality_at[cells[i]] = clock; }
  }

  // returns true if the vertex moved
  bool improve(Index v, std::vector<Index>& cells)
  {
    affected_cells(v, cells);
    const Vec3 x0 = P[v];
    q_old.resize(cells.size());
    double f0 = 1, m0 = 0;
    for(std::size_t i = 0; i < cells.size(); ++i) { q_old[i] = current_quality(cells[i]); f0 = (std::min)(f0, q_old[i]); m0 += q_old[i]; }
    order_worst_first();
    trial_q.resize(cells.size());
    // in the repair, the scaled Jacobian is guarded on its own too (a cell whose split is bad has
    // a low quality, which must not let its scaled Jacobian fall that low)
    base_old.resize(cells.size());
    // nor may the non-orthogonality rise beyond max(what it was, 60 degrees)
    double nonortho_cap = 0;
    const bool guard_sj = use_face_splits || use_folds || use_split_warp || use_non_orthogonality || use_polish || use_concavity;
    const bool guard_split = use_polish || use_non_orthogonality || use_concavity;
    if(guard_sj) {
      for(std::size_t i = 0; i < cells.size(); ++i) base_old[i] = cell_sj(cells[i]);
      // and no face split may get worse below the repair's threshold (in the non-orthogonality
      // repair too: unguarded, it folded a face of two grid cells on the motorBike, split
      // 0.04 -> -0.05, a face failing OpenFOAM's tet decomposition that the cleanup cannot remove)
      if(guard_split) {
        split_old.resize(cells.size());
        for(std::size_t i = 0; i < cells.size(); ++i) split_old[i] = cell_split(cells[i]);
        if(second_polish) { conc_old.resize(cells.size()); for(std::size_t i = 0; i < cells.size(); ++i) conc_old[i] = cell_concave(cells[i]); }
      }
      nonortho_cap = (std::max)(use_polish ? opt.max_non_orthogonality : 60.0, max_non_orthogonality(cells));
      if(use_concavity) {
        margin_old.resize(cells.size());
        for(std::size_t i = 0; i < cells.size(); ++i) margin_old[i] = split_cell[cells[i]] ? cell_concavity_margin(cells[i]) : 0.0;
      }
    }
    Vec3 best = x0;
    double fb = f0, mb = m0;
    const double h = local_size(v);
    // a move must raise the minimum, and no cell may fall below min(its quality, keep_quality):
    // the worst cell does not get better by making a good one bad
    const bool on_rim = onto_hole_rim(v, x0);
    auto trial = [&](const Vec3& y) {
      const Vec3 x = constrain(v, y);
      if(norm(sub(x, x0)) < 1e-12 * h) return;
      if(!on_rim && onto_hole_rim(v, x)) return;
      move(v, x);
      // (the rule below takes no trial with a cell below max(f0, fb): none is looked at further)
      const double need = (std::max)(f0, fb - 1e-12);
      // (the worst cells first, and a cell that fails a trial first in the next ones: most
      // trials fail on one of them; the minimum and the sum are taken in the cells' order, so
      // the outcome is the same as in that order)
      for(std::size_t k = 0; k < trial_order.size(); ++k) {
        const std::size_t i = trial_order[k];
        const double floor = (std::max)((std::min)(q_old[i], opt.keep_quality), need);
        double sj = 1;
        const double q = cell_quality_above(cells[i], floor, guard_sj ? &sj : nullptr);
        const bool fails = q < floor || (guard_sj && sj < (std::min)(base_old[i], sj_floor)) ||
                           (guard_split && cell_split(cells[i]) < (std::min)(split_old[i], opt.min_face_split_quality)) ||
                           (use_polish && second_polish && !conc_old[i] && cell_concave(cells[i])) ||
                           (use_concavity && split_cell[cells[i]] && cell_concavity_margin(cells[i]) < (std::min)(margin_old[i], opt.split_concave_margin));
        if(fails) { fail_first(k); return; }
        trial_q[i] = q;
      }
      double f = 1, mean = 0;
      for(std::size_t i = 0; i < cells.size(); ++i) { f = (std::min)(f, trial_q[i]); mean += trial_q[i]; }
      if((use_face_splits || use_folds || use_split_warp || use_polish || use_concavity) && max_non_orthogonality(cells) > nonortho_cap) return;
      // better: a higher minimum, or the same minimum (not below the start's) with a higher sum
      if(f > fb + 1e-4 || (f >= f0 && f >= fb - 1e-12 && mean > mb + 1e-3)) { fb = f; mb = mean; best = x; moved_q = trial_q; }
    };
    const Vec3 s = smoothing_target(v);
    trial(s);
    trial(mul(add(s, x0), 0.5));
    if(v < twin.size() && twin[v] != NONE) {
      // an inner buffer vertex: its place is under its twin, a buffer thickness along the normal
      // of the buffer's outer surface (the buffer cells then stand square on the surface)
      const Vec3 ideal = inner_target(v);
      trial(ideal);
      trial(mul(add(ideal, x0), 0.5));
    }
    // back onto the surface/curve (a surface vertex at the last point found for it is on it)
    if(kind[v] == CURVE || (kind[v] == SURFACE && !on_hint(v))) trial(x0);
    // numerical gradient of the minimum quality (for vertices of cells below the target)
    // (over the cells near the minimum: a step of eps cannot bring the others down to it)
    const double eps = 1e-4 * h;
    Vec3 g{{0, 0, 0}};
    if(f0 < opt.target_quality) {
      near_min.clear();
      for(std::size_t i = 0; i < cells.size(); ++i) if(q_old[i] <= f0 + 0.1) near_min.push_back(cells[i]);
      for(int a = 0; a < 3; ++a) {
        Vec3 y = x0; y[a] += eps;
        move(v, y);
        g[a] = (quality_of(near_min) - f0) / eps;
      }
    }
    const double gn = norm(g);
    if(gn > 0 && f0 < opt.target_quality)
      for(double alpha : {0.3, 0.1, 0.03, 0.01}) trial(add(x0, mul(g, alpha * h / gn)));
    // a move must gain something measurable (else sweeps never end on round-off)
    const bool gain = fb > f0 + 1e-4 || mb > m0 + 1e-3;
    move(v, gain ? best : x0);
    return gain;
  }

  // One Gauss-Seidel step on the shape energy of the vertex's cells: a backtracking line search
  // along the negative (central-difference) gradient, each trial point constrained to the vertex's
  // surface, curve or planes. Taken if the energy drops and no cell falls below min(its quality,
  // keep_quality). Returns true if the vertex moved.
  bool relax(Index v, std::vector<Index>& cells)
  {
    affected_cells(v, cells);
    const Vec3 x0 = P[v];
    const double h = local_size(v);
    const double delta2 = 1e-6 * h * h * h * h * h * h;
    // the energy of the cells, or a value at least `limit` once the sum reaches it (the terms are
    // not negative: a partial sum at least `limit` means the whole one is)
    auto energy = [&](double limit) {
      double e = 0;
      for(Index c : cells) {
        Vec3 x[8];
        for(int k = 0; k < 8; ++k) x[k] = P[m.hexahedra[c][k]];
        e += hex_shape_energy(x, delta2);
        if(e >= limit) return e;
      }
      return e;
    };
    q_old.resize(cells.size());
    for(std::size_t i = 0; i < cells.size(); ++i) q_old[i] = current_quality(cells[i]);
    order_worst_first();
    // the hanging nodes that follow the vertex move by a fixed fraction of its displacement
    dep_weights.clear();
    if(!deps[v].empty()) {
      for(Index d_ : deps[v]) dep_weights.push_back({d_, P[d_][0]});
      Vec3 y = x0;
      y[0] += h;
      move(v, y);
      for(auto& dw : dep_weights) dw.second = (P[dw.first][0] - dw.second) / h;
      move(v, x0);
    }
    double e0 = 0;
    Vec3 g{{0, 0, 0}};
    for(Index c : cells) {
      Vec3 x[8], G[8];
      for(int k = 0; k < 8; ++k) { x[k] = P[m.hexahedra[c][k]]; G[k] = Vec3{{0, 0, 0}}; }
      e0 += hex_shape_energy(x, delta2, G);
      for(int k = 0; k < 8; ++k) {
        const Index u = m.hexahedra[c][k];
        if(u == v) g = add(g, G[k]);
        else for(const auto& dw : dep_weights) if(dw.first == u) g = add(g, mul(G[k], dw.second));
      }
    }
    const double gn = norm(g);
    if(!(gn > 0)) return false;
    const Vec3 dir = mul(g, -1.0 / gn);
    const bool on_rim = onto_hole_rim(v, x0);
    for(double alpha = 0.25; alpha > 1e-3; alpha *= 0.5) {
      const Vec3 x = constrain(v, add(x0, mul(dir, alpha * h)));
      if(norm(sub(x, x0)) < 1e-9 * h) continue;
      if(!on_rim && onto_hole_rim(v, x)) continue;
      move(v, x);
      const double enough = e0 * (1 - 1e-6);
      if(!(energy(enough) < enough)) continue;
      // (the worst cells first, and one that fails first in the next trials)
      bool ok = true;
      moved_q.resize(cells.size());
      for(std::size_t k = 0; k < trial_order.size() && ok; ++k) {
        const std::size_t i = trial_order[k];
        const double floor = (std::min)(q_old[i], opt.keep_quality);
        moved_q[i] = cell_quality_above(cells[i], floor);
        ok = moved_q[i] >= floor;
        if(!ok) fail_first(k);
      }
      if(ok) return true;
    }
    move(v, x0);
    return false;
  }

  template <typename Visitor>
  void optimise(Visitor& visitor)
  {
    // Only cells below the target are worked on, and only cells around a moved vertex can change:
    // `low` (the cells below the target) is kept up to date from the cells each move touched,
    // so a sweep costs what the boundary region costs, not the whole mesh.
    std::vector<Index> cells, work, low, touched;
    std::vector<char> in_work(P.size(), 0), mark(m.hexahedra.size(), 0);
    moved_at.assign(P.size(), 0);
    for(auto& f : failed_at) f.assign(P.size(), 0);
    quality_at.assign(m.hexahedra.size(), 0);
    quality_cache.assign(m.hexahedra.size(), 0.0);
    use_quality_cache = true;
    struct Cache_off { bool& on; ~Cache_off() { on = false; } } cache_off{use_quality_cache};
    clock = 1;
    epoch = 1;
    // what `improve()` and `relax()` find depends on the positions they read and on the vertex
    // kinds (constraints): a change of kinds, or a move outside the sweeps, starts a new epoch
    auto new_epoch = [&]() { epoch = next_stamp(); };
    for(Index c = 0; c < m.hexahedra.size(); ++c) if(cell_quality_above(c, opt.target_quality) < opt.target_quality) low.push_back(c);
    auto add_vertex = [&](Index v) { add_work_vertex(v, work, in_work); };
    // improves the vertices in `work`; returns the number moved and refreshes `low`
    auto sweep = [&](bool smooth_energy) {
      std::sort(work.begin(), work.end());
      std::size_t moved = 0;
      touched.clear();
      std::vector<Stamp>& failed = failed_at[smooth_energy ? 1 : 0];
      for(Index v : work) {
        in_work[v] = 0;
        // a vertex that found no move, none of whose inputs moved since: it finds none again
        if(failed[v] >= epoch && last_input_move(v) <= failed[v]) continue;
        if(!(smooth_energy ? relax(v, cells) : improve(v, cells))) { failed[v] = clock; continue; }
        record_move(v, cells);
        ++moved;
        for(Index c : cells) if(!mark[c]) { mark[c] = 1; touched.push_back(c); }
      }
      work.clear();
      for(Index c : low) if(!mark[c]) { mark[c] = 1; touched.push_back(c); }
      low.clear();
      std::sort(touched.begin(), touched.end());
      for(Index c : touched) { mark[c] = 0; if(current_quality(c) < opt.target_quality) low.push_back(c); }
      return moved;
    };
    // Sweeps alternate between the shape energy (smooth: every cell of a vertex counts, so
    // neighbouring vertices improve a cell together; it spreads crowded vertices) and the worst
    // cells' minimum (what the energy averages away). Either alone stalls much earlier. The main
    // sweeps also set every inner buffer vertex under its twin (the first three) and report progress.
    auto smooth = [&](int passes, bool main_sweeps) {
      new_epoch();
      for(int pass = 0, idle = 0; pass < passes && !cancelled; ++pass) {
        for(Index c : low) for(Index v : m.hexahedra[c]) add_vertex(v);
        if(main_sweeps) {
          if(pass < 3) for(Index v : inner) add_vertex(v);
          rep.optimisation_passes = std::size_t(pass + 1);
        }
        if(work.empty()) break;
        const std::size_t nwork = work.size();
        const std::size_t moved = sweep(pass % 2 == 0);
        if(main_sweeps && !visitor.go_further(double(pass + 1) / passes)) { cancelled = true; break; }
        idle = moved * 200 < nwork ? idle + 1 : 0;   // fewer than 0.5 % of the vertices still move
        if(idle == 2) break;
      }
    };
    smooth(opt.passes, true);
    substep("optimise.sweeps");
    auto untangle = [&]() {
      new_epoch();
      for(int pass = 0; pass < opt.passes; ++pass) {
        for(Index c : low) if(cell_quality(c) <= degenerate_quality) for(Index v : m.hexahedra[c]) add_vertex(v);
        if(work.empty()) break;
        // the shape energy's barrier pulls inverted corners back; the max-min step then works on
        // what is left
        const bool energy = pass % 2 == 0;
        if(sweep(energy) == 0 && !energy) break;
      }
      work.clear();
    };
    // cells still inverted (or flat): first their curve and corner vertices go back to being
    // surface vertices (a feature is lost there rather than the surface), then their surface
    // vertices are released into the volume
    // (curve vertices first; corners only if that was not enough)
    struct Lost { Index v; Kind kind; Vec3 where; };
    std::vector<Lost> unsnapped_list;
    for(const Kind which : {CURVE, CORNER}) {
      bool unsnapped = false;
      for(Index c : low)
        if(cell_quality(c) <= degenerate_quality)
          for(Index v : m.hexahedra[c])
            if(kind[v] == which) {
              kind[v] = SURFACE;
              unsnapped = true;
              ++rep.unsnapped_vertices;
              unsnapped_list.push_back({v, which, P[v]});
              if(vregion[v] < 0) vregion[v] = region_of_point(P[v]);
            }
      if(unsnapped) untangle();
    }
    bool any_released = false;
    for(int round = 0; round < 4; ++round) {
    bool released = false;
    for(Index c : low)
      if(cell_quality(c) <= degenerate_quality)
        for(Index v : m.hexahedra[c])
          if(kind[v] == SURFACE || kind[v] == CURVE || kind[v] == CORNER) {
            if(kind[v] != SURFACE) {   // a feature vertex released: it goes back to its curve too
              ++rep.unsnapped_vertices;
              unsnapped_list.push_back({v, kind[v], P[v]});
            }
            kind[v] = RELEASED;
            released = true;
            any_released = true;
            // it starts again from the plain extrusion of the staircase: its inner vertex plus a
            // buffer thickness along the staircase normal (a snap may have dragged it cells away)
            Vec3 n{{0, 0, 0}};
            for(const Vec3& f : fnormals[v]) n = add(n, f);
            const double l = norm(n);
            if(l > 0 && inner_of[v] != NONE)
              move(v, clamp_planes(v, add(P[inner_of[v]], mul(n, opt.buffer_thickness * hloc[v] / l))));
          }
    if(!released) break;
    untangle();
    }
    // the cells around released vertices were only untangled: smooth them (and whatever else is
    // still below the target) once more
    substep("optimise.untangle");
    if(!any_released && unsnapped_list.empty() && sheet_caps.empty()) return;
    smooth(opt.final_passes, false);
    substep("optimise.final_sweeps");
    // Fidelity before quality: vertices that lost their constraint go back as far as their cells
    // allow (none may fall below min(its quality, keep_quality)) - released vertices towards the
    // surface, unsnapped ones towards their curve or corner; one that reaches it takes its kind
    // again. Smoothing between the rounds makes room.
    std::vector<Index> released_list;
    for(Index v = 0; v < P.size(); ++v) if(kind[v] == RELEASED) released_list.push_back(v);
    std::vector<std::pair<Index, std::size_t>> todo;   // vertex, its entry in unsnapped_list (or none)
    std::vector<double> cap_split_old;   // a sheet cap vertex's cells' face-split qualities before its move
    std::vector<char> cap_concave_old;   // and whether they were concave for OpenFOAM
    for(Index v : released_list) todo.push_back({v, std::size_t(-1)});
    for(std::size_t i = 0; i < unsnapped_list.size(); ++i) todo.push_back({unsnapped_list[i].v, i});
    for(Index v : sheet_caps) todo.push_back({v, std::size_t(-1)});
    std::vector<Stamp>& reattach_failed = failed_at[2];
    for(int round = 0; round < opt.reattach_rounds && !cancelled; ++round) {
      std::size_t moved = 0;
      for(const auto& td : todo) {
        const Index v = td.first;
        Vec3 target;
        Kind goal;
        int r = -1;
        const Vec3 x0 = P[v];
        const bool to_surface = kind[v] == RELEASED || kind[v] == CAP;
        if(to_surface) {
          if(td.second != std::size_t(-1)) continue;   // its surface entry comes first
        } else if(!(kind[v] == SURFACE && td.second != std::size_t(-1))) continue;
        // one that found no step, none of whose inputs (its place, the corners of its cells and
        // their hanging nodes' masters) moved since, finds none again (checked before its target
        // is looked for: on the motorBike most of the 20,000 vertices of the rounds are such)
        if(reattach_failed[v] != 0 && last_input_move(v) <= reattach_failed[v]) continue;
        if(to_surface) {
          r = region_of_point(x0);
          target = clamp_planes(v, closest_on_surface(x0, r));
          goal = SURFACE;
        } else {
          const Lost& l = unsnapped_list[td.second];
          goal = l.kind;
          target = goal == CORNER ? l.where : clamp_planes(v, closest_on_curve(x0, curve_of[v]));
        }
        affected_cells(v, cells);
        q_old.resize(cells.size());
        for(std::size_t i = 0; i < cells.size(); ++i) q_old[i] = cell_quality(cells[i]);
        // (a sheet's cap vertex is not invalid where it is: no cell may fall below
        // `sheet_cap_quality` for it, nor be made concave for OpenFOAM or get a face split worse
        // than min(its own, `min_face_split_quality`): at 0.2 without those two guards, a face
        // failing the tet decomposition was left on the motorBike)
        const bool cap = kind[v] == CAP;
        if(cap) {
          cap_split_old.resize(cells.size());
          cap_concave_old.resize(cells.size());
          for(std::size_t i = 0; i < cells.size(); ++i) { cap_split_old[i] = cell_split(cells[i]); cap_concave_old[i] = char(cell_concave(cells[i])); }
        }
        bool done = false;
        const double keep = cap ? opt.sheet_cap_quality : opt.keep_quality;
        for(double t : {1.0, 0.5, 0.25}) {
          const Vec3 y = add(x0, mul(sub(target, x0), t));
          move(v, t == 1.0 || goal == SURFACE ? y : constrain(v, y));
          bool ok = true;
          for(std::size_t i = 0; i < cells.size() && ok; ++i) {
            const double floor = (std::min)(q_old[i], keep);
            ok = cell_quality_above(cells[i], floor) >= floor;
          }
          for(std::size_t i = 0; cap && i < cells.size() && ok; ++i)
            ok = cell_split(cells[i]) >= (std::min)(cap_split_old[i], opt.min_face_split_quality) && (cap_concave_old[i] || !cell_concave(cells[i]));
          if(!ok) continue;
          if(t == 1.0) {
            if(kind[v] == CAP) --rep.cap_vertices;   // on its sheet's border now
            kind[v] = goal;
            if(goal == SURFACE) vregion[v] = r; else --rep.unsnapped_vertices;
          }
          ++moved;
          done = true;
          for(Index c : cells) if(cell_quality(c) < opt.target_quality) low.push_back(c);
          stamp_move(v);
          break;
        }
        if(!done) { move(v, x0); reattach_failed[v] = clock; }
      }
      std::sort(low.begin(), low.end());
      low.erase(std::unique(low.begin(), low.end()), low.end());
      if(moved == 0) break;
      smooth(2, false);
    }
    // Joint moves: a released vertex that still cannot go back alone (its closest surface point
    // inverts a cell of its own, as at fandisk's concave step) is put there, and its neighbours
    // (the other corners of its cells, not itself: it may be a master of a hanging one) make
    // room with `improve()`, which raises the worst of their cells, `joint_passes` times; kept
    // if every cell of theirs is then valid, at least min(its quality, `joint_quality`) and not
    // concave for OpenFOAM where it was not, else everything goes back. (At 0.2 the motorBike
    // got 198 more cells below 0.3, at 0.3 fandisk kept its far faces; see the manual.)
    substep("optimise.reattach");
    if(opt.joint_passes > 0) {
      std::vector<Index> around, nb, all, cu;
      std::vector<std::pair<Index, Vec3>> saved;
      std::vector<double> q0, s0;
      std::vector<char> c0;
      // A joint move reads the positions of the vertices of the cells it gathers (and of the
      // masters of their hanging nodes): one that failed is tried again only if a kept joint
      // move has moved one of them since (its outcome would be the same). The motorBike's second
      // round retried all of its 2,000-odd failures for 5.6 s and kept 34.
      const std::uint32_t never = std::numeric_limits<std::uint32_t>::max();
      std::uint32_t joint_clock = 0;
      std::vector<std::uint32_t> joint_moved_at(P.size(), 0), joint_failed_at(P.size(), never);
      auto inputs_moved_since = [&](const std::vector<Index>& cs, std::uint32_t t) {
        for(Index c : cs)
          for(Index w : m.hexahedra[c]) {
            if(joint_moved_at[w] > t) return true;
            if(kind[w] == HANGING)
              for(const auto& hm : hang_masters[hang_of[w]]) if(joint_moved_at[hm.first] > t) return true;
          }
        return false;
      };
      // v goes to the surface point closest to it, else to the one closest to the mean of its
      // surface neighbours, while its neighbours make room (their cells and baselines gathered
      // once for both); true if kept. With `lost` (v was unsnapped from a curve or a corner and
      // is a surface vertex again): to the curve point closest to it, else to the one closest to
      // the mean of its curve neighbours, or to its corner.
      auto joint_move = [&](Index v, const Lost* lost) {
        const bool is_cap = kind[v] == CAP;
        const Vec3 x0 = P[v];
        const int r = lost ? vregion[v] : region_of_point(x0);
        Vec3 targets[2];
        int ntargets = 2;
        if(!lost) {
          targets[0] = clamp_planes(v, closest_on_surface(x0, r));
          targets[1] = clamp_planes(v, closest_on_surface(smoothing_target(v), r));
        } else if(lost->kind == CORNER) {
          targets[0] = lost->where;
          ntargets = 1;
        } else {
          targets[0] = clamp_planes(v, closest_on_curve(x0, curve_of[v]));
        }
        // (a feature vertex more than a local size from its feature is not tried: on the
        // motorBike, 3,562 of its 6,612 tries were, for 6 of the 131 kept, and 5 s)
        if(lost && norm(sub(targets[0], x0)) > hloc[v]) return false;
        if(lost && lost->kind != CORNER) targets[1] = clamp_planes(v, closest_on_curve(smoothing_target(v), curve_of[v]));
        const double floor_quality = is_cap ? opt.sheet_cap_quality : lost ? opt.feature_joint_quality : opt.joint_quality;
        affected_cells(v, around);
        nb.clear();
        for(Index c : around) for(Index w : m.hexahedra[c]) if(w != v && movable(w)) nb.push_back(w);
        std::sort(nb.begin(), nb.end());
        nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
        all = around;
        for(Index u : nb) { affected_cells(u, cu); all.insert(all.end(), cu.begin(), cu.end()); }
        std::sort(all.begin(), all.end());
        all.erase(std::unique(all.begin(), all.end()), all.end());
        if(joint_failed_at[v] != never && !inputs_moved_since(all, joint_failed_at[v])) return false;
        q0.resize(all.size());
        c0.resize(all.size());
        for(std::size_t i = 0; i < all.size(); ++i) { q0[i] = current_quality(all[i]); c0[i] = char(cell_concave(all[i])); }
        // the quality cell i may not fall below (nor to `degenerate_quality`)
        auto cell_floor = [&](std::size_t i) { return (std::min)(q0[i], floor_quality); };
        s0.resize(all.size());
        // (a sheet's cap vertex and a feature vertex guard the face splits too: on bunny shifted
        // by round-off, a curve vertex put back without it left a face failing OpenFOAM's tet
        // decomposition, whose buffer cell the cleanup removed)
        const bool guard_splits = is_cap || lost;
        if(guard_splits) for(std::size_t i = 0; i < all.size(); ++i) s0[i] = cell_split(all[i]);
        saved.clear();
        saved.push_back({v, x0});
        for(Index u : nb) saved.push_back({u, P[u]});
        // (every move is stamped, and a neighbour's move leaves its cells' qualities in the cache,
        // as in the sweeps: the cache stays valid)
        for(int ti = 0; ti < ntargets; ++ti) {
          const Vec3& target = targets[ti];
          move(v, target);
          stamp_move(v);
          for(int pass = 0; pass < opt.joint_passes; ++pass) {
            bool any = false;
            for(Index u : nb) {
              if(!improve(u, cu)) continue;
              any = true;
              record_move(u, cu);
            }
            if(!any) break;
            // A try whose worst cell is still far below its floor after a few passes is given
            // up: such a try almost never recovers (motorBike: 4,202 of its 9,324 tries, none
            // of which would have been kept, 30 % of the passes, 1.6 s; fandisk at the test's
            // sizes: one, 18 vertices end elsewhere, the same figures).
            if(pass + 1 >= opt.joint_hopeless_passes && opt.joint_hopeless_passes > 0) {
              bool hopeless = false;
              for(std::size_t i = 0; i < all.size() && !hopeless; ++i)
                hopeless = current_quality(all[i]) < (std::max)(degenerate_quality, cell_floor(i)) - opt.joint_hopeless_margin;
              if(hopeless) break;
            }
          }
          bool ok = true;
          for(std::size_t i = 0; i < all.size() && ok; ++i) {
            const double q = current_quality(all[i]);
            ok = q > degenerate_quality && q >= cell_floor(i) && (c0[i] || !cell_concave(all[i]));
          }
          for(std::size_t i = 0; guard_splits && i < all.size() && ok; ++i) ok = cell_split(all[i]) >= (std::min)(s0[i], opt.min_face_split_quality);
          if(ok) {
            if(is_cap) --rep.cap_vertices;
            if(lost) {
              kind[v] = lost->kind;
              --rep.unsnapped_vertices;
              ++rep.feature_joint_moves;
            } else {
              kind[v] = SURFACE;
              vregion[v] = r;
            }
            ++joint_clock;
            joint_moved_at[v] = joint_clock;
            for(Index u : nb) joint_moved_at[u] = joint_clock;
            for(Index c : all) if(current_quality(c) < opt.target_quality) low.push_back(c);
            return true;
          }
          for(auto it = saved.rbegin(); it != saved.rend(); ++it) { move(it->first, it->second); stamp_move(it->first); }
        }
        joint_failed_at[v] = joint_clock;
        return false;
      };
      // (and the sheets' cap vertices still off their border, with their own floor and the
      // face-split guard of the rounds)
      std::vector<Index> joint_list = released_list;
      joint_list.insert(joint_list.end(), sheet_caps.begin(), sheet_caps.end());
      // Each vertex goes to its closest surface point, or else to the surface point nearest to
      // the mean of its surface neighbours (where a smoothing step would take it: near a concave
      // feature the closest point crowds it against the curve). A second round gives those that
      // failed another try once their neighbours have moved. (Measured on the motorBike: the
      // second target took the vertices off the surface from 403 to 376 and the cap vertices
      // from 1505 to 1456 for 4 s, the second round to 361 and 1437 for 4 s more; moving the
      // neighbours off the surface together, and a third round, 10 fewer for 6 s more: not kept.)
      for(int round = 0; round < 2 && !cancelled; ++round) {
        std::size_t kept = 0;
        for(Index v : joint_list)
          if((kind[v] == RELEASED || kind[v] == CAP) && !cancelled && joint_move(v, nullptr)) ++kept;
        // then the curve and corner vertices unsnapped that the rounds did not bring back (on
        // anchor, a straight concave edge lost 60 of its vertices to flat cells, 0.2 surface
        // sizes off it), those released included once they are surface vertices again
        for(const Lost& l : unsnapped_list)
          if(kind[l.v] == SURFACE && !cancelled && joint_move(l.v, &l)) ++kept;
        if(kept == 0) break;
      }
    }
    substep("optimise.joint_moves");
    for(Index v : released_list) if(kind[v] == RELEASED) rep.unreached_vertices.push_back(P[v]);
    for(const Lost& l : unsnapped_list) if(kind[l.v] != l.kind) rep.unsnapped_at.push_back(P[l.v]);
    CGAL_assertion(rep.unsnapped_at.size() == rep.unsnapped_vertices);
    {
      std::vector<Index> turns = turn_vertices;   // (a vertex may be a turn of two faces)
      std::sort(turns.begin(), turns.end());
      turns.erase(std::unique(turns.begin(), turns.end()), turns.end());
      for(Index v : turns) rep.curve_turns.push_back(P[v]);
    }
  }


  // how far the centre of top face f stands off the surface, relative to the smallest local size
  // of its corners (a hanging corner's own distance counts: its masters put it on the face's
  // edge, not on the surface)
  double top_face_centre_distance(std::size_t f) const
  {
    const auto& q = m.boundary_faces[top_faces[f]].vertices;
    Vec3 c{{0, 0, 0}};
    double h = 1e300;
    for(Index w : q) { c = add(c, P[w]); h = (std::min)(h, local_size(w)); }
    c = mul(c, 0.25);
    double dist = CGAL::to_double(d.squared_distance(Point_3(c[0], c[1], c[2])));
    for(Index w : q)
      if(kind[w] == HANGING) dist = (std::max)(dist, CGAL::to_double(d.squared_distance(Point_3(P[w][0], P[w][1], P[w][2]))));
    return std::sqrt(dist) / h;
  }
  // the largest of those distances over the top faces of v and of the hanging nodes that follow
  // it (not the faces with a cap or released corner)
  double top_face_offset(Index v) const
  {
    double worst = 0;
    for_each_top_face(v, [&](std::size_t f) { if(!top_face_skipped(f)) worst = (std::max)(worst, top_face_centre_distance(f)); });
    return worst;
  }
  // whether a top face of `v` (or of a hanging node it moves) is left out of the fidelity's watch
  bool touches_skipped_top_face(Index v) const
  {
    bool any = false;
    for_each_top_face(v, [&](std::size_t f) { any = any || top_face_skipped(f); });
    return any;
  }
  // the top faces of `v` and of the hanging nodes it moves
  template <typename F>
  void for_each_top_face(Index v, F f) const
  {
    if(v < vertex_top_faces.size()) for(std::size_t t : vertex_top_faces[v]) f(t);
    for(Index h : deps[v])
      if(h < vertex_top_faces.size()) for(std::size_t t : vertex_top_faces[h]) f(t);
  }
  bool top_face_skipped(std::size_t f) const
  {
    for(Index w : m.boundary_faces[top_faces[f]].vertices) if(kind[w] == CAP || kind[w] == RELEASED) return true;
    return false;
  }

  // The faces of the buffer's outer surface whose centre stands off the surface (where a feature
  // chain turns inside a face, or a stretched face bends over a convex region) have their corners
  // slid on their surface or curve to bring the centre closer: each surface or curve vertex of
  // such a face takes the first step down the (numerical) gradient of the largest centre distance
  // of its top faces (relative to their local sizes) that lowers it by 2 % and passes the
  // polish's guards: no cell below min(its quality, polish_quality), nor its scaled Jacobian, no
  // face split worse than min(its own, min_face_split_quality), no cell made concave, the
  // non-orthogonality not above max(its value, max_non_orthogonality). Fidelity before quality,
  // but within the quality goals.
  template <typename Visitor>
  void fidelity_polish(Visitor& visitor)
  {
    if(opt.fidelity_passes <= 0 || top_faces.empty()) return;
    // the vertices that slide: surface and curve vertices, not those the joint moves let off their feature
    auto slidable = [&](Index w) {
      return (kind[w] == SURFACE || kind[w] == CURVE) && !(w < left_feature.size() && left_feature[w]);
    };
    const bool polish_before = use_polish;
    use_polish = true;
    Move_guard guard;
    for(int pass = 0; pass < opt.fidelity_passes && !cancelled; ++pass) {
      std::vector<Index> work;
      for(std::size_t f = 0; f < top_faces.size(); ++f)
        if(!top_face_skipped(f) && top_face_centre_distance(f) > opt.fidelity_distance)
          for(Index w : m.boundary_faces[top_faces[f]].vertices)
            if(slidable(w)) work.push_back(w);
            else if(kind[w] == HANGING)   // its masters move it
              for(const auto& hm : hang_masters[hang_of[w]]) if(slidable(hm.first)) work.push_back(hm.first);
      std::sort(work.begin(), work.end());
      work.erase(std::unique(work.begin(), work.end()), work.end());
      if(work.empty()) break;
      std::size_t moved = 0, tried = 0;
      for(Index v : work) {
        if(++tried % 64 == 0 && !visitor.go_further(1.0)) { cancelled = true; break; }
        const Vec3 x0 = P[v];
        const double D0 = top_face_offset(v);
        if(D0 <= opt.fidelity_distance) continue;
        const double h = local_size(v);
        const double eps = 1e-3 * h;
        Vec3 g{{0, 0, 0}};
        for(int a = 0; a < 3; ++a) {
          Vec3 y = x0; y[a] += eps;
          move(v, constrain(v, y));
          const double Dp = top_face_offset(v);
          y = x0; y[a] -= eps;
          move(v, constrain(v, y));
          g[a] = (Dp - top_face_offset(v)) / (2 * eps);
        }
        move(v, x0);
        const double gn = norm(g);
        if(!(gn > 0)) continue;
        guard.take(*this, v);
        const bool on_rim = onto_hole_rim(v, x0);
        bool done = false;
        for(double alpha : {0.4, 0.2, 0.1, 0.05}) {
          const Vec3 x = constrain(v, sub(x0, mul(g, alpha * h / gn)));
          if(!on_rim && onto_hole_rim(v, x)) continue;   // (its cells towards the cap would collapse)
          move(v, x);
          if(!(top_face_offset(v) < D0 * 0.98)) continue;
          if(guard.passes(*this)) { done = true; break; }
        }
        if(done) ++moved; else move(v, x0);
      }
      rep.fidelity_moves += moved;
      if(moved == 0) break;
    }
    use_polish = polish_before;
  }

  // The polish's guards on a move of one vertex (`fidelity_polish()`, `turn_polish()`): no cell
  // of the vertex (and of the hanging nodes it moves) below min(its quality, polish_quality), nor
  // its scaled Jacobian, no face split worse than min(its own, min_face_split_quality), no cell
  // made concave, the non-orthogonality not above max(its value, max_non_orthogonality).
  // `take()` before the move, `passes()` after it.
  struct Move_guard
  {
    std::vector<Index> cells;
    std::vector<double> q0, sj0, split0;
    std::vector<char> conc0;
    double nonortho_cap = 0;
    void take(const Boundary_capture_3& bc, Index v)
    {
      bc.affected_cells(v, cells);
      take_cells(bc);
    }
    // (the cells of several vertices)
    void take(const Boundary_capture_3& bc, const std::vector<Index>& vs)
    {
      std::vector<Index> vc;
      cells.clear();
      for(Index v : vs) { bc.affected_cells(v, vc); cells.insert(cells.end(), vc.begin(), vc.end()); }
      std::sort(cells.begin(), cells.end());
      cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
      take_cells(bc);
    }
    void take_cells(const Boundary_capture_3& bc)
    {
      q0.resize(cells.size()); sj0.resize(cells.size()); split0.resize(cells.size()); conc0.resize(cells.size());
      for(std::size_t i = 0; i < cells.size(); ++i) {
        q0[i] = bc.cell_quality(cells[i]); sj0[i] = bc.cell_sj(cells[i]);
        split0[i] = bc.cell_split(cells[i]); conc0[i] = bc.cell_concave(cells[i]);
      }
      nonortho_cap = (std::max)(bc.opt.max_non_orthogonality, bc.max_non_orthogonality(cells));
    }
    bool passes(const Boundary_capture_3& bc) const
    {
      const double fq = bc.guard_floor > 0 ? bc.guard_floor : bc.opt.polish_quality;
      for(std::size_t i = 0; i < cells.size(); ++i) {
        const Index c = cells[i];
        const double floor = (std::min)(q0[i], fq);
        double sj = 1;   // (set when the quality reaches the floor)
        if(!(bc.cell_quality_above(c, floor, &sj) >= floor && sj >= (std::min)(sj0[i], fq) &&
             bc.cell_split(c) >= (std::min)(split0[i], bc.opt.min_face_split_quality) && (conc0[i] || !bc.cell_concave(c))))
          return false;
      }
      return !(bc.max_non_orthogonality(cells) > nonortho_cap);
    }
  };

  // Where a feature chain turns inside a top face (`turn_vertices`: two chain edges in a row in
  // one face), the middle vertex was left off its curve: on it, the face would have three corners
  // in a line. Where the optimisation leaves it (about half a cell off), the face straddles the
  // curve along its diagonal and folds by about half the curve's angle on both sides: the mesh's
  // creases run along all four of its edges, up to 0.7 cell sizes off the curve. Pulled towards
  // its curve, on its surface region, the face lies mostly on one side and the crease follows the
  // chain's two edges, closer to the curve. Each such vertex takes the longest of the steps 3/4,
  // 1/2, 1/4 of the way to `turn_distance` local sizes from its curve that passes the polish's
  // guards (`Move_guard`) and leaves no top face of it farther off the surface than max(before,
  // `fidelity_distance`) (`top_face_offset()`; without it rotor got 4 more faces beyond s/4).
  // (Also the curve vertices put back on the surface where their face would be flat.)
  // Where a step alone fails the guards, it is tried with the vertices around (`joint_turn_move()`;
  // after the first two sweeps only for vertices still beyond `turn_joint_far` local sizes of their
  // curve). The sweeps go on until one moves nothing (`turn_passes` at most): a vertex that failed
  // is tried again once a vertex its guards read has moved (stop 57: anchor's mesh creases
  // within 0.47 surface sizes of its sharp edges instead of 0.51).
  template <typename Visitor>
  void turn_polish(Visitor& visitor)
  {
    CGAL_assertion(turn_curve.size() == turn_vertices.size());
    if(opt.turn_passes <= 0 || turn_vertices.empty()) return;
    const bool polish_before = use_polish;
    use_polish = true;
    Move_guard guard;
    std::vector<Vec3> steps;
    // A vertex whose steps failed, none of whose inputs moved since, fails again: its inputs are
    // what `improve()` reads at it and at the corners of its cells (the masters of hanging ones),
    // which covers the guards and the joint move. Every move kept here is stamped.
    CGAL_assertion(moved_at.size() == P.size());
    std::vector<Stamp>& turn_failed = failed_at[2];
    turn_failed.assign(P.size(), 0);
    std::vector<Index> near, around;
    auto inputs_moved = [&](Index v) {
      cell_corner_masters(v, near, around);
      Stamp t = last_input_move(v);
      for(Index w : near) t = (std::max)(t, last_input_move(w));
      return t;
    };
    // (`far_pass`: the passes after those, see below; they count as later passes, `pass` >= 2,
    // for the joint moves)
    auto sweep = [&](int pass, bool far_pass) {
      std::size_t moved = 0;
      for(std::size_t i = 0; i < turn_vertices.size(); ++i) {
        if(i % 64 == 63 && !visitor.go_further(1.0)) { cancelled = true; break; }
        const Index v = turn_vertices[i];
        const int c = turn_curve[i];
        if(kind[v] != SURFACE || c < 0 || (v < left_feature.size() && left_feature[v])) continue;
        if(turn_failed[v] != 0 && inputs_moved(v) <= turn_failed[v]) continue;
        // (its top faces' offset, where the far passes already measured it: -1 if not)
        const double offset0 = far_pass ? top_face_offset(v) : -1.0;
        if(far_pass && !(offset0 > opt.turn_far_offset)) continue;
        const Vec3 x0 = P[v];
        const Vec3 target = clamp_planes(v, closest_on_curve(x0, c));
        const double d0 = norm(sub(target, x0)), keep = opt.turn_distance * local_size(v);
        if(!(d0 > keep * 1.05)) continue;
        guard.take(*this, v);
        const bool on_rim = onto_hole_rim(v, x0);
        // (nor may a face of it stand farther off the surface than max(before, fidelity_distance))
        const double offset_cap = (std::max)(offset0 >= 0 ? offset0 : top_face_offset(v), opt.fidelity_distance);
        // the steps, those that stay off a hole's border and come closer to the curve
        steps.clear();
        for(double t : {0.75, 0.5, 0.25}) {
          const Vec3 x = constrain(v, add(x0, mul(sub(target, x0), t * (d0 - keep) / d0)));
          if(!on_rim && onto_hole_rim(v, x)) continue;
          if(!(norm(sub(closest_on_curve(x, c), x)) < 0.98 * d0)) continue;
          steps.push_back(x);
        }
        bool done = false;
        for(const Vec3& x : steps) {
          move(v, x);
          if(top_face_offset(v) <= offset_cap && guard.passes(*this)) { done = true; break; }
        }
        if(!done) move(v, x0);
        else stamp_move(v);
        // (joint moves are most of the polish's time: after two sweeps, only where the vertex is
        // still far enough off its curve for its face to crease off it)
        if(!done && opt.turn_joint && !steps.empty() && (pass < 2 || d0 > opt.turn_joint_far * local_size(v)))
          done = joint_turn_move(v, x0, steps, offset_cap);
        if(done) ++moved;
        else turn_failed[v] = clock;
      }
      rep.turn_moves += moved;
      return moved;
    };
    for(int pass = 0; pass < opt.turn_passes && !cancelled; ++pass)
      if(sweep(pass, false) == 0) break;
    // Then the turn vertices whose top faces still stand farther than `turn_far_offset` local
    // sizes off the surface (a face folded across the curve, beyond the fidelity goal of a quarter
    // surface size) are tried again with the guards' floor at `turn_far_quality` instead of
    // `polish_quality`: fidelity before quality, within the quality goal.
    if(opt.turn_far_quality > 0 && opt.turn_far_quality < opt.polish_quality && !cancelled) {
      turn_failed.assign(P.size(), 0);
      guard_floor = opt.turn_far_quality;
      struct Floor_back { double& f; ~Floor_back() { f = 0; } } floor_back{guard_floor};
      for(int pass = 0; pass < opt.turn_passes && !cancelled; ++pass) {
        const std::size_t moved = sweep(2, true);
        rep.turn_far_moves += moved;
        if(moved == 0) break;
      }
    }
    use_polish = polish_before;
  }

  // A turn vertex's steps (`steps`, from `x0`) that fail the guards alone, mostly by a cell of it
  // falling a little below polish_quality (anchor: 0.37 -> 0.33), are tried again with the other
  // vertices of its cells (the masters of hanging ones; not the corners, nor a vertex of a top
  // face with a cap vertex, whose distance is not watched) each improved once after it
  // (`improve()`, in index order); the guards then hold on the cells of all of them, and no top
  // face of any of them may stand farther off the surface than max(before, half
  // `fidelity_distance`) (teapot, without those two rules: faces beyond s/4 75 -> 84, its local
  // sizes are up to 3 s). Undone if they fail. (anchor at the test's sizes: the mesh's creases
  // farther than s/4 from the input's sharp edges 51 -> 24, the farthest 0.69 -> 0.55 s; its
  // minimum scaled Jacobian 0.317 -> 0.345; inner vertices only: 35 creases, 0.317.) Returns
  // whether it moved.
  bool joint_turn_move(Index v, const Vec3& x0, const std::vector<Vec3>& steps, double offset_cap)
  {
    std::vector<Index> cells, vs;
    cell_corner_masters(v, vs, cells);
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    vs.erase(std::remove_if(vs.begin(), vs.end(), [&](Index w) { return w == v || !movable(w) || touches_skipped_top_face(w); }), vs.end());
    if(vs.empty()) return false;
    Move_guard g;
    vs.push_back(v);
    g.take(*this, vs);
    vs.pop_back();
    const double v_offset = top_face_offset(v);
    std::vector<Vec3> xs(vs.size());
    std::vector<double> offset_caps(vs.size());
    for(std::size_t i = 0; i < vs.size(); ++i) {
      xs[i] = P[vs[i]];
      offset_caps[i] = (std::max)(top_face_offset(vs[i]), 0.5 * opt.fidelity_distance);
    }
    const double cap_v = (std::min)(offset_cap, (std::max)(v_offset, 0.5 * opt.fidelity_distance));
    for(const Vec3& x : steps) {
      move(v, x);
      // (a step whose faces stand well beyond the cap before the vertices around move is not
      // tried: their moves bring them back within it rarely; never from beyond 1.2 times it on
      // the motorBike, where 1,538 of 16,400 steps were such, 0.3 s; bunny at the test's
      // sizes: 13 vertices end elsewhere, the same figures)
      if(opt.turn_joint_offset_slack > 0 && top_face_offset(v) > opt.turn_joint_offset_slack * cap_v) { move(v, x0); continue; }
      for(Index w : vs) improve(w, cells);
      bool ok = top_face_offset(v) <= cap_v && g.passes(*this);
      for(std::size_t i = 0; ok && i < vs.size(); ++i) ok = top_face_offset(vs[i]) <= offset_caps[i];
      if(ok) {
        stamp_move(v);
        for(Index w : vs) stamp_move(w);
        return true;
      }
      for(std::size_t i = 0; i < vs.size(); ++i) move(vs[i], xs[i]);
      move(v, x0);
    }
    return false;
  }

  // the repairs' floor of the scaled Jacobian (`sj_floor`): max(0.25, the mesh's minimum); returns
  // the floor before
  double set_repair_sj_floor()
  {
    double sj_min = 1;
    for(Index c = 0; c < m.hexahedra.size(); ++c) sj_min = (std::min)(sj_min, cell_sj(c));
    const double before = sj_floor;
    sj_floor = (std::max)(0.25, sj_min);
    return before;
  }

  // OpenFOAM's "face tets" (checkMesh -allGeometry) fail at a face none of whose diagonal splits
  // gives positive tetrahedra with the cell centres on both sides: a folded face of a cell the
  // optimisation left valid. Made a quality of its own, the splits trade the scaled Jacobian away
  // everywhere (eight: minimum 0.22 -> 0.04); so they are repaired last and locally: the cells of
  // the whole faces whose better diagonal split scores below `min_face_split_quality` in either
  // cell, if their own split quality is below it too, have their vertices moved by `improve()`,
  // the quality then counting the split. Guards: no cell falls below min(its quality,
  // keep_quality), nor its scaled Jacobian below min(its own, max(0.25, the mesh's minimum)), nor
  // does a face's non-orthogonality rise above max(its own, 60 degrees). Other cells are not touched.
  void repair_face_splits()
  {
    set_repair_sj_floor();
    {
      // the cell across each whole face: the other cell at its first corner with the same face
      // (from the cells around the vertices: the map of the open faces used before added 2 MB to
      // the capture's memory peak on the motorBike, whose peak is in the repairs and the unfolding)
      CGAL_assertion(cstart.size() == P.size() + 1 && cinc.size() == 8 * m.hexahedra.size());
      face_neighbour.assign(m.hexahedra.size(), std::array<Index, 6>{{NONE, NONE, NONE, NONE, NONE, NONE}});
      auto face_key = [&](Index c, int fi) {
        std::array<Index, 4> k;
        for(int i = 0; i < 4; ++i) k[std::size_t(i)] = m.hexahedra[c][std::size_t(hex_local_faces()[std::size_t(fi)][std::size_t(i)])];
        std::sort(k.begin(), k.end());
        return k;
      };
      for(Index c = 0; c < m.hexahedra.size(); ++c)
        for(int fi = 0; fi < 6; ++fi) {
          const std::array<Index, 4> k = face_key(c, fi);
          for(Index j = cstart[k[0]]; j < cstart[k[0] + 1] && face_neighbour[c][std::size_t(fi)] == NONE; ++j) {
            const Index d = cinc[j];
            if(d == c) continue;
            const auto& H = m.hexahedra[d];
            if(std::find(H.begin(), H.end(), k[1]) == H.end() || std::find(H.begin(), H.end(), k[2]) == H.end() ||
               std::find(H.begin(), H.end(), k[3]) == H.end())
              continue;
            for(int fj = 0; fj < 6; ++fj) if(face_key(d, fj) == k) { face_neighbour[c][std::size_t(fi)] = d; break; }
          }
        }
    }
    // the better diagonal split of a face, each scored by the worse of its corner tetrahedra in
    // the cell and in the cell across a whole face (as `hex_face_split_quality()`)
    std::vector<Vec3> centre;   // OpenFOAM's cell centres, once per selection
    auto shared_split = [&](Index c, int fi) {
      const Index d = face_neighbour[c][std::size_t(fi)];
      const Vec3 cc = centre[c], cd = d == NONE ? cc : centre[d];
      const auto& f = hex_local_faces()[std::size_t(fi)];
      const auto& H = m.hexahedra[c];
      Vec3 q[4];
      for(int i = 0; i < 4; ++i) q[i] = P[H[std::size_t(f[std::size_t(i)])]];
      return face_shared_split(q, cc, d == NONE ? nullptr : &cd);
    };
    use_face_splits = true;
    rep.face_split_repairs += repair_sweeps([&](std::vector<char>& chosen) {
      // the cells of the faces whose splits fail (or nearly), if their own splits do too
      std::vector<char> failing(m.hexahedra.size(), 0);
      centre.resize(m.hexahedra.size());
      for(Index c = 0; c < m.hexahedra.size(); ++c) { Vec3 x[8]; corners(c, x); centre[c] = foam_hex_centre(x); }
      for(Index c = 0; c < m.hexahedra.size(); ++c)
        for(int fi = 0; fi < 6; ++fi) {
          const Index d = face_neighbour[c][std::size_t(fi)];
          if(d != NONE && d < c) continue;
          if(!(shared_split(c, fi) < opt.min_face_split_quality)) continue;
          failing[c] = 1;
          if(d != NONE) failing[d] = 1;
        }
      for(Index c = 0; c < m.hexahedra.size(); ++c) {
        Vec3 x[8];
        corners(c, x);
        chosen[c] = failing[c] && hex_face_split_quality(x) < opt.min_face_split_quality;
      }
    }, opt.face_split_passes);
    use_face_splits = false;
  }

  // What the repairs and the polish leave folded: a face repaired through its cells' worst corner
  // (`hex_face_split_quality()`) may stay folded where that corner's diagonal is not the one its
  // two cells can share (motorBike: a face of two grid cells whose worst corners, -0.045 and
  // -0.005, were on different diagonals; OpenFOAM's tet decomposition failed, and the cleanup
  // cannot remove grid cells). The cells with a whole face whose better shared diagonal
  // (`cell_fold()`) scores below `opt.min_fold` have their vertices moved by `improve()`, that
  // score counted in their quality; the guards of the face-split repair. Other cells are not
  // touched. Run after the repairs and after the polish (whose guards keep the worst corners,
  // not the diagonals).
  void unfold_faces()
  {
    const double floor_before = set_repair_sj_floor();
    use_folds = true;
    // each cell's score: all of them at the first selection (the centres computed once), then
    // again only those of the cells the last sweep's moves touched (`swept_cells`) and of the
    // cells across their faces (whose score takes their centres): the same values as a full count
    std::vector<double> fold(m.hexahedra.size());
    bool first = true;
    std::vector<Index> todo;
    rep.face_split_repairs += repair_sweeps([&](std::vector<char>& chosen) {
      if(first) {
        std::vector<Vec3> centre(m.hexahedra.size());
        for(Index c = 0; c < m.hexahedra.size(); ++c) { Vec3 x[8]; corners(c, x); centre[c] = foam_hex_centre(x); }
        for(Index c = 0; c < m.hexahedra.size(); ++c) fold[c] = cell_fold(c, &centre);
        first = false;
      } else {
        todo.clear();
        for(Index c : swept_cells) {
          todo.push_back(c);
          for(Index d : face_neighbour[c]) if(d != NONE) todo.push_back(d);
        }
        std::sort(todo.begin(), todo.end());
        todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
        for(Index c : todo) fold[c] = cell_fold(c);
      }
      for(Index c = 0; c < m.hexahedra.size(); ++c) chosen[c] = fold[c] < opt.min_fold;
    }, opt.face_split_passes);
    use_folds = false;
    sj_floor = floor_before;
  }

  // The cells OpenFOAM would call concave (checkMesh -allGeometry) go in the cleanup, leaving their
  // neighbours' faces standing off the surface. The guards keep moves from making cells concave
  // (the second polish's, the joint moves'), but a cell the projection made concave stayed so
  // (motorBike: 11 buffer cells, concave with their faces whole). Last, after the polish: the
  // cells with whole faces whose `hex_concavity_margin()` is below `opt.concave_margin` have their
  // vertices moved by `improve()`, margin / concave_margin counted in their quality, under the
  // face-split repair's guards; and no cell with a hanging node on a face may lose margin below
  // min(its own, `opt.split_concave_margin`): such a cell can be concave for OpenFOAM through its
  // split faces' pieces at a whole-face margin of 0.24 (bunny at --thin-cells 5: made so by a
  // version that raised their margins to 0.2 unguarded). Those cells are not repaired (their test
  // needs the pieces with the export's bulge, `IO::internal::foam_points()`).
  void repair_concave_cells()
  {
    split_cell.assign(m.hexahedra.size(), 0);
    for(const auto& hn : m.hanging_nodes) {
      const Index m0 = hn.masters[0];
      for(Index i = cstart[m0]; i < cstart[m0 + 1]; ++i) {
        const auto& H = m.hexahedra[cinc[i]];
        bool all = true;
        for(int j = 1; j < hn.number_of_masters && all; ++j) all = std::find(H.begin(), H.end(), hn.masters[std::size_t(j)]) != H.end();
        if(all) split_cell[cinc[i]] = 1;
      }
    }
    const double floor_before = set_repair_sj_floor();
    use_concavity = true;
    // (each cell's margin computed at the first selection, then again only where the last
    // sweep's moves touched it)
    std::vector<double> margin(m.hexahedra.size());
    auto update = [&](Index c) { margin[c] = split_cell[c] ? 1.0 : cell_concavity_margin(c); };
    for(Index c = 0; c < m.hexahedra.size(); ++c) update(c);
    bool first = true;
    rep.concave_repairs += repair_sweeps([&](std::vector<char>& chosen) {
      if(!first) for(Index c : swept_cells) update(c);
      first = false;
      for(Index c = 0; c < m.hexahedra.size(); ++c) chosen[c] = margin[c] < opt.concave_margin;
    }, opt.face_split_passes);
    use_concavity = false;
    sj_floor = floor_before;
    std::vector<char>().swap(split_cell);
  }
  double cell_concavity_margin(Index c) const { Vec3 x[8]; corners(c, x); return hex_concavity_margin(x); }

  // the corners of the cells v moves (`affected_cells()`, into `cells`), a hanging one as its
  // independent masters, with repeats (v among them)
  void cell_corner_masters(Index v, std::vector<Index>& out, std::vector<Index>& cells) const
  {
    affected_cells(v, cells);
    out.clear();
    for(Index cell : cells)
      for(Index w : m.hexahedra[cell]) {
        if(kind[w] == HANGING) { for(const auto& x : hang_masters[hang_of[w]]) out.push_back(x.first); }
        else out.push_back(w);
      }
  }

  // a vertex to improve (the masters of a hanging one), once
  void add_work_vertex(Index v, std::vector<Index>& work, std::vector<char>& in_work) const
  {
    if(kind[v] == HANGING) {
      for(const auto& x : hang_masters[hang_of[v]])
        if(movable(x.first) && !in_work[x.first]) { in_work[x.first] = 1; work.push_back(x.first); }
    } else if(movable(v) && !in_work[v]) { in_work[v] = 1; work.push_back(v); }
  }

  // The sweeps of the repairs: `select(chosen)` marks the cells to work on, their vertices go
  // through `improve()` (with the repair's quality and guards), until none moves or after
  // `passes` sweeps. Returns the number of moves.
  template <typename Select>
  std::size_t repair_sweeps(Select&& select, int passes)
  {
    std::vector<Index> cells, work;
    std::vector<char> in_work(P.size(), 0), chosen(m.hexahedra.size(), 0);
    std::size_t total = 0;
    for(int pass = 0; pass < passes; ++pass) {
      std::fill(chosen.begin(), chosen.end(), 0);
      select(chosen);
      swept_cells.clear();
      for(Index c = 0; c < m.hexahedra.size(); ++c)
        if(chosen[c]) for(Index v : m.hexahedra[c]) add_work_vertex(v, work, in_work);
      if(work.empty()) break;
      std::sort(work.begin(), work.end());
      std::size_t moved = 0;
      for(Index v : work) {
        in_work[v] = 0;
        if(!improve(v, cells)) continue;
        ++moved;
        swept_cells.insert(swept_cells.end(), cells.begin(), cells.end());
        if(use_quality_cache) record_move(v, cells);   // (the polish: as in optimise()'s sweeps)
      }
      total += moved;
      work.clear();
      if(moved == 0) break;
    }
    return total;
  }

  // the warp of a cell's face: the largest distance of its corners from the plane through their
  // average normal to the diagonals' cross product, over its mean edge length
  static double face_warp(const Vec3* x, const std::array<int, 4>& f)
  {
    const Vec3& a = x[f[0]];
    const Vec3& b = x[f[1]];
    const Vec3& c = x[f[2]];
    const Vec3& d = x[f[3]];
    Vec3 n = cross(sub(c, a), sub(d, b));
    const double ln = norm(n);
    const double L = (norm(sub(b, a)) + norm(sub(c, b)) + norm(sub(d, c)) + norm(sub(a, d))) / 4;
    if(!(ln > 0) || !(L > 0)) return 1;
    n = mul(n, 1.0 / ln);
    const Vec3 m = mul(add(add(a, b), add(c, d)), 0.25);
    double w = 0;
    for(const Vec3* p : {&a, &b, &c, &d}) w = (std::max)(w, std::abs(dot(sub(*p, m), n)));
    return w / L;
  }
  // 1 for flat faces split in four, 0 at `opt.max_split_face_warp` x 2
  double split_warp_quality(Index c, const Vec3* x) const
  {
    double q = 1;
    if(c < split_faces.size())
      for(std::uint8_t fi : split_faces[c])
        q = (std::min)(q, 1 - face_warp(x, hex_local_faces()[fi]) / (2 * opt.max_split_face_warp));
    return q;
  }

  // Maximise the minimum scaled Jacobian, then reduce the non-orthogonality: the cells with a whole
  // face whose non-orthogonality (from the vertex averages) is beyond `opt.max_non_orthogonality`
  // have their vertices moved by `improve()` with the worst face's angle as their quality (1 up to
  // the limit, 0 at 90 degrees). Guards: no cell's scaled Jacobian falls below min(its own,
  // max(0.3, the mesh's minimum)), no cell becomes worse than min(its angle quality, keep_quality).
  void reduce_non_orthogonality()
  {
    const double floor_before = sj_floor;
    sj_floor = (std::max)(0.3, sj_floor);
    use_non_orthogonality = true;
    rep.non_orthogonality_repairs += repair_sweeps([&](std::vector<char>& chosen) {
      for(Index c = 0; c < m.hexahedra.size(); ++c) chosen[c] = cell_non_orthogonality(c) > opt.max_non_orthogonality;
    }, opt.face_split_passes);
    use_non_orthogonality = false;
    sj_floor = floor_before;
  }

  // The worst cells last: their vertices are moved by `improve()` alone (no energy step, which
  // trades a cell's minimum for its neighbours' shape), the split faces' warp counted in the
  // quality. Guards: no cell below min(its quality, `opt.polish_quality`), nor its scaled Jacobian
  // below min(its own, `opt.polish_quality`), nor its worst face split (`hex_face_split_quality`)
  // below min(its own, `opt.min_face_split_quality`); the worst non-orthogonality of the moved
  // vertex's cells (whole faces, vertex averages: `max_non_orthogonality()`) may not rise above
  // max(its value, `opt.max_non_orthogonality`). So neither the minimum scaled Jacobian below 0.35
  // nor the count of cells under it can get worse; OpenFOAM's non-orthogonality (cell centres,
  // split faces) may rise a little. `opt.polish_passes` 0 turns it off.
  void polish()
  {
    const double keep_before = opt.keep_quality, floor_before = sj_floor;
    opt.keep_quality = sj_floor = opt.polish_quality;
    use_polish = true;
    // (each cell's quality is computed once, then again only where a move of the last sweep touched
    // it; the cache of optimise() serves the moves, from a new epoch: the quality is the polish's)
    use_quality_cache = !moved_at.empty();
    struct Cache_off { bool& on; ~Cache_off() { on = false; } } cache_off{use_quality_cache};
    if(use_quality_cache) epoch = next_stamp();
    std::vector<char> below;
    rep.polish_moves += repair_sweeps([&](std::vector<char>& chosen) {
      if(below.empty()) {
        below.resize(m.hexahedra.size());
        for(Index c = 0; c < m.hexahedra.size(); ++c) below[c] = cell_quality(c) < opt.polish_quality;
      } else
        for(Index c : swept_cells) below[c] = current_quality(c) < opt.polish_quality;   // (just cached)
      chosen = below;
    }, opt.polish_passes);
    use_polish = false;
    opt.keep_quality = keep_before;
    sj_floor = floor_before;
  }

  // a cell's qualities one by one (the polish's joint moves): [0, 9) its scaled Jacobians
  // (`hex_scaled_jacobians()`), [9, 33) its face pyramids, [33, 57) its face splits, [57, 63) the
  // warp quality of its faces split in four (1 for the others). The polish's quality is the
  // minimum of all but the face splits.
  static constexpr int n_cell_values = 63;
  void cell_values(Index c, double* v) const
  {
    Vec3 x[8];
    corners(c, x);
    hex_scaled_jacobians(x, v);
    hex_pyramid_qualities(x, v + 9);
    if(second_polish) for(int i = 9; i < 33; ++i) v[i] *= pyramid_weight();
    hex_face_split_qualities(x, v + 33);
    for(int f = 0; f < 6; ++f) v[57 + f] = 1;
    if(c < split_faces.size())
      for(std::uint8_t fi : split_faces[c]) v[57 + fi] = 1 - face_warp(x, hex_local_faces()[fi]) / (2 * opt.max_split_face_warp);
  }

  // The polish moves one vertex at a time: a cell whose worst corner needs several vertices to
  // move together (a quad's angle on the surface opened by the vertices across it, whose other
  // cells then need their own neighbours to follow) stays where it is. Joint moves: around each
  // cell below `opt.patch_floor` (0.3), worst first, the movable vertices of the cells sharing a
  // vertex with it (a patch, `opt.patch_rings` rings; boundary vertices slide on their surface or
  // curve) go down the gradient of a soft minimum of the patch cells' values (`cell_values()`):
  // the sum of exp(k (t - v)) - 1 over the values v below t = `opt.patch_target`,
  // k = `opt.patch_sharpness`, the face splits rescaled so that min(2 x their floor, their value
  // before) counts as t. Guards, at every step, each cell against its value before the patch: its
  // quality and scaled Jacobian not below `opt.polish_quality` if they were at or above it, else
  // not below min(that value, the patch's minimum now) - a cell below 0.35 may fall to the
  // patch's minimum, what the max-min trades; its face split not below min(that value,
  // `opt.min_face_split_quality`); the patch's worst non-orthogonality not above max(its value,
  // `opt.max_non_orthogonality`). So neither the minimum below 0.35 nor the count of cells under
  // 0.35 can get worse (quality or scaled Jacobian). The values within
  // `slack` of their floor are constraints of the step: its direction is the gradient projected
  // so that none falls at first order (`project_direction()`). A step is taken if the penalty
  // falls and the guards hold (a backtracking line search); the patch stops after
  // `opt.patch_iterations` steps or `opt.patch_stall` steps without raising its worst cell, and is
  // kept only if its worst cell got better and its count of cells whose scaled Jacobian is below
  // `opt.patch_floor` did not grow. Gradients by forward differences of constrained moves. Around
  // a cell with curve or corner vertices, the patch is first tried with those loosened: surface
  // vertices of one region, within `opt.loosen_curve` local sizes of their curve
  // (`opt.loosen_corner` local sizes of their corner's point), a guard of every later step (see
  // the loop below).
  // In the second polish (`second_polish`): the pyramids weighted (`pyramid_weight()`), the
  // patches around the cells whose scaled Jacobian is below `opt.patch_floor`, and a step may not
  // make a patch cell concave (`cell_concave()`) that was not.
  // Returns the number of patches kept.
  template <typename Visitor>
  std::size_t polish_patches(Visitor& visitor)
  {
    const double t = opt.patch_target, k_sharp = opt.patch_sharpness, slack = 0.005;
    const double split_scale = t / (2 * opt.min_face_split_quality);
    use_polish = true;
    // what a cell must be below to have a patch (the second polish: its scaled Jacobian)
    auto seed_value = [&](Index c) { return second_polish ? cell_sj(c) : cell_quality(c); };
    std::vector<std::pair<double, Index>> bad;
    for(Index c = 0; c < m.hexahedra.size(); ++c) {
      const double q = seed_value(c);
      if(q < opt.patch_floor) bad.push_back({q, c});
    }
    std::sort(bad.begin(), bad.end());
    std::size_t kept = 0;
    std::vector<Index> pv, pc, cells;
    std::vector<char> in_pv(P.size(), 0), in_pc(m.hexahedra.size(), 0);
    std::vector<std::vector<Index>> vcells;   // per patch vertex: its cells (positions in pc), sorted
    std::vector<Vec3> x0, xs, g, ga;
    std::vector<double> q_old, sj_old, split_old_, split_ref, cv, vals, gbase;   // cv: the patch cells' values
    std::vector<char> conc_patch;   // (the second polish) the patch cells concave at its start
    struct Eval { double pen, q, sj, split; };
    std::vector<Eval> ev, ev1;
    std::vector<std::pair<Index, int>> active;   // the values near their floor: (cell in pc, value)
    std::vector<std::size_t> active_start;       // per cell in pc: its first entry in `active`
    double f_it = 0, sj_it = 0;                  // the patch's minimum quality and scaled Jacobian now
    // what a cell's quality and scaled Jacobian may not fall below: the polish's threshold if it
    // was at or above it, else min(its value, the patch's minimum now)
    auto floor_q = [&](std::size_t j) { return q_old[j] >= opt.polish_quality ? opt.polish_quality : (std::min)(q_old[j], f_it); };
    auto floor_sj = [&](std::size_t j) { return sj_old[j] >= opt.polish_quality ? opt.polish_quality : (std::min)(sj_old[j], sj_it); };
    auto count_below = [&]() {   // (from `ev`, the patch cells at their current places)
      std::size_t k = 0;
      for(const auto& r : ev) if(r.sj < opt.patch_floor) ++k;
      return k;
    };
    auto floor_of = [&](std::size_t j, int k) {
      const double fq = floor_q(j);
      if(k < 9) return (std::max)(fq, floor_sj(j));
      if(k >= 33 && k < 57) return (std::min)(split_old_[j], opt.min_face_split_quality);
      return fq;
    };
    // from a cell's values v: its penalty, quality (as `cell_quality()` in the polish), scaled
    // Jacobian and face split quality
    auto summarise = [&](std::size_t j, const double* v) {
      Eval r{0, 0, 0, 0};
      for(int k = 0; k < n_cell_values; ++k) {
        const double y = k >= 33 && k < 57 ? t + (v[k] - split_ref[j]) * split_scale : v[k];
        if(y < t) r.pen += std::expm1(k_sharp * (t - y));
      }
      r.sj = (std::max)(-1.0, (std::min)(1.0, min_of(v, 9)));
      r.q = (std::min)(r.sj, (std::min)(min_of(v + 9, 24), min_of(v + 57, 6)));
      r.split = min_of(v + 33, 24);
      return r;
    };
    auto evaluate = [&](std::size_t j, double* v) { cell_values(pc[j], v); return summarise(j, v); };
    // the curve and corner vertices let off their feature (those of the patches kept and of the
    // patch being tried): `constrain()` pulls them back towards it, a guard keeps them near it in
    // every later patch too
    loose.clear();
    loose_of.assign(P.size(), NO_LOOSE);
    // (the vertices that left their feature are remembered: `fidelity_polish()` leaves them where they are)
    struct Loose_off
    {
      Boundary_capture_3& c;
      ~Loose_off()
      {
        for(const Loose& l : c.loose)
          if(c.kind[l.v] == SURFACE) { c.left_feature.resize(c.P.size(), 0); c.left_feature[l.v] = 1; }
        c.loose_of.clear();
        c.loose.clear();
      }
    } loose_off{*this};
    auto guards_hold = [&](const std::vector<Eval>& ev) {
      for(Index v : pv)
        if(loose_of[v] != NO_LOOSE) {
          const Loose& l = loose[loose_of[v]];
          if(norm(sub(P[v], feature_point(l, P[v]))) > loose_tolerance(l)) return false;
        }
      for(std::size_t j = 0; j < ev.size(); ++j)
        if(ev[j].q < floor_q(j) || ev[j].sj < floor_sj(j) || ev[j].split < (std::min)(split_old_[j], opt.min_face_split_quality))
          return false;
      return true;
    };
    std::size_t tried = 0;
    bool loosening = false;   // the patch being tried has loosened vertices
    // one patch around c0: returns true if kept
    auto patch = [&](const Index c0) {
      // the patch: the movable vertices of the cells around c0 (a hanging node's masters)
      pv.clear();
      for(Index v : m.hexahedra[c0]) add_work_vertex(v, pv, in_pv);
      for(int ring = 0; ring < opt.patch_rings; ++ring) {
        const std::size_t nr = pv.size();
        for(std::size_t i = 0; i < nr; ++i) {
          const Index v = pv[i];
          for(Index k = cstart[v]; k < cstart[v + 1]; ++k)
            for(Index w : m.hexahedra[cinc[k]]) add_work_vertex(w, pv, in_pv);
        }
      }
      for(Index v : pv) in_pv[v] = 0;
      if(pv.empty()) return false;
      std::sort(pv.begin(), pv.end());
      // the cells they move
      pc.clear();
      for(Index v : pv) {
        affected_cells(v, cells);
        for(Index c : cells) if(!in_pc[c]) { in_pc[c] = 1; pc.push_back(c); }
      }
      std::sort(pc.begin(), pc.end());
      for(Index c : pc) in_pc[c] = 0;
      vcells.assign(pv.size(), {});
      for(std::size_t i = 0; i < pv.size(); ++i) {
        affected_cells(pv[i], cells);
        for(Index c : cells) vcells[i].push_back(Index(std::lower_bound(pc.begin(), pc.end(), c) - pc.begin()));
      }
      const std::size_t n = pv.size(), nc = pc.size();
      q_old.resize(nc); sj_old.resize(nc); split_old_.resize(nc); split_ref.resize(nc);
      cv.resize(nc * n_cell_values);
      ev.resize(nc);
      ev1.resize(nc);
      double f0 = 1, e = 0;
      sj_it = 1;
      for(std::size_t j = 0; j < nc; ++j) {
        double* v = &cv[j * n_cell_values];
        cell_values(pc[j], v);
        split_ref[j] = (std::min)(min_of(v + 33, 24), 2 * opt.min_face_split_quality);
        ev[j] = summarise(j, v);
        q_old[j] = ev[j].q;
        sj_old[j] = ev[j].sj;
        split_old_[j] = ev[j].split;
        e += ev[j].pen;
        f0 = (std::min)(f0, q_old[j]);
        sj_it = (std::min)(sj_it, sj_old[j]);
      }
      f_it = f0;
      const double sj0 = sj_it;
      const std::size_t count0 = count_below();
      const double nonortho_cap = (std::max)(opt.max_non_orthogonality, max_non_orthogonality(pc));
      if(second_polish) { conc_patch.resize(nc); for(std::size_t j = 0; j < nc; ++j) conc_patch[j] = cell_concave(pc[j]); }
      auto no_new_concave = [&]() {
        if(second_polish) for(std::size_t j = 0; j < nc; ++j) if(!conc_patch[j] && cell_concave(pc[j])) return false;
        return true;
      };
      x0.resize(n);
      for(std::size_t i = 0; i < n; ++i) x0[i] = P[pv[i]];
      auto restore = [&](const std::vector<Vec3>& x) { for(std::size_t i = 0; i < n; ++i) move(pv[i], x[i]); };
      g.resize(n);
      xs.resize(n);
      vals.resize(n_cell_values);
      double alpha0 = 0.2;
      int stalled = 0;
      for(int it = 0; it < opt.patch_iterations && e > 0; ++it) {
        // the constraints: the values within `slack` of their floor
        active.clear();
        active_start.assign(nc + 1, 0);
        gbase.clear();
        for(std::size_t j = 0; j < nc; ++j) {
          active_start[j] = active.size();
          const double* v = &cv[j * n_cell_values];
          for(int k = 0; k < n_cell_values; ++k)
            if(v[k] < floor_of(j, k) + slack) { active.push_back({Index(j), k}); gbase.push_back(v[k]); }
        }
        active_start[nc] = active.size();
        const std::size_t na = active.size();
        ga.assign(na * n, Vec3{{0, 0, 0}});   // their gradients, row by row
        // the gradients (the penalty's and the constraints'), by forward differences (a vertex
        // moves its own cells only) of constrained moves, per unit of the local size
        for(std::size_t i = 0; i < n; ++i) {
          // a vertex none of whose cells has a penalty or a constraint has no gradient
          bool hot = false;
          for(Index j : vcells[i]) hot = hot || ev[j].pen > 0 || active_start[j] < active_start[j + 1];
          if(!hot) { g[i] = Vec3{{0, 0, 0}}; continue; }
          const Index v = pv[i];
          const Vec3 x = P[v];
          const double h = local_size(v);
          const double eps = 1e-6 * h;
          double base = 0;
          for(Index j : vcells[i]) base += ev[j].pen;
          for(int a = 0; a < 3; ++a) {
            Vec3 y = x;
            y[a] += eps;
            move(v, constrain(v, y));   // along its surface or curve: the gradient is the constrained one
            double p = 0;
            for(Index j : vcells[i]) {
              p += evaluate(j, vals.data()).pen;
              for(std::size_t r = active_start[j]; r < active_start[j + 1]; ++r)
                ga[r * n + i][a] = (vals[std::size_t(active[r].second)] - gbase[r]) / eps * h;
            }
            g[i][a] = (p - base) / eps * h;
          }
          move(v, x);
        }
        project_direction(g, ga, na, n);
        double gmax = 0;
        for(std::size_t i = 0; i < n; ++i) gmax = (std::max)(gmax, norm(g[i]));
        if(!(gmax > 0)) break;
        for(std::size_t i = 0; i < n; ++i) xs[i] = P[pv[i]];
        // a backtracking line search, from twice the last step taken (at most 0.2 local sizes)
        bool stepped = false;
        for(double alpha = alpha0; alpha > 1e-3 && !stepped; alpha *= 0.5) {
          for(std::size_t i = 0; i < n; ++i) {
            const Index v = pv[i];
            const double h = local_size(v);
            move(v, constrain(v, sub(xs[i], mul(g[i], alpha * h / gmax))));
          }
          // (the penalties are not negative: once their partial sum reaches the bound, the step fails)
          const double bound = e * (1 - 1e-6);
          double e1 = 0;
          for(std::size_t j = 0; j < nc && e1 < bound; ++j) { ev1[j] = evaluate(j, vals.data()); e1 += ev1[j].pen; }
          if(e1 < bound && guards_hold(ev1) && max_non_orthogonality(pc) <= nonortho_cap && no_new_concave()) {
            e = e1;
            stepped = true;
            alpha0 = (std::min)(0.2, 2 * alpha);
          } else restore(xs);
        }
        if(!stepped) break;
        const double f_before = f_it;
        f_it = sj_it = 1;
        for(std::size_t j = 0; j < nc; ++j) {
          ev[j] = evaluate(j, &cv[j * n_cell_values]);
          f_it = (std::min)(f_it, ev[j].q);
          sj_it = (std::min)(sj_it, ev[j].sj);
        }
        // the worst cell no longer rising: done (the penalty's tail is not worth its cost)
        stalled = f_it > f_before + 1e-4 ? 0 : stalled + 1;
        if(stalled == opt.patch_stall) break;
      }
      // (`ev` is at the positions now: those of the last step taken, or of the start)
      // (a patch with loosened vertices must not lower its worst scaled Jacobian either: the
      // guards keep it from falling below min(its start, `polish_quality`); this rejects the
      // patches whose worst scaled Jacobian started above `polish_quality` and fell)
      if(f_it > f0 + 1e-4 && count_below() <= count0 && (!loosening || sj_it >= sj0 - 1e-12)) return true;
      restore(x0);
      return false;
    };
    for(const auto& b : bad) {
      // (polled between patches: a patch is kept whole or not at all)
      if(cancelled || (++tried % 32 == 0 && !visitor.go_further(1.0))) { cancelled = true; break; }
      const Index c0 = b.second;
      if(seed_value(c0) >= opt.patch_floor) continue;
      // The cell's curve and corner vertices may leave their feature (within `loosen_curve` /
      // `loosen_corner` local sizes of it), sliding on the surface (on the side of the curve
      // whose region they had, else of the nearest triangle's): a cell pinned between two
      // curves, or at a corner whose curves meet at a narrow angle, opens. The patch is tried
      // loosened first (kept on the usual terms, and only if its worst scaled Jacobian did not
      // fall); if it is not kept, the vertices go back to their feature and the plain patch is
      // tried. If it is kept, those that left their feature stay surface vertices, the others
      // take their kind again.
      const std::size_t first = loose.size();
      auto unloosen = [&]() {
        for(std::size_t i = loose.size(); i-- > first;) {
          const Loose& l = loose[i];
          kind[l.v] = l.kind;
          vregion[l.v] = l.region;
          loose_of[l.v] = NO_LOOSE;
        }
        loose.resize(first);
      };
      if(opt.loosen_curve > 0 || opt.loosen_corner > 0)
        for(Index v : m.hexahedra[c0])
          if((kind[v] == CURVE && opt.loosen_curve > 0) || (kind[v] == CORNER && opt.loosen_corner > 0)) {
            loose_of[v] = std::uint32_t(loose.size());
            loose.push_back({v, kind[v], vregion[v], P[v]});
            kind[v] = SURFACE;
            if(vregion[v] < 0) vregion[v] = region_of_point(P[v]);   // (else the side its faces chose)
          }
      if(loose.size() == first) { if(patch(c0)) ++kept; continue; }
      loosening = true;
      const bool kept_loose = patch(c0);
      loosening = false;
      if(!kept_loose) { unloosen(); if(patch(c0)) ++kept; continue; }
      ++kept;
      // those that did not leave their feature take their kind again
      std::size_t k = first;
      for(std::size_t i = first; i < loose.size(); ++i) {
        const Loose l = loose[i];
        if(norm(sub(P[l.v], feature_point(l, P[l.v]))) <= 1e-9 * local_size(l.v)) {
          kind[l.v] = l.kind;
          vregion[l.v] = l.region;
          loose_of[l.v] = NO_LOOSE;
        }
        else { loose_of[l.v] = std::uint32_t(k); loose[k++] = l; }
      }
      loose.resize(k);
      rep.loosened_vertices += loose.size() - first;
    }
    use_polish = false;
    return kept;
  }

  // A coarse cell's face split in four by a face node is written as four quarters meeting at
  // the node: on a warped face they form a saddle, whose diagonal quarters face each other, and
  // OpenFOAM calls the cell concave (checkMesh -allGeometry) unless the node's bulge outruns the
  // warp. The cells with such a face warped beyond `opt.max_split_face_warp` have their vertices
  // moved by `improve()`, the warp counted in their quality, under the face-split repair's guards.
  void repair_split_face_warp()
  {
    split_faces.assign(m.hexahedra.size());
    bool any = false;
    for(const auto& hn : m.hanging_nodes) {
      if(hn.number_of_masters != 4) continue;
      std::array<Index, 4> k{{hn.masters[0], hn.masters[1], hn.masters[2], hn.masters[3]}};
      std::sort(k.begin(), k.end());
      // the coarse cell: a cell of the first master having the four as one of its faces
      for(Index i = cstart[k[0]]; i < cstart[k[0] + 1]; ++i) {
        const Index c = cinc[i];
        for(int fi = 0; fi < 6; ++fi) {
          std::array<Index, 4> f;
          for(int j = 0; j < 4; ++j) f[std::size_t(j)] = m.hexahedra[c][std::size_t(hex_local_faces()[std::size_t(fi)][std::size_t(j)])];
          std::sort(f.begin(), f.end());
          if(f == k) { split_faces.at(c).push_back(std::uint8_t(fi)); any = true; }
        }
      }
    }
    if(!any) return;
    use_split_warp = true;
    rep.split_warp_repairs += repair_sweeps([&](std::vector<char>& chosen) {
      for(Index c = 0; c < m.hexahedra.size(); ++c) {
        if(split_faces[c].empty()) continue;
        Vec3 x[8];
        corners(c, x);
        chosen[c] = split_warp_quality(c, x) < 0.5;
      }
    }, opt.face_split_passes);
    use_split_warp = false;
  }

  // The last resort: a buffer cell the optimisation could not make valid is removed; the staircase
  // face under it and the side faces of its buffer neighbours become boundary faces (of the top
  // face's patch). Interior cells cannot be invalid: they start valid and no move makes a valid
  // cell invalid.
  void remove_invalid_buffer_cells(const std::vector<Index>& also)
  {
    const std::size_t first = m.hexahedra.size() - rep.buffer_cells;
    std::vector<char> gone(m.hexahedra.size(), 0);
    std::size_t n = 0;
    for(std::size_t c = first; c < m.hexahedra.size(); ++c)
      if(!(cell_quality(Index(c)) > opt.min_valid_quality)) { gone[c] = 1; ++n; }
    for(Index c : also) if(c >= first && !gone[c]) { gone[c] = 1; ++n; }
    if(n == 0) return;
    // the faces of the buffer cells (pillows included), by their sorted corners
    typedef std::array<Index, 4> Quad;
    struct Quad_hash
    {
      std::size_t operator()(const Quad& q) const
      {
        std::uint64_t h = 1469598103934665603ull;
        for(Index x : q) h = (h ^ x) * 1099511628211ull;
        return std::size_t(h);
      }
    };
    auto sorted = [](Quad q) { std::sort(q.begin(), q.end()); return q; };
    auto face_of = [&](Index c, int fi) {
      Quad q;
      for(int i = 0; i < 4; ++i) q[std::size_t(i)] = m.hexahedra[c][std::size_t(hex_local_faces()[std::size_t(fi)][std::size_t(i)])];
      return q;
    };
    std::unordered_map<Quad, std::vector<std::pair<Index, int>>, Quad_hash> by_face;
    for(std::size_t c = first; c < m.hexahedra.size(); ++c)
      for(int fi = 0; fi < 6; ++fi) by_face[sorted(face_of(Index(c), fi))].push_back({Index(c), fi});
    std::unordered_map<Index, std::array<Index, 2>> masters_of;
    std::unordered_map<std::uint64_t, Index> mid;
    for(const auto& hn : m.hanging_nodes)
      if(hn.number_of_masters == 2) {
        masters_of[hn.vertex] = {{hn.masters[0], hn.masters[1]}};
        mid[capture_edge_key(hn.masters[0], hn.masters[1])] = hn.vertex;
      }
    auto cells_with = [&](const Quad& q, Index except, std::vector<std::pair<Index, int>>& out) {
      auto it = by_face.find(sorted(q));
      if(it != by_face.end()) for(const auto& x : it->second) if(x.first != except) out.push_back(x);
    };
    // the cells across a face: the same quad, or the two halves of it split at hanging midpoints
    auto across = [&](Index c, int fi, std::vector<std::pair<Index, int>>& out) {
      out.clear();
      const Quad q = face_of(c, fi);
      cells_with(q, c, out);
      if(!out.empty()) return;
      for(int s_ = 0; s_ < 2; ++s_) {
        const Index a = q[std::size_t(s_)], b = q[std::size_t(s_ + 1)], c2 = q[std::size_t(s_ + 2)], d2 = q[std::size_t((s_ + 3) % 4)];
        auto m1 = mid.find(capture_edge_key(a, b)), m2 = mid.find(capture_edge_key(d2, c2));
        if(m1 == mid.end() || m2 == mid.end()) continue;
        cells_with({{a, m1->second, m2->second, d2}}, c, out);
        cells_with({{m1->second, b, c2, m2->second}}, c, out);
      }
    };
    // the whole face a half face belongs to (the half's two corners hanging on its edges)
    auto other_master = [&](Index x, Index p) {
      auto it = masters_of.find(x);
      if(it == masters_of.end()) return NONE;
      return it->second[0] == p ? it->second[1] : it->second[1] == p ? it->second[0] : NONE;
    };
    auto whole_of = [&](const Quad& q, Quad& out) {
      for(int s_ = 0; s_ < 4; ++s_) {
        const Index a = q[std::size_t(s_)], b = q[std::size_t((s_ + 1) % 4)], c2 = q[std::size_t((s_ + 2) % 4)], d2 = q[std::size_t((s_ + 3) % 4)];
        const Index r1 = other_master(b, a), r2 = other_master(c2, d2);
        if(r1 != NONE && r2 != NONE) { out = {{a, r1, r2, d2}}; return true; }
      }
      return false;
    };
    // a removed fine cell takes the coarse cell beside it (whose face it half covers) along
    std::vector<std::pair<Index, int>> nb;
    for(bool changed = true; changed;) {
      changed = false;
      for(std::size_t c = first; c < m.hexahedra.size(); ++c) {
        if(!gone[c]) continue;
        for(int fi = 0; fi < 6; ++fi) {
          Quad w;
          if(!whole_of(face_of(Index(c), fi), w)) continue;
          nb.clear();
          cells_with(w, Index(c), nb);
          for(const auto& x : nb) if(!gone[x.first]) { gone[x.first] = 1; ++n; changed = true; }
        }
      }
    }
    rep.removed_buffer_cells += n;
    for(std::size_t c = first; c < m.hexahedra.size(); ++c)
      if(gone[c]) {
        Vec3 x[8];
        corners(Index(c), x);
        rep.removed_buffer_cell_centres.push_back(hex_centre(x));
      }
    std::vector<int> top_patch(m.hexahedra.size(), 6);
    std::vector<typename HexMesh::Boundary_face> faces;
    for(const auto& f : m.boundary_faces) {
      if(f.cell >= first) top_patch[f.cell] = f.patch;
      if(!gone[f.cell]) faces.push_back(f);
    }
    // a buffer cell's side i (over its bottom edge i, i + 1), in the order the buffer made them
    static const int side_of_face[6] = {3, 1, 0, 2, -1, -1};
    auto exposed = [&](Index c, int fi) {
      const auto& h = m.hexahedra[c];
      const int i = side_of_face[fi];
      if(buffer_owner[c - first] == NONE || i < 0) return face_of(c, fi);
      return Quad{{h[std::size_t(i)], h[std::size_t((i + 1) % 4)], h[std::size_t((i + 1) % 4 + 4)], h[std::size_t(i + 4)]}};
    };
    for(std::size_t c = first; c < m.hexahedra.size(); ++c) {
      if(!gone[c]) continue;
      const auto& h = m.hexahedra[c];
      // the staircase face becomes a boundary face of the cell under it
      if(buffer_owner[c - first] != NONE)
        faces.push_back({Quad{{h[0], h[1], h[2], h[3]}}, buffer_owner[c - first], top_patch[c]});
      for(int fi : {2, 1, 3, 0, 4, 5}) {
        across(Index(c), fi, nb);
        for(const auto& x : nb)
          if(!gone[x.first]) faces.push_back({exposed(x.first, x.second), x.first, top_patch[x.first]});
      }
    }
    // compact the cells
    std::vector<Index> new_index(m.hexahedra.size(), NONE);
    std::size_t k = 0;
    for(std::size_t c = 0; c < m.hexahedra.size(); ++c)
      if(!gone[c]) { new_index[c] = Index(k); m.hexahedra[k] = m.hexahedra[c]; m.cell_levels[k] = m.cell_levels[c]; ++k; }
    m.hexahedra.resize(k);
    m.cell_levels.resize(k);
    std::vector<Index> owners;
    for(std::size_t c = first; c < gone.size(); ++c) if(!gone[c]) owners.push_back(buffer_owner[c - first]);
    buffer_owner.swap(owners);
    for(auto& f : faces) f.cell = new_index[f.cell];
    m.boundary_faces.swap(faces);
    rep.buffer_cells -= n;
  }

  // Before the cleanup (which builds the polyhedral mesh and its OpenFOAM geometry): what the
  // optimisation and the repairs used is freed. The cleanup reads the positions, the cells and
  // `buffer_owner` only. (Since then the capture's memory peak is no longer the cleanup's: on the
  // motorBike, 2026-12-06, it comes in the repairs and the last unfolding, their transients on top
  // of the work data, the regions' and curves' trees the largest part; the cleanup is well below.)
  void release_work_data()
  {
    auto drop = [](auto& x) { std::decay_t<decltype(x)>().swap(x); };
    drop(region_trees); drop(region_triangles); drop(curve_trees); drop(curve_segments);
    all_curves_tree.reset(); drop(all_curve_segments); drop(segment_curve); drop(curve_ends); drop(nearest_curve);
    drop(nbrs); drop(snbrs); drop(cnbrs); drop(deps); drop(vertex_top_faces); drop(fnormals);
    drop(hang_masters); drop(hang_of); drop(cstart); drop(cinc); drop(hint); drop(hint_region);
    drop(quality_cache); drop(quality_at); drop(moved_at); for(auto& f : failed_at) drop(f);
    drop(split_faces); drop(face_neighbour); drop(kind); drop(planes); drop(twin); drop(inner);
    drop(inner_of); drop(top_faces); drop(curve_of); drop(hloc); drop(vregion); drop(face_region);
    drop(tri_region); drop(pillow_sector_faces); drop(pillow_twins); drop(turn_vertices); drop(turn_curve);
    hole_tree.reset(); drop(hole_segments); drop(near_hole); drop(sheet_caps);
#if defined(__GLIBC__)
    // freed in many small blocks, which the allocator keeps, while the cleanup's large arrays are
    // mapped anew: without giving the pages back the peak would hold both (motorBike 511 -> 447 MB)
    malloc_trim(0);
#endif
  }

  // after removing cells: vertices no cell uses go, and so do the hanging nodes they were
  void drop_unused_vertices()
  {
    std::vector<Index> to(m.points.size(), NONE);
    for(const auto& h : m.hexahedra) for(Index v : h) to[v] = 0;
    // A face split in four whose centre a cell still uses keeps its four edge midpoints, even one
    // no cell uses any more (the fine cells on that side of it were removed): the coarse cell's
    // face runs through it (the face's quarters there are boundary faces now). Dropping it left a
    // split face without its midpoint, and the writer failed ("a split face lacks an edge
    // midpoint"): anchor with `--surface-size 0.025 --feature-size 0.00625 --box
    // -0.55,-0.3625,-0.48,0.55,0.3604,0.48`, two such midpoints (a test). (Of its masters' six
    // pairs, the face's edges are those with a hanging midpoint: a diagonal has none.)
    {
      std::unordered_map<std::uint64_t, Index> mid;
      for(const auto& h : m.hanging_nodes)
        if(h.number_of_masters == 2) mid[capture_edge_key(h.masters[0], h.masters[1])] = h.vertex;
      for(const auto& h : m.hanging_nodes) {
        if(h.number_of_masters == 2 || to[h.vertex] == NONE) continue;
        for(int i = 0; i < h.number_of_masters; ++i)
          for(int j = i + 1; j < h.number_of_masters; ++j) {
            auto it = mid.find(capture_edge_key(h.masters[i], h.masters[j]));
            if(it != mid.end()) to[it->second] = 0;
          }
      }
    }
    Index n = 0;
    for(std::size_t v = 0; v < to.size(); ++v)
      if(to[v] == 0) { to[v] = n; m.points[n] = m.points[v]; ++n; }
    m.points.resize(n);
    for(auto& h : m.hexahedra) for(Index& v : h) v = to[v];
    for(auto& f : m.boundary_faces) for(Index& v : f.vertices) v = to[v];
    std::vector<typename HexMesh::Hanging_node> hn;
    for(auto h : m.hanging_nodes) {
      if(to[h.vertex] == NONE) continue;
      bool ok = true;
      for(int i = 0; i < h.number_of_masters; ++i) if(to[h.masters[i]] == NONE) ok = false; else h.masters[i] = to[h.masters[i]];
      if(!ok) continue;   // cannot happen: a used hanging vertex lies in a cell having its masters
      h.vertex = to[h.vertex];
      hn.push_back(h);
    }
    m.hanging_nodes.swap(hn);
  }

  void assign_patches()
  {
    if(d.patch_names().size() <= 1) return;
    for(std::size_t f : top_faces) {
      auto& bf = m.boundary_faces[f];
      Vec3 c{{0, 0, 0}}, g{{0, 0, 0}};
      for(int k = 0; k < 4; ++k) c = add(c, mul(P[bf.vertices[k]], 0.25));
      for(Index v : m.hexahedra[bf.cell]) g = add(g, mul(P[v], 0.125));
      // of a sheet, the part of the side facing the face's cell (its centroid: the cell is valid)
      bf.patch = 6 + d.patch_facing(d.closest_triangle(Point_3(c[0], c[1], c[2])), Point_3(g[0], g[1], g[2]));
    }
  }

  typedef typename std::vector<Segment_3>::const_iterator Seg_it;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GT, CGAL::AABB_segment_primitive<GT, Seg_it>>> Segment_tree;
  typedef const Triangle_3* Tri_it;   // the domain's triangles (a region's tree copies none)
  typedef CGAL::AABB_tree<CGAL::AABB_traits<GT, CGAL::AABB_triangle_primitive<GT, Tri_it>>> Tree;

  HexMesh& m;
  const Domain& d;
  const FeatureCurves* fc;
  Options opt;
  Meshing_statistics& rep;   // the buffer_cells count is also where the buffer cells start
  double box_lo[3], box_hi[3];
  std::vector<Vec3> P;
  std::vector<double> split_old;   // improve() in the polish: the cells' face-split qualities before the move
  std::vector<double> q_old;
  std::vector<std::size_t> trial_order;   // improve(): its cells' positions, worst first
  std::vector<double> trial_q;            // and their qualities at a trial point
  // after improve() or relax() moved a vertex: its cells' qualities at the new place (as
  // `cell_quality()` gives them; improve(): at its best trial point), for `record_move()`
  std::vector<double> moved_q;
  // repair_sweeps(): the cells the moves of its last sweep touched (for its `select`)
  std::vector<Index> swept_cells;
  std::vector<std::pair<Index, double>> dep_weights;
  // the wall seconds of a part of a step since the last part or step ended (`capture_substep_seconds`)
  std::chrono::steady_clock::time_point sub_t0;
  void substep(const char* name)
  {
    const auto t = std::chrono::steady_clock::now();
    rep.capture_substep_seconds.emplace_back(name, std::chrono::duration<double>(t - sub_t0).count());
    sub_t0 = t;
  }
  // optimise(): when each vertex last moved (a hanging node: when its master did), and when each
  // last found no move (`failed_at`); a clock of moves (32 bits: these are at the capture's memory
  // peak; `next_stamp()` starts them again before they overflow)
  typedef std::uint32_t Stamp;
  std::vector<Stamp> moved_at;
  // per vertex: when its last step failed in the sweeps (max-min, energy), and in the loop running
  // apart from them (the steps back to the surface in optimise(), then the turn polish)
  std::array<std::vector<Stamp>, 3> failed_at;
  Stamp clock = 1, epoch = 1;
  // optimise(): each cell's quality and when it was computed (valid in the epoch, if no corner
  // moved since)
  std::vector<double> quality_cache;
  std::vector<Stamp> quality_at;
  bool use_quality_cache = false;
  std::vector<Index> near_min;   // improve(): the cells near the minimum
  mutable std::vector<Point_3> hint;     // closest_on_surface_from(): the last point found per vertex
  mutable std::vector<int> hint_region;  // and in which region (-1: none yet)

  // the next time stamp; before the stamps overflow (after 4 billion moves) they all start again:
  // the cached qualities are computed again and the vertices that found no move try again
  Stamp next_stamp()
  {
    if(clock == std::numeric_limits<Stamp>::max() - 1) {
      std::fill(moved_at.begin(), moved_at.end(), Stamp(0));
      for(auto& f : failed_at) std::fill(f.begin(), f.end(), Stamp(0));
      std::fill(quality_at.begin(), quality_at.end(), Stamp(0));
      clock = epoch = 1;
    }
    return ++clock;
  }

  // the quality of cell c at the current positions (the cache in optimise())
  double current_quality(Index c)
  {
    if(!use_quality_cache) return cell_quality(c);
    if(quality_at[c] >= epoch) {
      Stamp t = 0;
      for(Index w : m.hexahedra[c]) t = (std::max)(t, moved_at[w]);
      if(t <= quality_at[c]) return quality_cache[c];
    }
    quality_at[c] = clock;
    return quality_cache[c] = cell_quality(c);
  }

  // the last move of a vertex `improve()` or `relax()` reads at `v`: the corners of its cells and
  // of its hanging nodes' cells, its smoothing neighbours, and the top faces around its twin
  Stamp last_input_move(Index v) const
  {
    Stamp t = moved_at[v];
    auto cells_of = [&](Index u) {
      for(Index k = cstart[u]; k < cstart[u + 1]; ++k)
        for(Index w : m.hexahedra[cinc[k]]) t = (std::max)(t, moved_at[w]);
    };
    cells_of(v);
    for(Index h : deps[v]) cells_of(h);
    for(const auto* L : {&nbrs, &snbrs})
      if(v < L->size()) for(Index w : (*L)[v]) t = (std::max)(t, moved_at[w]);
    if(v < cnbrs.size()) for(Index w : cnbrs[v]) t = (std::max)(t, moved_at[w]);
    if(v < twin.size() && twin[v] != NONE)
      for(std::size_t f : vertex_top_faces[twin[v]])
        for(Index w : m.boundary_faces[top_faces[f]].vertices) t = (std::max)(t, moved_at[w]);
    return t;
  }
  Sparse_lists<Vec3> fnormals;   // unit staircase face normals at each twin
  std::vector<Index> twin, inner, inner_of;
  std::vector<std::size_t> top_faces;
  std::vector<Index> buffer_owner;   // the staircase cell under each buffer cell
  Polygon_list vertex_top_faces;   // top faces (indices into top_faces) at each twin
  std::vector<Kind> kind;
  std::vector<Index> sheet_caps;   // cap vertices at the border of a two-sided sheet
  std::vector<Segment_3> hole_segments;   // open edges of the input bordering holes (`place_twins()`)
  std::unique_ptr<Segment_tree> hole_tree;
  std::vector<char> near_hole;      // surface twins within 2 cells of a hole's border
  std::vector<std::uint8_t> planes;
  std::vector<Index> hang_of;
  std::vector<std::vector<std::pair<Index, double>>> hang_masters;
  std::vector<Index> cstart, cinc;
  Polygon_list deps, nbrs, snbrs;   // per vertex: its dependent hanging nodes, neighbours, surface neighbours
  Sparse_lists<Index> cnbrs;   // per curve vertex: its neighbours on its chain
  std::vector<double> hloc;
  std::vector<Loose> loose;               // `polish_patches()`: the loosened vertices
  std::vector<char> left_feature;         // ... those of them kept off their feature (per vertex; empty if none)
  std::vector<std::uint32_t> loose_of;    // ... each vertex's entry in `loose` (NO_LOOSE: none; empty outside the polish)
  std::vector<std::vector<Segment_3>> curve_segments;
  std::vector<std::unique_ptr<Segment_tree>> curve_trees;
  std::vector<Segment_3> all_curve_segments;           // every curve's segments, curve by curve ...
  std::vector<int> segment_curve;                      // ... the curve of each
  std::unique_ptr<Segment_tree> all_curves_tree;       // ... and their tree (`shortest_path()`)
  std::vector<std::pair<int, int>> curve_ends;         // each curve's end corners (-1: none, closed)
  static constexpr int NOT_YET = -2;
  std::vector<std::pair<int, double>> nearest_curve;   // per vertex, the curve nearest to it and its distance (NOT_YET: not asked)
  std::vector<int> curve_of;
  std::vector<Index> turn_vertices;   // feature-chain vertices where the chain turns inside a face (not snapped)
  std::vector<int> turn_curve;        // ... the curve of each
  std::unordered_set<std::uint64_t> feature_edges;
  double guard_floor = 0;   // (`turn_polish()`'s far passes: `Move_guard`'s floor instead of polish_quality)
  std::map<Index, std::vector<std::size_t>> pillow_sector_faces;   // a pillow's copy of a chain vertex -> the faces of its sector (into top_faces)
  std::map<Index, std::vector<Index>> pillow_twins;   // a pillowed chain vertex -> its copies, one per sector
  std::unordered_map<std::uint64_t, std::vector<Index>> curve_edge_triangles;   // an edge of a followed input curve -> its triangles
  std::vector<std::vector<const Triangle_3*>> region_triangles;   // into the domain's triangles
  std::vector<std::unique_ptr<Tree>> region_trees;
  std::vector<int> face_region, vregion, tri_region;
  bool cancelled = false;
  bool second_polish = false;      // the second polish: the face pyramids weighted, the cells' concavity guarded
  std::vector<char> conc_old;     // (the second polish, `improve()`) the cells concave before the move
  bool foam_checked = false;      // `foam_faults_found` was counted (the first check of the cleanup's rounds)
  bool use_polish = false;        // cell_quality() counts the split faces' warp, improve() guards the rest (the polish)
  bool use_face_splits = false;   // cell_quality() counts the face splits (the repair)
  bool use_folds = false;         // cell_quality() counts the folds of the whole faces (`unfold_faces()`)
  bool use_split_warp = false;    // cell_quality() counts the warp of faces split in four (that repair)
  bool use_concavity = false;     // cell_quality() counts the concavity margin (`repair_concave_cells()`)
  std::vector<char> split_cell;    // (that repair) the cells with a hanging node on a face
  std::vector<double> margin_old;  // (that repair, `improve()`) their margins before the move
  bool use_non_orthogonality = false;   // cell_quality() is the worst face's non-orthogonality (that repair)
  Sparse_lists<std::uint8_t> split_faces;   // per cell: its local faces split in four by a face node
  double sj_floor = 0.2;          // in the repair: nor below min(its scaled Jacobian, this)
  std::vector<double> base_old;   // improve(), in the repair: the scaled Jacobians before the move
  std::vector<std::array<Index, 6>> face_neighbour;   // in the repair: the cell across each whole face

  // the largest angle (degrees) between a face's normal and the line joining the vertex averages
  // of its two cells, over the whole faces of `cells` (OpenFOAM's non-orthogonality, roughly)
  double max_non_orthogonality(const std::vector<Index>& cells) const
  {
    double worst = 0;
    for(Index c : cells) worst = (std::max)(worst, cell_non_orthogonality(c));
    return worst;
  }
  // OpenFOAM's tet decomposition of a whole face (`face_tet_errors()`) needs a diagonal split of
  // it whose corner tetrahedra (`face_corner_quality()`) with the centres of both its cells are
  // positive: the better diagonal's worst corner, in c and in the cell across (`face_neighbour`;
  // a boundary face: in c alone); the worst over c's six faces. (The better diagonal may differ
  // from face to face, unlike the worst corner of all, `hex_face_split_quality()`.)
  // (`centres`, if given: the cells' centres, `foam_hex_centre()`)
  double cell_fold(Index c, const std::vector<Vec3>* centres = nullptr) const
  {
    Vec3 x[8], y[8];
    corners(c, x);
    const Vec3 cc = centres ? (*centres)[c] : foam_hex_centre(x);
    double worst = 1;
    for(int fi = 0; fi < 6; ++fi) {
      const Index d = face_neighbour[c][std::size_t(fi)];
      Vec3 cd = cc;
      if(d != NONE) {
        if(centres) cd = (*centres)[d];
        else { corners(d, y); cd = foam_hex_centre(y); }
      }
      const auto& f = hex_local_faces()[std::size_t(fi)];
      Vec3 q[4];
      for(int i = 0; i < 4; ++i) q[i] = x[f[std::size_t(i)]];
      worst = (std::min)(worst, face_shared_split(q, cc, d == NONE ? nullptr : &cd));
    }
    return worst;
  }
  // the same over one cell's whole faces
  double cell_non_orthogonality(Index c) const
  {
    double worst = 0;
    const Vec3 cc = cell_centre(c);
    for(int fi = 0; fi < 6; ++fi) {
      const Index d = face_neighbour[c][std::size_t(fi)];
      if(d == NONE) continue;
      const auto& f = hex_local_faces()[std::size_t(fi)];
      const auto& H = m.hexahedra[c];
      const Vec3 n = cross(sub(P[H[std::size_t(f[2])]], P[H[std::size_t(f[0])]]), sub(P[H[std::size_t(f[3])]], P[H[std::size_t(f[1])]]));
      const Vec3 e = sub(cell_centre(d), cc);
      const double l = norm(n) * norm(e);
      if(!(l > 0)) continue;
      worst = (std::max)(worst, std::acos((std::max)(-1.0, (std::min)(1.0, dot(n, e) / l))) * 180.0 / CGAL_PI);
    }
    return worst;
  }
};

} // namespace internal
} // namespace Hex_meshing_3
} // namespace CGAL

#endif // CGAL_HEX_MESHING_3_INTERNAL_BOUNDARY_CAPTURE_3_H
