#pragma once
// Which compiled copy of step()'s spring loop runs (core/physics/detail/spring_batch.cpp): the loop
// computes each spring's direction, force and tangent block in SIMD lanes, one spring per
// lane, and every build carries it twice, portable (baseline x86-64, or whatever the compiler
// targets) and for AVX2 (the x86-64-v3 set, under a target pragma). The copy is chosen at run
// time, like the sweep kernel's (core/sweep/kernel.hpp). Both round every operation as the
// scalar formulas of SPEC 1, 7 and 9 do, so step() gives the same bits with either.
#include "dampbound/physics/export.hpp"
#include <optional>
#include <string>

namespace dampbound DAMPBOUND_API {

/// The compiled copies of step()'s spring loop; `best` picks the widest this CPU runs.
enum class StepIsa { best, generic, avx2 };

const char* to_string(StepIsa isa);
/// Parses "best" | "generic" | "avx2"; nullopt when unknown.
std::optional<StepIsa> parse_step_isa(const std::string& s);
/// Whether this CPU (and OS) can run `isa` (always true for best and generic).
bool step_isa_supported(StepIsa isa);
/// What `best` resolves to on this machine: DAMPBOUND_STEP_ISA from the environment when it
/// names a supported copy (for benchmarks and tests), else the widest supported one (the plain
/// copy in a DAMPBOUND_NATIVE build for an AVX2 host: it is compiled for the host). Decided
/// once per process.
StepIsa best_step_isa();

}  // namespace dampbound
