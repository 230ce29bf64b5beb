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
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/radix_sort.h>

#include <CGAL/assertions.h>

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

// The spatial order of a mesh of n vertices and nf faces, read through coordinate(v, c) (the
// coordinate c of vertex v, a finite double), face_size(f) and corner(f, j) (the j-th vertex
// of face f, j < face_size(f)): face_order[p] is the input position of the p-th face,
// vertex_order[i] the input number of the i-th vertex (those of no face last, in input order).
// Faces are sorted by the Morton code of their centroid on a grid of 2^21 cells per axis over
// the bounding cube, ties in input order; the keys are distinct (code, position) pairs, so the
// order is the same for every number of threads. Empty orders where the coordinates' extent is
// not a finite positive number. Polygons of any size (the command-line tool orders a soup with
// it before triangulating, so that its outputs and a decomposition share this order).
template <typename Coordinate, typename FaceSize, typename Corner>
void spatial_order(std::size_t n, std::size_t nf, const Coordinate& coordinate, const FaceSize& face_size,
                   const Corner& corner, std::vector<Index>& vertex_order, std::vector<Index>& face_order)
{
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
      lo[c] = (std::min)(lo[c], double(coordinate(v, c)));
      hi[c] = (std::max)(hi[c], double(coordinate(v, c)));
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
      const std::size_t size = face_size(f);
      const double d = double(size);
      std::uint64_t code = 0;
      for(int c = 0; c < 3; ++c)
      {
        // the centroid's offset from the low corner, each term divided first (no overflow)
        double s = 0.;
        for(std::size_t j = 0; j < size; ++j)
          s += (double(coordinate(std::size_t(corner(f, j)), c)) - lo[c]) / d;
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
  {
    const std::size_t f = face_order[p];
    for(std::size_t j = 0, size = face_size(f); j < size; ++j)
    {
      const std::size_t v = std::size_t(corner(f, j));
      if(number[v] == invalid_index)
      {
        number[v] = static_cast<Index>(vertex_order.size());
        vertex_order.push_back(static_cast<Index>(v));
      }
    }
  }
  for(std::size_t v = 0; v < n; ++v)
    if(number[v] == invalid_index)
      vertex_order.push_back(static_cast<Index>(v));
}

// the spatial order of a triangle mesh (xyz: 3 finite doubles per vertex, tri: 3 vertex
// numbers per face)
inline void spatial_order(const std::vector<double>& xyz, const std::vector<Index>& tri, std::vector<Index>& vertex_order,
                          std::vector<Index>& face_order)
{
  const double* const p = xyz.data();
  const Index* const t = tri.data();
  spatial_order(
      xyz.size() / 3, tri.size() / 3, [p](std::size_t v, int c) { return p[3 * v + std::size_t(c)]; },
      [](std::size_t) { return std::size_t(3); }, [t](std::size_t f, std::size_t j) { return t[3 * f + j]; }, vertex_order,
      face_order);
}

// Both permutations gather in parallel into a scratch array of the package's pool (Block_pool:
// the blocks the ordering's sort freed), then copy it back into the array they permute, which
// keeps its memory. Why: gathered into a fresh array of the input's size and swapped in, the
// ordered 3.1M-vertex horse peaked higher (1652 MB against 1601 MB copied back, the pages of
// the levels' reduced arrays given back in both): glibc served the new array from fresh pages
// while the old one's stayed with the process, in its heap. Permuted in place, cycle by cycle, it peaked
// no lower and took 1.2 s more (a cache miss per element, sequential; design notes).
template <typename T>
void copy_back(const Uninitialized_vector<T>& from, std::vector<T>& to)
{
  CGAL_precondition(from.size() == to.size());
  parallel_for_blocks(from.size(), [&](std::size_t first, std::size_t last) {
    std::copy(from.begin() + std::ptrdiff_t(first), from.begin() + std::ptrdiff_t(last), to.begin() + std::ptrdiff_t(first));
  });
}

// values (dim per vertex, input numbers) in the vertex order (vertex_order[i]: the input number
// of the i-th)
inline void permute_values(const std::vector<Index>& vertex_order, std::size_t dim, std::vector<double>& values)
{
  Uninitialized_vector<double> out(values.size());   // every value written below
  parallel_for_blocks(vertex_order.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
      for(std::size_t c = 0; c < dim; ++c)
        out[i * dim + c] = values[std::size_t(vertex_order[i]) * dim + c];
  });
  copy_back(out, values);
}

// the face array in the face order, its vertices renamed to their places in the vertex order
inline void permute_faces(const std::vector<Index>& vertex_order, const std::vector<Index>& face_order, std::vector<Index>& tri)
{
  Index_array place(vertex_order.size());            // every place written below
  parallel_for_blocks(vertex_order.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
      place[vertex_order[i]] = static_cast<Index>(i);
  });
  Index_array out(tri.size());                       // every corner written below
  parallel_for_blocks(face_order.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t p = first; p < last; ++p)
      for(int c = 0; c < 3; ++c)
        out[3 * p + c] = place[tri[3 * std::size_t(face_order[p]) + c]];
  });
  Index_array().swap(place);
  copy_back(out, tri);
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SPATIAL_ORDER_H
