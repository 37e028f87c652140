// Unit and property tests of Hex_meshing_3 (one program: CGAL-heavy translation units are costly).
// Each check prints what it verified; any failure aborts through assert (live in test builds).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hex_mesh_criteria_3.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>
#include <CGAL/Hex_meshing_3/Surface_domain_3.h>
#include <CGAL/Hex_meshing_3/quality.h>
#include <CGAL/Hex_meshing_3/internal/Octree_mesher_3.h>
#include <CGAL/make_hex_mesh_3.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Random.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Hex_meshing_3::Surface_domain_3<K> Domain;
typedef CGAL::Hex_mesh_criteria_3<K> Criteria;
typedef CGAL::Hex_meshing_3::Hex_mesh_3<K> Mesh;
namespace HM = CGAL::Hex_meshing_3;
namespace HP = CGAL::Hex_meshing_3::parameters;

static unsigned g_seed = 0;

// ------------------------------------------------------------------------------------------------
// 1. winding number against Side_of_triangle_mesh on closed surfaces
void test_winding_number(const std::string& file)
{
  Domain domain(file);
  assert(domain.has_exact_inside_test());
  std::vector<Point_3> pts;
  std::vector<std::vector<std::size_t>> polys;
  CGAL::IO::read_polygon_soup(file, pts, polys);
  CGAL::Surface_mesh<Point_3> sm;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, polys, sm);
  CGAL::Side_of_triangle_mesh<CGAL::Surface_mesh<Point_3>, K> side(sm);
  const CGAL::Bbox_3 b = domain.bbox();
  const double diag = std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                                CGAL::square(b.zmax() - b.zmin()));
  CGAL::Random rng(g_seed);
  std::size_t near = 0, agree = 0, n = 10000;
  for(std::size_t i = 0; i < n; ++i) {
    Point_3 p;
    if(i % 2 == 0) {   // near the surface: a random point of a random triangle, moved by < 0.01 diag
      const auto& t = domain.triangle(rng.get_int(0, int(domain.number_of_triangles())));
      double u = rng.get_double(), v = rng.get_double();
      if(u + v > 1) { u = 1 - u; v = 1 - v; }
      const Point_3 q = t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]);
      const double r = 0.0099 * diag;
      p = Point_3(q.x() + rng.get_double(-r, r) / std::sqrt(3.0), q.y() + rng.get_double(-r, r) / std::sqrt(3.0),
                  q.z() + rng.get_double(-r, r) / std::sqrt(3.0));
    } else {
      const double m = 0.1 * diag;
      p = Point_3(rng.get_double(b.xmin() - m, b.xmax() + m), rng.get_double(b.ymin() - m, b.ymax() + m),
                  rng.get_double(b.zmin() - m, b.zmax() + m));
    }
    const CGAL::Bounded_side s = side(p);
    if(s == CGAL::ON_BOUNDARY) continue;   // measure zero
    if(std::sqrt(CGAL::to_double(domain.squared_distance(p))) <= 0.01 * diag) ++near;
    const bool in_exact = (s == CGAL::ON_BOUNDED_SIDE);
    const double w = domain.winding_number(p);
    if((w >= 0.5) == in_exact) ++agree;
    else std::cerr << "  disagreement at " << p << ": w = " << w << ", exact inside = " << in_exact << "\n";
  }
  std::cout << "winding number: " << file << ": " << agree << " / " << n << " agree with Side_of_triangle_mesh, "
            << near << " within 0.01 diag of the surface\n";
  assert(near >= 5000);
  assert(agree == n);
}

// ------------------------------------------------------------------------------------------------
// 2. properties of a mesh, checked on the output only (independent of the mesher's internals)
struct Lattice
{
  double lo[3], h[3];
  std::array<long, 3> key(const Point_3& p) const
  {
    return {{std::lround((p.x() - lo[0]) / h[0]), std::lround((p.y() - lo[1]) / h[1]), std::lround((p.z() - lo[2]) / h[2])}};
  }
};

