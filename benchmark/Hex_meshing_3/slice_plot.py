#!/usr/bin/python3
"""A plane slice through a hexmesh VTU and its input surface, as a PNG: where is a mesh bad or far?

Each hexahedron crossing the plane is drawn as its section polygon, coloured by its scaled
Jacobian (red 0 .. green 1); with --report (hexmesh's JSON report of that mesh), the buffer
cells of the body-fitted boundary are drawn in a blue-violet scale instead, so cavities and
notches of the staircase show. The input surface's section is drawn in blue.

Usage: benchmark/Hex_meshing_3/slice_plot.py MESH.vtu INPUT.off --axis y --at 0.149
           --centre 0.26,0.15,0.17 --radius 0.12 [--report REPORT.json] -o slice.png
Needs python3-meshio, python3-numpy and python3-matplotlib (Debian). The input is read as OFF or
ASCII/binary STL through meshio (any format meshio reads).
"""
import argparse
import json

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402

HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


def section(X, s, edges):
    """the points where the edges of a polytope with corners X cross the plane (s: signed distances)"""
    pts = []
    for a, b in edges:
        if (s[a] <= 0) != (s[b] <= 0):
            t = s[a] / (s[a] - s[b])
            pts.append(X[a] + t * (X[b] - X[a]))
    return np.array(pts)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("input")
    ap.add_argument("--axis", choices="xyz", required=True)
    ap.add_argument("--at", type=float, required=True, help="the plane's coordinate along the axis")
    ap.add_argument("--centre", required=True, help="x,y,z: the window's centre (its axis coordinate is ignored)")
    ap.add_argument("--radius", type=float, required=True, help="half the window's side")
    ap.add_argument("--report", help="hexmesh's JSON report: buffer cells drawn apart")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    axis = "xyz".index(args.axis)
    plane = [a for a in range(3) if a != axis]
    c0 = np.array([float(v) for v in args.centre.split(",")])
    R = args.radius

    m = meshio.read(args.mesh)
    P, H = m.points, m.cells_dict["hexahedron"]
    sj = m.cell_data_dict.get("scaled_jacobian", {}).get("hexahedron", np.ones(len(H)))
    first_buffer = len(H)
    if args.report:
        b = json.load(open(args.report)).get("boundary", {})
        first_buffer = len(H) - b.get("buffer_cells", 0) + b.get("removed_buffer_cells", 0)
    fig, ax = plt.subplots(figsize=(10, 10))
    centres = P[H].mean(axis=1)
    near = np.where(np.max(np.abs(centres[:, plane] - c0[plane]), axis=1) < 1.2 * R)[0]
    drawn = 0
    for c in near:
        X = P[H[c]]
        s = X[:, axis] - args.at
        if s.min() > 0 or s.max() < 0:
            continue
        pts = section(X, s, HEX_EDGES)
        if len(pts) < 3:
            continue
        q = pts[:, plane]
        mid = q.mean(axis=0)
        q = q[np.argsort(np.arctan2(q[:, 1] - mid[1], q[:, 0] - mid[0]))]
        v = min(1.0, max(0.0, float(sj[c])))
        colour = plt.cm.cool(v) if c >= first_buffer else plt.cm.RdYlGn(v)
        ax.fill(q[:, 0], q[:, 1], facecolor=colour, edgecolor="k", lw=0.4)
        drawn += 1
    surf = meshio.read(args.input)
    V = surf.points
    for block in surf.cells:
        if block.type != "triangle":
            continue
        for f in block.data:
            X = V[f]
            s = X[:, axis] - args.at
            if s.min() > 0 or s.max() < 0:
                continue
            pts = section(X, s, [(0, 1), (1, 2), (2, 0)])
            if len(pts) == 2:
                ax.plot(pts[:, plane[0]], pts[:, plane[1]], "b-", lw=2)
    ax.set_xlim(c0[plane[0]] - R, c0[plane[0]] + R)
    ax.set_ylim(c0[plane[1]] - R, c0[plane[1]] + R)
    ax.set_aspect("equal")
    ax.set_xlabel("xyz"[plane[0]])
    ax.set_ylabel("xyz"[plane[1]])
    ax.set_title(f"{args.mesh}: {args.axis} = {args.at} ({drawn} cells; colour: scaled Jacobian"
                 f"{', buffer cells in blue-violet' if args.report else ''})", fontsize=9)
    plt.savefig(args.output, dpi=80)
    print(f"wrote {args.output} ({drawn} cells)")


if __name__ == "__main__":
    main()
