#!/usr/bin/python3
"""Dirty input through the hexmesh command line: readers, repair, leaks, patches, writers, reports.

Judged by independent means: meshio (MSH, Medit, VTU read-back), OpenFOAM's checkMesh (boundary
names and types), Python's own html/xml parsers (HTML report), exact expectations for generated
surfaces (volumes of boxes, the position of a hole), and agreement between clean and dirty variants
of the same shape (inside volume within 2%).
"""
import argparse
import filecmp
import gzip
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET
from html.parser import HTMLParser

FAILURES = []


def check(cond, msg):
    print(("  ok: " if cond else "  FAILED: ") + msg)
    if not cond:
        FAILURES.append(msg)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


class Ctx:
    pass


def hexmesh(ctx, inputs, outputs, extra=(), report=None, expect=0, body_fitted=False):
    # the repair checks compare volumes of staircase meshes (exact box volumes); the body-fitted
    # boundary has its own section
    cmd = [ctx.hexmesh] + list(inputs) + ([] if body_fitted else ["--staircase"])
    for o in outputs:
        cmd += ["-o", o]
    if report:
        cmd += ["--report", report]
    cmd += list(extra)
    r = run(cmd)
    check(r.returncode == expect, f"hexmesh {' '.join(os.path.basename(i) for i in inputs)} {' '.join(extra)} "
                                  f"exits {expect} (got {r.returncode}: {r.stderr.strip()[-300:]})")
    return r


# ---- generated surfaces -----------------------------------------------------------------------

def write_obj(path, verts, groups):
    """groups: list of (name, faces) with 0-based faces"""
    with open(path, "w") as f:
        for v in verts:
            f.write("v %.17g %.17g %.17g\n" % tuple(v))
        for name, faces in groups:
            f.write(f"g {name}\n")
            for t in faces:
                f.write("f " + " ".join(str(i + 1) for i in t) + "\n")


def box_quads(x0, y0, z0, x1, y1, z1, base=0):
    """8 vertices and 6 outward quads per side name"""
    v = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    idx = lambda i, j, k: base + i + 2 * j + 4 * k
    q = {
        "xmin": (idx(0, 0, 0), idx(0, 0, 1), idx(0, 1, 1), idx(0, 1, 0)),
        "xmax": (idx(1, 0, 0), idx(1, 1, 0), idx(1, 1, 1), idx(1, 0, 1)),
        "ymin": (idx(0, 0, 0), idx(1, 0, 0), idx(1, 0, 1), idx(0, 0, 1)),
        "ymax": (idx(0, 1, 0), idx(0, 1, 1), idx(1, 1, 1), idx(1, 1, 0)),
        "zmin": (idx(0, 0, 0), idx(0, 1, 0), idx(1, 1, 0), idx(1, 0, 0)),
        "zmax": (idx(0, 0, 1), idx(1, 0, 1), idx(1, 1, 1), idx(0, 1, 1)),
    }
    return v, q


def cylinder(z0, z1, r=0.5, n=64):
    """closed triangulated cylinder along z, outward"""
    verts = [(0, 0, z0), (0, 0, z1)]
    for k in range(n):
        a = 2 * math.pi * k / n
        verts.append((r * math.cos(a), r * math.sin(a), z0))
        verts.append((r * math.cos(a), r * math.sin(a), z1))
    tris = []
    for k in range(n):
        b0, t0 = 2 + 2 * k, 3 + 2 * k
        b1, t1 = 2 + 2 * ((k + 1) % n), 3 + 2 * ((k + 1) % n)
        tris += [(0, b1, b0), (1, t0, t1), (b0, b1, t1), (b0, t1, t0)]
    return verts, tris


def box_quads_obj(lo, hi, group):
    v, q = box_quads(*lo, *hi)
    return v, [(group, [t for quad in q.values() for t in ((quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3]))])]


def box_with_hole(path):
    """the surface of [0,1]^3 whose top face has a square hole [0.3,0.7]^2 (an open shell)"""
    g = [0, 0.3, 0.7, 1]
    verts, faces = [], []
    def vid(p):
        if p not in verts:
            verts.append(p)
        return verts.index(p)
    v, q = box_quads(0, 0, 0, 1, 1, 1)
    for side in ["xmin", "xmax", "ymin", "ymax", "zmin"]:
        a, b, c, d = (vid(v[i]) for i in q[side])
        faces += [(a, b, c), (a, c, d)]
    for i in range(3):
        for j in range(3):
            if i == 1 and j == 1:
                continue   # the hole
            a, b = vid((g[i], g[j], 1)), vid((g[i + 1], g[j], 1))
            c, d = vid((g[i + 1], g[j + 1], 1)), vid((g[i], g[j + 1], 1))
            faces += [(a, b, c), (a, c, d)]
    write_obj(path, verts, [("shell", faces)])


# sizes of the body-fitted runs (default: size = largest extent / 10, surface size = size / 4);
# the inputs with plates, flanges or necks about two surface cells thick get 5 cells across their
# thin parts (data/MANIFEST.md)
THIN = ["--thin-cells", "5"]
# anchor's chamfers and fillets at s / 2 (its surface size is 0.025): no boundary face beyond s / 4
# (3 at s: folded across the chamfer's convex edge, and hanging corners there)
ANCHOR = THIN + ["--feature-size", "0.0125"]
# t20_part's too (s = 0.924; 0.7 asks for s/2): no face beyond s/4 (one at 0.254 at s, folded 88
# degrees along its diagonal), feature fidelity 0.70 / 0.80 s (2.17 / 1.17)
T20 = THIN + ["--feature-size", "0.7"]
# cube_nonmanifold's wedges (its fin meets a face at 19 degrees) meshed down to s/8 (s = 0.1) where
# narrower than 4 cells: the mesh then stops where the wedge is narrow enough for its cap to lie
# within s/4 of both sides (73 faces beyond s/4 with --thin-cells 5, caps at 0.41 s)
WEDGE = ["--thin-cells", "4", "--thin-size", "0.0125"]
# the organic models' parts thinner than two surface cells (bunny's ears, 1.2 to 1.8 s thick; the
# elephant's trunk, tail, tusks and ears, about 1 s) get 6 cells across, down to s/8: every boundary
# face within s/4 of the input and the whole input within s/2 of the mesh (at s: faces up to 1.04 s
# off where a part was lost or half kept, parts of the input 9 to 13 s from the mesh; with 6 cells
# down to s/4 the ears' rims still fold faces, 1 to 4 of them); their feature angle is 60 degrees:
# their coarse triangulations crease by 30 to 60 degrees where the shape is smooth (bunny at 30
# degrees: 103 feature curves, faces folded along them at its ears' rims)
BUNNY = ["--thin-cells", "6", "--thin-size", "0.031", "--feature-angle", "60"]
ELEPHANT = ["--thin-cells", "6", "--thin-size", "0.003125", "--feature-angle", "60"]
# fandisk's surface cells halved where the normals in them differ by more than 10 degrees (its
# fillets and blends): at s, the faces across the fillet of radius 1.75 s meet at 30 to 38 degrees,
# creases of the mesh up to 8.5 s from any of the input's (feature fidelity 1.92 / 8.56 s); with it
# 1.21 / 0.85, 44,141 cells instead of 27,249, 18.5 s instead of 9.9 (at 15 degrees 1.21 / 0.80 but
# 0.331 instead of 0.349; at 20 degrees 0.300)
FANDISK = THIN + ["--surface-size", "0.025:0.0125", "--curvature-angle", "10"]
BODY_FITTED_SIZES = {"anchor": ANCHOR, "anchor_dupflip": ANCHOR, "bunny": BUNNY, "cube_nonmanifold": WEDGE,
                     "elephant": ELEPHANT, "eight": THIN, "fandisk": FANDISK, "fandisk_crack": THIN, "t20_part": T20}
# clean closed inputs whose boundary keeps the input's topology at those sizes (the others have
# parts thinner than two surface cells: rotor's blades and rim, fin_slot's slot and fin)
# body-fitted meshes that checkMesh -allGeometry finds no concave cell in (all, since the rims of
# elephant-with-holes' holes in its smooth skin are no features: it had 2, at its capped holes)
NO_CONCAVE_CELLS = {"anchor", "anchor_dupflip", "bunny", "cube", "cube_nonmanifold", "cylinder", "eight", "elephant",
                    "elephant-with-holes", "fandisk", "fandisk_crack", "fin_slot", "rotor", "t20_part", "teapot"}
# inputs with no boundary face farther than one surface size from the input at those sizes (the
# goal is 0.25 for every input; with the thin parts kept, fandisk's farthest is 0.73, 1.32 without)
# body-fitted meshes on which checkMesh -allGeometry finds nothing at all (no concave cell, no face
# failing the tet decomposition, ...): all (elephant-with-holes had 2 concave cells and 2 faces
# failing the tet decomposition at its capped holes while their rims were features)
GEOMETRY_OK = {"anchor", "anchor_dupflip", "bunny", "cube", "cube_nonmanifold", "cylinder", "eight", "elephant",
               "elephant-with-holes", "fandisk", "fandisk_crack", "fin_slot", "rotor", "t20_part", "teapot"}
# (anchor's farthest was 1.9 while non-manifold staircase vertices removed every cell around them)
NO_FACE_BEYOND_SURFACE_SIZE = {"anchor", "anchor_dupflip", "bunny", "cube", "cylinder", "cube_nonmanifold", "eight",
                               "elephant", "fandisk", "fandisk_crack", "fin_slot", "rotor", "t20_part"}
NO_FACE_BEYOND_HALF_SURFACE_SIZE = {"anchor", "anchor_dupflip", "bunny", "cube", "cube_nonmanifold", "cylinder", "eight",
                                    "elephant", "fandisk", "fandisk_crack", "fin_slot", "t20_part"}
# the fidelity goal, every boundary face within 0.25 x surface size of the input (cylinder
# and eight since the fidelity polish slides the corners of faces standing off the surface: their
# farthest went from 0.28 and 0.30 to 0.20 and 0.21; it makes moves on both)
# (fandisk and fandisk_crack, 6 and 4 far faces at the staircase's gap of 0.4 cell sizes, since the
# mesh is made again with the staircase 0.25 and 0.2 cell sizes off the surface where faces are
# far: their meshes at 0.25 and 0.2 have none)
# (bunny and elephant since their thin parts get 6 cells across: 15 and 42 far faces at s)
NO_FACE_BEYOND_QUARTER_SURFACE_SIZE = {"anchor", "anchor_dupflip", "bunny", "cube", "cube_nonmanifold", "cylinder",
                                       "eight", "elephant", "fandisk", "fandisk_crack", "fin_slot", "t20_part"}
# the second fidelity figure, 10,000 points sampled on the input within 0.5 x surface size
# of the mesh boundary: the clean closed inputs whose thin parts are resolved at those sizes, and
# two dirty ones that reach it too (not fin_slot, rotor: their slot, fin, blades and rim are
# thinner than two surface cells and not resolved; not teapot nor elephant-with-holes: open, their
# holes capped; at s, bunny's lost ear tips were 13 s from its mesh)
INPUT_WITHIN_HALF_SURFACE_SIZE = {"anchor", "anchor_dupflip", "bunny", "cube", "cube_nonmanifold", "cylinder", "eight",
                                  "elephant", "fandisk", "fandisk_crack", "t20_part"}
# (cylinder no longer since its rims get feature pillows: no face of it stands off; bunny instead)
FIDELITY_MOVES = {"bunny", "eight"}
# curve and corner vertices unsnapped to untangle cells that the reattachment rounds leave off
# their feature go back in joint moves, their neighbours making room (`feature_joint_moves`): the
# feature vertices still unsnapped at most (before: anchor 76, anchor_dupflip 76, fandisk 104; with
# them 41, 31 and 51, 35, 45 and 53 joint moves kept)
UNSNAPPED_AT_MOST = {"anchor": 55, "anchor_dupflip": 55, "fandisk": 70}
# where that goal is not met yet: at most this many faces beyond it (regression guards a little
# above the figures of 2026-12-04 at fb28a15: bunny 16, elephant 46, elephant-with-holes 38,
# fandisk 6 (10 before the joint moves' second target and round), fandisk_crack 4, rotor 137,
# teapot 75; the meshes change from commit to commit in ways that move a few faces either way;
# since the staircase retries: bunny 15, elephant 42, elephant-with-holes 38, rotor 117, teapot 75;
# bunny and elephant none since their thin parts get 6 cells across; teapot 51 since the paths
# are searched again, 82 since closed curves are pillowed further off: its mesh with the staircase
# at 0.4 is kept, the others having a cell below 0.3; rotor 120)
FAR_FACES_AT_MOST = {"elephant-with-holes": 44, "rotor": 130, "teapot": 85}
# the files whose first mesh (staircase 0.4 cell sizes off the surface) had a face beyond 0.25 x
# surface size, made again with the staircase at 0.25 then 0.2 (`Meshing_statistics::
# staircase_tries`); the others are made once
# (elephant's mesh with its thin parts at s/8 is made once)
STAIRCASE_RETRIED = {"bunny", "elephant-with-holes", "fandisk", "fandisk_crack", "rotor", "teapot"}
# some of the files where the polish's joint moves let curve or corner vertices off their feature
# (within 0.2 / 0.1 local size) to raise a cell below 0.3 (their minima and counts in the manual)
# (fandisk and fandisk_crack no longer since flat cells count as inverted)
LOOSENED = {"elephant", "elephant-with-holes"}
# the quality goals, where they are met at those sizes: min scaled Jacobian >= 0.3, and
# max non-orthogonality <= 65 degrees
# (anchor rose from 0.157 to 0.302 when the staircase stopped digging notches at non-manifold
# vertices)
# (fandisk rose from 0.255 to 0.302 when the polish let feature vertices off their curve or corner,
# within 0.2 / 0.1 local size)
# (bunny 0.246 -> 0.323 and elephant 0.078 -> 0.309 with the second polish, whose face pyramids
# count twice their value)
# (fandisk_crack 0.210 -> 0.325 and teapot 0.183 -> 0.293 when the open edges along a smooth seam or
# crack stopped being features, one side of a crease along a seam is kept, and curve ends across
# a crack are joined)
# (teapot 0.293 -> 0.312 and elephant-with-holes 0.233 -> 0.313 when a capture leaving cells below
# 0.3 is run again with other feature-path weights and the best mesh kept, and the rims of holes
# are judged against a fill of the hole: every file meets the goal)
MIN_SJ_03 = {"anchor", "anchor_dupflip", "bunny", "cube", "cube_nonmanifold", "cylinder", "eight", "elephant",
             "elephant-with-holes", "fandisk", "fandisk_crack", "fin_slot", "rotor", "t20_part", "teapot"}
