#!/usr/bin/env bash
# Installs what tsmframe needs from Debian's packages (only what is missing; clang, its
# libFuzzer and OpenMP for the fuzz targets) and builds it (Release, g++) in build/. Safe to run
# again: a second run only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ make cmake libeigen3-dev nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev python3-matplotlib
          python3-dev pybind11-dev python3-numpy python3-pytest python3-venv python3-pip python3-setuptools python3-wheel
          python3-jsonschema python3-distributed ninja-build universal-ctags clang libclang-rt-14-dev libomp-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Ninja: a target's objects compile while the library it links is still building, so both cores
# stay busy to the end (a fresh build is the larger part of CI). A build/ made by an earlier
# setup with Makefiles is configured afresh once (CMake keeps one generator per directory).
if [ -f build/CMakeCache.txt ] && ! grep -q "^CMAKE_GENERATOR:INTERNAL=Ninja$" build/CMakeCache.txt; then
  rm -rf build/CMakeCache.txt build/CMakeFiles
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2
