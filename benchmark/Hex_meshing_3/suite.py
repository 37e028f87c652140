#!/usr/bin/python3
"""Tet versus hex: the benchmark suite (hexmesh, snappyHexMesh, TetGen raw and on a remeshed surface,
CGAL Mesh_3).

For every surface of the repository's test data (and of ../shared/data when present; a file of
the same name there is preferred), at resolutions h = bounding-box diagonal / D for each D of
--divisions (default 40 and 80), runs:
  hexmesh          --size h --surface-size h (cells of edge h inside and on the surface; defaults
                   otherwise), writing Gmsh MSH (its boundary quads are measured) and, when
                   OpenFOAM's checkMesh is installed, an OpenFOAM case judged by
                   `checkMesh -allTopology`;
  hexmesh-adaptive --size 4h --surface-size h --thin-cells 5 --soft-crease-angle 20 (the same
                   outputs);
  snappy           when OpenFOAM is installed, snappyHexMesh at the settings of hexmesh-adaptive
                   (dictionaries generated from h: background cells 4h over the bounding box grown
                   by 4h, the surface and its 30-degree feature edges at level 2 = h,
                   resolveFeatureAngle 30, nCellsBetweenLevels 1, explicit feature snapping, no
                   layers; locationInMesh a point found inside the input by its winding number);
                   its seconds are snappyHexMesh's, blockMesh and surfaceFeatureExtract apart;
  tetgen           TetGen -pq1.2/15 -a(h^3/(6 sqrt 2)) on the input's triangles;
  tetgen-remeshed  the same after CGAL's isotropic remeshing of the surface to edge length h;
  mesh3            CGAL Mesh_3: edge size h, facet size h/sqrt(3), cell size h sqrt(6)/4, facet
                   distance h/10 (see tet_baselines.cpp).
Each mesher runs as its own process under /usr/bin/time (wall seconds and peak memory of the
process), with a timeout. Every mesh's boundary is measured against the input by the same tool
(surface_distance: two-sided, area-uniform samples plus vertices). checkMesh -allTopology judges
every mesh that can go to OpenFOAM: hexmesh's cases, snappyHexMesh's, and the tetrahedral meshes
after gmshToFoam (at the coarsest h only, by default: --check-tets). Failures are results: each
run is classed valid mesh / clear error (non-zero exit with a message) / silent failure (exit 0 but
no mesh, an invalid one, a hexmesh mesh checkMesh rejects, or a boundary farther than 4h from the
input anywhere: a leak) / crash (killed by a signal, abort) / timeout.

Two jobs (input, h) run at a time, each pinned to one core (taskset); within a job the meshers
run one after the other on that core.

Writes into --work: results.csv (one row per run), results.json (with the quality histograms),
robustness.csv, elements_vs_h.png, time_vs_elements.png, quality_histograms.png; with --publish,
the manual's page doc/Hex_meshing_3/Benchmarks.txt (its figures in doc/Hex_meshing_3/fig/) and
the README's headline table between its <!-- benchmarks --> markers, all from this run.

Usage: benchmark/Hex_meshing_3/suite.py [--work DIR] [--divisions 40,80] [--only NAME ...]
           [--meshers LIST] [--jobs 2] [--timeout 150] [--check-tets coarsest|all|none]
           [--publish] [--reuse | --rerun MESHER,...]
Build first: scripts/build.sh, then cmake --build build --target tet_baselines surface_distance.
Needs Debian's python3-meshio, python3-numpy, python3-matplotlib (/usr/bin/python3).
"""
import argparse
import concurrent.futures
import csv
import datetime
import glob
import json
import math
import os
import platform
import re
import shutil
import signal
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
BUILD = os.path.join(ROOT, "build")
DATA_DIRS = [os.path.join(ROOT, "test", "Hex_meshing_3", "data"), os.path.normpath(os.path.join(ROOT, "..", "shared", "data"))]
MESHERS = ["hexmesh", "hexmesh-adaptive", "snappy", "tetgen", "tetgen-remeshed", "mesh3"]
HEX_OPTIONS = {"hexmesh": lambda h: ["--size", repr(h), "--surface-size", repr(h)],
               # what a user would ask for: coarser inside, h on the surface, thin parts and gaps
               # refined until 5 cells span them (down to h/4). Five, not three: the body-fitted
               # boundary needs a cut cell and the buffer gap on each side of a part plus one uncut
               # cell between; at 3, bunny's ears and fandisk's flange (3.6 h thick) keep voids
               # (bunny at diagonal/80: 343 boundary faces beyond h/4 at 3, 86 at 5); the creases
               # of faceted blends followed from 20 degrees (fandisk / 80: fidelity 0.0044 h ->
               # 0.0036 h with the same cells; t20_part's 0.0029 -> 0.0031)
               "hexmesh-adaptive": lambda h: ["--size", repr(4 * h), "--surface-size", repr(h), "--thin-cells", "5",
                                              "--soft-crease-angle", "20"]}
LEAK = 4   # a boundary point farther than LEAK * h from the input: the mesh leaked (see main)
ENV = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))


def inputs():
    """name -> path: the test data, overridden by ../shared/data's files of the same name"""
    found = {}
    for d in DATA_DIRS:
        for f in sorted(glob.glob(os.path.join(d, "*.off"))):
            found[os.path.basename(f)[:-4]] = f
    return dict(sorted(found.items()))


def dirty_inputs():
    """the inputs whose category in the test data's MANIFEST starts with 'dirty'"""
    dirty = set()
    for d in DATA_DIRS:
        man = os.path.join(d, "MANIFEST.md")
        if os.path.exists(man):
            for line in open(man):
                cols = [c.strip() for c in line.split("|")]
                if len(cols) > 3 and cols[1].endswith(".off") and cols[2].startswith("dirty"):
                    dirty.add(cols[1][:-4])
    return dirty


def source_commit():
    """the repository's commit the meshers were built from ('+ local changes' if include/, tools/
    or benchmark/ differ from it), or 'unknown' outside a git checkout"""
    try:
        h = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                           timeout=20)
        if h.returncode != 0:
            return "unknown"
        d = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--", "include", "tools", "benchmark"],
                           capture_output=True, text=True, timeout=20)
        return h.stdout.strip() + (" + local changes" if d.stdout.strip() else "")
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def read_off(path):
    """points and triangles (polygons fanned) of an OFF file"""
    with open(path) as f:
        toks = [t for line in f for t in line.split("#")[0].split()]
    i = 1 if toks[0].upper() == "OFF" else 0
    nv, nf = int(toks[i]), int(toks[i + 1])
    k = i + 3
    pts = [(float(toks[k + 3 * j]), float(toks[k + 3 * j + 1]), float(toks[k + 3 * j + 2])) for j in range(nv)]
    k += 3 * nv
    tris = []
    for _ in range(nf):
        n = int(toks[k])
        f = [int(x) for x in toks[k + 1:k + 1 + n]]
        k += 1 + n
        tris += [(f[0], f[j], f[j + 1]) for j in range(1, n - 1)]
    return pts, tris


def diagonal(path):
    pts = read_off(path)[0]
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    return math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3)))


def pinned(cmd, core):
    """cmd run on one core (taskset), when there is a core to pin to"""
    return ["taskset", "-c", str(core)] + cmd if core is not None and shutil.which("taskset") else cmd


