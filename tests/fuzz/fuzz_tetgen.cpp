// libFuzzer target: the TetGen reader. One input holds the .node, .ele and optional .face
// texts separated by lines "@@" (the seeds in corpus/tetgen/ are written that way).
#include <string>

#include "core/io/mesh_tetgen.hpp"
#include "tests/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string in(reinterpret_cast<const char*>(data), size);
  std::string part[3];
  size_t start = 0;
  for (int k = 0; k < 3 && start <= in.size(); ++k) {
    const size_t sep = k < 2 ? in.find("\n@@\n", start) : std::string::npos;
    part[k] = in.substr(start, sep == std::string::npos ? std::string::npos : sep - start);
    start = sep == std::string::npos ? in.size() + 1 : sep + 4;
  }
  return dampbound::fuzz::run([&] {
    return dampbound::parse_tetgen(part[0], "fuzz.node", part[1], "fuzz.ele", part[2], "fuzz.face");
  });
}
