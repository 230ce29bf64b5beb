#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Renders the figures of the user manual (fig/*.png), headless, with Debian's f3d under
# xvfb-run, each of the paper's figures as one labelled multi-panel image (ImageMagick's
# montage): Fig. 2 (the three relaxation operators on the eye of a scanned head), Fig. 3
# (colour relaxation), Fig. 5 (filters), Fig. 6 (a colour scan: denoising, colour- and
# geometry-guided adaptive reconstruction, magnified with their edges), from the smr tool and
# the examples; and the denoising comparison (fandisk and the scanned bunny of the standard
# noisy/clean pairs: noisy, bilateral normal filtering at its best, denoise()). Figs. 2, 5
# and 6 use the scans of ../shared/data (Venus, frag_115) when present, else CGAL meshes.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
bash "$ROOT/scripts/install_dependencies.sh" f3d xvfb xauth imagemagick fonts-dejavu-core
BUILD=${SMR_BUILD_DIR:-$ROOT/build}
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$BUILD" -j"$(nproc)" --target smr filter_bands denoise adaptive_reconstruction relax_colors
EX="$BUILD/examples/Surface_mesh_multiresolution"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
mkdir -p "$HERE/fig"

SMR="$BUILD/tools/smr/smr -q"
FONT=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
shot() {   # shot <mesh> <png> <width> <height> [f3d options...]: a panel in the work folder
  local in=$1 out=$2 w=$3 h=$4; shift 4
  xvfb-run -a f3d "$in" --output="$out" --resolution="$w,$h" --fxaa --color=0.85,0.85,0.9 "$@" > /dev/null 2>&1
}
figure() {   # figure <png> <columns> "label" panel.png ...: one labelled image of the paper's figure
  local out=$1 cols=$2; shift 2
  local args=()
  while [ $# -gt 0 ]; do args+=(-label "$1" "$2"); shift 2; done
  montage -font "$FONT" -pointsize 22 "${args[@]}" -tile "${cols}x" -geometry +4+4 -background white "$HERE/fig/$out"
  echo "fig/$out"
}
DATA="$ROOT/../shared/data"

# Fig. 2: (a) a scanned head's eye, (b) uniform Laplacian, (c) SOD, (d) curvature, 10 steps each
if [ -f "$DATA/venus-original.off.xz" ]; then
  xz -dc "$DATA/venus-original.off.xz" > venus.off
  EYE=(--up=+Z --camera-position=2.0,-0.10,-0.03 --camera-focal-point=0.3,-0.10,-0.03 --camera-view-up=0,0,1 --camera-view-angle=11 -e)
else
  cp "$BUILD/cgal_data/data/meshes/bunny00.off" venus.off; EYE=(--up=+Y -e)
fi
for s in uniform sod curvature; do $SMR relax venus.off -o "relaxed_$s.ply" --scheme "$s" --iterations 10; done
shot venus.off f2a.png 600 480 "${EYE[@]}"
for s in uniform sod curvature; do shot "relaxed_$s.ply" "f2_$s.png" 600 480 "${EYE[@]}"; done
figure fig2_relaxation.png 2 "(a) initial mesh" f2a.png "(b) uniform Laplacian, 10 steps" f2_uniform.png \
  "(c) SOD relaxation, 10 steps" f2_sod.png "(d) curvature relaxation, 10 steps" f2_curvature.png

# Fig. 3: colour relaxation on a part of a regular sphere
"$EX/relax_colors" > /dev/null
for i in 0 1 20; do shot "colors_$i.ply" "f3_$i.png" 420 420 --scalars=RGBA --comp=-2; done
figure fig3_colors.png 3 "(a) initial colours" f3_0.png "(b) 1 iteration" f3_1.png "(c) 20 iterations" f3_20.png

# Fig. 6b on a synthetic case: CGAL's fandisk with noise, and denoise()'s result
"$EX/denoise" > /dev/null
for f in noisy denoised; do shot "$f.ply" "f6b_$f.png" 560 480 --camera-azimuth-angle=30 --camera-elevation-angle=30; done
figure fig6b_fandisk.png 2 "noisy (0.3 mean edges along the normals)" f6b_noisy.png "denoise()" f6b_denoised.png

# Fig. 5: filtering of the Venus head
if [ -f venus.off ] && [ -f "$DATA/venus-original.off.xz" ]; then "$EX/filter_bands" venus.off > /dev/null; VIEW=(--up=+Z --camera-azimuth-angle=150)
else "$EX/filter_bands" > /dev/null; VIEW=(--up=+Y --camera-azimuth-angle=180); fi
for f in input low_pass stop_band enhanced; do shot "filter_$f.ply" "f5_$f.png" 500 500 "${VIEW[@]}"; done
figure fig5_filters.png 4 "(a) initial model" f5_input.png "(b) low pass" f5_low_pass.png "(c) stop band" f5_stop_band.png \
  "(d) enhancement" f5_enhanced.png

# Fig. 6: a colour scan denoised, then simplified to 10 % guided by its colours (and, to
# compare, by its geometry), magnified with the edges
if [ -f "$DATA/frag_115.ply.xz" ]; then
  xz -dc "$DATA/frag_115.ply.xz" > scan.ply
  RGB=(--scalars=RGB --comp=-2)
  ZOOM=(--camera-position=3.23,1.79,3.68 --camera-focal-point=1.95,2.15,1.0 --camera-view-up=0,1,0 --camera-view-angle=12 -e)
else
  "$EX/adaptive_reconstruction" > /dev/null   # CGAL's elephant with a colour checkerboard
  $SMR relax adaptive_geometry.ply -o scan.ply --iterations 0 2> /dev/null || true
  RGB=(--scalars=RGBA --comp=-2); ZOOM=(-e --camera-view-angle=15)
fi
$SMR decompose scan.ply -o scan.smrp
$SMR denoise scan.smrp -o denoised.ply
$SMR lod denoised.ply -o lod_colour.ply --ratio 0.1 --guide color
$SMR lod denoised.ply -o lod_geometry.ply --ratio 0.1
shot scan.ply f6a.png 500 500 "${RGB[@]}"
shot denoised.ply f6b.png 500 500 "${RGB[@]}"
shot lod_colour.ply f6c.png 500 500 "${RGB[@]}"
shot lod_geometry.ply f6c_geometry.png 500 500 "${RGB[@]}"
shot lod_colour.ply f6d.png 500 500 "${RGB[@]}" "${ZOOM[@]}"
shot lod_geometry.ply f6d_geometry.png 500 500 "${RGB[@]}" "${ZOOM[@]}"
figure fig6_scan.png 3 "(a) colour scan" f6a.png "(b) denoised" f6b.png "(c) 10 %%, guided by the colours" f6c.png \
  "(c') 10 %%, guided by the geometry" f6c_geometry.png "(d) (c) magnified" f6d.png "(d') (c') magnified" f6d_geometry.png

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
