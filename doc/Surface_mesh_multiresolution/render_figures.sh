#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Renders the figures of the user manual (fig/*.png) from the examples' outputs, headless,
# with Debian's f3d under xvfb-run: Fig. 3 (colour relaxation), Fig. 5 (filters), Fig. 6b
# (denoising), Fig. 6c (colour- and geometry-guided adaptive reconstruction) and, when
# ../shared/data is present, the denoising comparison (fandisk and the scanned bunny of the
# standard noisy/clean pairs: noisy, bilateral normal filtering at its best, denoise()).
# Fig. 5 uses ../shared/data/venus-original.off.xz when present, else CGAL's armadillo.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
bash "$ROOT/scripts/install_dependencies.sh" f3d xvfb xauth imagemagick
BUILD=${SMR_BUILD_DIR:-$ROOT/build}
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$BUILD" -j"$(nproc)" --target filter_bands denoise adaptive_reconstruction relax_colors
EX="$BUILD/examples/Surface_mesh_multiresolution"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
render() {   # render <ply> <png> [f3d options...]
  local in=$1 out=$2; shift 2
  xvfb-run -a f3d "$in" --output="$HERE/fig/$out" --resolution=480,400 --fxaa --color=0.85,0.85,0.9 "$@" > /dev/null 2>&1
  echo "fig/$out"
}
mkdir -p "$HERE/fig"

"$EX/relax_colors" > /dev/null
for i in 0 1 20; do render "colors_$i.ply" "fig3_colors_$i.png" --scalars=RGBA --comp=-2; done

VENUS="$ROOT/../shared/data/venus-original.off.xz"
if [ -f "$VENUS" ]; then xz -dc "$VENUS" > venus.off; "$EX/filter_bands" venus.off > /dev/null; VIEW=(--up=+Z --camera-azimuth-angle=150)
else "$EX/filter_bands" > /dev/null; VIEW=(--up=+Y --camera-azimuth-angle=180); fi
for f in input low_pass stop_band enhanced; do render "filter_$f.ply" "fig5_$f.png" "${VIEW[@]}"; done

"$EX/denoise" > /dev/null
for f in noisy denoised; do render "$f.ply" "fig6b_$f.png" --camera-azimuth-angle=30 --camera-elevation-angle=30; done

"$EX/adaptive_reconstruction" > /dev/null
for f in geometry colour; do render "adaptive_$f.ply" "fig6c_$f.png" --scalars=RGBA --comp=-2 -e --up=+Y; done

DATA="$ROOT/../shared/data"
if [ -f "$DATA/gd_Fandisk0.3_Noisy.obj.xz" ]; then
  cmake -S "$ROOT" -B "$BUILD" -DSMR_BUILD_BENCHMARKS=ON > /dev/null
  cmake --build "$BUILD" -j"$(nproc)" --target bench_denoise
  pairs=()
  for m in Fandisk0.3 Bunny0.2; do
    for k in Noisy Original; do xz -dc "$DATA/gd_${m}_$k.obj.xz" > "gd_${m}_$k.obj"; done
    pairs+=("gd_${m}_Noisy.obj" "gd_${m}_Original.obj")
  done
  "$BUILD/benchmark/Surface_mesh_multiresolution/bench_denoise" --write . "${pairs[@]}" > /dev/null
  for k in noisy bnf smr; do
    xvfb-run -a f3d "gd_Fandisk0.3_Noisy_$k.ply" --output="fandisk_$k.png" --resolution=480,400 --fxaa --color=0.85,0.85,0.9 \
      --camera-azimuth-angle=120 --camera-elevation-angle=35 > /dev/null 2>&1
    xvfb-run -a f3d "gd_Bunny0.2_Noisy_$k.ply" --output="bunny_$k.png" --resolution=480,400 --fxaa --color=0.85,0.85,0.9 \
      --up=+Y > /dev/null 2>&1
  done
  montage fandisk_noisy.png fandisk_bnf.png fandisk_smr.png bunny_noisy.png bunny_bnf.png bunny_smr.png \
    -tile 3x2 -geometry +0+0 "$HERE/fig/denoise_comparison.png"
  echo "fig/denoise_comparison.png"
fi
