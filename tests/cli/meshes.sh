# Mesh scenes and ParaView output: every format written by an independent writer (Debian's
# python3-meshio) loads as the same model; run --vtk writes a .vtu series and a .pvd that
# meshio reads back with the values the run reports in its --trace; bad mesh files fail on
# one line naming the file and line, and write nothing.
. "$(dirname "$0")/lib.inc"

# The tissue block: 6237 nodes, a series of every 20th step of the first 60.
expect_exit 0 "$DB" run "$SRC/scenes/tissue-block.toml" --max-iter 60 --vtk "$WORK/tissue" \
  --every 20 --trace "$WORK/tissue.csv" --verbose
expect_match "$OUT" 'scene +tissue-block \(6237 nodes, [0-9]+ springs, 0 anchors\)' "tissue run"
watched=$(printf '%s' "$OUT" | sed -nE 's/.*watched node ([0-9]+).*/\1/p')
for f in step_000000.vtu step_000020.vtu step_000040.vtu step_000060.vtu series.pvd; do
  [ -s "$WORK/tissue/$f" ] && ok || bad "missing $f"
done

# The quad cloth under the clamp policy: states vary (clamped, fixed, within), every step saved.
expect_exit 0 "$DB" run "$SRC/scenes/quad-cloth.toml" --policy clamp --gamma 0.0005 \
  --max-iter 30 --vtk "$WORK/cloth" --trace "$WORK/cloth.csv"

# Debian's python3 (where python3-meshio is installed) before any other on the PATH.
PY3=$(command -v /usr/bin/python3 || command -v python3 || true)
if [ -n "$PY3" ]; then
  "$PY3" - "$WORK" "$watched" <<'PY' && ok || bad "the VTU series does not read back with the run's values"
import csv, math, sys, xml.etree.ElementTree as ET
import meshio, numpy as np

work = sys.argv[1]
def check_series(name, watched, every, last):
    pvd = ET.parse(f"{work}/{name}/series.pvd").getroot()
    sets = pvd.findall("./Collection/DataSet")
    steps = [0] + list(range(every, last + 1, every))
    if steps[-1] != last:
        steps.append(last)
    assert [d.get("file") for d in sets] == [f"step_{k:06d}.vtu" for k in steps], sets
    rows = {int(r["iteration"]): r for r in csv.DictReader(open(f"{work}/{name}.csv"))}
    first = meshio.read(f"{work}/{name}/step_000000.vtu")
    rest = first.points - first.point_data["displacement"]  # X = x - (x - X)
    for d, k in zip(sets, steps):
        m = meshio.read(f"{work}/{name}/{d.get('file')}")
        # meshio keeps a column for one-component arrays: flatten those.
        pd = {k: v.ravel() if v.ndim == 2 and v.shape[1] == 1 else v for k, v in m.point_data.items()}
        cd = {k: v[0].ravel() for k, v in m.cell_data.items()}
        lines = m.cells_dict["line"]
        assert np.allclose(m.points - pd["displacement"], rest, rtol=0, atol=1e-12)
        # Strain from the points and the rest positions, independently of the writer.
        l = np.linalg.norm(m.points[lines[:, 1]] - m.points[lines[:, 0]], axis=1)
        l0 = np.linalg.norm(rest[lines[:, 1]] - rest[lines[:, 0]], axis=1)
        assert np.allclose(cd["strain"], (l - l0) / l0, rtol=1e-9, atol=1e-12)
        assert np.all(cd["stiffness"] > 0)
        state = pd["state"]
        assert set(np.unique(state)) <= {0, 1, 2, 3, 4}
        assert np.all(pd["effective_damping"][state == 4] == 0)
        assert math.isclose(float(d.get("timestep")), float(rows[k]["time"]) if k else 0.0)
        if k == 0:
            assert np.all(np.isinf(pd["upper"]))
            assert np.all(np.isinf(pd["safe"][state == 4])) and np.all(np.isfinite(pd["safe"][state != 4]))
            continue
        r = rows[k]  # --trace's row of this iteration: the watched node and the maximum
        disp = np.linalg.norm(pd["displacement"], axis=1)
        assert math.isclose(disp[watched], float(r["displacement"]), rel_tol=1e-12), (disp[watched], r)
        assert math.isclose(disp.max(), float(r["max_displacement"]), rel_tol=1e-12)
        assert math.isclose(pd["lower"][watched], float(r["lower_bound"]), rel_tol=1e-12)
        up = float(r["upper_bound"])
        assert math.isclose(pd["upper"][watched], up, rel_tol=1e-12) or (math.isinf(up) and np.isinf(pd["upper"][watched]))
        assert math.isclose(pd["effective_damping"][watched], float(r["gamma_effective"]), rel_tol=1e-12)
        sb = float(r["safe_bound"])  # SPEC 9's gamma_safe of the watched node, as --trace has it
        assert math.isclose(pd["safe"][watched], sb, rel_tol=1e-12) or (math.isinf(sb) and np.isinf(pd["safe"][watched]))
    return m, pd

