// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_LEVEL_TRANSFORM_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_LEVEL_TRANSFORM_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Sparse_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The analysis (Eq. 5) and synthesis (Eq. 6 and 7) of one level, in the rows of M_k, shared by
// decompose(), reconstruct(), denoise() and the re-analysis of a pyramid: the bit-exactness
// contract lives in this file.
//
// Odd rows are predicted from a state where each odd vertex holds the value of the vertex it
// collapses into (known on M_{k+1}), even rows from the original values (Eq. 6 and 7; with the
// curvature and uniform schemes an odd row only involves even vertices, so this is exactly
// Eq. 5). The synthesis computes the same predictions from the same values, so
// v = p + d (+ correction) gives back f bit for bit:
// - where fl(p + d) differs from f by rounding, an additive correction f - fl(p + d) is stored;
// - a prediction that is not finite (weights applied to values near the largest double) is
//   taken as 0 on both sides, and a detail f - p that would overflow is stored as -p (so that
//   p + d = 0) with f as its correction: every finite input comes back exactly;
// - -0.0 comes back as -0.0: p + (-p) is +0.0, and adding a correction cannot change the sign
//   of a zero, so a zero correction means "this zero has the correction's sign"
//   (apply_correction()). Analysis emits one only where fl(p + d) equals f but for the sign.

typedef std::vector<std::pair<Index, double> > Corrections;

inline double usable_prediction(double p) { return std::isfinite(p) ? p : 0.; }

// v + c for a correction c; a zero correction gives a zero v the sign of c (-0.0 exactly)
inline double apply_correction(double v, double c) { return c != 0. ? v + c : (v == 0. ? c : v); }

// the odd rows of `state` (rows of M_k) receive the values of their collapse targets (even
// rows, not written here: in parallel)
inline void odd_values_from_targets(const Pyramid_level& lev, std::size_t dim, double* state)
{
  parallel_for_blocks(lev.odd_rows.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t q = first; q < last; ++q)
      copy_values(state + std::size_t(lev.collapse_targets[q]) * dim, dim, state + std::size_t(lev.odd_rows[q]) * dim);
  });
}

// the state synthesis starts from: the values of M_{k+1} (`coarse`, its rows) at the even rows
// of M_k, and at each odd row the value of its collapse target
inline void spread_to_level(const Pyramid_level& lev, std::size_t dim, const double* coarse, std::vector<double>& state)
{
  state.resize(lev.number_of_rows() * dim);
  parallel_for_blocks(lev.even_rows.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t j = first; j < last; ++j)
      copy_values(coarse + j * dim, dim, state.data() + std::size_t(lev.even_rows[j]) * dim);
  });
  odd_values_from_targets(lev, dim, state.data());
}

// values_of_next_level() in place: f reduced to the rows of M_{k+1}, its capacity kept (the
// even rows increase, so row j is read where it lies before any row writes there). A new
// array per level, as large as the level, was mapped and touched anew on large meshes.
template <typename T>
void keep_values_of_next_level(const Pyramid_level& lev, std::size_t dim, std::vector<T>& f)
{
  // in blocks of rows of M_{k+1}, in parallel waves (move_down_in_waves()): block b writes rows
  // [b B, (b + 1) B) and reads from row even_rows[b B] on
  constexpr std::size_t block = 4096;
  T* data = f.data();
  const Index* even = lev.even_rows.data();
  const std::size_t n = lev.even_rows.size();
  move_down_in_waves((n + block - 1) / block,
                     [&](std::size_t b) { return std::size_t(even[b * block]); },
                     [&](std::size_t b) { return (std::min)(n, (b + 1) * block); },
                     [&](std::size_t b) {
                       for(std::size_t j = b * block, e = (std::min)(n, (b + 1) * block); j < e; ++j)
                         if(std::size_t(even[j]) != j)
                           copy_values(data + std::size_t(even[j]) * dim, dim, data + j * dim);
                     });
  f.resize(n * dim);
}

// the values of M_{k+1} (rows) from those of M_k: even vertices keep their values
template <typename T>
void values_of_next_level(const Pyramid_level& lev, std::size_t dim, const std::vector<T>& f, std::vector<T>& next)
{
  next.resize(lev.even_rows.size() * dim);
  for(std::size_t j = 0; j < lev.even_rows.size(); ++j)
    copy_values(f.data() + std::size_t(lev.even_rows[j]) * dim, dim, next.data() + j * dim);
}