void check_mesh(const Mesh& m, const std::string& what)
{
  assert(m.number_of_cells() > 0);
  assert(m.cell_levels.size() == m.number_of_cells());
  // finest lattice: the smallest cell edge per axis
  Lattice L;
  for(int a = 0; a < 3; ++a) { L.lo[a] = m.box.min(a); L.h[a] = 1e300; }
  for(const auto& c : m.hexahedra) {
    L.h[0] = (std::min)(L.h[0], m.points[c[1]].x() - m.points[c[0]].x());
    L.h[1] = (std::min)(L.h[1], m.points[c[3]].y() - m.points[c[0]].y());
    L.h[2] = (std::min)(L.h[2], m.points[c[4]].z() - m.points[c[0]].z());
  }
  std::map<std::array<long, 3>, std::uint32_t> vertex_at;
  for(std::uint32_t v = 0; v < m.points.size(); ++v) {
    const auto k = L.key(m.points[v]);
    assert(vertex_at.count(k) == 0);   // no duplicate vertices
    vertex_at[k] = v;
  }
  std::map<std::uint32_t, std::vector<std::uint32_t>> hanging;
  for(const auto& h : m.hanging_nodes) {
    assert(hanging.count(h.vertex) == 0);
    std::vector<std::uint32_t> ms(h.masters.begin(), h.masters.begin() + h.number_of_masters);
    std::sort(ms.begin(), ms.end());
    hanging[h.vertex] = ms;
    // position = average of the masters
    double x = 0, y = 0, z = 0;
    for(auto v : ms) { x += m.points[v].x(); y += m.points[v].y(); z += m.points[v].z(); }
    const double n = double(ms.size());
    assert(std::abs(x / n - m.points[h.vertex].x()) < 1e-9 * L.h[0]);
    assert(std::abs(y / n - m.points[h.vertex].y()) < 1e-9 * L.h[1]);
    assert(std::abs(z / n - m.points[h.vertex].z()) < 1e-9 * L.h[2]);
  }
  std::size_t checked_hanging = 0;
  for(const auto& c : m.hexahedra) {
    const auto k0 = L.key(m.points[c[0]]), k6 = L.key(m.points[c[6]]);
    const long e = k6[0] - k0[0];
    assert(e > 0 && e == k6[1] - k0[1] && e == k6[2] - k0[2]);   // isotropic cell
    // 2:1 balance across faces and edges: no vertex at a quarter position of the cell's boundary
    if(e % 4 == 0) {
      for(long i = 0; i <= 4; ++i)
        for(long j = 0; j <= 4; ++j)
          for(long k = 0; k <= 4; ++k) {
            const bool on_boundary = (i == 0 || i == 4 || j == 0 || j == 4 || k == 0 || k == 4);
            const int odd = (i % 2) + (j % 2) + (k % 2);
            if(!on_boundary || odd == 0) continue;
            const int on_faces = (i == 0 || i == 4) + (j == 0 || j == 4) + (k == 0 || k == 4);
            // quarter points on an edge (2 boundary coordinates) or on a face (1) are forbidden
            if(on_faces >= 1 && vertex_at.count({{k0[0] + i * e / 4, k0[1] + j * e / 4, k0[2] + k * e / 4}})) {
              std::cerr << what << ": 2:1 balance violated near " << m.points[c[0]] << "\n";
              assert(false);
            }
          }
    }
    // every vertex at an edge midpoint or face centre is a recorded hanging node with those masters
    if(e % 2 == 0) {
      for(const auto& ed : HM::hex_local_edges()) {
        const auto ka = L.key(m.points[c[ed[0]]]), kb = L.key(m.points[c[ed[1]]]);
        auto it = vertex_at.find({{(ka[0] + kb[0]) / 2, (ka[1] + kb[1]) / 2, (ka[2] + kb[2]) / 2}});
        if(it == vertex_at.end()) continue;
        auto h = hanging.find(it->second);
        assert(h != hanging.end());
        std::vector<std::uint32_t> ms = {c[ed[0]], c[ed[1]]};
        std::sort(ms.begin(), ms.end());
        assert(h->second == ms);
        ++checked_hanging;
      }
      for(const auto& f : HM::hex_local_faces()) {
        const auto ka = L.key(m.points[c[f[0]]]), kb = L.key(m.points[c[f[2]]]);
        auto it = vertex_at.find({{(ka[0] + kb[0]) / 2, (ka[1] + kb[1]) / 2, (ka[2] + kb[2]) / 2}});
        if(it == vertex_at.end()) continue;
        auto h = hanging.find(it->second);
        assert(h != hanging.end());
        std::vector<std::uint32_t> ms = {c[f[0]], c[f[1]], c[f[2]], c[f[3]]};
        std::sort(ms.begin(), ms.end());
        assert(h->second == ms);
        ++checked_hanging;
      }
    }
  }
  // polyhedral form: closed cells (sum of outward area vectors = 0), positive volumes summing to
  // the hexahedra's, all cells valid
  HM::Polyhedral_mesh_3 pm;
  pm.build(m);
  HM::OpenFOAM_geometry g;
  g.compute(m.points, pm);
  std::vector<std::array<double, 3>> closure(m.number_of_cells(), {{0, 0, 0}});
  for(std::size_t f = 0; f < pm.faces.size(); ++f) {
    assert(pm.faces[f].size() >= 4 && pm.faces[f].size() <= 8);
    for(int a = 0; a < 3; ++a) {
      closure[pm.owner[f]][a] += g.face_areas[f][a];
      if(f < pm.neighbour.size()) closure[pm.neighbour[f]][a] -= g.face_areas[f][a];
    }
    if(f < pm.neighbour.size()) assert(pm.owner[f] < pm.neighbour[f]);
    if(f > 0 && f < pm.neighbour.size())
      assert(pm.owner[f - 1] < pm.owner[f] || (pm.owner[f - 1] == pm.owner[f] && pm.neighbour[f - 1] < pm.neighbour[f]));
  }
  double vol_poly = 0, vol_hex = 0;
  for(std::size_t c = 0; c < m.number_of_cells(); ++c) {
    const double hx = m.points[m.hexahedra[c][1]].x() - m.points[m.hexahedra[c][0]].x();
    const double hy = m.points[m.hexahedra[c][3]].y() - m.points[m.hexahedra[c][0]].y();
    const double hz = m.points[m.hexahedra[c][4]].z() - m.points[m.hexahedra[c][0]].z();
    for(int a = 0; a < 3; ++a) assert(std::abs(closure[c][a]) < 1e-9 * hx * hy);
    assert(g.cell_volumes[c] > 0);
    assert(std::abs(g.cell_volumes[c] - hx * hy * hz) < 1e-9 * hx * hy * hz);
    vol_poly += g.cell_volumes[c]; vol_hex += hx * hy * hz;
  }
  const HM::Mesh_quality q = HM::compute_quality(m, pm);
  assert(q.number_of_inverted_cells() == 0);
  std::size_t nb = 0;
  for(const auto& p : pm.patches) nb += p.size;
  assert(pm.neighbour.size() + nb == pm.faces.size());
  std::cout << "mesh " << what << ": " << m.number_of_cells() << " cells, " << m.hanging_nodes.size()
            << " hanging nodes (" << checked_hanging << " edge/face checks), balanced, closed polyhedra, volume "
            << vol_poly << ", min SJ " << HM::Mesh_quality::range(q.scaled_jacobian).min << "\n";
}