def timed(cmd, core, timeout, log):
    """runs cmd pinned to `core`; returns (exit code or None on timeout, wall s, peak MiB, stdout)"""
    tf = log + ".time"
    full = pinned(["/usr/bin/time", "-f", "%e %M", "-o", tf] + cmd, core)
    # its own process group, so that a timeout kills the mesher, not only /usr/bin/time above it
    p = subprocess.Popen(full, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV, start_new_session=True)
    try:
        stdout, stderr = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        p.communicate()
        return None, float(timeout), None, "", "timeout"

    class R:
        pass
    r = R()
    r.stdout, r.stderr, r.returncode = stdout, stderr, p.returncode
    with open(log, "w") as f:
        f.write(r.stdout + r.stderr)
    wall, mib = None, None
    try:
        t = open(tf).read().split()
        # /usr/bin/time prints "Command terminated by signal N" / "Command exited with non-zero
        # status N" first when it applies
        wall, mib = float(t[-2]), float(t[-1]) / 1024
    except (OSError, ValueError, IndexError):
        pass
    rc = r.returncode
    txt = open(tf).read() if os.path.exists(tf) else ""
    m = re.search(r"terminated by signal (\d+)", txt)
    if m:
        rc = -int(m.group(1))
    return rc, wall, mib, r.stdout, r.stderr


def post(cmd, core, timeout, **kw):
    """a post-processing command (conversion, check, extraction): pinned to the job's core like the
    meshers (the other job's mesher is being timed on the other core), with a timeout; returns the
    CompletedProcess, or None on a timeout"""
    try:
        return subprocess.run(pinned(cmd, core), capture_output=True, text=True, env=ENV, timeout=timeout, **kw)
    except subprocess.TimeoutExpired:
        return None


def classify(rc, stderr, elements, valid):
    if rc == "not run":
        return "not run"
    if rc is None:
        return "timeout"
    if rc < 0 or rc >= 128:
        return "crash"
    if rc != 0:
        return "clear error" if stderr.strip() else "silent failure"
    return "valid mesh" if elements and valid else "silent failure"


def distance(tool, a, b, samples=10000):
    r = subprocess.run([tool, a, b, "--samples", str(samples)], capture_output=True, text=True)
    if r.returncode != 0:
        return None
    return json.loads(r.stdout)


def hex_boundary_and_edges(msh, out_obj):
    """the boundary quads of a hexmesh MSH as a triangulated OBJ, and the longest hexahedron edge"""
    import meshio
    import numpy as np
    m = meshio.read(msh)
    quads = np.concatenate([c.data for c in m.cells if c.type == "quad"]) if any(c.type == "quad" for c in m.cells) else np.zeros((0, 4), int)
    hexes = np.concatenate([c.data for c in m.cells if c.type == "hexahedron"])
    with open(out_obj, "w") as f:
        for p in m.points:
            f.write("v %.17g %.17g %.17g\n" % tuple(p))
        for q in quads:
            f.write("f %d %d %d\nf %d %d %d\n" % (q[0] + 1, q[1] + 1, q[2] + 1, q[0] + 1, q[2] + 1, q[3] + 1))
    E = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
    longest = 0.0
    P = m.points
    for a, b in E:
        longest = max(longest, float(np.max(np.linalg.norm(P[hexes[:, a]] - P[hexes[:, b]], axis=1))))
    return len(hexes), len(P), longest


FOAM_HEADER = "FoamFile {{ version 2.0; format ascii; class dictionary; object {}; }}\n"
FOAM_SYSTEM = {
    "controlDict": "application snappyHexMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;\n"
                   "writeControl timeStep; writeInterval 1; writeFormat ascii; writePrecision 17; writeCompression off;\n"
                   "timeFormat general; timePrecision 6; runTimeModifiable false;\n",
    "fvSchemes": "ddtSchemes {} gradSchemes {} divSchemes {} laplacianSchemes {} interpolationSchemes {} snGradSchemes {}\n",
    "fvSolution": "solvers {}\n",
}
# snappyHexMesh's quality controls: the values of the OpenFOAM tutorials' meshQualityDict
SNAPPY_QUALITY = """meshQualityControls
{
    maxNonOrtho 65; maxBoundarySkewness 20; maxInternalSkewness 4; maxConcave 80; minVol 1e-13;
    minTetQuality 1e-15; minArea -1; minTwist 0.02; minDeterminant 0.001; minFaceWeight 0.05;
    minVolRatio 0.01; minTriangleTwist -1; nSmoothScale 4; errorReduction 0.75;
    relaxed { maxNonOrtho 75; }
}
"""


def foam_case(case, extra, binary=False):
    """an OpenFOAM case directory with the system files every utility needs, plus `extra`
    {name: body} in system/"""
    os.makedirs(os.path.join(case, "system"), exist_ok=True)
    os.makedirs(os.path.join(case, "constant"), exist_ok=True)
    files = dict(FOAM_SYSTEM, **extra)
    if binary:
        files["controlDict"] = files["controlDict"].replace("writeFormat ascii", "writeFormat binary")
    for name, body in files.items():
        with open(os.path.join(case, "system", name), "w") as f:
            f.write(FOAM_HEADER.format(name) + body)


