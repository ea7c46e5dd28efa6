#pragma once
// Shared by the fuzz targets (libFuzzer): run a reader on the input, accept InputError (bad
// input is expected), and build the model of whatever parses, so the builder is fuzzed too.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/mesh.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::fuzz {

template <class Read>
int run(Read read) {
  try {
    const CellMesh mesh = read();
    MeshSprings how;
    how.bend = true;
    how.density = 1.0;
    how.young = 1.0;
    model_from_mesh(mesh, how);
  } catch (const InputError&) {
    // Rejected with a message: the expected outcome for most inputs.
  }
  return 0;
}

}  // namespace dampbound::fuzz
