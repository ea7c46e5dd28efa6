#pragma once
// Checks on a scene file's raw text and on the paths it names, made before the TOML parser
// sees it (docs/hardening.md): bounds that keep toml++ from running out of stack or reaching
// an internal assertion, and the rule for the files a scene may name.
#include <string>

namespace dampbound {

/// Most parts of one dotted key or table header (a.b.c = 1 has 3), and most nested arrays and
/// inline tables: toml++ recurses once per level and a hostile file could overflow the stack.
constexpr int kMaxTomlNesting = 64;

/// Largest OBJ mesh a scene may name, bytes (about 5e6 vertices).
constexpr unsigned long long kMaxMeshBytes = 256ull << 20;

/// Throws InputError("PATH:LINE: ...") when TEXT is not valid UTF-8, starts with a broken
/// byte-order mark, holds a NUL byte, or nests deeper than kMaxTomlNesting.
void check_scene_text(const std::string& text, const std::string& path);

/// Whether a scene may name a [mesh] file anywhere (an absolute path or one climbing out with
/// ".."). Off by default: a scene names files in its own folder or below it. The command line
/// turns it on with --allow-any-path.
void set_scene_paths_unrestricted(bool allow);
bool scene_paths_unrestricted();

/// The path of FILE named by the scene at SCENE_PATH: relative to the scene's folder. Throws
/// InputError saying why when FILE is absolute or climbs out of the folder and the rule
/// applies (the caller adds the file and line).
std::string scene_relative_path(const std::string& scene_path, const std::string& file);

/// Throws InputError("PATH:LINE: WHAT ...") when TEXT (a name or label that reaches CSV
/// headers and terminals) holds a control character (newline, escape, ...).
void check_plain_text(const std::string& text, const std::string& what, const std::string& path,
                      int line);

}  // namespace dampbound
