// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors

#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CONFIG_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CONFIG_H

#include <CGAL/config.h>
#include <CGAL/version.h>

#if CGAL_VERSION_NR < CGAL_VERSION_NUMBER(5,5,0)
#error "Surface_mesh_multiresolution requires CGAL 5.5 or later"
#endif

#include <CGAL/Surface_mesh_multiresolution/internal/Block_pool.h>

#include <boost/core/noinit_adaptor.hpp>
#include <boost/optional.hpp>
#include <cstdint>
#include <memory>
#include <vector>
#if defined(_MSC_VER) && (defined(_M_X64) || defined(_M_IX86))
#include <xmmintrin.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

#define CGAL_SMR_VERSION_MAJOR 0
#define CGAL_SMR_VERSION_MINOR 2
#define CGAL_SMR_VERSION_PATCH 0

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The optional type of the SMS policy signatures: boost::optional up to CGAL 5.x,
// std::optional in later CGAL sources.
template <typename T>
using Optional = boost::optional<T>;

// Row/column indices of the index-based data (CSR weights, triangles). 32 bits halve
// the memory traffic of the hot loops; meshes are limited to 2^32-1 vertices.
typedef std::uint32_t Index;

// Arrays whose elements are all written before they are read: resize() leaves the new
// elements uninitialised (Boost's noinit_adaptor) where a std::vector value-initialises them,
// a sequential memset of the whole array on the calling thread before the parallel loops that
// write it (5 % of a decomposition's samples). assign() and resize(n, value) still fill.
template <typename T>
using Uninitialized_vector = std::vector<T, boost::noinit_adaptor<Pooled_allocator<T> > >;
typedef Uninitialized_vector<Index> Index_array;

// Gives the pages of an array's unused capacity (past its size) back to the system, keeping
// the capacity: the arrays a decomposition reduces in place level by level (positions and
// other channels, the face array, the input numbers of the rows) otherwise keep the pages
// their first level touched (the 3.1M-vertex horse: 27 MB at the peak of its second level;
// design notes). Whole pages inside the unused capacity only, so no allocator's bookkeeping
// is touched; a page given back reads as zeros if written again. Linux (madvise with
// MADV_DONTNEED); elsewhere nothing. Why by hand: std::vector::shrink_to_fit() copies the
// array into a new block, which would raise the peak it is meant to lower.
template <typename Vector>
void release_unused_capacity(Vector& v)
{
#if defined(__linux__) && defined(MADV_DONTNEED)
  typedef typename Vector::value_type T;
  const long page_size = ::sysconf(_SC_PAGESIZE);
  if(page_size <= 0 || v.capacity() == v.size())
    return;
  const std::uintptr_t page = static_cast<std::uintptr_t>(page_size);
  const std::uintptr_t used_end = reinterpret_cast<std::uintptr_t>(v.data() + v.size());
  const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(v.data()) + v.capacity() * sizeof(T);
  const std::uintptr_t first = (used_end + page - 1) / page * page, last = end / page * page;
  if(last > first)
    ::madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);   // (a refusal changes nothing)
#else
  (void)v;
#endif
}

// A hint that the cache line holding `p` will be read soon. Loops that visit halfedges in
// cost order (random places of arrays larger than the cache) issue it a few iterations ahead,
// so that the misses overlap instead of stalling one after the other. No effect on results.
inline void prefetch(const void* p)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#elif defined(_MSC_VER) && (defined(_M_X64) || defined(_M_IX86))
  _mm_prefetch(static_cast<const char*>(p), _MM_HINT_T0);
#else
  (void)p;
#endif
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CONFIG_H
