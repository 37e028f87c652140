#!/usr/bin/python3
"""End-to-end tests of the hexmesh command line, judged by independent programs.

- every exported OpenFOAM case passes `checkMesh -allGeometry -allTopology` (run as an external
  program; a missing checkMesh is a failure, not a skip), with one documented exception: the
  "concave cells (using face planes)" check of -allGeometry, which flags every cell that has two
  coplanar faces -- each cell next to finer cells has them (its face split into four quarters).
  The test asserts that the flagged cells are exactly such cells;
- our reported max non-orthogonality and max skewness match checkMesh's within 0.01 deg and 1%;
- the VTU file is read back by meshio with the same counts and positive scaled Jacobians;
- the same input and options give byte-identical output files;
- bad input and existing outputs give the documented exit codes and one-line messages.
"""
import argparse
import filecmp
import json
import os
import re
import shutil
import subprocess
import sys

FAILURES = []


def check(cond, msg):
    if cond:
        print("  ok:", msg)
    else:
        print("  FAILED:", msg)
        FAILURES.append(msg)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def foam_list(path):
    """the entries of an OpenFOAM ASCII list file (labels or faces) as strings"""
    text = open(path).read()
    body = text[text.index("}", text.index("FoamFile")) + 1:]
    m = re.search(r"(\d+)\s*\(", body)
    n = int(m.group(1))
    inner = body[m.end():body.rindex(")")]
    return n, inner


def cells_with_coplanar_faces(case):
    """cells having more than 6 faces (a face split into quarters: coplanar faces)"""
    poly = os.path.join(case, "constant", "polyMesh")
    _, owner = foam_list(os.path.join(poly, "owner"))
    _, nei = foam_list(os.path.join(poly, "neighbour"))
    owner = [int(x) for x in owner.split()]
    nei = [int(x) for x in nei.split()]
    count = {}
    for c in owner + nei:
        count[c] = count.get(c, 0) + 1
    return {c for c, k in count.items() if k > 6}


def read_set(case, name):
    path = os.path.join(case, "constant", "polyMesh", "sets", name)
    if not os.path.exists(path):
        return set()
    _, inner = foam_list(path)
    return {int(x) for x in inner.split()}


def checkmesh(case, options=("-allGeometry", "-allTopology")):
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    r = run(["checkMesh", "-case", case] + list(options), env=env)
    return r.returncode, r.stdout + r.stderr


# what -allGeometry may still flag on a body-fitted mesh (reported, goals of the boundary work):
# split-face cells, face-tet decompositions, small cell determinants, highly skewed faces
BODY_FITTED_TOLERATED = ("***Concave cells (using face planes)", "***Error in face tets",
                         "***Cells with small determinant")


WARNED = []   # per case meshed by mesh_case(): whether hexmesh warned of parts of the input far from the mesh


