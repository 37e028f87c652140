#!/usr/bin/python3
"""The OpenFOAM motorBike, snappyHexMesh and hexmesh side by side, in one run on one core.

snappyHexMesh runs on the tutorial's dictionaries (motorBike/system here) with addLayers false:
blockMesh, surfaceFeatureExtract, snappyHexMesh -overwrite. hexmesh runs at the matching settings:
background 1 m in the box (-5,-4,0)-(15,4,8); surfaces 1/32 m, 1/64 m where the normals differ by
more than 30 degrees (level (5 6), resolveFeatureAngle 30); feature edges 1/64 m (level 6); the
refinement box (-1,-0.7,0)-(8,0.7,2.5) at 1/16 m (level 4); 3 cells between levels; the seed
(3.0001,3.0001,0.43). Both are pinned to one core (taskset) and timed by /usr/bin/time.

hexmesh also gets --thin-cells 6 --thin-size 0.015625 (--no-gaps leaves it out): the gaps and
plates thinner than 6 cells of 1/32 m get 1/64 m (level 6, no finer than snappy's cells).
snappyHexMesh's level (5 6) takes a cell to level 6 where the surface intersections it sees along
its connections have normals more than 30 degrees apart, which includes the two sides of a gap or
plate a cell or two across; --curvature-angle looks at the triangles within one cut cell only.
(2026-12-04: mesh to input 1.7 -> 1.4 mm mean, 360,048 -> 376,287 cells, peak memory 0.47 of
snappy's.)

For each mesher: cells, wall seconds and peak memory (snappy: snappyHexMesh -overwrite, with
blockMesh and surfaceFeatureExtract apart; hexmesh: from reading to writing), checkMesh
-allTopology verdict, the -allTopology -allGeometry verdict, the concave cells and face-tet (flatness) faces of -allGeometry, max
non-orthogonality and skewness, hexahedra, and the boundary fidelity: foamToSurface of each mesh,
box patches left out, measured both ways against the input by surface_distance (the same tool
for both: area-uniform samples, CGAL AABB tree).

With --repeat N, each mesher is timed N times, the runs alternating (hexmesh, snappyHexMesh,
hexmesh, ...: a slow spell of the machine falls on both), and the table gives the median wall
seconds and peak memory with their range; the ratios are the medians'. The first runs' meshes
are the ones checked and measured (the others write the same meshes again: hexmesh into
DIR/hexmesh_repeat, snappyHexMesh from a new blockMesh). On this 2-core VM the same run of
either mesher varies by 5-10 % from run to run (snappyHexMesh's by up to 2 times over days).

Usage: benchmark/Hex_meshing_3/motorbike_side_by_side.py [--hexmesh PATH] [--work DIR]
                                                         [--skip-snappy] [--samples N] [--no-gaps]
                                                         [--repeat N]
Writes DIR/results.json and prints a table. Needs OpenFOAM (Debian's openfoam) for snappy and
checkMesh; builds surface_distance (cmake --build build --target surface_distance) if missing.
"""
import argparse
import gzip
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import far_by_feature  # noqa: E402
import run as driver   # noqa: E402  (find_input: ../shared/data, test data, Debian's openfoam-examples)

ENV = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
HEXMESH_OPTIONS = ["--box", "-5,-4,0,15,4,8", "--size", "1", "--surface-size", "0.03125:0.015625",
                   "--curvature-angle", "30", "--feature-size", "0.015625",
                   "--refine-box", "-1,-0.7,0,8,0.7,2.5:0.0625", "--cells-between-levels", "3",
                   "--region", "seed:3.0001,3.0001,0.43"]
GAP_OPTIONS = ["--thin-cells", "6", "--thin-size", "0.015625"]   # (not with --no-gaps)
BOX_PATCHES = {"hexmesh": "xmin|xmax|ymin|ymax|zmin|zmax",
               "snappyHexMesh": "frontAndBack|inlet|outlet|lowerWall|upperWall"}
GROUND_PATCH = {"hexmesh": "zmin", "snappyHexMesh": "lowerWall"}
GROUND_AREA = 20.0 * 8.0   # the box (-5,-4,0)-(15,4,8)
FINE_SURFACE_SIZE = 0.015625   # the HFINE of --surface-size (snappyHexMesh: level 6)


