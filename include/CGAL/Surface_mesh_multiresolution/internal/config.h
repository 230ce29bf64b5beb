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
