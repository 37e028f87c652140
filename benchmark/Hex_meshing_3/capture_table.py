#!/usr/bin/python3
"""The body-fitted boundary's figures on every surface of the test data, one line each.

Runs hexmesh (VTU output only: the quality is measured on the exact points) with the given extra
options on every test/Hex_meshing_3/data/*.off, two at a time, and prints: cells, min scaled
Jacobian, cells below 0.3, max non-orthogonality (degrees), surface faces farther than 1/4, 1/2
and 1 surface size from the input and the farthest (x surface size), the input's farthest sampled
point from the mesh, the feature fidelity both ways (F: strict, T: within the report's angle tolerance of
10 degrees) and the worst corner (x surface size), feature
curves missed, buffer cells removed, vertices that could not reach the surface, total seconds,
and why the faces beyond 1/4 surface size stand off (the report's far_face_causes, h/k/c/f/b): the
farthest point a hanging corner (the midpoint of a coarser face's edge: a chord), a corner nearest
to a border edge of the input (a cap over a hole), another corner (a vertex that did not reach the
surface), the centre of a face folded along a diagonal (a feature curve or a crease across it), the
centre of a face only bent (too large for the curvature).

With --test-sizes, each file also gets the options the tests give it (BODY_FITTED_SIZES in
test/Hex_meshing_3/test_dirty_input.py, read from there); with --size-factor F, its surface size is
F times the default (the largest side of the input's bounding box / 40), e.g. 0.75: one more
refinement level where it binds. The test sizes are no margin: this shows how the capture's figures
hold at other sizes. The table then also gives the cells OpenFOAM finds concave and the faces
failing its tet decomposition (the report's counts of checkMesh -allGeometry's), the captures run,
and the number of files reaching the quality goals (min scaled Jacobian >= 0.3, no concave cell,
no face-tet failure). The last lines count the files with no boundary face beyond a quarter
surface size of the input (the fidelity goal), and the faces beyond it by cause over all files.

Usage: benchmark/Hex_meshing_3/capture_table.py [--hexmesh PATH] [--keep DIR] [--test-sizes]
                                                [--size-factor F] [--only STEM,...] [-- hexmesh options...]
e.g.   benchmark/Hex_meshing_3/capture_table.py -- --thin-cells 5
       benchmark/Hex_meshing_3/capture_table.py --test-sizes --size-factor 0.75
"""
import ast
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
DATA = os.path.join(ROOT, "test", "Hex_meshing_3", "data")
TEST = os.path.join(ROOT, "test", "Hex_meshing_3", "test_dirty_input.py")


def test_sizes():
    """BODY_FITTED_SIZES of the tests (file stem -> extra hexmesh options), read from the test's
    source: its module-level assignments of upper-case names up to BODY_FITTED_SIZES (the option
    lists it is made of), evaluated as literals and expressions of those names"""
    ns = {}
    for node in ast.parse(open(TEST).read()).body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and node.targets[0].id.isupper():
            try:
                ns[node.targets[0].id] = eval(compile(ast.Expression(node.value), TEST, "eval"), {"__builtins__": {}}, dict(ns))
            except (NameError, TypeError, ValueError, KeyError, AttributeError, IndexError):
                continue   # (not made of literals and earlier names: not an option list)
            if node.targets[0].id == "BODY_FITTED_SIZES":
                return ns["BODY_FITTED_SIZES"]
    sys.exit(f"capture_table.py: no BODY_FITTED_SIZES assignment found in {TEST}")


def default_surface_size(off):
    """hexmesh's default surface size for an OFF file: the largest side of its bounding box / 40"""
    with open(off) as f:
        tok = " ".join(line.split("#")[0] for line in f).split()
    if tok[0] != "OFF":
        sys.exit(f"capture_table.py: {off}: not a plain OFF file")
    i = 1
    nv = int(tok[i])
    i += 3
    xyz = [float(t) for t in tok[i:i + 3 * nv]]
    return max(max(xyz[a::3]) - min(xyz[a::3]) for a in range(3)) / 40


