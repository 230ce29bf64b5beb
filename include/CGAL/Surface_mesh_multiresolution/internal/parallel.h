// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PARALLEL_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PARALLEL_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

#include <cstddef>

#include <algorithm>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#endif

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// Runs f() and g() (independent: no data written by one is read by the other), at the same
// time with TBB when it is linked, else one after the other.
template <typename F, typename G>
void parallel_invoke(const F& f, const G& g)
{
#ifdef CGAL_LINKED_WITH_TBB
  tbb::parallel_invoke(f, g);
#else
  f();
  g();
#endif
}

// Calls f(first, last) on consecutive blocks of [0, n), in parallel with TBB when it is
// linked and n is large enough to pay for it. Callers only use it for loops whose
// iterations write disjoint data, so results do not depend on the number of threads.
template <typename F>
void parallel_for_blocks(std::size_t n, const F& f, std::size_t grain = 8192)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(n >= 2 * grain)
  {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); });
    return;
  }
#endif
  if(n > 0)
    f(std::size_t(0), n);
}

// Sorts [first, last) by `compare`, in parallel with TBB when it is linked. Callers sort by
// a total order (keys all different), so the result does not depend on the threads.
template <typename RandomIt, typename Compare>
void parallel_sort(RandomIt first, RandomIt last, const Compare& compare)
{
#ifdef CGAL_LINKED_WITH_TBB
  tbb::parallel_sort(first, last, compare);
#else
  std::sort(first, last, compare);
#endif
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PARALLEL_H