def inside_point(pts, tris, seed=1):
    """a point well inside the input (for snappyHexMesh's locationInMesh): of candidates on a
    jittered 12^3 lattice of the bounding box, one whose generalised winding number is above 1/2
    in absolute value (inside, also on open or inconsistent input: a floating-point estimate, as
    in hexmesh; either orientation) and
    whose distance to area-uniform samples of the surface is largest; None if none is inside"""
    import numpy as np
    P, T = np.array(pts, float), np.array(tris, int).reshape(-1, 3)
    if not len(T) or not len(P):
        return None
    A, B, C = P[T[:, 0]], P[T[:, 1]], P[T[:, 2]]
    lo, hi = P.min(0), P.max(0)
    rng = np.random.default_rng(seed)
    g = (np.stack(np.meshgrid(*[np.arange(12)] * 3, indexing="ij"), -1).reshape(-1, 3) + 0.5
         + rng.uniform(-0.3, 0.3, (12 ** 3, 3))) / 12
    Q = lo + g * (hi - lo)
    w = np.zeros(len(Q))
    step = max(1, 2000000 // len(T))   # candidates per chunk: arrays of at most 2e6 x 3 doubles
    for k in range(0, len(Q), step):   # Van Oosterom and Strackee's solid angle, summed over triangles
        a, b, c = A[None] - Q[k:k + step, None], B[None] - Q[k:k + step, None], C[None] - Q[k:k + step, None]
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        num = np.einsum("ijk,ijk->ij", a, np.cross(b, c))
        den = la * lb * lc + np.einsum("ijk,ijk->ij", a, b) * lc + np.einsum("ijk,ijk->ij", b, c) * la \
            + np.einsum("ijk,ijk->ij", c, a) * lb
        w[k:k + step] = np.arctan2(num, den).sum(1) / (2 * np.pi)
    inside = Q[np.abs(w) > 0.5]
    if not len(inside):
        return None
    area = np.linalg.norm(np.cross(B - A, C - A), axis=1)
    if not area.sum() > 0:
        return None
    pick = rng.choice(len(T), 20000, p=area / area.sum())
    u, v = rng.random(20000), rng.random(20000)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    S = np.concatenate([A[pick] + u[:, None] * (B - A)[pick] + v[:, None] * (C - A)[pick], P])
    d = np.array([np.min(np.linalg.norm(S - q, axis=1)) for q in inside])
    return tuple(float(x) for x in inside[np.argmax(d)])


def checkmesh_figures(case, core=None, timeout=None):
    """checkMesh -allTopology on a case: verdict, cells, points, hexahedra, tetrahedra, max
    non-orthogonality, max skewness"""
    r = post(["checkMesh", "-case", case, "-allTopology"], core, timeout)
    if r is None:
        return {"checkMesh": "checkMesh timed out", "checkMesh_flags": ""}
    s = r.stdout
    m = re.search(r"Failed (\d+) mesh checks", s)
    out = {"checkMesh": "Mesh OK" if "Mesh OK" in s else f"Failed {m.group(1)}" if m else "no verdict",
           "checkMesh_flags": " ".join(l.strip() for l in s.splitlines() if l.strip().startswith("***"))[:300]}
    for key, pat, conv in (("cells", r"^\s*cells:\s+(\d+)", int), ("points", r"^\s*points:\s+(\d+)", int),
                           ("hexahedra", r"^\s*hexahedra:\s+(\d+)", int), ("tetrahedra", r"^\s*tetrahedra:\s+(\d+)", int),
                           ("max_non_orthogonality", r"Mesh non-orthogonality Max: ([0-9.eE+-]+)", float),
                           ("max_skewness", r"Max skewness = ([0-9.eE+-]+)", float)):
        m = re.search(pat, s, re.M)
        if m:
            out[key] = conv(m.group(1))
    return out


def poly_longest_edge(case):
    """the longest edge of an ASCII polyMesh's faces"""
    import numpy as np
    poly = os.path.join(case, "constant", "polyMesh")
    def body(name):
        t = open(os.path.join(poly, name)).read()
        return t[t.index("}", t.index("FoamFile")) + 1:]
    P = np.array([[float(x) for x in t.split()] for t in re.findall(r"\(([^()]*)\)", body("points"))])
    longest = 0.0
    for t in re.findall(r"\d+\(([^()]*)\)", body("faces")):
        f = [int(x) for x in t.split()]
        q = P[f]
        longest = max(longest, float(np.max(np.linalg.norm(q - np.roll(q, 1, axis=0), axis=1))))
    return longest


def snappy_dicts(pts, h, location):
    """blockMeshDict, surfaceFeatureExtractDict and snappyHexMeshDict matching hexmesh-adaptive:
    background cells of 4h over the bounding box grown by one such cell, the surface and its feature
    edges (30 degrees) refined twice (to h), gaps and thin parts narrower than 5 cells refined up to
    level 4 (h/4; gapLevel (5 2 4), gapMode mixed: --thin-cells 5 down to h/4), resolveFeatureAngle
    30, one cell between levels (hexmesh's default), explicit feature snapping, no layers"""
    b = 4 * h
    lo = [min(p[k] for p in pts) - b for k in range(3)]
    hi = [max(p[k] for p in pts) + b for k in range(3)]
    n = [max(1, math.ceil((hi[k] - lo[k]) / b)) for k in range(3)]
    hi = [lo[k] + n[k] * b for k in range(3)]
    v = " ".join("(%r %r %r)" % (x, y, z) for z in (lo[2], hi[2]) for (x, y) in
                 ((lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])))
    block = (f"convertToMeters 1;\nvertices ({v});\nblocks (hex (0 1 2 3 4 5 6 7) ({n[0]} {n[1]} {n[2]}) simpleGrading (1 1 1));\n"
             "edges ();\nboundary ( box { type patch; faces ((0 3 2 1) (4 5 6 7) (0 1 5 4) (2 3 7 6) (1 2 6 5) (3 0 4 7)); } );\n"
             "mergePatchPairs ();\n")
    feature = ("body.obj { extractionMethod extractFromSurface; extractFromSurfaceCoeffs { includedAngle 150; }\n"
               "  subsetFeatures { nonManifoldEdges yes; openEdges yes; } writeObj no; }\n")
    snappy = f"""castellatedMesh true; snap true; addLayers false;
geometry {{ body.obj {{ type triSurfaceMesh; name body; }} }}
castellatedMeshControls
{{
    maxLocalCells 10000000; maxGlobalCells 50000000; minRefinementCells 0; maxLoadUnbalance 0.1;
    nCellsBetweenLevels 1;
    features ( {{ file "body.eMesh"; level 2; }} );
    refinementSurfaces {{ body {{ level (2 2); gapLevel (5 2 4); gapMode mixed; }} }}
    resolveFeatureAngle 30;
    refinementRegions {{}}
    locationInMesh ({location[0]!r} {location[1]!r} {location[2]!r});
    allowFreeStandingZoneFaces true;
}}
snapControls
{{
    nSmoothPatch 3; tolerance 2.0; nSolveIter 30; nRelaxIter 5;
    nFeatureSnapIter 10; implicitFeatureSnap false; explicitFeatureSnap true; multiRegionFeatureSnap false;
}}
addLayersControls
{{
    relativeSizes true; layers {{}} expansionRatio 1.0; finalLayerThickness 0.3; minThickness 0.1; nGrow 0;
    featureAngle 60; slipFeatureAngle 30; nRelaxIter 3; nSmoothSurfaceNormals 1; nSmoothNormals 3;
    nSmoothThickness 10; maxFaceThicknessRatio 0.5; maxThicknessToMedialRatio 0.3; minMedialAxisAngle 90;
    nBufferCellsNoExtrude 0; nLayerIter 50;
}}
{SNAPPY_QUALITY}
mergeTolerance 1e-6;
"""
    return {"blockMeshDict": block, "surfaceFeatureExtractDict": feature, "snappyHexMeshDict": snappy}


def run_snappy(args, path, h, wd, core, row):
    """snappyHexMesh at settings matching hexmesh-adaptive (snappy_dicts); its wall seconds and peak
    memory are snappyHexMesh's, blockMesh's and surfaceFeatureExtract's seconds are recorded apart.
    Returns (exit code, wall, MiB, stderr, elements, valid)"""
    case = os.path.join(wd, "snappy_case")
    obj = os.path.join(wd, "snappy_boundary.obj")
    shutil.rmtree(case, ignore_errors=True)
    if os.path.exists(obj):
        os.remove(obj)
    pts, tris = read_off(path)
    location = inside_point(pts, tris)
    if location is None:   # the suite's failure, not snappy's: "not run"
        row["message"] = "suite: no point found inside the input for locationInMesh"
        return "not run", None, None, "", 0, False
    foam_case(case, snappy_dicts(pts, h, location))
    os.makedirs(os.path.join(case, "constant", "triSurface"))
    with open(os.path.join(case, "constant", "triSurface", "body.obj"), "w") as f:
        f.writelines("v %.17g %.17g %.17g\n" % p for p in pts)
        f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in tris)
    row["location_in_mesh"] = location
    for tool in ("blockMesh", "surfaceFeatureExtract"):
        rc, wall, _, _, err = timed([tool, "-case", case], core, args.timeout, os.path.join(wd, f"snappy_{tool}.log"))
        row[f"{tool}_seconds"] = wall
        if rc != 0:
            return rc, wall, None, err or f"{tool} failed", 0, False
    rc, wall, mib, out, err = timed(["snappyHexMesh", "-case", case, "-overwrite"], core, args.timeout,
                                    os.path.join(wd, "snappy.log"))
    # the cells its gap refinement selected (gapLevel): "Big gap refinement iteration" blocks
    row["gap_refined_cells"] = sum(int(x) for x in re.findall(
        r"Big gap refinement iteration \d+\s*-+\s*(?:.*\n)*?Selected for refinement : (\d+) cells", out or ""))
    m = re.search(r"Finished meshing in = ([0-9.eE+-]+) s", out or "")
    if m:   # its own meshing time (without the process's start and the surface's reading)
        row["snappy_meshing_seconds"] = float(m.group(1))
    if rc != 0:
        # OpenFOAM prints its fatal errors on stdout
        fatal = [l.strip() for l in (out or "").splitlines() if l.strip()][-6:]
        return rc, wall, mib, err or " ".join(fatal), 0, False
    cm = checkmesh_figures(case, core, args.timeout)
    elements = cm.get("cells", 0)
    row.update({"elements": elements, "vertices": cm.get("points"), "seconds": wall, "checkMesh": cm["checkMesh"],
                "checkMesh_flags": cm["checkMesh_flags"],
                "hex_fraction": (cm.get("hexahedra", 0) / elements) if elements else None,
                "max_non_orthogonality": cm.get("max_non_orthogonality"), "max_skewness": cm.get("max_skewness")})
    if elements:
        row["longest_edge"] = poly_longest_edge(case)
        r = post(["foamToSurface", "-case", case, "-tri", obj], core, args.timeout)
        if r is not None and r.returncode == 0 and os.path.exists(obj):
            row["boundary"] = obj
        else:
            row["message"] = "foamToSurface failed: no boundary measured"
    return rc, wall, mib, err, elements, elements > 0


