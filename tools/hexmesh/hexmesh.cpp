// hexmesh: all-hexahedral meshes from triangulated surfaces (Hex_meshing_3's command line).
//
// Exit codes:
//   0  success (mesh written)
//   1  usage error (bad option or value)
//   2  input error (unreadable or unusable surface, bad box, bad seed)
//   3  output error (output exists and --force not given, or cannot be written)
//   4  the mesh failed a validity check (inverted cell or inconsistent faces): nothing written
//   5  cancelled (Ctrl-C): the valid, coarser mesh reached so far was written

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hex_mesh_criteria_3.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/IO/write_OpenFOAM.h>
#include <CGAL/Hex_meshing_3/IO/write_VTU.h>
#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>
#include <CGAL/Hex_meshing_3/Surface_domain_3.h>
#include <CGAL/Hex_meshing_3/quality.h>
#include <CGAL/make_hex_mesh_3.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Hex_meshing_3::Surface_domain_3<K> Domain;
typedef CGAL::Hex_mesh_criteria_3<K> Criteria;
typedef CGAL::Hex_meshing_3::Hex_mesh_3<K> Mesh;
namespace HM = CGAL::Hex_meshing_3;
namespace fs = std::filesystem;

enum Exit { OK = 0, USAGE = 1, INPUT = 2, OUTPUT = 3, INVALID = 4, CANCELLED = 5 };

static std::atomic<bool> g_interrupted(false);
extern "C" void on_sigint(int)
{
  g_interrupted = true;
  std::signal(SIGINT, SIG_DFL);   // a second Ctrl-C ends the program at once
}

static double peak_memory_mib()
{
  rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return double(ru.ru_maxrss) / 1024.0;
}

struct Progress
{
  bool quiet = false;
  bool tty = false;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now(), phase_t0;
  std::string phase;
  std::vector<std::pair<std::string, double>> seconds;
  std::vector<std::pair<std::string, std::size_t>> work;   // cells each phase starts with
  int last_percent = -1;

  void on_phase_begin(const char* name, std::size_t cells)
  {
    phase = name; phase_t0 = std::chrono::steady_clock::now(); last_percent = -1;
    work.push_back({name, cells});
    if(!quiet) {
      std::cerr << (tty ? "\r\033[K" : "") << "hexmesh: " << name << " (" << cells << " cells)";
      std::cerr << (tty ? "" : "\n") << std::flush;
    }
  }
  void on_phase_end(const char* name)
  {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - phase_t0).count();
    seconds.push_back({name, s});
    if(!quiet && tty) std::cerr << "\r\033[K" << std::flush;
    if(!quiet) std::cerr << "hexmesh: " << name << " done in " << s << " s\n";
  }
  bool go_further(double f)
  {
    const int p = int(100 * f);
    if(!quiet && tty && p != last_percent) {
      last_percent = p;
      std::cerr << "\r\033[Khexmesh: " << phase << " " << p << "%" << std::flush;
    }
    return !g_interrupted;
  }
};

static std::vector<double> parse_numbers(const std::string& s, std::size_t n, const std::string& what)
{
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  while(std::getline(ss, item, ',')) {
    try {
      std::size_t pos = 0;
      v.push_back(std::stod(item, &pos));
      if(pos != item.size()) throw std::invalid_argument(item);
    } catch(const std::exception&) {
      throw CLI::ValidationError(what, "'" + item + "' is not a number");
    }
    if(!std::isfinite(v.back())) throw CLI::ValidationError(what, "'" + item + "' is not finite");
  }
  if(v.size() != n) throw CLI::ValidationError(what, "expected " + std::to_string(n) + " comma-separated numbers in '" + s + "'");
  return v;
}

static CGAL::Bbox_3 parse_box(const std::string& s, const std::string& what)
{
  const std::vector<double> v = parse_numbers(s, 6, what);
  for(int a = 0; a < 3; ++a)
    if(!(v[a] < v[a + 3])) throw CLI::ValidationError(what, "the box's min must be below its max on every axis: '" + s + "'");
  return CGAL::Bbox_3(v[0], v[1], v[2], v[3], v[4], v[5]);
}

static bool is_vtu(const std::string& o)
{
  return o.size() > 4 && o.compare(o.size() - 4, 4, ".vtu") == 0;
}

