#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the benchmarks (Release) and runs them on the paper's meshes when ../shared/data is
# present (decompressed into the build folder), else on CGAL's largest data meshes.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD=${SMR_BENCH_BUILD_DIR:-$ROOT/build-bench}
bash "$ROOT/scripts/install_dependencies.sh" libopenmesh-dev libmeshoptimizer-dev
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DSMR_BUILD_BENCHMARKS=ON -DSMR_BUILD_TESTS=OFF -DSMR_BUILD_EXAMPLES=OFF > /dev/null
cmake --build "$BUILD" -j"$(nproc)" --target bench_relaxation bench_pyramid bench_denoise
DATA="$ROOT/../shared/data"
files=()
if [ -d "$DATA" ]; then
  mkdir -p "$BUILD/data"
  for f in bun_zipper.ply horse.ply dragon_vrip.ply; do
    [ -f "$BUILD/data/$f" ] || xz -dc "$DATA/$f.xz" > "$BUILD/data/$f"
    files+=("$BUILD/data/$f")
  done
fi
echo "## bench_relaxation"
"$BUILD/benchmark/Surface_mesh_multiresolution/bench_relaxation" "${files[@]}"
echo
echo "## bench_pyramid"
"$BUILD/benchmark/Surface_mesh_multiresolution/bench_pyramid" "${files[@]}"
echo
echo "## bench_pyramid --ratio (decomposition against meshopt_simplify, alternating pairs)"
"$BUILD/benchmark/Surface_mesh_multiresolution/bench_pyramid" --ratio 7 "${files[@]}"
pairs=()
if [ -d "$DATA" ]; then
  for m in Fandisk0.3 Fandisk0.7 Block0.4 Twelve0.5Impulsive SharpSphere0.3 Bunny0.2; do
    for k in Noisy Original; do
      [ -f "$BUILD/data/gd_${m}_$k.obj" ] || xz -dc "$DATA/gd_${m}_$k.obj.xz" > "$BUILD/data/gd_${m}_$k.obj"
    done
    pairs+=("$BUILD/data/gd_${m}_Noisy.obj" "$BUILD/data/gd_${m}_Original.obj")
  done
  for m in nicolo julius; do
    for k in noisy original; do
      [ -f "$BUILD/data/gd_${m}_$k.obj" ] || xz -dc "$DATA/gd_${m}_$k.obj.xz" > "$BUILD/data/gd_${m}_$k.obj"
    done
    pairs+=("$BUILD/data/gd_${m}_noisy.obj" "$BUILD/data/gd_${m}_original.obj")
  done
fi
# CGAL meshes with Gaussian noise along the normals and isotropic, 0.2 and 0.5 mean edge lengths
MESHES="$BUILD/cgal_data/data/meshes"
for kind in --synthetic --isotropic; do
  for m in elephant.off armadillo.off; do
    for s in 0.2 0.5; do
      [ -f "$MESHES/$m" ] && pairs+=("$kind" "$MESHES/$m" "$s")
    done
  done
done
echo
echo "## bench_denoise"
"$BUILD/benchmark/Surface_mesh_multiresolution/bench_denoise" "${pairs[@]}"
