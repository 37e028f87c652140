// Unit and property tests of Hex_meshing_3 (one program: CGAL-heavy translation units are costly).
// Each check prints what it verified; any failure aborts through assert (live in test builds).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hex_mesh_criteria_3.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>
#include <CGAL/Hex_meshing_3/Surface_domain_3.h>
#include <CGAL/Hex_meshing_3/IO/read_surface.h>
#include <CGAL/Hex_meshing_3/IO/write_OpenFOAM.h>
#include <CGAL/Hex_meshing_3/Feature_curves_3.h>
#include <CGAL/Hex_meshing_3/fidelity.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Hex_meshing_3/quality.h>
#include <CGAL/Hex_meshing_3/internal/Octree_mesher_3.h>
#include <CGAL/Hex_meshing_3/internal/hole_fill.h>
#include <CGAL/Hex_meshing_3/internal/sealed_border_edges.h>
#include <CGAL/make_hex_mesh_3.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Random.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <boost/iostreams/device/back_inserter.hpp>
#include <boost/iostreams/filter/gzip.hpp>
#include <boost/iostreams/filtering_stream.hpp>

#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
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
void expect_input_error(F&& f, const std::string& needle, std::optional<HM::Input_error_cause> cause = std::nullopt)
{
  try {
    f();
  } catch(const HM::Input_error& e) {
    const std::string w = e.what();
    std::cout << "  error as expected (" << HM::cause_name(e.cause()) << "): " << w << "\n";
    assert(w.find(needle) != std::string::npos);
    assert(!cause || e.cause() == *cause);
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
  HM::Status s = CGAL::make_hex_mesh_3(eight, criteria, m1, HP::body_fitted(false).max_cells(10000000).visitor(std::ref(v)));
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
  CGAL::make_hex_mesh_3(eight, criteria, m2, HP::body_fitted(false));
  assert(m1.points == m2.points && m1.hexahedra == m2.hexahedra && m1.boundary_faces.size() == m2.boundary_faces.size());

  // cancellation: stop at the first poll after the start; the mesh is valid and coarser
  Mesh m3;
  Counting_visitor stopper;
  stopper.stop_after = 1;
  s = CGAL::make_hex_mesh_3(eight, criteria, m3, HP::body_fitted(false).visitor(std::ref(stopper)));
  assert(s == HM::Status::CANCELED);
  check_mesh(m3, "eight cancelled");
  assert(m3.number_of_cells() < m1.number_of_cells());

  // cell limit
  Mesh m4;
  s = CGAL::make_hex_mesh_3(eight, criteria, m4, HP::body_fitted(false).max_cells(3000));
  assert(s == HM::Status::CELL_LIMIT_REACHED);
  check_mesh(m4, "eight cell limit");

  // sizes as fields: finer cells (and surface cells) for z > 0; max level caps the refinement
  {
    Criteria fc([](const Point_3& p) { return p.z() > 0 ? 0.05 : 0.1; }, 0.1,
                [](const Point_3& p) { return p.z() > 0 ? 0.0125 : 0.025; });
    Mesh mf;
    CGAL::make_hex_mesh_3(eight, fc, mf, HP::body_fitted(false));
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
    CGAL::make_hex_mesh_3(eight, fc, ml, HP::body_fitted(false));
    for(const auto& l : ml.cell_levels) assert(l[0] <= 1);
    check_mesh(ml, "eight max level 1");
  }

  // the air around the figure-eight in a box, from a seed; box faces are patches 0..5
  const CGAL::Bbox_3 box(-1, -1, -1, 1.5, 1, 1);
  Criteria c2(0.25, 0.05);
  Mesh m5;
  s = CGAL::make_hex_mesh_3(eight, c2, m5, HP::body_fitted(false).meshing_box(box).region_seed(Point_3(-0.9, -0.9, -0.9)));
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
  expect_input_error([&] { Mesh m; CGAL::make_hex_mesh_3(eight, c2, m, HP::body_fitted(false).meshing_box(box).region_seed(Point_3(5, 0, 0))); },
                     "outside the meshing box", HM::Input_error_cause::BAD_SEED);
  const Point_3 in_body = CGAL::midpoint(m1.points[m1.hexahedra[0][0]], m1.points[m1.hexahedra[0][6]]);
  expect_input_error([&] { Mesh m; CGAL::make_hex_mesh_3(eight, c2, m, HP::body_fitted(false).meshing_box(box).region_seed(in_body)); },
                     "inside a body", HM::Input_error_cause::BAD_SEED);
  expect_input_error([&] { Mesh m; Criteria bad(-1, 0); CGAL::make_hex_mesh_3(eight, bad, m, HP::body_fitted(false)); }, "positive", HM::Input_error_cause::BAD_PARAMETER);

  // exact hex-grid case: the cube [-1,1]^3 with a grid aligned to its faces; the cells touching
  // the faces are cut (closed hulls), the rest is exactly [-0.75,0.75]^3 at size 0.25
  Domain cube("data/cube.off");
  Criteria c3(0.25, 0.25);
  Mesh m6;
  CGAL::make_hex_mesh_3(cube, c3, m6, HP::body_fitted(false).meshing_box(CGAL::Bbox_3(-1.5, -1.5, -1.5, 1.5, 1.5, 1.5)));
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
    CGAL::make_hex_mesh_3(d, Criteria(0.3, 0.15), m, HP::body_fitted(false));
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
    Domain open(p, t, {}, {}, false);   // (its hole left open)
    assert(!open.has_exact_inside_test() && open.input_summary().filled_holes == 0);
    const double w = open.winding_number(Point_3(0, 0, 0));
    std::cout << "open cube: winding number at the centre " << w << "\n";
    assert(w > 0.5 && w < 1.0);
    Mesh m;
    CGAL::make_hex_mesh_3(open, Criteria(0.3, 0.15), m, HP::body_fitted(false));
    check_mesh(m, "open cube");
    // by default the hole is filled: a closed cube (the fill's triangles last, flagged, with the
    // part of the rim's faces), exact inside test
    Domain filled(p, t);
    const auto& fs = filled.input_summary();
    std::size_t fills = 0;
    for(std::size_t i = 0; i < filled.number_of_triangles(); ++i) {
      fills += filled.is_fill(i);
      assert(filled.is_fill(i) == (i >= t.size()) && filled.filled_hole(i) == (i >= t.size() ? 1u : 0u));
      assert(filled.patch(i) == 0);
    }
    std::cout << "open cube filled: " << fs.filled_holes << " hole, " << fs.fill_triangles << " triangles on "
              << fs.filled_rim_edges << " rim edges of " << fs.boundary_edges << "\n";
    assert(fs.filled_holes == 1 && fills == fs.fill_triangles && fills > 0 && fs.filled_rim_edges == fs.boundary_edges);
    assert(fs.closed && filled.has_exact_inside_test() && filled.is_inside(Point_3(0, 0, 0)));
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
                          HP::body_fitted(false).meshing_box(CGAL::Bbox_3(-1, -1, -1, 1, 1, 1)).region_seed(Point_3(0.3, 0.3, 0.7)));
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
    expect_input_error([] { Domain d("data/does_not_exist.off"); }, "does_not_exist.off: cannot open", HM::Input_error_cause::UNREADABLE);
    expect_input_error([] { Domain d("tmp_empty.off"); }, "tmp_empty.off: the file is empty", HM::Input_error_cause::EMPTY);
    expect_input_error([] { Domain d("tmp_garbage.off"); }, "tmp_garbage.off", HM::Input_error_cause::MALFORMED);
    expect_input_error([] { Domain d("tmp_nan.off"); }, "tmp_nan.off", HM::Input_error_cause::NON_FINITE);
    expect_input_error([] { Domain d("tmp_noface.off"); }, "tmp_noface.off", HM::Input_error_cause::NO_SURFACE);
    expect_input_error([] { Domain d("tmp_badindex.off"); }, "tmp_badindex.off", HM::Input_error_cause::BAD_INDEX);
    expect_input_error([] { Domain d("data/cube.xyz"); }, "unknown surface format", HM::Input_error_cause::UNSUPPORTED);
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


// ---- dirty input: readers from memory, repair, sheets, overlapping parts, leaks ---------------

typedef HM::IO::Surface_soup<Point_3> Soup;

/// appends the 12 outward triangles of the box [lo, hi] as part `part`
void add_box(Soup& s, const std::array<double, 3>& lo, const std::array<double, 3>& hi, int part)
{
  const std::size_t b = s.points.size();
  for(int k = 0; k < 8; ++k) {
    const auto& o = HM::hex_corner_offsets()[std::size_t(k)];
    s.points.push_back(Point_3(o[0] ? hi[0] : lo[0], o[1] ? hi[1] : lo[1], o[2] ? hi[2] : lo[2]));
  }
  for(const auto& f : HM::hex_local_faces()) {
    s.triangles.push_back({{std::uint32_t(b + f[0]), std::uint32_t(b + f[1]), std::uint32_t(b + f[2])}});
    s.triangles.push_back({{std::uint32_t(b + f[0]), std::uint32_t(b + f[2]), std::uint32_t(b + f[3])}});
    s.part_of_triangle.push_back(part);
    s.part_of_triangle.push_back(part);
  }
}

void test_dirty_input()
{
  std::cout << "dirty input\n";
  // OBJ: groups and objects are parts, relative indices, quads fanned, unknown keywords ignored
  {
    Soup s;
    HM::IO::read_surface_buffer("# x\nmtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                                "g base plate\nusemtl m\nf 1/1/1 2/1/1 3/1/1 4/1/1\no lid\nf -4//1 -2//1 -3//1\n",
                                "a.obj", "obj", s, 2.0);
    assert(s.part_names.size() == 2 && s.part_names[0] == "base plate" && s.part_names[1] == "lid");
    assert(s.triangles.size() == 3 && s.polygons == 2);
    assert((s.part_of_triangle == std::vector<int>{0, 0, 1}));
    assert(s.triangles[2] == (std::array<std::uint32_t, 3>{{0, 2, 1}}));
    assert(s.points[2] == Point_3(2, 2, 0));   // scaled
    expect_input_error([] { Soup t; HM::IO::read_surface_buffer("v 0 0 0\nv 1 0 0\nf -9223372036854775808 1 2\nv 0 1 0\n",
                                                                "h.obj", "obj", t); },
                       "h.obj: line 3", HM::Input_error_cause::BAD_INDEX);
    std::cout << "  OBJ: groups 'base plate', 'lid'; relative indices; scale\n";
  }
  // STL: ASCII with two solids, binary, and the same read from a gzip stream
  {
    const std::string tri = " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
                            "  endloop\n endfacet\n";
    Soup s;
    HM::IO::read_surface_buffer("solid alpha\n" + tri + "endsolid alpha\nsolid beta\n" + tri + tri + "endsolid beta\n",
                                "b.stl", "stl", s);
    assert(s.part_names.size() == 2 && s.part_names[1] == "beta" && s.triangles.size() == 3);
    Soup su;   // capitals, CRLF line ends
    HM::IO::read_surface_buffer("SOLID UP\r\nFACET NORMAL 0 0 1\r\nOUTER LOOP\r\nVERTEX 0 0 0\r\nVERTEX 1 0 0\r\n"
                                "VERTEX 0 1 0\r\nENDLOOP\r\nENDFACET\r\nENDSOLID UP\r\n", "u.stl", "stl", su);
    assert(su.triangles.size() == 1 && su.part_names[0] == "UP");
    assert((s.part_of_triangle == std::vector<int>{0, 1, 1}));
    std::string bin(80, 'x');
    const std::uint32_t n = 1;
    bin.append(reinterpret_cast<const char*>(&n), 4);
    const float f[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1.5f, 0};
    bin.append(reinterpret_cast<const char*>(f), 48);
    bin.append(2, '\0');
    Soup sb;
    HM::IO::read_surface_buffer(bin, "c.stl", "stl", sb);
    assert(sb.triangles.size() == 1 && sb.points[2] == Point_3(0, 1.5, 0) && sb.part_names[0] == "c");
    // gzip of the binary STL: the same soup
    std::string gz;
    {
      namespace bio = boost::iostreams;
      bio::filtering_ostream out;
      out.push(bio::gzip_compressor());
      out.push(bio::back_inserter(gz));
      out << bin;
    }
    Soup sg;
    HM::IO::read_surface_buffer(gz, "c.stl.gz", "stl", sg);
    assert(sg.points == sb.points && sg.triangles == sb.triangles && sg.part_names == sb.part_names);
    expect_input_error([&] { Soup t; HM::IO::read_surface_buffer(gz.substr(0, gz.size() - 9), "d.stl.gz", "stl", t); },
                       "d.stl.gz: the gzip stream is corrupt or truncated", HM::Input_error_cause::TRUNCATED);
    std::cout << "  STL: two solids, binary, gzip\n";
  }
  // PLY: binary big endian with extra properties and an extra element
  {
    std::string ply = "ply\nformat binary_big_endian 1.0\ncomment x\nelement vertex 3\nproperty float x\nproperty uchar red\n"
                      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                      "element edge 1\nproperty int a\nproperty int b\nend_header\n";
    auto be32 = [&](const void* p) { const char* c = static_cast<const char*>(p); for(int i = 3; i >= 0; --i) ply += c[i]; };
    const float xs[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
    for(const auto& v : xs) { be32(&v[0]); ply += char(7); be32(&v[1]); be32(&v[2]); }
    ply += char(3);
    for(int i : {0, 1, 2}) be32(&i);
    for(int i : {0, 1}) be32(&i);
    Soup s;
    HM::IO::read_surface_buffer(ply, "e.ply", "ply", s);
    assert(s.points.size() == 3 && s.points[2] == Point_3(0, 2, 0) && s.triangles.size() == 1);
    expect_input_error([&] { Soup t; HM::IO::read_surface_buffer(ply.substr(0, ply.size() - 12), "e.ply", "ply", t); },
                       "truncated", HM::Input_error_cause::TRUNCATED);
    std::cout << "  PLY: binary big endian, extra properties and elements\n";
  }
  // OFF: a failed read leaves the soup as it was (several files are appended one by one)
  {
    Soup s;
    HM::IO::read_surface_buffer("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "f.off", "off", s);
    expect_input_error([&] { HM::IO::read_surface_buffer("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "g.off", "off", s); },
                       "g.off: line 6: a face refers to vertex 5", HM::Input_error_cause::BAD_INDEX);
    assert(s.points.size() == 3 && s.triangles.size() == 1 && s.part_names.size() == 1 && s.files.size() == 1);
    std::cout << "  OFF: a failed read leaves the soup untouched\n";
  }
  // repair: a closed box with duplicated, reversed and flipped faces is repaired to the closed box
  {
    Soup s;
    add_box(s, {{0, 0, 0}}, {{1, 1, 1}}, 0);
    s.part_names = {"box"};
    s.triangles.push_back(s.triangles[0]); s.part_of_triangle.push_back(0);              // duplicate
    auto r = s.triangles[3]; std::swap(r[1], r[2]);
    s.triangles.push_back(r); s.part_of_triangle.push_back(0);                            // reversed copy
    std::swap(s.triangles[5][0], s.triangles[5][1]);                                      // flipped face
    Domain d(s);
    const auto& m = d.input_summary();
    assert(m.duplicate_triangles == 1 && m.reversed_duplicates == 1 && m.sheet_triangles == 0);
    assert(m.reoriented_triangles == 1 && m.closed && d.has_exact_inside_test() && d.number_of_triangles() == 12);
    assert(d.is_inside(Point_3(0.5, 0.5, 0.5)) && !d.is_inside(Point_3(1.5, 0.5, 0.5)));
    std::cout << "  repair: duplicate, reversed copy and flipped face of a box -> the closed box, exact test\n";
  }
  // a zero-thickness sheet (a square and its reversed copy) beside a box: kept, two-sided
  {
    Soup s;
    add_box(s, {{0, 0, 0}}, {{1, 1, 1}}, 0);
    const std::uint32_t b = std::uint32_t(s.points.size());
    for(const Point_3& p : {Point_3(2, 0, 0.5), Point_3(3, 0, 0.5), Point_3(3, 1, 0.5), Point_3(2, 1, 0.5)}) s.points.push_back(p);
    for(auto t : {std::array<std::uint32_t, 3>{{b, b + 1, b + 2}}, std::array<std::uint32_t, 3>{{b, b + 2, b + 3}},
                  std::array<std::uint32_t, 3>{{b, b + 2, b + 1}}, std::array<std::uint32_t, 3>{{b, b + 3, b + 2}}}) {
      s.triangles.push_back(t); s.part_of_triangle.push_back(1);
    }
    s.part_names = {"box", "sheet"};
    Domain d(s);
    const auto& m = d.input_summary();
    assert(m.sheet_triangles == 2 && m.reversed_duplicates == 2 && d.number_of_triangles() == 14);
    assert(std::abs(d.winding_number(Point_3(2.5, 0.5, 0.6))) < 1e-6);   // the sheet bounds nothing
    assert(std::abs(d.winding_number(Point_3(0.5, 0.5, 0.5)) - 1) < 1e-6);
    Mesh mesh;
    std::vector<HM::Region_leak> leaks;
    HM::Status st = CGAL::make_hex_mesh_3(d, Criteria(0.25, 0.125), mesh,
                                          HP::body_fitted(false).meshing_box(CGAL::Bbox_3(-1, -1, -1, 4, 2, 2)).region_seed(Point_3(-0.9, -0.9, -0.9))
                                              .leaks(std::back_inserter(leaks)));
    assert(st == HM::Status::SUCCESS && leaks.empty());
    check_mesh(mesh, "air around a box and a sheet");
    // both copies in part "sheet": its back side (below, against the first copy's normal +z) is
    // the added part "sheet_back"; each face's cell lies on its patch's side of the plane z = 0.5
    assert(m.sheet_back_parts == 1 && m.sheet_reoriented == 0);
    std::size_t front = 0, back = 0;
    for(const auto& f : mesh.boundary_faces) {
      const std::string& name = mesh.patch_names[std::size_t(f.patch)];
      if(name != "sheet" && name != "sheet_back") continue;
      double z = 0;
      for(auto v : mesh.hexahedra[f.cell]) z += CGAL::to_double(mesh.points[v].z()) / 8;
      assert(z != 0.5 && (name == "sheet") == (z > 0.5));
      ++(name == "sheet" ? front : back);
    }
    assert(front > 0 && back > 0);   // the sheet bounds the air on both sides, each side a patch
    std::cout << "  sheet: kept two-sided, bounds " << front << " + " << back
              << " boundary faces (front, back), winding number 0 beside it\n";
  }
  // overlapping parts: the inner faces are left out, the union is meshed as one
  {
    Soup s;
    add_box(s, {{0, 0, 0}}, {{1, 1, 1}}, 0);
    add_box(s, {{0.5, 0.25, 0.25}}, {{1.5, 0.75, 0.75}}, 1);
    s.part_names = {"a", "b"};
    Domain d(s);
    // b's face at x = 0.5 is inside a, b's sides and a's face at x = 1 partly
    assert(d.input_summary().internal_triangles == 12 && !d.has_exact_inside_test());
    Mesh mesh;
    CGAL::make_hex_mesh_3(d, Criteria(0.125, 0.125), mesh, HP::body_fitted(false).meshing_box(CGAL::Bbox_3(-0.5, -0.5, -0.5, 2, 1.5, 1.5)));
    check_mesh(mesh, "union of overlapping boxes");
    double v = 0;
    for(const auto& h : mesh.hexahedra) {
      const Point_3 &p = mesh.points[h[0]], &q = mesh.points[h[6]];
      v += (q.x() - p.x()) * (q.y() - p.y()) * (q.z() - p.z());
    }
    // staircase: the cells touching the union's boundary are cut, nothing inside it is
    std::cout << "  overlapping boxes: " << d.input_summary().internal_triangles << " triangles inside, "
              << d.input_summary().split_triangles << " pieces kept, volume " << v << "\n";
    assert(std::abs(v - (0.75 * 0.75 * 0.75 + 0.5 * 0.25 * 0.25)) < 1e-12);
  }
  // leak: a box with a hole in its top, meshed around from outside
  {
    Soup s;
    add_box(s, {{0, 0, 0}}, {{1, 1, 1}}, 0);
    // replace the top face (z+, the last two triangles) by a frame around the hole [0.3,0.7]^2
    s.triangles.resize(10); s.part_of_triangle.resize(10);
    const double g[4] = {0, 0.3, 0.7, 1};
    std::map<std::pair<int, int>, std::uint32_t> id;
    for(int i = 0; i < 4; ++i) for(int j = 0; j < 4; ++j) {
      id[{i, j}] = std::uint32_t(s.points.size());
      s.points.push_back(Point_3(g[i], g[j], 1));
    }
    for(int i = 0; i < 3; ++i) for(int j = 0; j < 3; ++j) {
      if(i == 1 && j == 1) continue;
      const std::uint32_t a = id[{i, j}], b = id[{i + 1, j}], c = id[{i + 1, j + 1}], e = id[{i, j + 1}];
      s.triangles.push_back({{a, b, c}}); s.triangles.push_back({{a, c, e}});
      s.part_of_triangle.push_back(0); s.part_of_triangle.push_back(0);
    }
    s.part_names = {"holed"};
    Domain d(s, false);   // (the hole left open: filled, there is no leak)
    Mesh mesh;
    std::vector<HM::Region_leak> leaks;
    CGAL::make_hex_mesh_3(d, Criteria(0.1, 0.05), mesh,
                          HP::body_fitted(false).meshing_box(CGAL::Bbox_3(-0.5, -0.5, -0.5, 1.5, 1.5, 1.5)).region_seed(Point_3(-0.45, -0.45, -0.45))
                              .leaks(std::back_inserter(leaks)));
    assert(leaks.size() == 1);
    const HM::Region_leak& l = leaks[0];
    std::cout << "  leak: " << l.cells << " cells, volume " << l.volume << ", passage (" << l.passage.xmin() << ", "
              << l.passage.ymin() << ", " << l.passage.zmin() << ") - (" << l.passage.xmax() << ", " << l.passage.ymax()
              << ", " << l.passage.zmax() << "), " << l.passage_faces << " faces\n";
    assert(l.passage.xmin() >= 0.3 - 1e-9 && l.passage.xmax() <= 0.7 + 1e-9 && l.passage.ymin() >= 0.3 - 1e-9 &&
           l.passage.ymax() <= 0.7 + 1e-9 && std::abs(l.passage.zmin() - 1) < 1e-9 && std::abs(l.passage.zmax() - 1) < 1e-9);
    assert(l.volume > 0.5 && l.volume < 1 && l.max_winding_number > 0.9);
    for(const auto& h : mesh.hexahedra) {   // no cell of the mesh inside the box
      const Point_3 c = CGAL::midpoint(mesh.points[h[0]], mesh.points[h[6]]);
      assert(!(c.x() > 0 && c.x() < 1 && c.y() > 0 && c.y() < 1 && c.z() > 0 && c.z() < 1));
    }
    check_mesh(mesh, "air around a holed box");
  }
}

// ---- feature curves: counts on simple shapes, and CGAL's detect_sharp_edges() as the oracle ----
void test_features()
{
  typedef HM::Feature_curves_3<K> Features;
  std::cout << "feature curves\n";
  {
    Domain cube("data/cube.off");
    Features f(cube);
    assert(f.number_of_edges(Features::SHARP) == 12 && f.edges().size() == 12);
    assert(f.corners().size() == 8 && f.curves().size() == 12);
    for(const auto& c : f.curves()) assert(c.vertices.size() == 2 && !c.closed);
    std::cout << "  cube: 12 sharp edges, 8 corners, 12 curves\n";
    // feature size: every cell the criteria see that meets a cube edge (independent test on the
    // axis-aligned edges) is flagged, every flagged one meets an edge, and none is left coarser
    Criteria along(0.5, 0.25);
    along.set_feature_size(0.0625);
    std::size_t flagged = 0, seen = 0;
    along.add_criterion([&](const HM::Cell_3<K>& c) {
      ++seen;
      const CGAL::Bbox_3 b = c.bbox();
      bool meets = false;   // the box meets an edge: two coordinates at +-1 inside the box, the third overlapping [-1, 1]
      for(int a = 0; a < 3 && !meets; ++a)
        for(double u : {-1.0, 1.0})
          for(double v : {-1.0, 1.0}) {
            const int i = (a + 1) % 3, j = (a + 2) % 3;
            if(b.min(i) <= u && u <= b.max(i) && b.min(j) <= v && v <= b.max(j) && b.min(a) <= 1 && b.max(a) >= -1) meets = true;
          }
      assert(meets == c.meets_feature);
      if(c.meets_feature) { ++flagged; assert(CGAL::to_double(c.size()) <= 0.0625 * (1 + 1e-9)); }
      return CGAL::Hex_mesh_criteria_3<K>::Is_cell_bad();
    });
    cube.set_feature_edges(f.edge_vertices());
    Mesh m1;
    CGAL::make_hex_mesh_3(cube, along, m1, HP::body_fitted(false));
    check_mesh(m1, "cube with feature size");
    assert(flagged > 0);
    std::cout << "  cube, feature size 0.0625: " << flagged << " of " << seen << " cells seen meet an edge, all flagged, "
              << "all of size 0.0625\n";
  }
  {
    // a user feature line inside the cube, away from the surface: the cells along it are refined
    std::ofstream("tmp_line.obj") << "v -0.5 0.1 0.1\nv 0.5 0.1 0.1\nv 0.5 0.5 0.1\nl 1 2 -1\n";
    std::vector<std::vector<Point_3>> lines;
    HM::IO::read_polylines("tmp_line.obj", lines);
    assert(lines.size() == 1 && lines[0].size() == 3 && lines[0][2] == Point_3(0.5, 0.5, 0.1));
    expect_input_error([] { std::ofstream("tmp_badline.obj") << "v 0 0 0\nl 1 2\n"; std::vector<std::vector<Point_3>> l;
                            HM::IO::read_polylines("tmp_badline.obj", l); }, "refers to vertex 2", HM::Input_error_cause::BAD_INDEX);
    std::remove("tmp_line.obj"); std::remove("tmp_badline.obj");
    Domain cube("data/cube.off");
    cube.add_feature_polylines(lines);
    Criteria c(0.5, 0.25);
    c.set_feature_size(0.0625);
    Mesh m;
    CGAL::make_hex_mesh_3(cube, c, m, HP::body_fitted(false));
    check_mesh(m, "cube with a feature line inside");
    std::size_t fine = 0;
    for(const auto& h : m.hexahedra) {
      const double e = CGAL::to_double(m.points[h[6]].x() - m.points[h[0]].x());
      if(e > 0.0625 + 1e-9) continue;
      ++fine;
      const CGAL::Bbox_3 b = m.points[h[0]].bbox() + m.points[h[6]].bbox();
      bool near = false;   // within 2 cells of one of the two segments (balance grades around them)
      for(const auto& seg : cube.feature_segments())
        near = near || CGAL::squared_distance(CGAL::midpoint(m.points[h[0]], m.points[h[6]]), seg) < CGAL::square(4 * 0.0625);
      assert(near);
      (void)b;
    }
    assert(fine > 0);
    std::cout << "  cube with a user feature line inside: " << fine << " cells of 0.0625, all along the line\n";
  }
  {
    Domain cyl("data/cylinder.off");
    Features f(cyl);
    assert(f.corners().empty() && f.curves().size() == 2);
    for(const auto& c : f.curves()) assert(c.closed && c.vertices.size() > 20);
    std::cout << "  cylinder: 2 closed rims of " << f.curves()[0].vertices.size() << " and " << f.curves()[1].vertices.size()
              << " vertices, no corner\n";
  }
  {
    // (the holes left open: the judgement of the open edges; filled, below)
    Domain holes("data/elephant-with-holes.off", 1.0, false);
    Features f(holes);
    // every border edge is an open feature edge, but the rims of holes in the smooth skin (loops
    // mostly within the feature angle of the surface closing them): left out
    assert(f.number_of_edges(Features::OPEN) + f.number_of_smooth_hole_rim_edges() + f.number_of_smooth_seam_edges() ==
           holes.input_summary().boundary_edges);
    assert(f.number_of_smooth_seam_edges() == 0);
    // its holes were cut in the smooth skin: judged against the fill of each hole, nearly every
    // rim is smooth (1342 of its 1353 border edges; against the plane of each loop: 631)
    assert(f.number_of_smooth_hole_rim_edges() >= 0.95 * double(holes.input_summary().boundary_edges));
    std::cout << "  elephant-with-holes: " << f.number_of_edges(Features::OPEN) << " open edges, "
              << f.number_of_smooth_hole_rim_edges() << " hole rims left out, " << f.curves().size() << " curves\n";
    // a window cut in the side of a closed cylinder (120 degrees of arc, 0.4 high): its rim is
    // not planar, and the plane of its vector area meets the rim's faces beyond 30 degrees along
    // 58% of its length (the arcs' ends and the vertical sides); the fill of the window follows
    // the cylinder, so the rim is no feature. The rim of an open end (a cup) meets the fill (a
    // flat disc) at 90 degrees: a feature.
    auto cylinder = [](bool window, bool top, bool fill = false) {
      const int n = 36, rows = 10;   // 10 degrees, 0.1 high
      std::vector<Point_3> p;
      std::vector<std::array<std::uint32_t, 3>> t;
      auto at = [&](int i, int k) { return std::uint32_t(k * n + (i % n)); };
      for(int k = 0; k <= rows; ++k)
        for(int i = 0; i < n; ++i) {
          const double a = (i * 10.0 - 60.0) * CGAL_PI / 180.0;
          p.push_back(Point_3(std::cos(a), std::sin(a), 0.1 * k));
        }
      for(int k = 0; k < rows; ++k)
        for(int i = 0; i < n; ++i) {
          if(window && i < 12 && k >= 3 && k < 7) continue;   // theta in [-60, 60], z in [0.3, 0.7]
          t.push_back({{at(i, k), at(i + 1, k), at(i + 1, k + 1)}});
          t.push_back({{at(i, k), at(i + 1, k + 1), at(i, k + 1)}});
        }
      const std::uint32_t b = std::uint32_t(p.size());
      p.push_back(Point_3(0, 0, 0));
      p.push_back(Point_3(0, 0, 0.1 * rows));
      for(int i = 0; i < n; ++i) {
        t.push_back({{b, at(i + 1, 0), at(i, 0)}});
        if(top) t.push_back({{b + 1, at(i, rows), at(i + 1, rows)}});
      }
      return Domain(p, t, {}, {}, fill);
    };
    {
      Domain d = cylinder(true, true);
      Features w(d);
      assert(d.input_summary().boundary_edges == 32);
      assert(w.number_of_smooth_hole_rim_edges() == 32 && w.number_of_edges(Features::OPEN) == 0);
      assert(w.curves().size() == 2);   // the rims of the ends
      Domain c = cylinder(false, false);
      Features u(c);
      assert(u.number_of_smooth_hole_rim_edges() == 0 && u.number_of_edges(Features::OPEN) == 36);
      std::cout << "  cylinder with a window: its 32 rim edges left out, " << w.curves().size()
                << " curves; cup: its 36 rim edges kept\n";
      // the same with the holes filled (the default): the window's rim meets its fill within the
      // feature angle (no feature, no open edge), the cup's rim meets its flat fill at 90 degrees:
      // 36 sharp edges, one closed curve with the bottom's rim
      Domain df = cylinder(true, true, true), cf = cylinder(false, false, true);
      Features wf(df), uf(cf);
      assert(df.input_summary().filled_holes == 1 && cf.input_summary().filled_holes == 1);
      assert(wf.number_of_smooth_filled_rim_edges() == 32 && wf.number_of_smooth_hole_rim_edges() == 0 &&
             wf.number_of_edges(Features::OPEN) == 0 && wf.curves().size() == 2);
      assert(uf.number_of_smooth_filled_rim_edges() == 0 && uf.number_of_edges(Features::OPEN) == 0 &&
             uf.number_of_edges(Features::SHARP) == 72 && uf.curves().size() == 2);
      std::cout << "  filled: the window's rim left out, the cup's rim " << uf.number_of_edges(Features::SHARP) / 2
                << " sharp edges\n";
    }
    {
      // elephant-with-holes filled: every rim is a fill's, nearly all of them smooth
      Domain filled("data/elephant-with-holes.off");
      Features ff(filled);
      std::cout << "  elephant-with-holes filled: " << filled.input_summary().filled_holes << " holes, "
                << ff.number_of_smooth_filled_rim_edges() << " rim edges left out, " << ff.curves().size() << " curves\n";
      assert(filled.input_summary().filled_rim_edges == filled.input_summary().boundary_edges);
      assert(ff.number_of_edges(Features::OPEN) == 0 &&
             ff.number_of_smooth_filled_rim_edges() >= 0.95 * double(filled.input_summary().boundary_edges));
    }
    // the teapot's rims (the spout's end, the body's rim under the lid) meet the fill of their
    // opening at an angle: they stay features
    Domain teapot("data/teapot.off", 1.0, false);
    Features t(teapot);
    assert(t.number_of_smooth_hole_rim_edges() == 0 && t.number_of_edges(Features::OPEN) > 0);
    std::cout << "  teapot: " << t.number_of_edges(Features::OPEN) << " open edges, no hole rim left out\n";
  }
  // fidelity of the staircase, both ways, against an independent brute-force distance
  {
    Domain eight("data/eight.off");
    Mesh m;
    CGAL::make_hex_mesh_3(eight, Criteria(0.1, 0.025), m, HP::body_fitted(false));
    const HM::Boundary_fidelity fid = HM::boundary_fidelity(m, eight, 2000);
    std::cout << "  eight fidelity: " << fid.surface_faces << " faces, mesh->input max " << fid.max_face_distance
              << " mean " << fid.mean_face_distance << "; input->mesh max " << fid.max_sample_distance << " mean "
              << fid.mean_sample_distance << " (surface size 0.025)\n";
    assert(fid.surface_faces == m.boundary_faces.size() && fid.samples == 2000);
    assert(fid.max_face_distance > 0 && fid.max_face_distance <= 2 * std::sqrt(3.0) * 0.025);
    assert(fid.max_sample_distance > 0 && fid.max_sample_distance <= 2 * std::sqrt(3.0) * 0.025);
    // brute force at the worst face point
    const Point_3 w(fid.worst_face_location[0], fid.worst_face_location[1], fid.worst_face_location[2]);
    double best = 1e30;
    for(std::size_t i = 0; i < eight.number_of_triangles(); ++i)
      best = (std::min)(best, CGAL::to_double(CGAL::squared_distance(w, eight.triangle(i))));
    assert(std::abs(std::sqrt(best) - fid.max_face_distance) < 1e-12);
    // topology: the figure-eight is a closed surface of genus 2, and so is this staircase of it
    const HM::Surface_topology in = HM::surface_topology(eight);
    HM::Polyhedral_mesh_3 pm;
    pm.build(m);
    const HM::Surface_topology out = HM::boundary_topology(pm);
    std::cout << "  eight topology: input " << in.components << " component(s), chi " << in.euler_characteristic
              << "; mesh boundary " << out.components << ", chi " << out.euler_characteristic << "\n";
    assert(in.components == 1 && in.euler_characteristic == -2 && in.boundary_edges == 0);
    assert(out.components == 1 && out.euler_characteristic == -2 && out.boundary_edges == 0);
    Domain cube("data/cube.off");
    const HM::Surface_topology ct = HM::surface_topology(cube);
    assert(ct.components == 1 && ct.euler_characteristic == 2 && ct.vertices == 8 && ct.edges == 18 && ct.faces == 12);
  }
  for(const char* file : {"data/fandisk.off", "data/anchor.off", "data/t20_part.off"}) {
    Domain d(file);
    Features f(d);
    typedef CGAL::Surface_mesh<Point_3> SM;
    SM sm;
    std::vector<std::vector<std::size_t>> polys;
    for(const auto& t : d.triangle_indices()) polys.push_back({t[0], t[1], t[2]});
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(d.points(), polys, sm);
    auto is_sharp = sm.add_property_map<SM::Edge_index, bool>("e:sharp", false).first;
    CGAL::Polygon_mesh_processing::detect_sharp_edges(sm, 30.0, is_sharp);
    std::set<std::pair<std::uint32_t, std::uint32_t>> theirs, ours;
    for(auto e : sm.edges())
      if(is_sharp[e]) {
        std::uint32_t a = std::uint32_t(sm.vertex(e, 0)), b = std::uint32_t(sm.vertex(e, 1));
        theirs.insert({(std::min)(a, b), (std::max)(a, b)});
      }
    for(const auto& e : f.edges())
      if(e.kind & Features::SHARP) ours.insert({e.vertices[0], e.vertices[1]});
    std::cout << "  " << file << ": " << ours.size() << " sharp edges (detect_sharp_edges: " << theirs.size() << "), "
              << f.corners().size() << " corners, " << f.curves().size() << " curves\n";
    assert(ours == theirs && !ours.empty());
    std::size_t in_curves = 0;   // every feature edge is on exactly one curve
    for(const auto& c : f.curves()) in_curves += c.vertices.size() - (c.closed ? 0 : 1);
    assert(in_curves == f.edges().size());
    // judged at the scale and by the contrast make_hex_mesh_3() uses: a CAD part keeps them all
    Features::Options o;
    o.scale = 0.0125;
    o.contrast = 3;
    const Features judged(d, o);
    assert(judged.number_of_smooth_edges() == 0 && judged.edges().size() == f.edges().size() &&
           judged.curves().size() == f.curves().size() && judged.corners() == f.corners());
  }
  {
    // the creases of a coarse triangulation of a smooth shape do not stand out from the edges
    // around them: eight.off's 149 sharp edges (30-60 degrees) among 10-15 degree ones
    Domain eight("data/eight.off");
    const Features all(eight);
    Features::Options o;
    o.contrast = 3;
    const Features judged(eight, o);
    std::set<std::array<std::uint32_t, 2>> kept;
    for(const auto& e : judged.edges()) kept.insert(e.vertices);
    std::size_t in_curves = 0;
    for(const auto& c : judged.curves()) in_curves += c.vertices.size() - (c.closed ? 0 : 1);
    assert(in_curves == judged.edges().size());
    // the edges left out are sharp edges of the plain detection, below twice the feature angle
    // (their dihedral angle recomputed here from the triangles)
    std::map<std::array<std::uint32_t, 2>, std::vector<std::size_t>> faces_of;
    const auto& tr = eight.triangle_indices();
    for(std::size_t t = 0; t < tr.size(); ++t)
      for(int k = 0; k < 3; ++k) {
        std::uint32_t a = tr[t][std::size_t(k)], b = tr[t][std::size_t((k + 1) % 3)];
        faces_of[{{(std::min)(a, b), (std::max)(a, b)}}].push_back(t);
      }
    std::size_t left = 0;
    for(const auto& e : all.edges()) {
      if(kept.count(e.vertices)) continue;
      ++left;
      const auto& fs = faces_of[e.vertices];
      assert(fs.size() == 2);
      const K::Vector_3 n0 = CGAL::unit_normal(eight.points()[tr[fs[0]][0]], eight.points()[tr[fs[0]][1]], eight.points()[tr[fs[0]][2]]);
      const K::Vector_3 n1 = CGAL::unit_normal(eight.points()[tr[fs[1]][0]], eight.points()[tr[fs[1]][1]], eight.points()[tr[fs[1]][2]]);
      const double angle = std::acos((std::max)(-1.0, (std::min)(1.0, CGAL::to_double(n0 * n1)))) * 180 / CGAL_PI;
      assert(angle >= 30 - 1e-9 && angle < 60);
    }
    assert(left == judged.number_of_smooth_edges() && left + kept.size() == all.edges().size());
    std::cout << "  eight, contrast 3: " << left << " of " << all.edges().size() << " sharp edges left out, "
              << judged.curves().size() << " curves (" << all.curves().size() << ")\n";
    assert(left >= all.edges().size() / 2);
    // at a scale wider than fin_slot's 0.01 slot and fin, the four 0.01 edges across their ends
    // are not sharp (the faces within the scale reach round them); at 0.002 they are
    Domain fin("data/fin_slot.off");
    Features::Options wide, narrow;
    wide.scale = 0.0125;
    narrow.scale = 0.002;
    const Features fw(fin, wide), fn(fin, narrow), f0(fin);
    std::set<std::array<std::uint32_t, 2>> in_wide;
    for(const auto& e : fw.edges()) in_wide.insert(e.vertices);
    std::size_t short_left = 0;
    for(const auto& e : f0.edges())
      if(!in_wide.count(e.vertices)) {
        const double l = std::sqrt(CGAL::to_double(CGAL::squared_distance(fin.points()[e.vertices[0]], fin.points()[e.vertices[1]])));
        assert(std::abs(l - 0.01) < 1e-9);
        ++short_left;
      }
    std::cout << "  fin_slot: scale 0.0125 leaves out " << fw.number_of_smooth_edges() << " edges (all 0.01 long), "
              << "scale 0.002 " << fn.number_of_smooth_edges() << "\n";
    assert(short_left == 4 && fw.number_of_smooth_edges() == 4 && fn.number_of_smooth_edges() == 0);
  }
  {
    // soft creases: a prism of 16 flat sides (22.5 degrees between them), 4 rows of triangles high,
    // its ends fans: 16 crease lines of 4 edges each between the two rims (90 degrees: sharp)
    const int ns = 16, rows = 4;
    std::vector<Point_3> pts;
    for(int r = 0; r <= rows; ++r)
      for(int i = 0; i < ns; ++i)
        pts.emplace_back(std::cos(2 * CGAL_PI * i / ns), std::sin(2 * CGAL_PI * i / ns), -1 + 2.0 * r / rows);
    pts.emplace_back(0, 0, -1);
    pts.emplace_back(0, 0, 1);
    auto id = [&](int r, int i) { return std::uint32_t(r * ns + i % ns); };
    std::vector<std::array<std::uint32_t, 3>> tris;
    for(int r = 0; r < rows; ++r)
      for(int i = 0; i < ns; ++i) {
        tris.push_back({{id(r, i), id(r, i + 1), id(r + 1, i + 1)}});
        tris.push_back({{id(r, i), id(r + 1, i + 1), id(r + 1, i)}});
      }
    for(int i = 0; i < ns; ++i) {
      tris.push_back({{std::uint32_t(pts.size() - 2), id(0, i + 1), id(0, i)}});
      tris.push_back({{std::uint32_t(pts.size() - 1), id(rows, i), id(rows, i + 1)}});
    }
    Domain prism(pts, tris);
    Features::Options o;
    o.scale = 0.05;
    o.contrast = 3;
    const Features plain(prism, o);
    o.soft_angle = 15;
    const Features soft(prism, o);
    assert(plain.number_of_edges(Features::SHARP) == 32 && plain.number_of_edges(Features::SOFT) == 0);
    assert(soft.number_of_edges(Features::SHARP) == 32 && soft.number_of_edges(Features::SOFT) == 64 &&
           soft.number_of_smooth_soft_edges() == 0 && soft.corners().size() == 32 && soft.curves().size() == 48);
    for(const auto& e : soft.edges())   // the soft ones run up the sides, at the polygon's corners
      if(e.kind == Features::SOFT) {
        const Point_3& a = pts[e.vertices[0]];
        const Point_3& b = pts[e.vertices[1]];
        assert(a.x() == b.x() && a.y() == b.y() && std::abs(CGAL::to_double(a.x() * a.x() + a.y() * a.y()) - 1) < 1e-12);
      }
    // above 22.5 degrees: none; without a judgement (scale and contrast 0): none; the creases are
    // 2 long: at the scale 0.45 (curves at least 1.8 long) all kept, at 0.55 (2.2) all left out
    o.soft_angle = 25;
    assert(Features(prism, o).number_of_edges(Features::SOFT) == 0);
    Features::Options unjudged;
    unjudged.soft_angle = 15;
    assert(Features(prism, unjudged).number_of_edges(Features::SOFT) == 0);
    o.soft_angle = 15;
    o.scale = 0.45;
    const Features long_enough(prism, o);
    assert(long_enough.number_of_edges(Features::SOFT) == 64 && long_enough.number_of_smooth_soft_edges() == 0);
    o.scale = 0.55;
    const Features too_short(prism, o);
    assert(too_short.number_of_edges(Features::SOFT) == 0 && too_short.number_of_smooth_soft_edges() == 64 &&
           too_short.number_of_edges(Features::SHARP) == 32);
    // a coarse triangulation of a smooth shape creases by 20 to 30 degrees among creases of 5 to
    // 15: eight.off (at the benchmark suite's scale for diagonal / 80) keeps none of them, and its
    // sharp edges are judged as without soft creases (some left out: the judgement runs)
    Domain eight("data/eight.off");
    Features::Options e8;
    e8.contrast = 3;
    e8.scale = 0.00707;
    const Features p8(eight, e8);
    e8.soft_angle = 20;
    const Features f8(eight, e8);
    const std::size_t kept = f8.number_of_edges(Features::SOFT), left = f8.number_of_smooth_soft_edges();
    std::cout << "  prism of 16 sides: 64 soft crease edges at 15 degrees (none at 25, none with curves too short); "
              << "eight at 20 degrees: " << kept << " soft crease edges kept, " << left << " left out; "
              << p8.number_of_smooth_edges() << " sharp edges left out with and without\n";
    assert(left > 100 && kept == 0 && p8.number_of_smooth_edges() > 0 && f8.number_of_smooth_edges() == p8.number_of_smooth_edges());
    // the same features but the soft creases, in the same order (sorted by vertices)
    for(const Features* f : {&soft, &f8}) {
      const Features& without = f == &soft ? plain : p8;
      std::vector<Features::Edge> rest;
      for(const auto& e : f->edges()) if(e.kind != Features::SOFT) rest.push_back(e);
      assert(rest.size() == without.edges().size());
      for(std::size_t i = 0; i < rest.size(); ++i)
        assert(rest[i].vertices == without.edges()[i].vertices && rest[i].kind == without.edges()[i].kind);
      for(std::size_t i = 1; i < f->edges().size(); ++i) assert(f->edges()[i - 1].vertices < f->edges()[i].vertices);
    }
  }
}

// ---- fidelity to the feature curves: exact answers where the mesh boundary is known -----------
void test_feature_fidelity()
{
  typedef HM::Feature_curves_3<K> Features;
  std::cout << "feature fidelity\n";
  auto rel = [](double x, double y) { return std::abs(x - y) <= 1e-9 * std::abs(y); };
  // 1. the cube [-1,1]^3 on a grid aligned with its faces: the staircase is a box [-a,a]^3 (a read
  //    from the boundary vertices), each face offset inward by d = 1 - a; its edges run parallel to
  //    the cube's at d*sqrt(2), and end d*sqrt(3) from the cube's corners
  {
    Domain cube("data/cube.off");
    Features f(cube);
    assert(f.number_of_edges(Features::SHARP) == 12 && f.corners().size() == 8);
    Mesh m;
    CGAL::make_hex_mesh_3(cube, Criteria(0.25, 0.25), m,
                          HP::meshing_box(CGAL::Bbox_3(-1.5, -1.5, -1.5, 1.5, 1.5, 1.5)).body_fitted(false));
    assert(m.hanging_nodes.empty());
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for(const auto& bf : m.boundary_faces) {
      assert(bf.patch >= 6);
      for(auto v : bf.vertices)
        for(int k = 0; k < 3; ++k) {
          lo[k] = (std::min)(lo[k], m.points[v][k]);
          hi[k] = (std::max)(hi[k], m.points[v][k]);
        }
    }
    const double a = hi[0];
    for(int k = 0; k < 3; ++k) assert(hi[k] == a && lo[k] == -a);
    assert(a > 0 && a < 1);
    const double d = 1 - a;
    // the boundary edges on the 12 edges of the box: their midpoint has two coordinates at +-a
    std::set<std::pair<std::uint32_t, std::uint32_t>> on_box_edges;
    for(const auto& bf : m.boundary_faces)
      for(int i = 0; i < 4; ++i) {
        const std::uint32_t u = bf.vertices[std::size_t(i)], v = bf.vertices[std::size_t((i + 1) % 4)];
        const Point_3 mid = CGAL::midpoint(m.points[u], m.points[v]);
        int extreme = 0;
        for(int k = 0; k < 3; ++k) extreme += (std::abs(mid[k]) == a);
        if(extreme >= 2) on_box_edges.insert({(std::min)(u, v), (std::max)(u, v)});
      }
    assert(on_box_edges.size() == 12 * 6);   // 6 cells of 0.25 along each edge of [-0.75, 0.75]^3
    const HM::Feature_fidelity ff = HM::feature_fidelity(m, cube, f);
    std::cout << "  cube staircase (offset " << d << "): " << ff.input_feature_edges << " input and "
              << ff.mesh_feature_edges << " mesh feature edges, input->mesh " << ff.input_to_mesh << ", mesh->input "
              << ff.mesh_to_input << ", corners " << ff.corners << " at most " << ff.max_corner_distance << " away\n";
    assert(ff.input_feature_edges == 12 && ff.mesh_feature_edges == on_box_edges.size());
    assert(rel(ff.input_to_mesh, d * std::sqrt(3.0)) && rel(ff.mesh_to_input, d * std::sqrt(2.0)));
    assert(ff.corners == 8 && rel(ff.max_corner_distance, d * std::sqrt(3.0)));
    for(int k = 0; k < 3; ++k) assert(std::abs(ff.worst_input_location[std::size_t(k)]) == 1);   // a cube corner
    for(int k = 0; k < 3; ++k) assert(std::abs(ff.worst_corner_location[std::size_t(k)]) == 1);
    int extreme = 0;   // the worst mesh sample is on an edge of the staircase box
    for(int k = 0; k < 3; ++k) extreme += (std::abs(std::abs(ff.worst_mesh_location[std::size_t(k)]) - a) < 1e-12);
    assert(extreme >= 2);
    assert(ff.sample_spacing > 0 && ff.sample_spacing <= 0.25 / 20 + 1e-15);
    // the same with an explicit spacing: the maxima are reached at sampled end points, so unchanged
    const HM::Feature_fidelity coarse = HM::feature_fidelity(m, cube, f, 30, 10.0);
    assert(coarse.sample_spacing == 10.0 && rel(coarse.input_to_mesh, d * std::sqrt(3.0)) &&
           rel(coarse.mesh_to_input, d * std::sqrt(2.0)));
  }
  // hand-built meshes of a box, every boundary face on patch 6, against the box itself
  auto box_mesh = [](const std::vector<std::array<int, 4>>& cells, const std::array<int, 3>& top, Mesh& m) {
    // cells: (x, y, z, size) on the integer lattice; vertices where needed
    std::map<std::array<int, 3>, std::uint32_t> id;
    auto vid = [&](int x, int y, int z) {
      auto it = id.find({{x, y, z}});
      if(it != id.end()) return it->second;
      m.points.push_back(Point_3(x, y, z));
      return id[{{x, y, z}}] = std::uint32_t(m.points.size() - 1);
    };
    for(const auto& c : cells) {
      Mesh::Hexahedron h;
      for(int k = 0; k < 8; ++k) {
        const auto& o = HM::hex_corner_offsets()[std::size_t(k)];
        h[std::size_t(k)] = vid(c[0] + c[3] * o[0], c[1] + c[3] * o[1], c[2] + c[3] * o[2]);
      }
      m.hexahedra.push_back(h);
      m.cell_levels.push_back({{0, 0, 0}});
    }
    for(std::uint32_t c = 0; c < m.hexahedra.size(); ++c)
      for(const auto& lf : HM::hex_local_faces()) {
        std::array<std::uint32_t, 4> q;
        for(int i = 0; i < 4; ++i) q[std::size_t(i)] = m.hexahedra[c][std::size_t(lf[std::size_t(i)])];
        bool on_side = false;   // all four corners on one side of the box [0, top]
        for(int k = 0; k < 3; ++k)
          for(double side : {0.0, double(top[std::size_t(k)])}) {
            bool all = true;
            for(auto v : q) all = all && m.points[v][k] == side;
            on_side = on_side || all;
          }
        if(on_side) m.boundary_faces.push_back({q, c, 6});
      }
    m.patch_names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax", "box"};
    m.box = CGAL::Bbox_3(0, 0, 0, top[0], top[1], top[2]);
  };
  // 2. a single hexahedron [0,2]x[0,1]x[0,3]: its 12 edges, at distance 0
  {
    Mesh m;
    box_mesh({{{0, 0, 0, 1}}}, {{1, 1, 1}}, m);
    for(auto& p : m.points) p = Point_3(2 * p.x(), p.y(), 3 * p.z());
    assert(m.boundary_faces.size() == 6);
    Soup s;
    add_box(s, {{0, 0, 0}}, {{2, 1, 3}}, 0);
    s.part_names = {"box"};
    Domain d(s);
    Features f(d);
    const HM::Feature_fidelity ff = HM::feature_fidelity(m, d, f);
    std::cout << "  one hexahedron: " << ff.mesh_feature_edges << " mesh feature edges, input->mesh " << ff.input_to_mesh
              << ", mesh->input " << ff.mesh_to_input << ", corners at most " << ff.max_corner_distance << "\n";
    assert(ff.input_feature_edges == 12 && ff.mesh_feature_edges == 12);
    assert(ff.input_to_mesh < 1e-12 && ff.mesh_to_input < 1e-12);
    assert(ff.corners == 8 && ff.max_corner_distance == 0);
    // above the feature angle of a right angle, the mesh has no feature edge: the input's are
    // infinitely far from them, and no mesh sample is far from anything
    const HM::Feature_fidelity blunt = HM::feature_fidelity(m, d, f, 95);
    assert(blunt.mesh_feature_edges == 0 && blunt.input_feature_edges == 12);
    assert(std::isinf(blunt.input_to_mesh) && blunt.mesh_to_input == 0);
    // within a 10 degree tolerance the right angles are mesh features again for the input's
    // (sharp at 30) edges to meet: input->mesh 0; no mesh edge reaches 95 degrees: mesh->input 0
    auto at = [&d](double angle) {
      Features::Options o;
      o.feature_angle = angle;
      return Features(d, o);
    };
    const Features f85 = at(85), f75 = at(75), f95 = at(95);
    assert(f85.number_of_edges(Features::SHARP) == 12 && f95.number_of_edges(Features::SHARP) == 0);
    const HM::Feature_fidelity tol = HM::feature_fidelity_with_tolerance(m, d, f, f85, 95, 10);
    assert(tol.mesh_feature_edges == 0 && tol.input_to_mesh < 1e-12 && tol.mesh_to_input == 0);
    // the other way: an input with no edge of 95 degrees and the mesh's at 85: strictly, the
    // mesh's 12 feature edges are infinitely far from the input's (none); within 10 degrees the
    // input's right angles (the curves at 75) count and they coincide
    const HM::Feature_fidelity sharp_mesh = HM::feature_fidelity(m, d, f95, 85);
    assert(sharp_mesh.mesh_feature_edges == 12 && sharp_mesh.input_feature_edges == 0);
    assert(sharp_mesh.input_to_mesh == 0 && std::isinf(sharp_mesh.mesh_to_input));
    const HM::Feature_fidelity tol2 = HM::feature_fidelity_with_tolerance(m, d, f95, f75, 85, 10);
    assert(tol2.input_to_mesh == 0 && tol2.mesh_to_input < 1e-12);
    // a tolerance of 0 ignores the second curves: the strict figures
    const HM::Feature_fidelity zero = HM::feature_fidelity_with_tolerance(m, d, f95, f75, 85, 0);
    assert(std::isinf(zero.mesh_to_input));
    std::cout << "  angle tolerance: input->mesh " << tol.input_to_mesh << " (strict inf), mesh->input "
              << tol2.mesh_to_input << " (strict inf)\n";
  }
  // 3. a coarse cell [0,2]^3 beside four fine ones [2,3]x[0,2]^2: the coarse faces' edges at x = 2
  //    carry hanging midpoints and meet the fine faces' half edges there (no feature), the box's
  //    edges are cut where the cells are: 4 x 2 along x, 2 x 1 + 2 x 2 along y and along z
  {
    Mesh m;
    box_mesh({{{0, 0, 0, 2}}, {{2, 0, 0, 1}}, {{2, 1, 0, 1}}, {{2, 0, 1, 1}}, {{2, 1, 1, 1}}}, {{3, 2, 2}}, m);
    auto vid = [&m](int x, int y, int z) {
      const std::size_t i = std::size_t(std::find(m.points.begin(), m.points.end(), Point_3(x, y, z)) - m.points.begin());
      assert(i < m.points.size());
      return std::uint32_t(i);
    };
    m.hanging_nodes.push_back({vid(2, 1, 0), {{vid(2, 0, 0), vid(2, 2, 0), 0, 0}}, 2});
    m.hanging_nodes.push_back({vid(2, 1, 2), {{vid(2, 2, 2), vid(2, 0, 2), 0, 0}}, 2});
    m.hanging_nodes.push_back({vid(2, 0, 1), {{vid(2, 0, 0), vid(2, 0, 2), 0, 0}}, 2});
    m.hanging_nodes.push_back({vid(2, 2, 1), {{vid(2, 2, 2), vid(2, 2, 0), 0, 0}}, 2});
    m.hanging_nodes.push_back({vid(2, 1, 1), {{vid(2, 0, 0), vid(2, 2, 0), vid(2, 2, 2), vid(2, 0, 2)}}, 4});
    assert(m.points.size() == 8 + 18 - 4 && m.boundary_faces.size() == 5 + 4 * 3);
    HM::Polyhedral_mesh_3 pm;
    pm.build(m);   // consistent
    Soup s;
    add_box(s, {{0, 0, 0}}, {{3, 2, 2}}, 0);
    s.part_names = {"box"};
    Domain d(s);
    Features f(d);
    const HM::Feature_fidelity ff = HM::feature_fidelity(m, d, f);
    std::cout << "  coarse and fine cells: " << ff.mesh_feature_edges << " mesh feature edges, input->mesh "
              << ff.input_to_mesh << ", mesh->input " << ff.mesh_to_input << "\n";
    assert(ff.input_feature_edges == 12 && ff.mesh_feature_edges == 4 * 2 + 2 * (2 * 1 + 2 * 2));
    assert(ff.input_to_mesh < 1e-12 && ff.mesh_to_input < 1e-12);
    assert(ff.corners == 8 && ff.max_corner_distance == 0);
    const HM::Surface_topology t = HM::boundary_topology(pm);
    assert(t.boundary_edges == 0 && t.euler_characteristic == 2);
  }
}

// ---- polyhedral form: a coarse face matched by two finer faces side by side is split 1:2 ----
void test_polyhedral_half_splits()
{
  std::cout << "polyhedral half splits\n";
  typedef std::array<double, 3> P;
  // a hand-made mesh of axis-aligned boxes (xmin, ymin, zmin, xmax, ymax, zmax): shared corners,
  // a hanging node wherever a vertex lies at the midpoint of a cell's edge or the centre of its
  // face, boundary faces on the bounding box with the patch of their side
  auto make = [](const std::vector<std::array<double, 6>>& boxes, const std::vector<P>& extra_points) {
    Mesh m;
    std::map<P, std::uint32_t> id;
    auto vertex = [&](const P& p) {
      auto it = id.find(p);
      if(it != id.end()) return it->second;
      const std::uint32_t v = std::uint32_t(m.points.size());
      id[p] = v;
      m.points.push_back(Point_3(p[0], p[1], p[2]));
      return v;
    };
    CGAL::Bbox_3 bb;
    for(const auto& b : boxes) {
      Mesh::Hexahedron h;
      for(int c = 0; c < 8; ++c) {
        const auto& o = HM::hex_corner_offsets()[c];
        h[c] = vertex({{b[3 * o[0]], b[1 + 3 * o[1]], b[2 + 3 * o[2]]}});
      }
      m.hexahedra.push_back(h);
      m.cell_levels.push_back({{0, 0, 0}});
      bb += CGAL::Bbox_3(b[0], b[1], b[2], b[3], b[4], b[5]);
    }
    for(const P& p : extra_points) vertex(p);
    m.box = bb;
    auto at = [&](std::uint32_t v) { return P{{m.points[v].x(), m.points[v].y(), m.points[v].z()}}; };
    std::set<std::uint32_t> hanging;
    for(const auto& h : m.hexahedra) {
      for(const auto& e : HM::hex_local_edges()) {
        const P a = at(h[e[0]]), b = at(h[e[1]]);
        auto it = id.find({{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}});
        if(it != id.end() && hanging.insert(it->second).second)
          m.hanging_nodes.push_back({it->second, {{h[e[0]], h[e[1]], 0, 0}}, 2});
      }
      for(const auto& f : HM::hex_local_faces()) {
        const P a = at(h[f[0]]), b = at(h[f[2]]);
        auto it = id.find({{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}});
        if(it != id.end() && hanging.insert(it->second).second)
          m.hanging_nodes.push_back({it->second, {{h[f[0]], h[f[1]], h[f[2]], h[f[3]]}}, 4});
      }
    }
    for(std::uint32_t c = 0; c < m.hexahedra.size(); ++c)
      for(int fi = 0; fi < 6; ++fi) {
        const auto& f = HM::hex_local_faces()[fi];
        const int axis = fi / 2;
        const double side = fi % 2 ? bb.max(axis) : bb.min(axis);
        bool on = true;
        for(int i = 0; i < 4; ++i) on = on && at(m.hexahedra[c][f[i]])[axis] == side;
        if(on) {
          const auto& h = m.hexahedra[c];
          m.boundary_faces.push_back({{{h[f[0]], h[f[1]], h[f[2]], h[f[3]]}}, c, fi});
        }
      }
    m.patch_names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    return m;
  };
  auto vid = [](const Mesh& m, double x, double y, double z) {
    for(std::uint32_t v = 0; v < m.points.size(); ++v)
      if(m.points[v] == Point_3(x, y, z)) return v;
    assert(false);
    return std::uint32_t(-1);
  };
  // closed cells, twice: (1) every directed edge of the outward polygons of a cell is met reversed
  // exactly once in that cell (hanging nodes listed alike on both sides of every edge); (2) the
  // area vectors (Newell's, and OpenFOAM's from `OpenFOAM_geometry`) of its faces, oriented
  // owner -> neighbour, sum to zero, and the volumes they enclose are the boxes'
  auto check_closed = [](const Mesh& m, const HM::Polyhedral_mesh_3& pm) {
    const std::size_t nc = m.hexahedra.size();
    assert(pm.number_of_cells == nc && pm.owner.size() == pm.faces.size());
    std::vector<std::map<std::pair<std::uint32_t, std::uint32_t>, int>> edges(nc);
    std::vector<std::array<double, 3>> closure(nc, {{0, 0, 0}}), closure_foam(nc, {{0, 0, 0}});
    std::vector<double> volume(nc, 0);
    HM::OpenFOAM_geometry g;
    g.compute(m.points, pm);
    for(std::size_t f = 0; f < pm.faces.size(); ++f) {
      const auto& F = pm.faces[f];
      assert(F.size() >= 4 && std::set<std::uint32_t>(F.begin(), F.end()).size() == F.size());
      std::array<double, 3> S = {{0, 0, 0}};
      for(std::size_t i = 0; i < F.size(); ++i) {
        const Point_3& p = m.points[F[i]];
        const Point_3& q = m.points[F[(i + 1) % F.size()]];
        S[0] += 0.5 * (p.y() * q.z() - p.z() * q.y());
        S[1] += 0.5 * (p.z() * q.x() - p.x() * q.z());
        S[2] += 0.5 * (p.x() * q.y() - p.y() * q.x());
      }
      const Point_3& p0 = m.points[F[0]];   // the faces are planar: x.n is constant on them
      const double flux = (p0.x() * S[0] + p0.y() * S[1] + p0.z() * S[2]) / 3;
      for(int side = 0; side < (f < pm.neighbour.size() ? 2 : 1); ++side) {
        const std::uint32_t c = side == 0 ? pm.owner[f] : pm.neighbour[f];
        const double sign = side == 0 ? 1 : -1;
        for(int a = 0; a < 3; ++a) { closure[c][a] += sign * S[a]; closure_foam[c][a] += sign * g.face_areas[f][a]; }
        volume[c] += sign * flux;
        for(std::size_t i = 0; i < F.size(); ++i) {
          std::uint32_t a = F[i], b = F[(i + 1) % F.size()];
          if(side == 1) std::swap(a, b);
          const int seen = ++edges[c][std::make_pair(a, b)];
          assert(seen == 1);
          (void)seen;
        }
      }
    }
    for(std::size_t c = 0; c < nc; ++c) {
      for(const auto& e : edges[c]) assert(edges[c].count({e.first.second, e.first.first}) == 1);
      const Point_3& lo = m.points[m.hexahedra[c][0]];
      const Point_3& hi = m.points[m.hexahedra[c][6]];
      const double v = (hi.x() - lo.x()) * (hi.y() - lo.y()) * (hi.z() - lo.z());
      for(int a = 0; a < 3; ++a) assert(std::abs(closure[c][a]) < 1e-12 && std::abs(closure_foam[c][a]) < 1e-12);
      assert(std::abs(volume[c] - v) < 1e-12 && std::abs(g.cell_volumes[c] - v) < 1e-12);
    }
    if(pm.neighbour.size() > 1)
      for(std::size_t f = 1; f < pm.neighbour.size(); ++f)
        assert(pm.owner[f - 1] < pm.owner[f] || (pm.owner[f - 1] == pm.owner[f] && pm.neighbour[f - 1] < pm.neighbour[f]));
  };
  auto patch_sizes = [](const HM::Polyhedral_mesh_3& pm) {
    std::vector<std::size_t> n;
    for(const auto& p : pm.patches) n.push_back(p.size);
    return n;
  };
  {
    // coarse A = [0,2]x[0,1]x[0,1]; its face x = 2 meets B1 = [2,3]x[0,0.5]x[0,1] and
    // B2 = [2,3]x[0.5,1]x[0,1], with hanging nodes (2,0.5,0) and (2,0.5,1) on A's edges
    const Mesh m = make({{{0, 0, 0, 2, 1, 1}}, {{2, 0, 0, 3, 0.5, 1}}, {{2, 0.5, 0, 3, 1, 1}}}, {});
    assert(m.hanging_nodes.size() == 2 && m.boundary_faces.size() == 13);
    HM::Polyhedral_mesh_3 pm;
    pm.build(m);
    check_closed(m, pm);
    assert(pm.number_of_internal_faces() == 3 && pm.faces.size() == 16);
    assert(pm.owner[0] == 0 && pm.neighbour[0] == 1 && pm.owner[1] == 0 && pm.neighbour[1] == 2 &&
           pm.owner[2] == 1 && pm.neighbour[2] == 2);
    for(int f = 0; f < 3; ++f) assert(pm.faces[f].size() == 4);
    assert(patch_sizes(pm) == std::vector<std::size_t>({1, 2, 2, 2, 3, 3}));
    for(std::size_t p : {4, 5}) {   // A's faces z = 0 and z = 1 list the midpoint on their edge x = 2
      std::size_t of_a = 0;
      for(std::size_t f = pm.patches[p].start; f < pm.patches[p].start + pm.patches[p].size; ++f)
        if(pm.owner[f] == 0) { ++of_a; assert(pm.faces[f].size() == 5); }
        else assert(pm.faces[f].size() == 4);
      assert(of_a == 1);
    }
    HM::Polyhedral_mesh_3 again;   // deterministic
    again.build(m);
    assert(again.faces == pm.faces && again.owner == pm.owner && again.neighbour == pm.neighbour);
    std::cout << "  coarse face x=2 split 1:2 between two finer cells: 3 internal faces, 13 boundary faces, "
                 "closed cells\n";
  }
  {
    // the other pair of opposite edges: A's face x = 2 split at z = 0.5 between B1 and B2; and A's
    // boundary face x = 0 given as two halves on the boundary (hanging nodes (0,0,0.5), (0,1,0.5))
    Mesh m = make({{{0, 0, 0, 2, 1, 1}}, {{2, 0, 0, 3, 1, 0.5}}, {{2, 0, 0.5, 3, 1, 1}}}, {{{0, 0, 0.5}}, {{0, 1, 0.5}}});
    assert(m.hanging_nodes.size() == 4);
    const std::uint32_t a0 = vid(m, 0, 0, 0), a1 = vid(m, 0, 0, 0.5), a2 = vid(m, 0, 0, 1), b0 = vid(m, 0, 1, 0),
                        b1 = vid(m, 0, 1, 0.5), b2 = vid(m, 0, 1, 1);
    std::size_t replaced = 0;
    for(auto& bf : m.boundary_faces)
      if(bf.patch == 0) { bf.vertices = {{a0, a1, b1, b0}}; ++replaced; }
    assert(replaced == 1);
    m.boundary_faces.push_back({{{a1, a2, b2, b1}}, 0, 0});
    HM::Polyhedral_mesh_3 pm;
    pm.build(m);
    check_closed(m, pm);
    assert(pm.number_of_internal_faces() == 3 && pm.faces.size() == 17);
    assert(patch_sizes(pm) == std::vector<std::size_t>({2, 2, 3, 3, 2, 2}));
    for(std::size_t f = pm.patches[0].start; f < pm.patches[0].start + 2; ++f) assert(pm.faces[f].size() == 4);
    for(std::size_t p : {2, 3})   // A's faces y = 0 and y = 1: midpoints on both their edges x = 0 and x = 2
      for(std::size_t f = pm.patches[p].start; f < pm.patches[p].start + pm.patches[p].size; ++f)
        assert(pm.faces[f].size() == (pm.owner[f] == 0 ? 6u : 4u));
    std::cout << "  split at the other pair of edges, and a boundary face given as two halves: closed cells\n";
  }
  {
    // not a split: A = [0,1]^3 and B = [1,2]x[0,1]x[0,1] share a whole face whose edges z = 0 and
    // z = 1 carry midpoints, from layers of finer cells below and above (which split A's and B's
    // faces z = 0 and z = 1 into quarters)
    std::vector<std::array<double, 6>> boxes = {{{0, 0, 0, 1, 1, 1}}, {{1, 0, 0, 2, 1, 1}}};
    for(double z : {-0.5, 1.0})
      for(double x = 0; x < 2; x += 0.5)
        for(double y = 0; y < 1; y += 0.5) boxes.push_back({{x, y, z, x + 0.5, y + 0.5, z + 0.5}});
    const Mesh m = make(boxes, {});
    HM::Polyhedral_mesh_3 pm;
    pm.build(m);
    check_closed(m, pm);
    std::size_t ab = 0;
    for(std::size_t f = 0; f < pm.number_of_internal_faces(); ++f)
      if(pm.owner[f] == 0 && pm.neighbour[f] == 1) { ++ab; assert(pm.faces[f].size() == 6); }
    assert(ab == 1);
    std::cout << "  whole face with midpoints on two opposite edges and a whole neighbour: not split ("
              << pm.number_of_internal_faces() << " internal faces)\n";
    // with B2 missing (B1's face y = 0.5 now on the boundary), the half of A's face x = 2 facing
    // nothing is neither a face of a cell nor of the boundary: the face is not split, and then it
    // bounds one cell without being a boundary face, an error
    Mesh broken = make({{{0, 0, 0, 2, 1, 1}}, {{2, 0, 0, 3, 0.5, 1}}}, {});
    const auto& h = broken.hexahedra[1];
    broken.boundary_faces.push_back({{{h[3], h[7], h[6], h[2]}}, 1, 3});
    std::string what;
    try { HM::Polyhedral_mesh_3 bad; bad.build(broken); } catch(const std::logic_error& e) { what = e.what(); }
    assert(what.find("not a boundary face") != std::string::npos);
    std::cout << "  half of a coarse face facing no cell: std::logic_error as expected (" << what << ")\n";
  }
  {
    // OpenFOAM's concave cells and the bulge of the hanging nodes written for it. A = [0,2]^3 has
    // its face x = 2 split into quarters by the four cells B = [2,3]x[j,j+1]x[k,k+1]: the quarters
    // are coplanar, so A is concave for OpenFOAM (and only A: the B are cubes)
    std::vector<std::array<double, 6>> boxes = {{{0, 0, 0, 2, 2, 2}}};
    for(double y : {0.0, 1.0})
      for(double z : {0.0, 1.0}) boxes.push_back({{2, y, z, 3, y + 1, z + 1}});
    Mesh m = make(boxes, {});
    assert(m.hanging_nodes.size() == 5);
    HM::Polyhedral_mesh_3 pm;
    pm.build(m);
    auto concave = [&](const auto& points) {
      HM::OpenFOAM_geometry g;
      g.compute(points, pm);
      return HM::concave_cells(pm, g);
    };
    assert(concave(m.points) == std::vector<char>({1, 0, 0, 0, 0}));
    assert(HM::compute_quality(m, pm).number_of_concave_cells() == 1);
    std::size_t n = 99;
    auto x = HM::IO::internal::foam_points(m, 0.01, &pm, 0.2, &n);   // a 1 % roof is enough here
    assert(n == 0 && concave(x) == std::vector<char>(5, 0));
    // a warped face: A's corners (2,0,0) and (2,2,2) pushed to x = 2.3 (and the hanging nodes
    // back at the centres of their masters) make a saddle that the 1 % roof leaves concave; the
    // adaptive bulge raises the node inside the mesh (the face centre) until A is convex, the
    // nodes on the boundary keep 1 %, and no cell falls below its scaled Jacobian
    for(auto& p : m.points)
      if(p == Point_3(2, 0, 0) || p == Point_3(2, 2, 2)) p = Point_3(2.3, p.y(), p.z());
    for(const auto& h : m.hanging_nodes) {
      double c[3] = {0, 0, 0};
      for(int i = 0; i < h.number_of_masters; ++i) {
        const Point_3& q = m.points[h.masters[std::size_t(i)]];
        c[0] += q.x() / h.number_of_masters; c[1] += q.y() / h.number_of_masters; c[2] += q.z() / h.number_of_masters;
      }
      m.points[h.vertex] = Point_3(c[0], c[1], c[2]);
    }
    const auto uniform = HM::IO::internal::foam_points(m, 0.01);
    assert(concave(uniform)[0] == 1);
    x = HM::IO::internal::foam_points(m, 0.01, &pm, 0.2, &n);
    assert(n == 0 && concave(x) == std::vector<char>(5, 0));
    const HM::Mesh_quality q0 = HM::compute_quality(m, pm);
    Mesh bulged = m;
    for(std::size_t v = 0; v < x.size(); ++v) bulged.points[v] = Point_3(x[v][0], x[v][1], x[v][2]);
    const HM::Mesh_quality q1 = HM::compute_quality(bulged, pm);
    for(std::size_t c = 0; c < 5; ++c) assert(q1.scaled_jacobian[c] >= (std::min)(q0.scaled_jacobian[c], 0.3) - 1e-12);
    double centre_rise = 0;
    for(const auto& h : m.hanging_nodes) {
      const std::uint32_t v = h.vertex;
      const double d = std::sqrt(CGAL::to_double(CGAL::squared_distance(m.points[v], Point_3(x[v][0], x[v][1], x[v][2]))));
      const double du = std::sqrt(CGAL::to_double(CGAL::squared_distance(m.points[v], Point_3(uniform[v][0], uniform[v][1], uniform[v][2]))));
      if(h.number_of_masters == 2) assert(std::abs(d - du) < 1e-12);   // on the boundary: as the uniform 1 %
      else centre_rise = d / du;
    }
    assert(centre_rise > 1.4);
    // OpenFOAM's face tets: none on these valid cells; a corner of A's split face pushed beyond B's
    // far side folds the face: its fan and B's centre make inverted tetrahedra
    {
      HM::OpenFOAM_geometry g;
      g.compute(x, pm);
      const auto ft = HM::face_tet_errors(x, pm, g);
      assert(std::count(ft.begin(), ft.end(), char(1)) == 0);
      auto folded = x;
      for(std::size_t v = 0; v < folded.size(); ++v)
        if(m.points[v] == Point_3(2.3, 0, 0)) folded[v][0] = 3.5;
      g.compute(folded, pm);
      const auto ft2 = HM::face_tet_errors(folded, pm, g);
      // the cells-only geometry: the same centres and volumes (bit for bit), the same flags
      HM::OpenFOAM_geometry gc;
      gc.compute_cells(folded, pm);
      assert(gc.face_centres.empty() && gc.face_areas.empty());
      assert(gc.cell_centres == g.cell_centres && gc.cell_volumes == g.cell_volumes);
      assert(HM::face_tet_errors(folded, pm, gc) == ft2);
      std::size_t n_bad = 0;
      for(std::size_t f = 0; f < ft2.size(); ++f) {
        if(!ft2[f]) continue;
        ++n_bad;
        bool has = false;   // every flagged face has the folded corner
        for(auto v : pm.faces[f]) has = has || m.points[v] == Point_3(2.3, 0, 0);
        assert(has);
      }
      assert(n_bad > 0);
      std::cout << "  face tets as OpenFOAM checks them: none on valid cells, " << n_bad << " faces at a folded corner\n";
    }
    std::cout << "  concave cells as OpenFOAM counts them: a face split into coplanar quarters (1 cell); a 1 % "
                 "roof makes it convex; a saddle needs the face centre raised " << centre_rise << " x as much\n";
  }
  {
    // the margin the capture's last repair raises (`hex_concavity_margin()`): 1/sqrt(2) on a cube,
    // and below OpenFOAM's 1e-6 exactly where its concave test (from the faces' centres and area
    // vectors, as `concave_cells()` takes them) calls a hexahedron with whole faces concave, on
    // hexahedra of random shape (the unit cube's corners moved by up to 0.1 to 0.7 along each axis)
    namespace I = HM::internal;
    I::Vec3 cube[8];
    for(int k = 0; k < 8; ++k) {
      const auto& u = HM::hex_corner_offsets()[std::size_t(k)];
      cube[k] = I::Vec3{{double(u[0]), double(u[1]), double(u[2])}};
    }
    assert(std::abs(I::hex_concavity_margin(cube) - std::sqrt(0.5)) < 1e-12);
    CGAL::Random rnd(g_seed + 7);
    int concave = 0, convex = 0;
    double smallest = 1;
    for(int t = 0; t < 4000; ++t) {
      I::Vec3 x[8];
      const double r = rnd.get_double(0.1, 0.7);
      for(int k = 0; k < 8; ++k)
        for(int a = 0; a < 3; ++a) x[k][std::size_t(a)] = cube[k][std::size_t(a)] + rnd.get_double(-r, r);
      std::vector<I::Vec3> fc(6), fa(6);
      for(int k = 0; k < 6; ++k) {
        const auto& f = HM::hex_local_faces()[std::size_t(k)];
        I::foam_face_centre_and_area(4, [&](std::size_t i) { return x[f[i]]; }, fc[std::size_t(k)], fa[std::size_t(k)]);
      }
      const double mg = I::hex_concavity_margin(x);
      const bool c = I::concave_cell(fc, fa);
      if(std::abs(mg - 1e-6) > 1e-12) assert(c == (mg < 1e-6));
      (c ? concave : convex) += 1;
      smallest = (std::min)(smallest, mg);
    }
    assert(concave > 100 && convex > 100);
    std::cout << "  concavity margin: cube " << I::hex_concavity_margin(cube) << ", OpenFOAM's test agreed on "
              << concave << " concave and " << convex << " convex random hexahedra (smallest margin " << smallest << ")\n";
  }
}

// Curvature refinement: cut cells in which the surface normals differ by more than the angle get
// the curvature size. On the cube [-1,1]^3 (flat faces, 90 degree edges) the cut cells whose closed
// box meets an edge see a spread of exactly 90 degrees and those on one face 0; the cut cells at
// the edges are refined to the curvature size, those on a face away from the edges keep the
// surface size.
void test_curvature_refinement()
{
  std::cout << "curvature refinement\n";
  Domain cube("data/cube.off");
  const CGAL::Bbox_3 box(-1.5, -1.5, -1.5, 1.5, 1.5, 1.5);
  // what the criteria see: the spread is measured (curvature size set) but never acted on (180)
  {
    Criteria criteria(0.5, 0.125);
    criteria.set_curvature_size(0.0625, 180);
    std::size_t at_edge = 0, on_face = 0;
    criteria.add_criterion([&](const HM::Cell_3<K>& c) -> Criteria::Is_cell_bad {
      if(!c.is_cut) { assert(c.normal_spread == 0); return {}; }
      const CGAL::Bbox_3 b = c.bbox();
      int touching = 0;   // box planes x, y, z = +-1 the closed box meets
      for(int a = 0; a < 3; ++a) touching += (b.min(a) <= 1 && b.max(a) >= 1) + (b.min(a) <= -1 && b.max(a) >= -1);
      if(touching >= 2) { ++at_edge; assert(std::abs(c.normal_spread - 90) < 1e-9); }
      if(touching == 1) { ++on_face; assert(c.normal_spread == 0); }
      return {};
    });
    Mesh m;
    CGAL::make_hex_mesh_3(cube, criteria, m, HP::body_fitted(false).meshing_box(box));
    std::cout << "  spreads seen: 90 degrees at " << at_edge << " cut cells at edges, 0 at " << on_face << " on faces\n";
    assert(at_edge > 0 && on_face > 0);
  }
  // the estimate is not just the spread around the first normal: a roof of three strips whose
  // middle one (horizontal, listed first, so its normal comes first in every cell it meets) has
  // the others at 50 degrees on either side; the cell meeting all three sees 100 degrees (a
  // spread around the first normal only would be 50)
  {
    const double c = std::cos(50 * CGAL_PI / 180), sn = std::sin(50 * CGAL_PI / 180);
    std::vector<Point_3> pts;
    for(double y : {-1.0, 1.0})
      for(const auto& xz : std::vector<std::array<double, 2>>{{{-0.2 - 0.8 * c, 0.8 * sn}}, {{-0.2, 0}}, {{0.2, 0}}, {{0.2 + 0.8 * c, 0.8 * sn}}})
        pts.emplace_back(xz[0], y, xz[1] + 0.1);   // off the grid plane z = 0
    // point k at y = -1 is k, at y = 1 is k + 4; the middle strip first, then the sides
    std::vector<std::array<std::uint32_t, 3>> tris = {{{1, 2, 6}}, {{1, 6, 5}}, {{0, 1, 5}}, {{0, 5, 4}}, {{2, 3, 7}}, {{2, 7, 6}}};
    Domain roof(pts, tris);
    Criteria criteria(0.5, 0.5);   // cells of 0.5 are asked; the one over x in [-0.25, 0.25] meets all three strips
    criteria.set_curvature_size(0.01, 180);
    double widest = 0;
    criteria.add_criterion([&](const HM::Cell_3<K>& cell) -> Criteria::Is_cell_bad {
      widest = (std::max)(widest, cell.normal_spread);
      return {};
    });
    Mesh m;
    CGAL::make_hex_mesh_3(roof, criteria, m, HP::body_fitted(false).meshing_box(CGAL::Bbox_3(-1.25, -1.25, -1, 1.25, 1.25, 1.5)));
    std::cout << "  roof of three strips at -50, 0, 50 degrees: widest spread seen " << widest << " degrees\n";
    assert(std::abs(widest - 100) < 1e-6);
  }
  // the cut cells the criteria accept (the extra criterion is asked only when no built-in one
  // splits the cell): at the edges they have the curvature size, on a face away from the edges
  // the surface size; without a curvature size, the surface size everywhere
  for(int fine = 0; fine < 2; ++fine) {
    Criteria criteria(0.5, 0.25);
    if(fine) criteria.set_curvature_size(0.0625, 30);
    std::size_t at_edge = 0, mid_face = 0;
    criteria.add_criterion([&](const HM::Cell_3<K>& c) -> Criteria::Is_cell_bad {
      if(!c.is_cut) return {};
      const CGAL::Bbox_3 b = c.bbox();
      int touching = 0;
      double far = 2;   // distance of the box to the nearest plane x, y, z = +-1 it does not meet
      for(int a = 0; a < 3; ++a) {
        const bool lo = b.min(a) <= -1 && b.max(a) >= -1, hi = b.min(a) <= 1 && b.max(a) >= 1;
        touching += lo + hi;
        if(!lo && !hi) far = (std::min)(far, (std::min)(1 - b.max(a), b.min(a) + 1));
      }
      const double e = b.xmax() - b.xmin();
      if(touching >= 2) { ++at_edge; assert(std::abs(e - (fine ? 0.0625 : 0.25)) < 1e-12); }
      if(touching == 1 && far >= 0.6) { ++mid_face; assert(std::abs(e - 0.25) < 1e-12); }
      return {};
    });
    Mesh m;
    CGAL::make_hex_mesh_3(cube, criteria, m, HP::body_fitted(false).meshing_box(box));
    std::cout << "  " << (fine ? "curvature size 0.0625: " : "no curvature size: ") << at_edge
              << " cut cells at the edges accepted at " << (fine ? 0.0625 : 0.25) << ", " << mid_face
              << " on the faces away from them at 0.25\n";
    assert(at_edge > 0 && mid_face > 0);
  }
  // a smooth organic surface: more cells than without, fewer than with the fine size everywhere
  Domain eight("data/eight.off");
  std::size_t n[3];
  for(int k = 0; k < 3; ++k) {
    Criteria criteria(0.1, k == 2 ? 0.0125 : 0.025);
    if(k == 1) criteria.set_curvature_size(0.0125, 30);
    Mesh m;
    CGAL::make_hex_mesh_3(eight, criteria, m, HP::body_fitted(false));
    n[k] = m.number_of_cells();
  }
  std::cout << "  eight: " << n[0] << " cells at 0.025, " << n[1] << " with 0.0125 where it bends by 30 degrees, " << n[2]
            << " at 0.0125\n";
  assert(n[0] < n[1] && n[1] < n[2]);
}

// Thin parts: a plate 0.06 thick, thinner than the surface size. The thickness the criteria see
// at the cells cut by its large faces is the plate's; refining to 3 cells across gives a staircase
// inside the plate, without it no cell lies inside.
void test_thin_part_refinement()
{
  std::cout << "thin-part refinement\n";
  std::ofstream("tmp_plate.off") << "OFF\n8 12 0\n"
                                    "-0.5 -0.5 -0.03\n0.5 -0.5 -0.03\n0.5 0.5 -0.03\n-0.5 0.5 -0.03\n"
                                    "-0.5 -0.5 0.03\n0.5 -0.5 0.03\n0.5 0.5 0.03\n-0.5 0.5 0.03\n"
                                    "3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n"
                                    "3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";
  Domain plate("tmp_plate.off");
  const CGAL::Bbox_3 box(-0.75, -0.75, -0.52, 0.75, 0.75, 0.48);   // the plate off the grid planes
  {
    // measured (cells of 1/32 > 0.001) but never acted on (1 cell across: 1/32 < 0.06)
    Criteria criteria(0.25, 0.03125);
    criteria.set_thin_part_refinement(1, 0.001);
    std::size_t seen = 0;
    criteria.add_criterion([&](const HM::Cell_3<K>& c) -> Criteria::Is_cell_bad {
      const CGAL::Bbox_3 b = c.bbox();
      if(!c.is_cut) { assert(std::isinf(c.thickness)); return {}; }
      if(b.xmin() > -0.4 && b.xmax() < 0.4 && b.ymin() > -0.4 && b.ymax() < 0.4) {
        ++seen;
        assert(std::abs(c.thickness - 0.06) < 1e-9);
      }
      return {};
    });
    Mesh m;
    CGAL::make_hex_mesh_3(plate, criteria, m, HP::body_fitted(false).meshing_box(box));
    std::cout << "  thickness 0.06 seen at " << seen << " cut cells of the large faces\n";
    assert(seen > 0);
  }
  double vol[2] = {0, 0};
  for(int thin = 0; thin < 2; ++thin) {
    Criteria criteria(0.25, 0.125);
    if(thin) criteria.set_thin_part_refinement(3, 0.01);
    Mesh m;
    CGAL::make_hex_mesh_3(plate, criteria, m, HP::body_fitted(false).meshing_box(box));
    for(const auto& c : m.hexahedra)
      vol[thin] += (m.points[c[6]].x() - m.points[c[0]].x()) * (m.points[c[6]].y() - m.points[c[0]].y()) *
                   (m.points[c[6]].z() - m.points[c[0]].z());
    std::cout << "  " << (thin ? "3 cells across, down to 0.01: " : "no thin-part refinement: ") << m.number_of_cells()
              << " cells, volume " << vol[thin] << " (plate 0.06)\n";
    if(thin) check_mesh(m, "plate");
  }
  assert(vol[0] == 0 && vol[1] > 0.5 * 0.06 && vol[1] < 0.06);
}

// the joint moves' step direction (`internal::project_direction()`): the direction closest to -g
// along which no constrained value falls at first order. Against an independent computation: the
// optimum is the projection of -g onto the orthogonal complement of some subset of the rows (a
// face of the cone), the closest such projection that satisfies every row.
// border edges along another border edge are a seam (sealed); the borders of a hole are not
void test_sealed_border_edges()
{
  namespace HI = CGAL::Hex_meshing_3::internal;
  {
    // the holes' loop walk: two triangular loops touching at vertex 0 (a figure eight), the walk
    // passing through 0 in the middle of the first loop it takes; a chain that does not close
    std::cout << "loops of border edges\n";
    const std::vector<std::array<int, 2>> eight = {{{1, 2}}, {{2, 0}}, {{0, 3}}, {{3, 4}}, {{4, 0}}, {{0, 1}}};
    std::vector<std::vector<std::size_t>> loops;
    auto tail = [&](std::size_t i) { return eight[i][0]; };
    auto head = [&](std::size_t i) { return eight[i][1]; };
    assert(HI::split_into_loops(eight.size(), tail, head, loops));
    assert(loops == (std::vector<std::vector<std::size_t>>{{2, 3, 4}, {5, 0, 1}}));
    assert(!HI::split_into_loops(2, tail, head, loops));   // 1 -> 2 -> 0: a dead end
    // a square folded flat spans no area; a 1 x 20 rectangle does (the limit is 1 x 119)
    assert(!HI::spans_an_area(0.0, 4.0) && HI::spans_an_area(20.0 * 20.0, 42.0) && !HI::spans_an_area(120.0 * 120.0, 242.0));
  }
  std::cout << "sealed border edges\n";
  typedef K::Segment_3 S;
  const Point_3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0), e(2, 0, 0), f(2, 1, 0);
  // two unit squares side by side, each with its own copy of the line x = 1 (indices 4, 5 and 6,
  // 7: the same points); the right one's copy split in two (a T-junction), and a slot of
  // 0.01 between x = 1 and the edge (1.01, 0)-(1.01, 1) of index 8-9
  std::vector<S> segs{S(a, b), S(b, c), S(c, d), S(d, a),                          // 0-3: left square (0 1 2 3)
                      S(b, Point_3(1, 0.4, 0)), S(Point_3(1, 0.4, 0), c),          // 4, 5: right copy of x = 1
                      S(e, f),                                                      // 6: far edge
                      S(Point_3(1.5, 0.2, 0), Point_3(1.5, 0.8, 0))};              // 7: alone
  std::vector<std::array<std::uint32_t, 2>> ends{{{0, 1}}, {{1, 2}}, {{2, 3}}, {{3, 0}},
                                                 {{4, 10}}, {{10, 5}}, {{6, 7}}, {{8, 9}}};
  const std::vector<char> sealed = HI::sealed_border_edges<K>(segs, ends, 0.01);
  // the left square's x = 1 edge lies on the right copy and the copy on it; nothing else is sealed
  // (edges 0 and 2 touch the copy only at their ends, which share no index but lie beyond
  // a quarter of their length from their midpoints)
  const std::vector<char> expected{0, 1, 0, 0, 1, 1, 0, 0};
  for(std::size_t i = 0; i < segs.size(); ++i) {
    if(sealed[i] != expected[i]) std::cerr << "edge " << i << " sealed " << int(sealed[i]) << '\n';
    assert(sealed[i] == expected[i]);
  }
  // a crack 0.005 wide is sealed at tolerance 0.01, not at 0.001
  std::vector<S> crack{S(a, b), S(Point_3(0, 0.005, 0), Point_3(1, 0.005, 0))};
  std::vector<std::array<std::uint32_t, 2>> crack_ends{{{0, 1}}, {{2, 3}}};
  assert((HI::sealed_border_edges<K>(crack, crack_ends, 0.01) == std::vector<char>{1, 1}));
  assert((HI::sealed_border_edges<K>(crack, crack_ends, 0.001) == std::vector<char>{0, 0}));
  // edges sharing an index never seal each other (a hole's border folding back on itself)
  std::vector<S> fold{S(a, b), S(b, Point_3(0, 0.001, 0))};
  std::vector<std::array<std::uint32_t, 2>> fold_ends{{{0, 1}}, {{1, 2}}};
  assert((HI::sealed_border_edges<K>(fold, fold_ends, 0.01) == std::vector<char>{0, 0}));
}

void test_project_direction()
{
  namespace HI = CGAL::Hex_meshing_3::internal;
  std::cout << "projected step direction\n";
  {
    // -g = (1, 0, 0), one row a = (-1, 1, 0): a . d >= 0 means d_y >= d_x; the answer is (0.5, 0.5, 0)
    std::vector<HI::Vec3> g{{{-1, 0, 0}}}, ga{{{-1, 1, 0}}};
    HI::project_direction(g, ga, 1, 1);
    assert(std::abs(g[0][0] + 0.5) < 1e-9 && std::abs(g[0][1] + 0.5) < 1e-9 && std::abs(g[0][2]) < 1e-12);
    // a row -g already satisfies changes nothing
    std::vector<HI::Vec3> g2{{{-1, 0, 0}}}, ga2{{{1, 1, 0}}};
    HI::project_direction(g2, ga2, 1, 1);
    assert(g2[0][0] == -1 && g2[0][1] == 0 && g2[0][2] == 0);
  }
  CGAL::Random rnd(g_seed);
  double worst_violation = 0, worst_gap = 0;
  for(int trial = 0; trial < 300; ++trial) {
    // (get_int's upper bound is excluded: 1-5 vertices, 0-5 rows; the sweeps far beyond the
    // capture's 200, so that the algorithm's optimum is what is checked)
    const std::size_t n = 1 + std::size_t(rnd.get_int(0, 5)), m = std::size_t(rnd.get_int(0, 6));
    std::vector<HI::Vec3> g(n), ga(m * n);
    for(auto& v : g) for(int a = 0; a < 3; ++a) v[a] = rnd.get_double(-1, 1);
    for(auto& v : ga) for(int a = 0; a < 3; ++a) v[a] = rnd.get_double(-1, 1);
    std::vector<HI::Vec3> d = g;
    HI::project_direction(d, ga, m, n, 20000);
    for(auto& v : d) v = HI::mul(v, -1);
    // flattened vectors of size 3n
    auto flat = [&](const std::vector<HI::Vec3>& v, std::size_t first) {
      std::vector<double> f(3 * n);
      for(std::size_t i = 0; i < n; ++i) for(int a = 0; a < 3; ++a) f[3 * i + std::size_t(a)] = v[first + i][a];
      return f;
    };
    auto dotv = [](const std::vector<double>& a, const std::vector<double>& b) {
      double s = 0;
      for(std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
      return s;
    };
    std::vector<double> mg = flat(g, 0), fd = flat(d, 0);
    for(double& x : mg) x = -x;
    std::vector<std::vector<double>> rows;
    for(std::size_t k = 0; k < m; ++k) rows.push_back(flat(ga, k * n));
    const double scale = std::sqrt(dotv(mg, mg));
    for(const auto& r : rows) {
      const double viol = -dotv(r, fd) / (scale * std::sqrt(dotv(r, r)));
      worst_violation = (std::max)(worst_violation, viol);
      // (Hildreth's method converges slowly where rows are nearly dependent: seed 20261122 has
      // one case in 300 at 7e-4 after 20000 sweeps; a wrong projection is off by order 1)
      assert(viol <= 2e-3);
    }
    // brute force over the subsets of rows: Gram-Schmidt basis of their span, -g minus its
    // projection on it; the closest candidate that satisfies every row
    auto remove_span = [&](std::vector<double>& v, const std::vector<std::vector<double>>& basis) {
      for(const auto& b : basis) { const double c = dotv(v, b); for(std::size_t i = 0; i < v.size(); ++i) v[i] -= c * b[i]; }
    };
    auto distance_to_mg = [&](const std::vector<double>& v) {
      double s = 0;
      for(std::size_t i = 0; i < v.size(); ++i) s += (v[i] - mg[i]) * (v[i] - mg[i]);
      return std::sqrt(s);
    };
    double best = std::numeric_limits<double>::max();
    for(unsigned mask = 0; mask < (1u << m); ++mask) {
      std::vector<std::vector<double>> basis;
      for(std::size_t k = 0; k < m; ++k) {
        if(!(mask & (1u << k))) continue;
        std::vector<double> r = rows[k];
        remove_span(r, basis);
        const double l = std::sqrt(dotv(r, r));
        if(l > 1e-9) { for(double& x : r) x /= l; basis.push_back(r); }
      }
      std::vector<double> c = mg;
      remove_span(c, basis);
      bool ok = true;
      for(const auto& r : rows) ok = ok && dotv(r, c) >= -1e-9 * scale * std::sqrt(dotv(r, r));
      if(ok) best = (std::min)(best, distance_to_mg(c));
    }
    worst_gap = (std::max)(worst_gap, (distance_to_mg(fd) - best) / scale);
    assert(distance_to_mg(fd) <= best + 1e-6 * scale);
  }
  std::cout << "  300 random cases: worst violation " << worst_violation << " |a| |g|, worst excess distance "
            << worst_gap << " |g|\n";
}

// Body-fitted boundary: buffer layer, projection, feature snapping, untangling. Validity is
// asserted independently (Verdict scaled Jacobian of every cell, closed polyhedral cells of
// positive volume); the cube's boundary must lie on the cube, with its 8 corners and 12 edges.
void test_body_fitted()
{
  typedef HM::Feature_curves_3<K> Features;
  std::cout << "body-fitted boundary\n";
  for(const char* file : {"data/cube.off", "data/eight.off", "data/fandisk.off"}) {
    Domain d(file);
    Features f(d);
    const CGAL::Bbox_3 bb = d.bbox();
    const double ext = (std::max)({bb.xmax() - bb.xmin(), bb.ymax() - bb.ymin(), bb.zmax() - bb.zmin()});
    const double s = ext / 40;
    Mesh m;
    HM::Meshing_statistics st;
    CGAL::make_hex_mesh_3(d, Criteria(ext / 10, s), m, HP::statistics(&st).feature_curves(&f));
    assert(m.number_of_cells() > 0 && st.buffer_cells > 0);
    HM::Polyhedral_mesh_3 pm;
    pm.build(m);
    HM::OpenFOAM_geometry g;
    g.compute(m.points, pm);
    std::vector<std::array<double, 3>> closure(m.number_of_cells(), {{0, 0, 0}});
    for(std::size_t i = 0; i < pm.faces.size(); ++i)
      for(int a = 0; a < 3; ++a) {
        closure[pm.owner[i]][a] += g.face_areas[i][a];
        if(i < pm.neighbour.size()) closure[pm.neighbour[i]][a] -= g.face_areas[i][a];
      }
    auto cell_sj = [](const Mesh& mesh, std::size_t c) {
      std::array<Point_3, 8> p;
      for(int k = 0; k < 8; ++k) p[k] = mesh.points[mesh.hexahedra[c][k]];
      return HM::scaled_jacobian(p);
    };
    double qmin = 1;
    std::size_t poor = 0;   // cells below 0.1
    for(std::size_t c = 0; c < m.number_of_cells(); ++c) {
      const double q = cell_sj(m, c);
      qmin = (std::min)(qmin, q);
      if(q < 0.1) ++poor;
      assert(g.cell_volumes[c] > 0);
      for(int a = 0; a < 3; ++a) assert(std::abs(closure[c][a]) < 1e-9 * ext * ext);
    }
    assert(qmin > 0);
    // surface faces on the input: on average within 0.15 x the surface size (the goal is 0.25 x for every face)
    const HM::Boundary_fidelity bf = HM::boundary_fidelity(m, d, 2000);
    const HM::Feature_fidelity ff = HM::feature_fidelity(m, d, f);
    std::cout << "  " << file << ": " << m.number_of_cells() << " cells (" << st.buffer_cells << " buffer), min SJ "
              << qmin << ", faces->input mean " << bf.mean_face_distance / s << " max " << bf.max_face_distance / s
              << ", input->mesh max " << bf.max_sample_distance / s << ", features both ways " << ff.input_to_mesh / s
              << " / " << ff.mesh_to_input / s << ", corners " << ff.max_corner_distance / s << " (x surface size); "
              << st.curves_captured << " curves captured, " << st.curves_missed << " missed, "
              << st.unreached_vertices.size() << " vertices off the surface; staircase tries " << st.staircase_tries
              << ", gap " << st.staircase_gap << "\n";
    // the capture removes buffer cells below 0.02 and releases few vertices; cells below 0.1 are
    // rare (fandisk: 1 of 3799 buffer cells; 25 before the shape energy)
    assert(qmin >= 0.02 && st.unreached_vertices.size() <= 20);
    assert(poor * 200 <= st.buffer_cells);
    // fandisk: 31 of its 35 curves; its worst corner 0.38 x surface size, 1.92 since feature paths
    // may stray 6 local sizes from their curve where none keeps within 3 (at this coarse size a
    // corner of a missed curve, (0.46, 0.256, 0.308), is left off; at the tests' sizes, with
    // --thin-cells 5, its worst corner went from 0.49 to 0.45); 2.21 since the mesh is made again
    // with the staircase closer to the surface where faces stand off it (the one kept, at 0.25
    // cell sizes: 25 faces beyond s/4 instead of 32, features input->mesh 3.4 s instead of 5.1);
    // since released curve vertices go back to their curve, the first (at 0.4 cell sizes) is kept
    // again: 32 far faces, min 0.314, features 3.65 / 8.47 s (3.42 / 8.56 with the one at 0.25,
    // min 0.340), corners 1.85 s, and all three are still made
    // (flat cells counted as inverted, 2026-12-06: its first mesh leaves 11 cells below 0.3, so
    // the staircase is not tried again - one unlucky sample, see the manual's "Round-off decides
    // some figures": shifted by 1e-9 of its diagonal it makes all three; eight makes them)
    if(std::string(file) == "data/fandisk.off")
      assert(st.curves_captured >= 31 && ff.max_corner_distance <= 2.4 * s);
    if(std::string(file) == "data/eight.off")
      assert(st.staircase_tries == 3);
    assert(bf.mean_face_distance <= 0.15 * s);
    // the faces beyond 1/4 surface size with their causes (`far_faces()`): all of them, farthest
    // first; the point given is the face's corner or centre named as its farthest, at that
    // distance from the input; a corner cause says whether that corner is a hanging node
    {
      const std::vector<HM::Far_face> far = HM::far_faces(m, bf, 0.25 * s);
      std::size_t n = 0;
      for(const auto& fd : bf.face_distances) n += fd.first > 0.25 * s;
      assert(far.size() == n && bf.face_indices.size() == bf.face_distances.size() &&
             bf.face_worst_points.size() == bf.face_distances.size());
      std::vector<char> hanging(m.points.size(), 0);
      for(const auto& h : m.hanging_nodes) hanging[h.vertex] = 1;
      std::size_t by_cause[5] = {0, 0, 0, 0, 0};
      for(std::size_t i = 0; i < far.size(); ++i) {
        assert(i == 0 || far[i - 1].distance >= far[i].distance);
        const auto& q = m.boundary_faces[far[i].face].vertices;
        int corner = -1;
        for(int k = 0; k < 4; ++k)
          if(std::abs(CGAL::to_double(m.points[q[k]].x()) - far[i].at[0]) == 0 && std::abs(CGAL::to_double(m.points[q[k]].y()) - far[i].at[1]) == 0 &&
             std::abs(CGAL::to_double(m.points[q[k]].z()) - far[i].at[2]) == 0)
            corner = k;
        const Point_3 at(far[i].at[0], far[i].at[1], far[i].at[2]);
        assert(std::abs(std::sqrt(CGAL::to_double(d.squared_distance(at))) - far[i].distance) <= 1e-12 * ext);
        switch(far[i].cause) {
        case HM::Far_face_cause::HANGING_CORNER: assert(corner >= 0 && hanging[q[corner]]); break;
        case HM::Far_face_cause::CAP_CORNER: assert(false); break;   // (closed inputs: no border edge)
        case HM::Far_face_cause::CORNER: assert(corner >= 0 && !hanging[q[corner]]); break;
        case HM::Far_face_cause::FOLDED: assert(far[i].fold > 30); break;
        case HM::Far_face_cause::BENT: assert(far[i].fold <= 30); break;
        }
        assert(far[i].size > 0);
        ++by_cause[int(far[i].cause)];
      }
      std::cout << "  " << file << ": " << far.size() << " faces beyond 0.25 x surface size: " << by_cause[0]
                << " at a hanging corner, " << by_cause[2] << " at another corner, " << by_cause[3] << " folded, "
                << by_cause[4] << " bent\n";
    }
    // the last step, the polish of the cells below 0.35 and its joint moves: against the same run
    // without them, the minimum below 0.35 and the count of cells under 0.35 are no worse, and
    // the count falls (eight: min 0.2346 -> 0.2349, cells under 0.35 39 -> 20; fandisk: 0.105 ->
    // 0.123, 31 -> 19)
    auto below = [&](const Mesh& mesh, double& qmin_out) {
      std::size_t n = 0;
      qmin_out = 1;
      for(std::size_t c = 0; c < mesh.number_of_cells(); ++c) {
        const double q = cell_sj(mesh, c);
        qmin_out = (std::min)(qmin_out, q);
        if(q < 0.35) ++n;
      }
      return n;
    };
    // (both made once, from the same staircase: `capture_retry_cells(0)`, as without the polish,
    // which runs no retry)
    if(std::string(file) != "data/cube.off") {
      Mesh rough, polished;
      HM::Meshing_statistics st0, st1;
      CGAL::make_hex_mesh_3(d, Criteria(ext / 10, s), rough, HP::statistics(&st0).feature_curves(&f).polish_worst_cells(false));
      CGAL::make_hex_mesh_3(d, Criteria(ext / 10, s), polished, HP::statistics(&st1).feature_curves(&f).capture_retry_cells(0));
      assert(st0.staircase_tries == 1 && st1.staircase_tries == 1 && st0.capture_tries == 1 && st1.capture_tries == 1);
      double q0 = 1, q1 = 1;
      const std::size_t n0 = below(rough, q0), n1 = below(polished, q1);
      std::cout << "    polish: " << st1.polish_moves << " moves, " << st1.polish_patches << " joint moves; min SJ " << q0 << " -> " << q1 << ", cells under 0.35 "
                << n0 << " -> " << n1 << "\n";
      assert(st0.polish_moves == 0 && st1.polish_moves > 0);
      // the cleanup after it (buffer cells below 0.02 or at faces skewed beyond 3.5) removes no more
      assert(st1.removed_buffer_cells <= st0.removed_buffer_cells);
      assert(q1 >= (std::min)(q0, 0.35) - 1e-12 && n1 <= n0);
      assert(n1 < n0);   // and it does something
      // fandisk's worst cell needed joint moves (`polish_patches()`): one vertex at a time left it
      // at 0.105, its patch raised it to 0.123 (0.077 -> 0.132 at stop 66); since the corners'
      // edges are kept for the curves leaving along them (stop 67, `corner_edge_cosine`) its
      // worst cell is 0.154 before the polish, which keeps it there: the joint moves still run.
      // eight's worst cell rises (0.247 -> 0.261)
      if(std::string(file) == "data/fandisk.off") assert(st1.polish_patches > 0);
      if(std::string(file) == "data/eight.off") assert(q1 > q0);
    }
    if(std::string(file) == "data/cube.off") {
      // every vertex reached the cube; its corners and edges are in the mesh exactly
      assert(st.unreached_vertices.empty() && st.corner_vertices == 8 && st.curves_captured == 12);
      assert(bf.max_face_distance < 1e-9 && bf.max_sample_distance < 1e-9);
      assert(ff.max_corner_distance < 1e-9 && ff.input_to_mesh < 1e-9 && ff.mesh_to_input < 1e-9);
      assert(qmin > 0.5);
    }
  }
}

// a user feature line on a face of the cube, oblique to the grid: followed by a chain of mesh
// edges, its ends are mesh vertices
void test_body_fitted_user_line()
{
  std::cout << "body-fitted boundary with a user feature line\n";
  Domain d("data/cube.off");
  HM::Feature_curves_3<K> f(d);
  const Point_3 a(-0.5, -0.7, 1), b(0.55, 0.6, 1);
  d.add_feature_polylines({{a, Point_3(0, -0.05, 1), b}});
  Mesh m;
  HM::Meshing_statistics st;
  CGAL::make_hex_mesh_3(d, Criteria(0.25, 0.0625), m, HP::statistics(&st).feature_curves(&f));
  std::cout << "  " << st.curves_captured << " curves captured, " << st.corner_vertices << " corners, "
            << st.curve_vertices << " curve vertices, " << st.curves_missed << " missed\n";
  assert(st.curves_captured == 13 && st.corner_vertices == 10 && st.curves_missed == 0);
  double da = 1e300, db = 1e300;
  for(const Point_3& p : m.points) {
    da = (std::min)(da, CGAL::to_double(CGAL::squared_distance(p, a)));
    db = (std::min)(db, CGAL::to_double(CGAL::squared_distance(p, b)));
  }
  assert(da < 1e-20 && db < 1e-20);
  double qmin = 1;
  for(const auto& h : m.hexahedra) {
    std::array<Point_3, 8> p;
    for(int k = 0; k < 8; ++k) p[k] = m.points[h[k]];
    qmin = (std::min)(qmin, HM::scaled_jacobian(p));
  }
  std::cout << "  ends are mesh vertices; min scaled Jacobian " << qmin << "\n";
  assert(qmin > 0);

  // cancelled during the capture: the sweeps stop, the mesh is still valid
  struct Capture_stopper
  {
    std::string phase;
    int polls_in_capture = 0;
    void on_phase_begin(const char* n, std::size_t) { phase = n; }
    void on_phase_end(const char*) {}
    bool go_further(double) { if(phase != "capture") return true; ++polls_in_capture; return false; }
  } stop;
  Domain e("data/eight.off");
  Mesh mc;
  const HM::Status s = CGAL::make_hex_mesh_3(e, Criteria(0.25, 0.0625), mc, HP::body_fitted(true).visitor(std::ref(stop)));
  assert(s == HM::Status::CANCELED && stop.polls_in_capture == 1 && mc.number_of_cells() > 0);
  HM::Polyhedral_mesh_3 pm;
  pm.build(mc);
  const HM::Mesh_quality q = HM::compute_quality(mc, pm);
  std::cout << "  cancelled in the capture: " << mc.number_of_cells() << " cells, min scaled Jacobian "
            << HM::Mesh_quality::range(q.scaled_jacobian).min << "\n";
  assert(q.number_of_inverted_cells() == 0);

  // a visitor that throws during the capture (while the capture holds the points apart): the
  // exception reaches the caller, and the mesh keeps a point for every vertex its cells use
  struct Capture_thrower
  {
    std::string phase;
    void on_phase_begin(const char* n, std::size_t) { phase = n; }
    void on_phase_end(const char*) {}
    bool go_further(double) { if(phase == "capture") throw std::runtime_error("stop"); return true; }
  } thrower;
  Mesh mt;
  bool thrown = false;
  try {
    CGAL::make_hex_mesh_3(e, Criteria(0.25, 0.0625), mt, HP::body_fitted(true).visitor(std::ref(thrower)));
  } catch(const std::runtime_error&) { thrown = true; }
  assert(thrown && mt.number_of_cells() > 0);
  std::size_t used = 0;
  for(const auto& h : mt.hexahedra) for(auto v : h) used = (std::max)(used, std::size_t(v) + 1);
  std::cout << "  a visitor throwing in the capture: " << mt.number_of_cells() << " cells, " << mt.points.size()
            << " points (" << used << " used)\n";
  assert(mt.points.size() >= used);
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
  test_curvature_refinement();
  test_thin_part_refinement();
  test_readers_and_errors();
  test_dirty_input();
  test_features();
  test_feature_fidelity();
  test_polyhedral_half_splits();
  test_sealed_border_edges();
  test_project_direction();
  test_body_fitted();
  test_body_fitted_user_line();
  std::cout << "all checks passed\n";
  return EXIT_SUCCESS;
}