def main():
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexmesh", default=os.path.join(ROOT, "build", "tools", "hexmesh", "hexmesh"))
    ap.add_argument("--keep", help="directory for the meshes and reports (default: a temporary one)")
    ap.add_argument("--test-sizes", action="store_true", help="each file with the options of the tests")
    ap.add_argument("--size-factor", type=float, help="surface size = this x the default")
    ap.add_argument("--only", help="comma-separated file stems (default: every file)")
    args = ap.parse_args(argv[:argv.index("--")] if "--" in argv else argv)
    per_file = test_sizes() if args.test_sizes else {}
    if args.size_factor is not None and (args.size_factor <= 0 or "--surface-size" in extra or "--size" in extra):
        sys.exit("capture_table.py: --size-factor needs a positive factor and no --surface-size or --size after --")
    if args.test_sizes and any(o in extra for v in per_file.values() for o in v if o.startswith("--")):
        sys.exit("capture_table.py: --test-sizes already gives " + " ".join(sorted({o for v in per_file.values() for o in v if o.startswith("--")})))
    work = args.keep or tempfile.mkdtemp(prefix="capture_table_")
    os.makedirs(work, exist_ok=True)

    def one(name):
        stem = name[:-4]
        rep = os.path.join(work, stem + ".json")
        opts = list(per_file.get(stem, []))
        if args.size_factor is not None:
            if "--surface-size" in opts:   # (the test's own sizes, H[:HFINE], scaled)
                k = opts.index("--surface-size") + 1
                opts[k] = ":".join(repr(args.size_factor * float(x)) for x in opts[k].split(":"))
            else:
                opts += ["--surface-size", repr(args.size_factor * default_surface_size(os.path.join(DATA, name)))]
        r = subprocess.run([args.hexmesh, os.path.join(DATA, name), "-o", os.path.join(work, stem + ".vtu"),
                            "--report", rep, "--force", "-q"] + opts + extra, capture_output=True, text=True)
        return stem, (json.load(open(rep)) if r.returncode == 0 else None), r.stderr[-300:]

    names = sorted(n for n in os.listdir(DATA) if n.endswith(".off") and
                   (not args.only or n[:-4] in args.only.split(",")))
    with concurrent.futures.ThreadPoolExecutor(2) as ex:
        results = list(ex.map(one, names))
    head = "hexmesh options: " + (" ".join(extra) or "(defaults)")
    if args.test_sizes:
        head += "; the tests' per-file options"
    if args.size_factor is not None:
        head += "; surface size %g x the default" % args.size_factor
    print(head + "; distances in surface sizes")
    print(f"{'file':20s} {'cells':>6s} {'minSJ':>6s} {'<.3':>4s} {'nonO':>5s} {'f>.25':>5s} {'f>.5':>4s} {'f>1':>4s} "
          f"{'fmax':>5s} {'i2m':>5s} {'F i2m':>6s} {'F m2i':>6s} {'T i2m':>5s} {'T m2i':>5s} {'corn':>5s} {'miss':>4s} {'rem':>4s} {'unr':>4s} "
          f"{'conc':>4s} {'ftet':>4s} {'capt':>4s} {'gap':>6s} {'sec':>5s}  {'h/k/c/f/b':s}")
    goals = near = 0
    cause_total = {}
    for stem, j, err in results:
        if j is None:
            print(f"{stem:20s} FAILED: {err.strip()}")
            continue
        s, q, fi, ff, b = j["fidelity"]["surface_size"], j["quality"], j["fidelity"], j["feature_fidelity"], j.get("boundary", {})
        ft = ff.get("within_tolerance", {})
        h = q["histograms"]["scaled_jacobian"]   # 20 bins from -1 to 1: bins 10..12 are [0, 0.3)
        rel = lambda x: float("inf") if x is None else x / s
        print(f"{stem:20s} {j['counts']['cells']:6d} {q['scaled_jacobian']['min']:6.3f} {sum(h['counts'][10:13]):4d} "
              f"{q['non_orthogonality']['max']:5.1f} {fi['faces_beyond_quarter_surface_size']:5d} "
              f"{fi['faces_beyond_half_surface_size']:4d} {fi['faces_beyond_surface_size']:4d} {fi['mesh_to_input_max'] / s:5.2f} "
              f"{fi['input_to_mesh_max'] / s:5.2f} {rel(ff['input_to_mesh']):6.2f} {rel(ff['mesh_to_input']):6.2f} "
              f"{rel(ft.get('input_to_mesh')):5.2f} {rel(ft.get('mesh_to_input')):5.2f} "
              f"{rel(ff['max_corner_distance']):5.2f} {b.get('curves_missed', -1):4d} {b.get('removed_buffer_cells', -1):4d} "
              f"{b.get('unreached_vertices', -1):4d} {q.get('concave_cells', -1):4d} {q.get('face_tet_errors', -1):4d} "
              f"{b.get('capture_tries', 0):4d} {b.get('staircase_tries', 1):1d}/{b.get('staircase_gap', 0.4):<4g} "
              f"{j['seconds']['total']:5.2f}  "
              + "/".join(str(fi.get("far_face_causes", {}).get(k, "-")) for k in ("hanging_corner", "cap_corner", "corner", "folded", "bent")))
        goals += q["scaled_jacobian"]["min"] >= 0.3 and q.get("concave_cells") == 0 and q.get("face_tet_errors") == 0
        near += fi["faces_beyond_quarter_surface_size"] == 0
        for k, v in fi.get("far_face_causes", {}).items():
            cause_total[k] = cause_total.get(k, 0) + v
    print(f"min scaled Jacobian >= 0.3, no concave cell and no face-tet failure: {goals} of {len(results)} files")
    print(f"no boundary face beyond 0.25 x surface size: {near} of {len(results)} files")
    if cause_total:
        print("faces beyond 0.25 x surface size by cause, all files: " + ", ".join(f"{k} {v}" for k, v in cause_total.items()))


if __name__ == "__main__":
    main()
