#!/usr/bin/python3
"""How robust the body-fitted figures are: every test surface meshed again after shifts by round-off.

Each surface of test/Hex_meshing_3/data is meshed at the tests' sizes (BODY_FITTED_SIZES of
test/Hex_meshing_3/test_dirty_input.py) as it is (shift 0) and translated by k x 1e-9 x its
bounding-box diagonal along (1, 0.7, 1.3) for k = 1 .. N-1: the same shape, the same grid relative
to it, only the last bits of the coordinates differ. A mesher whose goals hold by a margin gives the
same verdicts on every shift; where they hold by luck, a shift loses them. For every run it prints
the minimum scaled Jacobian, the boundary faces farther than a quarter surface size from the input,
the buffer cells removed at the end of the capture (cells the optimisation left inverted or
flat, or OpenFOAM faults: each leaves a staircase face at the boundary) and the feature fidelity
both ways (within the report's angle tolerance, in surface sizes), then per file the shifts
that miss a goal the unshifted mesh meets (min scaled Jacobian >= 0.3, no far face) and the
totals over all files.

Usage: benchmark/Hex_meshing_3/perturbation.py [--hexmesh PATH] [--shifts N | --from K --to L]
                                               [--only NAME ...] [--keep DIR] [--json OUT]
Two runs at a time; with the default 4 shifts, about 5 minutes on 2 cores. Needs python3-numpy.
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import capture_table  # noqa: E402  (the tests' sizes, the test data's place)
import suite  # noqa: E402  (its OFF reader)

DIRECTION = np.array([1.0, 0.7, 1.3])


def shifted_copy(src, k, work):
    """the OFF file `src` translated by k x 1e-9 x its diagonal along DIRECTION, written in `work`"""
    pts, tris = suite.read_off(src)
    V = np.array(pts, float)
    V = V + k * 1e-9 * np.linalg.norm(V.max(0) - V.min(0)) * DIRECTION
    out = os.path.join(work, "%s_%d.off" % (os.path.basename(src)[:-4], k))
    with open(out, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(V), len(tris)))
        for p in V:
            f.write("%.17g %.17g %.17g\n" % tuple(p))
        for t in tris:
            f.write("3 %d %d %d\n" % tuple(t))
    return out


def run(hexmesh, src, k, options, work):
    stem = os.path.basename(src)[:-4]
    inp = src if k == 0 else shifted_copy(src, k, work)
    rep = os.path.join(work, "%s_%d.json" % (stem, k))
    subprocess.run([hexmesh, inp, "-o", os.path.join(work, "%s_%d.vtu" % (stem, k)), "--report", rep, "--force", "-q"] + options,
                   capture_output=True)
    try:
        r = json.load(open(rep))
    except (OSError, ValueError):
        return stem, k, None
    b = r["boundary"]
    out = {"min_scaled_jacobian": r["quality"]["scaled_jacobian"]["min"],
           "far_faces": r["fidelity"]["faces_beyond_quarter_surface_size"],
           "removed_buffer_cells": b["removed_buffer_cells"],
           "seconds": r["seconds"]["total"]}
    # the feature fidelity within the report's angle tolerance, both ways, in surface sizes
    s = r["fidelity"]["surface_size"]
    tol = (r.get("feature_fidelity") or {}).get("within_tolerance") or {}
    if s > 0 and "input_to_mesh" in tol:
        out["features"] = [tol["input_to_mesh"] / s, tol["mesh_to_input"] / s]
    return stem, k, out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--hexmesh", default=os.path.join(capture_table.ROOT, "build", "tools", "hexmesh", "hexmesh"))
    ap.add_argument("--shifts", type=int, default=4, help="shifts 0 .. N-1 (0: the file as it is)")
    ap.add_argument("--from", dest="first", type=int, help="first shift (with --to: shifts K .. L-1)")
    ap.add_argument("--to", type=int)
    ap.add_argument("--only", nargs="*", help="these files only (stems)")
    ap.add_argument("--keep", help="keep the shifted inputs, meshes and reports in this directory")
    ap.add_argument("--json", help="write the results there")
    args = ap.parse_args()
    shifts = range(args.first, args.to) if args.first is not None and args.to is not None else range(args.shifts)
    sizes = capture_table.test_sizes()
    files = sorted(f for f in os.listdir(capture_table.DATA) if f.endswith(".off"))
    if args.only:
        files = [f for f in files if f[:-4] in args.only]
    work = args.keep or tempfile.mkdtemp(prefix="perturbation_")
    os.makedirs(work, exist_ok=True)
    jobs = [(os.path.join(capture_table.DATA, f), k, sizes.get(f[:-4], [])) for f in files for k in shifts]
    results = {}
    with concurrent.futures.ThreadPoolExecutor(2) as ex:
        for stem, k, r in ex.map(lambda j: run(args.hexmesh, j[0], j[1], j[2], work), jobs):
            results.setdefault(stem, {})[k] = r
            print("%-22s shift %d: %s" % (stem, k, "no report" if r is None else
                  "min scaled Jacobian %.3f, far faces %d, removed buffer cells %d, features %s s, %.1f s" %
                  (r["min_scaled_jacobian"], r["far_faces"], r["removed_buffer_cells"],
                   "%.2f / %.2f" % tuple(r["features"]) if "features" in r else "-", r["seconds"])), flush=True)
    print("\nper file, each shift as min scaled Jacobian / far faces / removed buffer cells:")
    runs = missed = missed_sj = missed_far = removed_runs = removed_cells = 0
    for stem in sorted(results):
        row = results[stem]
        cells = []
        for k in shifts:
            r = row.get(k)
            cells.append("no report" if r is None else "%.3f/%d/%d" % (r["min_scaled_jacobian"], r["far_faces"], r["removed_buffer_cells"]))
        print("  %-22s %s" % (stem, "  ".join(cells)))
        ff = [r["features"] for r in row.values() if r and "features" in r]
        if ff:
            print("  %-22s features (within the angle tolerance, x surface size): input->mesh %.2f - %.2f, "
                  "mesh->input %.2f - %.2f" % ("", min(f[0] for f in ff), max(f[0] for f in ff),
                                                min(f[1] for f in ff), max(f[1] for f in ff)))
        # the goals the unshifted mesh meets (all of them where shift 0 was not run)
        r0 = row.get(0)
        sj_goal = r0["min_scaled_jacobian"] >= 0.3 if r0 else True
        far_goal = r0["far_faces"] == 0 if r0 else True
        for k, r in row.items():
            if r is None:
                continue
            runs += 1
            low = sj_goal and r["min_scaled_jacobian"] < 0.3
            far = far_goal and r["far_faces"] > 0
            missed_sj += low
            missed_far += far
            missed += low or far
            if r["removed_buffer_cells"] > 0:
                removed_runs += 1
                removed_cells += r["removed_buffer_cells"]
    print("\n%d runs: %d miss a goal the unshifted mesh meets (%d below a min scaled Jacobian of 0.3, %d with faces "
          "beyond a quarter surface size), %d with buffer cells removed (%d cells)" %
          (runs, missed, missed_sj, missed_far, removed_runs, removed_cells))
    if args.json:
        json.dump({"hexmesh": args.hexmesh, "shifts": list(shifts),
                   "results": {s: {str(k): v for k, v in row.items()} for s, row in results.items()}},
                  open(args.json, "w"), indent=1)


if __name__ == "__main__":
    main()
