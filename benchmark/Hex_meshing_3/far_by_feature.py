#!/usr/bin/python3
"""Where a mesh boundary stands off its input: its far samples by the input feature nearest to them.

Reads the input surface (OBJ, optionally .gz, or plain OFF) and the mesh->input samples that
`surface_distance --dump PREFIX` writes (PREFIX_a_to_b.txt: x y z distance per line, the mesh
being the first surface), and sorts the samples farther than --beyond by the kind of the input
feature edge nearest to them within --radius: a convex or a concave sharp edge (dihedral angle of
at least --angle degrees), an open edge (one triangle), a non-manifold edge (more than two, where
surfaces meet), a crease or the border of a zero-thickness sheet given as a part and its reversed
copy (motorBike's NAME and NAME-shadow: every edge of such a sheet has two pairs of triangles on
the same vertices, its border one pair), or none within the radius (a smooth part: a gap
bridged, a face too large for the curvature, a vertex that did not reach the surface). For each
kind it prints the samples and the sum of their distances: with the same input and the same
sampling, the sums of two meshes compare where each stands off.

Convex and concave need outward normals: each part (OBJ group, or the whole OFF) is oriented so
that its signed volume is positive; the convexity of an open part's edges is only as good as its
triangles' orientation. Features are sampled every radius / 4 along their edges, so "within the
radius" is exact to that spacing.

Usage: benchmark/Hex_meshing_3/far_by_feature.py INPUT DUMP_a_to_b.txt --radius R --beyond T
                                                 [--angle 30] [--json OUT]
Needs python3-numpy (Debian).
"""
import argparse
import gzip
import json
import sys

import numpy as np

import suite  # (its OFF reader; the modules of benchmark/Hex_meshing_3 are imported from there)

KINDS = ["convex", "concave", "open", "non_manifold", "sheet_crease", "sheet_border"]


def read_surface(path):
    """vertices (n, 3), triangles (m, 3) and each triangle's part (m,) of an OFF or OBJ (.gz) file"""
    if path.endswith(".off"):
        pts, tris = suite.read_off(path)
        return np.array(pts, float), np.array(tris, int), np.zeros(len(tris), int)
    opener = gzip.open if path.endswith(".gz") else open
    V, T, P, names = [], [], [], {}
    part = 0
    with opener(path, "rt") as f:
        for line in f:
            if line.startswith("v "):
                V.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("g ") or line.startswith("o "):
                w = line.split()
                part = names.setdefault(w[1] if len(w) > 1 else "", len(names))
            elif line.startswith("f "):
                ids = [int(x.split("/")[0]) for x in line.split()[1:]]
                ids = [k - 1 if k > 0 else len(V) + k for k in ids]
                for j in range(1, len(ids) - 1):
                    T.append((ids[0], ids[j], ids[j + 1]))
                    P.append(part)
    return np.array(V, float), np.array(T, int), np.array(P, int)


def feature_samples(V, T, P, angle, spacing):
    """points along the input's feature edges and their kinds (indices into KINDS)"""
    A, B, C = V[T[:, 0]], V[T[:, 1]], V[T[:, 2]]
    vol = np.bincount(P, weights=np.einsum("ij,ij->i", A, np.cross(B, C)))
    T = T.copy()
    flip = vol[P] < 0
    T[flip] = T[flip][:, [0, 2, 1]]
    A, B, C = V[T[:, 0]], V[T[:, 1]], V[T[:, 2]]
    N = np.cross(B - A, C - A)
    N /= np.maximum(np.linalg.norm(N, axis=1), 1e-300)[:, None]
    # half-edges: (smaller end, larger end, triangle, opposite vertex)
    a = np.concatenate([T[:, 0], T[:, 1], T[:, 2]])
    b = np.concatenate([T[:, 1], T[:, 2], T[:, 0]])
    o = np.concatenate([T[:, 2], T[:, 0], T[:, 1]])
    tri = np.tile(np.arange(len(T)), 3)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    order = np.lexsort((hi, lo))
    lo, hi, o, tri = lo[order], hi[order], o[order], tri[order]
    key = lo.astype(np.int64) * (len(V) + 1) + hi
    start = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
    count = np.diff(np.r_[start, len(key)])
    cos_max = np.cos(np.radians(angle))
    ends, kinds = [], []
    one = start[count == 1]
    ends.append(np.stack([lo[one], hi[one]], 1)); kinds.append(np.full(len(one), 2))
    # A zero-thickness sheet is a part and its reversed copy (motorBike's NAME and NAME-shadow):
    # each of its triangles has a twin on the same three vertices. An edge of such a sheet has
    # four triangles, two pairs of twins: a crease of the sheet if the two pairs' planes meet at
    # `angle` or more (else no feature), not a junction of several surfaces; an edge with one pair
    # of twins is the sheet's border.
    S = np.sort(T, axis=1)
    many = start[count > 2]
    nm, crease = [], []
    for s0, c in zip(many, count[count > 2]):
        ts = tri[s0:s0 + c]
        keys = {}
        for t in ts:
            keys.setdefault(tuple(S[t]), []).append(t)
        groups = list(keys.values())
        if len(groups) == 2 and all(len(g) == 2 for g in groups):
            # one triangle of each pair, of the same part (so oriented alike) if there is one
            # (across parts the orientations may differ: then the angle between the planes)
            a, b = next(((a, b) for a in groups[0] for b in groups[1] if P[a] == P[b]), (groups[0][0], groups[1][0]))
            cos_ab = float(np.dot(N[a], N[b]))
            if (cos_ab if P[a] == P[b] else abs(cos_ab)) <= cos_max:
                crease.append(s0)
        else:
            nm.append(s0)
    nm, crease = np.array(nm, int), np.array(crease, int)
    ends.append(np.stack([lo[nm], hi[nm]], 1)); kinds.append(np.full(len(nm), 3))
    ends.append(np.stack([lo[crease], hi[crease]], 1)); kinds.append(np.full(len(crease), 4))
    two = start[count == 2]
    twins = np.all(S[tri[two]] == S[tri[two + 1]], axis=1)
    border = two[twins]
    ends.append(np.stack([lo[border], hi[border]], 1)); kinds.append(np.full(len(border), 5))
    two = two[~twins]
    f0, f1, o1 = tri[two], tri[two + 1], o[two + 1]
    sharp = np.einsum("ij,ij->i", N[f0], N[f1]) <= cos_max
    convex = np.einsum("ij,ij->i", V[o1] - V[lo[two]], N[f0]) < 0
    two, convex = two[sharp], convex[sharp]
    ends.append(np.stack([lo[two], hi[two]], 1)); kinds.append(np.where(convex, 0, 1))
    E, K = np.concatenate(ends), np.concatenate(kinds)
    pts, lab = [], []
    L = np.linalg.norm(V[E[:, 1]] - V[E[:, 0]], axis=1)
    parts = np.maximum(1, np.ceil(L / spacing).astype(int))
    for n in np.unique(parts):
        sel = parts == n
        t = np.linspace(0, 1, n + 1)
        p = V[E[sel, 0]][:, None, :] * (1 - t)[None, :, None] + V[E[sel, 1]][:, None, :] * t[None, :, None]
        pts.append(p.reshape(-1, 3))
        lab.append(np.repeat(K[sel], n + 1))
    if not pts:
        return np.zeros((0, 3)), np.zeros(0, int)
    return np.concatenate(pts), np.concatenate(lab)


