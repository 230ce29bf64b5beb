#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Time against vertex count for our decomposition and reconstruction and for the peers
# (CGAL SMS edge_collapse GH, OpenMesh independent-set decimater, meshopt_simplify), all to
# 1 % of the vertices, measured by bench_pyramid in one run, drawn by gnuplot into
# benchmark/Surface_mesh_multiresolution/timings.png. Meshes: the dragon at its four
# resolutions, the bunny and the horse from ../shared/data (else CGAL's data meshes).
# Usage: plot_timings.sh [build folder of run_benchmarks.sh [--plot-only]]
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
BUILD=${1:-$ROOT/build-bench}
bash "$ROOT/scripts/install_dependencies.sh" libopenmesh-dev libmeshoptimizer-dev gnuplot-nox
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DSMR_BUILD_BENCHMARKS=ON -DSMR_BUILD_TESTS=OFF -DSMR_BUILD_EXAMPLES=OFF > /dev/null
cmake --build "$BUILD" -j"$(nproc)" --target bench_pyramid
DATA="$ROOT/../shared/data"
files=()
if [ -d "$DATA" ]; then
  mkdir -p "$BUILD/data"
  for f in dragon_vrip_res4.ply dragon_vrip_res3.ply bun_zipper.ply horse.ply dragon_vrip_res2.ply dragon_vrip.ply; do
    [ -f "$BUILD/data/$f" ] || xz -dc "$DATA/$f.xz" > "$BUILD/data/$f"
    files+=("$BUILD/data/$f")
  done
fi
TABLE="$BUILD/timings.md"
[ "${2:-}" = "--plot-only" ] || "$BUILD/benchmark/Surface_mesh_multiresolution/bench_pyramid" "${files[@]}" | tee "$TABLE"
# columns: vertices, decompose, reconstruct, SMS, OpenMesh, meshopt (seconds), from the rows of
# the first table only (16 columns; the file table after it has 9)
awk -F'|' 'NF == 18 && $3 ~ /^ *[0-9]+ *$/ { gsub(/\([^)]*\)/, ""); print $3, $6, $7, $9, $10, $11 }' "$TABLE" | sort -n > "$BUILD/timings.dat"
gnuplot <<GNUPLOT
set terminal pngcairo size 900,600 font ",11" noenhanced
set output "$HERE/timings.png"
set logscale xy
set xlabel "input vertices"
set ylabel "seconds (to the vertex count of the coarsest level)"
set key top left
set grid
set title "Surface_mesh_multiresolution and peers (one run, $(nproc) cores)"
plot "$BUILD/timings.dat" using 1:4 with linespoints lw 2 title "CGAL SMS edge_collapse (GH)", \
     "" using 1:5 with linespoints lw 2 title "OpenMesh decimater (independent sets)", \
     "" using 1:2 with linespoints lw 2 title "SMR decompose (pyramid)", \
     "" using 1:6 with linespoints lw 2 title "meshopt_simplify", \
     "" using 1:3 with linespoints lw 2 title "SMR reconstruct"
GNUPLOT
echo "benchmark/Surface_mesh_multiresolution/timings.png"
