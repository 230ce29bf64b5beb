#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The pipeline (decompose, reconstruct, files, relax; every scheme) on small generated meshes
# under Valgrind's memcheck: the internal arrays written whole by parallel loops are left
# uninitialised until written, and memcheck reports any value read before it was written
# (the sanitizers of test_sanitizers.sh do not see those). Any report fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh valgrind
BUILD=${SMR_MEMCHECK_BUILD_DIR:-build-memcheck}
mkdir -p "$BUILD"
# -O1 -g: memcheck's reports point at lines; no rounding-mode check under Valgrind
g++ -std=c++17 -O1 -g -DCGAL_DISABLE_ROUNDING_MATH_CHECK -DCGAL_EIGEN3_ENABLED -DCGAL_LINKED_WITH_TBB \
  -Iinclude -Itest/Surface_mesh_multiresolution/include -I/usr/include/eigen3 \
  test/Surface_mesh_multiresolution/memcheck/memcheck_pipeline.cpp -o "$BUILD/memcheck_pipeline" -lgmp -lmpfr -ltbb
valgrind --error-exitcode=3 --track-origins=yes -q "$BUILD/memcheck_pipeline"
