#!/usr/bin/env python3
"""Writes the shipped tetrahedral tissue block and the quad cloth, and the small meshes the
tests and fuzz corpora use, reproducibly (no randomness, no third-party module).

  scripts/make-tissue-mesh.py            # scenes/meshes/tissue-block.msh, quad-cloth.obj,
                                         # tissue-slivers.msh
  scripts/make-tissue-mesh.py --small D  # one small block in every format under D/ (the
                                         # fuzz seeds: D = tests/fuzz/corpus; block.tetgen
                                         # joins .node, .ele, .face with lines "@@")
  scripts/make-tissue-mesh.py --block N D  # an N x N x N node block as TetGen files and a
                                         # scene, D/block-N.toml (docs/performance.md: the
                                         # 1M-node block is N = 100, about 1 GB of files)

The block is a structured grid of cubes, each split into the six tetrahedra of Kuhn's
(Freudenthal's) subdivision along its main diagonal, which conforms across cubes. Tetrahedra
are written with a positive signed volume (Gmsh's and VTK's convention). Regions: physical
volume 1 "tissue"; physical surface 2 "base" (the triangles of the face y = 0, to be fixed);
physical surface 3 "probe" (a square patch of the top face, to be pulled).
"""
import itertools
import os
import struct
import sys


def block(nx, ny, nz, h, patch):
    """Nodes, tetrahedra, base triangles and probe triangles of an nx x ny x nz node grid."""
    idx = lambda i, j, k: (i * ny + j) * nz + k
    nodes = [(i * h, j * h, k * h) for i in range(nx) for j in range(ny) for k in range(nz)]
    tets = []
    for i, j, k in itertools.product(range(nx - 1), range(ny - 1), range(nz - 1)):
        for perm in itertools.permutations(range(3)):
            c = [i, j, k]
            path = [idx(*c)]
            for axis in perm:
                c[axis] += 1
                path.append(idx(*c))
            a, b, d, e = (nodes[p] for p in path)
            u = [b[q] - a[q] for q in range(3)]
            v = [d[q] - a[q] for q in range(3)]
            w = [e[q] - a[q] for q in range(3)]
            det = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                   + u[2] * (v[0] * w[1] - v[1] * w[0]))
            if det < 0:
                path[2], path[3] = path[3], path[2]
            tets.append(path)

    def face(j, cells):  # triangles of the y = j*h face over the given (i, k) cells
        out = []
        for i, k in cells:
            a, b, c, d = idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j, k + 1), idx(i, j, k + 1)
            out += [[a, b, c], [a, c, d]]
        return out

    base = face(0, itertools.product(range(nx - 1), range(nz - 1)))
    ci, ck = (nx - 1) // 2, (nz - 1) // 2
    probe = face(ny - 1, [(i, k) for i in range(ci - patch, ci + patch)
                          for k in range(ck - patch, ck + patch)])
    return nodes, tets, base, probe


NAMES = [(3, 1, "tissue"), (2, 2, "base"), (2, 3, "probe")]


def msh41(nodes, tets, base, probe, binary=False):
    blocks = [(2, 2, 2, base), (2, 3, 2, probe), (3, 1, 4, tets)]  # (dim, entity, type, cells)
    out = bytearray(b"$MeshFormat\n4.1 %d 8\n" % binary)
    if binary:
        out += struct.pack("<i", 1) + b"\n"
    out += b"$EndMeshFormat\n$PhysicalNames\n3\n"
    out += b"".join(b'%d %d "%s"\n' % (d, t, n.encode()) for d, t, n in NAMES)
    out += b"$EndPhysicalNames\n$Entities\n"
    # Entities: surfaces 2 and 3 with physical tags 2 and 3, volume 1 with physical tag 1.
    ents = [(2, 2, 2), (2, 3, 3), (3, 1, 1)]
    if binary:
        out += struct.pack("<4Q", 0, 0, 2, 1)
        for _, tag, phys in ents:
            out += struct.pack("<i6dQiQ", tag, 0, 0, 0, 1, 1, 1, 1, phys, 0)
    else:
        out += b"0 0 2 1\n" + b"".join(b"%d 0 0 0 1 1 1 1 %d 0\n" % (t, p) for _, t, p in ents)
    out += b"$EndEntities\n$Nodes\n"
    n = len(nodes)
    if binary:
        out += struct.pack("<4Q", 1, n, 1, n) + struct.pack("<3iQ", 3, 1, 0, n)
        out += struct.pack("<%dQ" % n, *range(1, n + 1))
        out += b"".join(struct.pack("<3d", *p) for p in nodes)
    else:
        out += b"1 %d 1 %d\n3 1 0 %d\n" % (n, n, n)
        out += b"".join(b"%d\n" % (k + 1) for k in range(n))
        out += b"".join(b"%.17g %.17g %.17g\n" % p for p in nodes)
    out += b"\n$EndNodes\n$Elements\n" if binary else b"$EndNodes\n$Elements\n"
    total = sum(len(b[3]) for b in blocks)
    tag = 1
    if binary:
        out += struct.pack("<4Q", len(blocks), total, 1, total)
    else:
        out += b"%d %d 1 %d\n" % (len(blocks), total, total)
    for dim, ent, typ, cells in blocks:
        if binary:
            out += struct.pack("<3iQ", dim, ent, typ, len(cells))
        else:
            out += b"%d %d %d %d\n" % (dim, ent, typ, len(cells))
        for c in cells:
            if binary:
                out += struct.pack("<%dQ" % (len(c) + 1), tag, *[v + 1 for v in c])
            else:
                out += (" ".join(str(v) for v in [tag] + [v + 1 for v in c]) + "\n").encode()
            tag += 1
    out += b"\n$EndElements\n" if binary else b"$EndElements\n"
    return bytes(out)