int main(int argc, char** argv)
{
  CLI::App app{"hexmesh - all-hexahedral meshes from triangulated surfaces (Hex_meshing_3)"};
  app.footer(
      "Outputs: a name ending in .vtu writes a VTK unstructured grid (ParaView); any other name is an\n"
      "OpenFOAM case directory (constant/polyMesh; system/controlDict only if absent).\n\n"
      "Examples:\n"
      "  hexmesh part.stl -o part.vtu\n"
      "  hexmesh part.off -o part.vtu -o partCase --size 0.1 --surface-size 0.025\n"
      "  hexmesh bike.obj -o bikeCase --box -5,-4,0,15,4,8 --size 1 --surface-size 0.03125 \\\n"
      "          --refine-box -1,-0.7,0,8,0.7,2.5:0.0625 --region seed:3.0001,3.0001,0.43\n\n"
      "Exit codes: 0 success; 1 usage error; 2 input error; 3 output error (exists without --force,\n"
      "or not writable); 4 the mesh failed a validity check; 5 cancelled by Ctrl-C (the coarser mesh\n"
      "reached so far is written).");
  std::string input;
  std::vector<std::string> outputs;
  double size = 0, surface_size = 0;
  std::string box_s, region = "inside", report;
  std::vector<std::string> refine_boxes;
  int max_level = 12;
  bool force = false, quiet = false;
  app.add_option("input", input, "triangulated surface: .off, .obj, .stl or .ply")->required();
  app.add_option("-o,--output", outputs, "output: FILE.vtu, or a directory for an OpenFOAM case (repeatable)")->required();
  auto* size_opt = app.add_option("--size", size, "largest cell edge (default: the largest side of the input's bounding box / 10)");
  auto* ssize_opt = app.add_option("--surface-size", surface_size, "largest edge of cells cut by the surface (default: size / 4)");
  app.add_option("--box", box_s, "meshing box xmin,ymin,zmin,xmax,ymax,zmax, honoured exactly "
                                 "(default: the input's bounding box grown by one cell size)");
  app.add_option("--refine-box", refine_boxes, "xmin,ymin,zmin,xmax,ymax,zmax:SIZE - cells overlapping the box get "
                                               "at most SIZE (repeatable)");
  app.add_option("--region", region, "inside (cells inside the surface) or seed:X,Y,Z (cells reached from the point "
                                     "without crossing the surface)");
  app.add_option("--max-level", max_level, "most refinement levels below the initial grid")->check(CLI::Range(0, 20));
  app.add_option("--report", report, "write a JSON report (counts, seconds, memory, quality) to this file");
  app.add_flag("--force", force, "overwrite existing output files and polyMesh directories");
  app.add_flag("-q,--quiet", quiet, "print nothing but errors");

  CGAL::Bbox_3 box;
  bool has_box = false;
  std::vector<std::pair<CGAL::Bbox_3, double>> rboxes;
  bool has_seed = false;
  Point_3 seed;
  try {
    app.parse(argc, argv);
    if(size_opt->count() && !(size > 0 && std::isfinite(size))) throw CLI::ValidationError("--size", "must be a positive number");
    if(ssize_opt->count() && !(surface_size > 0 && std::isfinite(surface_size)))
      throw CLI::ValidationError("--surface-size", "must be a positive number");
    if(!box_s.empty()) { box = parse_box(box_s, "--box"); has_box = true; }
    for(const std::string& rb : refine_boxes) {
      const auto colon = rb.rfind(':');
      if(colon == std::string::npos) throw CLI::ValidationError("--refine-box", "expected BOX:SIZE in '" + rb + "'");
      const double s = parse_numbers(rb.substr(colon + 1), 1, "--refine-box")[0];
      if(!(s > 0)) throw CLI::ValidationError("--refine-box", "the size must be positive in '" + rb + "'");
      rboxes.push_back({parse_box(rb.substr(0, colon), "--refine-box"), s});
    }
    if(region.rfind("seed:", 0) == 0) {
      const auto v = parse_numbers(region.substr(5), 3, "--region");
      seed = Point_3(v[0], v[1], v[2]); has_seed = true;
    } else if(region != "inside")
      throw CLI::ValidationError("--region", "expected 'inside' or 'seed:X,Y,Z', got '" + region + "'");
    for(const std::string& o : outputs) {
      const std::string ext = fs::path(o).extension().string();
      if(!is_vtu(o) && !ext.empty() && ext != "/" && fs::path(o).filename() != "." )
        throw CLI::ValidationError("--output", "'" + o + "': unknown output format '" + ext +
                                   "' (a .vtu file, or a directory name without extension for an OpenFOAM case)");
    }
  } catch(const CLI::ParseError& e) {
    if(e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "hexmesh: " << e.what() << "\n" << "Run 'hexmesh --help' for the options.\n";
    return USAGE;
  }

  // refuse to overwrite before any work
  for(const std::string& o : outputs) {
    if(is_vtu(o)) {
      if(fs::exists(o) && !force) {
        std::cerr << "hexmesh: " << o << " exists; use --force to overwrite it\n";
        return OUTPUT;
      }
    } else if(fs::exists(fs::path(o) / "constant" / "polyMesh") && !force) {
      std::cerr << "hexmesh: " << (fs::path(o) / "constant" / "polyMesh").string()
                << " exists; use --force to overwrite it\n";
      return OUTPUT;
    }
  }

  Progress progress;
  progress.quiet = quiet;
  progress.tty = isatty(2);
  std::signal(SIGINT, on_sigint);
  const auto t_start = std::chrono::steady_clock::now();
  auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };

  try {
    auto t = std::chrono::steady_clock::now();
    Domain domain(input);
    const double t_read = since(t);
    const auto& sum = domain.input_summary();
    if(!quiet) {
      std::cerr << "hexmesh: read " << input << ": " << domain.number_of_triangles() << " triangles";
      if(sum.merged_points) std::cerr << ", " << sum.merged_points << " duplicate points merged";
      if(sum.degenerate_triangles) std::cerr << ", " << sum.degenerate_triangles << " degenerate triangles removed";
      std::cerr << "; inside test: " << (domain.has_exact_inside_test() ? "exact (closed surface)" : "winding number")
                << (sum.reoriented ? " (inward orientation flipped)" : "") << " [" << t_read << " s]\n";
    }
    const CGAL::Bbox_3 bb = domain.bbox();
    const double extent = (std::max)({bb.xmax() - bb.xmin(), bb.ymax() - bb.ymin(), bb.zmax() - bb.zmin()});
    if(size <= 0) size = (has_box ? (std::max)({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()}) / 1.2
                                  : extent) / 10;
    if(surface_size <= 0) surface_size = size / 4;
    Criteria criteria(size, surface_size, max_level);
    for(const auto& rb : rboxes) criteria.add_refinement_box(rb.first, rb.second);

    Mesh mesh;
    HM::Status status;
    namespace HP = HM::parameters;
    if(!has_box) {
      box = CGAL::Bbox_3(bb.xmin() - size, bb.ymin() - size, bb.zmin() - size, bb.xmax() + size, bb.ymax() + size, bb.zmax() + size);
    }
    if(has_seed)
      status = CGAL::make_hex_mesh_3(domain, criteria, mesh, HP::meshing_box(box).region_seed(seed).visitor(std::ref(progress)));
    else
      status = CGAL::make_hex_mesh_3(domain, criteria, mesh, HP::meshing_box(box).visitor(std::ref(progress)));
    if(status == HM::Status::CANCELED)
      std::cerr << "hexmesh: warning: cancelled; the valid, coarser mesh reached so far is kept\n";
    if(mesh.number_of_cells() == 0) {
      std::cerr << "hexmesh: " << input << ": the region is empty: no cell of the grid lies "
                << (has_seed ? "in the seeded region" : "inside the surface")
                << " (is the surface open, or the surface size too coarse for its thinnest part?)\n";
      return INPUT;
    }

    t = std::chrono::steady_clock::now();
    HM::Polyhedral_mesh_3 pm;
    pm.build(mesh);
    const HM::Mesh_quality q = HM::compute_quality(mesh, pm);
    const double t_quality = since(t);
    const auto sj = HM::Mesh_quality::range(q.scaled_jacobian);
    const auto no = HM::Mesh_quality::range(q.non_orthogonality);
    const auto sk = HM::Mesh_quality::range(q.skewness);
    const auto ar = HM::Mesh_quality::range(q.aspect_ratio);
    if(q.number_of_inverted_cells() > 0) {
      std::cerr << "hexmesh: internal error: " << q.number_of_inverted_cells() << " inverted cells; nothing written\n";
      return INVALID;
    }

    t = std::chrono::steady_clock::now();
    for(const std::string& o : outputs) {
      const bool ok = is_vtu(o) ? HM::IO::write_VTU(o, mesh, q.scaled_jacobian) : HM::IO::write_OpenFOAM(o, mesh, pm);
      if(!ok) { std::cerr << "hexmesh: cannot write " << o << "\n"; return OUTPUT; }
    }
    const double t_write = since(t);
    const double total = since(t_start);
    std::size_t nboundary = mesh.boundary_faces.size();

    if(!quiet) {
      std::printf("cells %zu  vertices %zu  hanging nodes %zu  boundary faces %zu  polyhedral faces %zu\n",
                  mesh.number_of_cells(), mesh.number_of_vertices(), mesh.hanging_nodes.size(), nboundary, pm.faces.size());
      std::printf("scaled Jacobian    min %.6g  mean %.6g  max %.6g\n", sj.min, sj.mean, sj.max);
      std::printf("non-orthogonality  min %.6g  mean %.6g  max %.6g  (degrees, internal faces)\n", no.min, no.mean, no.max);
      std::printf("skewness           min %.6g  mean %.6g  max %.6g\n", sk.min, sk.mean, sk.max);
      std::printf("aspect ratio       min %.6g  mean %.6g  max %.6g\n", ar.min, ar.mean, ar.max);
      std::printf("status %s  seconds %.3f  peak memory %.1f MiB\n", HM::status_name(status), total, peak_memory_mib());
      for(const std::string& o : outputs) std::printf("wrote %s\n", o.c_str());
    }
    if(!report.empty()) {
      nlohmann::ordered_json j;
      j["input"] = input;
      j["options"] = {{"size", size}, {"surface_size", surface_size}, {"max_level", max_level}, {"region", region},
                      {"box", {box.xmin(), box.ymin(), box.zmin(), box.xmax(), box.ymax(), box.zmax()}}};
      j["input_summary"] = {{"triangles", domain.number_of_triangles()}, {"merged_points", sum.merged_points},
                            {"degenerate_triangles", sum.degenerate_triangles}, {"closed", sum.closed},
                            {"exact_inside_test", sum.exact_inside_test}, {"reoriented", sum.reoriented}};
      j["status"] = HM::status_name(status);
      j["counts"] = {{"cells", mesh.number_of_cells()}, {"vertices", mesh.number_of_vertices()},
                     {"hanging_nodes", mesh.hanging_nodes.size()}, {"boundary_faces", nboundary},
                     {"polyhedral_faces", pm.faces.size()}, {"internal_faces", pm.number_of_internal_faces()}};
      nlohmann::ordered_json sec;
      sec["read"] = t_read;
      for(const auto& s : progress.seconds) sec[s.first] = s.second;
      sec["quality"] = t_quality; sec["write"] = t_write; sec["total"] = total;
      j["seconds"] = sec;
      j["peak_memory_mib"] = peak_memory_mib();
      {
        // grid speed: leaf cells of the balanced grid per second of refine + balance + classify
        std::size_t leaves = 0;
        double grid_seconds = 0;
        for(const auto& w : progress.work) if(w.first == "classify") leaves = w.second;
        for(const auto& s : progress.seconds)
          if(s.first == "refine" || s.first == "balance" || s.first == "classify") grid_seconds += s.second;
        j["grid"] = {{"leaf_cells", leaves}, {"seconds", grid_seconds},
                     {"leaf_cells_per_second", grid_seconds > 0 ? double(leaves) / grid_seconds : 0.0}};
      }
      auto rj = [](const HM::Mesh_quality::Range& r) { return nlohmann::ordered_json{{"min", r.min}, {"mean", r.mean}, {"max", r.max}}; };
      j["quality"] = {{"scaled_jacobian", rj(sj)}, {"non_orthogonality", rj(no)}, {"skewness", rj(sk)}, {"aspect_ratio", rj(ar)}};
      j["outputs"] = outputs;
      std::ofstream os(report);
      os << j.dump(2) << "\n";
      if(!os) { std::cerr << "hexmesh: cannot write " << report << "\n"; return OUTPUT; }
    }
    return status == HM::Status::CANCELED ? CANCELLED : OK;
  } catch(const HM::Input_error& e) {
    std::cerr << "hexmesh: " << e.what() << "\n";
    return INPUT;
  } catch(const std::bad_alloc&) {
    std::cerr << "hexmesh: out of memory; use a larger --size or --surface-size\n";
    return INPUT;
  } catch(const std::logic_error& e) {
    std::cerr << "hexmesh: internal error: " << e.what() << "\n";
    return INVALID;
  }
}
