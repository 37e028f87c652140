#!/usr/bin/python3
"""Where a body-fitted mesh's creases and the input's sharp edges miss each other, and why.

`feature_fidelity()` (the report's `feature_fidelity`) gives the two one-sided distances between
the input's sharp edges and the mesh boundary's creases and the one point where each is reached.
This script lists all the edges beyond a threshold (a quarter of the surface size by default),
both ways, and sorts the mesh's far creases by a cause:

- straddle: the crease is an edge of a boundary face that straddles an input sharp edge along
  its diagonal: two opposite corners of the face lie on the input's sharp edges and the corners
  between them, on both sides, do not. This is where a feature chain turns inside a face
  (the manual's "Chains that turn inside a face"): the face cannot fold along its diagonal, so the
  input's crease is shared between the face's edges on either side, half a cell off.
- other: a crease of the mesh with no such face (a curved part whose faces meet at the angle or
  more - a blend too coarse for its cells - a fold where a chain runs a row of faces off its
  curve, a curve missed).

Input: an OpenFOAM case written by hexmesh (-o DIR; the polygons with their hanging nodes) and the
input surface (OFF, or OBJ optionally .gz), exact duplicate input vertices merged. Mesh creases:
edges of the boundary polygons (box patches xmin..zmax left out) between two faces whose (Newell)
normals differ by at least --angle degrees, or on one or more than two faces. Input sharp edges:
edges between two triangles at --angle or more, open or non-manifold edges. Unlike the report,
the input's sharp edges are all those of the triangulation (the mesher leaves out curves that a
coarse triangulation creases by accident, `--feature-contrast`, `--feature-scale`, and curves
shorter than two cells), so the figures can be larger than the report's where it left some out.
Distances: 5 points per edge against the other set's segments (exact point-segment distances).

Usage: benchmark/Hex_meshing_3/feature_creases.py CASE INPUT --surface-size S [--angle 30]
                                                  [--beyond 0.25] [--list 20] [--json OUT]
e.g. anchor at the test's sizes (hexmesh anchor.off -o a_case --thin-cells 5 --feature-size 0.0125):
411 mesh creases beyond s/4, 401 of them straddling (worst 0.69 s), 4 input edges beyond s/4
(worst 0.32 s). Needs python3-numpy (Debian). Brute force: meant for the test surfaces' sizes.
"""
import argparse
import collections
import json
import re
import sys

import numpy as np

import far_by_feature  # (its surface reader)

BOX = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"}


def foam_list(path):
    t = open(path).read()
    t = re.sub(r"/\*.*?\*/", "", t, flags=re.S)
    t = re.sub(r"FoamFile\s*\{.*?\}", "", t, flags=re.S)
    return t[t.index("("):]


def read_case(case):
    """points, faces (lists of point ids) and the ids of the faces on surface patches"""
    pm = case + "/constant/polyMesh/"
    P = np.array([[float(x) for x in m.split()] for m in re.findall(r"\(([^()]*)\)", foam_list(pm + "points"))])
    F = [[int(x) for x in m.split()] for m in re.findall(r"\d+\(([^()]*)\)", foam_list(pm + "faces"))]
    bt = re.sub(r"FoamFile\s*\{.*?\}", "", open(pm + "boundary").read(), flags=re.S)
    surf = []
    for name, body in re.findall(r"(\w+)\s*\{([^}]*)\}", bt):
        n = int(re.search(r"nFaces\s+(\d+)", body).group(1))
        start = int(re.search(r"startFace\s+(\d+)", body).group(1))
        if name not in BOX:
            surf += range(start, start + n)
    return P, F, surf


def seg_dist(points, A, B, chunk=2048):
    """distance from each point to the nearest segment AB"""
    out = np.full(len(points), np.inf)
    if len(A) == 0:
        return out
    d = B - A
    l2 = (d * d).sum(1)
    l2 = np.where(l2 > 0, l2, 1.0)
    for i in range(0, len(points), chunk):
        p = points[i:i + chunk][:, None, :]
        t = np.clip(((p - A) * d).sum(2) / l2, 0, 1)
        q = A + t[:, :, None] * d
        out[i:i + chunk] = np.sqrt(((q - p) ** 2).sum(2)).min(1)
    return out


