#!/usr/bin/env bash
# Every core source has its test file: core/X.cpp is tested in tests/core/X_test.cpp.
# Usage: test_files.sh SOURCE_DIR
set -euo pipefail
cd "$1"
missing=0
while IFS= read -r src; do
  test=tests/${src%.cpp}_test.cpp
  if [ ! -f "$test" ]; then
    echo "FAIL: $src has no test file ($test)"
    missing=$((missing + 1))
  fi
done < <(find core -name '*.cpp' | sort)
[ "$missing" -eq 0 ] || exit 1
echo "test files: every one of $(find core -name '*.cpp' | wc -l) core sources has its own"
