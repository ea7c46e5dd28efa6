#!/usr/bin/env bash
# ARM, correct: cross-builds the batched sweep kernel and step() (core only: no CLI, tuner or
# CHOLMOD) for aarch64 with Debian's g++-aarch64-linux-gnu, runs scripts/ci/aarch64_bits.cpp
# under qemu-aarch64-static (every trial of a sample through the kernel's generic copy and
# through step(), bit for bit). With --compare-host it also builds and runs the same check
# natively and requires the two architectures' digests of the results to be equal (twice
# the build time, so CI leaves it out).
#   scripts/ci/aarch64.sh [--compare-host] [WORK_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
compare_host=0
if [[ ${1:-} == --compare-host ]]; then compare_host=1; shift; fi
work=${1:-$(mktemp -d)}
mkdir -p "$work"
for tool in aarch64-linux-gnu-g++ qemu-aarch64-static g++; do
  command -v "$tool" >/dev/null ||
    { echo "aarch64.sh: $tool not found (scripts/install-deps.sh installs it)" >&2; exit 1; }
done
# The check and the part of core it reaches: the physics layer (implicit Euler solves with
# core/stiffness) and the kernel.
common=(scripts/ci/aarch64_bits.cpp core/physics/bounds.cpp core/physics/detail/spring_pass.cpp
  core/physics/detail/spring_batch.cpp core/physics/step_isa.cpp core/physics/forces.cpp
  core/physics/integrate.cpp core/physics/model.cpp core/physics/node_threads.cpp core/physics/params.cpp core/run/protocol.cpp
  core/physics/safe_bound.cpp core/physics/safe_bound_damped.cpp core/physics/safe_bound_nodes.cpp core/run/scene.cpp
  core/run/session.cpp core/physics/step.cpp core/sweep/kernel.cpp core/sweep/detail/kernel_body.cpp
  core/sweep/trials.cpp core/physics/stiffness.cpp core/physics/closed_forms.cpp
  core/run/settle_proof.cpp core/physics/damping_ratio.cpp)
x86_only=(core/sweep/detail/kernel_avx2.cpp core/sweep/detail/kernel_avx512.cpp
  core/physics/detail/spring_batch_avx2.cpp)
# The project's rounding flags: no FMA contraction (CMakeLists.txt). -O1 compiles faster and
# rounds the same (IEEE operations, no contraction, no fast-math). Sections let the static
# link drop the analysis code that needs CHOLMOD (only implicit Euler's matrices are reached).
flags=(-std=c++17 -O1 -ffp-contract=off -pthread -Wno-psabi -ffunction-sections -fdata-sections
  -I"$root" -I"$root/include" -I/usr/include/eigen3)
build() {  # build COMPILER OUT SOURCES...
  local cxx=$1 out=$2
  shift 2
  mkdir -p "$out"
  printf '%s\n' "$@" |
    xargs -P "$(nproc)" -I{} sh -c 'o="$1/$(echo "$3" | tr / _).o"; s="$2/$3"; shift 3; '"$cxx"' "$@" -c "$s" -o "$o" || exit 255' \
      _ "$out" "$root" {} "${flags[@]}" >/dev/null 2>"$out/errors" ||
    { cat "$out/errors" >&2; echo "aarch64.sh: $cxx build failed" >&2; exit 1; }
  "$cxx" -pthread -static -Wl,--gc-sections "$out"/*.o -o "$out/bits"
}
start=$SECONDS
build aarch64-linux-gnu-g++ "$work/arm64" "${common[@]}"
# ELF e_machine (bytes 18-19) 0xb7: AArch64.
[[ $(od -An -tx1 -j18 -N2 "$work/arm64/bits" | tr -d ' ') == b700 ]] ||
  { echo "aarch64.sh: $work/arm64/bits is not an aarch64 binary" >&2; exit 1; }
arm=$(qemu-aarch64-static "$work/arm64/bits") || { echo "$arm" >&2; exit 1; }
echo "aarch64 (qemu): $arm"
if ((compare_host)); then
  extra=()
  [[ $(uname -m) == x86_64 ]] && extra=("${x86_only[@]}")
  build g++ "$work/host" "${common[@]}" "${extra[@]}"
  host=$("$work/host/bits")
  echo "$(uname -m): $host"
  [[ ${arm##*digest } == "${host##*digest }" ]] ||
    { echo "aarch64.sh: the two architectures' results differ" >&2; exit 1; }
  echo "aarch64.sh: same bits on aarch64 and $(uname -m)"
fi
echo "aarch64.sh: passed ($((SECONDS - start)) s)"