# the files whose first capture left cells below 0.3 or a cell concave for OpenFOAM at those sizes
# (the others are captured once; elephant-with-holes' first capture reaches 0.315 since the corner
# rule of the feature chains; teapot and t20_part since feature paths may stray 6 local sizes from
# their curve where none keeps within 3: bunny's first capture fell to 0.176 then; anchor's with
# its sharp edges at s / 2 left a cell below 0.3 without feature pillows, its first capture reaches
# 0.334 with them (0.317 at the second without); t20_part's first leaves one, 0.354 at the second;
# cube_nonmanifold's wedges at s / 8: 0.252 with pillows, 0.353 at the third without;
# fandisk_crack: 0.212 with pillows, 0.325 without; since 8 smoothing sweeps instead of 12,
# fandisk_crack and t20_part are captured once (0.350 and 0.360) and teapot twice (0.350));
# these are the captures of the mesh kept: since the staircase retries, bunny's is the mesh with
# the staircase 0.2 cell sizes off the surface, captured once; elephant's (0.25), fandisk's (0.25)
# and fandisk_crack's (0.2) leave cells below 0.3 at their first capture
# (fandisk's with its curved parts at s/2 is captured once, 0.349); since the unfolding of faces
# (`unfold_faces()`, stop 48) elephant's and teapot's first captures have no face failing the tet
# decomposition, and are kept (elephant 0.302, teapot 0.351); since the feature paths are searched
# again with the curves left short first (no gap left at teapot's corners), teapot's first capture
# leaves a cell below 0.3 again: the third is kept (0.328); since closed curves get pillows with
# their chains up to 2.5 local sizes off (`choose_pillows()`), its first capture is kept (0.357);
# since flat cells count as inverted (see the manual's "Round-off decides some figures": which
# capture is kept follows round-off) cube_nonmanifold's first capture is kept (0.320), elephant's
# and elephant-with-holes' second; since a capture with pillows that leaves faces beyond a quarter
# surface size is run again without them (cylinder at 0.7 to 0.9 times its surface size: 68 to 94
# far faces, none without the pillows), rotor's and teapot's are captured twice, the second (no
# pillows) kept; since the captures with other path weights wait for the closer staircases where
# the captures before them leave far faces (`Staircase_record::weights_deferred`), the mesh kept
# for elephant-with-holes is the first of those made afterwards on its first staircase's grid
# (the same mesh as its second capture before: one capture of that mesh)
CAPTURE_RETRIED = {"elephant", "fandisk_crack", "rotor", "teapot"}
# the feature paths searched again with the corners' edges kept for the curves leaving along them
# (a chain had taken another curve's edge at a corner) and that search kept, in the capture kept:
# fandisk's corner (0.4603, 0.1544, -0.0071) (also bunny and elephant, whose meshes it leaves as
# they were or with the same figures; not asserted for them)
CORNER_EDGES_KEPT = {"fandisk"}
# feature fidelity, input->mesh / mesh->input in surface sizes: regression guards a little above
# the figures of 2026-12-04 (anchor 0.35 / 0.64 with the feature pillows, 0.64 / 0.68 without;
# t20_part 0.70 / 0.80; fandisk 1.02 / 8.47: a fillet of radius 1.75 s whose faces meet at more
# than 30 degrees counts as mesh feature edges; cube 0 / 0; with 8 smoothing sweeps anchor 0.33 /
# 0.69, t20_part 0.70 / 0.74)
# (fandisk 1.00 -> 1.92 input->mesh since its mesh is the one with the staircase 0.25 cell sizes
# off the surface, no face beyond s/4 instead of 6: an input edge of 30 degrees or more whose mesh
# edge turns by 20 to 30 degrees, 0.50 within the tolerance)
# (fandisk 1.92 / 8.56 -> 1.21 / 0.85 with its curved parts at s/2: the input edge of 28 to 32
# degrees at (0.26, 0.14, -0.34) is where the input is farthest)
# (the vertices where a chain turns inside a face pulled towards their curve, `turn_polish()`:
# anchor 0.33 -> 0.24 input->mesh, fandisk 1.21 -> 0.66; t20_part 0.70 / 0.74 -> 0.70 / 0.75)
# (a turn vertex's step that fails the guards alone tried with the vertices of its cells improved,
# `joint_turn_move()`: anchor 0.24 / 0.69 -> 0.24 / 0.55, strict and within the tolerance)
# (curve and corner vertices released into the volume to untangle cells go back to their curve,
# not only to the surface: fandisk 0.66 / 0.85 -> 0.66 / 0.64)
# (a feature path pays for a vertex on another curve of one of its corners, `shortest_path()`:
# fandisk 0.66 / 0.64 -> 0.66 / 0.47, all 35 curves captured; anchor 0.24 / 0.55 -> 0.26 / 0.48)
# (the paths searched again with the curves left short of a corner first, `snap_features()`:
# anchor 0.26 / 0.48 -> 0.24 / 0.42, no gap; its input->mesh guard is the goal, 0.25)
# (closed curves pillowed with their chains up to 2.5 local sizes off, `choose_pillows()`: cylinder
# 0.37 / 0.74 -> 0.03 / 0.02, its rims no longer turn inside faces; anchor's eight hole rims
# pillowed, its turns 220 -> 117, but the worst places, elsewhere, move: 0.24 / 0.42 -> 0.26 / 0.45,
# the turn at the corner (0.36, -0.2, 0.16))
# (flat cells counted as inverted: anchor 0.26 / 0.45 -> 0.33 / 0.51, fandisk 0.66 / 0.47 -> 0.66 /
# 0.92; these are single samples of a wide spread: over the test surfaces shifted by 1e-9 of their
# diagonal, `benchmark/Hex_meshing_3/perturbation.py --shifts 8`, anchor's mesh->input went 0.45 -
# 0.81 before and 0.42 - 0.68 after, fandisk's 0.47 - 2.13 before and 0.52 - 0.94 after)
# (unsnapped feature vertices put back in joint moves: anchor 0.33 / 0.51 -> 0.26 / 0.51; over the
# 8 shifts anchor's input->mesh 0.23 - 0.62 -> 0.23 - 0.36, fandisk's 0.60 - 1.23 -> 0.59 - 0.71)
# (the turn polish in sweeps until nothing moves, stop 57: anchor 0.26 / 0.51 -> 0.24 / 0.47, its
# input -> mesh guard the goal again; fandisk 0.66 / 0.92 -> 0.65 / 0.92, t20_part 0.70 / 0.78 -> 0.70 / 0.75)
# (stop 67: the paths searched again where a chain took the corner edge another curve leaves
# along, `corner_edge_cosine`: fandisk 0.65 / 0.92 -> 0.65 / 0.63, its worst crease was at the corner
# (0.4603, 0.1544, -0.0071))
FEATURE_FIDELITY_FLOOR = {"anchor": (0.25, 0.5), "anchor_dupflip": (0.25, 0.5), "t20_part": (0.75, 0.8),
                          "fandisk": (0.75, 0.7), "cube": (0.05, 0.05), "cylinder": (0.1, 0.1)}
# the same within the report's angle tolerance (10 degrees), figures of 2026-12-04 at 8 sweeps:
# anchor 0.31 / 0.69 (faces folded where a chain turns inside a face), t20_part 0.31 / 0.73,
# fandisk 0.52 / 1.61 (its blend's 22.5 degree edges count as input creases; 0.66 / 0.85 with its
# curved parts at s/2)
# (with the turns pulled: anchor 0.24 / 0.69, t20_part 0.35 / 0.75, fandisk 0.28 / 0.85; with the
# vertices that would flatten a face pulled too, t20_part 0.35 / 0.63; the joint turn moves:
# anchor 0.24 / 0.55, t20_part 0.35 / 0.56; released curve vertices back on their curve: fandisk
# 0.27 / 0.64; paths paying for another curve's vertices: fandisk 0.27 / 0.47, anchor 0.26 / 0.48;
# the paths searched again: anchor 0.24 / 0.42; closed curves pillowed: anchor 0.26 / 0.45,
# cylinder 0.03 / 0.02)
# (flat cells counted as inverted: anchor 0.26 / 0.51, fandisk 0.27 / 0.92)
# (unsnapped feature vertices put back in joint moves: fandisk 0.27 / 0.92 -> 0.23 / 0.92; over the 8
# shifts its input->mesh 0.26 - 0.61 -> 0.22 - 0.36)
# (stop 57: anchor 0.26 / 0.51 -> 0.22 / 0.47, fandisk 0.23 / 0.92 -> 0.22 / 0.92, t20_part 0.35 / 0.54)
# (stop 67, the corners' edges kept: fandisk 0.22 / 0.92 -> 0.19 / 0.63)
FEATURE_FIDELITY_TOLERANT_FLOOR = {"anchor": (0.25, 0.5), "anchor_dupflip": (0.25, 0.5), "t20_part": (0.4, 0.7),
                                   "fandisk": (0.25, 0.7), "cube": (0.05, 0.05), "cylinder": (0.1, 0.1)}
# where the goal is not met yet: regression guards a little below the figures of 2026-12-02
# (fandisk_crack rose from 0.030 to 0.202 when its crack stopped counting as a hole to cap)
# (elephant-with-holes rose from 0.021 to 0.038 when surface vertices stopped sliding onto its holes' rims)
# (loosened feature vertices: elephant 0.059 -> 0.078, elephant-with-holes 0.038 -> 0.059,
# fandisk_crack 0.202 -> 0.210; the second polish: teapot 0.175 -> 0.183)
# (elephant-with-holes 0.059 -> 0.233 when the rims of its holes in the smooth skin stopped being
# features)
# (elephant-with-holes 0.233 -> 0.313, teapot 0.293 -> 0.312: in MIN_SJ_03 since)
MIN_SJ_FLOOR = {}
# (every file since the buffer cells at faces beyond 70 degrees are removed: elephant-with-holes
# had one, 73 degrees, at a capped hole)
NON_ORTHO_65 = {"anchor", "anchor_dupflip", "bunny", "cube", "cube_nonmanifold", "cylinder", "eight", "elephant",
                "elephant-with-holes", "fandisk", "fandisk_crack", "fin_slot", "rotor", "t20_part", "teapot"}
SAME_TOPOLOGY = {"anchor", "cube", "eight", "elephant", "fandisk", "t20_part", "bunny", "cylinder", "fin_slot"}


# ---- OpenFOAM polyMesh, read back independently -----------------------------------------------

def foam_list(path):
    """the inside of an OpenFOAM ASCII list file, and its declared length"""
    text = open(path).read()
    body = text[text.index("}", text.index("FoamFile")) + 1:]
    m = re.search(r"(\d+)\s*\(", body)
    return int(m.group(1)), body[m.end():body.rindex(")")]


def read_poly(case):
    """points, faces, owner, neighbour and patches {name: (start, n)} of an OpenFOAM ASCII polyMesh"""
    import numpy as np
    poly = os.path.join(case, "constant", "polyMesh")
    _, s = foam_list(os.path.join(poly, "points"))
    pts = np.array([[float(x) for x in t.split()] for t in re.findall(r"\(([^()]*)\)", s)])
    _, s = foam_list(os.path.join(poly, "faces"))
    faces = [[int(x) for x in t.split()] for t in re.findall(r"\d+\(([^()]*)\)", s)]
    owner = [int(x) for x in foam_list(os.path.join(poly, "owner"))[1].split()]
    nei = [int(x) for x in foam_list(os.path.join(poly, "neighbour"))[1].split()]
    b = open(os.path.join(poly, "boundary")).read()
    patches = {m.group(1): (int(m.group(3)), int(m.group(2))) for m in
               re.finditer(r"(\S+)\s*\{[^}]*?nFaces\s+(\d+);\s*startFace\s+(\d+);", b)}
    return pts, faces, owner, nei, patches


def cell_centroids(pts, faces, owner, nei):
    """volume centroids of the polyhedral cells (faces fanned from their centre, tetrahedra from a
    point of the cell): inside any valid cell, whatever its hanging points"""
    import numpy as np
    n = max(max(owner), max(nei) if nei else 0) + 1
    ref = np.zeros((n, 3))
    cnt = np.zeros(n)
    for lst in (owner, nei):
        for f, c in enumerate(lst):
            ref[c] += pts[faces[f][0]]
            cnt[c] += 1
    ref /= cnt[:, None]
    vol = np.zeros(n)
    mom = np.zeros((n, 3))

    def add(c, P):
        fc = P.mean(axis=0)
        for i in range(len(P)):
            a, b = P[i], P[(i + 1) % len(P)]
            v = np.dot(np.cross(a - ref[c], b - ref[c]), fc - ref[c]) / 6
            vol[c] += v
            mom[c] += v * (ref[c] + a + b + fc) / 4
    for f, c in enumerate(owner):
        add(c, pts[faces[f]])
        if f < len(nei):
            add(nei[f], pts[faces[f]][::-1])
    return mom / vol[:, None]