// Eq. 5, last step: the details of one channel (f: rows of M_k) from its predictions
// (prediction_of(k): the prediction of value k), written to details[k], and the corrections
// where prediction + detail misses f. prediction_of(k) may read details[k]: that value is read
// before it is written.
template <typename PredictionOf>
void details_and_corrections(const std::vector<double>& f, const PredictionOf& prediction_of, double* details,
                             Corrections& corrections)
{
  const std::size_t n = f.size();
  // One pass, in parallel over fixed blocks of values: each block writes its details and lists
  // its corrections (rare: rounding or overflow) apart, and the lists are joined in block
  // order, so the corrections come in increasing k for any number of threads. (An ordered
  // compaction computed every detail twice, once to count the corrections and once to write
  // them: a second pass over the level's values and predictions, 2-3 % of a decomposition.)
  constexpr std::size_t block = std::size_t(1) << 14;
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<Corrections> of_block(blocks);
  parallel_for_blocks(blocks, [&](std::size_t b0, std::size_t b1) {
    for(std::size_t b = b0; b < b1; ++b)
      for(std::size_t k = b * block, e = (std::min)(n, (b + 1) * block); k < e; ++k)
      {
        const double p = usable_prediction(prediction_of(k));
        double d = f[k] - p;
        if(!std::isfinite(d))
          d = -p;
        const double t = p + d;
        if(t != f[k] || std::signbit(t) != std::signbit(f[k]))
          of_block[b].emplace_back(static_cast<Index>(k), f[k] - t);
        details[k] = d;
      }
  }, 1);
  std::size_t total = 0;
  for(const Corrections& c : of_block)
    total += c.size();
  corrections.clear();
  corrections.reserve(total);
  for(const Corrections& c : of_block)
    corrections.insert(corrections.end(), c.begin(), c.end());
}

inline void details_from_predictions(const std::vector<double>& f, const double* prediction, std::vector<double>& details,
                                     Corrections& corrections)
{
  details.resize(f.size());
  details_and_corrections(f, [&](std::size_t k) { return prediction[k]; }, details.data(), corrections);
}

// Eq. 5: the details and corrections of one channel (f: rows of M_k) with the weights w
inline void analyse_level(const Pyramid_level& lev, const Sparse_weights& w, std::size_t dim, const std::vector<double>& f,
                          std::vector<double>& details, Corrections& corrections)
{
  const std::size_t n = lev.number_of_rows() * dim;
  std::vector<double> state(f);
  Uninitialized_vector<double> prediction(n);   // every row is odd or even: all written
  odd_values_from_targets(lev, dim, state.data());
  w.apply_row_list(state.data(), prediction.data(), dim, lev.odd_rows.data(), lev.odd_rows.size());
  w.apply_row_list(f.data(), prediction.data(), dim, lev.even_rows.data(), lev.even_rows.size());
  details_from_predictions(f, prediction.data(), details, corrections);
}

// Eq. 5 for every channel of a level of a 1-ring scheme (curvature, uniform) at once, with
// weights computed row by row and not stored: compute_rows(apply_row) hands every row i of M_k
// once to apply_row(i, columns, values, length) (Relaxation_weight_builder::apply_rows()), in
// any order and in parallel, and each row is applied to every channel there, with the sums of
// Sparse_weights::apply_row_list() (Sparse_weights::combine()). An analysis applies each row
// once, so storing the rows only wrote and read them again (12 bytes per entry).
// Every row is applied to the values f themselves. analyse_level() applies the odd rows to a
// state whose odd rows hold their targets' values; but an odd row's columns are its 1-ring
// neighbours (border rows: its border neighbours; never the row itself), all even since no two
// odd vertices are adjacent, so the state equals f wherever such a row reads it, and the
// predictions are analyse_level()'s bit for bit. (Not so for SOD, whose rows reach the
// 2-ring.) The predictions therefore depend on M_k and its values alone, not on the level's
// selection: the decomposition computes them beside it. f[c]: channel c (dims[c] per row) in
// the rows of M_k; prediction[c]: f[c].size() values, allocated by the caller, all written
// (details_in_place() turns them into the details).
template <typename ComputeRows>
void predict_with_rows_once(const ComputeRows& compute_rows, const std::vector<std::size_t>& dims,
                            const std::vector<std::vector<double> >& f, std::vector<std::vector<double> >& prediction)
{
  const std::size_t nc = f.size();
  compute_rows([&](std::size_t i, const Index* col, const double* val, std::size_t length) {
    for(std::size_t c = 0; c < nc; ++c)
      Sparse_weights::combine(col, val, length, f[c].data(), prediction[c].data() + i * dims[c], dims[c]);
  });
}

