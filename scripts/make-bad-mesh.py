#!/usr/bin/python3
"""Writes a scene: a 12 x 12 grid (1 cm, one diagonal per cell, anchors) whose springs are rods
of one material (kappa_ij = kappa * h / l_ij), with two nodes squeezed against a neighbour: the
few bad elements of docs/worked-example.md. --fixed writes the same mesh with them in place.
Usage: make-bad-mesh.py OUT.toml [--fixed]"""
import math
import sys

n, h = 12, 1.0
bad = {(4, 7): (0.95, 0.0), (8, 3): (0.0, 0.95)}  # node -> how far it is moved towards a neighbour
out, fixed = sys.argv[1], "--fixed" in sys.argv[2:]
pos = {}
for a in range(n):
    for b in range(n):
        dx, dz = (0.0, 0.0) if fixed else bad.get((a, b), (0.0, 0.0))
        pos[(a, b)] = ((a + dx) * h, 0.0, (b + dz) * h)
index = {k: i for i, k in enumerate(sorted(pos))}
lines = ['name = "%s"' % ("bad-mesh-fixed" if fixed else "bad-mesh"),
         'description = "12 x 12 rods of one material%s"' % ("" if fixed else ", two squeezed nodes"),
         "watch = %d" % index[(6, 6)], ""]
for k in sorted(pos):
    lines += ["[[node]]", "x = [%r, %r, %r]" % pos[k], "anchor_scale = 1", ""]
for (a, b) in sorted(pos):
    for (c, d) in ((a + 1, b), (a, b + 1), (a + 1, b + 1)):
        if (c, d) in pos:
            l = math.dist(pos[(a, b)], pos[(c, d)])
            lines += ["[[spring]]", "nodes = [%d, %d]" % (index[(a, b)], index[(c, d)]),
                      "kappa_scale = %r" % (h / l), ""]
lines += ["[params]", "m = 0.001", "kappa = 0.1", "zeta = 1", "dt = 0.01", "",
          "[[perturb]]", "node = %d" % index[(6, 6)], "displacement = [0.0, 0.5, 0.0]", "",
          "[protocol]", "max_iterations = 2000", ""]
open(out, "w").write("\n".join(lines))