def patch_areas(obj):
    """the area of each group of a triangulated OBJ (foamToSurface writes one group per patch)"""
    pts, areas, group = [], {}, None
    for line in open(obj):
        if line.startswith("v "):
            pts.append(tuple(float(x) for x in line.split()[1:4]))
        elif line.startswith("g ") or line.startswith("o "):
            group = line.split()[1]
        elif line.startswith("f "):
            a, b, c = (pts[int(x.split("/")[0]) - 1] for x in line.split()[1:4])
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            areas[group] = areas.get(group, 0.0) + 0.5 * math.sqrt(sum(x * x for x in n))
    return areas


def timed(cmd, cwd, log):
    """runs cmd pinned to core 0; returns (exit code, wall seconds, peak MiB)"""
    tfile = log + ".time"
    full = ["/usr/bin/time", "-f", "%e %M", "-o", tfile]
    if shutil.which("taskset"):
        full += ["taskset", "-c", "0"]
    with open(log, "w") as f:
        r = subprocess.run(full + cmd, cwd=cwd, env=ENV, stdout=f, stderr=subprocess.STDOUT)
    try:
        wall, kb = open(tfile).read().split()[-2:]
        return r.returncode, float(wall), float(kb) / 1024
    except (OSError, ValueError):
        return r.returncode, None, None


def spread(value, runs, fmt):
    """a value, and the range of the runs it is the median of, if more than one"""
    if len(runs) < 2:
        return fmt % value
    return (fmt + " (" + fmt + "-" + fmt + ")") % (value, min(runs), max(runs))


def checkmesh(case):
    out = {}
    r = subprocess.run(["checkMesh", "-case", case, "-constant", "-allTopology"], capture_output=True, text=True, env=ENV)
    failed = re.search(r"Failed (\d+) mesh checks", r.stdout)
    out["allTopology"] = "Mesh OK" if "Mesh OK" in r.stdout else (f"Failed {failed.group(1)}" if failed else "no verdict")
    out["allTopology_flags"] = [l.strip() for l in r.stdout.splitlines() if l.strip().startswith("***")]
    r = subprocess.run(["checkMesh", "-case", case, "-constant", "-allTopology", "-allGeometry"], capture_output=True,
                       text=True, env=ENV)
    s = r.stdout
    get = lambda pat, conv=float: (conv(m.group(1)) if (m := re.search(pat, s)) else None)
    out["allGeometry"] = "Mesh OK" if "Mesh OK" in s else "failed"
    out["flags"] = [l.strip() for l in s.splitlines() if l.strip().startswith("***")]
    out["cells"] = int(m.group(1)) if (m := re.search(r"^\s*cells:\s+(\d+)", s, re.M)) else None
    out["hexahedra"] = int(m.group(1)) if (m := re.search(r"^\s*hexahedra:\s+(\d+)", s, re.M)) else None
    out["concave_cells"] = get(r"Concave cells.*?number of cells: (\d+)", int) or 0
    out["face_tet_faces"] = get(r"face tets: (\d+) faces", int) or 0
    out["max_non_orthogonality"] = get(r"Mesh non-orthogonality Max: ([0-9.eE+-]+)")
    out["max_skewness"] = get(r"Max skewness = ([0-9.eE+-]+)")
    return out


