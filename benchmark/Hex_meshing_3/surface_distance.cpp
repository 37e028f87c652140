// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
//
// surface_distance A B [--exclude REGEX]... [--samples N] [--dump PREFIX]
//
// Two-sided distance between two triangulated surfaces (any format hexmesh reads: OFF, OBJ, STL,
// PLY, optionally gzipped), the same measure for every mesher of the benchmarks: points sampled
// uniformly by area on each surface (N per surface, fixed seed, plus every vertex) are measured
// against the other surface with CGAL's AABB tree. Parts (OBJ groups, STL solids) whose name
// matches one of the --exclude regular expressions are left out on both sides (a mesh's box
// patches). Prints one JSON object: per direction the largest, mean, 95th and 99th percentile
// distances, per part of the sampled surface (a_to_b_parts, b_to_a_parts) its points and the sum
// and largest of their distances, and each surface's triangles and area. --dump PREFIX also writes every sample as a
// line "x y z distance" to PREFIX_a_to_b.txt and PREFIX_b_to_a.txt (where the distance comes from).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Hex_meshing_3/IO/read_surface.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <random>
#include <regex>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef K::Triangle_3 Triangle_3;
typedef std::vector<Triangle_3>::const_iterator Iterator;
typedef CGAL::AABB_triangle_primitive<K, Iterator> Primitive;
typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;

struct Surface
{
  std::vector<Triangle_3> triangles;
  std::vector<Point_3> vertices;
  std::vector<int> triangle_part, vertex_part;   // (a vertex: the part of its first triangle kept)
  std::vector<std::string> part_names;
  double area = 0;
};

static Surface load(const std::string& file, const std::vector<std::regex>& exclude)
{
  CGAL::Hex_meshing_3::IO::Surface_soup<Point_3> soup;
  CGAL::Hex_meshing_3::IO::read_surface(file, soup);
  std::vector<char> skip(soup.part_names.size(), 0);
  for(std::size_t p = 0; p < soup.part_names.size(); ++p)
    for(const auto& r : exclude)
      if(std::regex_match(soup.part_names[p], r)) skip[p] = 1;
  Surface s;
  s.part_names = soup.part_names;
  std::vector<int> used(soup.points.size(), -1);
  for(std::size_t t = 0; t < soup.triangles.size(); ++t) {
    if(skip[std::size_t(soup.part_of_triangle[t])]) continue;
    const auto& f = soup.triangles[t];
    Triangle_3 tr(soup.points[f[0]], soup.points[f[1]], soup.points[f[2]]);
    const double a = std::sqrt(tr.squared_area());
    if(!(a > 0)) continue;
    s.triangles.push_back(tr);
    s.triangle_part.push_back(soup.part_of_triangle[t]);
    s.area += a;
    for(int k = 0; k < 3; ++k) if(used[f[k]] < 0) used[f[k]] = soup.part_of_triangle[t];
  }
  for(std::size_t v = 0; v < soup.points.size(); ++v)
    if(used[v] >= 0) { s.vertices.push_back(soup.points[v]); s.vertex_part.push_back(used[v]); }
  return s;
}

// the distances of `n` area-uniform samples of `a` (and of its vertices) to `b`; `part`
// receives the part of `a` each comes from
static std::vector<double> distances(const Surface& a, const Tree& b, std::size_t n, std::vector<int>& part,
                                     std::FILE* dump = nullptr)
{
  part.clear();
  std::vector<double> cum;
  cum.reserve(a.triangles.size());
  double acc = 0;
  for(const auto& t : a.triangles) { acc += std::sqrt(t.squared_area()); cum.push_back(acc); }
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> d;
  d.reserve(n + a.vertices.size());
  for(std::size_t i = 0; i < n && acc > 0; ++i) {
    const std::size_t t = std::size_t(std::lower_bound(cum.begin(), cum.end(), u(rng) * acc) - cum.begin());
    const Triangle_3& tr = a.triangles[(std::min)(t, a.triangles.size() - 1)];
    part.push_back(a.triangle_part[(std::min)(t, a.triangles.size() - 1)]);
    double r1 = u(rng), r2 = u(rng);
    if(r1 + r2 > 1) { r1 = 1 - r1; r2 = 1 - r2; }
    const Point_3 p = tr[0] + r1 * (tr[1] - tr[0]) + r2 * (tr[2] - tr[0]);
    d.push_back(std::sqrt(b.squared_distance(p)));
    if(dump) std::fprintf(dump, "%.9g %.9g %.9g %.9g\n", p.x(), p.y(), p.z(), d.back());
  }
  for(std::size_t v = 0; v < a.vertices.size(); ++v) {
    const Point_3& p = a.vertices[v];
    part.push_back(a.vertex_part[v]);
    d.push_back(std::sqrt(b.squared_distance(p)));
    if(dump) std::fprintf(dump, "%.9g %.9g %.9g %.9g\n", p.x(), p.y(), p.z(), d.back());
  }
  return d;
}