// ------------------------------------------------------------------------------------------------
struct Counting_visitor
{
  std::vector<std::string> phases;
  int polls = 0, stop_after = -1;
  void on_phase_begin(const char* n, std::size_t) { phases.push_back(n); }
  void on_phase_end(const char*) {}
  bool go_further(double) { ++polls; return stop_after < 0 || polls <= stop_after; }
};

template <typename F>
void expect_input_error(F&& f, const std::string& needle)
{
  try {
    f();
  } catch(const HM::Input_error& e) {
    const std::string w = e.what();
    std::cout << "  error as expected: " << w << "\n";
    assert(w.find(needle) != std::string::npos);
    return;
  }
  std::cerr << "no Input_error (expected one containing '" << needle << "')\n";
  assert(false);
}

void test_meshing()
{
  // inside of the figure-eight, with a refinement box
  Domain eight("data/eight.off");
  Criteria criteria(0.1, 0.025);
  criteria.add_refinement_box(CGAL::Bbox_3(-0.3, -0.2, 0.0, 0.3, 0.2, 0.6), 0.0125);
  Mesh m1;
  Counting_visitor v;
  HM::Status s = CGAL::make_hex_mesh_3(eight, criteria, m1, HP::max_cells(10000000).visitor(std::ref(v)));
  assert(s == HM::Status::SUCCESS);
  assert((v.phases == std::vector<std::string>{"refine", "balance", "classify", "extract"}));
  check_mesh(m1, "eight inside");
  // the mesh lies inside: every cell centre has winding number >= 0.5 and no cell meets the surface
  for(const auto& c : m1.hexahedra) {
    std::array<Point_3, 8> p;
    for(int k = 0; k < 8; ++k) p[k] = m1.points[c[k]];
    assert(eight.is_inside(CGAL::midpoint(p[0], p[6])));
    for(std::size_t t = 0; t < eight.number_of_triangles(); ++t) assert(!eight.do_intersect(p, t));
  }
  // its volume approaches the solid's from below
  double vol = 0;
  for(const auto& c : m1.hexahedra)
    vol += (m1.points[c[6]].x() - m1.points[c[0]].x()) * (m1.points[c[6]].y() - m1.points[c[0]].y()) *
           (m1.points[c[6]].z() - m1.points[c[0]].z());
  std::cout << "eight: hex volume " << vol << " vs solid 0.0401729\n";
  assert(vol < 0.0401729 && vol > 0.5 * 0.0401729);

  // determinism: same input and options, same mesh
  Mesh m2;
  CGAL::make_hex_mesh_3(eight, criteria, m2);
  assert(m1.points == m2.points && m1.hexahedra == m2.hexahedra && m1.boundary_faces.size() == m2.boundary_faces.size());

  // cancellation: stop at the first poll after the start; the mesh is valid and coarser
  Mesh m3;
  Counting_visitor stopper;
  stopper.stop_after = 1;
  s = CGAL::make_hex_mesh_3(eight, criteria, m3, CGAL::parameters::visitor(std::ref(stopper)));
  assert(s == HM::Status::CANCELED);
  check_mesh(m3, "eight cancelled");
  assert(m3.number_of_cells() < m1.number_of_cells());

  // cell limit
  Mesh m4;
  s = CGAL::make_hex_mesh_3(eight, criteria, m4, HP::max_cells(3000));
  assert(s == HM::Status::CELL_LIMIT_REACHED);
  check_mesh(m4, "eight cell limit");

  // sizes as fields: finer cells (and surface cells) for z > 0; max level caps the refinement
  {
    Criteria fc([](const Point_3& p) { return p.z() > 0 ? 0.05 : 0.1; }, 0.1,
                [](const Point_3& p) { return p.z() > 0 ? 0.0125 : 0.025; });
    Mesh mf;
    CGAL::make_hex_mesh_3(eight, fc, mf);
    check_mesh(mf, "eight with size fields");
    std::size_t fine_top = 0, fine_bottom = 0;
    int top_level = 0;
    for(std::size_t c = 0; c < mf.number_of_cells(); ++c) {
      const double z = CGAL::midpoint(mf.points[mf.hexahedra[c][0]], mf.points[mf.hexahedra[c][6]]).z();
      top_level = (std::max)(top_level, int(mf.cell_levels[c][0]));
      if(mf.cell_levels[c][0] == 3) (z > 0 ? fine_top : fine_bottom)++;
    }
    std::cout << "size fields: " << fine_top << " level-3 cells above z = 0, " << fine_bottom << " below\n";
    assert(top_level == 3 && fine_top > 4 * fine_bottom);
    fc.set_max_level(1);
    Mesh ml;
    CGAL::make_hex_mesh_3(eight, fc, ml);
    for(const auto& l : ml.cell_levels) assert(l[0] <= 1);
    check_mesh(ml, "eight max level 1");
  }

  // the air around the figure-eight in a box, from a seed; box faces are patches 0..5
  const CGAL::Bbox_3 box(-1, -1, -1, 1.5, 1, 1);
  Criteria c2(0.25, 0.05);
  Mesh m5;
  s = CGAL::make_hex_mesh_3(eight, c2, m5, HP::meshing_box(box).region_seed(Point_3(-0.9, -0.9, -0.9)));
  assert(s == HM::Status::SUCCESS);
  check_mesh(m5, "air around eight");
  std::array<std::size_t, 7> per_patch = {{0, 0, 0, 0, 0, 0, 0}};
  for(const auto& f : m5.boundary_faces) ++per_patch[std::size_t(f.patch)];
  // 2.5 x 2 faces of 0.25: 10 x 8 = 80 on x faces ...
  assert(per_patch[0] == 64 && per_patch[1] == 64 && per_patch[2] == 80 && per_patch[3] == 80);
  assert(per_patch[4] == 80 && per_patch[5] == 80 && per_patch[6] > 0);
  assert(m5.patch_names[6] == "eight");
  for(const auto& p : m5.points)   // the box is honoured exactly
    assert(p.x() >= -1 && p.x() <= 1.5 && p.y() >= -1 && p.y() <= 1 && p.z() >= -1 && p.z() <= 1);
  // cells of the air and of the inside do not overlap: no air cell centre is inside
  for(const auto& c : m5.hexahedra) assert(!eight.is_inside(CGAL::midpoint(m5.points[c[0]], m5.points[c[6]])));

  // bad seeds and boxes
  expect_input_error([&] { Mesh m; CGAL::make_hex_mesh_3(eight, c2, m, HP::meshing_box(box).region_seed(Point_3(5, 0, 0))); },
                     "outside the meshing box");
  const Point_3 in_body = CGAL::midpoint(m1.points[m1.hexahedra[0][0]], m1.points[m1.hexahedra[0][6]]);
  expect_input_error([&] { Mesh m; CGAL::make_hex_mesh_3(eight, c2, m, HP::meshing_box(box).region_seed(in_body)); },
                     "inside a body");
  expect_input_error([&] { Mesh m; Criteria bad(-1, 0); CGAL::make_hex_mesh_3(eight, bad, m); }, "positive");

  // exact hex-grid case: the cube [-1,1]^3 with a grid aligned to its faces; the cells touching
  // the faces are cut (closed hulls), the rest is exactly [-0.75,0.75]^3 at size 0.25
  Domain cube("data/cube.off");
  Criteria c3(0.25, 0.25);
  Mesh m6;
  CGAL::make_hex_mesh_3(cube, c3, m6, HP::meshing_box(CGAL::Bbox_3(-1.5, -1.5, -1.5, 1.5, 1.5, 1.5)));
  check_mesh(m6, "cube aligned");
  assert(m6.number_of_cells() == 6 * 6 * 6);
  assert(m6.hanging_nodes.empty());
}

