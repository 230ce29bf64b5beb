#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The test suite: installs what is missing, builds the tests, the examples, the benchmarks
# (built, not run: they stay compilable) and the documentation (warnings are errors), and
# runs every test with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh libopenmesh-dev libmeshoptimizer-dev
BUILD=${SMR_BUILD_DIR:-build}
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DSMR_WERROR=ON -DSMR_BUILD_DOC=ON -DSMR_BUILD_BENCHMARKS=ON
cmake --build "$BUILD" -j"$(nproc)"
cmake --build "$BUILD" --target doc
ctest --test-dir "$BUILD" -j"$(nproc)" --output-on-failure
