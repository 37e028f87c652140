#!/usr/bin/python3
"""Benchmark driver: runs hexmesh on a suite of inputs and prints one JSON line per run.

Each line: name, inputs, options, exit code, status, counts (cells, vertices, hanging nodes,
boundary faces), seconds per stage, peak memory (MiB, as getrusage reports it), quality summary
(min/mean/max of scaled Jacobian, non-orthogonality, skewness, aspect ratio, face warpage),
repair summary, leaks, and -- with --checkmesh -- OpenFOAM checkMesh's verdict (-allTopology
-allGeometry) on the exported case.

Suites: the built-in "default" suite meshes every surface of ../shared/data (or of the repository's
test data when ../shared is absent) with hexmesh's default settings, and motorBike (from
../shared/data or Debian's openfoam-examples) around the bike as the OpenFOAM tutorial does.
A suite file is a JSON list of {"name": ..., "inputs": [...], "options": [...]}; relative input
paths are looked up in the data directories.

Usage: benchmark/Hex_meshing_3/run.py [--hexmesh build/tools/hexmesh/hexmesh] [--suite FILE.json]
                                      [--only NAME ...] [--checkmesh] [--keep DIR]
Run on an otherwise idle machine: timings are wall-clock seconds on one core.
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
DATA_DIRS = [os.path.normpath(os.path.join(ROOT, "..", "shared", "data")),
             os.path.join(ROOT, "test", "Hex_meshing_3", "data"),
             "/usr/share/openfoam/tutorials/resources/geometry",
             "/usr/share/doc/openfoam-examples/examples/resources/geometry"]

# the OpenFOAM motorBike tutorial's setting: the air in the box, finer near the bike
MOTORBIKE_OPTIONS = ["--box", "-5,-4,0,15,4,8", "--size", "1", "--surface-size", "0.03125",
                     "--refine-box", "-1,-0.7,0,8,0.7,2.5:0.0625", "--region", "seed:3.0001,3.0001,0.43"]


def find_input(name):
    if os.path.isabs(name):
        return name if os.path.exists(name) else None
    for d in DATA_DIRS:
        p = os.path.join(d, name)
        if os.path.exists(p):
            return p
    return None


def default_suite():
    runs = []
    for d in DATA_DIRS[:2]:
        files = sorted(glob.glob(os.path.join(d, "*.off")))
        if files:
            runs += [{"name": os.path.basename(f)[:-4], "inputs": [f], "options": []} for f in files]
            break
    runs.append({"name": "motorBike", "inputs": ["motorBike.obj.gz"], "options": MOTORBIKE_OPTIONS})
    return runs


def checkmesh(case):
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    try:
        std = subprocess.run(["checkMesh", "-case", case, "-allTopology"], capture_output=True, text=True, env=env)
        r = subprocess.run(["checkMesh", "-case", case, "-allTopology", "-allGeometry"], capture_output=True,
                           text=True, env=env)
    except FileNotFoundError:
        return {"verdict": "checkMesh not installed"}
    so = std.stdout + std.stderr
    sfailed = re.search(r"Failed (\d+) mesh checks", so)
    standard = {"verdict": "Mesh OK" if "Mesh OK" in so else (f"Failed {sfailed.group(1)} mesh checks" if sfailed else "no verdict"),
                "flags": [l.strip().lstrip("*") for l in so.splitlines() if l.strip().startswith("***")]}
    out = r.stdout + r.stderr
    failed = re.search(r"Failed (\d+) mesh checks", out)
    flags = [l.strip().lstrip("*") for l in out.splitlines() if l.strip().startswith("***")]
    get = lambda pat: (float(m.group(1)) if (m := re.search(pat, out)) else None)
    return {"allTopology": standard,
            "verdict": "Mesh OK" if "Mesh OK" in out else (f"Failed {failed.group(1)} mesh checks" if failed else "no verdict"),
            "flags": flags, "max_non_orthogonality": get(r"Mesh non-orthogonality Max: ([0-9.eE+-]+)"),
            "max_skewness": get(r"Max skewness = ([0-9.eE+-]+)")}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--hexmesh", default=os.path.join(ROOT, "build", "tools", "hexmesh", "hexmesh"))
    ap.add_argument("--suite", help="a JSON suite file (default: the built-in suite)")
    ap.add_argument("--only", nargs="*", help="run only these names")
    ap.add_argument("--checkmesh", action="store_true", help="export an OpenFOAM case and add checkMesh's verdict")
    ap.add_argument("--keep", help="keep the outputs (VTU, case, reports) in this directory")
    args = ap.parse_args()
    runs = json.load(open(args.suite)) if args.suite else default_suite()
    if args.only:
        runs = [r for r in runs if r["name"] in args.only]
    work = args.keep or tempfile.mkdtemp(prefix="hexmesh_bench_")
    os.makedirs(work, exist_ok=True)
    try:
        for run in runs:
            inputs = [find_input(i) for i in run["inputs"]]
            line = {"name": run["name"], "inputs": run["inputs"], "options": run["options"]}
            if None in inputs:
                line["error"] = "input not found in " + ", ".join(DATA_DIRS)
                print(json.dumps(line), flush=True)
                continue
            out = os.path.join(work, run["name"])
            shutil.rmtree(out, ignore_errors=True)
            os.makedirs(out)
            rep = os.path.join(out, "report.json")
            cmd = [args.hexmesh] + inputs + ["-o", os.path.join(out, "mesh.vtu"), "--report", rep, "-q"] + run["options"]
            if args.checkmesh:
                cmd += ["-o", os.path.join(out, "case")]
            r = subprocess.run(cmd, capture_output=True, text=True)
            line["exit"] = r.returncode
            warnings = [l for l in r.stderr.splitlines() if l.strip()]
            if warnings:
                line["stderr"] = warnings[-5:]
            if os.path.exists(rep):
                j = json.load(open(rep))
                q = j["quality"]
                line.update({
                    "status": j["status"], "cells": j["counts"]["cells"], "vertices": j["counts"]["vertices"],
                    "hanging_nodes": j["counts"]["hanging_nodes"], "boundary_faces": j["counts"]["boundary_faces"],
                    "volume": j["volume"], "seconds": {k: round(v, 4) for k, v in j["seconds"].items()},
                    "peak_memory_mib": round(j["peak_memory_mib"], 1),
                    "grid_leaf_cells_per_second": round(j["grid"]["leaf_cells_per_second"]),
                    "quality": {k: {s: round(q[k][s], 4) for s in ("min", "mean", "max")}
                                for k in ("scaled_jacobian", "non_orthogonality", "skewness", "aspect_ratio", "face_warpage")
                                if k in q},
                    "input": {k: j["input_summary"][k] for k in ("triangles", "parts", "components", "boundary_edges",
                                                                  "non_manifold_edges", "exact_inside_test")},
                    "repair": {k: v for k, v in j["repair"].items() if v},
                    "leaks": [{"cells": l["cells"], "volume": round(l["volume"], 6), "passage": l["passage"]} for l in j["leaks"]],
                })
                if "boundary" in j:
                    line["boundary"] = {k: v for k, v in j["boundary"].items() if not k.endswith("_first_100")}
                if "fidelity" in j:
                    f = j["fidelity"]
                    s_ = f["surface_size"]
                    line["fidelity_in_surface_sizes"] = {k: round(f[k] / s_, 3) for k in
                                                         ("mesh_to_input_max", "mesh_to_input_mean", "input_to_mesh_max", "input_to_mesh_mean")}
                    line["faces_beyond"] = {k: f[f"faces_beyond_{k}_surface_size"] for k in ("quarter", "half")}
                    line["faces_beyond"]["one"] = f["faces_beyond_surface_size"]
                    line["surface_faces"] = f["surface_faces"]
                if "feature_fidelity" in j:
                    ff, s_ = j["feature_fidelity"], j["fidelity"]["surface_size"]
                    line["features_in_surface_sizes"] = {k: (None if ff[k] is None else round(ff[k] / s_, 3)) for k in
                                                         ("input_to_mesh", "mesh_to_input", "max_corner_distance")}
                if "topology" in j:
                    t = j["topology"]
                    line["topology"] = {w: (t[w]["components"], t[w]["euler_characteristic"]) for w in ("input", "mesh_boundary")}
                if args.checkmesh:
                    line["checkMesh"] = checkmesh(os.path.join(out, "case"))
            print(json.dumps(line), flush=True)
            if not args.keep:
                shutil.rmtree(out, ignore_errors=True)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
