// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_INTERNAL_FAST_WINDING_NUMBER_3_H
#define CGAL_HEX_MESHING_3_INTERNAL_FAST_WINDING_NUMBER_3_H

// Hierarchical generalised winding number of a triangle soup (Jacobson et al. 2013; far field by
// the dipole expansion of Barill et al. 2018). A bounding-volume hierarchy over the triangles
// stores per node its area-weighted centroid c, its area vector N = sum of (1/2)(b-a)x(c-a), and
// the radius r of its bounding box around c. Seen from p with |p - c| > beta r a node contributes
// (c-p).N / (4 pi |c-p|^3) (plus the second-order term); nearer nodes are opened, and leaves sum
// the exact solid angles of their triangles (van Oosterom & Strackee):
//     tan(Omega/2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|).
// The result is 1 inside and 0 outside a closed, outward-oriented surface, and a smooth estimate
// in between for open or inconsistent soups. All of it is floating point (the documented exception
// to exact predicates); closed input uses Side_of_triangle_mesh instead.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {
namespace internal {

class Fast_winding_number_3
{
public:
  typedef std::array<double, 3> V3;

  Fast_winding_number_3() {}

  /// `points`: 3 doubles per point; `triangles`: 3 indices into the points per triangle (the
  /// points shared by triangles are stored once: 9 doubles per triangle took 14 MB on motorBike)
  void build(std::vector<double> points, std::vector<std::uint32_t> triangles, double beta = 2.0)
  {
    m_beta2 = beta * beta;
    const std::size_t n = triangles.size() / 3;
    m_points = std::move(points);
    m_triangles = std::move(triangles);
    m_nodes.clear();
    m_order.resize(n);
    std::iota(m_order.begin(), m_order.end(), std::uint32_t(0));
    if(n == 0) return;
    m_centroids.resize(n);
    for(std::size_t t = 0; t < n; ++t) {
      double x[9];
      corners(t, x);
      for(int d = 0; d < 3; ++d) m_centroids[t][d] = (x[d] + x[3+d] + x[6+d]) / 3.0;
    }
    m_nodes.reserve(2 * n / kLeaf + 2);
    build_node(0, std::uint32_t(n));
    m_nodes.shrink_to_fit();   // the reserve is a guess: the nodes outgrow it, and a doubling wastes up to half
    // store the triangles in BVH order for locality
    std::vector<std::uint32_t> ordered(m_triangles.size());
    for(std::size_t i = 0; i < n; ++i)
      std::copy(m_triangles.begin() + 3 * m_order[i], m_triangles.begin() + 3 * m_order[i] + 3, ordered.begin() + 3 * i);
    m_triangles.swap(ordered);
    m_centroids.clear(); m_centroids.shrink_to_fit();
    m_order.clear(); m_order.shrink_to_fit();
  }

  double operator()(const V3& p) const
  {
    if(m_nodes.empty()) return 0.0;
    double sum = 0.0;
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while(top > 0) {
      const Node& nd = m_nodes[stack[--top]];
      const double dx = nd.c[0] - p[0], dy = nd.c[1] - p[1], dz = nd.c[2] - p[2];
      const double d2 = dx*dx + dy*dy + dz*dz;
      if(d2 > m_beta2 * nd.r2) {
        // dipole + second-order term of the far-field expansion
        const double inv = 1.0 / std::sqrt(d2);
        const double inv3 = inv * inv * inv;
        double w = (dx * nd.N[0] + dy * nd.N[1] + dz * nd.N[2]) * inv3;
        // second order: grad of (r.N/|r|^3) contracted with the area-weighted tensor
        // T_ij = sum_t A_t (x_t - c)_i n_t,j ; term = sum_ij T_ij (delta_ij/|r|^3 - 3 r_i r_j/|r|^5)
        const double r[3] = {dx, dy, dz};
        double tr = nd.T[0] + nd.T[4] + nd.T[8];
        double rtr = 0.0;
        for(int i = 0; i < 3; ++i)
          for(int j = 0; j < 3; ++j) rtr += r[i] * nd.T[3*i+j] * r[j];
        w += tr * inv3 - 3.0 * rtr * inv3 * inv * inv;
        sum += w;
        continue;
      }
      if(nd.leaf) {
        for(std::uint32_t t = nd.begin; t < nd.end; ++t) {
          double x[9];
          corners(t, x);
          sum += solid_angle(p, x);
        }
      } else {
        stack[top++] = nd.left;
        stack[top++] = nd.right;
      }
    }
    return sum / (4.0 * M_PI);
  }

