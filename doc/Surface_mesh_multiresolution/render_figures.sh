#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Renders the figures of the user manual (fig/*.png) from the examples' outputs, headless,
# with Debian's f3d under xvfb-run: Fig. 3 (colour relaxation), Fig. 5 (filters), Fig. 6b
# (denoising) and Fig. 6c (colour- and geometry-guided adaptive reconstruction).
# Fig. 5 uses ../shared/data/venus-original.off.xz when present, else CGAL's armadillo.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
bash "$ROOT/scripts/install_dependencies.sh" f3d xvfb xauth
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
