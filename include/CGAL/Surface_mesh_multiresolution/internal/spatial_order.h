// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SPATIAL_ORDER_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SPATIAL_ORDER_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/radix_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>


namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The order a pyramid keeps of its own (decompose(), Memory_order): faces in the Morton order of
// their centroids, vertices numbered in the order those faces first name them. A level's arrays
// are indexed by vertex and read ring by ring, so an input whose numbering is scattered (Loop
// subdivision appends every step's new vertices after the old ones) makes every ring a set of
// cache misses: the subdivided 3.1M-vertex horse decomposes in 10.0-10.5 s ordered against
// 13.6-13.9 s as numbered (design notes, "The input's numbering and locality").

// Memory_order::AUTOMATIC orders meshes from this many vertices on (smaller ones fit the
// caches better, and ordering costs 1-3 % on meshes already in order)
constexpr std::size_t automatic_spatial_order_size = std::size_t(1) << 18;

// Whether the numbering of a mesh of n vertices with faces `tri` is scattered: the median,
// over up to 4,096 faces taken evenly, of the span of a face's vertex numbers (largest minus
// smallest) is above 32 sqrt(n). Scans and meshes written in spatial order have medians of
// 0.1-4 sqrt(n); the subdivided horse has 960 sqrt(n).
inline bool numbering_is_scattered(std::size_t n, const std::vector<Index>& tri)
{
  const std::size_t nf = tri.size() / 3;
  if(nf == 0)
    return false;
  const std::size_t samples = (std::min)(nf, std::size_t(4096));
  std::vector<Index> span(samples);
  for(std::size_t i = 0; i < samples; ++i)
  {
    const Index* t = tri.data() + 3 * (i * nf / samples);
    span[i] = (std::max)({t[0], t[1], t[2]}) - (std::min)({t[0], t[1], t[2]});
  }
  std::nth_element(span.begin(), span.begin() + samples / 2, span.end());
  return double(span[samples / 2]) > 32. * std::sqrt(double(n));
}

