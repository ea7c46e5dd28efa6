// Fuzz target: the TOML scene parser (core/io/scene_file.cpp, core/io/scene_text.cpp). Any input
// must give a scene or an InputError, never a crash, a hang or another exception.
#include <toml++/toml.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/scene_file.hpp"
#include "core/io/scene_text.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/scene.hpp"

namespace {

/// Whether a [grid] of the text is larger than a fuzz run affords: the parser accepts up to
/// 4e6 nodes (seconds each), which is not a bug but would stall the fuzzer.
bool huge_grid(const std::string& text) {
  try {
    dampbound::check_scene_text(text, "fuzz.toml");  // toml++ must not see what it refuses
    const std::string name = "fuzz.toml";
    const toml::table root = toml::parse(text, name);
    // as_integer(), not value<long long>(): toml++ 3.3 converts a float node to an integer
    // before checking its range (undefined for nx = 4.4e57, which the fuzzer found), and the
    // parser refuses a float nx anyway.
    const auto count = [&](const char* key) -> long long {
      const toml::value<std::int64_t>* v = root["grid"][key].as_integer();
      return v ? v->get() : 1;
    };
    return count("nx") > 64 || count("nz") > 64;
  } catch (...) {
    return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (huge_grid(text)) return -1;  // not added to the corpus
  try {
    const dampbound::SceneSpec s = dampbound::parse_scene(text, "fuzz.toml");
    (void)s;
  } catch (const dampbound::InputError&) {
  }
  return 0;
}
