// libFuzzer target: the VTK legacy unstructured-grid reader.
#include "core/io/mesh_vtk.hpp"
#include "tests/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return dampbound::fuzz::run(
      [&] { return dampbound::parse_vtk(reinterpret_cast<const char*>(data), size, "fuzz.vtk"); });
}
