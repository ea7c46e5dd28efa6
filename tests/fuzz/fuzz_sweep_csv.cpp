// Fuzz target: the sweep CSV reader (core/sweep/csv.cpp) that `map`, `merge` and `--resume`
// use. Any input must be read or refused with an InputError naming the line, never a crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/sweep/csv.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/fuzz/memory_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static dampbound::fuzz::MemoryFile file;
  const std::string path = file.hold(data, size);
  if (path.empty()) return 0;
  try {
    const dampbound::SweepTable t = dampbound::read_sweep_csv(path, true);
    (void)t;
  } catch (const dampbound::InputError&) {
  }
  return 0;
}