def mesh_case(args, name, extra, label):
    print(f"[{label}] hexmesh {name} {' '.join(extra)}")
    work = os.path.join(args.work, label)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    case = os.path.join(work, "case")
    vtu = os.path.join(work, "mesh.vtu")
    report = os.path.join(work, "report.json")
    r = run([args.hexmesh, os.path.join(args.data, name), "-o", vtu, "-o", case, "--report", report, "-q"] + extra)
    check(r.returncode == 0, f"hexmesh exits 0 (got {r.returncode}: {r.stderr.strip()[:300]})")
    if r.returncode != 0:
        return None
    rep = json.load(open(report))
    # the capture's timing: each step's parts ("step.part") take at most the step's time, in order
    bd = rep.get("boundary")
    if bd and "step_seconds" in bd:
        steps, parts = bd["step_seconds"], bd.get("substep_seconds", {})
        check("optimise.sweeps" in parts and all(v >= 0 for v in parts.values()),
              f"the report times the capture's parts ({', '.join(parts)})")
        for st, t in steps.items():
            own = [v for k, v in parts.items() if k.split(".")[0] == st]
            check(sum(own) <= t + 1e-6, f"the parts of step {st} take {sum(own):.4f} s of its {t:.4f} s")
        check(all(k.split(".")[0] in steps for k in parts), "every part belongs to a step of the report")
    # the warning on parts of the input far from the mesh (said even with -q): exactly when the
    # report's input -> mesh distance exceeds the surface size, on a body-fitted mesh
    fi = rep.get("fidelity")
    if fi:
        warned = "warning: parts of the input are up to" in r.stderr
        WARNED.append(warned)
        check(warned == ("--staircase" not in extra and fi["input_to_mesh_max"] > fi["surface_size"]),
              f"warned of parts of the input far from the mesh: {warned} (input -> mesh "
              f"{fi['input_to_mesh_max'] / fi['surface_size']:.2f} surface sizes)")
    rc, out = checkmesh(case)
    check(rc == 0, "checkMesh runs")
    # topology: all OK
    for key in ["Boundary definition OK", "Cell to face addressing OK", "Point usage OK",
                "Upper triangular ordering OK", "Face vertices OK", "Topological cell zip-up check OK",
                "Face-face connectivity OK"]:
        check(key in out, f"checkMesh: {key}")
    regions = re.search(r"Number of regions: (\d+)", out)
    check(regions is not None, f"checkMesh counts {regions.group(1) if regions else '?'} region(s)")
    failed = re.search(r"Failed (\d+) mesh checks", out)
    stars = [l.strip() for l in out.splitlines() if l.strip().startswith("***")]
    if "--staircase" not in extra:
        # body-fitted: the standard checks with all topology pass; what -allGeometry adds is reported
        rc2, out2 = checkmesh(case, ("-allTopology",))
        std_flags = [l.strip() for l in out2.splitlines() if l.strip().startswith("***")]
        # no flag at all: buffer cells at faces skewed beyond 3.5 are removed by the mesher
        check(rc2 == 0 and ("Mesh OK" in out2),
              f"checkMesh -allTopology: Mesh OK (flags: {std_flags})")
        other = [s for s in stars if not s.startswith(BODY_FITTED_TOLERATED)]
        check(not other, f"checkMesh -allGeometry flags only tolerated checks (other: {other})")
        print(f"  reported: -allGeometry flags {stars}")
        stars = []
        failed = None
    # staircase: every failed check is the concave-cells one, and it flags exactly the cells with coplanar faces
    other = [s for s in stars if not s.startswith("***Concave cells (using face planes)")]
    check(not other, f"checkMesh flags nothing but coplanar-face cells (flags: {stars})")
    if failed:
        check(int(failed.group(1)) == len(stars) == 1, "the only failed check is 'concave cells'")
        concave = read_set(case, "concaveCells")
        coplanar = cells_with_coplanar_faces(case)
        check(concave == coplanar, f"concave cells ({len(concave)}) are exactly the cells with split faces ({len(coplanar)})")
    elif "--staircase" in extra:
        check("Mesh OK" in out, "checkMesh: Mesh OK")
    # our quality figures agree with checkMesh's
    m = re.search(r"Mesh non-orthogonality Max: ([0-9.eE+-]+)", out)
    s = re.search(r"Max skewness = ([0-9.eE+-]+)", out)
    a = re.search(r"Max aspect ratio = ([0-9.eE+-]+)", out)
    cm = re.search(r"cells:\s+(\d+)", out)
    q = rep["quality"]
    check(cm and int(cm.group(1)) == rep["counts"]["cells"], "checkMesh counts the same cells")
    check(m and abs(float(m.group(1)) - q["non_orthogonality"]["max"]) <= 0.01,
          f"max non-orthogonality: ours {q['non_orthogonality']['max']:.6g}, checkMesh {m.group(1) if m else None}")
    check(s and abs(float(s.group(1)) - q["skewness"]["max"]) <= 0.01 * max(1e-12, float(s.group(1))),
          f"max skewness: ours {q['skewness']['max']:.6g}, checkMesh {s.group(1) if s else None}")
    check(a and abs(float(a.group(1)) - q["aspect_ratio"]["max"]) <= 0.01 * float(a.group(1)),
          f"max aspect ratio: ours {q['aspect_ratio']['max']:.6g}, checkMesh {a.group(1) if a else None}")
    check(q["scaled_jacobian"]["min"] > 0, f"min scaled Jacobian {q['scaled_jacobian']['min']} > 0")
    # VTU read back independently
    try:
        import meshio
        import numpy as np
        vm = meshio.read(vtu)
        hexes = vm.cells_dict.get("hexahedron")
        check(hexes is not None and len(hexes) == rep["counts"]["cells"], "meshio reads the VTU: same cell count")
        check(len(vm.points) == rep["counts"]["vertices"], "meshio reads the VTU: same vertex count")
        sj = vm.cell_data["scaled_jacobian"][0]
        # (the VTU holds the mesh's points: the report's qualities are an OpenFOAM case's where one
        # is written and the mesh has hanging nodes, bulged; its `mesh_points_scaled_jacobian` is the VTU's)
        check(float(np.min(sj)) > 0 and abs(float(np.min(sj)) - q["mesh_points_scaled_jacobian"]["min"]) < 1e-12 and
              q["measured_on"] == ("openfoam_case_points" if rep["counts"]["hanging_nodes"] > 0 else "mesh_points") and
              (rep["counts"]["hanging_nodes"] > 0 or q["scaled_jacobian"]["min"] == q["mesh_points_scaled_jacobian"]["min"]),
              f"VTU scaled Jacobian ({float(np.min(sj)):.6g}) agrees with the report's on the mesh's points "
              f"({q['mesh_points_scaled_jacobian']['min']:.6g}; measured on {q['measured_on']}: {q['scaled_jacobian']['min']:.6g})")
        # independent volume: hexahedra of the VTU are boxes here; sum of |det| of the edge vectors
        p = vm.points[hexes]
        vol = np.abs(np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 3] - p[:, 0], p[:, 4] - p[:, 0]))).sum()
        check(vol > 0, f"VTU volume {vol:.6g}")
    except ImportError:
        check(False, "meshio (python3-meshio) is installed")
    return work, rep, out


