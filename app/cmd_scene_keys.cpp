// dampbound scene-format (not listed in --help): prints docs/scene-format.md, the scene file
// reference, from the key table the reader checks against (scripts/scene-reference.sh).
#include <cstdio>

#include "app/commands.hpp"
#include "core/io/scene_keys.hpp"

namespace dampbound::app::cmd_scene_keys {
namespace {

std::function<int()> setup(CLI::App& root) {
  CLI::App* cmd = root.add_subcommand(
      "scene-format", "Print the scene file reference (Markdown) from the scene key table.");
  cmd->group("");  // a maintainer's tool: kept out of --help and docs/cli.md
  return [] {
    std::fputs(scene_format_markdown().c_str(), stdout);
    return 0;
  };
}

const bool registered = register_command("scene-format", setup);

}  // namespace
}  // namespace dampbound::app::cmd_scene_keys
