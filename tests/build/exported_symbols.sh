#!/usr/bin/env bash
# libdampbound_core.so exports its API and nothing else: at most 400 defined dynamic symbols,
# none of toml++, Eigen, Spectra, the OpenMP runtime or core's detail code, not even as a
# template argument.
# Usage: exported_symbols.sh NM LIBRARY
set -euo pipefail
nm=$1 lib=$2
symbols=$("$nm" -D --defined-only -C "$lib" | cut -d' ' -f3-)
count=$(grep -c . <<<"$symbols")
echo "exported_symbols: $count defined dynamic symbols in $(basename "$lib")"
status=0
if [ "$count" -gt 400 ]; then
  echo "exported_symbols: FAILED: $count symbols, at most 400 (include/dampbound/physics/export.hpp)" >&2
  status=1
fi
# Names that mean an internal leaked (templates over them included) or another library's
# entry point is defined here.
# (The name is what comes before the parameter list: an Eigen argument type is fine.)
leaks=$(sed 's/(.*//' <<<"$symbols" |
        grep -E '(^|[^_A-Za-z])(toml|Eigen|Spectra)::|dampbound::([A-Za-z_]+::)*detail::|^(GOMP_|omp_|cholmod_|dgemm|dsyrk)' ||
        true)
if [ -n "$leaks" ]; then
  echo "exported_symbols: FAILED: $(grep -c . <<<"$leaks") internal or foreign symbols, the first:" >&2
  head -5 <<<"$leaks" >&2
  status=1
fi
exit $status