def run_job(args, name, path, div, core):
    diag = diagonal(path)
    h = diag / div
    wd = os.path.join(args.work, "runs", f"{name}_{div}")
    os.makedirs(wd, exist_ok=True)
    saved = os.path.join(wd, "rows.json")
    kept = []
    if (args.reuse or args.rerun) and os.path.exists(saved):
        rows = [r for r in json.load(open(saved)) if r["mesher"] in args.meshers]
        if args.rerun:   # these meshers again, the others' rows as they were
            kept = [r for r in rows if r["mesher"] not in args.rerun]
        elif {r["mesher"] for r in rows} == set(args.meshers):
            print(f"  {name} /{div}: reused {saved}", flush=True)
            return rows
    rows = []
    for mesher in args.meshers:
        if any(r["mesher"] == mesher for r in kept):
            rows.append(next(r for r in kept if r["mesher"] == mesher))
            continue
        row = {"input": name, "divisions": div, "h": h, "diagonal": diag, "mesher": mesher}
        log = os.path.join(wd, mesher + ".log")
        if mesher in HEX_OPTIONS:
            msh, rep = os.path.join(wd, mesher + ".msh"), os.path.join(wd, mesher + ".json")
            case = os.path.join(wd, mesher + "_case")
            outs = ["-o", msh] + (["-o", case] if shutil.which("checkMesh") else [])
            rc, wall, mib, out, err = timed([args.hexmesh, path] + outs + ["--report", rep, "--force", "-q"] + HEX_OPTIONS[mesher](h),
                                            core, args.timeout, log)
            elements, valid = 0, False
            if rc == 0 and os.path.exists(rep):
                j = json.load(open(rep))
                q = j["quality"]
                elements = j["counts"]["cells"]
                valid = q["inverted_cells"] == 0 and q["scaled_jacobian"]["min"] > 0
                row.update({"elements": elements, "vertices": j["counts"]["vertices"],
                            "seconds": j["seconds"]["total"], "quality_min": q["scaled_jacobian"]["min"],
                            "sj_mean": q["scaled_jacobian"]["mean"], "max_non_orthogonality": q["non_orthogonality"]["max"],
                            "max_skewness": q["skewness"]["max"], "hist": {"scaled_jacobian": q["histograms"]["scaled_jacobian"]}})
                # the boundary captures it ran (the retries' log) and their seconds together
                caps = j.get("boundary", {}).get("captures", [])
                row["captures"] = len(caps)
                row["capture_seconds"] = sum(c["seconds"] for c in caps)
                obj = os.path.join(wd, mesher + "_boundary.obj")
                try:
                    _, _, longest = hex_boundary_and_edges(msh, obj)
                    row["longest_edge"] = longest
                    row["boundary"] = obj
                except Exception as e:
                    row["message"] = f"reading the MSH back failed: {e!r}"[:200]
                if os.path.isdir(case):
                    cm = checkmesh_figures(case, core, args.timeout)
                    row["checkMesh"], row["checkMesh_flags"] = cm["checkMesh"], cm["checkMesh_flags"]
        elif mesher == "snappy":
            try:
                rc, wall, mib, err, elements, valid = run_snappy(args, path, h, wd, core, row)
            except Exception as e:   # the suite's failure (parsing, memory): this row only
                rc, wall, mib, err, elements, valid = "not run", None, None, "", 0, False
                row["message"] = f"suite: {e!r}"[:200]
        else:
            off = os.path.join(wd, mesher + "_boundary.off")
            msh = os.path.join(wd, mesher + ".msh")
            # checkMesh on the tetrahedra at the coarsest h only (--check-tets): at the finest, the
            # conversion and the check of up to a few million tetrahedra would double the suite's time
            check = (shutil.which("checkMesh") is not None and shutil.which("gmshToFoam") is not None
                     and (args.check_tets == "all" or (args.check_tets == "coarsest" and div == min(args.division_list))))
            rc, wall, mib, out, err = timed([args.tet_baselines, mesher, path, repr(h), "--boundary", off]
                                            + (["--msh", msh] if check else []), core, args.timeout, log)
            elements, valid = 0, False
            try:
                j = json.loads(out.strip().splitlines()[-1]) if out.strip() else {}
            except json.JSONDecodeError:
                j = {}
            if j.get("status") == "ok":
                elements = j["elements"]
                valid = j["inverted"] == 0
                row.update({"elements": elements, "vertices": j["vertices"], "seconds": j["seconds"],
                            "quality_min": j["dihedral"]["min"], "max_dihedral": j["dihedral"]["max"],
                            "max_radius_edge": j["radius_edge"]["max"], "mean_radius_edge": j["radius_edge"]["mean"],
                            "longest_edge": j["longest_edge"], "remeshing_seconds": j.get("remeshing_seconds"),
                            "remeshed_triangles": j.get("remeshed_triangles"),
                            "hist": {"dihedral": {k: j["dihedral"][k] for k in ("lo", "hi", "counts")},
                                     "radius_edge": {k: j["radius_edge"][k] for k in ("lo", "hi", "counts")}}})
                if elements:
                    row["boundary"] = off
                if elements and check and os.path.exists(msh):
                    # the same judge as for the hexahedra: OpenFOAM's own conversion, then checkMesh
                    case = os.path.join(wd, mesher + "_case")
                    shutil.rmtree(case, ignore_errors=True)
                    foam_case(case, {}, binary=True)
                    t_check = datetime.datetime.now()
                    g = post(["gmshToFoam", "-case", case, msh], core, args.timeout)
                    if g is not None and g.returncode == 0:
                        cm = checkmesh_figures(case, core, args.timeout)
                        row.update({"checkMesh": cm["checkMesh"], "checkMesh_flags": cm["checkMesh_flags"],
                                    "max_non_orthogonality": cm.get("max_non_orthogonality"),
                                    "max_skewness": cm.get("max_skewness")})
                    else:
                        row["conversion"] = "gmshToFoam failed" if g is not None else "gmshToFoam timed out"
                    row["check_seconds"] = (datetime.datetime.now() - t_check).total_seconds()
                    shutil.rmtree(case, ignore_errors=True)
                    os.remove(msh)
            elif j.get("message"):
                row["message"] = j["message"]
        row.update({"exit": rc if rc != "not run" else None, "wall_seconds": wall, "peak_MiB": mib})
        row["outcome"] = classify(rc, err, elements, valid)
        if rc not in (0, None, "not run") and "message" not in row:
            row["message"] = (err.strip().splitlines() or [""])[-1][:200]
        if row.get("boundary"):
            d = distance(args.surface_distance, row["boundary"], path)
            if d:
                row.update({"mesh_to_input_mean": d["a_to_b"]["mean"], "mesh_to_input_max": d["a_to_b"]["max"],
                            "input_to_mesh_mean": d["b_to_a"]["mean"], "input_to_mesh_max": d["b_to_a"]["max"]})
                row["fidelity"] = max(d["a_to_b"]["mean"], d["b_to_a"]["mean"])
        print(f"  {name} /{div} {mesher:16s} {row['outcome']:14s} elements {row.get('elements', 0):>9} "
              f"seconds {row.get('seconds') or 0:8.2f} peak {mib or 0:7.0f} MiB"
              + (f" fidelity {row['fidelity'] / h:.3f} h" if "fidelity" in row else ""), flush=True)
        rows.append(row)
    json.dump(rows, open(saved, "w"), indent=1)
    return rows


