// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_RADIX_SORT_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_RADIX_SORT_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>

#include <CGAL/assertions.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// the digits of radix_sort_bits(): passes of 10 bits
constexpr int sort_digit_bits = 10;
constexpr std::size_t sort_buckets = std::size_t(1) << sort_digit_bits;

// The counts of the digits (in[i] >> shift) & (sort_buckets - 1), i in [first, last), into
// hist (sort_buckets entries), through `four` (4 sort_buckets scratch counters): four
// histograms counted in turn, then summed. Equal digits in a row (nearby costs; exact ties,
// common on subdivided meshes) made each increment wait on the one before (the dragon's
// sort: 0.111 -> 0.091 s on one thread).
inline void count_sort_digits(const std::uint64_t* in, std::size_t first, std::size_t last, int shift,
                              std::uint32_t* four, std::size_t* hist)
{
  constexpr std::size_t buckets = sort_buckets;
  constexpr std::uint64_t mask = buckets - 1;
  CGAL_precondition(last - first <= std::size_t(std::numeric_limits<std::uint32_t>::max()));   // 32-bit counters
  std::fill(four, four + 4 * buckets, std::uint32_t(0));
  std::size_t i = first;
  for(; i + 4 <= last; i += 4)
  {
    ++four[(in[i] >> shift) & mask];
    ++four[buckets + ((in[i + 1] >> shift) & mask)];
    ++four[2 * buckets + ((in[i + 2] >> shift) & mask)];
    ++four[3 * buckets + ((in[i + 3] >> shift) & mask)];
  }
  for(; i < last; ++i)
    ++four[(in[i] >> shift) & mask];
  for(std::size_t v = 0; v < buckets; ++v)
    hist[v] = std::size_t(four[v]) + four[buckets + v] + four[2 * buckets + v] + four[3 * buckets + v];
}

// Sorts c[0..n) stably by the field of `bits` bits that starts at bit `shift` of each key
// (the bits above it must be zero, or the field must reach bit 63): a least-significant-digit
// radix sort, passes of 10 bits, a pass skipped when all keys share its digit. Each pass is a
// stable counting sort split into fixed blocks of keys: a block counts its digits, then
// writes its keys after those of the smaller digits and of the same digit in the blocks
// before it. A stable sort has one result, whatever the blocks and threads: the same order
// for every number of threads. In parallel (parallel_for_blocks()) with or without TBB's
// sorts. Why by hand: neither the standard library nor Boost has a parallel stable sort of
// integer keys on a bit field; a comparison sort of the decomposition's candidates was 16 % of
// the dragon's decomposition, and TBB's parallel_sort of the spatial order's keys a third more
// than these passes (design notes).
inline void radix_sort_bits(std::uint64_t* c, std::size_t n, int shift, int bits)
{
  constexpr int digit_bits = sort_digit_bits;
  constexpr std::size_t buckets = sort_buckets;
  constexpr std::uint64_t mask = buckets - 1;
  const int digits = (bits + digit_bits - 1) / digit_bits;
  constexpr std::size_t block = std::size_t(1) << 16;
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<std::size_t> count(blocks * buckets);
  Uninitialized_vector<std::uint64_t> scratch(n);
  std::uint64_t* from = c;
  std::uint64_t* to = scratch.data();
  for(int d = 0; d < digits; ++d)
  {
    const int s = shift + d * digit_bits;
    if(s >= 64)
      break;                                              // no bits left: every digit is 0
    parallel_for_blocks(blocks, [&](std::size_t first, std::size_t last) {
      std::vector<std::uint32_t> four(4 * sort_buckets);
      for(std::size_t b = first; b < last; ++b)
        count_sort_digits(from, b * block, (std::min)(n, (b + 1) * block), s, four.data(),
                          count.data() + b * sort_buckets);
    }, 1);
    std::size_t sum = 0;
    bool one_digit = false;
    for(std::size_t v = 0; v < buckets && !one_digit; ++v)
    {
      std::size_t total = 0;
      for(std::size_t b = 0; b < blocks; ++b)
        total += count[b * buckets + v];
      one_digit = (total == n);
      for(std::size_t b = 0; b < blocks; ++b)
      {
        const std::size_t t = count[b * buckets + v];
        count[b * buckets + v] = sum;
        sum += t;
      }
    }
    if(one_digit)
      continue;                                           // one digit for all: nothing to do
    // (the lambda copies what it reads into locals: through its captured references, every
    // store made the compiler load the loop bound and the arrays' addresses again)
    parallel_for_blocks(blocks, [&](std::size_t first, std::size_t last) {
      const std::uint64_t* in = from;
      std::uint64_t* out = to;
      const int sh = s;
      for(std::size_t b = first; b < last; ++b)
      {
        std::size_t* pos = count.data() + b * buckets;
        for(std::size_t i = b * block, e = (std::min)(n, (b + 1) * block); i < e; ++i)
          out[pos[(in[i] >> sh) & mask]++] = in[i];
      }
    }, 1);
    std::swap(from, to);
  }
  if(from != c)
    std::copy(from, from + n, c);
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_RADIX_SORT_H
