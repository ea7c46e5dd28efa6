// Fuzz target: the Wavefront OBJ mesh reader (core/mesh_obj.cpp) and the springs it builds.
// Any input must give a mesh or an InputError, never a crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "core/mesh_obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const dampbound::ObjMesh mesh = dampbound::parse_obj(text, "fuzz.obj");
    dampbound::MeshSprings how;
    how.bend = size % 2 == 0;  // both edge sets, from the same corpus
    const dampbound::Model m = dampbound::model_from_obj(mesh, how);
    (void)m;
  } catch (const dampbound::InputError&) {
  }
  return 0;
}
