// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: AGPL-3.0-or-later
// (links TetGen 1.5, AGPL-3.0: this program is benchmark code only, never part of the package)
// Author(s)     : Hex_meshing_3 developers
//
// tet_baselines MESHER INPUT H [--boundary OUT.off] [--msh OUT.msh]
//
// The tetrahedral baselines of the benchmark suite, at the resolution H (an edge length):
//   mesh3            CGAL Mesh_3 on the input as a polyhedral domain with its sharp edges (60
//                    degrees) protected: edge size H, facet size H/sqrt(3), facet distance H/10,
//                    facet angle 25, cell size H*sqrt(6)/4, radius-edge ratio 3; perturbation and
//                    exudation on (the defaults);
//   tetgen           TetGen -pq1.2/15 -a(H^3/(6 sqrt 2)) on the input's triangles as they are;
//   tetgen-remeshed  the same on the input first remeshed to edge length H (CGAL's
//                    isotropic_remeshing, 3 iterations, sharp edges (60 degrees) constrained).
// mesh3 and tetgen-remeshed need the input as a polygon mesh (after CGAL's soup repair and
// orientation): otherwise a clear error. An open one is meshed anyway ("closed_input": false):
// what the mesher then does is the result.
// Prints one JSON object: status ("ok", or "error" with a message), elements, vertices, seconds
// (meshing only: reading, remeshing and measuring apart), remeshing seconds and triangles, longest
// and shortest edge, dihedral angles (min, max, histogram over [0, 180] in 18 bins), radius-edge
// ratio (circumradius over shortest edge: min, mean, max, histogram over [0.6, 3.0] in 12 bins,
// last bin open), boundary triangles; with --boundary, writes the boundary triangles as OFF (the
// suite measures every mesher's boundary against the input with the same tool); with --msh, writes
// the tetrahedra as Gmsh MSH 2.2 (ASCII; the suite converts it with OpenFOAM's gmshToFoam and
// judges it with checkMesh, as it does the hexahedral meshes). Exit codes: 0 a
// mesh (possibly empty: "elements": 0 is a silent failure of the mesher, reported as such), 2 a
// clear error (unreadable input, not a closed polygon mesh where one is needed, an exception).
#define TETLIBRARY
#include <tetgen.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_polyhedron_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Hex_meshing_3/IO/read_surface.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Surface_mesh;
namespace PMP = CGAL::Polygon_mesh_processing;

struct Tets
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 4>> tets;
  std::vector<std::array<std::size_t, 3>> boundary;
  double seconds = 0;
};

static double since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// the input as a consistently oriented triangle mesh (a clear error if it is not a polygon mesh
// after CGAL's soup repair); `closed` tells whether it has no border edge. An open one is still
// given to the mesher: what the mesher does with it is what the robustness table records.
static Surface_mesh as_mesh(const std::vector<Point_3>& points, const std::vector<std::array<std::uint32_t, 3>>& tris, bool& closed)
{
  std::vector<Point_3> pts = points;
  std::vector<std::vector<std::size_t>> polys;
  for(const auto& t : tris) polys.push_back({t[0], t[1], t[2]});
  PMP::repair_polygon_soup(pts, polys);
  PMP::orient_polygon_soup(pts, polys);
  if(!PMP::is_polygon_soup_a_polygon_mesh(polys)) throw std::runtime_error("the input is not a polygon mesh (non-manifold after repair)");
  Surface_mesh sm;
  PMP::polygon_soup_to_polygon_mesh(pts, polys, sm);
  closed = CGAL::is_closed(sm);
  return sm;
}

