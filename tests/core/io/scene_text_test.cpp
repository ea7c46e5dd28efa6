// Hostile scene text (core/io/scene_text.cpp, and what core/io/scene_file.cpp checks with it): each
// case was a crash, a wrapped number or a passed-through control character once.
#include "core/io/scene_text.hpp"

#include <gtest/gtest.h>

#include <string>

#include "core/io/scene_file.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

const char* kGridText = "[grid]\nnx = 3\nnz = 3\nspacing = 1.0\n";

std::string text_error_of(const std::string& text) {
  return test::input_error([&] { parse_scene(text, "bad.toml"); });
}

bool starts(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

TEST(SceneText, DeepNestingIsRefusedBeforeTheParser) {
  // 40 000 dotted key parts overflowed toml++'s stack.
  std::string dotted = "a";
  for (int k = 0; k < 40000; ++k) dotted += ".a";
  EXPECT_EQ(text_error_of(dotted + " = 1\n"),
            "bad.toml:1: a dotted key or table name has more than 64 parts");
  std::string header = "[a";
  for (int k = 0; k < 70; ++k) header += ".a";
  EXPECT_TRUE(starts(text_error_of(std::string(kGridText) + header + "]\n"), "bad.toml:5: a dotted key"));
  const std::string deep = "x = " + std::string(100000, '[') + std::string(100000, ']') + "\n";
  EXPECT_EQ(text_error_of(deep), "bad.toml:1: arrays, tables or inline tables nested deeper than 64 levels");
  // What a real scene has stays well inside: long arrays of floats, dotted values, strings
  // holding brackets and dots, comments.
  std::string floats = "watch = [";
  for (int k = 0; k < 200; ++k) floats += "1.5, ";
  floats += "1.5]\n";
  EXPECT_TRUE(starts(text_error_of(floats + kGridText), "bad.toml:1: watch must be"));
  const std::string fine = std::string("name = \"a.b.c.[[[{{{\" # ...... [[[[\n") +
                           "description = '''x.y [{ .z'''\n" + kGridText;
  EXPECT_EQ(text_error_of(fine), "");
}

TEST(SceneText, BytesThatAreNotUtf8) {
  // toml++ 3.3 reached its "unreachable" marker on a torn byte-order mark.
  EXPECT_EQ(text_error_of("\xEF\xBB\xBB" + std::string(kGridText)),
            "bad.toml:1: the file starts with a broken byte-order mark (EF BB without BF)");
  EXPECT_EQ(text_error_of(std::string(kGridText) + "name = \"\xC0\xAF\"\n"),
            "bad.toml:5: the file is not valid UTF-8");
  EXPECT_EQ(text_error_of(std::string("name = \"a\0b\"\n", 13) + kGridText),
            "bad.toml:1: the file holds a NUL byte (not a text file)");
  EXPECT_EQ(text_error_of("\xEF\xBB\xBF" + std::string(kGridText)), "");  // a whole BOM is fine
  EXPECT_EQ(text_error_of("name = \"caf\xC3\xA9\"\n" + std::string(kGridText)), "");
}

TEST(SceneText, NumbersThatWrapped) {
  // nx * nz overflowed long long past the size check and built an empty model.
  EXPECT_EQ(text_error_of("[grid]\nnx = 4294967296\nnz = 4294967296\nspacing = 1\n"),
            "bad.toml:1: grid size must be 1..4e6 nodes");
  EXPECT_EQ(text_error_of(std::string(kGridText) +
                     "[[cut]]\niteration = 4294967296\nfrom = [0, 0]\nto = [1, 1]\n"),
            "bad.toml:5: cut iteration must be in 0..100000000");
  EXPECT_EQ(text_error_of(std::string(kGridText) + "[[expect]]\niterations = [4294967296, 4294967297]\n"),
            "bad.toml:6: iterations must lie in 0..100000000");
  EXPECT_EQ(text_error_of(std::string(kGridText) + "[[expect]]\nunstabilisable_max = 1e300\n"),
            "bad.toml:6: unstabilisable_max must be at most 1e18");
  const SceneSpec ok = parse_scene(std::string(kGridText) + "[[expect]]\nviolations_max = 1e18\n",
                                   "ok.toml");
  EXPECT_EQ(*ok.expectations.at(0).violations_max, 1000000000000000000LL);
}

TEST(SceneText, AnEmptyModelIsRefused) {
  // node = [] with [params] crashed in step().
  EXPECT_EQ(text_error_of("node = []\n[params]\nm = 0.001\n"), "bad.toml:1: the scene has no node");
}

TEST(SceneText, NamesAndLabelsHoldNoControlCharacters) {
  // A newline in the name broke the sweep CSV's header; escapes reached the terminal.
  EXPECT_EQ(text_error_of("name = \"a\\nb\"\n" + std::string(kGridText)),
            "bad.toml:1: name holds a control character (a newline, tab or escape)");
  EXPECT_EQ(text_error_of("description = \"\\u001b[2J\"\n" + std::string(kGridText)),
            "bad.toml:1: description holds a control character (a newline, tab or escape)");
  EXPECT_EQ(text_error_of(std::string(kGridText) + "[[run]]\nlabel = \"x\\ty\"\n"),
            "bad.toml:5: run label holds a control character (a newline, tab or escape)");
}

TEST(SceneText, MeshPathsStayInTheScenesFolder) {
  auto why = [](const std::string& file) {
    try {
      scene_relative_path("dir/a.toml", file);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(scene_relative_path("dir/a.toml", "meshes/m.obj"), "dir/meshes/m.obj");
  EXPECT_EQ(scene_relative_path("a.toml", "m.obj"), "m.obj");
  EXPECT_NE(why("/etc/passwd").find("absolute path"), std::string::npos);
  EXPECT_NE(why("meshes/../../x.obj").find("'..'"), std::string::npos);
  EXPECT_NE(why("..").find("'..'"), std::string::npos);
  EXPECT_EQ(scene_relative_path("dir/a.toml", "a..b/m.obj"), "dir/a..b/m.obj");
  EXPECT_EQ(text_error_of("[mesh]\nfile = \"/etc/passwd\"\n"),
            "bad.toml:2: mesh file '/etc/passwd' is an absolute path; a scene names files in its "
            "own folder (--allow-any-path lifts this)");
  set_scene_paths_unrestricted(true);
  EXPECT_EQ(scene_relative_path("dir/a.toml", "/abs/m.obj"), "/abs/m.obj");
  EXPECT_EQ(scene_relative_path("dir/a.toml", "../m.obj"), "dir/../m.obj");
  set_scene_paths_unrestricted(false);
}

}  // namespace
}  // namespace dampbound
