#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Times the decompositions and reconstructions of two trees of this package against each
# other in one process.
#
#   compare_trees.sh TREE_A TREE_B FILE [THREADS] [ROUNDS]
#
# TREE_A and TREE_B are checkouts of the repository (their include/ folders are used; make
# one with `git worktree add /tmp/base HEAD`). Both copies are compiled into one program, the
# namespace CGAL renamed in each (the package and CGAL are header-only), which loads FILE
# once per copy and alternates their decompositions to 1 % and full reconstructions (A B,
# then B A, ...): on a shared machine whose speed drifts by 10-30 % within minutes, timing one
# tree's process after the other's cannot resolve a change of a few percent; pairs in one
# process see the same state. Prints, per step, the best of each tree, the ratio of the bests,
# the median of the pairs' ratios, and whether the two pyramids are the same bit for bit (for
# the reconstructions: whether both are exact). The same sources in two copies gave median
# ratios of 0.98-1.02 with 12 pairs on the reference machine, 0.92-1.07 with 8 in a noisier
# hour: the noise of this measure.
# Defaults: 1 thread, 12 pairs. Needs g++ (or CXX) and the packages of the build (CGAL, TBB,
# Eigen, GMP, MPFR).
set -eu
if [ $# -lt 3 ]; then
  sed -n '3,20p' "$0"
  exit 1
fi
here=$(cd "$(dirname "$0")" && pwd)
tree_a=$(cd "$1" && pwd)
tree_b=$(cd "$2" && pwd)
file=$3
threads=${4:-1}
rounds=${5:-12}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
flags="-std=c++17 -O3 -DNDEBUG -frounding-math -DCGAL_EIGEN3_ENABLED -DCGAL_LINKED_WITH_TBB -DCGAL_USE_GMPXX=1 -isystem /usr/include/eigen3"
${CXX:-g++} $flags -I"$tree_a/include" -DCGAL=CGAL_tree_a '-DSIDE(x)=a_##x' -c "$here/compare_trees/tree.cpp" -o "$work/a.o" &
${CXX:-g++} $flags -I"$tree_b/include" -DCGAL=CGAL_tree_b '-DSIDE(x)=b_##x' -c "$here/compare_trees/tree.cpp" -o "$work/b.o" &
${CXX:-g++} -std=c++17 -O2 -c "$here/compare_trees/main.cpp" -o "$work/main.o"
wait
${CXX:-g++} "$work/main.o" "$work/a.o" "$work/b.o" -o "$work/compare" -ltbb -lgmpxx -lgmp -lmpfr
echo "A: $tree_a"
echo "B: $tree_b"
echo "mesh: $file"
"$work/compare" "$file" "$threads" "$rounds"