def edge_points(A, B, k=5):
    t = np.linspace(0, 1, k)
    return (A[:, None, :] + t[None, :, None] * (B - A)[:, None, :]).reshape(-1, 3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("case")
    ap.add_argument("input")
    ap.add_argument("--surface-size", type=float, required=True)
    ap.add_argument("--angle", type=float, default=30.0)
    ap.add_argument("--beyond", type=float, default=0.25, help="in surface sizes")
    ap.add_argument("--list", type=int, default=20, help="the farthest this many of each side")
    ap.add_argument("--json")
    a = ap.parse_args()
    s, cos_max = a.surface_size, np.cos(np.radians(a.angle))

    # input: exact duplicates merged, sharp / open / non-manifold edges
    V, T, _ = far_by_feature.read_surface(a.input)
    V, inv = np.unique(V, axis=0, return_inverse=True)
    T = inv.reshape(-1)[T]
    n = np.cross(V[T[:, 1]] - V[T[:, 0]], V[T[:, 2]] - V[T[:, 0]])
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-300)[:, None]
    tri_of = collections.defaultdict(list)
    for t, tri in enumerate(T):
        for k in range(3):
            u, w = int(tri[k]), int(tri[(k + 1) % 3])
            if u != w:
                tri_of[(min(u, w), max(u, w))].append(t)
    sharp = [e for e, ts in tri_of.items() if len(ts) != 2 or n[ts[0]] @ n[ts[1]] <= cos_max]
    IA = V[[e[0] for e in sharp]].reshape(-1, 3)
    IB = V[[e[1] for e in sharp]].reshape(-1, 3)

    # mesh: creases of the boundary polygons on surface patches
    P, F, surf = read_case(a.case)
    normal = {}
    faces_of = collections.defaultdict(list)
    for f in surf:
        q = P[F[f]]
        normal[f] = np.cross(q, np.roll(q, -1, 0)).sum(0)
        normal[f] /= max(np.linalg.norm(normal[f]), 1e-300)
        for k in range(len(F[f])):
            u, w = F[f][k], F[f][(k + 1) % len(F[f])]
            faces_of[(min(u, w), max(u, w))].append(f)
    creases, angle = [], []
    for e, fs in faces_of.items():
        if len(fs) != 2:
            creases.append((e, fs))
            angle.append(180.0)
            continue
        c = normal[fs[0]] @ normal[fs[1]]
        if c <= cos_max:
            creases.append((e, fs))
            angle.append(float(np.degrees(np.arccos(np.clip(c, -1, 1)))))
    MA = P[[e[0] for e, _ in creases]].reshape(-1, 3)
    MB = P[[e[1] for e, _ in creases]].reshape(-1, 3)

    # distances, per edge the largest of its 5 points
    m2i = seg_dist(edge_points(MA, MB), IA, IB).reshape(-1, 5).max(1) / s if len(MA) else np.zeros(0)
    i2m = seg_dist(edge_points(IA, IB), MA, MB).reshape(-1, 5).max(1) / s if len(IA) else np.zeros(0)

    # causes of the far mesh creases
    tol = 1e-3 * s
    on_cache = {}

    def on_input_edge(v):
        if v not in on_cache:
            on_cache[v] = seg_dist(P[v][None, :], IA, IB)[0] < tol
        return on_cache[v]

    def straddles(f):
        poly = F[f]
        k = len(poly)
        on = [on_input_edge(v) for v in poly]
        for i in range(k):
            for j in range(i + 2, k):
                if not (on[i] and on[j]) or (k - (j - i)) < 2:
                    continue
                if not any(on[x] for x in range(i + 1, j)) and not any(on[x % k] for x in range(j + 1, i + k)):
                    return True
        return False

    far_mesh = []
    for idx in np.nonzero(m2i > a.beyond)[0]:
        e, fs = creases[idx]
        cause = "straddle" if any(straddles(f) for f in fs) else "other"
        mid = (P[e[0]] + P[e[1]]) / 2
        far_mesh.append({"distance": float(m2i[idx]), "angle": angle[idx], "cause": cause, "at": [float(x) for x in mid]})
    far_mesh.sort(key=lambda r: -r["distance"])
    far_input = [{"distance": float(i2m[i]), "at": [float(x) for x in (IA[i] + IB[i]) / 2]}
                 for i in np.nonzero(i2m > a.beyond)[0]]
    far_input.sort(key=lambda r: -r["distance"])
    by_cause = collections.Counter(r["cause"] for r in far_mesh)
    worst = {c: max(r["distance"] for r in far_mesh if r["cause"] == c) for c in by_cause}
    res = {"surface_size": s, "angle": a.angle, "beyond": a.beyond, "input_sharp_edges": len(sharp),
           "mesh_creases": len(creases), "mesh_to_input_max": float(m2i.max()) if len(m2i) else 0.0,
           "input_to_mesh_max": float(i2m.max()) if len(i2m) else 0.0, "far_mesh_creases": len(far_mesh),
           "far_mesh_creases_by_cause": dict(by_cause), "worst_by_cause": worst, "far_input_edges": len(far_input),
           "farthest_mesh_creases": far_mesh[:a.list], "farthest_input_edges": far_input[:a.list]}
    print(f"input sharp edges {len(sharp)}, mesh creases {len(creases)} (at {a.angle:g} degrees)")
    print(f"mesh -> input: max {res['mesh_to_input_max']:.2f} s; {len(far_mesh)} creases beyond {a.beyond:g} s: " +
          ", ".join(f"{c} {by_cause[c]} (worst {worst[c]:.2f} s)" for c in sorted(by_cause)))
    for r in far_mesh[:a.list]:
        print(f"  {r['distance']:.2f} s  {r['cause']:8s} {r['angle']:5.1f} deg  at ({r['at'][0]:.4g}, {r['at'][1]:.4g}, {r['at'][2]:.4g})")
    print(f"input -> mesh: max {res['input_to_mesh_max']:.2f} s; {len(far_input)} sharp edges beyond {a.beyond:g} s")
    for r in far_input[:a.list]:
        print(f"  {r['distance']:.2f} s  at ({r['at'][0]:.4g}, {r['at'][1]:.4g}, {r['at'][2]:.4g})")
    if a.json:
        with open(a.json, "w") as o:
            json.dump(res, o, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
