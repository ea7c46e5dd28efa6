#pragma once
// The scene format as one table: every section and key a scene file may hold, with its type,
// default and meaning. The reader refuses any key not listed here (scene_file::Reader::check_keys),
// and docs/scene-format.md is written from it (scripts/scene-reference.sh).
#include <string>
#include <string_view>
#include <vector>

namespace dampbound {

/// A section of a scene file: "" (the top level), "[grid]", "[[node]]", ...
struct SceneSection {
  std::string name;
  std::string meaning;
  /// Another section whose keys this one also takes ("[[run]]" takes every "[params]" key).
  std::string inherits;
};

/// One key of a section.
struct SceneKey {
  std::string section;  ///< SceneSection::name
  std::string key;
  std::string type;           ///< number, integer, boolean, string, [x, y, z], node, [min, max]
  std::string default_value;  ///< "required", "none" or the value used when the key is absent
  std::string meaning;
};

/// The sections, in the order a scene file usually gives them.
const std::vector<SceneSection>& scene_sections();

/// Every key of every section, grouped by section in scene_sections() order.
const std::vector<SceneKey>& scene_keys();

/// Whether `key` may appear in `section` (its own keys and those of the section it inherits).
bool scene_key_allowed(std::string_view section, std::string_view key);

/// docs/scene-format.md: the sections and their keys as Markdown tables.
std::string scene_format_markdown();

}  // namespace dampbound