def patch_sides(case, side):
    """per patch: (faces, area, min and max of side(face centre, owner cell centroid) over the faces
    where it is not None, how many those are)"""
    import numpy as np
    pts, faces, owner, nei, patches = read_poly(case)
    g = cell_centroids(pts, faces, owner, nei)
    res = {}
    for name, (start, n) in patches.items():
        area, vals = 0.0, []
        for f in range(start, start + n):
            P = pts[faces[f]]
            c = P.mean(axis=0)
            a = sum(np.cross(P[i] - c, P[(i + 1) % len(P)] - c) for i in range(len(P)))
            area += 0.5 * np.linalg.norm(a)
            v = side(c, g[owner[f]])
            if v is not None:
                vals.append(v)
        res[name] = (n, area, min(vals, default=0.0), max(vals, default=0.0), len(vals))
    return res


def vtu_min_sj(mv):
    """the minimum scaled Jacobian of the hexahedra of a VTU file read by meshio, from its points (numpy)"""
    import numpy as np
    x = mv.points[mv.cells_dict["hexahedron"]]
    worst = 1.0
    for i, (a, b, c) in enumerate([(1, 3, 4), (2, 0, 5), (3, 1, 6), (0, 2, 7), (7, 5, 0), (4, 6, 1), (5, 7, 2), (6, 4, 3)]):
        e1, e2, e3 = x[:, a] - x[:, i], x[:, b] - x[:, i], x[:, c] - x[:, i]
        d = np.einsum("ij,ij->i", np.cross(e1, e2), e3)
        n = np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1) * np.linalg.norm(e3, axis=1)
        worst = min(worst, float(np.min(np.where(n > 0, d / np.where(n > 0, n, 1), 0.0))))
    return worst


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--hexmesh", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    ctx = Ctx()
    ctx.hexmesh = args.hexmesh
    W = args.work
    shutil.rmtree(W, ignore_errors=True)
    os.makedirs(W)
    D = args.data
    import meshio
    import numpy as np

    # 1. every surface of the test data meshes (default settings), dirty ones included
    print("[every test surface meshes]")
    reports = {}
    for name in sorted(os.listdir(D)):
        if not name.endswith(".off"):
            continue
        rep = os.path.join(W, name + ".json")
        hexmesh(ctx, [os.path.join(D, name)], [os.path.join(W, name + ".vtu")], ["-q"], rep)
        if os.path.exists(rep):
            j = json.load(open(rep))
            reports[name] = j
            check(j["counts"]["cells"] > 0 and j["quality"]["scaled_jacobian"]["min"] > 0,
                  f"{name}: {j['counts']['cells']} cells, min scaled Jacobian {j['quality']['scaled_jacobian']['min']:.3g}")
    if "anchor_dupflip.off" in reports:
        r = reports["anchor_dupflip.off"]["repair"]
        s = reports["anchor_dupflip.off"]["input_summary"]
        check(r["duplicate_triangles"] == 21 and r["reversed_duplicates"] == 10 and r["reoriented_triangles"] > 0
              and r["sheet_triangles"] == 0,
              f"anchor_dupflip: 21 duplicates and 10 reversed copies removed, flipped faces reoriented ({r})")
        check(s["closed"] and s["exact_inside_test"] and s["triangles"] == 1050,
              "anchor_dupflip repaired into the closed 1050-triangle anchor (exact inside test)")
    if "elephant-with-holes.off" in reports:
        s = reports["elephant-with-holes.off"]["input_summary"]
        r = reports["elephant-with-holes.off"]["repair"]
        check(s["boundary_edges"] == 1353 and r["filled_holes"] > 100 and r["filled_rim_edges"] == 1353 and
              s["exact_inside_test"],
              f"elephant-with-holes: 1353 boundary edges reported, all round {r['filled_holes']} holes filled "
              f"({r['fill_triangles']} triangles): closed, exact inside test ({s['exact_inside_test']})")

    # 2. dirty variants: inside volume within 2% of the clean original at the same settings
    print("[dirty variants keep the volume]")
    vl, tl = cylinder(0, 1.5)
    write_obj(os.path.join(W, "cyl_long.obj"), vl, [("cyl", tl)])
    v1, t1 = cylinder(0, 1)
    v2, t2 = cylinder(0.5, 1.5)
    write_obj(os.path.join(W, "cyl_overlap.obj"), v1 + v2,
              [("lower", t1), ("upper", [tuple(i + len(v1) for i in t) for t in t2])])
    pairs = [
        ("elephant-with-holes.off", "elephant.off", ["--size", "0.06", "--surface-size", "0.015",
                                                     "--box", "-0.6,-0.7,-0.5,0.6,0.7,0.5"]),
        ("fandisk_crack.off", "fandisk.off", ["--size", "0.08", "--surface-size", "0.02",
                                              "--box", "-0.6,-0.6,-0.6,0.6,0.6,0.6"]),
        ("anchor_dupflip.off", "anchor.off", ["--size", "0.08", "--surface-size", "0.02",
                                              "--box", "-0.8,-0.8,-0.8,0.8,0.8,0.8"]),
        (os.path.join(W, "cyl_overlap.obj"), os.path.join(W, "cyl_long.obj"),
         ["--size", "0.1", "--surface-size", "0.025", "--box", "-0.6,-0.6,-0.1,0.6,0.6,1.6"]),
    ]
    for dirty, clean, opts in pairs:
        vols = []
        for f in (dirty, clean):
            path = f if os.path.isabs(f) else os.path.join(D, f)
            rep = os.path.join(W, "vol_" + os.path.basename(f) + ".json")
            hexmesh(ctx, [path], [os.path.join(W, "vol_" + os.path.basename(f) + ".vtu")], ["-q"] + opts, rep)
            vols.append(json.load(open(rep))["volume"] if os.path.exists(rep) else float("nan"))
        rel = abs(vols[0] - vols[1]) / vols[1]
        check(rel <= 0.02, f"{os.path.basename(dirty)} volume {vols[0]:.6g} vs {os.path.basename(clean)} {vols[1]:.6g}: "
                           f"{100 * rel:.2f}% apart (<= 2%)")
    # 3. OBJ groups and STL solids are the patch names in every writer
    print("[patch names from OBJ groups and STL solids]")
    v, q = box_quads(0, 0, 0, 2, 1, 1)
    tri = lambda quad: [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]
    groups = [("inlet", tri(q["xmin"])), ("outlet", tri(q["xmax"])),
              ("walls", sum((tri(q[s]) for s in ["ymin", "ymax", "zmin", "zmax"]), []))]
    write_obj(os.path.join(W, "duct.obj"), v, groups)
    with open(os.path.join(W, "duct.stl"), "w") as f:
        for name, faces in groups:
            f.write(f"solid {name}\n")
            for t in faces:
                f.write(" facet normal 0 0 0\n  outer loop\n")
                for i in t:
                    f.write("   vertex %g %g %g\n" % v[i])
                f.write("  endloop\n endfacet\n")
            f.write(f"endsolid {name}\n")
    for src in ("duct.obj", "duct.stl"):
        out = os.path.join(W, "patches_" + src.replace(".", "_"))
        os.makedirs(out)
        case, msh, med, vtu, rep = (os.path.join(out, n) for n in ("case", "m.msh", "m.mesh", "m.vtu", "r.json"))
        hexmesh(ctx, [os.path.join(W, src)], [case, msh, med, vtu], ["-q", "--size", "0.25", "--surface-size", "0.125"], rep)
        j = json.load(open(rep))
        faces = {p["name"]: p["faces"] for p in j["patches"]}
        # the duct's ends are 1x1 and its walls 2x1 (x4): faces of 0.125 or coarser cells
        check(faces.get("inlet", 0) > 0 and faces.get("outlet", 0) > 0 and faces.get("walls", 0) > 0,
              f"{src}: report patches inlet/outlet/walls have faces ({faces})")
        boundary = open(os.path.join(case, "constant", "polyMesh", "boundary")).read()
        for n in ("inlet", "outlet", "walls"):
            check(re.search(r"^\s+%s\s*\n\s*\{[^}]*type\s+wall;[^}]*nFaces\s+%d;" % (n, faces.get(n, -1)), boundary, re.M)
                  is not None, f"{src}: OpenFOAM patch {n}, type wall, {faces.get(n)} faces")
        m = meshio.read(msh)
        names = {k: int(v_[0]) for k, v_ in m.field_data.items()}
        for n in ("inlet", "outlet", "walls"):
            quads = m.cell_sets.get(n)
            nq = sum(len(x) for x in quads) if quads else 0
            check(n in names and nq == faces.get(n), f"{src}: MSH physical group {n} with {nq} quads (meshio)")
        check(len(m.cells_dict["hexahedron"]) == j["counts"]["cells"] and len(m.points) == j["counts"]["vertices"],
              f"{src}: MSH read back with the same cells and vertices (meshio)")
        me = meshio.read(med)
        check(len(me.cells_dict["hexahedron"]) == j["counts"]["cells"] and len(me.points) == j["counts"]["vertices"]
              and len(me.cells_dict["quad"]) == j["counts"]["boundary_faces"],
              f"{src}: Medit read back with the same hexahedra, vertices and boundary quads (meshio)")
        mv = meshio.read(vtu)
        vpatch = np.concatenate([d for d in mv.cell_data["patch"]])
        for p_index, p in enumerate(j["patches"]):
            if p["name"] in ("inlet", "outlet", "walls"):
                arr = mv.field_data.get("patch:" + p["name"])
                check(arr is not None and int(np.ravel(arr)[0]) == p_index and int((vpatch == p_index).sum()) == p["faces"],
                      f"{src}: VTU field data patch:{p['name']} = {p_index}, {p['faces']} quads with that patch (meshio)")
        check(len(mv.cells_dict["hexahedron"]) == j["counts"]["cells"] and len(mv.cells_dict["quad"]) == j["counts"]["boundary_faces"],
              f"{src}: VTU read back with the hexahedra and the boundary quads (meshio)")
        comments = open(med).read()
        refs = me.cell_data_dict["medit:ref"]["quad"]
        for p_index, p in enumerate(j["patches"]):
            if p["name"] in ("inlet", "outlet", "walls"):
                ok = re.search(r"#.*\b%d\b.*%s" % (p_index + 1, p["name"]), comments) is not None
                check(ok and int((refs == p_index + 1).sum()) == p["faces"],
                      f"{src}: Medit ref {p_index + 1} = {p['name']} with {p['faces']} quads")
    # renaming and grouping, types; checkMesh accepts the result
    out = os.path.join(W, "patches_renamed")
    os.makedirs(out)
    case = os.path.join(out, "case")
    rep = os.path.join(out, "r.json")
    hexmesh(ctx, [os.path.join(W, "duct.obj")], [case],
            ["-q", "--size", "0.25", "--surface-size", "0.125", "--patch-name", "(in|out)let=ports",
             "--patch-type", "ports=patch", "--patch-type", "zmin=symmetryPlane"], rep)
    j = json.load(open(rep))
    faces = {p["name"]: (p["type"], p["faces"]) for p in j["patches"]}
    before = json.load(open(os.path.join(W, "patches_duct_obj", "r.json")))
    bf = {p["name"]: p["faces"] for p in before["patches"]}
    check("inlet" not in faces and faces.get("ports") == ("patch", bf["inlet"] + bf["outlet"]),
          f"--patch-name merges inlet and outlet into 'ports' of type patch ({faces})")
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
    r = run(["checkMesh", "-case", case], env=env)
    check(r.returncode == 0 and "Mesh OK" in r.stdout and re.search(r"^\s+ports\s+\d+", r.stdout, re.M),
          "checkMesh: Mesh OK with the renamed patch")
    boundary = open(os.path.join(case, "constant", "polyMesh", "boundary")).read()
    check(re.search(r"zmin\s*\{\s*type\s+symmetryPlane;", boundary) is not None, "--patch-type zmin=symmetryPlane written")

    # 4. a box with a hole, meshed around from outside: the hole is filled (its cap is the top
    # face's missing square); with --no-fill-holes the leak is reported at the hole
    print("[holes filled]")
    box_with_hole(os.path.join(W, "holed_box.obj"))
    rep = os.path.join(W, "filled.json")
    opts = ["--box", "-0.5,-0.5,-0.5,1.5,1.5,1.5", "--size", "0.1", "--surface-size", "0.05",
            "--region", "seed:-0.45,-0.45,-0.45"]
    r = hexmesh(ctx, [os.path.join(W, "holed_box.obj")], [os.path.join(W, "filled.vtu")], opts + ["--strict"], rep)
    j = json.load(open(rep))
    check(j["repair"]["filled_holes"] == 1 and j["repair"]["filled_rim_edges"] == 4 and not j["leaks"] and
          "1 hole filled" in r.stderr,
          f"holed box: 1 hole filled ({j['repair']['fill_triangles']} triangles on {j['repair']['filled_rim_edges']} rim "
          f"edges), no leak, --strict accepts it")
    # (the staircase: the box's inside is not meshed, as it is with the leak cut off below)
    check(6.6 < j["volume"] < 7.0, f"holed box: meshed volume {j['volume']:.4g} excludes the box's inside")
    # an open box (its top face missing): the cap lies on the missing face, the box is a cube with
    # sharp edges (without the fill, where the winding number is 0.5: a dome above the rim); a
    # single open square is the rim of an open surface, not a hole (its fill would be as large as
    # the surface): left open
    v, q = box_quads(0, 0, 0, 1, 1, 1)
    tris = []
    for side in ["xmin", "xmax", "ymin", "ymax", "zmin"]:
        a, b, c, d = q[side]
        tris += [(a, b, c), (a, c, d)]
    write_obj(os.path.join(W, "open_box.obj"), v, [("open_box", tris)])
    vols = {}
    for tag, extra in (("fill", []), ("nofill", ["--no-fill-holes"])):
        rep = os.path.join(W, f"open_box_{tag}.json")
        hexmesh(ctx, [os.path.join(W, "open_box.obj")], [os.path.join(W, f"open_box_{tag}.vtu")], ["-q"] + extra, rep,
                body_fitted=True)
        j = json.load(open(rep))
        vols[tag] = j["volume"]
        if tag == "fill":
            fi = j["fidelity"]
            check(j["repair"]["filled_holes"] == 1 and j["input_summary"]["exact_inside_test"] and
                  abs(j["volume"] - 1) < 1e-9 and abs(fi["cap_area"] - 1) < 1e-9 and
                  j["quality"]["scaled_jacobian"]["min"] > 0.8 and fi["faces_beyond_quarter_surface_size"] == 0 and
                  j["features"]["corners"] == 8,
                  f"open box filled: a closed cube (exact inside test), volume {j['volume']:.12g}, cap area "
                  f"{fi['cap_area']:.12g}, {j['features']['corners']} corners, min scaled Jacobian "
                  f"{j['quality']['scaled_jacobian']['min']:.3f}")
    check(vols["nofill"] > 1.01, f"open box left open: the mesh bulges above the rim (volume {vols['nofill']:.4f})")
    write_obj(os.path.join(W, "square.obj"), [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [("square", [(0, 1, 2), (0, 2, 3)])])
    rep = os.path.join(W, "square.json")
    hexmesh(ctx, [os.path.join(W, "square.obj")], [os.path.join(W, "square.vtu")],
            ["-q", "--box", "-0.5,-0.5,-0.5,1.5,1.5,0.5", "--size", "0.25", "--region", "seed:-0.4,-0.4,-0.4"], rep)
    j = json.load(open(rep))
    check(j["repair"]["filled_holes"] == 0, f"an open square: its rim is no hole ({j['repair']['filled_holes']} filled)")

    print("[leaks]")
    opts = opts + ["--no-fill-holes"]
    rep = os.path.join(W, "leak.json")
    r = hexmesh(ctx, [os.path.join(W, "holed_box.obj")], [os.path.join(W, "leak.vtu")], opts, rep)
    check("leak 1" in r.stderr and "hole" in r.stderr, f"the leak is reported on stderr: {r.stderr.strip()[-300:]}")
    j = json.load(open(rep))
    leaks = j["leaks"]
    check(len(leaks) >= 1, f"{len(leaks)} leak(s) in the report")
    if leaks:
        lo, hi = leaks[0]["passage"][:3], leaks[0]["passage"][3:]
        check(0.2 <= lo[0] and hi[0] <= 0.8 and 0.2 <= lo[1] and hi[1] <= 0.8 and 0.85 <= lo[2] and hi[2] <= 1.15,
              f"the leak's passage {leaks[0]['passage']} is at the hole [0.3,0.7]^2 x {{1}}")
        check(0.5 < leaks[0]["volume"] <= 1.0, f"the leak is the box's inside (volume {leaks[0]['volume']:.3g})")
    # the box's inside is not meshed: the volume is the box's minus the shell's inside (about 8 - 1)
    # 8 minus the box grown by the cut layer (1.1^3 = 1.33); with the inside it would be above 7.3
    check(6.6 < j["volume"] < 7.0, f"meshed volume {j['volume']:.4g} excludes the box's inside (8 - 1.1^3 = 6.67)")
    r = hexmesh(ctx, [os.path.join(W, "holed_box.obj")], [os.path.join(W, "strict.vtu")], opts + ["--strict"], expect=2)
    check("error" in r.stderr and "leak" in r.stderr and not os.path.exists(os.path.join(W, "strict.vtu")),
          "--strict: a leak is an error and nothing is written")

    # 5. gzip gives the same mesh; several files; --scale
    print("[gzip, several files, scale]")
    gz = os.path.join(W, "eight.off.gz")
    with open(os.path.join(D, "eight.off"), "rb") as f, gzip.open(gz, "wb") as g:
        g.write(f.read())
    hexmesh(ctx, [os.path.join(D, "eight.off")], [os.path.join(W, "plain.vtu"), os.path.join(W, "plain_case")], ["-q"])
    hexmesh(ctx, [gz], [os.path.join(W, "gz.vtu"), os.path.join(W, "gz_case")], ["-q"])
    check(filecmp.cmp(os.path.join(W, "plain.vtu"), os.path.join(W, "gz.vtu"), shallow=False), "gzip input: identical VTU")
    for f in ["points", "faces", "owner", "neighbour", "boundary"]:
        check(filecmp.cmp(os.path.join(W, "plain_case/constant/polyMesh", f), os.path.join(W, "gz_case/constant/polyMesh", f),
                          shallow=False), f"gzip input: identical polyMesh/{f}")
    # two boxes in two files: two parts named after the files
    for n, x0 in (("left", 0), ("right", 2)):
        v, q = box_quads(x0, 0, 0, x0 + 1, 1, 1)
        write_obj(os.path.join(W, n + ".obj"), v, [])
        with open(os.path.join(W, n + ".obj"), "a") as f:
            for quad in q.values():
                f.write("f " + " ".join(str(i + 1) for i in quad) + "\n")
    rep = os.path.join(W, "two.json")
    hexmesh(ctx, [os.path.join(W, "left.obj"), os.path.join(W, "right.obj")], [os.path.join(W, "two.vtu")],
            ["-q", "--size", "0.25"], rep)
    j = json.load(open(rep))
    names = [p["name"] for p in j["patches"] if p["faces"] > 0]
    # staircase: the cells touching a face are cut, so each unit box keeps [s/4, 1 - s/4]^3 (s = 0.25)
    check(sorted(names) == ["left", "right"] and abs(j["volume"] - 2 * 0.875 ** 3) < 1e-12,
          f"two files: patches {names}, volume {j['volume']} (2 x 0.875^3 exactly)")
    rep = os.path.join(W, "scaled.json")
    hexmesh(ctx, [os.path.join(W, "left.obj")], [os.path.join(W, "scaled.vtu")], ["-q", "--scale", "0.001", "--size", "0.00025"], rep)
    j = json.load(open(rep))
    check(abs(j["volume"] - 0.875 ** 3 * 1e-9) < 1e-21, f"--scale 0.001: volume {j['volume']:.6g} (0.875^3 1e-9 exactly)")

    # 6. malformed files: one-line typed errors naming the file and the cause
    print("[malformed files]")
    E = os.path.join(W, "bad")
    os.makedirs(E)
    tet = b"solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid t\n"
    binstl = b"x" * 80 + struct.pack("<I", 2) + b"\0" * 50
    bad = {
        "truncated_ascii.stl": (tet[:70], "truncated"),
        "truncated_binary.stl": (binstl, "truncated"),
        "garbage.obj": (b"\x00\x01\x02 hello\nworld\n", "no face"),
        "inf.obj": (b"v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", "not a finite number"),
        "badindex.obj": (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "refers to vertex 9"),
        "truncated.off": (b"OFF\n4 4 0\n0 0 0\n1 0 0\n", "truncated"),
        "truncated.ply": (b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          b"property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" + b"\0" * 20,
                          "truncated"),
        "corrupt.stl.gz": (gzip.compress(tet)[:-12], "gzip"),
        "empty.ply": (b"", "empty"),
    }
    for name, (content, needle) in bad.items():
        path = os.path.join(E, name)
        open(path, "wb").write(content)
        r = run([args.hexmesh, path, "-o", os.path.join(E, "x.vtu")])
        lines = [l for l in r.stderr.splitlines() if l.strip()]
        prefix = "hexmesh: " + path + ": "
        check(r.returncode == 2 and len(lines) == 1 and lines[0].startswith(prefix) and needle in lines[0][len(prefix):],
              f"{name}: exit {r.returncode}, '{lines[0] if lines else ''}'")
    check(not os.path.exists(os.path.join(E, "x.vtu")), "nothing written for malformed input")

    # 7. --max-cells: a valid, coarser mesh and a warning
    print("[max cells]")
    rep = os.path.join(W, "maxcells.json")
    r = hexmesh(ctx, [os.path.join(D, "bunny.off")], [os.path.join(W, "maxcells.vtu")],
                ["--max-cells", "3000", "--size", "1", "--surface-size", "0.05"], rep)
    j = json.load(open(rep))
    check(j["status"] == "CELL_LIMIT_REACHED" and "warning" in r.stderr and "--max-cells" in r.stderr,
          f"status {j['status']}, warning printed")
    check(j["grid"]["leaf_cells"] <= 3000 * 1.3 and j["quality"]["scaled_jacobian"]["min"] > 0,
          f"grid of {j['grid']['leaf_cells']} leaves (limit 3000, balance may add a few), valid")

    # 8a. regressions found in review
    print("[review regressions]")
    R = os.path.join(W, "review")
    os.makedirs(R)
    def box_tris(lo, hi, inward=False):
        v, q = box_quads(*lo, *hi)
        tris = []
        for quad in q.values():
            t = [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]
            tris += [(a, c, b) for a, b, c in t] if inward else t
        return v, tris
    def write_off(path, parts):
        verts, faces = [], []
        for v, t in parts:
            faces += [tuple(i + len(verts) for i in f) for f in t]
            verts += v
        with open(path, "w") as f:
            f.write(f"OFF\n{len(verts)} {len(faces)} 0\n")
            f.writelines("%.17g %.17g %.17g\n" % tuple(p) for p in verts)
            f.writelines("3 %d %d %d\n" % t for t in faces)
    outer, inner = box_tris((0, 0, 0), (4, 4, 4)), box_tris((1, 1, 1), (3, 3, 3), inward=True)
    stray = ([(10, 10, 10), (10.5, 10, 10), (10, 10.5, 10)], [(0, 1, 2)])
    write_off(os.path.join(R, "hollow.off"), [outer, inner])
    write_off(os.path.join(R, "hollow_open.off"), [outer, inner, stray])
    vols = []
    for n in ("hollow", "hollow_open"):
        rep = os.path.join(R, n + ".json")
        hexmesh(ctx, [os.path.join(R, n + ".off")], [os.path.join(R, n + ".vtu")],
                ["-q", "--box", "-1,-1,-1,5,5,5", "--size", "0.5", "--surface-size", "0.25"], rep)
        vols.append(json.load(open(rep))["volume"])
    check(abs(vols[0] - vols[1]) < 1e-9 and vols[0] < 3.5 ** 3 - 2 ** 3,
          f"a cavity stays a cavity with the winding number as with the exact test (inward shell kept inward): {vols}")
    v, t = box_tris((0, 0, 0), (1, 1, 1))
    write_off(os.path.join(R, "double.off"), [(v, t + [(a, c, b) for a, b, c in t])])
    rep = os.path.join(R, "double.json")
    hexmesh(ctx, [os.path.join(R, "double.off")], [os.path.join(R, "double.vtu")], ["-q", "--size", "0.25"], rep)
    j = json.load(open(rep))
    check(j["repair"]["sheet_triangles"] == 0 and abs(j["volume"] - 0.875 ** 3) < 1e-12,
          f"a closed surface exported double-sided is a solid, not a sheet (volume {j['volume']})")
    # a hollow tank, each shell with a hole: the cavity, reached only through the wall, is cut off
    ov, ot = box_tris((0, 0, 0), (4, 4, 4))
    iv, it = box_tris((1, 1, 1), (3, 3, 3), inward=True)
    # holes in the outer top and in the inner bottom: the cavity is reached only through the wall
    write_off(os.path.join(R, "tank.off"), [(ov, ot[:-1]), (iv, it[:8] + it[9:])])
    case = os.path.join(R, "tank_case")
    rep = os.path.join(R, "tank.json")
    r = hexmesh(ctx, [os.path.join(R, "tank.off")], [case], ["--box", "-1,-1,-1,5,5,5", "--size", "0.5",
                                                           "--surface-size", "0.25", "--region", "seed:-0.9,-0.9,-0.9",
                                                           "--no-fill-holes"], rep)
    j = json.load(open(rep))
    cut = sum(l["cut_off_cells"] for l in j["leaks"])
    check(len(j["leaks"]) >= 1 and cut > 0 and "reachable only through it" in r.stderr,
          f"tank: {len(j['leaks'])} leak(s), {cut} cavity cells cut off with them")
    rc = run(["checkMesh", "-case", case], env=dict(os.environ, WM_PROJECT_DIR="/usr/share/openfoam"))
    check("Number of regions: 1 " in rc.stdout or "Number of regions: 1\n" in rc.stdout,
          "tank: the mesh is one region (checkMesh)")
    # patch names: regex applied once, no empty names, unique names, repeated file names
    rep = os.path.join(R, "names.json")
    hexmesh(ctx, [os.path.join(D, "cube.off")], [os.path.join(R, "names.vtu")], ["-q", "--patch-name", "(.*)=w_$1"], rep)
    names = [p["name"] for p in json.load(open(rep))["patches"]]
    check(names == ["w_xmin", "w_xmax", "w_ymin", "w_ymax", "w_zmin", "w_zmax", "w_cube"], f"--patch-name '(.*)=w_$1': {names}")
    r = run([args.hexmesh, os.path.join(D, "cube.off"), "-o", os.path.join(R, "empty_name.vtu"), "--patch-name", "cube=$2"])
    check(r.returncode == 1 and "empty name" in r.stderr, f"an empty patch name is a usage error (exit {r.returncode})")
    write_obj(os.path.join(R, "xmin.obj"), *box_quads_obj((0, 0, 0), (1, 1, 1), "xmin"))
    os.makedirs(os.path.join(R, "a")); os.makedirs(os.path.join(R, "b"))
    write_off(os.path.join(R, "a", "part.off"), [box_tris((0, 0, 0), (1, 1, 1))])
    write_off(os.path.join(R, "b", "part.off"), [box_tris((2, 0, 0), (3, 1, 1))])
    rep = os.path.join(R, "unique.json")
    case = os.path.join(R, "unique_case")
    hexmesh(ctx, [os.path.join(R, "xmin.obj"), os.path.join(R, "a", "part.off"), os.path.join(R, "b", "part.off")], [case],
            ["-q", "--size", "0.25"], rep)
    names = [p["name"] for p in json.load(open(rep))["patches"]]
    check(names[6:] == ["xmin_2", "part", "part_2"], f"unique patch names: group 'xmin' and two files part.off -> {names[6:]}")
    r = run([args.hexmesh, os.path.join(D, "cube.off"), "-o", os.path.join(R, "x" * 300 + ".vtu")])
    check(r.returncode in (1, 3) and r.stderr.startswith("hexmesh: "), f"an impossible output name: exit {r.returncode}, no crash")

    # 8a. feature pillows on closed curves: a tube (radii 0.5 and 0.25, height 0.6, 96 segments)
    # has four convex circular rims, two of them around its bore; their chains run 1.5 to 2 local
    # sizes off the rims before snapping, too far for an open curve's pillow, near enough for a
    # loop's (`choose_pillows()`): pillowed, no chain turns inside a face and the rims are exact
    # (at s = 0.06: 0.02 / 0.02 s both ways, 0.24 / 0.27 without pillows; min scaled Jacobian 0.643)
    print("[feature pillows on closed curves]")
    nseg, tube_v, tube_t = 96, [], []
    def tube_ring(r, z):
        tube_v.extend((r * math.cos(2 * math.pi * k / nseg), r * math.sin(2 * math.pi * k / nseg), z) for k in range(nseg))
        return len(tube_v) - nseg
    def tube_strip(a, b):   # quads between rings a and b, oriented a -> b counter-clockwise
        for k in range(nseg):
            a0, a1, b0, b1 = a + k, a + (k + 1) % nseg, b + k, b + (k + 1) % nseg
            tube_t.extend([(a0, a1, b1), (a0, b1, b0)])
    rings_out = [tube_ring(0.5, 0.1 * i) for i in range(7)]
    rings_in = [tube_ring(0.25, 0.1 * i) for i in range(7)]
    top = [rings_out[6]] + [tube_ring(0.5 - 0.25 * i / 3, 0.6) for i in (1, 2)] + [rings_in[6]]
    bottom = [rings_out[0]] + [tube_ring(0.5 - 0.25 * i / 3, 0.0) for i in (1, 2)] + [rings_in[0]]
    for i in range(6):
        tube_strip(rings_out[i], rings_out[i + 1])
        tube_strip(rings_in[i + 1], rings_in[i])
    for i in range(3):
        tube_strip(top[i], top[i + 1])
        tube_strip(bottom[i + 1], bottom[i])
    write_off(os.path.join(R, "tube.off"), [(tube_v, tube_t)])
    tube = {}
    for name, extra in (("pillows", []), ("no_pillows", ["--no-feature-pillows"])):
        rep = os.path.join(R, f"tube_{name}.json")
        hexmesh(ctx, [os.path.join(R, "tube.off")], [os.path.join(R, f"tube_{name}.vtu")], ["-q", "--surface-size", "0.06"] + extra, rep,
                body_fitted=True)
        tube[name] = json.load(open(rep))
    tj, tn = tube["pillows"], tube["no_pillows"]
    ts = tj["fidelity"]["surface_size"]
    tf, tfn = tj["feature_fidelity"], tn["feature_fidelity"]
    check(tj["repair"]["sheet_triangles"] == 0 and tj["features"]["curves"] == 4 and tj["boundary"]["curves_captured"] == 4,
          f"tube: four rims found and captured ({tj['features']['curves']}, {tj['boundary']['curves_captured']})")
    check(tj["boundary"]["pillow_cells"] > 0 and tj["boundary"]["curve_turns"] == 0 and tn["boundary"]["pillow_cells"] == 0,
          f"tube: the rims pillowed ({tj['boundary']['pillow_cells']} cells, none with --no-feature-pillows), no turn "
          f"left ({tj['boundary']['curve_turns']})")
    check(max(tf["input_to_mesh"], tf["mesh_to_input"]) <= 0.1 * ts and
          max(tf["input_to_mesh"], tf["mesh_to_input"]) * 4 <= max(tfn["input_to_mesh"], tfn["mesh_to_input"]),
          f"tube: feature fidelity {tf['input_to_mesh'] / ts:.2f} / {tf['mesh_to_input'] / ts:.2f} x surface size "
          f"<= 0.1 and a quarter of that without pillows ({tfn['input_to_mesh'] / ts:.2f} / {tfn['mesh_to_input'] / ts:.2f})")
    check(tj["quality"]["scaled_jacobian"]["min"] >= 0.3 and tj["fidelity"]["faces_beyond_quarter_surface_size"] == 0,
          f"tube: min scaled Jacobian {tj['quality']['scaled_jacobian']['min']:.3f} >= 0.3, no face beyond s/4 "
          f"({tj['fidelity']['faces_beyond_quarter_surface_size']})")
    # where the capture with pillows leaves faces beyond a quarter surface size (cylinder at 0.9
    # times its default surface size: some of its rims' pillow vertices stop short of the surface,
    # 68 far faces), the capture without pillows runs on the same grid and is kept (none), before
    # any staircase retry
    rep = os.path.join(R, "cylinder_09.json")
    hexmesh(ctx, [os.path.join(D, "cylinder.off")], [os.path.join(R, "cylinder_09.vtu")], ["-q", "--surface-size", "0.0225"],
            rep, body_fitted=True)
    cj = json.load(open(rep))
    cb, cc = cj["boundary"], cj["boundary"]["captures"]
    check(len(cc) == 2 and cb["staircase_tries"] == 1 and cc[0]["feature_pillows"] and cc[0]["evaluated"] and
          cc[0]["far_faces"] > 0 and cc[0]["cells_below_0_3"] == 0 and not cc[1]["feature_pillows"] and cc[1]["kept"] and
          cc[1]["far_faces"] == 0 and cb["capture_choice"] == 1 and cb["pillow_cells"] == 0 and
          cj["fidelity"]["faces_beyond_quarter_surface_size"] == 0 and cj["quality"]["scaled_jacobian"]["min"] >= 0.3,
          f"cylinder at surface size 0.0225: captures {[(c['feature_pillows'], c.get('far_faces'), c['kept']) for c in cc]}, "
          f"{cb['staircase_tries']} staircase(s), {cj['fidelity']['faces_beyond_quarter_surface_size']} faces beyond s/4, "
          f"min scaled Jacobian {cj['quality']['scaled_jacobian']['min']:.3f}")
    # where every face beyond s/4 stands over a part or gap thinner than two surface sizes (fin_slot's
    # 0.01-wide slot and fin at cells of 0.0197: 4 faces at the slot's end, whatever the staircase),
    # the mesh is not made again with the staircase closer; at twice that size one of its far faces
    # is elsewhere and the closer staircases run
    for size, thin in (("0.019724667297574376", True), ("0.039449334595148752", False)):
        rep_ = os.path.join(R, f"fin_slot_{size}.json")
        hexmesh(ctx, [os.path.join(D, "fin_slot.off")], [os.path.join(R, f"fin_slot_{size}.vtu")],
                ["-q", "--size", size, "--surface-size", size], rep_, body_fitted=True)
        fj = json.load(open(rep_))
        fb, ff = fj["boundary"], fj["fidelity"]["faces_beyond_quarter_surface_size"]
        check(fb["far_faces_over_thin_parts"] == thin and (fb["staircase_tries"] == 1) == thin and
              len(fb["staircases"]) == fb["staircase_tries"] and fb["staircases"][0]["far_faces"] > 0 and
              fj["quality"]["scaled_jacobian"]["min"] >= 0.3 and (not thin or 0 < ff <= 10),
              f"fin_slot at size {size}: far faces over thin parts only {fb['far_faces_over_thin_parts']} (expected {thin}), "
              f"{fb['staircase_tries']} staircase(s), {ff} faces beyond s/4, min scaled Jacobian "
              f"{fj['quality']['scaled_jacobian']['min']:.3f}")

    # 8a. sheets: two sides, two patches (OpenFOAM baffles), oriented consistently
    print("[sheets: each side its own patch]")
    ang = math.radians(20)
    su, sv = np.array([math.cos(ang), 0, math.sin(ang)]), np.array([0, 1, 0.05])   # an oblique plane
    so = np.array([0, 0, 0.5])
    sn = np.cross(su, sv)
    plate_area = 1.44 * np.linalg.norm(sn)
    sn /= np.linalg.norm(sn)
    nq = 8
    sverts = [tuple(so + (-0.6 + 1.2 * i / nq) * su + (-0.6 + 1.2 * j / nq) * sv) for i in range(nq + 1) for j in range(nq + 1)]
    stris = []
    for i in range(nq):
        for j in range(nq):
            p0, q0 = i * (nq + 1) + j, (i + 1) * (nq + 1) + j
            stris += [(p0, q0, q0 + 1), (p0, q0 + 1, p0 + 1)]   # normal su x sv
    rev = lambda t: (t[0], t[2], t[1])
    # (a) as the motorBike has them: the faces in one part, their reversed copies in a '-shadow' part;
    # (b) both copies in one part, the first copy of every other pair the reversed one
    write_obj(os.path.join(W, "plate.obj"), sverts, [("plate", stris), ("plate-shadow", [rev(t) for t in stris])])
    mixed = []
    for k, t in enumerate(stris):
        mixed += [t, rev(t)] if k % 2 == 0 else [rev(t), t]
    write_obj(os.path.join(W, "plate_mixed.obj"), sverts, [("plate", mixed)])

    def plate_side(c, g):   # faces over the plate, away from its rim: which side is the cell on?
        d = c - so
        if abs(np.dot(d, su)) > 0.6 - 0.125 or abs(np.dot(d, sv)) / np.dot(sv, sv) > 0.6 - 0.125:
            return None
        return float(np.dot(g - so, sn))
    for stem, back, flipped, extra in (("plate", "plate-shadow", 0, []), ("plate_mixed", "plate_back", 64, []),
                                       ("plate_mixed", "plate_back", 64, ["--staircase"])):
        label = stem + (" (staircase)" if extra else "")
        case = os.path.join(W, stem + ("_st" if extra else "") + "_case")
        rep = os.path.join(W, stem + ("_st" if extra else "") + ".json")
        hexmesh(ctx, [os.path.join(W, stem + ".obj")], [case],
                ["-q", "--box", "-1,-1,0,1,1,1", "--size", "0.25", "--surface-size", "0.0625", "--region", "seed:0.9,0.9,0.9"] + extra,
                rep, body_fitted=True)
        j = json.load(open(rep))
        r = j["repair"]
        check(r["sheet_triangles"] == 128 and r["sheet_reoriented"] == flipped and r["sheet_back_parts"] == (back == "plate_back"),
              f"{label}: 128 sheet faces, {flipped} flipped to the sheet's orientation, back part {back} ({r})")
        sides = patch_sides(case, plate_side)
        front, behind = sides.get("plate"), sides.get(back)
        check(front is not None and behind is not None and front[4] > 100 and behind[4] > 100 and front[2] > 0 and behind[3] < 0,
              f"{label}: every face over the plate has its cell on its patch's side: 'plate' above "
              f"({front[4] if front else 0} faces, cell centroids {front[2] if front else 0:.4f}..{front[3] if front else 0:.4f} "
              f"from the plane), '{back}' below ({behind[4] if behind else 0} faces, {behind[2] if behind else 0:.4f}.."
              f"{behind[3] if behind else 0:.4f})")
        check(front is not None and behind is not None and min(front[1], behind[1]) >= 0.95 * plate_area,
              f"{label}: each side covers the plate (areas {front[1] if front else 0:.3f} and {behind[1] if behind else 0:.3f}, "
              f"plate {plate_area:.3f})")
        rc = run(["checkMesh", "-case", case, "-allTopology"], env=dict(os.environ, WM_PROJECT_DIR="/usr/share/openfoam"))
        check(rc.returncode == 0 and "Mesh OK" in rc.stdout, f"{label}: checkMesh -allTopology: Mesh OK")
        if not extra:   # the buffer wraps round the rim: its cap vertices go onto the rim where they can
            fi, bd = j["fidelity"], j["boundary"]
            # (233 and 0.427 while no cell could fall below 0.35 for them, 203 and 0.284 at 0.2,
            # 186 and 0.279 with the joint moves)
            check(fi["cap_area"] < 0.3 and bd["cap_vertices"] < 200,
                  f"{label}: the cap round the rim shrinks ({bd['cap_vertices']} cap vertices, cap area {fi['cap_area']:.3f}; "
                  f"290 and 0.533 while no cap vertex moved onto the rim)")

    # 8a'. a body touching or crossing a box face: the hole in the box patch, the body's section,
    # the filled wedge (reported)
    print("[contacts with the box faces]")
    def write_cylinder(path, R, dip, n=64, L=1.0):   # lying on the ground along y, dipping below z = 0
        pts, tri = [], []
        for k in range(n):
            a = 2 * math.pi * k / n + math.pi / n   # a flat facet at the bottom
            pts += [(R * math.sin(a), -L, R - dip - R * math.cos(a)), (R * math.sin(a), L, R - dip - R * math.cos(a))]
        for k in range(n):
            a0, b0, a1, b1 = 2 * k, 2 * k + 1, 2 * ((k + 1) % n), 2 * ((k + 1) % n) + 1
            tri += [(a0, a1, b1), (a0, b1, b0), (2 * n, a0, a1), (2 * n + 1, b1, b0)]
        pts += [(0, -L, R - dip), (0, L, R - dip)]
        with open(path, "w") as f:
            f.write(f"OFF\n{len(pts)} {len(tri)} 0\n")
            f.writelines("%.17g %.17g %.17g\n" % p for p in pts)
            f.writelines("3 %d %d %d\n" % t for t in tri)
        # the section by z = 0: the polygon's width there (its facets crossing z = 0), times 2L
        xs = []
        for k in range(n):
            (x0, _, z0), (x1, _, z1) = pts[2 * k], pts[2 * ((k + 1) % n)]
            if (z0 < 0) != (z1 < 0):
                xs.append(x0 + (x1 - x0) * (0 - z0) / (z1 - z0))
        return (max(xs) - min(xs)) * 2 * L
    R_, h_ = 0.5, 0.0625
    section = write_cylinder(os.path.join(W, "cylinder_ground.off"), R_, 0.002)
    write_off(os.path.join(W, "box_ground.off"), [box_tris((-0.5, -0.5, -0.3), (0.5, 0.5, 0.5))])
    for stem, body in (("cylinder_ground", section), ("box_ground", 1.0)):
        case, rep = os.path.join(W, stem + "_case"), os.path.join(W, stem + ".json")
        hexmesh(ctx, [os.path.join(W, stem + ".off")], [case],
                ["-q", "--box", "-2,-2,0,2,2,2", "--size", "0.25", "--surface-size", str(h_), "--region", "seed:1.9,1.9,1.9"],
                rep, body_fitted=True)
        bc = json.load(open(rep))["box_contacts"]
        pts, faces, owner, nei, patches = read_poly(case)
        st, n = patches["zmin"]
        meshed = 0.0
        for f in range(st, st + n):
            P = pts[faces[f]]
            meshed += 0.5 * abs(sum(P[i][0] * P[(i + 1) % len(P)][1] - P[(i + 1) % len(P)][0] * P[i][1] for i in range(len(P))))
        c = bc["first_100"][0] if bc["first_100"] else None
        check(bc["contacts"] == 1 and c["patch"] == "zmin" and abs(c["area"] - (16 - meshed)) < 1e-9 * 16
              and all(f["unmeshed_area"] == 0 for f in bc["faces"] if f["patch"] != "zmin"),
              f"{stem}: one contact, on zmin; its area {c['area'] if c else 0:.6f} is what the zmin patch read back from "
              f"polyMesh leaves uncovered ({16 - meshed:.6f})")
        check(c is not None and abs(c["centre"][0]) < 0.02 and abs(c["centre"][1]) < 0.02,
              f"{stem}: the contact is under the body (centre {c['centre'] if c else None})")
        check(c is not None and abs(c["body_area"] - body) <= 0.25 * body,
              f"{stem}: the body's section {c['body_area'] if c else 0:.4f} (sampled) is the exact one {body:.4f} within 25%")
        if stem == "cylinder_ground":
            # the wedge thinner than the local size is filled, and only it: the gap under a cylinder
            # is about x^2 / 2R, so the hole reaches |x| <= sqrt(2 R gap)
            reach = max(-c["bbox"][0], c["bbox"][3])
            check(c["filled_area"] > 0.5 and 0.5 * h_ <= c["max_gap"] <= 1.5 * h_ and reach <= math.sqrt(2 * R_ * 1.5 * h_),
                  f"{stem}: a wedge of {c['filled_area']:.3f} filled, up to {c['max_gap'] / h_:.2f} x the surface size thick, "
                  f"reaching |x| = {reach:.3f} (gap {reach * reach / (2 * R_) / h_:.2f} x surface size)")
        else:
            check(c["filled_area"] <= 0.02 * c["area"], f"{stem}: a wall crossing the ground leaves nothing filled "
                  f"({c['filled_area']:.2g} of {c['area']:.4f})")
        rc = run(["checkMesh", "-case", case, "-allTopology"], env=dict(os.environ, WM_PROJECT_DIR="/usr/share/openfoam"))
        check(rc.returncode == 0 and "Mesh OK" in rc.stdout, f"{stem}: checkMesh -allTopology: Mesh OK")

    # 8b. features: detected, reported, refined along; user lines
    print("[features]")
    lines = os.path.join(W, "lines.obj.gz")
    with gzip.open(lines, "wt") as f:
        f.write("v -0.3 0 0\nv 0.3 0 0\nl 1 2\n")
    rep = os.path.join(W, "features.json")
    hexmesh(ctx, [os.path.join(D, "fandisk.off")], [os.path.join(W, "features.vtu")],
            ["-q", "--size", "0.1", "--surface-size", "0.05", "--feature-size", "0.0125", "--features", lines], rep)
    j = json.load(open(rep))
    fe = j["features"]
    check(fe["sharp_edges"] == 722 and fe["corners"] == 25 and fe["curves"] == 35 and fe["user_lines"] == 1,
          f"fandisk: 722 sharp edges, 35 curves, 25 corners, 1 user line reported ({fe})")
    rep0 = os.path.join(W, "features0.json")
    hexmesh(ctx, [os.path.join(D, "fandisk.off")], [os.path.join(W, "features0.vtu")],
            ["-q", "--size", "0.1", "--surface-size", "0.05"], rep0)
    j0 = json.load(open(rep0))
    check(j["grid"]["max_level"] == j0["grid"]["max_level"] + 2 and j["grid"]["leaf_cells"] > j0["grid"]["leaf_cells"],
          f"--feature-size 0.0125 refines two levels below the surface size 0.05 (max level {j0['grid']['max_level']} -> "
          f"{j['grid']['max_level']}, leaves {j0['grid']['leaf_cells']} -> {j['grid']['leaf_cells']})")
    r = run([args.hexmesh, os.path.join(D, "fandisk.off"), "-o", os.path.join(W, "x.vtu"), "--features",
             os.path.join(W, "missing.obj"), "--feature-size", "0.1"])
    check(r.returncode == 2 and "missing.obj: cannot open" in r.stderr, "a missing feature-line file is an input error")
    # soft creases: a prism of 16 flat sides (22.5 degrees between them, below the feature angle)
    # meshed at a tenth of its radius: crossing the creases its faces cut under them (volume short
    # by 0.0095 of the prism's 8 sin(22.5 deg) x 2 = 6.1229); following them (--soft-crease-angle
    # 15: 16 crease lines of 4 edges, ending at 32 corners on the rims) it keeps to the facets
    nside, rows = 16, 4
    pv = [(math.cos(2 * math.pi * i / nside), math.sin(2 * math.pi * i / nside), -1 + 2 * r / rows)
          for r in range(rows + 1) for i in range(nside)] + [(0, 0, -1), (0, 0, 1)]
    pid = lambda r, i: r * nside + i % nside
    pt = [t for r in range(rows) for i in range(nside)
          for t in ((pid(r, i), pid(r, i + 1), pid(r + 1, i + 1)), (pid(r, i), pid(r + 1, i + 1), pid(r + 1, i)))]
    pt += [(len(pv) - 2, pid(0, i + 1), pid(0, i)) for i in range(nside)]
    pt += [(len(pv) - 1, pid(rows, i), pid(rows, i + 1)) for i in range(nside)]
    write_obj(os.path.join(W, "prism.obj"), pv, [("prism", pt)])
    exact = nside / 2 * math.sin(2 * math.pi / nside) * 2
    js = {}
    for tag, extra in (("plain", []), ("soft", ["--soft-crease-angle", "15"])):
        rep = os.path.join(W, f"prism_{tag}.json")
        hexmesh(ctx, [os.path.join(W, "prism.obj")], [os.path.join(W, f"prism_{tag}.vtu")],
                ["-q", "--surface-size", "0.1"] + extra, rep, body_fitted=True)
        js[tag] = json.load(open(rep))
    fs, fp = js["soft"]["features"], js["plain"]["features"]
    check(fs["soft_crease_edges"] == 64 and fs["soft_crease_edges_left_out"] == 0 and fs["corners"] == 32 and
          fs["curves"] == 48 and fp["soft_crease_edges"] == 0 and fp["corners"] == 0,
          f"prism: 64 soft crease edges on 16 curves, 32 corners with --soft-crease-angle 15, none without ({fs})")
    err = {t: abs(js[t]["volume"] - exact) for t in js}
    check(err["soft"] < 0.5 * err["plain"] and js["soft"]["quality"]["scaled_jacobian"]["min"] > 0.3,
          f"prism: the mesh following its soft creases keeps closer to it (volume off by {err['soft']:.3g}, "
          f"{err['plain']:.3g} crossing them; min scaled Jacobian {js['soft']['quality']['scaled_jacobian']['min']:.3f})")

    # 8. reports: JSON with histograms and worst cells; self-contained HTML with SVG
    print("[reports]")
    rj, rh = os.path.join(W, "rep.json"), os.path.join(W, "rep.html")
    hexmesh(ctx, [os.path.join(D, "anchor.off")], [os.path.join(W, "rep.vtu")], ["-q", "--report", rj], rh)
    j = json.load(open(rj))
    hist = j["quality"].get("histograms", {})
    for k in ("scaled_jacobian", "non_orthogonality", "skewness", "aspect_ratio", "face_warpage"):
        h = hist.get(k)
        check(h is not None and len(h["counts"]) > 1, f"histogram of {k}")
    if "scaled_jacobian" in hist:
        check(sum(hist["scaled_jacobian"]["counts"]) == j["counts"]["cells"], "the scaled Jacobian histogram counts every cell")
    check(len(j["quality"].get("worst_cells", [])) > 0, "worst cells listed")
    html = open(rh).read()

    class P(HTMLParser):
        def __init__(self):
            super().__init__()
            self.tags = []
        def handle_starttag(self, tag, attrs):
            self.tags.append(tag)
    p = P()
    p.feed(html)
    check("svg" in p.tags and "script" not in p.tags and "http" not in html.split("xmlns")[0],
          f"HTML report: {p.tags.count('svg')} inline SVGs, no script, no external resource")
    svgs = re.findall(r"<svg.*?</svg>", html, re.S)
    ok = True
    for s in svgs:
        try:
            ET.fromstring(s)
        except ET.ParseError:
            ok = False
    check(svgs and ok, f"every SVG of the HTML report parses as XML ({len(svgs)})")
    polys = len(re.findall(r"[M]-?\d", html))
    check(polys > 100, f"the slices draw the cells ({polys} polygons)")

    # N. body-fitted boundary (buffer layer, projection, feature snapping, untangling) on every
    # surface of the test data, at the sizes of BODY_FITTED_SIZES (data/MANIFEST.md)
    print("[body-fitted boundary on every test surface]")
    env = dict(os.environ, WM_PROJECT_DIR="/usr/share/openfoam")
    features_of = {}
    far_causes_verified = {}   # cause -> far faces whose cause the VTU confirms
    for name in sorted(os.listdir(D)):
        if not name.endswith(".off"):
            continue
        stem = name[:-4]
        case = os.path.join(W, "bf_" + stem)
        rep = os.path.join(W, "bf_" + stem + ".json")
        hexmesh(ctx, [os.path.join(D, name)], [case, case + ".vtu"], ["-q"] + BODY_FITTED_SIZES.get(stem, []), rep,
                body_fitted=True)
        if not os.path.exists(rep):
            continue
        j = json.load(open(rep))
        q, fi, topo = j["quality"], j["fidelity"], j["topology"]
        sj = q["scaled_jacobian"]["min"]
        s_ = fi["surface_size"]
        # valid, and no cell below 0.02: the capture removes buffer cells it cannot raise above
        # that, and the grid cells start square and may not fall below 0.2 (the goals: 0.3, 65 deg)
        no = q["non_orthogonality"]["max"]
        check(sj >= 0.02 and no < 80, f"{stem}: {j['counts']['cells']} cells, min scaled Jacobian {sj:.3g} >= 0.02, "
                                      f"max non-orthogonality {no:.1f} < 80 deg")
        if stem in MIN_SJ_03:
            check(sj >= 0.3, f"{stem}: min scaled Jacobian {sj:.3g} >= 0.3 (the goal)")
        b_ = j["boundary"]
        retried = stem in CAPTURE_RETRIED
        check(b_["capture_choice"] < b_["capture_tries"] and (b_["capture_tries"] > 1) == retried,
              f"{stem}: {b_['capture_tries']} capture(s) run (more than one: {retried}), setting {b_['capture_choice']} kept")
        if stem in CORNER_EDGES_KEPT:
            check(b_["corner_edge_searches"] >= 1, f"{stem}: the paths searched again with the corners' edges kept "
                                                    f"({b_['corner_edge_searches']} time(s) in the capture kept)")
        s_retried = stem in STAIRCASE_RETRIED
        check((b_["staircase_tries"] > 1) == s_retried and b_["staircase_tries"] <= 5 and not b_["far_faces_over_thin_parts"] and
              b_["staircase_gap"] in (0.4, 0.25, 0.2) and (s_retried or b_["staircase_gap"] == 0.4),
              f"{stem}: {b_['staircase_tries']} mesh(es) made (more than one: {s_retried}), the one with the staircase "
              f"{b_['staircase_gap']} cell sizes off the surface kept")
        # the report's log of the captures and staircases agrees with the counts above, and the kept
        # ones with the mesh written (its cells; its minimum scaled Jacobian, where the retries
        # evaluated it, as computed here from the VTU's points: the report's qualities are those
        # of the OpenFOAM case's points when one is asked, the hanging nodes bulged, eight 0.350 ->
        # 0.327)
        mv_ = meshio.read(case + ".vtu")
        vsj_ = vtu_min_sj(mv_)
        caps_, st_ = b_["captures"], b_["staircases"]
        kept_st = [i for i, x in enumerate(st_) if x["kept"]]
        ok_ = len(st_) == b_["staircase_tries"] and len(kept_st) == 1 and sum(x["captures"] for x in st_) == len(caps_)
        mine_, kept_c = [], []
        if ok_:
            ks = st_[kept_st[0]]
            first_ = sum(x["captures"] for x in st_[:kept_st[0]])
            mine_ = caps_[first_:first_ + ks["captures"]]
            kept_c = [c for c in mine_ if c["kept"]]
            ok_ = (ks["gap"] == b_["staircase_gap"] and len(mine_) == b_["capture_tries"] and len(kept_c) == 1 and
                   kept_c[0]["choice"] == b_["capture_choice"] and kept_c[0]["cells"] == j["counts"]["cells"] and
                   all(c["staircase_gap"] == ks["gap"] for c in mine_) and
                   (not (ks["evaluated"] or kept_c[0]["evaluated"]) or
                    all(not r_["evaluated"] or abs(r_["min_scaled_jacobian"] - vsj_) < 1e-9 for r_ in (ks, kept_c[0]))) and
                   (not (ks["evaluated"] and kept_c[0]["evaluated"]) or ks["far_faces"] == kept_c[0]["far_faces"]))
        check(ok_, f"{stem}: the log of {len(caps_)} capture(s) and {len(st_)} staircase(s) agrees with the counts and the "
                   f"mesh (kept capture {kept_c[0] if kept_c else None})")
        # the report's qualities are the case's points' (hanging nodes bulged) where the mesh has
        # hanging nodes; its scaled Jacobian on the mesh's points, and the VTU's cell data, are
        # those of the VTU's own points (numpy, from its points and hexahedra)
        vtu_data_ = float(np.min(np.concatenate([d for cb, d in zip(mv_.cells, mv_.cell_data["scaled_jacobian"])
                                                 if cb.type == "hexahedron"])))
        hanging_ = j["counts"]["hanging_nodes"] > 0
        mp_ = q["mesh_points_scaled_jacobian"]["min"]
        check(q["measured_on"] == ("openfoam_case_points" if hanging_ else "mesh_points") and
              abs(mp_ - vsj_) < 1e-9 and abs(vtu_data_ - vsj_) < 1e-9 and (hanging_ or mp_ == sj),
              f"{stem}: qualities measured on {q['measured_on']} (min {sj:.4f}); on the mesh's points min {mp_:.4f}, "
              f"the VTU's cell data {vtu_data_:.4f}, its points {vsj_:.4f}")
        # the report's seconds per phase: a phase run once per mesh made is summed, so the phases
        # together take no longer than the whole run, and most of it (0.92 to 0.99 of it on the 15
        # files; where the last mesh's phases overwrote the others', bunny's came to 0.25 of it)
        sec_ = j["seconds"]
        parts_ = sum(v for k, v in sec_.items() if k != "total")
        check(0.8 * sec_["total"] <= parts_ <= sec_["total"] * 1.001 + 0.01,
              f"{stem}: the phases' seconds sum to {parts_:.2f} s, 0.8 to 1 times the total {sec_['total']:.2f} s")
        def once_run(tag, opts):   # one capture, the default weights (no retries)
            rep0 = os.path.join(W, "bf_" + stem + "_" + tag + ".json")
            case0 = os.path.join(W, "bf_" + stem + "_" + tag)
            hexmesh(ctx, [os.path.join(D, name)], [case0 + ".vtu", case0], ["-q"] + opts, rep0, body_fitted=True)
            return json.load(open(rep0)), case0

        def all_geometry_ok(case_):
            rg = run(["checkMesh", "-case", case_, "-allTopology", "-allGeometry"], env=env)
            flags = [l.strip() for l in rg.stdout.splitlines() if l.strip().startswith("***")]
            return rg.returncode == 0 and "Mesh OK" in rg.stdout and not flags, flags

        if stem == "bunny":
            # at the default sizes (its ears lost or half kept), a cell below 0.3 starts the
            # retries: without them, one capture, no better
            jd, _ = once_run("default", [])
            j0, _ = once_run("once", ["--capture-retry-cells", "0"])
            sj0, sjd = j0["quality"]["scaled_jacobian"]["min"], jd["quality"]["scaled_jacobian"]["min"]
            once = j0["boundary"]["capture_tries"] == 1 and j0["boundary"]["capture_choice"] == 0 and \
                j0["boundary"]["staircase_tries"] == 1
            check(once and sj0 < 0.3 <= sjd and jd["boundary"]["staircase_tries"] > 1,
                  f"{stem}: --capture-retry-cells 0 captures once ({j0['boundary']['capture_tries']}), minimum {sj0:.3f} "
                  f"(< 0.3; {sjd:.3f} with the retries, {jd['boundary']['staircase_tries']} meshes made)")
            # with 5 cells across its thin parts (its ears) none of the four captures is free of
            # cells concave for OpenFOAM or at faces failing the tet decomposition: the one kept
            # (a retry) runs a fifth time, with the removal
            # (at 6 smoothing sweeps: at the default 8 one capture is free of them; at 12, since the
            # feature paths are searched again with the curves left short first, the first capture
            # is kept, 2 cells removed). The retries'
            # budget of 100,000 cells allows three retries of its ~27,400 cells, not a fourth: no
            # staircase retry although the mesh kept has faces beyond s/4 (with the default budget
            # of 200,000 a staircase retry runs and its first capture is kept, 2 cells removed)
            j5, case5 = once_run("thin5", ["--thin-cells", "5", "--smoothing-sweeps", "6", "--capture-retry-cells", "100000"])
            b5, q5 = j5["boundary"], j5["quality"]
            ok5, flags5 = all_geometry_ok(case5)
            check(b5["capture_tries"] == 5 and b5["capture_choice"] > 0 and b5["foam_fault_cells"] > 0 and
                  q5["concave_cells"] == 0 and q5["face_tet_errors"] == 0 and ok5,
                  f"{stem} --thin-cells 5: {b5['capture_tries']} captures (5: the kept one again), kept choice "
                  f"{b5['capture_choice']} (> 0), {b5['foam_fault_cells']} buffer cell(s) removed at OpenFOAM faults "
                  f"(> 0), checkMesh -allGeometry: Mesh OK (flags: {flags5})")
            far5 = j5["fidelity"]["faces_beyond_quarter_surface_size"]
            check(b5["staircase_tries"] == 1 and far5 > 0 and 20000 < j5["counts"]["cells"] <= 33333,
                  f"{stem} --thin-cells 5 --capture-retry-cells 100000: {b5['staircase_tries']} staircase (1: the budget "
                  f"is spent, {j5['counts']['cells']} cells a capture, although {far5} faces are beyond s/4)")
        if stem == "cube_nonmanifold":
            # with 3 cells across its thin parts, its first capture without pillows has a cell
            # concave for OpenFOAM (every cell above 0.3): with the retries another capture has none
            # and no buffer cell goes; without them, the one capture removes the buffer cells
            # checkMesh -allGeometry would flag (with pillows, the one capture falls to 0.284)
            # (at 12 smoothing sweeps: at the default 8 the retries keep the first capture)
            # (every cell above 0.3 until the joint moves of released vertices, which may take a
            # neighbour's cell down to 0.25: 0.265 since)
            # (since the feature paths are searched again with the curves left short first, the
            # retries that avoid the fault are the staircase's: one capture each, 0.303, no cell
            # removed)
            j1, _ = once_run("thin3", ["--thin-cells", "3", "--smoothing-sweeps", "12"])
            j0, case0 = once_run("thin3_once", ["--thin-cells", "3", "--capture-retry-cells", "0", "--no-feature-pillows",
                                                "--smoothing-sweeps", "12"])
            sj0 = j0["quality"]["scaled_jacobian"]["min"]
            once = j0["boundary"]["capture_tries"] == 1 and j0["boundary"]["capture_choice"] == 0
            c0, c1 = j0["quality"]["concave_cells"], j1["quality"]["concave_cells"]
            r0, r1 = j0["boundary"]["foam_fault_cells"], j1["boundary"]["foam_fault_cells"]
            check(once and r0 > 0 and sj0 >= 0.25 and c0 == 0 and j0["quality"]["face_tet_errors"] == 0 and
                  (j1["boundary"]["capture_tries"] > 1 or j1["boundary"]["staircase_tries"] > 1) and c1 == 0 and r1 == 0,
                  f"{stem} --thin-cells 3: --capture-retry-cells 0 captures once ({j0['boundary']['capture_tries']}), "
                  f"minimum {sj0:.3f} (>= 0.25), and removes {r0} buffer cell(s) at OpenFOAM faults (> 0), leaving {c0} "
                  f"concave cells and {j0['quality']['face_tet_errors']} faces failing the tet decomposition; with the "
                  f"retries ({j1['boundary']['capture_tries']} captures, {j1['boundary']['staircase_tries']} staircases) "
                  f"{c1} concave, {r1} removed")
            ok0, flags0 = all_geometry_ok(case0)
            check(ok0, f"{stem} --thin-cells 3: once, with those cells removed: checkMesh -allGeometry: Mesh OK (flags: {flags0})")
        if stem == "anchor":
            # the buffer cells removed at OpenFOAM faults may take some of the fine cells on a face
            # split in four: the coarse cell's face still runs through an edge midpoint no cell
            # uses any more, which the capture must keep (it dropped it, and the writer stopped:
            # "internal error: Polyhedral_mesh_3: a split face lacks an edge midpoint"); with
            # feature cells at s/4 and this box, two such midpoints near (0.39, 0.137, -0.37)
            jm, casem = once_run("midpoints", ["--capture-retry-cells", "0", "--surface-size", "0.025",
                                               "--feature-size", "0.00625", "--box",
                                               "-0.55,-0.3625,-0.48,0.55,0.3604,0.48"])
            rm_ = run(["checkMesh", "-case", casem, "-allTopology"], env=env)
            check(jm["boundary"]["removed_buffer_cells"] > 0 and rm_.returncode == 0 and "Mesh OK" in rm_.stdout,
                  f"{stem} with feature cells at s/4 and a box: written ({jm['counts']['cells']} cells, "
                  f"{jm['boundary']['removed_buffer_cells']} buffer cells removed, > 0), checkMesh -allTopology: Mesh OK")
        if stem in MIN_SJ_FLOOR:
            check(sj >= MIN_SJ_FLOOR[stem], f"{stem}: min scaled Jacobian {sj:.3g} >= {MIN_SJ_FLOOR[stem]} (no regression; the goal is 0.3)")
        if stem in NON_ORTHO_65:
            check(no <= 65, f"{stem}: max non-orthogonality {no:.1f} <= 65 deg (the goal)")
        rc = run(["checkMesh", "-case", case, "-allTopology"], env=env)
        std_flags = [l.strip() for l in rc.stdout.splitlines() if l.strip().startswith("***")]
        # no flag at all: buffer cells at faces skewed beyond 3.5 are removed by the mesher
        check(rc.returncode == 0 and ("Mesh OK" in rc.stdout),
              f"{stem}: checkMesh -allTopology: Mesh OK (flags: {std_flags})")
        rg = run(["checkMesh", "-case", case, "-allTopology", "-allGeometry"], env=env)
        flags = [l.strip() for l in rg.stdout.splitlines() if l.strip().startswith("***")]
        print(f"  reported: {stem}: -allGeometry flags {flags}")
        # split faces at 2:1 transitions are written with a slight convex roof: no cell is
        # concave for OpenFOAM there (without it: cube 2032, cylinder 1116, fin_slot 450 cells);
        # the report counts the concave cells as checkMesh does (an independent computation)
        m = [re.search(r"number of cells: (\d+)", f) for f in flags if "Concave cells" in f]
        foam_concave = int(m[0].group(1)) if m and m[0] else 0
        check(q["concave_cells"] == foam_concave,
              f"{stem}: the report's concave cells ({q['concave_cells']}) are checkMesh's ({foam_concave})")
        m = [re.search(r"face tets: (\d+) faces", f) for f in flags if "face tets" in f]
        foam_face_tets = int(m[0].group(1)) if m and m[0] else 0
        check(q["face_tet_errors"] == foam_face_tets,
              f"{stem}: the report's faces failing the tet decomposition ({q['face_tet_errors']}) are checkMesh's ({foam_face_tets})")
        # and its cell determinants ("wellposedness": over each cell's internal faces) as checkMesh
        # prints them; cells below 0.001 are flagged (motorBike: one buffer cell, now removed)
        m = re.search(r"Cell determinant \(wellposedness\) : minimum: (\S+) average: (\S+)", rg.stdout)
        det_min, det_mean = (float(m.group(1)), float(m.group(2))) if m else (None, None)
        check(m is not None and abs(q["cell_determinant"]["min"] - det_min) <= 1e-9 * max(1.0, det_min) and
              abs(q["cell_determinant"]["mean"] - det_mean) <= 1e-9 * max(1.0, det_mean),
              f"{stem}: the report's cell determinant min / mean ({q['cell_determinant']['min']:.12g} / "
              f"{q['cell_determinant']['mean']:.12g}) are checkMesh's ({det_min} / {det_mean})")
        m = [re.search(r"number of cells: (\d+)", f) for f in flags if "small determinant" in f]
        foam_small = int(m[0].group(1)) if m and m[0] else 0
        check(q["small_determinant_cells"] == foam_small,
              f"{stem}: the report's cells of small determinant ({q['small_determinant_cells']}) are checkMesh's ({foam_small})")
        if stem in GEOMETRY_OK:
            check(rg.returncode == 0 and "Mesh OK" in rg.stdout and not flags,
                  f"{stem}: checkMesh -allGeometry: Mesh OK (flags: {flags})")
        if stem in NO_CONCAVE_CELLS:
            concave = [f for f in flags if "Concave cells" in f]
            check(not concave, f"{stem}: no concave cell under checkMesh -allGeometry ({concave})")
        # fidelity: faces on the surface (mean), components and Euler characteristic
        # faces capping holes (nearest input point on a border edge) are counted apart
        open_input = topo["input"]["boundary_edges"] > 0
        if stem == "elephant-with-holes":
            check(fi["cap_faces"] > 0 and fi["cap_area"] > 0,
                  f"{stem}: the holes are capped: {fi['cap_faces']} cap faces, area {fi['cap_area']:.4g}")
        if not open_input:
            check(fi["cap_faces"] == 0, f"{stem}: closed input, no cap face ({fi['cap_faces']})")
        if stem == "fandisk_crack":   # its border edges run along each other: a crack, not a hole
            check(fi["cap_faces"] == 0 and j["boundary"]["cap_vertices"] == 0,
                  f"{stem}: the crack is not capped ({fi['cap_faces']} cap faces, {j['boundary']['cap_vertices']} cap vertices)")
        features_of[stem] = dict(j["features"], input_boundary_edges=topo["input"]["boundary_edges"])
        check(fi["mesh_to_input_mean"] <= 0.2 * s_,
              f"{stem}: mean distance of boundary faces to the input {fi['mesh_to_input_mean'] / s_:.3f} x surface size <= 0.2 "
              f"(max {fi['mesh_to_input_max'] / s_:.2f}, input->mesh max {fi['input_to_mesh_max'] / s_:.2f}; "
              f"{fi['cap_faces']} cap faces excluded)")
        # the figures, reported per file (its goals: no face beyond 0.25 x surface size,
        # feature curves within 0.25 x and corners within 0.1 x both ways)
        ff = j["feature_fidelity"]
        sz = lambda x: "inf" if x is None else f"{x / s_:.2f}"
        print(f"  reported: {stem}: faces beyond 0.25 / 0.5 / 1 x surface size: "
              f"{fi['faces_beyond_quarter_surface_size']} / {fi['faces_beyond_half_surface_size']} / "
              f"{fi['faces_beyond_surface_size']} of {fi['surface_faces']}; features input->mesh {sz(ff['input_to_mesh'])}, "
              f"mesh->input {sz(ff['mesh_to_input'])} (within {ff['within_tolerance']['tolerance_degrees']:g} degrees: "
              f"{sz(ff['within_tolerance']['input_to_mesh'])} / {sz(ff['within_tolerance']['mesh_to_input'])}), "
              f"worst corner {sz(ff['max_corner_distance'])} x surface size")
        if stem in FEATURE_FIDELITY_FLOOR:
            lim_i, lim_m = FEATURE_FIDELITY_FLOOR[stem]
            check(ff["input_to_mesh"] is not None and ff["mesh_to_input"] is not None and
                  ff["input_to_mesh"] <= lim_i * s_ and ff["mesh_to_input"] <= lim_m * s_,
                  f"{stem}: feature fidelity {sz(ff['input_to_mesh'])} / {sz(ff['mesh_to_input'])} x surface size, "
                  f"within {lim_i} / {lim_m} (no regression; the goal is 0.25)")
        if stem in FEATURE_FIDELITY_TOLERANT_FLOOR:
            lim_i, lim_m = FEATURE_FIDELITY_TOLERANT_FLOOR[stem]
            ft = ff["within_tolerance"]
            check(ft["tolerance_degrees"] == 10 and ft["input_to_mesh"] is not None and ft["mesh_to_input"] is not None and
                  ft["input_to_mesh"] <= min(lim_i * s_, ff["input_to_mesh"]) and
                  ft["mesh_to_input"] <= min(lim_m * s_, ff["mesh_to_input"]),
                  f"{stem}: feature fidelity within 10 degrees {sz(ft['input_to_mesh'])} / {sz(ft['mesh_to_input'])} x "
                  f"surface size, within {lim_i} / {lim_m} and no more than the strict figures")
        check(fi["faces_beyond_surface_size"] <= fi["faces_beyond_half_surface_size"] <= fi["faces_beyond_quarter_surface_size"]
              <= fi["surface_faces"] and (fi["faces_beyond_quarter_surface_size"] == 0) == (fi["mesh_to_input_max"] <= 0.25 * s_),
              f"{stem}: the counts of far faces agree with the largest face distance")
        # why the faces beyond 1/4 stand off: the causes count them all, and each listed face is
        # found in the VTU (read by meshio) with its cause recomputed there: a hanging corner is a
        # vertex flagged hanging, another corner one that is not (a cap's corner only on an open
        # input), a centre is a surface quad's vertex average, folded beyond 30 degrees along a
        # diagonal or not (bent)
        causes = fi["far_face_causes"]
        listed = fi["farthest_faces"]
        check(sum(causes.values()) == fi["faces_beyond_quarter_surface_size"] and
              len(listed) == min(50, fi["faces_beyond_quarter_surface_size"]) and
              all(a["distance"] >= b["distance"] for a, b in zip(listed, listed[1:])) and
              all(f["distance"] > 0.25 * s_ and f["cause"] in causes for f in listed),
              f"{stem}: far faces by cause {causes} sum to the {fi['faces_beyond_quarter_surface_size']} beyond 0.25 x surface "
              f"size, {len(listed)} listed farthest first")
        if listed:
            mv = meshio.read(case + ".vtu")
            X = mv.points
            hang = mv.point_data["hanging"]
            quads = np.concatenate([cb.data[cd >= 6] for cb, cd in zip(mv.cells, mv.cell_data["patch"]) if cb.type == "quad"])
            centres = X[quads].mean(axis=1)
            corner_ids = np.unique(quads)
            tol = 1e-9 * float(np.linalg.norm(X.max(axis=0) - X.min(axis=0)))

            def fold_of(q):
                a, b, c, d = X[q]
                ang = lambda u, w: math.degrees(math.acos(max(-1.0, min(1.0, float(np.dot(u, w)) / (float(np.linalg.norm(u) * np.linalg.norm(w)) or 1.0)))))
                return max(ang(np.cross(b - a, c - a), np.cross(c - a, d - a)), ang(np.cross(b - a, d - a), np.cross(c - b, d - b)))
            bad = []
            for f in listed:
                p = np.array(f["at"])
                if f["cause"] in ("hanging_corner", "cap_corner", "corner"):
                    at = np.nonzero(np.linalg.norm(X[corner_ids] - p, axis=1) <= tol)[0]
                    ok = len(at) > 0 and any(bool(hang[corner_ids[i]]) == (f["cause"] == "hanging_corner") for i in at)
                    ok = ok and (f["cause"] != "cap_corner" or topo["input"]["boundary_edges"] > 0)
                else:
                    at = np.nonzero(np.linalg.norm(centres - p, axis=1) <= tol)[0]
                    ok = any((fold_of(quads[i]) > 30) == (f["cause"] == "folded") and abs(fold_of(quads[i]) - f["fold"]) < 1e-6
                             for i in at)
                if ok:
                    far_causes_verified[f["cause"]] = far_causes_verified.get(f["cause"], 0) + 1
                else:
                    bad.append(f)
            check(not bad, f"{stem}: the {len(listed)} listed far faces have the cause the VTU gives them (wrong: {bad[:2]})")
        if stem in NO_FACE_BEYOND_SURFACE_SIZE:
            check(fi["faces_beyond_surface_size"] == 0,
                  f"{stem}: no boundary face farther than the surface size from the input (farthest "
                  f"{fi['mesh_to_input_max'] / s_:.2f} x)")
        if stem in NO_FACE_BEYOND_QUARTER_SURFACE_SIZE:
            check(fi["faces_beyond_quarter_surface_size"] == 0,
                  f"{stem}: no boundary face farther than a quarter of the surface size from the input (farthest "
                  f"{fi['mesh_to_input_max'] / s_:.2f} x)")
        if stem in FAR_FACES_AT_MOST:
            check(fi["faces_beyond_quarter_surface_size"] <= FAR_FACES_AT_MOST[stem],
                  f"{stem}: {fi['faces_beyond_quarter_surface_size']} boundary faces farther than a quarter of the surface "
                  f"size from the input, at most {FAR_FACES_AT_MOST[stem]} (no regression; the goal is none)")
        check(stem in NO_FACE_BEYOND_QUARTER_SURFACE_SIZE or stem in FAR_FACES_AT_MOST,
              f"{stem}: has a far-face figure to meet (none, or a ceiling in FAR_FACES_AT_MOST)")
        if stem in FIDELITY_MOVES:
            check(j["boundary"]["fidelity_moves"] > 0, f"{stem}: the fidelity polish moved vertices ({j['boundary']['fidelity_moves']})")
        if stem in NO_FACE_BEYOND_HALF_SURFACE_SIZE:
            check(fi["faces_beyond_half_surface_size"] == 0,
                  f"{stem}: no boundary face farther than half the surface size from the input (farthest "
                  f"{fi['mesh_to_input_max'] / s_:.2f} x)")
        b = j["boundary"]
        if stem in LOOSENED:
            check(b["loosened_vertices"] > 0, f"{stem}: {b['loosened_vertices']} feature vertices loosened (expected some)")
        if stem in UNSNAPPED_AT_MOST:
            check(b["feature_joint_moves"] > 0 and b["unsnapped_vertices"] <= UNSNAPPED_AT_MOST[stem],
                  f"{stem}: {b['feature_joint_moves']} unsnapped feature vertices put back in joint moves, "
                  f"{b['unsnapped_vertices']} still off their feature (at most {UNSNAPPED_AT_MOST[stem]})")
        check(len(b["missed_curves_first_100"]) == min(100, b["curves_missed"]) and
              len(b["curve_turns_first_100"]) == min(100, b["curve_turns"]) and
              len(b["removed_buffer_cells_first_100"]) == min(100, b["removed_buffer_cells"]) and
              len(b["unsnapped_first_100"]) == min(100, b["unsnapped_vertices"]),
              f"{stem}: the report locates the {b['curves_missed']} missed curves, the {b['curve_turns']} chain turns, "
              f"the {b['removed_buffer_cells']} removed buffer cells and the {b['unsnapped_vertices']} unsnapped vertices")
        if stem in INPUT_WITHIN_HALF_SURFACE_SIZE:
            check(fi["samples"] == 10000 and fi["input_to_mesh_max"] <= 0.5 * s_,
                  f"{stem}: the {fi['samples']} points sampled on the input within 0.5 x surface size of the mesh boundary "
                  f"(farthest {fi['input_to_mesh_max'] / s_:.2f} x)")
        if stem in SAME_TOPOLOGY:
            same = (topo["input"]["components"] == topo["mesh_boundary"]["components"] and
                    topo["input"]["euler_characteristic"] == topo["mesh_boundary"]["euler_characteristic"])
            check(same, f"{stem}: boundary has the input's components and Euler characteristic "
                        f"({topo['mesh_boundary']['components']}, {topo['mesh_boundary']['euler_characteristic']})")
    # (at these sizes: a hanging corner and corners on fandisk, cap corners on teapot, folded and
    # bent faces on the organic models)
    check(len(far_causes_verified) >= 3, f"far-face causes confirmed in the VTUs: {far_causes_verified} (at least 3 causes seen)")
    # a crack through a smooth surface is no feature: fandisk_crack's curves are fandisk's (its
    # open edges left are one side of the creases the crack runs along)
    if "fandisk" in features_of and "fandisk_crack" in features_of:
        fc, fd = features_of["fandisk_crack"], features_of["fandisk"]
        check(fc["curves"] == fd["curves"] and fc["seam_edges_left_out"] > 0 and fc["seam_bridges"] > 0 and
              fc["input_open_edges"] == fc["input_boundary_edges"] and fc["open_edges"] < fc["input_open_edges"] / 10,
              f"fandisk_crack: {fc['curves']} feature curves, fandisk's {fd['curves']} ({fc['seam_edges_left_out']} open edges "
              f"left out of {fc['input_open_edges']}, {fc['seam_bridges']} curve ends joined across the crack)")

    print()
    if FAILURES:
        print(f"{len(FAILURES)} checks failed:")
        for f in FAILURES:
            print("  -", f)
        sys.exit(1)
    print("all dirty-input checks passed")


if __name__ == "__main__":
    main()
