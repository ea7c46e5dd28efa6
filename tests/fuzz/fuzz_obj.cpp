// libFuzzer target: the Wavefront OBJ reader.
#include <string>

#include "core/io/mesh_obj.hpp"
#include "tests/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return dampbound::fuzz::run([&] {
    const std::string text(reinterpret_cast<const char*>(data), size);
    return dampbound::cells_from_obj(dampbound::parse_obj(text, "fuzz.obj"));
  });
}
