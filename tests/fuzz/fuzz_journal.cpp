// Fuzz target: the sweep journal reader (core/sweep/journal.cpp): a journal left by a killed
// or broken run, or forged. Any input must be read back (its valid prefix) or refused with an
// InputError, and what is read back must be what a run can produce.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/sweep/journal.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/fuzz/memory_file.hpp"

namespace {
// The header of the seed corpus's journals (tests/fuzz/corpus/journal/).
const std::string kHeader = "dampbound-journal v1 sweep=0123456789abcdef 1/1 classes=64";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static dampbound::fuzz::MemoryFile file;
  const std::string path = file.hold(data, size);
  if (path.empty()) return 0;
  try {
    const dampbound::JournalContents jc = dampbound::read_journal(path, kHeader, 64);
    for (const dampbound::JournalEntry& e : jc.entries) {
      const dampbound::TrialResult& r = e.result;
      if (e.cls >= 64 || r.iterations < 0 || r.violations < 0 || r.unstabilisable < 0 ||
          r.clamped < 0 || r.zero_length_springs < 0 || r.max_displacement < 0 ||
          (!std::isfinite(r.max_displacement) && r.outcome != dampbound::Outcome::diverged))
        std::abort();  // a journal line no run can write was accepted
    }
    if (jc.valid_bytes > size) std::abort();
  } catch (const dampbound::InputError&) {
  }
  return 0;
}