def msh22(nodes, tets, base, probe, binary=False):
    groups = [(2, 2, base), (2, 3, probe), (4, 1, tets)]  # (type, physical, cells)
    out = bytearray(b"$MeshFormat\n2.2 %d 8\n" % binary)
    if binary:
        out += struct.pack("<i", 1) + b"\n"
    out += b"$EndMeshFormat\n$PhysicalNames\n3\n"
    out += b"".join(b'%d %d "%s"\n' % (d, t, n.encode()) for d, t, n in NAMES)
    out += b"$EndPhysicalNames\n$Nodes\n%d\n" % len(nodes)
    for k, p in enumerate(nodes):
        out += struct.pack("<i3d", k + 1, *p) if binary else b"%d %.17g %.17g %.17g\n" % (k + 1, *p)
    out += b"\n$EndNodes\n" if binary else b"$EndNodes\n"
    out += b"$Elements\n%d\n" % sum(len(g[2]) for g in groups)
    tag = 1
    for typ, phys, cells in groups:
        if binary:
            out += struct.pack("<3i", typ, len(cells), 2)
        for c in cells:
            vals = [tag, phys, phys] + [v + 1 for v in c]
            if binary:
                out += struct.pack("<%di" % len(vals), *vals)
            else:
                out += (" ".join(str(v) for v in [tag, typ, 2] + vals[1:]) + "\n").encode()
            tag += 1
    out += b"\n$EndElements\n" if binary else b"$EndElements\n"
    return bytes(out)


def tetgen(nodes, tets, base, probe):
    node = "# tissue block\n%d 3 0 0\n" % len(nodes)
    node += "".join("%d %.17g %.17g %.17g\n" % (k + 1, *p) for k, p in enumerate(nodes))
    ele = "%d 4 1\n" % len(tets)
    ele += "".join("%d %d %d %d %d 1\n" % (k + 1, *[v + 1 for v in t]) for k, t in enumerate(tets))
    faces = [(f, 2) for f in base] + [(f, 3) for f in probe]
    face = "%d 1\n" % len(faces)
    face += "".join("%d %d %d %d %d\n" % (k + 1, *[v + 1 for v in f], m)
                    for k, (f, m) in enumerate(faces))
    return node, ele, face


def vtk(nodes, tets, base, probe):
    cells = [(f, 5, 2) for f in base] + [(f, 5, 3) for f in probe] + [(t, 10, 1) for t in tets]
    out = "# vtk DataFile Version 4.2\ntissue block\nASCII\nDATASET UNSTRUCTURED_GRID\n"
    out += "POINTS %d double\n" % len(nodes)
    out += "".join("%.17g %.17g %.17g\n" % p for p in nodes)
    out += "CELLS %d %d\n" % (len(cells), sum(len(c) + 1 for c, _, _ in cells))
    out += "".join("%d %s\n" % (len(c), " ".join(map(str, c))) for c, _, _ in cells)
    out += "CELL_TYPES %d\n" % len(cells) + "".join("%d\n" % t for _, t, _ in cells)
    out += "CELL_DATA %d\nSCALARS region int 1\nLOOKUP_TABLE default\n" % len(cells)
    out += "".join("%d\n" % r for _, _, r in cells)
    return out


