// hexmesh: all-hexahedral meshes from triangulated surfaces (Hex_meshing_3's command line).
//
// Exit codes:
//   0  success (mesh written)
//   1  usage error (bad option or value)
//   2  input error (unreadable or unusable surface, bad box, bad seed, a leak with --strict)
//   3  output error (output exists and --force not given, or cannot be written)
//   4  the mesh failed a validity check (inverted cell or inconsistent faces): nothing written
//   5  cancelled (Ctrl-C): the valid, coarser mesh reached so far was written

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hex_mesh_criteria_3.h>
#include <CGAL/Hex_meshing_3/Feature_curves_3.h>
#include <CGAL/Hex_meshing_3/fidelity.h>
#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/IO/read_surface.h>
#if defined(__GLIBC__)
#include <malloc.h>   // malloc_trim
#endif
#include <CGAL/Hex_meshing_3/IO/write_MSH.h>
#include <CGAL/Hex_meshing_3/IO/write_Medit.h>
#include <CGAL/Hex_meshing_3/IO/write_OpenFOAM.h>
#include <CGAL/Hex_meshing_3/IO/write_VTU.h>
#include <CGAL/Hex_meshing_3/Polyhedral_mesh_3.h>
#include <CGAL/Hex_meshing_3/Surface_domain_3.h>
#include <CGAL/Hex_meshing_3/quality.h>
#include <CGAL/make_hex_mesh_3.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include "html_report.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <regex>
#include <sstream>
#include <optional>
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
  std::vector<std::pair<std::string, double>> peaks;       // peak memory (MiB) at the end of each phase
  int last_percent = -1;

  void on_phase_begin(const char* name, std::size_t cells)
  {
    // a second "refine": the mesh is made again with the staircase closer to the surface (the
    // staircase retries of `capture_retry_cells`)
    const bool again = std::string(name) == "refine" &&
                       std::any_of(work.begin(), work.end(), [](const auto& w) { return w.first == "refine"; });
    // a "capture" right after another: after the three staircases, an earlier staircase's grid
    // (kept) captured for its deferred captures
    const bool deferred = std::string(name) == "capture" && !work.empty() && work.back().first == "capture";
    phase = name; phase_t0 = std::chrono::steady_clock::now(); last_percent = -1;
    work.push_back({name, cells});
    if(!quiet && again)
      std::cerr << (tty ? "\r\033[K" : "") << "hexmesh: a boundary face stands beyond 1/4 surface size off the input "
                   "or a cell is below 0.3: the mesh is made again with the staircase closer to the surface\n";
    if(!quiet && deferred)
      std::cerr << (tty ? "\r\033[K" : "") << "hexmesh: a cell is below 0.3 or an OpenFOAM fault is left: an earlier "
                   "staircase's grid is captured again for its deferred captures (without pillows, other path weights)\n";
    if(!quiet) {
      std::cerr << (tty ? "\r\033[K" : "") << "hexmesh: " << name << " (" << cells << " cells)";
      std::cerr << (tty ? "" : "\n") << std::flush;
    }
  }
  void on_phase_end(const char* name)
  {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - phase_t0).count();
    seconds.push_back({name, s});
    peaks.push_back({name, peak_memory_mib()});
    if(!quiet && tty) std::cerr << "\r\033[K" << std::flush;
    if(!quiet) std::cerr << "hexmesh: " << name << " done in " << s << " s (peak memory so far " << peaks.back().second << " MiB)\n";
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

enum class Output_kind { VTU, MSH, MEDIT, OPENFOAM };
static Output_kind output_kind(const std::string& o)
{
  const std::string ext = fs::path(o).extension().string();
  if(ext == ".vtu") return Output_kind::VTU;
  if(ext == ".msh") return Output_kind::MSH;
  if(ext == ".mesh") return Output_kind::MEDIT;
  return Output_kind::OPENFOAM;
}

/// REGEX=VALUE rules (the last '=' separates, so a regex may contain '=')
struct Rule { std::string text; std::regex re; std::string value; };
static std::vector<Rule> parse_rules(const std::vector<std::string>& v, const std::string& what)
{
  std::vector<Rule> rules;
  for(const std::string& r : v) {
    const auto eq = r.rfind('=');
    if(eq == std::string::npos || eq == 0 || eq + 1 == r.size())
      throw CLI::ValidationError(what, "expected REGEX=VALUE in '" + r + "'");
    try {
      rules.push_back({r.substr(0, eq), std::regex(r.substr(0, eq), std::regex::ECMAScript), r.substr(eq + 1)});
    } catch(const std::regex_error& e) {
      throw CLI::ValidationError(what, "'" + r.substr(0, eq) + "' is not a valid regular expression (" + e.what() + ")");
    }
  }
  return rules;
}


/// histograms, face warpage summary and the worst elements with their locations
static void add_quality_details(nlohmann::ordered_json& jq, const Mesh& mesh, const HM::Polyhedral_mesh_3& pm,
                                const HM::Mesh_quality& q)
{
  const auto fw = HM::Mesh_quality::range(q.face_warpage);
  jq["face_warpage"] = {{"min", fw.min}, {"mean", fw.mean}, {"max", fw.max}};
  jq["inverted_cells"] = q.number_of_inverted_cells();
  jq["histograms"] = histograms_json(HM::quality_histograms(q));
  jq["worst_cells"] = worst_cells_json(HM::worst_cells(mesh, pm, q, 10));
}

