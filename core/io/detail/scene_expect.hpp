#pragma once
// The [[expect]] tables of a scene file. Private to the scene reader.
#include "core/io/detail/scene_reader.hpp"

namespace dampbound::scene_file {

/// Reads the [[expect]] tables (core/io/detail/scene_expect.cpp).
void read_expectations(const Reader& r, const toml::table& root, SceneSpec& s);

}  // namespace dampbound::scene_file
