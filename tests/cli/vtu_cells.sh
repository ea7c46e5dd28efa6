# ParaView sees the model: run --vtk writes the scene's mesh cells (tetrahedra of a Gmsh file,
# triangles and quads of OBJ files) after the springs, in the same piece over the same points,
# so the per-node arrays colour the volume and the surface. meshio reads both parts back: the
# line cells are the springs, the other cells those meshio itself reads from the mesh file
# (tetrahedra with a positive volume, whatever the file's orientation), and the Kuhn cube with
# mixed orientation comes out all positive.
. "$(dirname "$0")/lib.inc"

PY3=/usr/bin/python3
if ! "$PY3" -c "import meshio" 2>/dev/null; then
  echo "python3-meshio absent: skipped"
  finish
  exit $?
fi
for s in tissue-block quad-cloth tissue-cap; do
  expect_exit 0 "$DB" run "$SRC/scenes/$s.toml" --max-iter 2 --vtk "$WORK/$s" --every 1
done
"$PY3" - "$WORK" "$SRC" <<'PY' 2>&1 && ok || bad "the body cells do not read back"
import sys, meshio, numpy as np
work, src = sys.argv[1], sys.argv[2]
for scene, mesh_file, kind in (("tissue-block", "tissue-block.msh", "tetra"),
                               ("quad-cloth", "quad-cloth.obj", "quad"),
                               ("tissue-cap", "tissue-cap.obj", "triangle")):
    source = meshio.read(f"{src}/scenes/meshes/{mesh_file}")
    want = source.cells_dict[kind]
    for step in ("step_000000.vtu", "step_000002.vtu"):
        m = meshio.read(f"{work}/{scene}/{step}")
        blocks = [c.type for c in m.cells]
        assert blocks == ["line", kind], (scene, blocks)
        got = m.cells_dict[kind]
        assert got.shape == want.shape, (scene, got.shape, want.shape)
        # The same cells, corners maybe reordered (tetrahedra turned positive).
        assert sorted(map(tuple, np.sort(got, axis=1))) == sorted(map(tuple, np.sort(want, axis=1)))
        spring = m.cell_data["spring"]
        assert np.all(spring[0].ravel() == np.arange(len(m.cells_dict["line"])))
        assert np.all(spring[1].ravel() == -1)
        assert np.all(np.isnan(m.cell_data["strain"][1]))
        assert len(m.point_data["safe"]) == len(m.points)
        if kind == "tetra":
            p = m.points
            v = np.einsum("ij,ij->i", p[got[:, 1]] - p[got[:, 0]],
                          np.cross(p[got[:, 2]] - p[got[:, 0]], p[got[:, 3]] - p[got[:, 0]]))
            assert np.all(v > 0) or step != "step_000000.vtu", "tetrahedra written positive"
print("body cells read back")
PY

# The Kuhn cube with 3 of 6 tetrahedra flipped: written positive.
"$PY3" - "$WORK" <<'PY' 2>/dev/null || bad "meshio could not write the cube"
import sys, itertools, meshio, numpy as np
p = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
tets = []
for perm in itertools.permutations(range(3)):
    c, path = [0, 0, 0], [0]
    for a in perm:
        c[a] = 1
        path.append(4 * c[0] + 2 * c[1] + c[2])
    tets.append(path)
meshio.write(f"{sys.argv[1]}/cube.msh", meshio.Mesh(p, [("tetra", np.array(tets))]), file_format="gmsh22", binary=False)
PY
printf '[mesh]\nfile = "cube.msh"\n[[perturb]]\nnode = 0\ndisplacement = [0, 0.1, 0]\n' >"$WORK/cube.toml"
expect_exit 0 "$DB" run "$WORK/cube.toml" --max-iter 1 --vtk "$WORK/cube"
"$PY3" - "$WORK/cube/step_000000.vtu" <<'PY' 2>&1 && ok || bad "the cube's tetrahedra are not all positive"
import sys, meshio, numpy as np
m = meshio.read(sys.argv[1])
t, p = m.cells_dict["tetra"], m.points
v = np.einsum("ij,ij->i", p[t[:, 1]] - p[t[:, 0]], np.cross(p[t[:, 2]] - p[t[:, 0]], p[t[:, 3]] - p[t[:, 0]]))
assert len(t) == 6 and np.all(v > 0), v
PY
finish