// ------------------------------------------------------------------------------------------------
void test_readers_and_errors()
{
  // the same cube through every reader gives the same mesh
  std::vector<Point_3> pts;
  std::vector<std::vector<std::size_t>> polys;
  CGAL::IO::read_polygon_soup("data/cube.off", pts, polys);
  std::size_t reference = 0;
  for(const std::string ext : {"off", "obj", "stl", "ply"}) {
    const std::string f = "tmp_cube." + ext;
    bool ok = CGAL::IO::write_polygon_soup(f, pts, polys, CGAL::parameters::stream_precision(17));
    assert(ok);
    Domain d(f);
    assert(d.number_of_triangles() == 12);
    assert(d.has_exact_inside_test());
    Mesh m;
    CGAL::make_hex_mesh_3(d, Criteria(0.3, 0.15), m);
    if(reference == 0) reference = m.number_of_cells();
    assert(m.number_of_cells() == reference);
    std::cout << "reader ." << ext << ": " << m.number_of_cells() << " cells\n";
    std::remove(f.c_str());
  }
  // open surface (a cube without its top): winding-number inside test, still a mesh
  {
    std::vector<Point_3> p = pts;
    std::vector<std::array<std::uint32_t, 3>> t;
    for(const auto& q : polys) {
      const double zc = (pts[q[0]].z() + pts[q[1]].z() + pts[q[2]].z()) / 3;
      if(zc > 0.99) continue;
      t.push_back({{std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])}});
    }
    Domain open(p, t);
    assert(!open.has_exact_inside_test());
    const double w = open.winding_number(Point_3(0, 0, 0));
    std::cout << "open cube: winding number at the centre " << w << "\n";
    assert(w > 0.5 && w < 1.0);
    Mesh m;
    CGAL::make_hex_mesh_3(open, Criteria(0.3, 0.15), m);
    check_mesh(m, "open cube");
  }
  // duplicated points and degenerate triangles are merged / removed
  {
    std::vector<Point_3> p = {Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(0, 1, 0), Point_3(1, 0, 0), Point_3(2, 0, 0)};
    std::vector<std::array<std::uint32_t, 3>> t = {{{0, 1, 2}}, {{0, 3, 4}}};
    Domain d(p, t);
    assert(d.input_summary().merged_points == 1);
    assert(d.input_summary().degenerate_triangles == 1);
    assert(d.number_of_triangles() == 1);
  }
  // a huge triangle crossing the box is seen (no integer overflow when locating it), and a bad
  // part index is an error
  {
    std::vector<Point_3> p = {Point_3(-1e25, -1e25, 0.1), Point_3(1e25, -1e25, 0.1), Point_3(0, 1e25, 0.1)};
    std::vector<std::array<std::uint32_t, 3>> t = {{{0, 1, 2}}};
    Domain d(p, t);
    Mesh m;
    CGAL::make_hex_mesh_3(d, Criteria(0.5, 0.25), m,
                          HP::meshing_box(CGAL::Bbox_3(-1, -1, -1, 1, 1, 1)).region_seed(Point_3(0.3, 0.3, 0.7)));
    for(const auto& c : m.hexahedra) assert(m.points[c[0]].z() >= 0.1);   // the plane bounds the region
    assert(m.has_hanging_nodes());
    check_mesh(m, "huge plane");
    expect_input_error([&] { Domain bad(p, t, std::vector<int>{3}, std::vector<std::string>{"a", "b"}); }, "part index");
    expect_input_error([&] { Domain bad(p, t, std::vector<int>{-1}, std::vector<std::string>{"a"}); }, "part index");
  }
  // unreadable, empty, garbage, NaN files: typed errors naming the file
  {
    std::ofstream("tmp_empty.off").close();
    std::ofstream("tmp_garbage.off") << "this is not an OFF file\n";
    std::ofstream("tmp_nan.off") << "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n";
    std::ofstream("tmp_noface.off") << "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n";
    std::ofstream("tmp_badindex.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
    expect_input_error([] { Domain d("data/does_not_exist.off"); }, "does_not_exist.off: cannot open");
    expect_input_error([] { Domain d("tmp_empty.off"); }, "tmp_empty.off: the file is empty");
    expect_input_error([] { Domain d("tmp_garbage.off"); }, "tmp_garbage.off");
    expect_input_error([] { Domain d("tmp_nan.off"); }, "tmp_nan.off");
    expect_input_error([] { Domain d("tmp_noface.off"); }, "tmp_noface.off");
    expect_input_error([] { Domain d("tmp_badindex.off"); }, "tmp_badindex.off");
    expect_input_error([] { Domain d("data/cube.xyz"); }, "unknown surface format");
    for(const char* f : {"tmp_empty.off", "tmp_garbage.off", "tmp_nan.off", "tmp_noface.off", "tmp_badindex.off"}) std::remove(f);
  }
}