CSV_FIELDS = ["input", "divisions", "h", "mesher", "outcome", "exit", "elements", "vertices", "seconds", "wall_seconds",
              "peak_MiB", "longest_edge", "quality_min", "sj_mean", "max_non_orthogonality", "max_skewness", "max_dihedral",
              "max_radius_edge", "mean_radius_edge", "mesh_to_input_mean", "mesh_to_input_max", "input_to_mesh_mean",
              "input_to_mesh_max", "fidelity", "checkMesh", "checkMesh_flags", "check_seconds", "hex_fraction", "blockMesh_seconds",
              "surfaceFeatureExtract_seconds", "snappy_meshing_seconds", "gap_refined_cells", "location_in_mesh", "remeshing_seconds", "remeshed_triangles",
              "captures", "capture_seconds", "message"]


def robustness_of(rows):
    """input -> mesher -> the worst outcome over the resolutions"""
    order = ["not run", "valid mesh", "clear error", "timeout", "silent failure", "crash"]
    robustness = {}
    for r in rows:
        per = robustness.setdefault(r["input"], {})
        if r["mesher"] not in per or order.index(r["outcome"]) > order.index(per[r["mesher"]]):
            per[r["mesher"]] = r["outcome"]
    return robustness


def at_fidelity(rows, mesher, name, f):
    """elements of `mesher` on `name` at fidelity f: log-log interpolation (or extrapolation, flagged)
    through its runs"""
    pts = sorted((r["fidelity"], r["elements"]) for r in rows
                 if r["input"] == name and r["mesher"] == mesher and r["outcome"] == "valid mesh" and r.get("fidelity"))
    pts = [p for p in pts if p[0] > 0]
    if len(pts) < 2:
        return None, None
    (f0, n0), (f1, n1) = pts[0], pts[-1]
    # a better fidelity must cost more elements, or the line says nothing
    if f0 == f1 or n0 <= n1:
        return None, None
    t = (math.log(f) - math.log(f0)) / (math.log(f1) - math.log(f0))
    if not -1 <= t <= 2:   # at most one span beyond the runs' range
        return None, None
    return math.exp(math.log(n0) + t * (math.log(n1) - math.log(n0))), not (0 <= t <= 1)


def summarise(rows, divisions):
    """per input at the finest h: element ratios at matched h and at the hex mesh's fidelity, times"""
    fine = max(divisions)
    names = sorted({r["input"] for r in rows})
    out = []
    for n in names:
        by = {r["mesher"]: r for r in rows if r["input"] == n and r["divisions"] == fine}
        s = {"input": n, "divisions": fine}
        for m in MESHERS:
            r = by.get(m)
            s[m] = r["elements"] if r and r["outcome"] == "valid mesh" else r["outcome"] if r else "-"
        for hv, tag in (("hexmesh", "hex"), ("hexmesh-adaptive", "adaptive")):
            hx = by.get(hv)
            if not (hx and hx["outcome"] == "valid mesh"):
                continue
            if "fidelity" in hx:
                s[f"{tag} fidelity / h"] = hx["fidelity"] / hx["h"]
            if hx.get("captures") is not None:
                s[f"{tag} captures"] = hx["captures"]
            for m in ("mesh3", "tetgen-remeshed", "tetgen", "snappy"):
                r = by.get(m)
                if r and r["outcome"] == "valid mesh":
                    s[f"{m}/{tag} at h"] = r["elements"] / hx["elements"]
                    s[f"{tag} seconds / {m}"] = hx["seconds"] / max(r["seconds"] or 0, 1e-9)
                if hx.get("fidelity"):
                    n_eq, extrapolated = at_fidelity(rows, m, n, hx["fidelity"])
                    if n_eq:
                        s[f"{m}/{tag} at fidelity"] = n_eq / hx["elements"]
                        s[f"{m}/{tag} at fidelity extrapolated"] = extrapolated
        sn = by.get("snappy")
        if sn and sn["outcome"] == "valid mesh" and "fidelity" in sn:
            s["snappy fidelity / h"] = sn["fidelity"] / sn["h"]
        out.append(s)
    return out


def plots(rows, work):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colours = {"hexmesh": "tab:red", "hexmesh-adaptive": "tab:orange", "tetgen": "tab:blue", "tetgen-remeshed": "tab:cyan",
               "mesh3": "tab:green", "snappy": "tab:purple"}
    ok = [r for r in rows if r["outcome"] == "valid mesh"]
    # elements versus h (relative to the diagonal), one line per input and mesher
    fig, ax = plt.subplots(figsize=(7, 5))
    for m in MESHERS:
        for n in sorted({r["input"] for r in ok}):
            pts = sorted((1 / r["divisions"], r["elements"]) for r in ok if r["mesher"] == m and r["input"] == n)
            if pts:
                ax.plot(*zip(*pts), "o-", color=colours[m], alpha=0.5, lw=1, label=m if n == sorted({r["input"] for r in ok if r["mesher"] == m})[0] else None)
    ax.set_xscale("log"); ax.set_yscale("log")
    ax.set_xlabel("h / bounding-box diagonal"); ax.set_ylabel("elements"); ax.legend(); ax.grid(True, which="both", alpha=0.3)
    ax.set_title("elements versus h (each line: one input)")
    fig.tight_layout(); fig.savefig(os.path.join(work, "elements_vs_h.png"), dpi=90); plt.close(fig)
    # time versus elements
    fig, ax = plt.subplots(figsize=(7, 5))
    for m in MESHERS:
        pts = [(r["elements"], r["seconds"]) for r in ok if r["mesher"] == m and r.get("seconds")]
        if pts:
            ax.scatter(*zip(*pts), color=colours[m], label=m, s=18)
    ax.set_xscale("log"); ax.set_yscale("log")
    ax.set_xlabel("elements"); ax.set_ylabel("meshing seconds (one core)"); ax.legend(); ax.grid(True, which="both", alpha=0.3)
    ax.set_title("time versus elements")
    fig.tight_layout(); fig.savefig(os.path.join(work, "time_vs_elements.png"), dpi=90); plt.close(fig)
    # quality histograms summed over the inputs at each mesher's runs
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    def summed(m, key):
        tot = None
        for r in ok:
            if r["mesher"] == m and key in r.get("hist", {}):
                c = r["hist"][key]["counts"]
                tot = list(c) if tot is None else [a + b for a, b in zip(tot, c)]
                lo, hi = r["hist"][key]["lo"], r["hist"][key]["hi"]
        return (tot, lo, hi) if tot else (None, 0, 1)
    for hv in ("hexmesh", "hexmesh-adaptive"):
        tot, lo, hi = summed(hv, "scaled_jacobian")
        if tot:
            w = (hi - lo) / len(tot)
            s = sum(tot)
            axes[0].step([lo + (i + 0.5) * w for i in range(len(tot))], [c / s for c in tot], where="mid", color=colours[hv], label=hv)
    axes[0].set_title("hexahedra: scaled Jacobian"); axes[0].set_xlabel("scaled Jacobian"); axes[0].set_ylabel("fraction of cells")
    axes[0].set_yscale("log"); axes[0].legend()
    for k, (key, label) in enumerate((("dihedral", "dihedral angle (degrees)"), ("radius_edge", "radius-edge ratio"))):
        ax = axes[k + 1]
        for m in ("tetgen", "tetgen-remeshed", "mesh3"):
            tot, lo, hi = summed(m, key)
            if not tot:
                continue
            w = (hi - lo) / len(tot)
            s = sum(tot)
            ax.step([lo + (i + 0.5) * w for i in range(len(tot))], [c / s for c in tot], where="mid", color=colours[m], label=m)
        ax.set_title(f"tetrahedra: {label}"); ax.set_xlabel(label); ax.legend()
    fig.tight_layout(); fig.savefig(os.path.join(work, "quality_histograms.png"), dpi=90); plt.close(fig)