// 21 bits of x spread to every third bit (a Morton code's part of one axis)
inline std::uint64_t spread_to_every_third_bit(std::uint64_t x)
{
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

// The spatial order of a mesh (xyz: 3 finite doubles per vertex, tri: 3 vertex numbers per
// face): face_order[p] is the input position of the p-th face, vertex_order[i] the input number
// of the i-th vertex (those of no face last, in input order). Faces are sorted by the Morton
// code of their centroid on a grid of 2^21 cells per axis over the bounding cube, ties in input
// order; the keys are distinct (code, position) pairs, so the order is the same for every
// number of threads. Empty orders where the coordinates' extent is not a finite positive number.
inline void spatial_order(const std::vector<double>& xyz, const std::vector<Index>& tri, std::vector<Index>& vertex_order,
                          std::vector<Index>& face_order)
{
  const std::size_t n = xyz.size() / 3, nf = tri.size() / 3;
  vertex_order.clear();
  face_order.clear();
  double lo[3], hi[3];
  for(int c = 0; c < 3; ++c)
  {
    lo[c] = std::numeric_limits<double>::infinity();
    hi[c] = -lo[c];
  }
  for(std::size_t v = 0; v < n; ++v)
    for(int c = 0; c < 3; ++c)
    {
      lo[c] = (std::min)(lo[c], xyz[3 * v + c]);
      hi[c] = (std::max)(hi[c], xyz[3 * v + c]);
    }
  double extent = 0.;
  for(int c = 0; c < 3; ++c)
    extent = (std::max)(extent, hi[c] - lo[c]);
  if(n == 0 || !(extent > 0.) || !std::isfinite(extent))
    return;
  int position_bits = 1;
  while(position_bits < 40 && (std::uint64_t(1) << position_bits) < nf)
    ++position_bits;
  const double cells = 2097151.;                           // 2^21 - 1
  const double scale = cells / extent;
  Uninitialized_vector<std::uint64_t> keys(nf);   // every key written below
  parallel_for_blocks(nf, [&](std::size_t first, std::size_t last) {
    for(std::size_t f = first; f < last; ++f)
    {
      std::uint64_t code = 0;
      for(int c = 0; c < 3; ++c)
      {
        // the centroid's offset from the low corner, each term divided first (no overflow)
        const double s = (xyz[3 * std::size_t(tri[3 * f]) + c] - lo[c]) / 3. + (xyz[3 * std::size_t(tri[3 * f + 1]) + c] - lo[c]) / 3.
                       + (xyz[3 * std::size_t(tri[3 * f + 2]) + c] - lo[c]) / 3.;
        double cell = s * scale;
        cell = cell >= 0. ? (std::min)(cell, cells) : 0.;
        code |= spread_to_every_third_bit(static_cast<std::uint64_t>(cell)) << c;
      }
      keys[f] = (code >> position_bits << position_bits) | f;   // the code's 64 - position_bits leading bits
    }
  });
  // keys in input order, sorted stably by their code bits: by (code, position)
  radix_sort_bits(keys.data(), nf, position_bits, 64 - position_bits);
  const std::uint64_t position_mask = (std::uint64_t(1) << position_bits) - 1;
  face_order.resize(nf);
  parallel_for_blocks(nf, [&](std::size_t first, std::size_t last) {
    for(std::size_t p = first; p < last; ++p)
      face_order[p] = static_cast<Index>(keys[p] & position_mask);
  });
  Uninitialized_vector<std::uint64_t>().swap(keys);
  // first use (sequential: the numbers follow the order of the faces)
  std::vector<Index> number(n, invalid_index);
  vertex_order.reserve(n);
  for(std::size_t p = 0; p < nf; ++p)
    for(int c = 0; c < 3; ++c)
    {
      const Index v = tri[3 * std::size_t(face_order[p]) + c];
      if(number[v] == invalid_index)
      {
        number[v] = static_cast<Index>(vertex_order.size());
        vertex_order.push_back(v);
      }
    }
  for(std::size_t v = 0; v < n; ++v)
    if(number[v] == invalid_index)
      vertex_order.push_back(static_cast<Index>(v));
}

// Both permutations are made in place, cycle by cycle: the input's arrays keep their memory.
// Why: gathered into a fresh array of the input's size and swapped in, the ordered 3.1M-vertex
// horse peaked higher (1616 -> 1600 MB with the in-place moves of the levels' arrays as well):
// glibc served the new array from fresh pages while the old one's stayed with the process, in
// its heap (design notes). Sequential, random reads: 0.09 s at 3.1M vertices.

// a[i] = a before at from[i] for every i < from.size(), in blocks of `dim` values (from: a
// permutation)
template <typename T>
void permute_in_place(const std::vector<Index>& from, std::size_t dim, std::vector<T>& a)
{
  const std::size_t n = from.size();
  std::vector<bool> done(n, false);
  std::vector<T> held(dim);
  for(std::size_t start = 0; start < n; ++start)
  {
    if(done[start])
      continue;
    std::copy(a.begin() + std::ptrdiff_t(start * dim), a.begin() + std::ptrdiff_t((start + 1) * dim), held.begin());
    std::size_t i = start;
    for(;;)
    {
      done[i] = true;
      const std::size_t j = from[i];
      if(j == start)
      {
        std::copy(held.begin(), held.end(), a.begin() + std::ptrdiff_t(i * dim));
        break;
      }
      std::copy(a.begin() + std::ptrdiff_t(j * dim), a.begin() + std::ptrdiff_t((j + 1) * dim), a.begin() + std::ptrdiff_t(i * dim));
      i = j;
    }
  }
}
// values (dim per vertex, input numbers) in the vertex order (vertex_order[i]: the input number
// of the i-th)
inline void permute_values(const std::vector<Index>& vertex_order, std::size_t dim, std::vector<double>& values)
{
  permute_in_place(vertex_order, dim, values);
}
// the face array in the face order, its vertices renamed to their places in the vertex order
inline void permute_faces(const std::vector<Index>& vertex_order, const std::vector<Index>& face_order, std::vector<Index>& tri)
{
  permute_in_place(face_order, 3, tri);
  Index_array place(vertex_order.size());            // every place written below
  parallel_for_blocks(vertex_order.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
      place[vertex_order[i]] = static_cast<Index>(i);
  });
  parallel_for_blocks(tri.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t k = first; k < last; ++k)
      tri[k] = place[tri[k]];
  });
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SPATIAL_ORDER_H