def write_two_cubes(path, gap):
    """two unit cubes, one over the other, `gap` apart (OFF, outward triangles)"""
    V, T = [], []
    for z0 in (0.03, 1.03 + gap):
        lo, hi = (0.03, 0.03, z0), (1.03, 1.03, z0 + 1)
        o = len(V)
        V += [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
        # corners: bit 0 x, bit 1 y, bit 2 z
        for a, b, c, d in ((0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (1, 3, 7, 5), (0, 4, 6, 2)):
            T += [(o + a, o + b, o + c), (o + a, o + c, o + d)]
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(T)} 0\n")
        f.writelines(f"{x} {y} {z}\n" for x, y, z in V)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in T)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexmesh", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    if shutil.which("checkMesh") is None:
        print("FAILED: checkMesh is not installed (apt-get install openfoam); it is the judge of this test")
        sys.exit(1)

    cases = [
        ("eight.off", [], "eight_default"),
        ("eight.off", ["--staircase"], "eight_staircase"),
        ("eight.off", ["--staircase", "--box", "-1,-1,-1,2,1,1", "--size", "0.25", "--surface-size", "0.03",
                       "--region", "seed:-0.9,-0.9,-0.9"], "eight_external_staircase"),
        ("cube.off", ["--size", "0.3", "--surface-size", "0.075", "--no-feature-pillows"], "cube"),
        ("cube.off", ["--size", "0.3", "--surface-size", "0.075"], "cube_pillows"),
        # (at 10 smoothing sweeps the capture with pillows is kept; at the default 8, and at 11 or 12
        # since released curve vertices go back to their curve, a retry without; since the feature
        # paths are searched again with the curves left short first: at 11, 13 and 16 sweeps the
        # capture with pillows, at 9, 10, 12 and 14 a retry without; since flat cells count as
        # inverted: at 8, 9 and 14 with pillows, at 10 - 13, 15 and 16 without - the choice
        # follows round-off, see the manual's "Round-off decides some figures")
        # (since the turn polish's far passes, stop 61, the retries keep a capture without pillows at
        # every count of sweeps from 8 to 16: the capture with them is asked for alone, no retry)
        ("fandisk.off", ["--size", "0.1", "--surface-size", "0.025", "--feature-pillows", "--smoothing-sweeps", "9",
                         "--capture-retry-cells", "0"],
         "fandisk_pillows"),
        ("anchor.off", ["--size", "0.12", "--surface-size", "0.03"], "anchor"),
        ("bunny.off", [], "bunny_default"),
        ("elephant.off", ["--size", "0.1", "--surface-size", "0.025"], "elephant"),
        ("fandisk.off", ["--size", "0.1", "--surface-size", "0.025"], "fandisk"),
        ("t20_part.off", ["--size", "4", "--surface-size", "1"], "t20_part"),
        ("teapot.off", [], "teapot_open_winding"),
        ("cube_nonmanifold.off", [], "cube_nonmanifold"),
        ("eight.off", ["--box", "-1,-1,-1,2,1,1", "--size", "0.25", "--surface-size", "0.03",
                       "--refine-box", "-0.4,-0.3,-0.6,1.5,0.3,0.6:0.0625", "--region", "seed:-0.9,-0.9,-0.9"],
         "eight_external"),
    ]
    # cells between levels: the staircase keeps the grid's boxes, so the rule can be checked exactly
    between = ["--staircase", "--box", "-1,-1,-1,2,1,1", "--size", "0.25", "--surface-size", "0.03125",
               "--region", "seed:-0.9,-0.9,-0.9"]
    cases += [("eight.off", between, "eight_between_1"),
              ("eight.off", between + ["--cells-between-levels", "3"], "eight_between_3")]
    results = {}
    for name, extra, label in cases:
        res = mesh_case(args, name, extra, label)
        if res:
            results[label] = res

    # external mesh: box patches present with the exact box
    if "eight_external" in results:
        work, rep, out = results["eight_external"]
        check("Overall domain bounding box (-1 -1 -1) (2 1 1)" in out, "the box is honoured exactly")
        check(re.search(r"Number of regions: 1 \(OK\)", out) is not None, "a seeded region is one region (checkMesh)")
        for p in ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax", "eight"]:
            check(re.search(r"^\s+%s\s+[1-9]\d*\s" % p, out, re.M) is not None, f"patch {p} has faces")

    # A seeded region's gap 2.5 cells wide between two bodies: trimming keeps the plate of grid
    # cells in it (kept neighbours along two axes), and the buffer cells on both sides make it a
    # channel of three cells. (Before, the plate went as a "plate one cell thick" and the mesh
    # closed the gap as if the two bodies were one: no cell in it; 0.35 apart, it had room already.)
    print("[gap between two bodies]")
    two_cubes = os.path.join(args.work, "two_cubes_gap.off")
    write_two_cubes(two_cubes, 0.25)
    res = mesh_case(args, two_cubes, ["--box", "-0.5,-0.5,-0.5,1.6,1.6,2.9", "--size", "0.2", "--surface-size", "0.1",
                                      "--region", "seed:-0.3,-0.3,-0.3"], "two_cubes_gap")
    if res:
        import meshio
        import numpy as np
        work, rep, out = res
        check("Mesh OK" in out, "two cubes 0.25 apart: checkMesh -allGeometry -allTopology: Mesh OK")
        vm = meshio.read(os.path.join(work, "mesh.vtu"))
        c = vm.points[vm.cells_dict["hexahedron"]].mean(axis=1)
        inner = (c[:, 0] > 0.2) & (c[:, 0] < 0.86) & (c[:, 1] > 0.2) & (c[:, 1] < 0.86)
        in_gap = inner & (c[:, 2] > 1.03) & (c[:, 2] < 1.28)
        # a column through the middle of the gap: the plate's cell and a buffer cell on each side
        column = in_gap & (np.abs(c[:, 0] - 0.53) < 0.05) & (np.abs(c[:, 1] - 0.53) < 0.05)
        layers = np.unique(np.round(c[column, 2], 3))
        check(in_gap.sum() >= 100 and len(layers) >= 3,
              f"two cubes 0.25 apart: {in_gap.sum()} cells in the gap (>= 100), {len(layers)} layers across it at its middle (>= 3)")
        # the channel's walls are the cubes' faces: every boundary vertex between them is on one
        b = np.unique(vm.cells_dict["hexahedron"][in_gap].ravel())
        z = vm.points[b, 2]
        walls = np.minimum(np.abs(z - 1.03), np.abs(z - 1.28))
        check(walls.min() < 1e-9, f"the gap's cells reach its walls (closest {walls.min():.2g})")

    # cells between levels: with n = 3, no cell of level <= l-2 comes within 3 cells of level l-1 of
    # the level-(l-1) box (the parent) of a cell of level l; the plain 2:1 balance breaks that rule
    print("[cells between levels]")
    def between_violations(label, n):
        import meshio
        import numpy as np
        vm = meshio.read(os.path.join(args.work, label, "mesh.vtu"))
        p = vm.points[vm.cells_dict["hexahedron"]]
        lo, hi = p.min(axis=1), p.max(axis=1)
        h = (hi - lo).max(axis=1)
        level = np.rint(np.log2(h.max() / h)).astype(int)   # 0: the initial grid (its cells are the largest)
        bad, pairs = 0, 0
        for l in range(2, level.max() + 1):
            a = np.where(level == l)[0]
            b = np.where(level <= l - 2)[0]
            if len(a) == 0 or len(b) == 0:
                continue
            hp = 2 * h[a[0]]                          # the parent's size
            plo = lo[a] - np.mod(lo[a] - lo.min(axis=0), hp) # the parent boxes (lattice from the box corner)
            plo = np.where(np.abs(np.mod(lo[a] - lo.min(axis=0), hp) - hp) < 1e-9 * hp, lo[a], plo)
            phi = plo + hp
            for i in range(0, len(a), 256):
                g = np.maximum(lo[b][None, :, :] - phi[i:i + 256, None, :], plo[i:i + 256, None, :] - hi[b][None, :, :])
                gap = g.max(axis=2)                   # Chebyshev gap between the boxes (< 0: overlapping)
                bad += int((gap < n * hp - 1e-9 * hp).sum())
            pairs += len(a) * len(b)
        return bad, pairs, len(level), int(level.max())
    if "eight_between_1" in results and "eight_between_3" in results:
        b1, _, n1, l1 = between_violations("eight_between_1", 3)
        b3, p3, n3, l3 = between_violations("eight_between_3", 3)
        check(l1 == l3 >= 3, f"the meshes have the same {l3 + 1} levels")
        check(b1 > 0, f"the plain 2:1 balance has cells of levels two apart within 3 cells ({b1} pairs)")
        check(b3 == 0, f"--cells-between-levels 3: no such pair ({b3} of {p3} pairs of cells two or more levels apart)")
        check(n3 > n1, f"--cells-between-levels 3 costs cells: {n3} (2:1: {n1})")
        r1 = results["eight_between_1"][1]["options"]
        check(r1.get("cells_between_levels") == 1 and results["eight_between_3"][1]["options"].get("cells_between_levels") == 3,
              "the report gives the option")

    # feature pillows (the default; --no-feature-pillows turns them off): a sheet of hexahedra
    # along the convex curves; on the cube every edge is convex, its chain runs on it, and every
    # corner joins three, so no boundary face has three corners on an edge: the worst cell is far
    # better than without, and the corners are exact
    print("[feature pillows]")
    if "cube" in results and "cube_pillows" in results and "fandisk" in results and "fandisk_pillows" in results:
        plain, pil = results["cube"][1], results["cube_pillows"][1]
        size = pil["fidelity"]["surface_size"]
        check(plain["boundary"].get("pillow_cells") == 0 and pil["boundary"]["pillow_cells"] > 0,
              f"pillow cells by default, none with --no-feature-pillows ({pil['boundary']['pillow_cells']})")
        check(pil["options"].get("feature_pillows") is True and plain["options"].get("feature_pillows") is False,
              "the report gives the option")
        sj0, sj1 = plain["quality"]["scaled_jacobian"]["min"], pil["quality"]["scaled_jacobian"]["min"]
        check(sj1 >= 0.8 and sj1 > sj0 + 0.1, f"cube: min scaled Jacobian {sj1:.3f} with pillows ({sj0:.3f} without)")
        ff = pil["feature_fidelity"]
        check(ff["max_corner_distance"] <= 0.01 * size, f"cube: every corner has a vertex within 0.01 s ({ff['max_corner_distance']:.3g})")
        check(ff["input_to_mesh"] <= 0.25 * size and ff["mesh_to_input"] <= 0.25 * size,
              f"cube: feature edges within 0.25 s both ways ({ff['input_to_mesh']:.3g}, {ff['mesh_to_input']:.3g})")
        # fandisk: only some convex curves run close enough to their chain; the mesh is checked
        # like every other (checkMesh, scaled Jacobian) above
        fp = results["fandisk_pillows"][1]
        check(0 < fp["boundary"]["pillow_cells"] < pil["boundary"]["pillow_cells"] * 10,
              f"fandisk: some pillows ({fp['boundary']['pillow_cells']} cells)")
        # --smoothing-sweeps bounds the capture's main sweeps (8 by default)
        fd = results["fandisk"][1]
        check(fp["options"].get("smoothing_sweeps") == 9 and fd["options"].get("smoothing_sweeps") == 8 and
              0 < fd["boundary"]["optimisation_passes"] <= 8 < fp["boundary"]["optimisation_passes"] <= 9,
              f"--smoothing-sweeps: the report gives 9 and 8 (default), and at most that many sweeps ran "
              f"({fp['boundary']['optimisation_passes']}, {fd['boundary']['optimisation_passes']})")

    # per-part surface sizes: a unit box whose top face is the part "lid"; as a staircase the cells
    # keep their boxes, so the sizes can be read off exactly
    print("[patch size]")
    box_obj = os.path.join(args.work, "box_lid.obj")
    with open(box_obj, "w") as f:
        for z in (0, 1):
            for y in (0, 1):
                for x in (0, 1):
                    f.write(f"v {x} {y} {z}\n")
        vid = lambda x, y, z: 1 + x + 2 * y + 4 * z
        quads = {"body": [[(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)], [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],
                          [(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)], [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)],
                          [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)]],
                 "lid": [[(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]]}
        for g, qs in quads.items():
            f.write(f"g {g}\n")
            for q in qs:
                a, b, c, d = [vid(*v) for v in q]
                f.write(f"f {a} {b} {c}\nf {a} {c} {d}\n")
    stair = ["--staircase", "--size", "0.25", "--surface-size", "0.125"]
    plain_box = os.path.join(args.work, "box_plain.vtu")
    r = run([args.hexmesh, box_obj, "-o", plain_box, "-q"] + stair)
    check(r.returncode == 0, "hexmesh meshes the box without --patch-size")
    res = mesh_case(args, box_obj, stair + ["--patch-size", "lid=0.03125"], "box_patch_size")
    if res and r.returncode == 0:
        import meshio
        import numpy as np
        def boxes(path):
            vm = meshio.read(path)
            p = vm.points[vm.cells_dict["hexahedron"]]
            lo, hi = p.min(axis=1), p.max(axis=1)
            return lo, hi, (hi - lo).max(axis=1)
        lo0, hi0, h0 = boxes(plain_box)
        lo1, hi1, h1 = boxes(os.path.join(res[0], "mesh.vtu"))
        check(abs(hi0[:, 2].max() - 0.875) < 1e-9, f"without: the staircase stops a surface size (1/8) under the lid ({hi0[:, 2].max()})")
        check(abs(hi1[:, 2].max() - 0.96875) < 1e-9, f"lid=1/32: the staircase stops 1/32 under the lid ({hi1[:, 2].max()})")
        under_lid = hi1[:, 2] > 0.96875 - 1e-9
        check(under_lid.any() and h1[under_lid].max() <= 0.03125 * (1 + 1e-9), f"the cells under the lid are 1/32 ({h1[under_lid].max()})")
        bottom = lo1[:, 2] < 0.125 + 1e-9
        check(bottom.any() and abs(h1[bottom].min() - 0.125) < 1e-9, f"the cells over the bottom (part body) stay 1/8 ({h1[bottom].min()})")
        check(res[1]["options"].get("patch_size") == ["lid=0.03125"], "the report gives the rule")
    # HFINE of a rule covering the only part is the global HFINE: same grid, byte for byte; without
    # it the surface size is too coarse for eight's handles (the region is empty)
    fine = os.path.join(args.work, "eight_fine_global.vtu")
    fine_p = os.path.join(args.work, "eight_fine_patch.vtu")
    coarse = os.path.join(args.work, "eight_coarse.vtu")
    eight = os.path.join(args.data, "eight.off")
    common = ["-q", "--staircase", "--size", "0.4", "--curvature-angle", "20"]
    r1 = run([args.hexmesh, eight, "-o", fine] + common + ["--surface-size", "0.1:0.025"])
    r2 = run([args.hexmesh, eight, "-o", fine_p] + common + ["--surface-size", "0.1", "--patch-size", "eig.*=0.1:0.025"])
    r3 = run([args.hexmesh, eight, "-o", coarse] + common + ["--surface-size", "0.1"])
    check(r1.returncode == 0 and r2.returncode == 0 and filecmp.cmp(fine, fine_p, shallow=False),
          "--patch-size eig.*=0.1:0.025 on eight gives the grid of --surface-size 0.1:0.025 (identical VTU)")
    check(r3.returncode != 0 and "region is empty" in r3.stderr, "without HFINE the region is empty (so HFINE refined)")
    for bad, what in ((["--patch-size", "nothing=0.1"], "no input part matches"), (["--patch-size", "lid=0.1:0.2"], "HFINE <= H"),
                      (["--patch-size", "lid=abc"], "expected H or H:HFINE")):
        r = run([args.hexmesh, box_obj, "-o", os.path.join(args.work, "bad_patch.vtu"), "-q"] + stair + bad)
        check(r.returncode == 2 and what in r.stderr and not os.path.exists(os.path.join(args.work, "bad_patch.vtu")),
              f"{' '.join(bad)}: exit 2, '{what}', nothing written (got {r.returncode}: {r.stderr.strip()[:120]})")

    # (bunny at the default sizes loses its ear tips, 13 surface sizes from the mesh; cube loses nothing)
    check(any(WARNED) and not all(WARNED), f"the far-input warning given on some cases, not all ({sum(WARNED)} of {len(WARNED)})")
    # the summary's fidelity line, without -q: the report's counts
    print("[fidelity summary]")
    d = os.path.join(args.work, "fidelity_summary")
    os.makedirs(d)
    r = run([args.hexmesh, os.path.join(args.data, "bunny.off"), "-o", os.path.join(d, "m.vtu"), "--report",
             os.path.join(d, "r.json")])
    m = re.search(r"^fidelity\s+(\d+) boundary faces on the input \((\d+) more capping holes\), (\d+) beyond 1/4 surface size "
                  r"\(the farthest (\S+) surface sizes off.*; (\d+) points of the input within (\S+) surface sizes", r.stdout, re.M)
    check(r.returncode == 0 and m is not None, f"the summary has a fidelity line ({r.stdout[-400:]!r})")
    if m:
        fi = json.load(open(os.path.join(d, "r.json")))["fidelity"]
        s_ = fi["surface_size"]
        check(int(m.group(1)) == fi["surface_faces"] and int(m.group(2)) == fi["cap_faces"] and
              int(m.group(3)) == fi["faces_beyond_quarter_surface_size"] and int(m.group(5)) == fi["samples"] and
              abs(float(m.group(4)) - fi["mesh_to_input_max"] / s_) <= 0.01 * fi["mesh_to_input_max"] / s_ and
              abs(float(m.group(6)) - fi["input_to_mesh_max"] / s_) <= 0.01 * fi["input_to_mesh_max"] / s_,
              f"the fidelity line agrees with the report: {m.group(0)}")
    # and, with a report, a line on the feature curves (bunny's 30-degree creases), its figures the report's
    mf = re.search(r"^features\s+(\d+) input feature edges within (\S+) surface sizes of the mesh's \(.*\), (\d+) mesh feature "
                   r"edges within (\S+) of the input's \(.*\); within \S+ degrees: (\S+) and (\S+); (\d+) corners within (\S+)$",
                   r.stdout, re.M)
    check(r.returncode == 0 and mf is not None, f"the summary has a features line ({r.stdout[-600:]!r})")
    if mf:
        rep = json.load(open(os.path.join(d, "r.json")))
        ff, s_ = rep["feature_fidelity"], rep["fidelity"]["surface_size"]
        close = lambda txt, v: v is not None and abs(float(txt) - v / s_) <= 0.01 * v / s_ + 1e-12
        check(ff["input_feature_edges"] > 0 and int(mf.group(1)) == ff["input_feature_edges"] and
              int(mf.group(3)) == ff["mesh_feature_edges"] and int(mf.group(7)) == ff["corners"] and
              close(mf.group(2), ff["input_to_mesh"]) and close(mf.group(4), ff["mesh_to_input"]) and
              close(mf.group(5), ff["within_tolerance"]["input_to_mesh"]) and
              close(mf.group(6), ff["within_tolerance"]["mesh_to_input"]) and close(mf.group(8), ff["max_corner_distance"]),
              f"the features line agrees with the report: {mf.group(0)}")
    # the warning's suggestion, followed, meshes bunny's ears: no warning, the input within the
    # surface size of the mesh (0.25 s at 6 cells down to s/8; 13.3 s at the default sizes)
    w = re.search(r"warning: parts of the input are up to \S+ surface sizes .*--thin-cells 6 --thin-size (\S+) meshes it", r.stderr)
    check(w is not None, f"bunny at the default sizes: the warning suggests a --thin-size ({r.stderr.strip()[-300:]!r})")
    if w:
        r2 = run([args.hexmesh, os.path.join(args.data, "bunny.off"), "-o", os.path.join(d, "m2.vtu"), "--report",
                  os.path.join(d, "r2.json"), "-q", "--thin-cells", "6", "--thin-size", w.group(1)])
        fi2 = json.load(open(os.path.join(d, "r2.json")))["fidelity"] if r2.returncode == 0 else None
        check(fi2 is not None and "warning: parts of the input" not in r2.stderr and
              fi2["input_to_mesh_max"] <= fi2["surface_size"],
              f"bunny with --thin-cells 6 --thin-size {w.group(1)}: no warning, the input within "
              f"{fi2['input_to_mesh_max'] / fi2['surface_size'] if fi2 else float('nan'):.2f} surface sizes of the mesh")
    # a plate too thin for the thin-part refinement already given (0.004 thick, cells of s/8 =
    # 0.0094 at most): the warning says so and suggests no --thin-size it already has; without the
    # refinement, it suggests one (0.00938: s/8 rounded up)
    plate = os.path.join(d, "cube_plate.obj")
    with open(plate, "w") as o:
        for lo, hi in (((0, 0, 0), (1, 1, 1)), ((0.9, 0.2, 0.498), (1.5, 0.8, 0.502))):
            for z in (lo[2], hi[2]):
                for x, y in ((lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])):
                    o.write(f"v {x} {y} {z}\n")
        for g, b in (("cube", 0), ("plate", 8)):
            o.write(f"g {g}\n")
            for q in ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)):
                o.write("f " + " ".join(str(b + i + 1) for i in q) + "\n")
    for extra, given in (([], False), (["--thin-cells", "6", "--thin-size", "0.009"], True)):
        r3 = run([args.hexmesh, plate, "-o", os.path.join(d, "plate.vtu"), "--force", "-q", "--size", "0.3",
                  "--surface-size", "0.075"] + extra)
        said = re.search(r"warning: parts of the input are up to (\S+) surface sizes", r3.stderr)
        check(r3.returncode == 0 and said is not None and float(said.group(1)) > 6 and
              ("--thin-cells 6 --thin-size 0.00938 meshes it" in r3.stderr) == (not given) and
              ("too thin for the thin-part refinement given (--thin-cells 6 --thin-size 0.009)" in r3.stderr) == given,
              f"a 0.004 plate {'with' if given else 'without'} --thin-cells 6 --thin-size 0.009: the warning "
              f"{'names the refinement given' if given else 'suggests --thin-size 0.00938'} ({r3.stderr.strip()[-330:]!r})")

    # determinism: byte-identical outputs
    print("[determinism]")
    d = os.path.join(args.work, "determinism")
    os.makedirs(d)
    for k in (1, 2):
        r = run([args.hexmesh, os.path.join(args.data, "anchor.off"), "-o", os.path.join(d, f"m{k}.vtu"),
                 "-o", os.path.join(d, f"case{k}"), "-q", "--size", "0.1", "--surface-size", "0.02"])
        check(r.returncode == 0, "hexmesh runs")
    check(filecmp.cmp(os.path.join(d, "m1.vtu"), os.path.join(d, "m2.vtu"), shallow=False), "VTU files identical")
    for f in ["points", "faces", "owner", "neighbour", "boundary"]:
        check(filecmp.cmp(os.path.join(d, "case1/constant/polyMesh", f), os.path.join(d, "case2/constant/polyMesh", f),
                          shallow=False), f"polyMesh/{f} identical")
    # whatever the number of threads: anchor at --surface-size 0.045 (cells of 0.18, 4,300 to 4,900
    # of them) runs 7 captures: at the staircases 0.4 and 0.25 the capture with pillows leaves far
    # faces and cells below 0.3, so the one without pillows waits (`pillow_free_deferred`) until
    # the closer staircase 0.2 is made; its mesh keeps 3 cells below 0.3, so the deferred captures
    # then run on those two grids (kept). With two threads each capture without pillows runs ahead
    # while the one with them runs, and is kept when it is deferred (not run again): the same mesh
    for k in (1, 2):
        r = run([args.hexmesh, os.path.join(args.data, "anchor.off"), "-o", os.path.join(d, f"t{k}.msh"),
                 "--report", os.path.join(d, f"t{k}.json"), "-q", "--threads", str(k), "--surface-size", "0.045"])
        check(r.returncode == 0, f"hexmesh --threads {k} runs")
    jt = [json.load(open(os.path.join(d, f"t{k}.json"))) for k in (1, 2)]
    check(jt[0]["options"]["threads"] == 1 and jt[1]["options"]["threads"] == min(2, os.cpu_count() or 1),
          f"the report's threads: {jt[0]['options']['threads']}, {jt[1]['options']['threads']}")
    check(jt[1]["boundary"]["capture_tries"] >= 2,
          f"anchor retries the capture ({jt[1]['boundary']['capture_tries']} captures, "
          f"{jt[1]['boundary']['staircase_tries']} staircases)")
    def by_staircase(jr):   # (each staircase's captures, in order)
        caps, out = jr["boundary"]["captures"], []
        for x in jr["boundary"]["staircases"]:
            out.append((x, caps[:x["captures"]]))
            caps = caps[x["captures"]:]
        return out
    for jr in jt:
        st = by_staircase(jr)
        deferred_ahead = sum(c["ran_ahead"] for x, cs in st if x["deferred_weights"] for c in cs)
        check([x["gap"] for x, _ in st] == [0.4, 0.25, 0.2, 0.4, 0.25] and
              all(x["pillow_free_deferred"] and x["weights_deferred"] for x, _ in st[:2]) and
              all(not c["feature_pillows"] for x, cs in st[3:] for c in cs) and
              all(len(cs) == 1 and cs[0]["feature_pillows"] for x, cs in st[:2]) and
              st[2][0]["kept"] and (deferred_ahead > 0) == (jr["options"]["threads"] > 1),
              f"anchor, {jr['options']['threads']} thread(s): the captures without pillows deferred at 0.4 and 0.25, "
              f"made after 0.2 on those grids: staircases (gap, captures, pillow-free deferred, deferred ones, kept) "
              f"{[(x['gap'], len(cs), x['pillow_free_deferred'], x['deferred_weights'], x['kept']) for x, cs in st]}, "
              f"{deferred_ahead} deferred captures kept from their run ahead")
    check(filecmp.cmp(os.path.join(d, "t1.msh"), os.path.join(d, "t2.msh"), shallow=False),
          "--threads 1 and --threads 2: MSH files identical")
    # the report's log of the captures: the same captures with the same results for any thread
    # count; with two threads (on two cores) some ran ahead, with one none did
    def outcomes(jr):
        return [(c["staircase_gap"], c["choice"], c["rerun"], c["cells"], c["evaluated"], c.get("cells_below_0_3"),
                 c.get("min_scaled_jacobian"), c["kept"]) for c in jr["boundary"]["captures"]]
    check(outcomes(jt[0]) == outcomes(jt[1]) and len(outcomes(jt[0])) >= 2,
          f"--threads 1 and 2: the same {len(outcomes(jt[0]))} captures with the same outcomes")
    ahead_ = [sum(c["ran_ahead"] for c in jr["boundary"]["captures"]) for jr in jt]
    check(ahead_[0] == 0 and (ahead_[1] > 0) == (jt[1]["options"]["threads"] > 1),
          f"captures run ahead: {ahead_[0]} with one thread, {ahead_[1]} with {jt[1]['options']['threads']}")
    # --all-capture-retries: every capture of the sequence at each of the three staircases; the
    # captures the default rules ran are among them, with the same outcomes (the same grid, the
    # same settings: the same capture). elephant-with-holes at the default sizes: its first
    # capture leaves faces beyond s/4, which other path weights do not reach, so those weights
    # wait until the closer staircases are made and then run on the grid of the staircase kept so
    # far, made again (`Staircase_record::weights_deferred`, `deferred_weights`); with a budget of
    # 8,000 cells (its captures are 2,877 cells: no room for two captures of each closer
    # staircase and one more) they run at once, before one closer staircase. (Its holes left
    # open, --no-fill-holes: filled, its first capture's far faces are different ones.)
    r = run([args.hexmesh, os.path.join(args.data, "elephant-with-holes.off"), "-o", os.path.join(d, "all.msh"),
             "--report", os.path.join(d, "all.json"), "-q", "--threads", "1", "--all-capture-retries", "--no-fill-holes"])
    check(r.returncode == 0, "hexmesh --all-capture-retries runs")
    ja = json.load(open(os.path.join(d, "all.json")))
    jdef = []
    for tag, extra in (("def", []), ("b8k", ["--capture-retry-cells", "8000"])):
        r = run([args.hexmesh, os.path.join(args.data, "elephant-with-holes.off"), "-o", os.path.join(d, tag + ".msh"),
                 "--report", os.path.join(d, tag + ".json"), "-q", "--threads", "1", "--no-fill-holes"] + extra)
        check(r.returncode == 0, f"hexmesh elephant-with-holes {' '.join(extra)} runs")
        jdef.append(json.load(open(os.path.join(d, tag + ".json"))))
    def key(c):   # (a deferred capture's `choice` counts in its own sequence)
        return (c["staircase_gap"], c["feature_pillows"], c["paths_ratio"])
    full = {key(c): c for c in ja["boundary"]["captures"] if not c["rerun"]}
    def among(jr):
        return all(key(c) in full and all(full[key(c)].get(f) == c.get(f) for f in
                   ("cells", "evaluated", "openfoam_faults_found", "cells_below_0_3", "min_scaled_jacobian"))
                   for c in jr["boundary"]["captures"] if not c["rerun"])
    sd = jdef[0]["boundary"]["staircases"]
    s8 = jdef[1]["boundary"]["staircases"]
    check([x["gap"] for x in sd] == [0.4, 0.25, 0.2, 0.4] and sd[0]["weights_deferred"] and sd[1]["weights_deferred"] and
          not sd[2]["weights_deferred"] and sd[3]["deferred_weights"] and sum(x["deferred_weights"] for x in sd) == 1 and
          sum(x["kept"] for x in sd) == 1 and among(jdef[0]) and
          not any(x["weights_deferred"] or x["deferred_weights"] for x in s8) and jdef[1]["boundary"]["capture_tries"] >= 2 and
          among(jdef[1]),
          f"deferred path weights: staircases (gap, deferred, the deferred ones, kept) "
          f"{[(x['gap'], x['weights_deferred'], x['deferred_weights'], x['kept']) for x in sd]}; with a budget of 8,000 "
          f"cells {[(x['gap'], x['weights_deferred'], x['kept']) for x in s8]}; their captures the same as in the full sequence")
    sa, ca = ja["boundary"]["staircases"], ja["boundary"]["captures"]
    check(ja["options"]["all_capture_retries"] is True and len(sa) == 3 and
          all(x["captures"] >= 4 for x in sa) and len(full) > len(jdef[0]["boundary"]["captures"]) and
          not any(x["weights_deferred"] or x["deferred_weights"] for x in sa),
          f"--all-capture-retries: {len(ca)} captures in {len(sa)} staircases "
          f"({[x['captures'] for x in sa]}), more than the default's {len(jdef[0]['boundary']['captures'])}, none deferred")

    # errors and exit codes
    print("[errors]")
    e = os.path.join(args.work, "errors")
    os.makedirs(e)
    open(os.path.join(e, "empty.off"), "w").close()
    with open(os.path.join(e, "garbage.stl"), "w") as f:
        f.write("solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 zz\n")
    with open(os.path.join(e, "nan.off"), "w") as f:
        f.write("OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n")
    eight = os.path.join(args.data, "eight.off")
    def expect(cmd, code, needle, what):
        r = run([args.hexmesh] + cmd)
        msg = r.stderr.strip()
        # the error is one line "hexmesh: <cause>" (information lines may precede it)
        lines = [l for l in msg.splitlines() if needle in l]
        check(r.returncode == code and len(lines) == 1 and lines[0].startswith("hexmesh: "),
              f"{what}: exit {r.returncode} (want {code}), message: {msg[:200]}")
    expect([os.path.join(e, "missing.off"), "-o", os.path.join(e, "x.vtu")], 2, "cannot open", "missing file")
    expect([os.path.join(e, "empty.off"), "-o", os.path.join(e, "x.vtu")], 2, "empty", "empty file")
    expect([os.path.join(e, "garbage.stl"), "-o", os.path.join(e, "x.vtu")], 2, "garbage.stl", "garbage file")
    expect([os.path.join(e, "nan.off"), "-o", os.path.join(e, "x.vtu")], 2, "nan.off", "NaN coordinate")
    expect([eight, "-o", os.path.join(e, "x.vtu"), "--region", "seed:9,9,9"], 2, "outside the meshing box", "seed outside")
    expect([eight, "-o", os.path.join(e, "x.vtu"), "--region", "seed:0.0368,0.0509,-0.0874"], 2, "inside a body", "seed inside")
    expect([eight, "-o", os.path.join(e, "x.vtu"), "--size", "-1"], 1, "--size: must be a positive number", "negative size")
    expect([eight, "-o", os.path.join(e, "x.vtu"), "--smoothing-sweeps", "0"], 1, "--smoothing-sweeps: Value 0 not in range",
           "no smoothing sweep")
    expect([eight, "-o", os.path.join(e, "x.vtu"), "--box", "1,1,1,0,0,0"], 1, "min must be below", "inverted box")
    expect([eight, "-o", os.path.join(e, "x.vtu"), "--surface-size", "0.02:0.04"], 1, "HFINE must not exceed H",
           "curvature size above the surface size")
    expect([eight, "-o", os.path.join(e, "x.vtu"), "--surface-size", "0.02:x"], 1, "'x' is not a number",
           "curvature size not a number")
    expect([eight, "-o", os.path.join(e, "x.vtu"), "--thin-cells", "3", "--thin-size", "0"], 1,
           "--thin-size: must be a positive number", "thin size zero")
    expect([eight, "-o", os.path.join(e, "x.xyz")], 1, "unknown output format", "unknown output format")
    check(not os.path.exists(os.path.join(e, "x.vtu")), "nothing written on errors")
    # refuses to overwrite
    keep = os.path.join(e, "keep.vtu")
    with open(keep, "w") as f:
        f.write("user data")
    expect([eight, "-o", keep], 3, "use --force", "existing VTU")
    check(open(keep).read() == "user data", "the existing file is untouched")
    os.makedirs(os.path.join(e, "case", "constant", "polyMesh"))
    expect([eight, "-o", os.path.join(e, "case")], 3, "use --force", "existing polyMesh")
    r = run([args.hexmesh, eight, "-o", keep, "--force", "-q"])
    check(r.returncode == 0 and open(keep, "rb").read(5) == b"<?xml", "--force overwrites")
    # help
    r = run([args.hexmesh, "--help"])
    check(r.returncode == 0 and "Examples:" in r.stdout and "Exit codes" in r.stdout, "--help with examples and exit codes")

    print()
    if FAILURES:
        print(f"{len(FAILURES)} checks failed:")
        for f in FAILURES:
            print("  -", f)
        sys.exit(1)
    print("all CLI checks passed")


if __name__ == "__main__":
    main()