// per part of the sampled surface: its points, and the sum and the largest of their distances
static void print_parts(const char* name, const Surface& s, const std::vector<double>& d, const std::vector<int>& part)
{
  std::vector<double> sum(s.part_names.size(), 0.0), mx(s.part_names.size(), 0.0);
  std::vector<std::size_t> count(s.part_names.size(), 0);
  for(std::size_t i = 0; i < d.size(); ++i) {
    const std::size_t p = std::size_t(part[i]);
    sum[p] += d[i]; mx[p] = (std::max)(mx[p], d[i]); ++count[p];
  }
  std::printf("\"%s_parts\": {", name);
  bool first = true;
  for(std::size_t p = 0; p < count.size(); ++p) {
    if(count[p] == 0) continue;
    std::string n;
    for(char c : s.part_names[p]) { if(c == '"' || c == '\\') n += '\\'; n += c; }
    std::printf("%s\"%s\": {\"points\": %zu, \"sum\": %.9g, \"max\": %.9g}", first ? "" : ", ", n.c_str(), count[p], sum[p], mx[p]);
    first = false;
  }
  std::printf("}");
}

static void print_stats(const char* name, std::vector<double> d)
{
  std::sort(d.begin(), d.end());
  double mean = 0;
  for(double x : d) mean += x;
  mean = d.empty() ? 0 : mean / double(d.size());
  auto pct = [&](double q) { return d.empty() ? 0.0 : d[std::size_t(q * double(d.size() - 1))]; };
  std::printf("\"%s\": {\"max\": %.9g, \"mean\": %.9g, \"p95\": %.9g, \"p99\": %.9g, \"points\": %zu}", name,
              d.empty() ? 0.0 : d.back(), mean, pct(0.95), pct(0.99), d.size());
}

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  std::vector<std::regex> exclude;
  std::size_t samples = 200000;
  std::string dump;
  for(int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if(a == "--exclude" && i + 1 < argc) exclude.emplace_back(argv[++i]);
    else if(a == "--samples" && i + 1 < argc) samples = std::size_t(std::strtoull(argv[++i], nullptr, 10));
    else if(a == "--dump" && i + 1 < argc) dump = argv[++i];
    else files.push_back(a);
  }
  if(files.size() != 2) {
    std::fprintf(stderr, "usage: surface_distance A B [--exclude REGEX]... [--samples N] [--dump PREFIX]\n");
    return 1;
  }
  try {
    const Surface a = load(files[0], exclude), b = load(files[1], exclude);
    if(a.triangles.empty() || b.triangles.empty()) {
      std::fprintf(stderr, "surface_distance: a surface has no triangle left\n");
      return 2;
    }
    Tree ta(a.triangles.begin(), a.triangles.end()), tb(b.triangles.begin(), b.triangles.end());
    ta.accelerate_distance_queries();
    tb.accelerate_distance_queries();
    std::printf("{\"a\": \"%s\", \"b\": \"%s\", \"a_triangles\": %zu, \"b_triangles\": %zu, \"a_area\": %.9g, \"b_area\": %.9g, ",
                files[0].c_str(), files[1].c_str(), a.triangles.size(), b.triangles.size(), a.area, b.area);
    auto open_dump = [&](const char* which) -> std::FILE* {
      if(dump.empty()) return nullptr;
      std::FILE* f = std::fopen((dump + which).c_str(), "w");
      if(!f) throw std::runtime_error("cannot write " + dump + which);
      return f;
    };
    std::vector<int> part;
    std::FILE* da = open_dump("_a_to_b.txt");
    const std::vector<double> dab = distances(a, tb, samples, part, da);
    if(da) std::fclose(da);
    print_stats("a_to_b", dab);
    std::printf(", ");
    print_parts("a_to_b", a, dab, part);
    std::printf(", ");
    std::FILE* db = open_dump("_b_to_a.txt");
    const std::vector<double> dba = distances(b, ta, samples, part, db);
    if(db) std::fclose(db);
    print_stats("b_to_a", dba);
    std::printf(", ");
    print_parts("b_to_a", b, dba, part);
    std::printf("}\n");
  } catch(const std::exception& e) {
    std::fprintf(stderr, "surface_distance: %s\n", e.what());
    return 2;
  }
  return 0;
}
