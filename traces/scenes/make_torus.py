#!/usr/bin/env python3
"""Writes torus.obj: the OBJ mesh shipped with the scenes (traces/scenes/README.md).

A torus around the y axis (major radius 1, minor radius 0.4, centred on the origin) as 48 x 24
quads with exact per-vertex normals (`f v//vn`), so that glint's OBJ path, its normal handling and
its polygon splitting are exercised by a shipped scene. Run: python3 make_torus.py > torus.obj
"""
import math

MAJOR, MINOR, RING, TUBE = 1.0, 0.4, 48, 24


def fmt(v):
    s = "%.6f" % v
    return "0.000000" if s == "-0.000000" else s


print("# A torus: major radius %g, minor radius %g, %d x %d quads; written by make_torus.py"
      % (MAJOR, MINOR, RING, TUBE))
for i in range(RING):
    a = 2 * math.pi * i / RING
    for j in range(TUBE):
        b = 2 * math.pi * j / TUBE
        n = (math.cos(b) * math.cos(a), math.sin(b), math.cos(b) * math.sin(a))
        c = (MAJOR * math.cos(a), 0.0, MAJOR * math.sin(a))
        print("v " + " ".join(fmt(c[k] + MINOR * n[k]) for k in range(3)))
        print("vn " + " ".join(fmt(x) for x in n))
for i in range(RING):
    for j in range(TUBE):
        quad = [(i, j), (i, j + 1), (i + 1, j + 1), (i + 1, j)]
        ids = [(p % RING) * TUBE + (q % TUBE) + 1 for p, q in quad]
        print("f " + " ".join("%d//%d" % (k, k) for k in ids))
