// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SPARSE_WEIGHTS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SPARSE_WEIGHTS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>

#include <cstddef>
#include <vector>


namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// Row-stochastic weights in compressed sparse rows: row i holds the pairs
// (columns[k], values[k]) for offsets[i] <= k < offsets[i+1]. Two kinds of arrays (the same
// rows, the same arithmetic): Sparse_weights, the package's own, whose resize() leaves the
// entries uninitialised (Uninitialized_vector: the builders write every entry; the zero fill
// of a std::vector was a sequential memset of 12 bytes per entry, with its first-touch page
// faults, at every level of a decomposition), and Operator_weights, in the std::vector types
// that Relaxation_operator's accessors return.
template <typename IndexVector, typename ValueVector>
struct Basic_sparse_weights
{
  IndexVector offsets{0};
  IndexVector columns;
  ValueVector values;

  std::size_t number_of_rows() const { return offsets.size() - 1; }

  // out[i] = sum_j w_ij in[j], where in/out hold `dimension` doubles per row. in != out.
  void apply(const double* in, double* out, std::size_t dimension) const
  {
    // rows are independent: the result does not depend on the number of threads
    parallel_for_blocks(number_of_rows(), [&](std::size_t first, std::size_t last) { apply_rows(in, out, dimension, first, last); });
  }

  void apply_rows(const double* in, double* out, std::size_t dimension, std::size_t first, std::size_t last) const
  {
    switch(dimension)
    {
      case 1: apply_fixed<1>(in, out, first, last); break;
      case 2: apply_fixed<2>(in, out, first, last); break;
      case 3: apply_fixed<3>(in, out, first, last); break;
      case 4: apply_fixed<4>(in, out, first, last); break;
      default:
        for(std::size_t i = first; i < last; ++i)
          row_general(i, in, out, dimension);
    }
  }

  // out[r] = sum_j w_rj in[j] for the rows r listed in rows[0..count) only (same arithmetic
  // as apply(), so that a pyramid's decomposition and reconstruction agree bit for bit)
  void apply_row_list(const double* in, double* out, std::size_t dimension, const Index* rows, std::size_t count) const
  {
    parallel_for_blocks(count, [&](std::size_t first, std::size_t last) {
      switch(dimension)
      {
        case 1: for(std::size_t q = first; q < last; ++q) row_fixed<1>(rows[q], in, out); break;
        case 2: for(std::size_t q = first; q < last; ++q) row_fixed<2>(rows[q], in, out); break;
        case 3: for(std::size_t q = first; q < last; ++q) row_fixed<3>(rows[q], in, out); break;
        case 4: for(std::size_t q = first; q < last; ++q) row_fixed<4>(rows[q], in, out); break;
        default: for(std::size_t q = first; q < last; ++q) row_general(rows[q], in, out, dimension);
      }
    });
  }

  // o[0..dimension) = sum_k val[k] in[col[k]] over one row of `length` entries: the arithmetic
  // of apply(), for rows that are not stored (Relaxation_weight_builder::build_and_apply())
  static void combine(const Index* col, const double* val, std::size_t length, const double* in, double* o,
                      std::size_t dimension)
  {
    switch(dimension)
    {
      case 1: combine_fixed<1>(col, val, length, in, o); break;
      case 2: combine_fixed<2>(col, val, length, in, o); break;
      case 3: combine_fixed<3>(col, val, length, in, o); break;
      case 4: combine_fixed<4>(col, val, length, in, o); break;
      default: combine_general(col, val, length, in, o, dimension);
    }
  }

private:
  template <std::size_t D>
  static void combine_fixed(const Index* col, const double* val, std::size_t length, const double* in, double* o)
  {
    double acc[D] = {};
    for(std::size_t k = 0; k < length; ++k)
    {
      const double w = val[k];
      const double* x = in + std::size_t(col[k]) * D;
      for(std::size_t c = 0; c < D; ++c) acc[c] += w * x[c];
    }
    for(std::size_t c = 0; c < D; ++c) o[c] = acc[c];
  }

  static void combine_general(const Index* col, const double* val, std::size_t length, const double* in, double* o,
                              std::size_t dimension)
  {
    for(std::size_t c = 0; c < dimension; ++c) o[c] = 0.;
    for(std::size_t k = 0; k < length; ++k)
    {
      const double w = val[k];
      const double* x = in + std::size_t(col[k]) * dimension;
      for(std::size_t c = 0; c < dimension; ++c) o[c] += w * x[c];
    }
  }

  template <std::size_t D>
  void row_fixed(std::size_t i, const double* in, double* out) const
  {
    combine_fixed<D>(columns.data() + offsets[i], values.data() + offsets[i], offsets[i + 1] - offsets[i], in, out + i * D);
  }

  void row_general(std::size_t i, const double* in, double* out, std::size_t dimension) const
  {
    combine_general(columns.data() + offsets[i], values.data() + offsets[i], offsets[i + 1] - offsets[i], in,
                    out + i * dimension, dimension);
  }

  template <std::size_t D>
  void apply_fixed(const double* in, double* out, std::size_t first, std::size_t last) const
  {
    for(std::size_t i = first; i < last; ++i)
      row_fixed<D>(i, in, out);
  }
};

typedef Basic_sparse_weights<Index_array, Uninitialized_vector<double> > Sparse_weights;
typedef Basic_sparse_weights<std::vector<Index>, std::vector<double> > Operator_weights;

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SPARSE_WEIGHTS_H