  static double solid_angle(const V3& p, const double* t)
  {
    const double a[3] = {t[0]-p[0], t[1]-p[1], t[2]-p[2]};
    const double b[3] = {t[3]-p[0], t[4]-p[1], t[5]-p[2]};
    const double c[3] = {t[6]-p[0], t[7]-p[1], t[8]-p[2]};
    const double la = std::sqrt(a[0]*a[0]+a[1]*a[1]+a[2]*a[2]);
    const double lb = std::sqrt(b[0]*b[0]+b[1]*b[1]+b[2]*b[2]);
    const double lc = std::sqrt(c[0]*c[0]+c[1]*c[1]+c[2]*c[2]);
    const double det = a[0]*(b[1]*c[2]-b[2]*c[1]) - a[1]*(b[0]*c[2]-b[2]*c[0]) + a[2]*(b[0]*c[1]-b[1]*c[0]);
    const double ab = a[0]*b[0]+a[1]*b[1]+a[2]*b[2];
    const double bc = b[0]*c[0]+b[1]*c[1]+b[2]*c[2];
    const double ca = c[0]*a[0]+c[1]*a[1]+c[2]*a[2];
    const double den = la*lb*lc + ab*lc + bc*la + ca*lb;
    return 2.0 * std::atan2(det, den);
  }

private:
  static constexpr std::uint32_t kLeaf = 8;
  struct Node
  {
    double c[3];      // area-weighted centroid
    double N[3];      // area vector
    double T[9];      // sum A (x - c) n^T
    double r2;        // squared radius of the bbox around c
    std::uint32_t begin, end, left, right;
    bool leaf;
  };

  std::uint32_t build_node(std::uint32_t begin, std::uint32_t end)
  {
    const std::uint32_t id = std::uint32_t(m_nodes.size());
    m_nodes.push_back(Node());
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double area = 0, c[3] = {0, 0, 0}, N[3] = {0, 0, 0};
    for(std::uint32_t i = begin; i < end; ++i) {
      double t[9];
      corners(m_order[i], t);
      for(int v = 0; v < 3; ++v)
        for(int d = 0; d < 3; ++d) { lo[d] = std::min(lo[d], t[3*v+d]); hi[d] = std::max(hi[d], t[3*v+d]); }
      double n[3]; area_vector(t, n);
      const double A = std::sqrt(n[0]*n[0]+n[1]*n[1]+n[2]*n[2]);
      area += A;
      for(int d = 0; d < 3; ++d) { c[d] += A * m_centroids[m_order[i]][d]; N[d] += n[d]; }
    }
    if(area > 0) for(int d = 0; d < 3; ++d) c[d] /= area;
    else for(int d = 0; d < 3; ++d) c[d] = 0.5 * (lo[d] + hi[d]);
    double T[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    for(std::uint32_t i = begin; i < end; ++i) {
      double t[9];
      corners(m_order[i], t);
      double n[3]; area_vector(t, n);
      for(int a = 0; a < 3; ++a)
        for(int b = 0; b < 3; ++b) T[3*a+b] += (m_centroids[m_order[i]][a] - c[a]) * n[b];
    }
    double r2 = 0;
    for(int d = 0; d < 3; ++d) { const double e = std::max(hi[d] - c[d], c[d] - lo[d]); r2 += e * e; }
    Node& nd = m_nodes[id];
    std::copy(c, c + 3, nd.c); std::copy(N, N + 3, nd.N); std::copy(T, T + 9, nd.T);
    nd.r2 = r2; nd.begin = begin; nd.end = end; nd.leaf = (end - begin <= kLeaf);
    if(!nd.leaf) {
      int axis = 0;
      for(int d = 1; d < 3; ++d) if(hi[d] - lo[d] > hi[axis] - lo[axis]) axis = d;
      const std::uint32_t mid = begin + (end - begin) / 2;
      std::nth_element(m_order.begin() + begin, m_order.begin() + mid, m_order.begin() + end,
                       [&](std::uint32_t x, std::uint32_t y) {
                         if(m_centroids[x][axis] != m_centroids[y][axis])
                           return m_centroids[x][axis] < m_centroids[y][axis];
                         return x < y; });
      const std::uint32_t l = build_node(begin, mid);
      const std::uint32_t r = build_node(mid, end);
      m_nodes[id].left = l; m_nodes[id].right = r;
    }
    return id;
  }

  static void area_vector(const double* t, double* n)
  {
    const double u[3] = {t[3]-t[0], t[4]-t[1], t[5]-t[2]};
    const double v[3] = {t[6]-t[0], t[7]-t[1], t[8]-t[2]};
    n[0] = 0.5 * (u[1]*v[2] - u[2]*v[1]);
    n[1] = 0.5 * (u[2]*v[0] - u[0]*v[2]);
    n[2] = 0.5 * (u[0]*v[1] - u[1]*v[0]);
  }

  // the 9 coordinates of triangle `t` (of the order the triangles are stored in)
  void corners(std::size_t t, double* x) const
  {
    for(int v = 0; v < 3; ++v)
      for(int d = 0; d < 3; ++d) x[3 * v + d] = m_points[3 * std::size_t(m_triangles[3 * t + std::size_t(v)]) + std::size_t(d)];
  }

  std::vector<double> m_points;
  std::vector<std::uint32_t> m_triangles;
  std::vector<V3> m_centroids;
  std::vector<std::uint32_t> m_order;
  std::vector<Node> m_nodes;
  double m_beta2 = 4.0;
};

} // namespace internal
} // namespace Hex_meshing_3
} // namespace CGAL

#endif
