#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The main job: installs what is missing, builds the command-line tool and the examples and
# runs them on a real mesh of CGAL's data set (or the mesh given as first argument), writing
# results to out/: the tool through every subcommand, the pipeline (pyramid, filters,
# denoising, adaptive reconstruction), the pyramid's levels with the exact reconstruction,
# then the relaxation operators.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
BUILD=${SMR_BUILD_DIR:-build}
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$BUILD" -j"$(nproc)" --target smr pipeline decompose_reconstruct relax_geometry relax_colors filter_bands adaptive_reconstruction
ROOT=$PWD
mkdir -p out && cd out
SMR="$ROOT/$BUILD/tools/smr/smr"
MESH=${1:-"$ROOT/$BUILD/cgal_data/data/meshes/bunny00.off"}
echo "== The command-line tool smr on $MESH =="
"$SMR" info "$MESH"
"$SMR" decompose "$MESH" -o smr_pyramid.smrp
"$SMR" reconstruct smr_pyramid.smrp -o smr_level5.ply --level 5
"$SMR" filter smr_pyramid.smrp -o smr_enhanced.ply --enhance 2 4 2
"$SMR" denoise smr_pyramid.smrp -o smr_denoised.ply
"$SMR" lod smr_pyramid.smrp -o smr_lod_5pc.ply --ratio 0.05
"$SMR" relax "$MESH" -o smr_relaxed.ply --iterations 10
echo
echo "== Pipeline (Roy et al.): decompose, filter (Fig. 5), denoise (Fig. 6b), adaptive reconstruction (Fig. 6c) =="
"$ROOT/$BUILD/examples/Surface_mesh_multiresolution/pipeline" "$@"
echo
echo "== Mesh pyramid (Section 3): decomposition, levels, exact reconstruction =="
"$ROOT/$BUILD/examples/Surface_mesh_multiresolution/decompose_reconstruct" "$@"
echo
echo "== Relaxation operators (Fig. 2): one step of each scheme =="
"$ROOT/$BUILD/examples/Surface_mesh_multiresolution/relax_geometry" "$@"
echo
echo "== Colour relaxation (Fig. 3): weights from the geometry, applied to colours =="
"$ROOT/$BUILD/examples/Surface_mesh_multiresolution/relax_colors"
SHARED="$ROOT/../shared/data"
if [ -f "$SHARED/venus-original.off.xz" ] && [ -f "$SHARED/frag_115.ply.xz" ]; then
  # the paper's kind of data, when the project's data folder is there
  mkdir -p data
  [ -f data/venus-original.off ] || xz -dc "$SHARED/venus-original.off.xz" > data/venus-original.off
  [ -f data/frag_115.ply ] || xz -dc "$SHARED/frag_115.ply.xz" > data/frag_115.ply
  echo
  echo "== Filtering bands (Fig. 5) on the Venus head =="
  "$ROOT/$BUILD/examples/Surface_mesh_multiresolution/filter_bands" data/venus-original.off
  echo
  echo "== Adaptive reconstruction (Fig. 6c) of a scan with real colours, 10 % of the vertices =="
  "$ROOT/$BUILD/examples/Surface_mesh_multiresolution/adaptive_reconstruction" data/frag_115.ply 0.1
  echo
  echo "== The colour scan through smr: its colours and normals kept in every output =="
  "$SMR" info data/frag_115.ply
  "$SMR" -q decompose data/frag_115.ply -o frag_115.smrp
  "$SMR" lod frag_115.smrp -o frag_115_lod_colour_10pc.ply --ratio 0.1 --guide color
  "$SMR" lod frag_115.smrp -o frag_115_lod_geometry_10pc.ply --ratio 0.1
  "$SMR" filter frag_115.smrp -o frag_115_low_pass.ply --low-pass 3
fi
echo
echo "Results written to $ROOT/out: $(ls | tr '\n' ' ')"
