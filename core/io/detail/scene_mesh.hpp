#pragma once
// The [mesh] table of a scene file and its [[mesh_region]]s. Private to the scene reader.
#include "core/io/detail/scene_reader.hpp"

namespace dampbound::scene_file {

/// [mesh]: a mesh file of any format (core/io/mesh_file.hpp), its path relative to the scene
/// file, with its [[mesh_region]] tables (core/io/detail/scene_mesh.cpp).
void read_mesh(const Reader& r, const toml::table& root, SceneSpec& s);

}  // namespace dampbound::scene_file
