#!/usr/bin/env bash
# Installs dampbound's dependencies from Debian 12's packages. Nothing is downloaded from
# anywhere else.
#   install-deps.sh --app   what the CLI and the tuner need (the first quick-start command)
#   install-deps.sh         everything: tests, benchmarks, the Python module, CI's jobs
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
APP=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libspectra-dev libtomlplusplus-dev libcli11-dev libstb-dev libsuitesparse-dev
  libopenblas0-serial            # CHOLMOD's BLAS: factorisations ~2x faster than the reference BLAS
  liblapack-dev                  # dstebz/dstein (OpenBLAS's LAPACK once libopenblas0-serial is in)
  libimgui-dev libglfw3-dev libgl-dev libegl-dev libegl-mesa0 libgl1-mesa-dri
  fonts-dejavu-core
)
REST=(
  git
  libgtest-dev libbenchmark-dev
  pybind11-dev python3-dev python3-pytest   # the Python module and its tests (and numpy)
  xvfb xauth xdotool
  libx11-dev                     # cli.gui_close builds its window-manager close request (tests/tools)
  clang libclang-rt-14-dev
  slurm-wlm munge                # scripts/ci/slurm.sh: a single-node Slurm on localhost
  python3-meshio python3-numpy   # tests read the ParaView (VTU) output back with meshio
  python3-scipy                  # linear_limits takes scipy.sparse matrices (module, tests)
  locales                        # de_DE.UTF-8 below: numbers keep their point under a comma locale
  g++-aarch64-linux-gnu qemu-user-static  # scripts/ci/aarch64.sh: the kernel and step() on aarch64
)
case "${1:-}" in
  --app) PACKAGES=("${APP[@]}") ;;
  "") PACKAGES=("${APP[@]}" "${REST[@]}") ;;
  *) echo "install-deps.sh: unknown option '$1' (use --app, or nothing for everything)" >&2; exit 2 ;;
esac
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if [ "${1:-}" = "--app" ]; then
  echo "dependencies: the ${#PACKAGES[@]} packages the CLI and the tuner need are installed"
  exit 0
fi
# A locale with a decimal comma, for the tests that a host's setlocale(LC_ALL, "") in Germany
# leaves dampbound's files and mesh readers alone (tests/core/io/format_test.cpp, pytest).
if ! locale -a 2>/dev/null | grep -qix 'de_DE\.utf-\?8'; then
  $SUDO localedef -i de_DE -f UTF-8 de_DE.UTF-8
fi
echo "dependencies: all ${#PACKAGES[@]} packages installed, and the de_DE.UTF-8 locale"