def fidelity(case, name, work, distance_tool, bike, samples):
    surf = os.path.join(work, name + "_boundary.obj")
    subprocess.run(["foamToSurface", "-case", case, "-constant", "-tri", surf], capture_output=True, env=ENV)
    r = subprocess.run([distance_tool, surf, bike, "--exclude", BOX_PATCHES[name], "--samples", str(samples),
                        "--dump", os.path.join(work, name + "_distances")], capture_output=True, text=True)
    if r.returncode != 0:
        return {"error": r.stderr.strip()}
    j = json.loads(r.stdout)
    areas = patch_areas(surf)
    # the ground the mesh does not cover: under the tyres (their section and any filled wedge)
    ground = GROUND_AREA - areas.get(GROUND_PATCH[name], 0.0)
    # patches on the two sides of the zero-thickness sheets (our NAME / NAME-shadow pairs)
    shadow = sorted(n for n, a in areas.items() if "-shadow" in n and a > 0)
    return {"mesh_to_input": j["a_to_b"], "input_to_mesh": j["b_to_a"], "mesh_triangles": j["a_triangles"],
            "ground_left_out_m2": ground, "shadow_patches_with_faces": len(shadow),
            "input_to_mesh_parts": j.get("b_to_a_parts", {}),
            "mesh_to_input_dump": os.path.join(work, name + "_distances_a_to_b.txt")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexmesh", default=os.path.join(ROOT, "build", "tools", "hexmesh", "hexmesh"))
    ap.add_argument("--surface-distance", default=os.path.join(ROOT, "build", "benchmark", "Hex_meshing_3", "surface_distance"))
    ap.add_argument("--work", help="directory for the cases (default: a temporary one, kept)")
    ap.add_argument("--skip-snappy", action="store_true")
    ap.add_argument("--samples", type=int, default=200000, help="points sampled on each surface for the fidelity")
    ap.add_argument("--no-gaps", action="store_true", help="hexmesh without the refinement of gaps and plates thinner "
                    "than 6 cells to 1/64 m (--thin-cells 6 --thin-size 0.015625)")
    ap.add_argument("--repeat", type=int, default=1, help="time each mesher N times, alternately; report the medians")
    args = ap.parse_args()
    if args.repeat < 1:
        sys.exit("--repeat: at least 1")
    bike = driver.find_input("motorBike.obj.gz")
    if not bike:
        sys.exit("motorBike.obj.gz not found (../shared/data or Debian's openfoam-examples)")
    for prog in ["blockMesh", "snappyHexMesh", "surfaceFeatureExtract", "checkMesh", "foamToSurface"]:
        if shutil.which(prog) is None:
            sys.exit(f"{prog} not found: install OpenFOAM (apt-get install openfoam)")
    if not os.path.exists(args.surface_distance):
        subprocess.run(["cmake", "--build", os.path.join(ROOT, "build"), "--target", "surface_distance"], check=True)
    work = os.path.abspath(args.work or tempfile.mkdtemp(prefix="motorbike_"))
    os.makedirs(work, exist_ok=True)
    results = {"input": bike, "machine": os.uname().nodename, "cores_used": 1, "repeat": args.repeat}

    # ours
    case = os.path.join(work, "hexmesh")
    shutil.rmtree(case, ignore_errors=True)
    rep = os.path.join(work, "hexmesh_report.json")
    options = HEXMESH_OPTIONS + ([] if args.no_gaps else GAP_OPTIONS)
    rc, wall, mib = timed([args.hexmesh, bike, "-o", case, "--report", rep, "--force", "-q"] + options,
                          work, os.path.join(work, "hexmesh.log"))
    ours = {"exit": rc, "options": options, "seconds": wall, "peak_MiB": mib, "runs_seconds": [wall], "runs_peak_MiB": [mib]}
    if rc == 0:
        ours["checkMesh"] = checkmesh(case)
        ours["fidelity"] = fidelity(case, "hexmesh", work, args.surface_distance, bike, args.samples)
        jr = json.load(open(rep))
        ours["report_seconds"] = jr.get("seconds", {})
        ours["capture_step_seconds"] = jr.get("boundary", {}).get("step_seconds", {})
        ours["capture_substep_seconds"] = jr.get("boundary", {}).get("substep_seconds", {})
        ours["box_contacts"] = jr.get("box_contacts", {})
    results["hexmesh"] = ours

    # snappyHexMesh
    if not args.skip_snappy:
        case = os.path.join(work, "snappyHexMesh")
        shutil.rmtree(case, ignore_errors=True)
        shutil.copytree(os.path.join(HERE, "motorBike", "system"), os.path.join(case, "system"))
        # the tutorial's controlDict includes function objects (streamLines, forceCoeffs...) from
        # its own directory: not needed to mesh, left out
        cd = os.path.join(case, "system", "controlDict")
        lines = [l for l in open(cd) if not re.match(r'\s*#include\s+"', l)]
        open(cd, "w").write("".join(lines))
        d = os.path.join(case, "system", "snappyHexMeshDict")
        txt = open(d).read()
        txt = re.sub(r"^addLayers\s+true;", "addLayers       false;", txt, flags=re.M)
        open(d, "w").write(txt)
        os.makedirs(os.path.join(case, "constant", "triSurface"))
        with gzip.open(bike, "rb") as src, open(os.path.join(case, "constant", "triSurface", "motorBike.obj"), "wb") as dst:
            shutil.copyfileobj(src, dst)
        snappy = {"addLayers": False}
        for step, cmd in [("blockMesh", ["blockMesh"]), ("surfaceFeatureExtract", ["surfaceFeatureExtract"]),
                          ("snappyHexMesh", ["snappyHexMesh", "-overwrite"])]:
            rc, wall, mib = timed(cmd, case, os.path.join(work, step + ".log"))
            snappy[step] = {"exit": rc, "seconds": wall, "peak_MiB": mib}
            if rc != 0:
                break
        snappy["seconds"] = snappy.get("snappyHexMesh", {}).get("seconds")
        snappy["peak_MiB"] = snappy.get("snappyHexMesh", {}).get("peak_MiB")
        snappy["runs_seconds"], snappy["runs_peak_MiB"] = [snappy["seconds"]], [snappy["peak_MiB"]]
        if snappy.get("snappyHexMesh", {}).get("exit") == 0:
            snappy["checkMesh"] = checkmesh(case)
            snappy["fidelity"] = fidelity(case, "snappyHexMesh", work, args.surface_distance, bike, args.samples)
        results["snappyHexMesh"] = snappy

    # the repeated runs, alternating; then the medians
    snappy_ok = results.get("snappyHexMesh", {}).get("snappyHexMesh", {}).get("exit") == 0
    snappy_case = os.path.join(work, "snappyHexMesh")
    for _ in range(1, args.repeat):
        if ours["exit"] == 0:
            rc, wall, mib = timed([args.hexmesh, bike, "-o", os.path.join(work, "hexmesh_repeat"), "--force", "-q"] + options,
                                  work, os.path.join(work, "hexmesh_repeat.log"))
            if rc == 0 and wall is not None:
                ours["runs_seconds"].append(wall)
                ours["runs_peak_MiB"].append(mib)
        if snappy_ok:
            rc = timed(["blockMesh"], snappy_case, os.path.join(work, "blockMesh_repeat.log"))[0]
            if rc == 0:
                rc, wall, mib = timed(["snappyHexMesh", "-overwrite"], snappy_case, os.path.join(work, "snappyHexMesh_repeat.log"))
                if rc == 0 and wall is not None:
                    results["snappyHexMesh"]["runs_seconds"].append(wall)
                    results["snappyHexMesh"]["runs_peak_MiB"].append(mib)
    for r in (results.get("hexmesh", {}), results.get("snappyHexMesh", {})):
        if len(r.get("runs_seconds", [])) > 1 and None not in r["runs_seconds"]:
            r["seconds"] = statistics.median(r["runs_seconds"])
            r["peak_MiB"] = statistics.median(r["runs_peak_MiB"])

    # each boundary's samples farther than a quarter of the finest surface size from the input, by
    # the input feature nearest to them (within two finest cells): where each stands off (the
    # input's features found once for both)
    features = None
    for name in ("hexmesh", "snappyHexMesh"):
        fid = results.get(name, {}).get("fidelity", {})
        if "mesh_to_input_dump" in fid:
            fid["far_by_feature"], features = far_by_feature.far_by_feature(
                bike, fid["mesh_to_input_dump"], 2 * FINE_SURFACE_SIZE, FINE_SURFACE_SIZE / 4, loaded=features)
    json.dump(results, open(os.path.join(work, "results.json"), "w"), indent=1)
    # the table
    names = [n for n in ("hexmesh", "snappyHexMesh") if n in results]
    median_of = f" (median of {args.repeat})" if args.repeat > 1 else ""
    rows = [("cells", lambda r: r["checkMesh"]["cells"]),
            ("checkMesh hexahedra (6 faces)", lambda r: r["checkMesh"]["hexahedra"]),
            ("wall seconds" + median_of, lambda r: spread(r["seconds"], r["runs_seconds"], "%.2f")),
            ("peak MiB" + median_of, lambda r: spread(r["peak_MiB"], r["runs_peak_MiB"], "%.0f")),
            ("checkMesh -allTopology", lambda r: r["checkMesh"]["allTopology"]),
            ("checkMesh -allTopology -allGeometry", lambda r: r["checkMesh"]["allGeometry"] + (f" ({len(r['checkMesh']['flags'])} flags)" if r["checkMesh"]["flags"] else "")),
            ("-allGeometry concave cells", lambda r: r["checkMesh"]["concave_cells"]),
            ("-allGeometry face-tet faces", lambda r: r["checkMesh"]["face_tet_faces"]),
            ("max non-orthogonality", lambda r: "%.1f" % r["checkMesh"]["max_non_orthogonality"]),
            ("max skewness", lambda r: "%.2f" % r["checkMesh"]["max_skewness"]),
            ("mesh->input mean / p99 / max (m)", lambda r: "%.4f / %.4f / %.4f" % tuple(r["fidelity"]["mesh_to_input"][k] for k in ("mean", "p99", "max"))),
            ("input->mesh mean / p99 / max (m)", lambda r: "%.4f / %.4f / %.4f" % tuple(r["fidelity"]["input_to_mesh"][k] for k in ("mean", "p99", "max"))),
            ("ground left out of the mesh (m2)", lambda r: "%.4f" % r["fidelity"]["ground_left_out_m2"]),
            ("'-shadow' patches with faces", lambda r: r["fidelity"]["shadow_patches_with_faces"]),
            ("filled at box contacts (our report, m2)", lambda r: "%.4f" % r["box_contacts"]["filled_area"])]
    print(f"{'':36s}" + "".join(f"{n:>26s}" for n in names))
    for label, f in rows:
        cells = []
        for n in names:
            try:
                cells.append(str(f(results[n])))
            except (KeyError, TypeError):
                cells.append("-")
        print(f"{label:36s}" + "".join(f"{c:>26s}" for c in cells))
    # where our time goes (hexmesh's own report: its phases, and the boundary capture's steps)
    o = results.get("hexmesh", {})
    if o.get("report_seconds"):
        print("hexmesh phases (s): " + ", ".join(f"{k} {v:.1f}" for k, v in o["report_seconds"].items()))
    if o.get("capture_step_seconds"):
        print("hexmesh capture steps (s): " + ", ".join(f"{k} {v:.1f}" for k, v in o["capture_step_seconds"].items()))
    if "snappyHexMesh" in results:
        s = results["snappyHexMesh"]
        print(f"snappy's blockMesh {s.get('blockMesh', {}).get('seconds')} s, surfaceFeatureExtract "
              f"{s.get('surfaceFeatureExtract', {}).get('seconds')} s (not counted above)")
        try:
            o, p = results["hexmesh"], s
            print(f"ratios hexmesh / snappyHexMesh: cells {o['checkMesh']['cells'] / p['checkMesh']['cells']:.2f}, "
                  f"time {o['seconds'] / p['seconds']:.2f}, peak memory {o['peak_MiB'] / p['peak_MiB']:.2f}")
        except (KeyError, TypeError, ZeroDivisionError):
            pass
        # where the input is farther from our boundary than from snappy's: the input's parts by
        # the excess of the summed input->mesh distances (the same samples on both sides)
        try:
            po = results["hexmesh"]["fidelity"]["input_to_mesh_parts"]
            ps = s["fidelity"]["input_to_mesh_parts"]
            excess = sorted(((po[k]["sum"] - ps[k]["sum"], k) for k in po if k in ps), reverse=True)
            total_o = sum(v["sum"] for v in po.values())
            total_s = sum(v["sum"] for v in ps.values())
            print(f"input->mesh distance summed over the samples: hexmesh {total_o:.1f} m, snappyHexMesh {total_s:.1f} m; "
                  "the input's parts where ours exceeds snappy's most (sum, mean mm):")
            for ex, k in excess[:8]:
                print(f"  {k:32s} +{ex:6.1f}   hexmesh {po[k]['sum']:6.1f} ({1000 * po[k]['sum'] / po[k]['points']:.1f})"
                      f"   snappyHexMesh {ps[k]['sum']:6.1f} ({1000 * ps[k]['sum'] / ps[k]['points']:.1f})")
        except (KeyError, TypeError, ZeroDivisionError):
            pass
        # where each boundary stands off (computed before results.json is written)
        if all("far_by_feature" in results[n].get("fidelity", {}) for n in ("hexmesh", "snappyHexMesh")):
            fo, fs = results["hexmesh"]["fidelity"]["far_by_feature"], s["fidelity"]["far_by_feature"]
            print(f"mesh->input samples beyond {FINE_SURFACE_SIZE / 4:g} m, by the input feature nearest within "
                  f"{2 * FINE_SURFACE_SIZE:g} m (samples, distances summed in m):")
            for k in far_by_feature.KINDS + ["none"]:
                print(f"  {k:13s} hexmesh {fo[k]['samples']:7d} {fo[k]['sum']:7.1f}"
                      f"   snappyHexMesh {fs[k]['samples']:7d} {fs[k]['sum']:7.1f}")
    print(f"results: {os.path.join(work, 'results.json')}")


if __name__ == "__main__":
    main()
