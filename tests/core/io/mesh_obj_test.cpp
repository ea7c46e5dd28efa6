// OBJ surface meshes as mass-spring models (core/io/mesh_obj.hpp) and the scene's [mesh] table.
#include "core/io/mesh_obj.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/analysis/figures.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

/// The error message of parse_obj on `text` ("" when it parses).
std::string obj_error(const std::string& text) {
  return test::input_error([&] { parse_obj(text, "m.obj"); });
}

/// A unit square in the xz-plane as two triangles sharing the edge 0-2.
const char* kSquare =
    "# a square\n"
    "o square\n"
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 0 1\n"
    "v 0 0 1   # a comment\n"
    "vt 0 0\n"
    "vn 0 1 0\n"
    "usemtl skin\n"
    "f 1/1/1 2/1/1 3/1/1\n"
    "f -4//1 -2//1 -1//1\n";

TEST(MeshObj, ParsesVerticesAndFacesInEveryCornerForm) {
  const ObjMesh m = parse_obj(kSquare, "square.obj");
  ASSERT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.vertices[3], Vec3(0, 0, 1));
  ASSERT_EQ(m.faces.size(), 2u);
  EXPECT_EQ(m.faces[0], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(m.faces[1], (std::vector<int>{0, 2, 3}));  // negative: counted back from the last
}

TEST(MeshObj, BadFilesNameTheLine) {
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 x 0\n"), "m.obj:2: 'x' is not a finite number");
  EXPECT_EQ(obj_error("v 0 0\n"), "m.obj:1: a vertex needs 3 coordinates (v x y z)");
  EXPECT_EQ(obj_error("v 0 0 nan\n"), "m.obj:1: 'nan' is not a finite number");
  // The same numbers as every mesh reader (finite_number): no hex, no NUL inside a token.
  EXPECT_EQ(obj_error("v 0 0 0x1p3\n"), "m.obj:1: '0x1p3' is not a finite number");
  EXPECT_EQ(obj_error(std::string("v 0 0 1\0" "5\n", 10)),
            "m.obj:1: '1\\x005' is not a finite number");
  EXPECT_EQ(obj_error(std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\0" "9\n", 34)),
            "m.obj:4: face corner '3\\x009' has no vertex index");
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 0 0\nf 1 2\n"), "m.obj:3: a face needs at least 3 corners");
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
            "m.obj:4: face corner '4' refers to a vertex that does not exist (3 so far)");
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"),
            "m.obj:4: face corner '0' refers to a vertex that does not exist (3 so far)");
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -1\nf 1 /2 3\n"),
            "m.obj:5: face corner '/2' has no vertex index");
  EXPECT_EQ(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1\n"),
            "m.obj:4: a face uses the same vertex twice");
  EXPECT_EQ(obj_error("v 0 0 0\n"), "m.obj:1: the mesh has no face (f ...)");
}

TEST(MeshObj, EdgesOnceBendingSpringsAcrossSharedEdgesAnchorsAndScale) {
  const ObjMesh m = parse_obj(kSquare, "square.obj");
  MeshSprings how;
  how.scale = 2.0;
  ModelSpec plain = model_from_obj(m, how);
  ASSERT_EQ(plain.node_count(), 4);
  EXPECT_EQ(plain.rest[2], Vec3(2, 0, 2));
  // 0-1, 1-2, 2-0 then 2-3, 3-0: the shared edge once, in order of first appearance.
  ASSERT_EQ(plain.spring_count(), 5);
  EXPECT_EQ(plain.springs[2].i, 2);
  EXPECT_EQ(plain.springs[2].j, 0);
  EXPECT_DOUBLE_EQ(plain.springs[2].rest_length, 2 * std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(plain.springs[0].rest_length, 2.0);
  for (double a : plain.anchor_scale) EXPECT_EQ(a, 1.0);
  how.bend = true;
  how.anchors = false;
  ModelSpec bent = model_from_obj(m, how);
  ASSERT_EQ(bent.spring_count(), 6);  // + the far corners 1-3 across the shared edge 0-2
  EXPECT_EQ(std::min(bent.springs[5].i, bent.springs[5].j), 1);
  EXPECT_EQ(std::max(bent.springs[5].i, bent.springs[5].j), 3);
  for (double a : bent.anchor_scale) EXPECT_EQ(a, 0.0);
}

TEST(MeshObj, TissueCapScene) {
  const SceneSpec s = load_scene(test::source_path("scenes/tissue-cap.toml"));
  // A disc triangulation: V - E + F = 1, so E = 433 + 828 - 1 = 1260 edges, of which the 36
  // of the rim are on one triangle only: 1224 bending springs.
  EXPECT_EQ(s.model.node_count(), 433);
  EXPECT_EQ(s.model.spring_count(), 1260 + 1224);
  EXPECT_EQ(std::count(s.model.fixed.begin(), s.model.fixed.end(), 1), 36);
  EXPECT_EQ(s.model.anchor_count(), 0);
  EXPECT_EQ(s.perturbations.at(0).node, 0);
  EXPECT_FALSE(s.model.fixed[0]);
}

TEST(MeshObj, TissueCapFigureRunsAndItsLogAxis) {
  // The scene's three declared runs; one diverges, so the figure takes a log10 axis.
  const SceneSpec s = load_scene(test::source_path("scenes/tissue-cap.toml"));
  FigureData f = figure_scene(s);
  ASSERT_EQ(f.runs.size(), 3u);
  EXPECT_EQ(f.runs[0].result.outcome, Outcome::settled);  // a scene's figure: settled rule
  EXPECT_EQ(f.runs[0].result.first_entry, 1422);
  EXPECT_EQ(f.runs[2].result.outcome, Outcome::diverged);
  EXPECT_TRUE(f.log_y);
  EXPECT_DOUBLE_EQ(f.restore_threshold, 0.02);  // 1 % of the 2 cm pull
  SceneSpec calm = s;
  calm.runs.pop_back();
  calm.rules.max_iterations = 50;
  for (RunSpec& r : calm.runs) r.rules.max_iterations = 50;
  EXPECT_FALSE(figure_scene(calm).log_y);
}

TEST(MeshObj, SceneErrorsNameTheSceneOrTheMeshFile) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = dir + "mesh_scene.toml";
  auto error_of = [&](const std::string& toml) {
    std::ofstream(scene) << toml;
    try {
      load_scene(scene);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of("[mesh]\nfile = \"missing.obj\"\n"),
            scene + ":2: cannot read the mesh file: " + dir +
                "missing.obj: cannot open the file (No such file or directory)");
  std::ofstream(dir + "bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
  EXPECT_EQ(error_of("[mesh]\nfile = \"bad.obj\"\n"),
            dir + "bad.obj:4: face corner '9' refers to a vertex that does not exist (3 so far)");
  EXPECT_EQ(error_of("[mesh]\nfile = \"bad.obj\"\nbend = 1\n"),
            scene + ":3: bend must be true or false");
  EXPECT_EQ(error_of("[mesh]\nfiles = \"bad.obj\"\n"), scene + ":2: unknown key 'files' in [mesh]");
  EXPECT_EQ(error_of("[grid]\nnx = 2\nnz = 2\nspacing = 1\n[mesh]\nfile = \"bad.obj\"\n"),
            scene + ":1: a scene has one geometry: [grid], [[node]] or [mesh], not several");
  std::remove(scene.c_str());
  std::remove((dir + "bad.obj").c_str());
}

}  // namespace
}  // namespace dampbound