static Tets run_mesh3(const Surface_mesh& sm, double h)
{
  typedef CGAL::Mesh_polyhedron_3<K>::type Polyhedron;
  typedef CGAL::Polyhedral_mesh_domain_with_features_3<K, Polyhedron> Domain;
  typedef CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type Tr;
  typedef CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index> C3t3;
  typedef CGAL::Mesh_criteria_3<Tr> Criteria;
  namespace params = CGAL::parameters;
  Polyhedron poly;
  CGAL::copy_face_graph(sm, poly);
  const auto t0 = std::chrono::steady_clock::now();
  Domain domain(poly);
  domain.detect_features(60);
  Criteria criteria(params::edge_size = h, params::facet_angle = 25, params::facet_size = h / std::sqrt(3.0),
                    params::facet_distance = h / 10, params::cell_radius_edge_ratio = 3,
                    params::cell_size = h * std::sqrt(6.0) / 4);
  C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria);
  Tets r;
  r.seconds = since(t0);
  std::map<Tr::Vertex_handle, std::size_t> index;
  auto id = [&](Tr::Vertex_handle v) {
    auto it = index.find(v);
    if(it != index.end()) return it->second;
    const Point_3 p = c3t3.triangulation().point(v).point();
    r.points.push_back({{p.x(), p.y(), p.z()}});
    return index[v] = r.points.size() - 1;
  };
  for(auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
    r.tets.push_back({{id(c->vertex(0)), id(c->vertex(1)), id(c->vertex(2)), id(c->vertex(3))}});
  for(auto f = c3t3.facets_in_complex_begin(); f != c3t3.facets_in_complex_end(); ++f) {
    std::array<std::size_t, 3> t;
    for(int k = 0, j = 0; k < 4; ++k)
      if(k != f->second) t[std::size_t(j++)] = id(f->first->vertex(k));
    r.boundary.push_back(t);
  }
  return r;
}

static Tets run_tetgen(const std::vector<Point_3>& points, const std::vector<std::array<std::size_t, 3>>& tris, double h)
{
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = int(points.size());
  in.pointlist = new REAL[3 * points.size()];
  for(std::size_t i = 0; i < points.size(); ++i) {
    in.pointlist[3 * i] = points[i].x(); in.pointlist[3 * i + 1] = points[i].y(); in.pointlist[3 * i + 2] = points[i].z();
  }
  in.numberoffacets = int(tris.size());
  in.facetlist = new tetgenio::facet[tris.size()];
  for(std::size_t i = 0; i < tris.size(); ++i) {
    tetgenio::facet& f = in.facetlist[i];
    f.numberofpolygons = 1;
    f.polygonlist = new tetgenio::polygon[1];
    f.numberofholes = 0;
    f.holelist = nullptr;
    f.polygonlist[0].numberofvertices = 3;
    f.polygonlist[0].vertexlist = new int[3];
    for(int k = 0; k < 3; ++k) f.polygonlist[0].vertexlist[k] = int(tris[i][std::size_t(k)]);
  }
  std::ostringstream sw;
  sw.precision(9);
  sw << "pq1.2/15a" << h * h * h / (6 * std::sqrt(2.0)) << "Q";
  std::string sws = sw.str();
  const auto t0 = std::chrono::steady_clock::now();
  try {
    tetrahedralize(&sws[0], &in, &out);
  } catch(int code) {
    throw std::runtime_error("TetGen stopped with error code " + std::to_string(code));
  }
  Tets r;
  r.seconds = since(t0);
  for(int i = 0; i < out.numberofpoints; ++i)
    r.points.push_back({{out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]}});
  for(int i = 0; i < out.numberoftetrahedra; ++i)
    r.tets.push_back({{std::size_t(out.tetrahedronlist[4 * i]), std::size_t(out.tetrahedronlist[4 * i + 1]),
                       std::size_t(out.tetrahedronlist[4 * i + 2]), std::size_t(out.tetrahedronlist[4 * i + 3])}});
  for(int i = 0; i < out.numberoftrifaces; ++i)
    r.boundary.push_back({{std::size_t(out.trifacelist[3 * i]), std::size_t(out.trifacelist[3 * i + 1]), std::size_t(out.trifacelist[3 * i + 2])}});
  return r;
}

