#pragma once
// Scene files (docs/scene-format.md): TOML text read into a SceneSpec, every error naming the file
// and the line.
#include <string>

#include "dampbound/run/scene.hpp"

namespace dampbound {

/// Loads and validates a scene file. Throws InputError("FILE:LINE: message") on any
/// malformed or inconsistent content (unknown key, missing value, NaN, negative mass,
/// spring to a missing node, duplicate spring, ...).
SceneSpec load_scene(const std::string& path);

/// Parses scene text; `path` is used in messages only.
SceneSpec parse_scene(const std::string& text, const std::string& path);

/// What a scene argument names: `text` itself when it is a path (has a '/', or exists), else
/// the scene of that name in `scenes_dir` ("two-node" or "two-node.toml") when there is one,
/// else `text` (whose load then reports it missing). The CLI and the tuner both use it.
std::string resolve_scene(const std::string& text, const std::string& scenes_dir);

}  // namespace dampbound
