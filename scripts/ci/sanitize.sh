#!/usr/bin/env bash
# CI job: the whole tree (core, ui, app, tests, fuzz targets) built with clang 14 under
# AddressSanitizer + UndefinedBehaviorSanitizer, the ctest suite run under them, then every
# fuzz target (tests/fuzz/fuzz_*.cpp) for a fixed time on its committed seed corpus. This is
# also the "builds with clang" job: warnings are errors. Details: docs/hardening.md.
# The Python module is built instrumented too, and the Python battery (python/tests/
# test_battery_*.py) runs against it in Debian's uninstrumented interpreter with clang's ASan
# runtime preloaded (leak detection off there: CPython keeps its objects to the end by design).
#   FUZZ_SECONDS (default 7) per target; BUILD_DIR (default build-asan); JOBS (default nproc).
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT=$PWD
BUILD_DIR=${BUILD_DIR:-build-asan}
FUZZ_SECONDS=${FUZZ_SECONDS:-7}
JOBS=${JOBS:-$(nproc)}
T0=$(date +%s)
for tool in clang-14 clang++-14; do
  command -v "$tool" >/dev/null || { echo "sanitize: $tool is missing (apt-get install clang libclang-rt-14-dev)"; exit 3; }
done
LAUNCHER=()
if command -v ccache >/dev/null; then LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

# -gline-tables-only: file and line in every report's stack, without the full debug info that
# makes the Eigen-heavy sources slow to compile and link. The GPU sweep's CUDA side is compiled
# and checked by the main build (build.gpu_fatbinary); here its stand-in keeps nvcc out.
SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 "${LAUNCHER[@]}" \
  -DCMAKE_CXX_FLAGS="-O1 -gline-tables-only $SAN" -DCMAKE_CXX_FLAGS_DEBUG="" \
  -DCMAKE_C_FLAGS_DEBUG="" -DCMAKE_EXE_LINKER_FLAGS="$SAN" \
  -DDAMPBOUND_WERROR=ON -DDAMPBOUND_BENCH=OFF -DDAMPBOUND_FUZZ=ON -DDAMPBOUND_PYTHON=ON \
  -DDAMPBOUND_CUDA=OFF
# Only what runs below: the unit suites, the program the battery drives, the hunter, the Python
# module and the fuzz targets (not the build checks' helper programs, which the plain build runs).
FUZZ_TARGETS=()
for src in tests/fuzz/fuzz_*.cpp; do FUZZ_TARGETS+=("$(basename "$src" .cpp)"); done
cmake --build "$BUILD_DIR" -j "$JOBS" --target core_tests ui_tests dampbound guarantee_hunter \
  dampbound_python "${FUZZ_TARGETS[@]}"
T1=$(date +%s)

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$ROOT/scripts/ci/lsan.supp:print_suppressions=0"
# Under the sanitizers: the unit suites (core_tests, ui_tests: the EGL renders included) and the
# bad-input battery (the dampbound binary on 190+ hostile inputs). The shell tests of tests/cli/
# run in the plain build only (scripts/test.sh): under ASan each takes minutes (cli.bounds 88 s)
# and the battery already drives every subcommand's input paths; the fuzzers below drive the
# parsers. Leak detection is on for core's tests; for the tests that open an EGL/GL context
# (ui, and the battery, whose figure/map/gui cases may) it is off: llvmpipe's driver is
# dlclosed before LeakSanitizer reports, so its allocations show as "<unknown module>" and no
# suppression can name them. ASan's memory errors and UBSan stay on everywhere.
# The slowest unit tests (scripts/ci/asan-skip.txt, each with its reason) run in the plain
# build only.
unset DISPLAY
SKIP=$(sed -e 's/#.*//' -e 's/[[:space:]]//g' -e '/^$/d' -e 's/\./\\./g' scripts/ci/asan-skip.txt |
  paste -sd'|')
(cd "$BUILD_DIR" && ctest --output-on-failure -j "$JOBS" -L '^core$' -E "^($SKIP)\$")
(cd "$BUILD_DIR" && ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" \
   ctest --output-on-failure -j "$JOBS" -L '^ui$' -E "^(ui\\.glfw_host_under_xvfb|$SKIP)\$")
(cd "$BUILD_DIR" && ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" \
   ctest --output-on-failure -j "$JOBS" -R '^battery$')
# The guarantee hunter (docs/hardening.md) at another seed than the plain build's ctest (which
# runs seed 1 with 300 scenes and is skipped here), under the sanitizers: about 45 s on 2
# cores. `guarantee_hunter --seed S --scenes N` hunts longer by hand.
"$BUILD_DIR/tests/guarantee_hunter" --seed 2 --scenes 60 --sweeps 2 \
  --regressions "$ROOT/tests/hunter/found.txt"
# The Python battery (382 cases: states, indices, flags, out arrays, parameters at every
# door, the GIL) against the instrumented module.
ASAN_RT=$(clang-14 -print-file-name=libclang_rt.asan-x86_64.so)
[ -f "$ASAN_RT" ] || { echo "sanitize: clang's ASan runtime is missing (apt-get install libclang-rt-14-dev)"; exit 3; }
(cd "$BUILD_DIR/python" && LD_PRELOAD="$ASAN_RT" ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" \
   PYTHONPATH=. /usr/bin/python3 -m pytest -q -p no:cacheprovider \
   "$ROOT/python/tests/test_battery_arrays.py" "$ROOT/python/tests/test_battery_params.py")
T2=$(date +%s)

echo "== fuzzing: ${FUZZ_SECONDS} s per target on its seed corpus"
summary=()
for src in tests/fuzz/fuzz_*.cpp; do
  name=$(basename "$src" .cpp)
  corpus_name=${name#fuzz_}
  seeds=tests/fuzz/corpus/$corpus_name
  [ -d "$seeds" ] || { echo "sanitize: $seeds is missing (every target needs a seed corpus)"; exit 1; }
  work=$(mktemp -d)  # new inputs go here; the committed corpus is only read
  log=$work/log
  if ! "$BUILD_DIR/tests/fuzz/$name" -max_total_time="$FUZZ_SECONDS" -timeout=10 \
      -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix="$work/" \
      "$work" "$seeds" >"$log" 2>&1; then
    tail -n 40 "$log"
    echo "sanitize: $name found a failure; the input is in $work"
    exit 1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  summary+=("$name: $runs executions in ${FUZZ_SECONDS} s, corpus $(ls "$seeds" | wc -l) seeds")
  rm -rf "$work"
done
T3=$(date +%s)
echo "== sanitize summary"
echo "build (clang 14, ASan+UBSan, -Werror): $((T1 - T0)) s"
echo "ctest and the Python battery under ASan+UBSan: $((T2 - T1)) s"
printf '%s\n' "${summary[@]}"
echo "fuzzing: $((T3 - T2)) s; total $((T3 - T0)) s"
