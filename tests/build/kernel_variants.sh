#!/usr/bin/env bash
# The per-instruction-set copies of the sweep kernel (core/sweep/detail/kernel_avx2.cpp, _avx512.cpp)
# and of step()'s spring batch (core/physics/detail/spring_batch_avx2.cpp) must keep everything they
# share with the rest of the library portable: a template or inline
# function they emit (weak symbol) may be the copy the linker keeps for the whole program, so
# it must contain no AVX instruction. And each copy must really use its instruction set.
# Usage: kernel_variants.sh OBJDUMP NATIVE(ON|OFF) OBJECT...
set -euo pipefail
objdump=$1 native=$2
shift 2
fail=0
for obj in "$@"; do
  case "$obj" in
    *kernel_avx512.cpp.o) wide='%zmm' ;;
    *kernel_avx2.cpp.o) wide='%ymm' ;;
    *kernel_body.cpp.o) wide='' ;;
    *spring_batch_avx2.cpp.o) wide='%ymm' ;;
    *spring_batch.cpp.o) wide='' ;;
    *) continue ;;
  esac
  dis=$("$objdump" -d --no-show-raw-insn -C "$obj")
  # Functions other than the kernel's own (internal linkage: local symbols) and its factory.
  shared=$(nm -C --defined-only "$obj" | awk '$2 ~ /^[TWV]$/ {$1=$2=""; print substr($0,3)}' |
           grep -v -e '::kernel_[a-z0-9]*::make(' -e '::spring_batch_[a-z0-9]*::compute(' || true)
  # In a native build (-march=native) the whole library is compiled for this CPU: nothing
  # shared can be more portable than the rest, so only a portable build is checked for it.
  [ "$native" = OFF ] || shared=""
  while IFS= read -r sym; do
    [ -n "$sym" ] || continue
    body=$(awk -v s="<$sym>:" 'index($0, s) {p=1; next} /^$/ {p=0} p' <<<"$dis")
    if grep -qE '\s(v[a-z0-9]+|andn|bextr|blsi|blsmsk|blsr|bzhi|mulx|pdep|pext|rorx|sarx|shlx|shrx|tzcnt|lzcnt|popcnt)\s' <<<"$body"; then
      echo "FAIL: $(basename "$obj") emits shared '$sym' with AVX instructions" >&2
      fail=1
    fi
  done <<<"$shared"
  if [ -n "$wide" ] && ! grep -q "$wide" <<<"$dis"; then
    echo "FAIL: $(basename "$obj") has no $wide instruction: not compiled for its target" >&2
    fail=1
  fi
  if [ -z "$wide" ] && [ "$native" = OFF ] && grep -qE '%ymm|%zmm' <<<"$dis"; then
    echo "FAIL: the generic $(basename "$obj") uses AVX registers in a portable build" >&2
    fail=1
  fi
  echo "$(basename "$obj"): ok ($(wc -l <<<"$shared") shared symbols checked)"
done
exit $fail