// the details and corrections of every channel, the details written over its predictions
// (predict_with_rows_once(); no second array of the level's size)
inline void details_in_place(const std::vector<std::vector<double> >& f, std::vector<std::vector<double> >& details,
                             std::vector<Corrections>& corrections)
{
  corrections.resize(f.size());
  for(std::size_t c = 0; c < f.size(); ++c)
  {
    double* d = details[c].data();
    details_and_corrections(f[c], [d](std::size_t k) { return d[k]; }, d, corrections[c]);
  }
}

inline void odd_row_flags(const Pyramid_level& lev, std::vector<unsigned char>& is_odd)
{
  is_odd.assign(lev.number_of_rows(), 0);
  for(Index r : lev.odd_rows)
    is_odd[r] = 1;
}

// state = prediction + detail on the rows listed (distinct: in parallel)
inline void add_details(const std::vector<Index>& rows, std::size_t dim, const std::vector<double>& prediction, const double* d,
                        std::vector<double>& state)
{
  parallel_for_blocks(rows.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t q = first; q < last; ++q)
      for(std::size_t i = std::size_t(rows[q]) * dim; i < (std::size_t(rows[q]) + 1) * dim; ++i)
        state[i] = usable_prediction(prediction[i]) + d[i];
  });
}

// Eq. 6 then Eq. 7 on the rows of M_k with the weights w (Sparse_weights, or any class with
// its apply_row_list(): Level_weights::Rows_as_applied), each row applied once: `state` comes
// from spread_to_level(); on return, the values of M_k. is_odd: odd_row_flags() of the level.
template <typename Weights>
void synthesize_level(const Pyramid_level& lev, const Weights& w, std::size_t dim, const double* d,
                      const Corrections& corrections, const std::vector<unsigned char>& is_odd,
                      std::vector<double>& state, std::vector<double>& prediction)
{
  prediction.resize(state.size());
  // Eq. 6: odd vertices (corrected before the even vertices read them)
  w.apply_row_list(state.data(), prediction.data(), dim, lev.odd_rows.data(), lev.odd_rows.size());
  add_details(lev.odd_rows, dim, prediction, d, state);
  for(const auto& cr : corrections)
    if(is_odd[cr.first / dim])
      state[cr.first] = apply_correction(state[cr.first], cr.second);
  // Eq. 7: even vertices, from the intermediate mesh
  w.apply_row_list(state.data(), prediction.data(), dim, lev.even_rows.data(), lev.even_rows.size());
  add_details(lev.even_rows, dim, prediction, d, state);
  for(const auto& cr : corrections)
    if(!is_odd[cr.first / dim])
      state[cr.first] = apply_correction(state[cr.first], cr.second);
}

// The face array of M_k (rows of M_k) from the one of M_{k+1} (rows of M_{k+1}): rows
// renumbered, removed faces back at their places, odd vertices back at their corners (vertex
// splits on arrays). Written into `scratch`, which is then swapped with F, in parallel blocks of
// M_k's faces: face p is the removed face r when removed_face_positions[r] == p, else the kept
// face p - r of M_{k+1}, where r removed positions lie before p (a binary search at each
// block's start). Why not in place: the merge from the end was sequential (7 % of a
// reconstruction of the dragon on two threads); callers that expand level after level keep
// one scratch array, reserved at the largest size, so no level allocates.
inline void expand_faces(const Pyramid_level& lev, std::vector<Index>& F, std::vector<Index>& scratch)
{
  const std::vector<Index>& removed = lev.removed_face_positions;
  const std::size_t nf = F.size() / 3 + removed.size();
  scratch.resize(3 * nf);
  parallel_for_blocks(nf, [&](std::size_t first, std::size_t last) {
    std::size_t r = std::size_t(std::lower_bound(removed.begin(), removed.end(), first) - removed.begin());
    std::size_t kept = first - r;
    for(std::size_t p = first; p < last; ++p)
    {
      Index* face = scratch.data() + 3 * p;
      if(r < removed.size() && removed[r] == p)
        copy_values(lev.removed_faces.data() + 3 * r++, 3, face);
      else
      {
        const Index* before = F.data() + 3 * kept++;
        for(int c = 0; c < 3; ++c)
          face[c] = lev.even_rows[before[c]];
      }
    }
  }, 4096);
  // distinct corners (check_records_and_expand_faces() checks a file's)
  parallel_for_blocks(lev.renamed_corners.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t q = first; q < last; ++q)
      scratch[lev.renamed_corners[q]] = lev.renamed_vertices[q];
  });
  F.swap(scratch);
}

// expand_faces() with a scratch array of its own, for a single expansion
inline void expand_faces(const Pyramid_level& lev, std::vector<Index>& F)
{
  std::vector<Index> scratch;
  expand_faces(lev, F, scratch);
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_LEVEL_TRANSFORM_H
