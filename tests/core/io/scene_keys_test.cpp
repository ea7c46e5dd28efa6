// The scene key table (core/io/scene_keys.cpp): one row per key, the reader accepts exactly its
// keys, and the reference page lists every row.
#include "core/io/scene_keys.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>

#include "core/io/scene_file.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

const char* kGridKeys = "[grid]\nnx = 3\nnz = 3\nspacing = 1.0\n[[perturb]]\nnode = 4\n";

TEST(SceneKeys, EveryKeyIsOnceInADeclaredSection) {
  std::set<std::string> sections;
  for (const SceneSection& s : scene_sections()) {
    EXPECT_TRUE(sections.insert(s.name).second) << s.name;
    EXPECT_FALSE(s.meaning.empty()) << s.name;
  }
  std::set<std::pair<std::string, std::string>> seen;
  for (const SceneKey& k : scene_keys()) {
    EXPECT_TRUE(sections.count(k.section)) << k.section << " " << k.key;
    EXPECT_TRUE(seen.insert({k.section, k.key}).second) << k.section << " " << k.key;
    EXPECT_FALSE(k.type.empty() || k.default_value.empty() || k.meaning.empty()) << k.key;
  }
}

TEST(SceneKeys, RunsTakeEveryParamsKeyAndTheTopLevelTakesTheSections) {
  EXPECT_TRUE(scene_key_allowed("[[run]]", "label"));
  EXPECT_TRUE(scene_key_allowed("[[run]]", "rayleigh_stiffness"));
  EXPECT_FALSE(scene_key_allowed("[params]", "label"));
  EXPECT_TRUE(scene_key_allowed("", "mesh_region"));
  EXPECT_TRUE(scene_key_allowed("", "watch"));
  EXPECT_FALSE(scene_key_allowed("", "x"));
  EXPECT_FALSE(scene_key_allowed("[grid]", "x"));
}

TEST(SceneKeys, TheReaderAcceptsATableKeyAndRefusesAnyOther) {
  // Every [params] key of the table reads (with a valid value), and one not in it does not.
  for (const SceneKey& k : scene_keys()) {
    if (k.section != "[params]") continue;
    const std::string value = k.type == "string" ? k.default_value : "0.5";
    const std::string text = std::string(kGridKeys) + "[params]\n" + k.key + " = " + value + "\n";
    EXPECT_NO_THROW(parse_scene(text, "s.toml")) << k.key;
  }
  try {
    parse_scene(std::string(kGridKeys) + "[params]\nmass = 1\n", "s.toml");
    FAIL() << "an unknown key was read";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "s.toml:8: unknown key 'mass' in [params]");
  }
}

TEST(SceneKeys, TheReferenceListsEveryKey) {
  const std::string md = scene_format_markdown();
  for (const SceneKey& k : scene_keys())
    EXPECT_NE(md.find("| `" + k.key + "` | " + k.type + " | " + k.default_value + " |"),
              std::string::npos)
        << k.section << " " << k.key;
  EXPECT_NE(md.find("## `[[expect]]`"), std::string::npos);
}

}  // namespace
}  // namespace dampbound
