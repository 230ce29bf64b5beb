#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (any report fails
# the test that triggers it), leak detection on. Tests only (no examples, benchmarks or docs):
# the seeded fuzz test and the crafted-file tests are the ones this is for.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
BUILD=${SMR_SANITIZE_BUILD_DIR:-build-sanitize}
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSMR_WERROR=ON -DSMR_SANITIZE=ON -DSMR_BUILD_EXAMPLES=OFF
cmake --build "$BUILD" -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir "$BUILD" -j"$(nproc)" --output-on-failure -E install_find_package
