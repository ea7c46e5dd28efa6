# Meshes as they come: a Kuhn-split cube (8 nodes, 6 tetrahedra) written by Debian's
# python3-meshio with every other tetrahedron's corners swapped loads in every mesh format that
# has tetrahedra (Gmsh 2.2 and 4.1, ASCII and binary; VTK; TetGen) as the same model as the
# consistently oriented cube: the same springs, |V| masses and stiffnesses. The count of
# reoriented tetrahedra is said once on stderr. A zero-volume tetrahedron stays an error naming
# the file and the line.
. "$(dirname "$0")/lib.inc"

PY3=/usr/bin/python3
if ! "$PY3" -c "import meshio" 2>/dev/null; then
  echo "python3-meshio absent: skipped"
  finish
  exit $?
fi
"$PY3" - "$WORK" <<'PY' 2>/dev/null || bad "meshio could not write the cubes"
import sys, meshio, numpy as np
d = sys.argv[1]
p = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
idx = lambda x, y, z: 4 * x + 2 * y + z
tets = []  # Kuhn: one tetrahedron per path 0 -> 7 along the axes
import itertools
for perm in itertools.permutations(range(3)):
    c, path = [0, 0, 0], [0]
    for a in perm:
        c[a] = 1
        path.append(idx(*c))
    tets.append(path)
tets = np.array(tets)
vol = lambda t: np.linalg.det(p[t[1:]] - p[t[0]]) / 6
pos = np.array([t if vol(t) > 0 else t[[0, 2, 1, 3]] for t in tets])
mixed = pos.copy()
mixed[1::2] = mixed[1::2][:, [0, 2, 1, 3]]  # 3 of 6 against the convention
assert sum(vol(t) < 0 for t in mixed) == 3
for name, t in (("pos", pos), ("mix", mixed)):
    m = meshio.Mesh(p, [("tetra", t)])
    meshio.write(f"{d}/{name}-a22.msh", m, file_format="gmsh22", binary=False)
    meshio.write(f"{d}/{name}-b22.msh", m, file_format="gmsh22", binary=True)
    meshio.write(f"{d}/{name}-a41.msh", m, file_format="gmsh", binary=False)
    meshio.write(f"{d}/{name}-b41.msh", m, file_format="gmsh", binary=True)
    meshio.write(f"{d}/{name}.vtk", m, binary=False)
    meshio.write(f"{d}/{name}-t.node", m, file_format="tetgen")
flat = p.copy()
flat[7] = [0.5, 0.5, 0.0]  # node 7 into the plane z = 0 with 0, 2, 4: tetrahedron 0-4-6-7 is flat
m = meshio.Mesh(flat, [("tetra", mixed)])
meshio.write(f"{d}/flat.vtk", m, binary=False)
PY

scene() {  # scene FILE OUT: geometric masses and stiffnesses, no anchors, node 7 pulled
  printf '[mesh]\nfile = "%s"\nanchors = false\ndensity = 2\nyoung = 3\n[[perturb]]\nnode = 0\ndisplacement = [0, 0.1, 0]\n' "$1" >"$2"
}
for f in a22.msh b22.msh a41.msh b41.msh .vtk t.node; do
  scene "pos$([ "${f#.}" = "$f" ] && echo - || true)$f" "$WORK/pos.toml"
  scene "mix$([ "${f#.}" = "$f" ] && echo - || true)$f" "$WORK/mix.toml"
  expect_exit 0 "$DB" bounds "$WORK/pos.toml" || continue
  want=$(printf '%s' "$OUT" | grep -v '^scene')
  [ -z "$ERR" ] && ok || bad "$f: a consistently oriented cube said something: $ERR"
  expect_exit 0 "$DB" bounds "$WORK/mix.toml" || continue
  expect_match "$OUT" '8 nodes, 19 springs, 0 anchors' "mixed $f loads as the cube"
  expect_one_line "$ERR" "mixed $f: the note"
  expect_match "$ERR" "mix.*: note: 3 of 6 tetrahedra list their corners in the other orientation" \
    "mixed $f: the count said"
  got=$(printf '%s' "$OUT" | grep -v '^scene')
  [ "$got" = "$want" ] && ok || bad "mixed $f: bounds differ from the oriented cube's"
done

scene flat.vtk "$WORK/flat.toml"
expect_exit 2 "$DB" bounds "$WORK/flat.toml"
expect_one_line "$ERR" "flat tetrahedron"
expect_match "$ERR" "flat.vtk:[0-9]+: degenerate tetrahedron \(zero volume\)" "flat names file and line"
finish