tissue, tpd = check_series("tissue", int(sys.argv[2]), 20, 60)
lower = tpd["lower"]
assert lower.max() / lower.min() > 2, "geometric masses and stiffnesses give non-uniform bounds"
assert tissue.points.shape[0] == 6237
cloth, cpd = check_series("cloth", 210, 1, 30)
states = set(np.unique(cpd["state"]))
assert {1, 4} <= states, states  # clamped and fixed nodes in the cloth
print("vtk series read back:", len(tissue.points), "tissue nodes,", len(cloth.cells_dict["line"]), "cloth springs")
PY
else
  echo "python3 absent: the read-back is skipped"
fi

# Round trip through meshio's writers: Gmsh 2.2 and 4.1 (ASCII, binary), VTK 5.1, TetGen.
if [ -n "$PY3" ]; then
  mkdir -p "$WORK/rt"
  "$PY3" - "$SRC/tests/fuzz/corpus/vtk/block.vtk" "$WORK/rt" <<'PY' >/dev/null 2>&1 && ok || bad "meshio could not write the round-trip files"
import sys, meshio, numpy as np
m0 = meshio.read(sys.argv[1])
tets = m0.cells_dict["tetra"]
tag = np.where(m0.points[tets].mean(axis=1)[:, 0] < 0.5, 7, 1)  # cubes at x < 0.5 cm: tag 7
m = meshio.Mesh(m0.points, [("tetra", tets)], cell_data={"gmsh:physical": [tag], "gmsh:geometrical": [tag]})
d = sys.argv[2]
meshio.write(f"{d}/a22.msh", m, file_format="gmsh22", binary=False)
meshio.write(f"{d}/b22.msh", m, file_format="gmsh22", binary=True)
meshio.write(f"{d}/a41.msh", m, file_format="gmsh", binary=False)
meshio.write(f"{d}/b41.msh", m, file_format="gmsh", binary=True)
meshio.write(f"{d}/t.node", m, file_format="tetgen")
meshio.Mesh(m0.points, [("tetra", tets)], cell_data={"region": [tag]}).write(f"{d}/a.vtk", binary=False)
PY
  for f in a22.msh b22.msh a41.msh b41.msh a.vtk t.node; do
    # meshio's MSH 4.1 writer puts every tetrahedron in one entity and writes no $Entities,
    # so its 4.1 files carry no physical groups: there only the counts are compared.
    region='[[mesh_region]]\ntag = 7\nfixed = true\n'
    free=24
    case $f in *41.msh) region=''; free=48 ;; esac
    printf "[mesh]\nfile = \"%s\"\nanchors = false\n$region[[perturb]]\nnode = 47\ndisplacement = [0, 0.1, 0]\n" "$f" >"$WORK/rt/s.toml"
    expect_exit 0 "$DB" --digits 8 bounds "$WORK/rt/s.toml"
    expect_match "$OUT" '48 nodes, 197 springs, 0 anchors' "$f loads as the small block"
    expect_match "$OUT" "n = $free free nodes" "$f: its region 7 (the 24 nodes at x <= 0.5 cm) fixed"
  done
fi

# Bad mesh files: one line naming the mesh file and the line or byte, exit 2, nothing written.
cp "$SRC/scenes/quad-cloth.toml" "$WORK/bad.toml"
sed -i 's|meshes/quad-cloth.obj|bad.msh|' "$WORK/bad.toml"
printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n1 5 0 1 1 1 1 1 1 1 1\n$EndElements\n' >"$WORK/bad.msh"
expect_exit 2 "$DB" run "$WORK/bad.toml" --vtk "$WORK/none"
expect_one_line "$ERR" "bad mesh"
expect_match "$ERR" "bad.msh:10: unsupported element type 5 \(hexahedron\)" "bad mesh names file and line"
[ ! -e "$WORK/none" ] && ok || bad "a failed run wrote its output folder"
head -c 300 "$SRC/tests/fuzz/corpus/msh/block-41b.msh" >"$WORK/bad.msh"
expect_exit 2 "$DB" run "$WORK/bad.toml"
expect_match "$ERR" "bad.msh: byte [0-9]+: " "truncated binary names the byte"
sed -i 's|bad.msh|bad.vtk|' "$WORK/bad.toml"
cp "$SRC/scenes/meshes/quad-cloth.obj" "$WORK/bad.vtk"
expect_exit 2 "$DB" run "$WORK/bad.toml"
expect_match "$ERR" "bad.vtk:1: not a VTK legacy file" "wrong format"
expect_exit 2 "$DB" run "$SRC/scenes/quad-cloth.toml" --vtk "$WORK/cloth2" --every 0
finish