typedef std::array<double, 3> V;
static V sub(const V& a, const V& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
static V cross(const V& a, const V& b) { return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}}; }
static double dot(const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double norm(const V& a) { return std::sqrt(dot(a, a)); }

// the JSON line is gathered here and printed once at the end, so that anything a mesher prints to
// stdout meanwhile cannot split it
static std::string g_json;
template <typename... Args>
static void out(const char* format, Args... args)
{
  char buf[4096];
  std::snprintf(buf, sizeof buf, format, args...);
  g_json += buf;
}

static std::string hist_json(const std::vector<std::size_t>& h)
{
  std::string s = "[";
  for(std::size_t i = 0; i < h.size(); ++i) s += (i ? ", " : "") + std::to_string(h[i]);
  return s + "]";
}

int main(int argc, char** argv)
{
  if(argc < 4) {
    std::cerr << "usage: tet_baselines mesh3|tetgen|tetgen-remeshed INPUT H [--boundary OUT.off] [--msh OUT.msh]\n";
    return 1;
  }
  const std::string mesher = argv[1], input = argv[2];
  const double h = std::atof(argv[3]);
  std::string boundary_file, msh_file;
  for(int i = 4; i + 1 < argc; ++i) {
    if(std::string(argv[i]) == "--boundary") boundary_file = argv[i + 1];
    if(std::string(argv[i]) == "--msh") msh_file = argv[i + 1];
  }
  out("{\"mesher\": \"%s\", \"h\": %.9g", mesher.c_str(), h);
  try {
    if(!(h > 0)) throw std::runtime_error("H must be positive");
    CGAL::Hex_meshing_3::IO::Surface_soup<Point_3> soup;
    CGAL::Hex_meshing_3::IO::read_surface(input, soup);
    Tets r;
    bool closed = true;
    if(mesher == "mesh3") {
      const Surface_mesh sm = as_mesh(soup.points, soup.triangles, closed);
      out(", \"closed_input\": %s", closed ? "true" : "false");
      if(!closed) std::cerr << "tet_baselines: the input is open; meshing it anyway\n";
      r = run_mesh3(sm, h);
    } else if(mesher == "tetgen") {
      std::vector<std::array<std::size_t, 3>> tris;
      for(const auto& t : soup.triangles) tris.push_back({{t[0], t[1], t[2]}});
      r = run_tetgen(soup.points, tris, h);
    } else if(mesher == "tetgen-remeshed") {
      Surface_mesh sm = as_mesh(soup.points, soup.triangles, closed);
      out(", \"closed_input\": %s", closed ? "true" : "false");
      if(!closed) std::cerr << "tet_baselines: the input is open; meshing it anyway\n";
      const auto t0 = std::chrono::steady_clock::now();
      auto eif = sm.add_property_map<Surface_mesh::Edge_index, bool>("e:sharp", false).first;
      PMP::detect_sharp_edges(sm, 60, eif);
      PMP::isotropic_remeshing(faces(sm), h, sm, CGAL::parameters::number_of_iterations(3).edge_is_constrained_map(eif));
      sm.collect_garbage();
      const double t_remesh = since(t0);
      std::vector<Point_3> pts;
      std::map<Surface_mesh::Vertex_index, std::size_t> vid;
      for(auto v : vertices(sm)) { vid[v] = pts.size(); pts.push_back(sm.point(v)); }
      std::vector<std::array<std::size_t, 3>> tris;
      for(auto f : faces(sm)) {
        std::array<std::size_t, 3> t;
        int k = 0;
        for(auto v : vertices_around_face(halfedge(f, sm), sm)) if(k < 3) t[std::size_t(k++)] = vid[v];
        tris.push_back(t);
      }
      out(", \"remeshing_seconds\": %.6g, \"remeshed_triangles\": %zu", t_remesh, tris.size());
      r = run_tetgen(pts, tris, h);
    } else {
      throw std::runtime_error("unknown mesher '" + mesher + "'");
    }
    // quality: dihedral angles, radius-edge ratio, edge lengths
    const double pi = std::acos(-1.0);
    std::vector<std::size_t> dih(18, 0), rer(12, 0);
    double dmin = 180, dmax = 0, rmin = 1e300, rmax = 0, rsum = 0, emax = 0, emin = 1e300;
    std::size_t inverted = 0;
    static const int E[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    for(const auto& t : r.tets) {
      const V p[4] = {r.points[t[0]], r.points[t[1]], r.points[t[2]], r.points[t[3]]};
      if(dot(cross(sub(p[1], p[0]), sub(p[2], p[0])), sub(p[3], p[0])) <= 0) ++inverted;
      double lmin = 1e300;
      for(const auto& e : E) {
        const double l = norm(sub(p[e[1]], p[e[0]]));
        lmin = (std::min)(lmin, l); emin = (std::min)(emin, l); emax = (std::max)(emax, l);
      }
      // dihedral angle at edge (a, b): between the faces (a, b, c) and (a, b, d)
      for(const auto& e : E) {
        int o[2], n = 0;
        for(int k = 0; k < 4; ++k) if(k != e[0] && k != e[1]) o[n++] = k;
        const V ab = sub(p[e[1]], p[e[0]]);
        const V n1 = cross(ab, sub(p[o[0]], p[e[0]])), n2 = cross(ab, sub(p[o[1]], p[e[0]]));
        const double c = dot(n1, n2) / (norm(n1) * norm(n2));
        const double a = std::acos((std::max)(-1.0, (std::min)(1.0, c))) * 180 / pi;
        dmin = (std::min)(dmin, a); dmax = (std::max)(dmax, a);
        ++dih[(std::min)(std::size_t(17), std::size_t(a / 10))];
      }
      // circumradius: |a|^2 (b x c) + |b|^2 (c x a) + |c|^2 (a x b) over 2 a.(b x c), from p0
      const V a = sub(p[1], p[0]), b = sub(p[2], p[0]), c = sub(p[3], p[0]);
      const double det = 2 * dot(a, cross(b, c));
      const V bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
      V num;
      for(int k = 0; k < 3; ++k) num[std::size_t(k)] = dot(a, a) * bc[std::size_t(k)] + dot(b, b) * ca[std::size_t(k)] + dot(c, c) * ab[std::size_t(k)];
      const double R = det != 0 ? norm(num) / std::abs(det) : 1e300;
      const double q = R / lmin;
      rmin = (std::min)(rmin, q); rmax = (std::max)(rmax, q); rsum += q;
      const int bin = int((q - 0.6) / 0.2);
      ++rer[std::size_t((std::max)(0, (std::min)(11, bin)))];
    }
    const std::size_t n = r.tets.size();
    out(", \"status\": \"ok\", \"elements\": %zu, \"vertices\": %zu, \"seconds\": %.6g, \"boundary_triangles\": %zu, "
                "\"inverted\": %zu, \"longest_edge\": %.9g, \"shortest_edge\": %.9g, "
                "\"dihedral\": {\"min\": %.6g, \"max\": %.6g, \"lo\": 0, \"hi\": 180, \"counts\": %s}, "
                "\"radius_edge\": {\"min\": %.6g, \"mean\": %.6g, \"max\": %.6g, \"lo\": 0.6, \"hi\": 3.0, \"counts\": %s}}\n",
                n, r.points.size(), r.seconds, r.boundary.size(), inverted, n ? emax : 0.0, n ? emin : 0.0,
                n ? dmin : 0.0, n ? dmax : 0.0, hist_json(dih).c_str(), n ? rmin : 0.0, n ? rsum / double(n) : 0.0,
                n ? rmax : 0.0, hist_json(rer).c_str());
    std::fflush(stdout);
    std::fputs(("\n" + g_json).c_str(), stdout);
    if(!boundary_file.empty()) {
      std::ofstream os(boundary_file);
      os.precision(17);
      os << "OFF\n" << r.points.size() << " " << r.boundary.size() << " 0\n";
      for(const auto& p : r.points) os << p[0] << " " << p[1] << " " << p[2] << "\n";
      for(const auto& t : r.boundary) os << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    }
    if(!msh_file.empty() && n) {
      // Gmsh's tetrahedron (type 4) has the orientation counted as valid above; no boundary
      // elements: gmshToFoam puts the exposed faces into one patch. Only the tetrahedra's points
      // (Mesh_3 may have surface facets with no tetrahedron on either side, on parts thinner
      // than its sizes: their points are not the volume mesh's)
      std::vector<std::size_t> used(r.points.size(), 0);
      for(const auto& t : r.tets) for(std::size_t v : t) used[v] = 1;
      std::size_t m = 0;
      for(auto& u : used) u = u ? ++m : 0;
      std::ofstream os(msh_file);
      os.precision(17);
      os << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << m << "\n";
      for(std::size_t i = 0; i < r.points.size(); ++i)
        if(used[i]) os << used[i] << " " << r.points[i][0] << " " << r.points[i][1] << " " << r.points[i][2] << "\n";
      os << "$EndNodes\n$Elements\n" << n << "\n";
      for(std::size_t i = 0; i < n; ++i) {
        const auto& t = r.tets[i];
        os << i + 1 << " 4 2 1 1 " << used[t[0]] << " " << used[t[1]] << " " << used[t[2]] << " " << used[t[3]] << "\n";
      }
      os << "$EndElements\n";
    }
    return 0;
  } catch(const std::exception& e) {
    std::string msg = e.what();
    for(char& c : msg) if(c == '"' || c == '\\' || c == '\n') c = ' ';
    out(", \"status\": \"error\", \"message\": \"%s\"}\n", msg.c_str());
    std::fflush(stdout);
    std::fputs(("\n" + g_json).c_str(), stdout);
    std::cerr << "tet_baselines: " << msg << "\n";
    return 2;
  }
}