// ------------------------------------------------------------------------------------------------
void test_exact_cell_test()
{
  // a sheared (non axis-aligned) cell: the convex hull, not the bounding box, decides
  std::vector<Point_3> p = {Point_3(0.9, 0.9, 0.5), Point_3(2, 0.9, 0.5), Point_3(0.9, 2, 0.5)};
  std::vector<std::array<std::uint32_t, 3>> t = {{{0, 1, 2}}};
  Domain d(p, t);
  std::array<Point_3, 8> cell;
  const int off[8][3] = {{0,0,0},{1,0,0},{1,1,0},{0,1,0},{0,0,1},{1,0,1},{1,1,1},{0,1,1}};
  for(int k = 0; k < 8; ++k) cell[k] = Point_3(off[k][0] - 0.5 * off[k][2], off[k][1] - 0.5 * off[k][2], off[k][2]);
  // at z = 0.5 the hull spans [-0.25,0.75]^2 + ... : the triangle's corner (0.9,0.9) is outside it,
  // while the cell's bounding box [-0.5,1]^2 x [0,1] contains it
  assert(!HM::Surface_domain_3<K>::is_axis_aligned_box(cell));
  assert(!d.do_intersect(cell, 0));
  for(int k = 0; k < 8; ++k) cell[k] = Point_3(off[k][0] + 0.5 * off[k][2], off[k][1] + 0.5 * off[k][2], off[k][2]);
  assert(d.do_intersect(cell, 0));
  // touching counts: a box whose face contains a triangle corner exactly
  std::array<Point_3, 8> box;
  for(int k = 0; k < 8; ++k) box[k] = Point_3(off[k][0] - 0.1, off[k][1] - 0.1, off[k][2] * 0.5);
  assert(HM::Surface_domain_3<K>::is_axis_aligned_box(box));
  assert(d.do_intersect(box, 0));   // (0.9, 0.9, 0.5) is a corner of the box and of the triangle
  std::cout << "exact cell/triangle tests: sheared hull and touching box OK\n";
}

int main(int argc, char** argv)
{
  std::cout << std::unitbuf;   // keep the log in order with assertion messages
  g_seed = argc > 1 ? unsigned(std::atoi(argv[1])) : 20261122u;
  std::cout << "random seed " << g_seed << "\n";
  test_exact_cell_test();
  for(const char* f : {"data/cube.off", "data/eight.off", "data/anchor.off", "data/bunny.off", "data/elephant.off",
                       "data/fandisk.off", "data/t20_part.off"})
    test_winding_number(f);
  test_meshing();
  test_readers_and_errors();
  std::cout << "all checks passed\n";
  return EXIT_SUCCESS;
}