def slivers(nx, ny, nz, h, moved):
    """The block with a few top-face nodes moved 97/100 of the way towards their +x neighbour:
    the tetrahedra around each become slivers (short edges, little volume), which hold the
    whole mesh's step (scenes/tissue-slivers.toml, SPEC 11's mass scaling). A node moves along
    the face inside its star, which is convex, so every tetrahedron keeps a positive volume."""
    nodes, tets, base, probe = block(nx, ny, nz, h, 1)
    idx = lambda i, j, k: (i * ny + j) * nz + k
    for i, k in moved:
        x, y, z = nodes[idx(i, ny - 1, k)]
        nodes[idx(i, ny - 1, k)] = (x + 0.97 * h, y, z)
    for t in tets:
        a, b, d, e = (nodes[p] for p in t)
        u, v, w = ([q[r] - a[r] for r in range(3)] for q in (b, d, e))
        det = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
               + u[2] * (v[0] * w[1] - v[1] * w[0]))
        assert det > 0, "a sliver turned inside out"
    return nodes, tets, base, probe


def quad_cloth(n, h):
    out = "# a %d x %d quad cloth in the xz-plane, spacing %g cm\n" % (n, n, h)
    out += "".join("v %g 0 %g\n" % (a * h, b * h) for a in range(n) for b in range(n))
    q = lambda a, b: a * n + b + 1
    out += "".join("f %d %d %d %d\n" % (q(a, b), q(a + 1, b), q(a + 1, b + 1), q(a, b + 1))
                   for a in range(n - 1) for b in range(n - 1))
    return out


BLOCK_SCENE = """# An %(n)d x %(n)d x %(n)d node tetrahedral block (%(nodes)d nodes), written by
# scripts/make-tissue-mesh.py --block: the tissue block's cubes, 0.3 cm apart, Kuhn's six
# tetrahedra each; masses and stiffnesses from the geometry as in tissue-block.toml.
name = "block-%(n)d"
description = "Tetrahedral block (TetGen), %(nodes)d nodes, base fixed, a 2x2 patch pulled 5 mm"

[mesh]
file = "block-%(n)d.node"
anchors = false
density = 0.001
young = 100.0

[[mesh_region]]
tag = 2
fixed = true

[[mesh_region]]
tag = 3
displacement = [0.0, 0.5, 0.0]

[params]
m = 1.0
kappa = 1.0
gamma = 0.02
dt = 0.0002
policy = "fixed"

[protocol]
max_iterations = 100
"""


def write(path, data):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    if len(sys.argv) == 3 and sys.argv[1] == "--small":
        d = sys.argv[2]
        m = block(4, 3, 4, 0.5, 1)
        write(os.path.join(d, "msh", "block-22.msh"), msh22(*m))
        write(os.path.join(d, "msh", "block-22b.msh"), msh22(*m, binary=True))
        write(os.path.join(d, "msh", "block-41.msh"), msh41(*m))
        write(os.path.join(d, "msh", "block-41b.msh"), msh41(*m, binary=True))
        node, ele, face = tetgen(*m)
        write(os.path.join(d, "tetgen", "block.node"), node)
        write(os.path.join(d, "tetgen", "block.ele"), ele)
        write(os.path.join(d, "tetgen", "block.face"), face)
        write(os.path.join(d, "tetgen", "block.tetgen"), "\n@@\n".join((node, ele, face)))
        write(os.path.join(d, "vtk", "block.vtk"), vtk(*m))
        write(os.path.join(d, "obj", "cloth.obj"), quad_cloth(4, 0.5))
        return
    if len(sys.argv) == 4 and sys.argv[1] == "--block" and sys.argv[2].isdigit():
        n, d = int(sys.argv[2]), sys.argv[3]
        if n < 3:
            sys.exit("make-tissue-mesh.py: --block needs N >= 3")
        node, ele, face = tetgen(*block(n, n, n, 0.3, 1))
        for ext, text in (("node", node), ("ele", ele), ("face", face)):
            write(os.path.join(d, "block-%d.%s" % (n, ext)), text)
        write(os.path.join(d, "block-%d.toml" % n), BLOCK_SCENE % {"n": n, "nodes": n ** 3})
        return
    if len(sys.argv) != 1:
        sys.exit("usage: make-tissue-mesh.py [--small DIR | --block N DIR]")
    # 27 x 11 x 21 nodes, 0.3 cm apart: an 7.8 x 3 x 6 cm block, 6237 nodes, 31200 tetrahedra.
    write(os.path.join(root, "scenes", "meshes", "tissue-block.msh"),
          msh41(*block(27, 11, 21, 0.3, 1)))
    write(os.path.join(root, "scenes", "meshes", "quad-cloth.obj"), quad_cloth(20, 0.5))
    # 15 x 7 x 11 nodes, 0.3 cm apart, three top-face nodes moved (scenes/tissue-slivers.toml).
    write(os.path.join(root, "scenes", "meshes", "tissue-slivers.msh"),
          msh41(*slivers(15, 7, 11, 0.3, [(3, 2), (9, 7), (11, 3)])))


if __name__ == "__main__":
    main()