def fmt(x, nd=2):
    if isinstance(x, float):
        return f"{x:.{nd}f}"
    return str(x)


def tables(rows, summary, robustness, meta):
    """markdown-ish text tables for the manual page and the README"""
    head = ["input", "hexmesh", "hexmesh-adaptive", "snappy", "mesh3", "tetgen-remeshed", "tetgen", "mesh3/hex at h",
            "tetgen-remeshed/hex at h", "hex fidelity / h", "adaptive fidelity / h", "snappy fidelity / h",
            "mesh3/adaptive at fidelity", "tetgen-remeshed/adaptive at fidelity", "hex s / tetgen-remeshed s",
            "adaptive s / snappy s", "captures (hex, adaptive)"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for s in summary:
        def ratio(k):
            v = s.get(k)
            if v is None:
                return "-"
            return fmt(v, 1) + ("*" if s.get(k + " extrapolated") else "")
        lines.append("| " + " | ".join([s["input"], fmt(s["hexmesh"]), fmt(s["hexmesh-adaptive"]), fmt(s["snappy"]),
                                         fmt(s["mesh3"]), fmt(s["tetgen-remeshed"]), fmt(s["tetgen"]), ratio("mesh3/hex at h"),
                                         ratio("tetgen-remeshed/hex at h"), fmt(s.get("hex fidelity / h", "-"), 3),
                                         fmt(s.get("adaptive fidelity / h", "-"), 3), fmt(s.get("snappy fidelity / h", "-"), 3),
                                         ratio("mesh3/adaptive at fidelity"), ratio("tetgen-remeshed/adaptive at fidelity"),
                                         fmt(s.get("hex seconds / tetgen-remeshed", "-"), 2),
                                         fmt(s.get("adaptive seconds / snappy", "-"), 2),
                                         f"{s.get('hex captures', '-')}, {s.get('adaptive captures', '-')}"]) + " |")
    rob_head = ["input"] + MESHERS
    rob = ["| " + " | ".join(rob_head) + " |", "|" + "---|" * len(rob_head)]
    for n, per in robustness.items():
        rob.append("| " + " | ".join([n] + [per.get(m, "-") for m in MESHERS]) + " |")
    return "\n".join(lines), "\n".join(rob)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--hexmesh", default=os.path.join(BUILD, "tools", "hexmesh", "hexmesh"))
    ap.add_argument("--tet-baselines", default=os.path.join(BUILD, "benchmark", "Hex_meshing_3", "tet_baselines"))
    ap.add_argument("--surface-distance", default=os.path.join(BUILD, "benchmark", "Hex_meshing_3", "surface_distance"))
    ap.add_argument("--work", default=os.path.join(ROOT, "out", "benchmarks"))
    ap.add_argument("--divisions", default="40,80")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--meshers", default=",".join(MESHERS))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--check-tets", choices=["coarsest", "all", "none"], default="coarsest",
                    help="where the tetrahedral meshes go through gmshToFoam and checkMesh (default: at the coarsest h)")
    ap.add_argument("--timeout", type=float, default=150)
    ap.add_argument("--publish", action="store_true", help="write the manual's Benchmarks page and the README's table")
    ap.add_argument("--reuse", action="store_true", help="reuse the runs already in --work (to redo the tables and plots)")
    ap.add_argument("--rerun", default="", help="MESHER,...: run these again, reusing the other meshers' runs in --work")
    args = ap.parse_args()
    args.meshers = [m for m in args.meshers.split(",") if m]
    args.rerun = [m for m in args.rerun.split(",") if m]
    if "snappy" in args.meshers and not all(shutil.which(t) for t in ("blockMesh", "surfaceFeatureExtract", "snappyHexMesh",
                                                                       "checkMesh", "foamToSurface")):
        print("suite: OpenFOAM is not installed; snappyHexMesh left out", flush=True)
        args.meshers.remove("snappy")
    divisions = [int(x) for x in args.divisions.split(",")]
    args.division_list = divisions
    for tool in (args.hexmesh, args.tet_baselines, args.surface_distance):
        if not os.path.exists(tool):
            sys.exit(f"suite: {tool} is missing (scripts/build.sh; cmake --build build --target tet_baselines surface_distance)")
    os.makedirs(args.work, exist_ok=True)
    files = inputs()
    if args.only:
        files = {n: p for n, p in files.items() if n in args.only}
    jobs = [(n, p, d) for d in sorted(divisions) for n, p in files.items()]
    t0 = datetime.datetime.now()
    commit = source_commit()   # what the meshers were built from, before they run
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        free = list(range(args.jobs))
        futures = {}
        pending = list(jobs)
        while pending or futures:
            while pending and free:
                core = free.pop(0)
                n, p, d = pending.pop(0)
                futures[ex.submit(run_job, args, n, p, d, core if args.jobs > 1 else None)] = core
            done, _ = concurrent.futures.wait(futures, return_when=concurrent.futures.FIRST_COMPLETED)
            for f in done:
                free.append(futures.pop(f))
                try:
                    rows += f.result()
                except Exception as e:   # a broken measurement is a result, not the end of the suite
                    print(f"  suite: a job failed: {e!r}", flush=True)
    rows.sort(key=lambda r: (r["input"], r["divisions"], MESHERS.index(r["mesher"])))
    for r in rows:
        if r["outcome"] != "valid mesh":
            continue
        # an OpenFOAM mesh (ours, snappyHexMesh's) that checkMesh rejects is not a valid mesh (the
        # tetrahedral meshes' verdicts are informational: their meshers do not claim OpenFOAM)
        if (r["mesher"] in HEX_OPTIONS or r["mesher"] == "snappy") and r.get("checkMesh") not in (None, "Mesh OK"):
            r["outcome"] = "silent failure"
            r["message"] = f"checkMesh: {r['checkMesh']}"
        # nor, for any mesher, one whose boundary goes farther than 4h from the input: a mesh that
        # leaked out through a hole (snappyHexMesh then meshes its background box, at 4h from the input)
        elif r.get("mesh_to_input_max") is not None and r["mesh_to_input_max"] > LEAK * r["h"]:
            r["outcome"] = "silent failure"
            r["message"] = f"the boundary goes {r['mesh_to_input_max'] / r['h']:.1f} h away from the input (a leak)"
    elapsed = (datetime.datetime.now() - t0).total_seconds()
    meta = {"date": t0.strftime("%Y-%m-%d"), "commit": commit, "machine": platform.node(), "cpu": cpu_model(),
            "dirty": sorted(dirty_inputs()),
            "cores": os.cpu_count(), "jobs": args.jobs, "divisions": divisions, "suite_seconds": elapsed,
            "inputs": {n: os.path.relpath(p, ROOT) for n, p in files.items()}}
    # the date and duration of the run that made the rows: a --reuse pass keeps those of the last
    # pass that ran them all (run.json)
    run_file = os.path.join(args.work, "run.json")
    if (args.reuse or args.rerun) and os.path.exists(run_file):
        rerun = (f"{', '.join(args.rerun)} run again on {meta['date']} (commit {commit}) in {elapsed:.0f} s"
                 if args.rerun else None)
        meta.update(json.load(open(run_file)))
        meta["reused"] = True
        if rerun:
            meta["rerun"] = ((meta.get("rerun") + "; ") if meta.get("rerun") else "") + rerun
            json.dump({k: meta[k] for k in ("date", "commit", "machine", "cpu", "cores", "jobs", "suite_seconds", "rerun") if k in meta},
                      open(run_file, "w"))
    elif not args.reuse:
        json.dump({k: meta[k] for k in ("date", "commit", "machine", "cpu", "cores", "jobs", "suite_seconds")},
                  open(run_file, "w"))
    with open(os.path.join(args.work, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=CSV_FIELDS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)
    robustness = robustness_of(rows)
    with open(os.path.join(args.work, "robustness.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["input"] + MESHERS)
        for n, per in robustness.items():
            w.writerow([n] + [per.get(m, "-") for m in MESHERS])
    summary = summarise(rows, divisions)
    json.dump({"meta": meta, "runs": rows, "summary": summary, "robustness": robustness},
              open(os.path.join(args.work, "results.json"), "w"), indent=1)
    # the tables first: a missing plotting library costs the plots, not the run's results
    t_main, t_rob = tables(rows, summary, robustness, meta)
    print()
    print(t_main)
    print()
    print(t_rob)
    print(f"\nsuite: {len(rows)} runs in {elapsed:.0f} s ({args.jobs} jobs); results in {args.work}")
    try:
        import matplotlib  # noqa: F401  (Debian's python3-matplotlib, for /usr/bin/python3)
    except ImportError:
        print("suite: no plots: matplotlib is missing (apt-get install python3-matplotlib; then --reuse "
              "redoes the tables and plots from these runs)", file=sys.stderr)
        if args.publish:
            sys.exit("suite: --publish needs the plots: nothing published")
        return
    plots(rows, args.work)
    if args.publish:
        publish(args, rows, summary, t_main, t_rob, meta)


def publish(args, rows, summary, t_main, t_rob, meta):
    fig = os.path.join(ROOT, "doc", "Hex_meshing_3", "fig")
    os.makedirs(fig, exist_ok=True)
    for p in ("elements_vs_h.png", "time_vs_elements.png", "quality_histograms.png"):
        shutil.copy(os.path.join(args.work, p), os.path.join(fig, "benchmark_" + p))
    fine = max(meta["divisions"])
    clean = [s for s in summary if s["input"] not in meta["dirty"]]
    lines = []
    for key, what, goal, sense in (
            ("mesh3/hex at h", "Mesh_3 tetrahedra per hexahedron at matched h", 8, ">="),
            ("tetgen-remeshed/hex at h", "TetGen (surface remeshed to h) tetrahedra per hexahedron at matched h", 5, ">="),
            ("mesh3/adaptive at fidelity", "Mesh_3 tetrahedra per hexahedron of hexmesh-adaptive at its boundary fidelity", 4, ">="),
            ("tetgen-remeshed/adaptive at fidelity", "TetGen (remeshed) tetrahedra per hexahedron of hexmesh-adaptive at its fidelity", 4, ">="),
            ("hex seconds / tetgen-remeshed", "hexmesh seconds over TetGen's (remeshed) at matched h", 1, "<="),
            ("snappy/adaptive at h", "snappyHexMesh cells per hexmesh-adaptive cell at matching settings", None, None),
            ("snappy/adaptive at fidelity", "snappyHexMesh cells per hexmesh-adaptive cell at hexmesh-adaptive's fidelity", None, None),
            ("adaptive seconds / snappy", "hexmesh-adaptive seconds over snappyHexMesh's (process wall) at matching settings", None, None)):
        # matched h: only where the uniform hex mesh keeps the shape (fidelity <= h/2); at
        # fidelity: interpolated values only (extrapolations are in the table, marked *)
        if goal is None and not any(r["mesher"] == "snappy" for r in rows):
            continue
        if goal is None:
            # both meshes keep the shape (fidelity within h/2: not where snappyHexMesh lost the
            # rotor's blades or either lost fin_slot's slot)
            keeps = lambda s, k: s.get(k) is not None and s[k] <= 0.5
            pool = [s for s in clean if not s.get(key + " extrapolated")
                    and keeps(s, "snappy fidelity / h") and keeps(s, "adaptive fidelity / h")]
            scope = "clean inputs where both keep the shape (fidelity within h/2)" + (", interpolated" if "fidelity" in key else "")
        elif key.endswith("at h") or key.startswith("hex seconds"):
            pool = [s for s in clean if s.get("hex fidelity / h") is not None and s["hex fidelity / h"] <= 0.5]
            scope = "clean inputs where hexmesh's fidelity is within h/2"
        else:
            pool = [s for s in clean if not s.get(key + " extrapolated")]
            scope = "clean inputs with an interpolated value"
        v = [s[key] for s in pool if s.get(key) is not None]
        if not v:
            lines.append(f"- {what}: no {scope}")
            continue
        if goal is None:
            lines.append(f"- {what}: {min(v):.2f} to {max(v):.2f} (median {statistics.median(v):.2f}) on {len(v)} {scope}")
            continue
        met = sum(1 for x in v if (x >= goal if sense == ">=" else x <= goal))
        lines.append(f"- {what}: {min(v):.1f} to {max(v):.1f}; {sense} {goal} on {met} of {len(v)} {scope}")
    fids = [(s["input"], s["adaptive fidelity / h"]) for s in clean if s.get("adaptive fidelity / h") is not None]
    if fids:
        lines.append("- hexmesh-adaptive boundary fidelity (larger mean distance, in h): " +
                     ", ".join(f"{n} {f:.3f}" for n, f in fids))
    gap = [r["gap_refined_cells"] for r in rows if r["mesher"] == "snappy" and r.get("gap_refined_cells") is not None]
    if gap:
        lines.append(f"- snappyHexMesh's gap refinement (gapLevel (5 2 4)) selected {sum(gap)} cells over its {len(gap)} runs")
    for m in MESHERS:
        verdicts = [r["checkMesh"] for r in rows if r["mesher"] == m and r.get("checkMesh")]
        failed = sum(1 for r in rows if r["mesher"] == m and r.get("conversion"))
        if verdicts or failed:
            where = "at the coarsest h (after gmshToFoam)" if m in ("tetgen", "tetgen-remeshed", "mesh3") else "at every h"
            lines.append(f"- checkMesh -allTopology, {m}, {where}: Mesh OK on {verdicts.count('Mesh OK')} of {len(verdicts)} meshes checked"
                         + (f" ({failed} not converted)" if failed else ""))
    for m in MESHERS:
        outs = [per.get(m, "-") for n, per in robustness_of(rows).items() if n in meta["dirty"]]
        if outs:
            counts = {o: outs.count(o) for o in sorted(set(outs))}
            lines.append(f"- dirty inputs ({len(outs)}), {m}: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
    text = f"""/*!
\\page hexmesh_benchmarks Benchmarks: tetrahedra versus hexahedra
\\anchor Chapter_Hex_meshing_3_Benchmarks

This page is written by `benchmark/Hex_meshing_3/suite.py --publish`; every number comes from the
run of {meta['date']} (commit {meta.get('commit', 'unknown')}) on {meta['machine']} ({meta['cpu']}, {meta['cores']} cores, {meta['jobs']} jobs at a
time, each pinned to one core; the whole suite took {meta['suite_seconds']:.0f} s{'; ' + meta['rerun'] if meta.get('rerun') else ''}).
Rerun it to refresh the page. Dirty inputs (the test data's MANIFEST): {', '.join(meta['dirty'])}.

\\section hexmesh_bench_setup What is compared
Every surface of the test data, at h = bounding-box diagonal / D for D in {meta['divisions']}:
- `hexmesh --size h --surface-size h` (hexahedra of edge h, hanging nodes allowed), and
  `hexmesh-adaptive`: `--size 4h --surface-size h --thin-cells 5 --soft-crease-angle 20` (coarser
  inside, thin parts and gaps refined until 5 cells span them, down to h/4; the creases of faceted
  blends from 20 degrees followed where they stand out), what a user would ask for: the body-fitted
  boundary needs about five grid cells across a part (a cut cell and the buffer gap on each side,
  one uncut cell between; with 3, thin parts such as bunny's ears keep voids in the mesh). The soft
  creases change fandisk's fidelity (0.0044 h -> 0.0036 h with the same cells: Mesh_3 at that
  fidelity 3.7 -> 5.8 times the cells), fandisk_crack's, t20_part's (0.0029 h -> 0.0031 h, worse)
  and teapot's, no other (their creases of 20 to 30 degrees do not stand out);
- TetGen 1.5 `-pq1.2/15 -a(h^3/(6 sqrt 2))` on the input's own triangles (`tetgen`) and on the
  surface remeshed first to edge length h by CGAL's isotropic remeshing (`tetgen-remeshed`);
- CGAL Mesh_3: edge size h, facet size h/sqrt(3), cell size h sqrt(6)/4, facet distance h/10,
  sharp edges protected;
- snappyHexMesh (OpenFOAM v1912, `snappy`) at settings matching `hexmesh-adaptive`, from
  dictionaries the suite generates from h: background cells of 4h over the bounding box grown by
  4h, the surface and its feature edges (surfaceFeatureExtract, included angle 150 degrees) at
  level 2 (h), gap refinement asked for gaps and thin parts narrower than 5 cells up to level 4
  (h/4: `gapLevel (5 2 4)`, `gapMode mixed`, for `--thin-cells 5`; the headline says how many
  cells it selected), resolveFeatureAngle 30, nCellsBetweenLevels 1,
  explicit feature snapping, no layers, the tutorials' mesh-quality controls; locationInMesh is a
  point inside the input (winding number above 1/2 in absolute value, farthest from the surface of
  a 12^3 lattice), so it meshes the one region holding it. Its seconds are the snappyHexMesh
  process's wall time (its own "Finished meshing in" is in results.csv, a few tenths of a second
  less); blockMesh and surfaceFeatureExtract are recorded apart. Its cells are polyhedra where it
  splits hexahedra (hex_fraction in results.csv). A run the suite could not set up (no inside
  point found) is "not run", not snappy's failure.
Boundary fidelity is measured the same way for all: the two-sided distance between the mesh's
boundary and the input (`surface_distance`, 10,000 area-uniform samples plus every vertex each
way); "fidelity" is the larger of the two mean distances. "At fidelity" compares element counts
at the hex mesh's fidelity, interpolating each tetrahedral mesher's count log-log through its runs
(* marks an extrapolation, at most one span beyond the runs; no value where a mesher's finer run
did not improve its fidelity). The headline's matched-h ratios leave out the inputs where the
uniform hex mesh loses parts of the shape (fidelity beyond h/2: thin parts below the cell size,
which `hexmesh-adaptive` refines), and its at-fidelity ratios the extrapolated values. Seconds are
meshing seconds. They are not quite alike: hexmesh's are from reading to writing, including its
quality measures and two outputs (MSH and, with OpenFOAM, a case); the baselines' are their
meshing call only, without reading, measuring, writing or (for `tetgen-remeshed`) the remeshing.
hexmesh's time depends most on how many boundary captures its retries ran (the last column, at the
finest h: 1 where the first capture left no cell below a scaled Jacobian of 0.3, no OpenFOAM fault
and no boundary face beyond h/4; at most 18, six a staircase; `captures` and `capture_seconds` in results.csv, the
report's `boundary.captures`). Peak memory is the process's, from `/usr/bin/time`. OpenFOAM's `checkMesh -allTopology` judges
every mesh that can be exported to OpenFOAM: hexmesh's cases, snappyHexMesh's, and the tetrahedral
meshes converted by `gmshToFoam` (at the coarsest h only: converting and checking millions of
tetrahedra at the finest would double the suite's time; `--check-tets all` does it everywhere).
A hexmesh or snappyHexMesh mesh that checkMesh rejects counts as a silent failure (the
tetrahedral meshers do not claim OpenFOAM meshes: their verdicts are informational), and so does,
for every mesher, a mesh whose boundary goes farther than 4h from the input anywhere (a leak
through a hole: then snappyHexMesh meshes its background box). The rule is one-sided: a mesh that
leaves parts of the input out (snappyHexMesh meshing only the region of its locationInMesh, thin
parts lost below the cell size) stays valid, and its fidelity shows the loss. The snappyHexMesh
ratios of the headline count only the inputs where both it and hexmesh-adaptive keep the shape
(fidelity within h/2).

\\section hexmesh_bench_headline Headline (h = diagonal / {fine})
{chr(10).join(lines)}

\\section hexmesh_bench_table Elements, ratios and times at h = diagonal / {fine}
{t_main}

\\section hexmesh_bench_robust Robustness (worst outcome over the resolutions)
{t_rob}

\\section hexmesh_bench_figures Figures
\\image html benchmark_elements_vs_h.png
\\image html benchmark_time_vs_elements.png
\\image html benchmark_quality_histograms.png

The full results (every run, with quality figures and histograms) are in the run's results.csv
and results.json.
*/
"""
    open(os.path.join(ROOT, "doc", "Hex_meshing_3", "Benchmarks.txt"), "w").write(text)
    readme = os.path.join(ROOT, "README.md")
    s = open(readme).read()
    block = (f"<!-- benchmarks: written by benchmark/Hex_meshing_3/suite.py --publish -->\n"
             f"Tetrahedra versus hexahedra, and snappyHexMesh beside them, on the test surfaces, measured {meta['date']} (commit {meta.get('commit', 'unknown')}) on {meta['machine']} "
             f"({meta['cores']} cores{'; ' + meta['rerun'] if meta.get('rerun') else ''}; the manual's Benchmarks page has "
             f"the whole table, robustness and figures):\n\n"
             + "\n".join(lines) + "\n<!-- /benchmarks -->")
    if "<!-- benchmarks" in s:
        s = re.sub(r"<!-- benchmarks.*?<!-- /benchmarks -->", lambda m: block, s, flags=re.S)
    else:
        s = s.rstrip("\n") + "\n\n## Benchmarks\n" + block + "\n"
    open(readme, "w").write(s)
    print("published: doc/Hex_meshing_3/Benchmarks.txt, doc/Hex_meshing_3/fig/benchmark_*.png, README.md")


if __name__ == "__main__":
    main()
