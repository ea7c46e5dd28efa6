#!/usr/bin/env bash
# CI job: dampbound used from someone else's code. Installs the build into a fresh temporary
# prefix, then, against that prefix only: runs the installed CLI (--version, a shipped scene
# found under share/dampbound), builds examples/ with find_package(dampbound CONFIG) and runs
# its programs, compiles the README's C++ example with pkg-config, imports the Python module
# from the prefix and runs its pytest suite and the NumPy example, and checks that the
# README's three five-line examples are the files run here. Reuses build/ when configured.
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT=$(pwd)
start=$SECONDS
BUILD=${DAMPBOUND_BUILD_DIR:-build}
PY=/usr/bin/python3
step() { echo "install-consumer: $*"; }
fail() { echo "install-consumer: FAILED: $*" >&2; exit 1; }

if [ ! -f "$BUILD/build.ninja" ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDAMPBOUND_WERROR=ON >/dev/null
fi
grep -q '^DAMPBOUND_PYTHON:BOOL=ON' "$BUILD/CMakeCache.txt" || fail "$BUILD has DAMPBOUND_PYTHON off (install pybind11-dev)"
cmake --build "$BUILD" -j "$(nproc)" --target dampbound dampbound_core dampbound_core_shared \
  dampbound_python >/dev/null

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
P=$WORK/prefix
cmake --install "$BUILD" --prefix "$P" >/dev/null
step "installed into a fresh prefix"

# The layout the issue asks for.
for f in bin/dampbound include/dampbound/monitor.hpp include/dampbound/version.hpp \
         include/dampbound/physics/model.hpp include/dampbound/dampbound.hpp lib/libdampbound_core.a lib/pkgconfig/dampbound.pc \
         lib/cmake/dampbound/dampboundConfig.cmake share/dampbound/scenes/paper-plane.toml \
         share/man/man1/dampbound.1; do
  [ -e "$P/$f" ] || fail "missing $f"
done
so=$(ls "$P"/lib/libdampbound_core.so.* | head -1)
soname=$(objdump -p "$so" | awk '/SONAME/ {print $2}')
[[ "$soname" == libdampbound_core.so.[0-9]* ]] || fail "shared library has no SONAME ($soname)"
# Only the public headers: no sweep, UI or app header is installed.
[ -z "$(find "$P/include" -name 'sweep_*' -o -name 'gui_*' -o -name 'options.hpp')" ] ||
  fail "a private header was installed"
# The installed headers are the public folder as it stands (tests/build/layers.sh compiles each
# of those alone): the same files, byte for byte, beside the generated version.hpp. The
# umbrella header then compiles with only the prefix and Eigen on the path.
for h in $(cd "$P/include" && find dampbound -name '*.hpp' ! -name version.hpp); do
  cmp -s "$P/include/$h" "include/$h" || fail "installed $h is not include/$h"
done
for h in $(cd include && find dampbound -name '*.hpp'); do
  [ -f "$P/include/$h" ] || fail "include/$h was not installed"
done
echo "#include <dampbound/dampbound.hpp>" | g++ -std=c++17 -fsyntax-only -x c++ - -I"$P/include" \
  $(pkg-config --cflags eigen3) || fail "dampbound/dampbound.hpp does not compile from the prefix"
step "layout ok (SONAME $soname); the installed headers are include/'s; the umbrella compiles"

# The CLI, with the source tree out of reach of its scene lookup.
version=$("$P/bin/dampbound" --version)
[[ "$version" == "dampbound $(sed -n 's/^project(dampbound VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt) "* ]] ||
  fail "--version printed '$version'"
found=$(cd "$WORK" && DAMPBOUND_SOURCE_DIR=/nonexistent "$P/bin/dampbound" check 2>&1 | head -3 || true)
grep -q "$P/share/dampbound/scenes" <<<"$found" ||
  fail "installed dampbound check did not use $P/share/dampbound/scenes: $found"
(cd "$WORK" && PATH="$P/bin:$PATH" bash -e "$ROOT/examples/cli/readme.sh") >/dev/null ||
  fail "the README's CLI example"
step "CLI: $version; shipped scenes found under the prefix"

# C++ through find_package, and through pkg-config.
cmake -S examples -B "$WORK/examples" -G Ninja -DCMAKE_PREFIX_PATH="$P" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$WORK/examples" >/dev/null
"$WORK/examples/guarded_spring_loop"
"$WORK/examples/readme_example"
PKG_CONFIG_PATH=$P/lib/pkgconfig g++ -std=c++17 examples/readme_example.cpp -o "$WORK/pc_example" \
  $(PKG_CONFIG_PATH=$P/lib/pkgconfig pkg-config --cflags --libs dampbound) -Wl,-rpath,"$P/lib"
"$WORK/pc_example" >/dev/null
step "C++: examples built with find_package and pkg-config, and ran"

# Python from the prefix (not the build tree).
export PYTHONPATH=$P/lib/python3/dist-packages DAMPBOUND_SCENES_DIR=$P/share/dampbound/scenes
where=$(cd "$WORK" && $PY -c 'import dampbound; print(dampbound.__file__)')
[[ "$where" == "$P"/* ]] || fail "python imported dampbound from $where"
(cd "$WORK" && $PY -m pytest -q -p no:cacheprovider "$ROOT/python/tests")
(cd "$WORK" && $PY "$ROOT/examples/python/guarded_loop.py")
(cd "$WORK" && $PY "$ROOT/examples/python/readme.py") >/dev/null
step "Python: imported from $where; pytest suite and examples passed"

# The README shows exactly these examples.
for f in examples/cli/readme.sh examples/readme_example.cpp examples/python/readme.py; do
  while IFS= read -r line; do
    [ -z "$line" ] || [[ "$line" == '#!'* ]] || grep -qF -- "$line" README.md ||
      fail "README.md lacks this line of $f: $line"
  done <"$f"
done
step "README examples are the ones run here"
echo "install-consumer: passed in $((SECONDS - start)) s"
