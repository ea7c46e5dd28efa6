#!/usr/bin/env python3
"""Writes scenes/meshes/tissue-cap.obj: a spherical cap (sphere radius 20 cm, 12 rings of 36
vertices around an apex at the origin, 0.03 rad apart), triangulated, normal +y at the apex.
The scene scenes/tissue-cap.toml loads it. Run from the repository root."""
import math

RS, RINGS, PER_RING, STEP = 20.0, 12, 36, 0.03
verts = [(0.0, 0.0, 0.0)]
for k in range(1, RINGS + 1):
    t = k * STEP
    for j in range(PER_RING):
        p = 2 * math.pi * j / PER_RING
        verts.append((RS * math.sin(t) * math.cos(p), RS * math.cos(t) - RS,
                      RS * math.sin(t) * math.sin(p)))


def ring(k, j):  # 1-based OBJ index of vertex j of ring k (k >= 1)
    return 2 + (k - 1) * PER_RING + j % PER_RING


faces = [(1, ring(1, j), ring(1, j + 1)) for j in range(PER_RING)]
for k in range(2, RINGS + 1):
    for j in range(PER_RING):
        a, b = ring(k - 1, j), ring(k - 1, j + 1)
        c, d = ring(k, j), ring(k, j + 1)
        faces += [(a, c, d), (a, d, b)]
with open("scenes/meshes/tissue-cap.obj", "w") as f:
    f.write("# dampbound: a spherical cap of soft tissue (scripts/make-cap-mesh.py)\n")
    for v in verts:
        f.write("v %.6f %.6f %.6f\n" % v)
    for t in faces:
        f.write("f %d %d %d\n" % t)