def nearest_within(points, queries, radius):
    """index of the nearest point within `radius` of each query (-1: none), through a grid of
    cells of that size"""
    out = np.full(len(queries), -1)
    if len(points) == 0:
        return out
    cell = np.floor(points / radius).astype(np.int64)
    order = np.lexsort((cell[:, 2], cell[:, 1], cell[:, 0]))
    keys = cell[order]
    buckets = {}
    start = np.flatnonzero(np.r_[True, np.any(keys[1:] != keys[:-1], axis=1)])
    stop = np.r_[start[1:], len(keys)]
    for s, e in zip(start, stop):
        buckets[tuple(keys[s])] = order[s:e]
    qcell = np.floor(queries / radius).astype(np.int64)
    offsets = [(i, j, k) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)]
    for qi, (q, c) in enumerate(zip(queries, qcell)):
        cand = [buckets[key] for d in offsets if (key := (c[0] + d[0], c[1] + d[1], c[2] + d[2])) in buckets]
        if not cand:
            continue
        idx = np.concatenate(cand)
        d2 = ((points[idx] - q) ** 2).sum(1)
        k = int(np.argmin(d2))
        if d2[k] <= radius * radius:
            out[qi] = idx[k]
    return out


def far_by_feature(surface, dump, radius, beyond, angle=30.0, loaded=None):
    """{kind: {"samples", "sum"}} over the dump's samples farther than `beyond`, plus "none" and
    "total"; `loaded` may hold (feature points, kinds) from an earlier call on the same input"""
    if loaded is None:
        V, T, P = read_surface(surface)
        loaded = feature_samples(V, T, P, angle, radius / 4)
    pts, lab = loaded
    S = np.loadtxt(dump, ndmin=2)
    far = S[S[:, 3] > beyond]
    near = nearest_within(pts, far[:, :3], radius)
    out = {"samples": int(len(S)), "sum": float(S[:, 3].sum()), "beyond": beyond, "radius": radius,
           "far_samples": int(len(far)), "far_sum": float(far[:, 3].sum())}
    for k, name in enumerate(KINDS):
        m = (near >= 0) & (lab[np.maximum(near, 0)] == k)
        out[name] = {"samples": int(m.sum()), "sum": float(far[m, 3].sum())}
    m = near < 0
    out["none"] = {"samples": int(m.sum()), "sum": float(far[m, 3].sum())}
    return out, loaded


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("input")
    ap.add_argument("dump")
    ap.add_argument("--radius", type=float, required=True, help="how near a feature must be")
    ap.add_argument("--beyond", type=float, required=True, help="the samples farther than this from the input")
    ap.add_argument("--angle", type=float, default=30.0, help="dihedral angle of a sharp edge (degrees)")
    ap.add_argument("--json", help="write the counts there too")
    args = ap.parse_args()
    if args.radius <= 0 or args.beyond < 0:
        sys.exit("far_by_feature.py: --radius must be positive and --beyond not negative")
    r, _ = far_by_feature(args.input, args.dump, args.radius, args.beyond, args.angle)
    print(f"samples {r['samples']} (distances summed: {r['sum']:.4g}); beyond {args.beyond:g}: {r['far_samples']} "
          f"(summed: {r['far_sum']:.4g}), by the input feature nearest within {args.radius:g}:")
    for name in KINDS + ["none"]:
        print(f"  {name:13s} {r[name]['samples']:8d}  {r[name]['sum']:10.4g}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(r, f, indent=1)


if __name__ == "__main__":
    main()