int main(int argc, char** argv)
{
#if defined(__GLIBC__)
  // Arrays of 1 MiB and more are mapped apart and given back to the system when freed. By default
  // glibc raises that threshold as such arrays are freed, and keeps the freed memory of the later
  // ones: motorBike's peak then held 130 MiB of freed arrays next to the live ones (368 -> 309 MiB)
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  mallopt(M_TRIM_THRESHOLD, 2 << 20);
#endif
  CLI::App app{"hexmesh - all-hexahedral meshes from triangulated surfaces (Hex_meshing_3)"};
  app.footer(
      "Inputs: .off, .obj, .stl (ASCII or binary) or .ply, each optionally gzip-compressed (.gz);\n"
      "several files are meshed together. OBJ groups, STL solids, or else the file names become\n"
      "the surface patches; the six box faces are the patches xmin, xmax, ymin, ymax, zmin, zmax.\n\n"
      "Outputs (by extension): .vtu VTK unstructured grid (ParaView); .msh Gmsh 4.1 (physical groups\n"
      "= patches); .mesh Medit; any other name is an OpenFOAM case directory (constant/polyMesh;\n"
      "system files only if absent). Reports: --report FILE.json and/or --report FILE.html.\n\n"
      "Examples:\n"
      "  hexmesh part.stl -o part.vtu\n"
      "  hexmesh part.off -o part.vtu -o partCase --size 0.1 --surface-size 0.025 --report part.html\n"
      "  hexmesh motorBike.obj.gz -o bikeCase --box -5,-4,0,15,4,8 --size 1 --surface-size 0.03125 \\\n"
      "          --refine-box -1,-0.7,0,8,0.7,2.5:0.0625 --region seed:3.0001,3.0001,0.43 \\\n"
      "          --patch-name 'motorBike.*=motorBike' --patch-name 'zmin=ground' --patch-type 'ground=wall'\n\n"
      "Exit codes: 0 success; 1 usage error; 2 input error (unreadable input, bad seed, or a leak with\n"
      "--strict); 3 output error (exists without --force, or not writable); 4 the mesh failed a validity\n"
      "check; 5 cancelled by Ctrl-C (the coarser mesh reached so far is written).");
  std::vector<std::string> inputs, outputs, reports, refine_boxes, patch_name_rules, patch_type_rules, patch_size_rules, feature_files;
  double size = 0, surface_size = 0, scale = 1, feature_angle = 30, feature_size = 0, feature_scale = -1, feature_contrast = 3, soft_crease_angle = 0;
  double curvature_size = 0, curvature_angle = 30, thin_size = 0;
  int thin_cells = 0, cells_between_levels = 1;
  std::string box_s, region = "inside", surface_size_s;
  int max_level = 12;
  std::size_t max_cells = 0;
  bool force = false, quiet = false, strict = false, staircase = false, feature_pillows = true, fill_holes = true;
  std::size_t capture_retry_cells = 200000;
  bool all_capture_retries = false;
  int smoothing_sweeps = 8;
  int threads = 0;
  app.add_option("input", inputs, "triangulated surface files: .off, .obj, .stl, .ply, optionally .gz")->required();
  app.add_option("-o,--output", outputs, "output: FILE.vtu, FILE.msh, FILE.mesh, or a directory for an OpenFOAM case "
                                         "(repeatable)")->required();
  auto* size_opt = app.add_option("--size", size, "largest cell edge (default: the largest side of the input's bounding box / 10)");
  auto* ssize_opt = app.add_option("--surface-size", surface_size_s, "H[:HFINE] - largest edge of cells cut by the surface "
                                                                    "(default: size / 4); HFINE: of those where the surface "
                                                                    "normals differ by more than --curvature-angle");
  app.add_option("--curvature-angle", curvature_angle, "cut cells in which the surface normals differ by more than this many "
                                                       "degrees get the HFINE of --surface-size (default 30)")
      ->check(CLI::Range(0.0, 180.0));
  app.add_option("--thin-cells", thin_cells, "cut cells where the part or the gap is thinner than this many cells are "
                                             "split, down to --thin-size (default 0: no such refinement)")
      ->check(CLI::Range(0, 64));
  app.add_option("--cells-between-levels", cells_between_levels, "cells of each size around a finer region before the "
                                                                 "next coarser size (default 1: the plain 2:1 balance; "
                                                                 "snappyHexMesh's nCellsBetweenLevels)")
      ->check(CLI::Range(1, 16));
  auto* tsize_opt = app.add_option("--thin-size", thin_size, "smallest cell edge that --thin-cells asks for "
                                                             "(default: surface size / 4)");
  auto* scale_opt = app.add_option("--scale", scale, "multiply the input coordinates by this factor (e.g. 0.001 for millimetres)");
  app.add_option("--feature-angle", feature_angle, "an edge whose face normals differ by at least this many degrees is a "
                                                   "feature (default 30)")->check(CLI::Range(0.0, 180.0));
  app.add_option("--soft-crease-angle", soft_crease_angle, "edges whose face normals differ by at least this many degrees "
                                                           "but less than --feature-angle are soft creases, followed like "
                                                           "features where they stand out (the creases between the facets "
                                                           "of a faceted blend: the mesh keeps as close to them as the "
                                                           "facets are); judged like sharp edges at this angle, on curves "
                                                           "at least 4 x the feature scale long (twice the finest size by "
                                                           "default; default 0: none)")
      ->check(CLI::Range(0.0, 180.0));
  app.add_option("--feature-scale", feature_scale, "a sharp edge must also be sharp with the input's normals averaged this far "
                                                   "on each side, or its curve is left out (the creases of a coarse "
                                                   "triangulation of a smooth shape); 0 keeps every sharp edge "
                                                   "(default: half the smallest of the surface, curvature and feature sizes)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--feature-contrast", feature_contrast, "a sharp edge must also have at least this many times the mean "
                                                         "angle of the other edges around it, or its curve is left out "
                                                         "(a coarse triangulation of a smooth shape); 0 keeps every sharp "
                                                         "edge (default 3)")
      ->check(CLI::NonNegativeNumber);
  auto* fsize_opt = app.add_option("--feature-size", feature_size, "largest edge of cells meeting a feature edge (sharp, open, "
                                                                   "non-manifold or part-border edges; default: no such criterion)");
  app.add_option("--features", feature_files, "OBJ file of feature lines ('l' polylines, optionally .gz): cells they "
                                              "meet get at most --feature-size (repeatable)");
  app.add_option("--box", box_s, "meshing box xmin,ymin,zmin,xmax,ymax,zmax, honoured exactly "
                                 "(default: the input's bounding box grown by one cell size)");
  app.add_option("--refine-box", refine_boxes, "xmin,ymin,zmin,xmax,ymax,zmax:SIZE - cells overlapping the box get "
                                               "at most SIZE (repeatable)");
  app.add_option("--region", region, "inside (cells inside the surface) or seed:X,Y,Z (cells reached from the point "
                                     "without crossing the surface)");
  app.add_option("--max-level", max_level, "most refinement levels below the initial grid")->check(CLI::Range(0, 20));
  app.add_option("--max-cells", max_cells, "stop refining before the grid exceeds this many cells (the mesh stays valid; "
                                           "a warning says so)");
  app.add_flag("--feature-pillows,!--no-feature-pillows", feature_pillows, "a sheet of hexahedra along each convex sharp "
               "curve whose chain runs within half a cell of it, two boundary faces meeting at the curve; where that leaves "
               "a cell below a scaled Jacobian of 0.3, a checkMesh fault or a boundary face beyond 1/4 of the surface size from the "
               "input, the retries run without (default: on)");
  app.add_option("--capture-retry-cells", capture_retry_cells, "the retries' budget, in cells: where the boundary "
                 "capture leaves a cell below a scaled Jacobian of 0.3, a cell concave for OpenFOAM or a face failing its tet "
                 "decomposition, it runs again (without the feature pillows, then with other weights of the feature paths: "
                 "those wait until the closer staircases are made where the captures before them leave boundary faces beyond "
                 "1/4 of the surface size, and so does the one without pillows where the one with them also leaves a cell "
                 "below 0.3), "
                 "and where the mesh kept still has such a cell or a boundary face beyond 1/4 of the surface size from the "
                 "input, the whole mesh is made again with the staircase 0.25, then 0.2 cell sizes off the surface instead "
                 "of 0.4 (not where those faces are its only faults and all stand over parts or gaps thinner than two "
                 "surface sizes); each retry counts the first capture's cells against the budget and runs only if they fit (a mesh "
                 "of N cells: at most budget / N retries); the best mesh is kept (faults, cells below 0.3, far faces); "
                 "0: never (default 200000)");
  app.add_flag("--all-capture-retries", all_capture_retries, "run every retry of --capture-retry-cells whatever its "
               "budget and however good the captures before it (every capture of the sequence at each of the three "
               "staircase distances, up to 18) and keep the best by the same rules: the best mesh the retries can give, "
               "for that much time (the report's boundary.captures lists them)");
  app.add_option("--smoothing-sweeps", smoothing_sweeps, "the boundary capture's main optimisation sweeps at most: more "
                 "raise the worst cells a little, at a cost in time (default 8)")->check(CLI::Range(1, 1000));
  app.add_option("--threads", threads, "threads at most (0: all of the machine's): a retry of the boundary capture "
                 "runs ahead on another thread while the one before it runs; the mesh is the same whatever the number "
                 "(default 0)")->check(CLI::Range(0, 4096));
  app.add_flag("--staircase", staircase, "keep the staircase of grid faces as the boundary: no buffer layer, no projection");
  app.add_flag("--fill-holes,!--no-fill-holes", fill_holes, "close each hole of the surface (a loop of border edges "
               "not along another one) with triangles on its rim's points (CGAL's triangulate_hole_polyline): the mesh "
               "boundary lies on the fill there, counted as caps in the fidelity; without, the hole is closed where "
               "the winding number is 0.5 (default: on)");
  app.add_flag("--strict", strict, "a leak of the seeded region (a hole in the surface) is an error: nothing is written");
  app.add_option("--patch-size", patch_size_rules, "REGEX=H[:HFINE]: cut cells meeting the input parts whose whole name "
                                                   "matches REGEX get at most H (HFINE where the surface bends beyond "
                                                   "--curvature-angle); the input's part names, before --patch-name (repeatable)");
  app.add_option("--patch-name", patch_name_rules, "REGEX=NAME: rename the patches whose whole name matches REGEX "
                                                   "(NAME may use $1...); patches given the same name are merged (repeatable)");
  app.add_option("--patch-type", patch_type_rules, "REGEX=TYPE: set the type of the patches matching REGEX (after renaming) "
                                                   "to wall, patch or symmetryPlane (repeatable; default: box faces patch, "
                                                   "surface parts wall)");
  app.add_option("--report", reports, "write a report to FILE.json or FILE.html (repeatable)");
  app.add_flag("--force", force, "overwrite existing output files and polyMesh directories");
  app.add_flag("-q,--quiet", quiet, "print nothing but errors and warnings");

  CGAL::Bbox_3 box;
  bool has_box = false;
  std::vector<std::pair<CGAL::Bbox_3, double>> rboxes;
  bool has_seed = false;
  Point_3 seed;
  std::vector<Rule> name_rules, type_rules;
  try {
    app.parse(argc, argv);
    if(size_opt->count() && !(size > 0 && std::isfinite(size))) throw CLI::ValidationError("--size", "must be a positive number");
    if(ssize_opt->count()) {
      const auto colon = surface_size_s.find(':');
      surface_size = parse_numbers(surface_size_s.substr(0, colon), 1, "--surface-size")[0];
      if(colon != std::string::npos) curvature_size = parse_numbers(surface_size_s.substr(colon + 1), 1, "--surface-size")[0];
      if(!(surface_size > 0 && std::isfinite(surface_size)) ||
         (colon != std::string::npos && !(curvature_size > 0 && std::isfinite(curvature_size))))
        throw CLI::ValidationError("--surface-size", "expected H or H:HFINE with positive numbers, got '" + surface_size_s + "'");
      if(curvature_size > surface_size)
        throw CLI::ValidationError("--surface-size", "HFINE must not exceed H in '" + surface_size_s + "'");
    }
    if(tsize_opt->count() && !(thin_size > 0 && std::isfinite(thin_size)))
      throw CLI::ValidationError("--thin-size", "must be a positive number");
    if(scale_opt->count() && !(scale > 0 && std::isfinite(scale))) throw CLI::ValidationError("--scale", "must be a positive number");
    if(fsize_opt->count() && !(feature_size > 0 && std::isfinite(feature_size)))
      throw CLI::ValidationError("--feature-size", "must be a positive number");
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
    name_rules = parse_rules(patch_name_rules, "--patch-name");
    type_rules = parse_rules(patch_type_rules, "--patch-type");
    for(const Rule& r : type_rules)
      if(r.value != "wall" && r.value != "patch" && r.value != "symmetryPlane")
        throw CLI::ValidationError("--patch-type", "'" + r.value + "' is not wall, patch or symmetryPlane");
    for(const std::string& o : outputs) {
      const std::string ext = fs::path(o).extension().string();
      if(output_kind(o) == Output_kind::OPENFOAM && !ext.empty() && fs::path(o).filename() != ".")
        throw CLI::ValidationError("--output", "'" + o + "': unknown output format '" + ext +
                                   "' (.vtu, .msh, .mesh, or a directory name without extension for an OpenFOAM case)");
    }
    for(const std::string& r : reports) {
      const std::string ext = fs::path(r).extension().string();
      if(ext != ".json" && ext != ".html")
        throw CLI::ValidationError("--report", "'" + r + "': a report is a .json or an .html file");
    }
  } catch(const CLI::ParseError& e) {
    if(e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "hexmesh: " << e.what() << "\n" << "Run 'hexmesh --help' for the options.\n";
    return USAGE;
  }
  // (--threads: TBB's limit for the whole run)
#ifdef CGAL_LINKED_WITH_TBB
  std::optional<tbb::global_control> thread_limit;
  if(threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
#endif
  const std::size_t used_threads = HM::internal::available_threads();

  // refuse to overwrite before any work; an input is never an output
  {
    std::vector<std::string> files = reports;
    for(const std::string& o : outputs)
      files.push_back(output_kind(o) == Output_kind::OPENFOAM ? (fs::path(o) / "constant" / "polyMesh").string() : o);
    auto exists = [](const std::string& p) { std::error_code ec; return fs::exists(p, ec); };
    for(const std::string& f : files) {
      for(const std::string& in : inputs) {
        std::error_code ec;
        if(exists(in) && exists(f) && fs::equivalent(in, f, ec)) {
          std::cerr << "hexmesh: " << f << " is an input; it is never overwritten\n";
          return OUTPUT;
        }
      }
      if(exists(f) && !force) {
        std::cerr << "hexmesh: " << f << " exists; use --force to overwrite it\n";
        return OUTPUT;
      }
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
    HM::IO::Surface_soup<Point_3> soup;
    for(const std::string& in : inputs) HM::IO::read_surface(in, soup, scale);
    const std::size_t read_points = soup.points.size(), read_polygons = soup.polygons;
    const double t_read = since(t);
    t = std::chrono::steady_clock::now();
    Domain domain(soup, fill_holes);
    const double t_repair = since(t);
    soup = HM::IO::Surface_soup<Point_3>();
#if defined(__GLIBC__)
    malloc_trim(0);   // the soup and the repair's work arrays were many small blocks
#endif
    const auto& sum = domain.input_summary();
    std::vector<std::string> repairs;
    auto note = [&](std::size_t n, const std::string& what) { if(n) repairs.push_back(std::to_string(n) + " " + what); };
    note(sum.merged_points, "duplicate points merged");
    note(sum.degenerate_triangles, "degenerate triangles removed");
    note(sum.duplicate_triangles, "duplicate triangles removed");
    note(sum.reversed_duplicates, "reversed duplicate triangles removed");
    note(sum.sheet_triangles, "triangles kept as two-sided zero-thickness sheets");
    note(sum.sheet_reoriented, "sheet triangles flipped so that each sheet's two sides are consistent");
    note(sum.sheet_back_parts, "parts added for the back side of sheets (NAME_back)");
    note(sum.reoriented_triangles, "triangles reoriented");
    note(sum.internal_triangles, "triangles wholly or partly inside the volume (overlapping parts) left out of the boundary");
    note(sum.split_triangles, "pieces of the partly inside ones kept");
    if(sum.filled_holes)
      repairs.push_back(std::to_string(sum.filled_holes) + " hole" + (sum.filled_holes > 1 ? "s" : "") + " filled (" +
                        std::to_string(sum.fill_triangles) + " triangles on " + std::to_string(sum.filled_rim_edges) + " rim edges)");
    if(!quiet) {
      std::cerr << "hexmesh: read " << inputs.size() << " file" << (inputs.size() > 1 ? "s" : "") << ": "
                << read_polygons << " polygons, " << read_points << " points, " << domain.patch_names().size()
                << " part" << (domain.patch_names().size() > 1 ? "s" : "") << " [" << t_read << " s]\n";
      std::cerr << "hexmesh: repair: " << (repairs.empty() ? std::string("nothing to repair") : "") ;
      for(std::size_t i = 0; i < repairs.size(); ++i) std::cerr << (i ? ", " : "") << repairs[i];
      std::cerr << " [" << t_repair << " s]\n";
      std::cerr << "hexmesh: surface: " << domain.number_of_triangles() << " triangles, " << sum.components
                << " component" << (sum.components == 1 ? "" : "s") << ", " << sum.boundary_edges << " boundary edges"
                << (sum.filled_rim_edges ? " (" + std::to_string(sum.filled_rim_edges) + " round filled holes)" : std::string()) << ", "
                << sum.non_manifold_edges << " non-manifold edges; inside test: "
                << (domain.has_exact_inside_test() ? "exact (closed surface)" : "winding number (open or inconsistent surface)")
                << "\n";
    }
    const CGAL::Bbox_3 bb = domain.bbox();
    const double extent = (std::max)({bb.xmax() - bb.xmin(), bb.ymax() - bb.ymin(), bb.zmax() - bb.zmin()});
    if(size <= 0) size = (has_box ? (std::max)({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()}) / 1.2
                                  : extent) / 10;
    if(surface_size <= 0) surface_size = size / 4;
    Criteria criteria(size, surface_size, max_level);
    if(feature_size > 0) criteria.set_feature_size(feature_size);
    if(curvature_size > 0) criteria.set_curvature_size(curvature_size, curvature_angle);
    if(thin_size <= 0) thin_size = surface_size / 4;
    if(thin_cells > 0) criteria.set_thin_part_refinement(thin_cells, thin_size);
    criteria.set_cells_between_levels(cells_between_levels);
    for(const auto& rb : rboxes) criteria.add_refinement_box(rb.first, rb.second);
    // per-part surface sizes: each rule must match a part of the input; a later rule wins
    for(const Rule& r : parse_rules(patch_size_rules, "--patch-size")) {
      double h = 0, hf = 0;
      const auto colon = r.value.find(':');
      try {
        h = parse_numbers(r.value.substr(0, colon), 1, "--patch-size")[0];
        if(colon != std::string::npos) hf = parse_numbers(r.value.substr(colon + 1), 1, "--patch-size")[0];
      } catch(const CLI::ValidationError&) {
        throw HM::Input_error("--patch-size '" + r.text + "=" + r.value + "': expected H or H:HFINE", HM::Input_error_cause::BAD_PARAMETER);
      }
      if(!(h > 0) || hf < 0 || hf > h)
        throw HM::Input_error("--patch-size '" + r.text + "=" + r.value + "': sizes must be positive and HFINE <= H", HM::Input_error_cause::BAD_PARAMETER);
      bool any = false;
      for(std::size_t p = 0; p < domain.patch_names().size(); ++p)
        if(std::regex_match(domain.patch_names()[p], r.re)) { criteria.set_patch_size(int(p), h, hf); any = true; }
      if(!any) {
        std::string names;
        for(const auto& n : domain.patch_names()) names += (names.empty() ? "" : ", ") + n;
        throw HM::Input_error("--patch-size '" + r.text + "': no input part matches (parts: " + names + ")", HM::Input_error_cause::BAD_PARAMETER);
      }
    }
    if(!patch_size_rules.empty()) criteria.set_curvature_angle(curvature_angle);
    // feature curves: reported, refined to --feature-size, followed by the boundary
    t = std::chrono::steady_clock::now();
    HM::Feature_curves_3<K>::Options fopt = HM::default_feature_curve_options<K>(criteria);
    fopt.feature_angle = feature_angle;
    if(feature_scale >= 0) fopt.scale = feature_scale;
    feature_scale = fopt.scale;
    fopt.contrast = feature_contrast;
    fopt.soft_angle = soft_crease_angle;
    if(soft_crease_angle > 0 && (soft_crease_angle >= feature_angle || (fopt.scale <= 0 && feature_contrast <= 0)))
      std::cerr << "hexmesh: warning: --soft-crease-angle " << soft_crease_angle << " makes no soft crease: it must be below "
                << "--feature-angle, with --feature-scale or --feature-contrast above 0 to judge them\n";
    const HM::Feature_curves_3<K> features(domain, fopt);
    if(feature_size > 0) domain.set_feature_edges(features.edge_vertices());
    std::vector<std::vector<Point_3>> user_lines;
    for(const std::string& f : feature_files) HM::IO::read_polylines(f, user_lines, scale);
    if(!user_lines.empty()) {
      if(feature_size <= 0)
        std::cerr << "hexmesh: warning: --features without --feature-size: the feature lines refine nothing\n";
      domain.add_feature_polylines(user_lines);
    }
    const double t_features = since(t);
    typedef HM::Feature_curves_3<K> FC;
    if(!quiet)
      std::cerr << "hexmesh: features (" << feature_angle << " degrees): " << features.number_of_edges(FC::SHARP) << " sharp, "
                << features.number_of_edges(FC::OPEN) << " open, " << features.number_of_edges(FC::NON_MANIFOLD)
                << " non-manifold, " << features.number_of_edges(FC::PATCH_BORDER) << " part-border edges";
    if(!quiet && features.number_of_smooth_edges())
      std::cerr << " (" << features.number_of_smooth_edges() << " sharp edges left out: not sharp at the scale "
                << feature_scale << " or not standing out " << feature_contrast << " times from the edges around)";
    if(!quiet && features.number_of_smooth_seam_edges())
      std::cerr << " (" << features.number_of_smooth_seam_edges() << " open edges left out: along a seam or a crack, smooth "
                << "across it or the second side of a crease; " << features.number_of_seam_bridges() << " curve ends joined across it)";
    if(!quiet && features.number_of_smooth_hole_rim_edges())
      std::cerr << " (" << features.number_of_smooth_hole_rim_edges() << " open edges left out: rims of holes in a smooth surface)";
    if(!quiet && features.number_of_smooth_filled_rim_edges())
      std::cerr << " (" << features.number_of_smooth_filled_rim_edges() << " rim edges of filled holes left out: smooth with their fill)";
    if(!quiet && fopt.soft_angle > 0)
      std::cerr << "; " << features.number_of_edges(FC::SOFT) << " soft creases (" << soft_crease_angle << " degrees; "
                << features.number_of_smooth_soft_edges() << " left out)";
    if(!quiet)
      std::cerr << "; "
                << features.curves().size() << " curves, " << features.corners().size() << " corners\n";

    Mesh mesh;
    HM::Status status;
    std::vector<HM::Region_leak> leaks;
    namespace HP = HM::parameters;
    if(!has_box) {
      box = CGAL::Bbox_3(bb.xmin() - size, bb.ymin() - size, bb.zmin() - size, bb.xmax() + size, bb.ymax() + size, bb.zmax() + size);
    }
    const std::size_t cell_limit = max_cells > 0 ? max_cells : std::size_t(-1);
    // (CGAL's `visitor` must come last: its pack only chains CGAL's own names)
    HM::Meshing_statistics stats;
    if(has_seed)
      status = CGAL::make_hex_mesh_3<CGAL::Parallel_if_available_tag>(domain, criteria, mesh, HP::region_seed(seed).meshing_box(box).max_cells(cell_limit)
                                                               .leaks(std::back_inserter(leaks)).statistics(&stats)
                                                               .body_fitted(!staircase).feature_curves(&features)
                                                               .feature_pillows(feature_pillows)
                                                               .capture_retry_cells(capture_retry_cells).all_capture_retries(all_capture_retries)
                                                               .smoothing_sweeps(smoothing_sweeps)
                                                               .visitor(std::ref(progress)));
    else
      status = CGAL::make_hex_mesh_3<CGAL::Parallel_if_available_tag>(domain, criteria, mesh, HP::meshing_box(box).max_cells(cell_limit)
                                                               .leaks(std::back_inserter(leaks)).statistics(&stats)
                                                               .body_fitted(!staircase).feature_curves(&features)
                                                               .feature_pillows(feature_pillows)
                                                               .capture_retry_cells(capture_retry_cells).all_capture_retries(all_capture_retries)
                                                               .smoothing_sweeps(smoothing_sweeps)
                                                               .visitor(std::ref(progress)));
    if(!quiet && !staircase) {
      std::cerr << "hexmesh: boundary: " << stats.staircase_removed_cells << " staircase cells removed for room, "
                << stats.buffer_cells << " buffer cells (" << stats.pillow_cells << " in feature pillows), " << stats.surface_vertices << " vertices on the surface ("
                << stats.curve_vertices << " on " << stats.curves_captured << " feature curves, " << stats.corner_vertices
                << " on corners, " << stats.cap_vertices << " capping holes), " << stats.curve_gaps << " curve ends short of their corner, " << stats.curve_turns.size() << " chain turns left off their curve, " << stats.curves_missed
                << " curves missed, " << stats.unreached_vertices.size() << " vertices could not reach the surface, "
                << stats.removed_buffer_cells << " buffer cells could not be made valid (removed)";
      if(stats.staircase_tries > 1)
        std::cerr << "; the mesh made " << stats.staircase_tries << " times, the one with the staircase " << stats.staircase_gap
                  << " cell sizes off the surface kept";
      if(stats.far_faces_over_thin_parts)
        std::cerr << "; its faces beyond 1/4 surface size all stand over parts or gaps thinner than two surface sizes "
                     "(--thin-cells meshes them), so it was not made again with the staircase closer";
      std::cerr << "\n";
      // the retries' search, capture by capture (where there was one)
      if(stats.captures.size() > 1) {
        std::size_t k = 0;
        for(const CGAL::Hex_meshing_3::Capture_record& r : stats.captures) {
          std::cerr << "hexmesh: capture " << ++k << " of " << stats.captures.size() << ": staircase " << r.staircase_gap
                    << ", " << (r.feature_pillows ? "pillows, " : "") << "paths " << std::setprecision(3) << r.paths_ratio
                    << (r.rerun ? ", rerun removing its OpenFOAM faults" : "") << (r.ran_ahead ? ", run ahead" : "") << ": ";
          if(r.evaluated)
            std::cerr << r.openfoam_faults_found << " OpenFOAM faults found, " << r.openfoam_faults_left << " left, "
                      << r.cells_below_0_3 << " cells below 0.3, min " << r.min_scaled_jacobian << ", " << r.far_faces
                      << " faces beyond 1/4 surface size, ";
          std::cerr << r.seconds << " s" << (r.kept ? " (kept for its staircase)" : "") << std::setprecision(6) << "\n";
        }
        for(const CGAL::Hex_meshing_3::Staircase_record& r : stats.staircases)
          if(r.evaluated)
            std::cerr << "hexmesh: staircase " << r.gap << (r.deferred_weights ? " (its deferred captures)" : "") << ": "
                      << r.captures << " captures, " << r.far_faces << " faces beyond 1/4 surface size, "
                      << r.openfoam_faults << " OpenFOAM faults, " << r.cells_below_0_3 << " cells below 0.3, min "
                      << std::setprecision(3) << r.min_scaled_jacobian << ", " << r.seconds << " s" << std::setprecision(6)
                      << (r.pillow_free_deferred ? " (the capture without pillows and other path weights deferred: far faces)" :
                          r.weights_deferred ? " (other path weights deferred: far faces)" : "") << (r.kept ? " (kept)" : "") << "\n";
      }
    }
    if(!quiet && (stats.trimmed_cells || stats.disconnected_cells))
      std::cerr << "hexmesh: " << stats.trimmed_cells << " cells trimmed (fingers and plates one cell thick)"
                << (stats.disconnected_cells ? ", " + std::to_string(stats.disconnected_cells) +
                                                   " cells cut off from the seed's region by trimming removed" : std::string())
                << "\n";
    if(status == HM::Status::CANCELED)
      std::cerr << "hexmesh: warning: cancelled; the valid, coarser mesh reached so far is kept\n";
    if(status == HM::Status::CELL_LIMIT_REACHED)
      std::cerr << "hexmesh: warning: refinement stopped before exceeding --max-cells " << max_cells
                << "; the mesh is valid but coarser than the sizes asked for\n";
    for(std::size_t i = 0; i < leaks.size(); ++i) {
      if(i == 10) {
        std::fprintf(stderr, "hexmesh: %s: ... and %zu more leaks (all are in the report)\n", strict ? "error" : "warning",
                     leaks.size() - 10);
        break;
      }
      const HM::Region_leak& l = leaks[i];
      std::fprintf(stderr, "hexmesh: %s: leak %zu: the region reached %zu cells (volume %.6g) inside a body, through "
                           "%zu faces (area %.6g) in the box (%.6g, %.6g, %.6g) - (%.6g, %.6g, %.6g): a hole in the "
                           "surface there%s; %s\n",
                   strict ? "error" : "warning", i + 1, l.cells, l.volume, l.passage_faces, l.passage_area,
                   l.passage.xmin(), l.passage.ymin(), l.passage.zmin(), l.passage.xmax(), l.passage.ymax(), l.passage.zmax(),
                   l.cut_off_cells ? (" (and " + std::to_string(l.cut_off_cells) + " cells reachable only through it)").c_str() : "",
                   strict ? "nothing is written (--strict)" : "these cells are not meshed (the winding number decides)");
    }
    if(strict && !leaks.empty()) return INPUT;
    if(mesh.number_of_cells() == 0) {
      std::cerr << "hexmesh: " << inputs[0] << ": the region is empty: no cell of the grid lies "
                << (has_seed ? "in the seeded region" : "inside the surface")
                << " (is the surface open, or the surface size too coarse for its thinnest part?)\n";
      return INPUT;
    }

    // patches: rename / merge, then types; the box faces' patches are remembered (box contacts)
    std::vector<std::string> box_patch_names(mesh.patch_names.begin(), mesh.patch_names.begin() + 6);
    if(!name_rules.empty()) {
      auto rename = [&](const std::string& n) {
        std::smatch m;
        for(const Rule& r : name_rules)
          if(std::regex_match(n, m, r.re)) return m.format(r.value);
        return n;
      };
      std::vector<std::pair<std::string, std::vector<std::string>>> merged;   // new name -> old types
      for(std::size_t p = 0; p < mesh.patch_names.size(); ++p) {
        const std::string n = rename(mesh.patch_names[p]);
        if(n.empty()) {
          std::cerr << "hexmesh: --patch-name: patch '" << mesh.patch_names[p] << "' would get an empty name\n";
          return USAGE;
        }
        auto it = std::find_if(merged.begin(), merged.end(), [&](const auto& x) { return x.first == n; });
        if(it == merged.end()) merged.push_back({n, {mesh.patch_type(p)}});
        else it->second.push_back(mesh.patch_type(p));
      }
      for(const auto& m : merged)
        for(const std::string& t : m.second)
          if(t != m.second.front()) {
            std::cerr << "hexmesh: warning: patch '" << m.first << "' merges patches of types " << m.second.front()
                      << " and " << t << "; it gets type " << m.second.front() << " (choose with --patch-type)\n";
            break;
          }
      mesh.rename_patches(rename);
      for(std::string& n : box_patch_names) n = rename(n);
    }
    mesh.patch_types.resize(mesh.patch_names.size());
    for(std::size_t p = 0; p < mesh.patch_names.size(); ++p) {
      mesh.patch_types[p] = mesh.patch_type(p);
      for(const Rule& r : type_rules)
        if(std::regex_match(mesh.patch_names[p], r.re)) mesh.patch_types[p] = r.value;
    }

    t = std::chrono::steady_clock::now();
    domain.release_search_tree();   // the quality measures make no surface query: the memory peak
    HM::Polyhedral_mesh_3 pm;
    pm.build(mesh);
    // an OpenFOAM case gets its hanging nodes bulged slightly (write_OpenFOAM): the quality is
    // then measured on what is written there, as checkMesh measures it
    bool foam_output = false;
    for(const std::string& o : outputs) foam_output = foam_output || output_kind(o) == Output_kind::OPENFOAM;
    // (the points are computed for the report's count of concave cells even without such output;
    // the bulged ones are kept apart and swapped into `mesh` where needed: a copy of the whole
    // mesh took 20 MB more at the peak on motorBike)
    std::vector<K::Point_3> bulged;
    std::size_t foam_concave = 0, foam_face_tets = 0, foam_small_determinant = 0;
    HM::Mesh_quality::Range foam_determinant;
    {
      const auto x = HM::IO::internal::foam_points(mesh, HM::IO::default_hanging_bulge, &pm,
                                                   HM::IO::default_max_hanging_bulge, &foam_concave);
      {
        HM::OpenFOAM_geometry g;
        g.compute_cells(x, pm);   // (the faces' geometry is not kept: a memory peak)
        const std::vector<char> ft = HM::face_tet_errors(x, pm, g);
        foam_face_tets = std::size_t(std::count(ft.begin(), ft.end(), char(1)));
      }
      {
        const std::vector<double> det = HM::cell_determinants(x, pm);
        foam_small_determinant = std::size_t(std::count_if(det.begin(), det.end(), [](double d) {
          return d < HM::openfoam_min_cell_determinant; }));
        foam_determinant = HM::Mesh_quality::range(det);
      }
      if(foam_output && mesh.has_hanging_nodes()) {   // (after the geometry is freed: a memory peak)
        bulged.reserve(x.size());
        for(std::size_t v = 0; v < x.size(); ++v) bulged.push_back(K::Point_3(x[v][0], x[v][1], x[v][2]));
      }
    }
    const bool has_bulged = !bulged.empty();
    if(has_bulged) mesh.points.swap(bulged);
    HM::Mesh_quality q = HM::compute_quality(mesh, pm);
    if(has_bulged) mesh.points.swap(bulged);
    // the other outputs (VTU, MSH, Medit) hold the points as they are: their cells' scaled
    // Jacobians, which the capture's retries judged, are said too (and the VTU carries them)
    const std::vector<double> bulged_mesh_points_sj = has_bulged ? HM::cell_scaled_jacobians(mesh) : std::vector<double>();
    const std::vector<double>& mesh_points_sj = has_bulged ? bulged_mesh_points_sj : q.scaled_jacobian;
    const double t_quality = since(t);
    const auto sj = HM::Mesh_quality::range(q.scaled_jacobian);
    const auto sj_mesh_points = HM::Mesh_quality::range(mesh_points_sj);
    const auto no = HM::Mesh_quality::range(q.non_orthogonality);
    const auto sk = HM::Mesh_quality::range(q.skewness);
    const auto ar = HM::Mesh_quality::range(q.aspect_ratio);
    if(q.number_of_inverted_cells() > 0) {
      std::cerr << "hexmesh: internal error: " << q.number_of_inverted_cells() << " inverted cells; nothing written\n";
      return INVALID;
    }
    double volume = 0;
    for(double v : q.cell_volume) volume += v;

    // the report's quality details first: the per-face quality arrays are freed before the
    // outputs are written (the writers' work arrays come on top of the rest)
    nlohmann::ordered_json jquality;
    if(!reports.empty()) {
      auto rj = [](const HM::Mesh_quality::Range& r) { return nlohmann::ordered_json{{"min", r.min}, {"mean", r.mean}, {"max", r.max}}; };
      jquality = {{"scaled_jacobian", rj(sj)}, {"non_orthogonality", rj(no)}, {"skewness", rj(sk)}, {"aspect_ratio", rj(ar)}};
      // which points these are: an OpenFOAM case's (its hanging nodes bulged, as checkMesh sees
      // them) where one is written and the mesh has hanging nodes, else the mesh's; and the
      // scaled Jacobian on the mesh's points (those of the VTU, MSH and Medit outputs) in both cases
      jquality["measured_on"] = has_bulged ? "openfoam_case_points" : "mesh_points";
      jquality["mesh_points_scaled_jacobian"] = rj(sj_mesh_points);
      add_quality_details(jquality, mesh, pm, q);
      // as checkMesh -allGeometry counts them on the OpenFOAM export (hanging nodes bulged)
      jquality["concave_cells"] = foam_concave;
      jquality["face_tet_errors"] = foam_face_tets;
      jquality["cell_determinant"] = {{"min", foam_determinant.min}, {"mean", foam_determinant.mean}};   // checkMesh's "wellposedness"
      jquality["small_determinant_cells"] = foam_small_determinant;   // checkMesh: "Cells with small determinant (< 0.001)"
    }
    for(auto* v : {&q.aspect_ratio, &q.non_orthogonality, &q.skewness, &q.cell_volume, &q.face_warpage})
      std::vector<double>().swap(*v);   // the VTU and the HTML report still need the scaled Jacobian
    std::vector<char>().swap(q.concave);
    t = std::chrono::steady_clock::now();
    for(const std::string& o : outputs) {
      bool ok = false;
      switch(output_kind(o)) {
        case Output_kind::VTU: ok = HM::IO::write_VTU(o, mesh, mesh_points_sj); break;
        case Output_kind::MSH: ok = HM::IO::write_MSH(o, mesh); break;
        case Output_kind::MEDIT: ok = HM::IO::write_Medit(o, mesh); break;
        // the points with bulged hanging nodes are already in `bulged` (if there are any)
        case Output_kind::OPENFOAM:
          if(bulged.empty()) ok = HM::IO::write_OpenFOAM(o, mesh, pm, HM::IO::default_hanging_bulge);
          else {
            mesh.points.swap(bulged);
            ok = HM::IO::write_OpenFOAM(o, mesh, pm, 0.0);
            mesh.points.swap(bulged);
          }
          break;
      }
      if(!ok) { std::cerr << "hexmesh: cannot write " << o << "\n"; return OUTPUT; }
    }
    const double t_write = since(t);
    const double total = since(t_start);
    std::vector<K::Point_3>().swap(bulged);   // written: the report's measures below run on `mesh`
    const std::size_t nboundary = mesh.boundary_faces.size();

    if(!quiet) {
      std::printf("cells %zu  vertices %zu  hanging nodes %zu  boundary faces %zu  polyhedral faces %zu  volume %.9g\n",
                  mesh.number_of_cells(), mesh.number_of_vertices(), mesh.hanging_nodes.size(), nboundary, pm.faces.size(), volume);
      std::printf("scaled Jacobian    min %.6g  mean %.6g  max %.6g\n", sj.min, sj.mean, sj.max);
      if(has_bulged)
        std::printf("                   (on the OpenFOAM case's points, hanging nodes bulged; on the mesh's, as the other outputs hold them: min %.6g  mean %.6g)\n",
                    sj_mesh_points.min, sj_mesh_points.mean);
      std::printf("non-orthogonality  min %.6g  mean %.6g  max %.6g  (degrees, internal faces)\n", no.min, no.mean, no.max);
      std::printf("skewness           min %.6g  mean %.6g  max %.6g\n", sk.min, sk.mean, sk.max);
      std::printf("aspect ratio       min %.6g  mean %.6g  max %.6g\n", ar.min, ar.mean, ar.max);
      std::printf("status %s  seconds %.3f  peak memory %.1f MiB\n", HM::status_name(status), total, peak_memory_mib());
      for(const std::string& o : outputs) std::printf("wrote %s\n", o.c_str());
    }
    // the boundary's fidelity (both ways; the report gives the details): measured on every run,
    // so that a part of the input lost or capped is said even without a report
    HM::Boundary_fidelity fid;
    bool have_fid = false;
    // the feature curves' fidelity, strict and within the angle tolerance, measured for a report
    // (the summary then says it too)
    const double feature_tolerance = (std::min)(10.0, feature_angle / 2);
    std::optional<std::pair<HM::Feature_fidelity, HM::Feature_fidelity>> feature_fids;
    // its faces farther than r surface sizes from the input
    auto faces_beyond = [&](double r) {
      return std::size_t(std::count_if(fid.face_distances.begin(), fid.face_distances.end(),
                                       [&](const auto& fd) { return fd.first > r * surface_size; }));
    };
    if(!reports.empty()) {
      nlohmann::ordered_json j;
      j["inputs"] = inputs;
      j["options"] = {{"size", size}, {"surface_size", surface_size}, {"curvature_size", curvature_size},
                      {"curvature_angle", curvature_angle}, {"thin_cells", thin_cells},
                      {"thin_size", thin_cells > 0 ? thin_size : 0.0}, {"cells_between_levels", cells_between_levels},
                      {"feature_pillows", feature_pillows}, {"capture_retry_cells", capture_retry_cells}, {"all_capture_retries", all_capture_retries}, {"smoothing_sweeps", smoothing_sweeps},
                      {"threads", used_threads},
                      {"feature_angle", feature_angle}, {"soft_crease_angle", soft_crease_angle},
                      {"feature_size", feature_size}, {"scale", scale}, {"max_level", max_level},
                      {"max_cells", max_cells}, {"region", region}, {"strict", strict}, {"fill_holes", fill_holes},
                      {"box", {box.xmin(), box.ymin(), box.zmin(), box.xmax(), box.ymax(), box.zmax()}},
                      {"patch_name", patch_name_rules}, {"patch_size", patch_size_rules}, {"patch_type", patch_type_rules}};
      j["input_summary"] = {{"polygons_read", read_polygons}, {"points_read", read_points},
                            {"triangles", domain.number_of_triangles()}, {"parts", domain.patch_names().size()},
                            {"components", sum.components}, {"boundary_edges", sum.boundary_edges},
                            {"non_manifold_edges", sum.non_manifold_edges}, {"closed", sum.closed},
                            {"self_intersecting", sum.self_intersecting}, {"exact_inside_test", sum.exact_inside_test}};
      j["repair"] = {{"merged_points", sum.merged_points}, {"degenerate_triangles", sum.degenerate_triangles},
                     {"duplicate_triangles", sum.duplicate_triangles}, {"reversed_duplicates", sum.reversed_duplicates},
                     {"sheet_triangles", sum.sheet_triangles}, {"sheet_reoriented", sum.sheet_reoriented},
                     {"sheet_back_parts", sum.sheet_back_parts}, {"reoriented_triangles", sum.reoriented_triangles},
                     {"internal_triangles", sum.internal_triangles}, {"split_triangle_pieces_kept", sum.split_triangles},
                     {"filled_holes", sum.filled_holes}, {"fill_triangles", sum.fill_triangles},
                     {"filled_rim_edges", sum.filled_rim_edges}};
      j["features"] = {{"feature_angle", feature_angle}, {"feature_size", feature_size}, {"sharp_edges", features.number_of_edges(FC::SHARP)},
                       {"feature_scale", feature_scale}, {"feature_contrast", feature_contrast}, {"smooth_edges_left_out", features.number_of_smooth_edges()},
                       {"soft_crease_edges", features.number_of_edges(FC::SOFT)}, {"soft_crease_edges_left_out", features.number_of_smooth_soft_edges()},
                       {"open_edges", features.number_of_edges(FC::OPEN)},
                       {"input_open_edges", features.number_of_edges(FC::OPEN) + features.number_of_smooth_seam_edges() +
                                            features.number_of_smooth_hole_rim_edges() + sum.filled_rim_edges},
                       {"hole_rim_edges_left_out", features.number_of_smooth_hole_rim_edges()},
                       {"filled_rim_edges_left_out", features.number_of_smooth_filled_rim_edges()},
                       {"seam_edges_left_out", features.number_of_smooth_seam_edges()},
                       {"seam_bridges", features.number_of_seam_bridges()},
                       {"non_manifold_edges", features.number_of_edges(FC::NON_MANIFOLD)},
                       {"part_border_edges", features.number_of_edges(FC::PATCH_BORDER)},
                       {"curves", features.curves().size()}, {"corners", features.corners().size()},
                       {"user_lines", user_lines.size()}, {"user_segments", domain.feature_segments().size()}};
      nlohmann::ordered_json jl = nlohmann::ordered_json::array();
      for(const HM::Region_leak& l : leaks) {
        auto bj = [](const CGAL::Bbox_3& b) { return nlohmann::ordered_json{b.xmin(), b.ymin(), b.zmin(), b.xmax(), b.ymax(), b.zmax()}; };
        jl.push_back({{"cells", l.cells}, {"volume", l.volume}, {"bbox", bj(l.bbox)}, {"passage", bj(l.passage)},
                      {"passage_faces", l.passage_faces}, {"passage_area", l.passage_area},
                      {"max_winding_number", l.max_winding_number}, {"cut_off_cells", l.cut_off_cells},
                      {"cut_off_volume", l.cut_off_volume}});
      }
      j["leaks"] = jl;
      j["status"] = HM::status_name(status);
      j["counts"] = {{"cells", mesh.number_of_cells()}, {"vertices", mesh.number_of_vertices()},
                     {"hanging_nodes", mesh.hanging_nodes.size()}, {"boundary_faces", nboundary},
                     {"polyhedral_faces", pm.faces.size()}, {"internal_faces", pm.number_of_internal_faces()}};
      j["volume"] = volume;
      // what needs the polyhedral mesh comes first: it is freed before the fidelity builds its
      // trees
      const HM::Surface_topology boundary_topology = HM::boundary_topology(pm);
      std::vector<char> box_patch(mesh.patch_names.size(), 0);
      for(std::size_t p = 0; p < mesh.patch_names.size(); ++p)
        box_patch[p] = std::find(box_patch_names.begin(), box_patch_names.end(), mesh.patch_names[p]) != box_patch_names.end();
      const HM::Box_contacts bc = HM::box_contacts(mesh, pm, domain, box_patch);
      pm = HM::Polyhedral_mesh_3();
      {
        const auto tf = std::chrono::steady_clock::now();
        fid = HM::boundary_fidelity(mesh, domain, 10000);
        have_fid = true;
        auto loc = [](const std::array<double, 3>& p) { return nlohmann::ordered_json{p[0], p[1], p[2]}; };
        j["fidelity"] = {{"surface_faces", fid.surface_faces}, {"cap_faces", fid.cap_faces}, {"cap_area", fid.cap_area}, {"mesh_to_input_max", fid.max_face_distance},
                         {"mesh_to_input_mean", fid.mean_face_distance}, {"mesh_to_input_worst_at", loc(fid.worst_face_location)},
                         {"samples", fid.samples}, {"input_to_mesh_max", fid.max_sample_distance},
                         {"input_to_mesh_mean", fid.mean_sample_distance}, {"input_to_mesh_worst_at", loc(fid.worst_sample_location)},
                         {"surface_size", surface_size}};
        // the faces beyond 1/4, farthest first, each with why it stands off (`far_faces()`)
        const std::vector<HM::Far_face> far = HM::far_faces(mesh, fid, 0.25 * surface_size);
        nlohmann::ordered_json causes = {{"hanging_corner", 0}, {"cap_corner", 0}, {"corner", 0}, {"folded", 0}, {"bent", 0}};
        for(const HM::Far_face& ff : far) {
          auto& n = causes[HM::far_face_cause_name(ff.cause)];
          n = n.get<std::size_t>() + 1;
        }
        nlohmann::ordered_json jf = nlohmann::ordered_json::array();
        for(std::size_t i = 0; i < far.size() && i < 50; ++i)
          jf.push_back({{"distance", far[i].distance}, {"at", loc(far[i].at)}, {"cause", HM::far_face_cause_name(far[i].cause)},
                        {"fold", far[i].fold}, {"size", far[i].size}});
        // faces farther than 1/4, 1/2 and 1 surface size (the bound is 1/4)
        j["fidelity"]["faces_beyond_quarter_surface_size"] = faces_beyond(0.25);
        j["fidelity"]["faces_beyond_half_surface_size"] = faces_beyond(0.5);
        j["fidelity"]["faces_beyond_surface_size"] = faces_beyond(1.0);
        j["fidelity"]["far_face_causes"] = causes;
        j["fidelity"]["farthest_faces"] = jf;
        // the feature curves: input sharp, open and non-manifold edges against the mesh
        // boundary's edges of the same dihedral angle, both ways; input corners against the
        // nearest boundary vertex
        const HM::Feature_fidelity ff = HM::feature_fidelity(mesh, domain, features, feature_angle);
        auto finite = [](double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr); };
        j["feature_fidelity"] = {{"input_feature_edges", ff.input_feature_edges}, {"mesh_feature_edges", ff.mesh_feature_edges},
                                 {"input_to_mesh", finite(ff.input_to_mesh)}, {"input_to_mesh_worst_at", loc(ff.worst_input_location)},
                                 {"mesh_to_input", finite(ff.mesh_to_input)}, {"mesh_to_input_worst_at", loc(ff.worst_mesh_location)},
                                 {"corners", ff.corners}, {"max_corner_distance", finite(ff.max_corner_distance)},
                                 {"worst_corner_at", loc(ff.worst_corner_location)}, {"sample_spacing", ff.sample_spacing}};
        // the same within an angle tolerance: each side against the other's edges at 10 degrees
        // less (all the input's edges there, unfiltered), so that a crease near the angle is not
        // counted as missed or invented for lying on the other side of it
        {
          HM::Feature_curves_3<K>::Options lopt = fopt;
          lopt.feature_angle = feature_angle - feature_tolerance;
          lopt.scale = 0;
          lopt.contrast = 0;   // (and so no soft crease)
          const HM::Feature_curves_3<K> loose(domain, lopt);
          const HM::Feature_fidelity ft =
              HM::feature_fidelity_with_tolerance(mesh, domain, features, loose, feature_angle, feature_tolerance, ff.sample_spacing);
          feature_fids.emplace(ff, ft);
          j["feature_fidelity"]["within_tolerance"] = {
              {"tolerance_degrees", feature_tolerance},
              {"input_to_mesh", finite(ft.input_to_mesh)}, {"input_to_mesh_worst_at", loc(ft.worst_input_location)},
              {"mesh_to_input", finite(ft.mesh_to_input)}, {"mesh_to_input_worst_at", loc(ft.worst_mesh_location)}};
        }
        j["fidelity"]["seconds"] = since(tf);
        auto tj = [](const HM::Surface_topology& t) {
          return nlohmann::ordered_json{{"components", t.components}, {"euler_characteristic", t.euler_characteristic},
                                        {"vertices", t.vertices}, {"edges", t.edges}, {"faces", t.faces},
                                        {"boundary_edges", t.boundary_edges}};
        };
        j["topology"] = {{"input", tj(HM::surface_topology(domain))}, {"mesh_boundary", tj(boundary_topology)}};
        // where a body touches or crosses a box face: the holes of the box patches, the body's
        // section and the filled wedge around it (`bc`, above)
        const auto& box_names = HM::box_face_names();
        nlohmann::ordered_json jfaces = nlohmann::ordered_json::array(), jc = nlohmann::ordered_json::array();
        for(int p = 0; p < 6; ++p)
          jfaces.push_back({{"patch", box_names[std::size_t(p)]}, {"area", bc.face_area[std::size_t(p)]}, {"meshed_area", bc.meshed_area[std::size_t(p)]},
                            {"unmeshed_area", bc.unmeshed_area[std::size_t(p)]}, {"unmeshed_at_border", bc.border_area[std::size_t(p)]}});
        for(std::size_t i = 0; i < bc.contacts.size() && i < 100; ++i) {
          const HM::Box_contact& c = bc.contacts[i];
          jc.push_back({{"patch", box_names[std::size_t(c.patch)]}, {"area", c.area}, {"body_area", c.body_area}, {"filled_area", c.filled_area},
                        {"max_gap", c.max_gap}, {"samples", c.samples}, {"centre", loc(c.centre)},
                        {"bbox", {c.bbox.xmin(), c.bbox.ymin(), c.bbox.zmin(), c.bbox.xmax(), c.bbox.ymax(), c.bbox.zmax()}}});
        }
        j["box_contacts"] = {{"filled_area", bc.filled_area}, {"contacts", bc.contacts.size()}, {"faces", jfaces}, {"first_100", jc}};
        if(!quiet)
          for(std::size_t i = 0; i < bc.contacts.size() && i < 10; ++i) {
            const HM::Box_contact& c = bc.contacts[i];
            std::cerr << "hexmesh: contact with the box face " << box_names[std::size_t(c.patch)] << " at (" << c.centre[0] << ", " << c.centre[1]
                      << ", " << c.centre[2] << "): " << c.area << " left out of the mesh, " << c.body_area << " inside the input, "
                      << c.filled_area << " filled (a wedge up to " << c.max_gap << " thick)\n";
          }
      }
      nlohmann::ordered_json jp = nlohmann::ordered_json::array();
      const auto psizes = mesh.patch_sizes();
      for(std::size_t p = 0; p < mesh.patch_names.size(); ++p)
        jp.push_back({{"name", mesh.patch_names[p]}, {"type", mesh.patch_type(p)}, {"faces", psizes[p]}});
      j["patches"] = jp;
      nlohmann::ordered_json sec;
      sec["read"] = t_read;
      sec["repair"] = t_repair;
      sec["features"] = t_features;
      // (a phase run several times, by the staircase retries: the sum)
      for(const auto& s : progress.seconds) sec[s.first] = (sec.contains(s.first) ? sec[s.first].get<double>() : 0.0) + s.second;
      sec["quality"] = t_quality; sec["write"] = t_write; sec["total"] = total;
      j["seconds"] = sec;
      j["peak_memory_mib"] = peak_memory_mib();
      {
        nlohmann::ordered_json pk = nlohmann::ordered_json::object();
        for(const auto& pp : progress.peaks) pk[pp.first] = (std::max)(pk.contains(pp.first) ? pk[pp.first].get<double>() : 0.0, pp.second);
        j["peak_memory_mib_by_phase"] = pk;
      }
      {
        // grid speed: leaf cells of the balanced grid per second of refine + balance + classify
        // (all of the grids the staircase retries made: each has the same leaves)
        std::size_t leaves = 0, grids = 0;
        double grid_seconds = 0;
        for(const auto& w : progress.work) if(w.first == "classify") { leaves = w.second; ++grids; }
        for(const auto& s : progress.seconds)
          if(s.first == "refine" || s.first == "balance" || s.first == "classify") grid_seconds += s.second;
        if(!staircase) {
          // the first 100 of a list of points
          auto first_100 = [](const std::vector<std::array<double, 3>>& pts) {
            nlohmann::ordered_json a = nlohmann::ordered_json::array();
            for(std::size_t i = 0; i < pts.size() && i < 100; ++i) a.push_back({pts[i][0], pts[i][1], pts[i][2]});
            return a;
          };
          j["boundary"] = {{"staircase_removed_cells", stats.staircase_removed_cells}, {"buffer_cells", stats.buffer_cells},
                           {"pillow_cells", stats.pillow_cells}, {"removed_buffer_cells", stats.removed_buffer_cells}, {"skewed_faces", stats.skewed_faces}, {"non_orthogonal_faces", stats.non_orthogonal_faces}, {"foam_fault_cells", stats.foam_fault_cells},
                           {"unsnapped_vertices", stats.unsnapped_vertices}, {"feature_joint_moves", stats.feature_joint_moves}, {"face_split_repairs", stats.face_split_repairs}, {"split_warp_repairs", stats.split_warp_repairs}, {"concave_repairs", stats.concave_repairs}, {"non_orthogonality_repairs", stats.non_orthogonality_repairs}, {"polish_moves", stats.polish_moves}, {"polish_patches", stats.polish_patches}, {"fidelity_moves", stats.fidelity_moves}, {"turn_moves", stats.turn_moves}, {"turn_far_moves", stats.turn_far_moves}, {"capture_tries", stats.capture_tries}, {"capture_choice", stats.capture_choice}, {"staircase_tries", stats.staircase_tries}, {"staircase_gap", stats.staircase_gap}, {"far_faces_over_thin_parts", stats.far_faces_over_thin_parts}, {"loosened_vertices", stats.loosened_vertices}, {"surface_vertices", stats.surface_vertices},
                           {"curve_vertices", stats.curve_vertices}, {"corner_vertices", stats.corner_vertices},
                           {"cap_vertices", stats.cap_vertices}, {"curves_captured", stats.curves_captured},
                           {"curves_missed", stats.curves_missed}, {"curve_gaps", stats.curve_gaps}, {"corner_edge_searches", stats.corner_edge_searches}, {"optimisation_passes", stats.optimisation_passes},
                           {"unreached_vertices", stats.unreached_vertices.size()}, {"unreached_first_100", first_100(stats.unreached_vertices)}};
          j["boundary"]["removed_buffer_cells_first_100"] = first_100(stats.removed_buffer_cell_centres);
          {
            nlohmann::ordered_json caps = nlohmann::ordered_json::array(), stairs = nlohmann::ordered_json::array();
            for(const CGAL::Hex_meshing_3::Capture_record& r : stats.captures) {
              nlohmann::ordered_json c = {{"staircase_gap", r.staircase_gap}, {"choice", r.choice}, {"feature_pillows", r.feature_pillows},
                                          {"paths_ratio", r.paths_ratio}, {"rerun", r.rerun}, {"ran_ahead", r.ran_ahead},
                                          {"seconds", r.seconds}, {"cells", r.cells}, {"evaluated", r.evaluated}};
              if(r.evaluated) {
                c["openfoam_faults_found"] = r.openfoam_faults_found;
                c["openfoam_faults_left"] = r.openfoam_faults_left;
                c["cells_below_0_3"] = r.cells_below_0_3;
                c["min_scaled_jacobian"] = r.min_scaled_jacobian;
                c["far_faces"] = r.far_faces;
              }
              c["kept"] = r.kept;
              caps.push_back(c);
            }
            for(const CGAL::Hex_meshing_3::Staircase_record& r : stats.staircases) {
              nlohmann::ordered_json c = {{"gap", r.gap}, {"captures", r.captures}, {"seconds", r.seconds}, {"evaluated", r.evaluated},
                                          {"weights_deferred", r.weights_deferred}, {"pillow_free_deferred", r.pillow_free_deferred},
                                          {"deferred_weights", r.deferred_weights}};
              if(r.evaluated) {
                c["far_faces"] = r.far_faces;
                c["openfoam_faults"] = r.openfoam_faults;
                c["cells_below_0_3"] = r.cells_below_0_3;
                c["min_scaled_jacobian"] = r.min_scaled_jacobian;
              }
              c["kept"] = r.kept;
              stairs.push_back(c);
            }
            j["boundary"]["captures"] = caps;
            j["boundary"]["staircases"] = stairs;
          }
          j["boundary"]["curve_turns"] = stats.curve_turns.size();
          j["boundary"]["curve_turns_first_100"] = first_100(stats.curve_turns);
          j["boundary"]["missed_curves_first_100"] = first_100(stats.missed_curves);
          j["boundary"]["unsnapped_first_100"] = first_100(stats.unsnapped_at);
          nlohmann::ordered_json cs = nlohmann::ordered_json::object();
          for(const auto& st : stats.capture_seconds) cs[st.first] = st.second;
          j["boundary"]["step_seconds"] = cs;
          nlohmann::ordered_json ps = nlohmann::ordered_json::object();
          for(const auto& st : stats.capture_substep_seconds) ps[st.first] = st.second;
          j["boundary"]["substep_seconds"] = ps;
        }
        j["grid"] = {{"initial_cells", {stats.initial_cells[0], stats.initial_cells[1], stats.initial_cells[2]}},
                     {"leaf_cells", leaves}, {"cut_leaves", stats.cut_leaves}, {"balance_splits", stats.balance_splits},
                     {"components", stats.components}, {"trimmed_cells", stats.trimmed_cells},
                     {"disconnected_cells", stats.disconnected_cells}, {"max_level", stats.max_level_reached},
                     {"seconds", grid_seconds},
                     {"leaf_cells_per_second", grid_seconds > 0 ? double(leaves * grids) / grid_seconds : 0.0}};
      }
      j["quality"] = std::move(jquality);
      j["outputs"] = outputs;
      for(const std::string& r : reports) {
        std::ofstream os(r);
        if(fs::path(r).extension() == ".html") os << html_report(j, mesh, q.scaled_jacobian);
        else os << j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";   // names from files may not be UTF-8
        if(!os) { std::cerr << "hexmesh: cannot write " << r << "\n"; return OUTPUT; }
      }
    }
    if(!have_fid) {
      pm = HM::Polyhedral_mesh_3();   // (freed first: the fidelity builds its own trees)
      fid = HM::boundary_fidelity(mesh, domain, 10000);
    }
    if(fid.surface_faces > 0) {
      const std::size_t far = faces_beyond(0.25);
      auto at = [](const std::array<double, 3>& p) {
        return "(" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + ")";
      };
      if(!quiet)
        std::printf("fidelity           %zu boundary faces on the input (%zu more capping holes), %zu beyond 1/4 surface size "
                    "(the farthest %.3g surface sizes off, at %s); %zu points of the input within %.3g surface sizes of "
                    "the mesh (the farthest at %s)\n",
                    fid.surface_faces, fid.cap_faces, far, fid.max_face_distance / surface_size, at(fid.worst_face_location).c_str(),
                    fid.samples, fid.max_sample_distance / surface_size, at(fid.worst_sample_location).c_str());
      // the feature curves, both ways (with a report: it measures them)
      if(!quiet && feature_fids && (feature_fids->first.input_feature_edges > 0 || feature_fids->first.mesh_feature_edges > 0)) {
        const HM::Feature_fidelity& strict = feature_fids->first;
        const HM::Feature_fidelity& tolerant = feature_fids->second;
        auto sizes = [&](double d) {
          char b[32];
          if(std::isfinite(d)) std::snprintf(b, sizeof b, "%.3g", d / surface_size);
          else std::snprintf(b, sizeof b, "inf");
          return std::string(b);
        };
        std::printf("features           %zu input feature edges within %s surface sizes of the mesh's (the farthest at %s), "
                    "%zu mesh feature edges within %s of the input's (the farthest at %s); within %g degrees: %s and %s; "
                    "%zu corners within %s\n",
                    strict.input_feature_edges, sizes(strict.input_to_mesh).c_str(), at(strict.worst_input_location).c_str(),
                    strict.mesh_feature_edges, sizes(strict.mesh_to_input).c_str(), at(strict.worst_mesh_location).c_str(),
                    feature_tolerance, sizes(tolerant.input_to_mesh).c_str(), sizes(tolerant.mesh_to_input).c_str(),
                    strict.corners, sizes(strict.max_corner_distance).c_str());
      }
      // a part of the input the body-fitted mesh does not cover: said even with --quiet (a staircase
      // stands up to a cell's half diagonal off by design)
      if(!staircase && fid.samples > 0 && fid.max_sample_distance > surface_size) {
        // the suggested --thin-size: s/8 rounded up to 3 digits (cells are split while larger
        // than it: s/8 is the last level, whatever the rounding)
        const double mag = std::pow(10.0, std::floor(std::log10(surface_size / 8)) - 2);
        const double thin = std::ceil(surface_size / 8 / mag) * mag;
        std::cerr << "hexmesh: warning: parts of the input are up to " << fid.max_sample_distance / surface_size
                  << " surface sizes from the mesh (the farthest at " << at(fid.worst_sample_location) << "): ";
        // (a run that refines its thin parts at least as much already is not told to: the part
        // there is thinner than its refinement resolves)
        if(thin_cells >= 6 && thin_size <= thin)
          std::cerr << "a part or gap too thin for the thin-part refinement given (--thin-cells " << thin_cells
                    << " --thin-size " << thin_size << ") is lost or only partly meshed there, ";
        else
          std::cerr << "a part thinner than about two surface cells is lost or only partly meshed there (--thin-cells 6 "
                       "--thin-size " << thin << " meshes it: 6 cells across, down to 1/8 of the surface size), ";
        std::cerr << "or a gap is closed, a hole capped, or the input lies outside the meshed region\n";
      }
    }
    return status == HM::Status::CANCELED ? CANCELLED : OK;
  } catch(const HM::Input_error& e) {
    std::cerr << "hexmesh: " << e.what() << "\n";
    return INPUT;
  } catch(const std::bad_alloc&) {
    std::cerr << "hexmesh: out of memory; use a larger --size or --surface-size, or --max-cells\n";
    return INPUT;
  } catch(const std::logic_error& e) {
    std::cerr << "hexmesh: internal error: " << e.what() << "\n";
    return INVALID;
  } catch(const fs::filesystem_error& e) {
    std::cerr << "hexmesh: " << e.what() << "\n";
    return OUTPUT;
  } catch(const std::exception& e) {
    std::cerr << "hexmesh: error: " << e.what() << "\n";
    return INVALID;
  }
}
