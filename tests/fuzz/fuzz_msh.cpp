// libFuzzer target: the Gmsh MSH reader (2.2 and 4.1, ASCII and binary).
#include "core/io/mesh_msh.hpp"
#include "tests/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return dampbound::fuzz::run(
      [&] { return dampbound::parse_msh(reinterpret_cast<const char*>(data), size, "fuzz.msh"); });
}
