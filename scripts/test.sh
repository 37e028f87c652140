#!/usr/bin/env bash
# The README's second command (and CI's): installs what is needed, builds everything with tests,
# and runs the test suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dependencies.sh
export WM_PROJECT_DIR=/usr/share/openfoam
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure -j"$jobs")

# the readers' fuzz targets (libFuzzer needs clang): a short run each, ctest label "fuzz"
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DHEX_MESHING_3_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$jobs"
(cd build-fuzz && ctest -L fuzz --output-on-failure -j"$jobs")
