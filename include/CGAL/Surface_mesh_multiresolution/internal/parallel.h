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

#include <atomic>
#include <cstddef>

#include <algorithm>
#include <vector>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>
#endif

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// Runs here() in the calling thread and beside() at the same time in a TBB task when TBB is
// linked, else one after the other; they must be independent (no data written by one is read
// by the other). beside() should not allocate large buffers: on another thread, glibc's malloc
// serves them from that thread's arena, whose freed pages go back to the system, so every call
// pays their page faults again (reserve them in the calling thread first).
template <typename Here, typename Beside>
void run_beside(const Here& here, const Beside& beside)
{
#ifdef CGAL_LINKED_WITH_TBB
  tbb::task_group group;
  group.run([&] { beside(); });
  try { here(); }
  catch(...) { group.wait(); throw; }
  group.wait();
#else
  here();
  beside();
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

// Calls f(b, first, last) for every fixed block b of `block` positions of [0, n) ([first,
// last) its positions), blocks in parallel: unlike parallel_for_blocks()' ranges, the blocks do
// not depend on the number of threads, so per-block results joined in block order do not either.
template <typename F>
void for_fixed_blocks(std::size_t n, std::size_t block, const F& f)
{
  parallel_for_blocks((n + block - 1) / block, [&](std::size_t first, std::size_t last) {
    for(std::size_t b = first; b < last; ++b)
      f(b, b * block, (std::min)(n, (b + 1) * block));
  }, 1);
}

// The first position p < n where fails(p) holds, or n: blocks in parallel, each stopping at
// its first failure or where an earlier one was already found (a shared atomic minimum), so
// the answer is the sequential scan's for any number of threads.
template <typename Fails>
std::size_t first_position_where(std::size_t n, const Fails& fails, std::size_t grain = 8192)
{
  std::atomic<std::size_t> first(n);
  parallel_for_blocks(n, [&](std::size_t b, std::size_t e) {
    for(std::size_t p = b; p < e && p < first.load(std::memory_order_relaxed); ++p)
      if(fails(p))
      {
        std::size_t seen = first.load();
        while(p < seen && !first.compare_exchange_weak(seen, p)) {}
        return;
      }
  }, grain);
  return first.load();
}

// An ordered compaction in parallel: keep(p) is evaluated per position p < n in fixed blocks,
// the kept positions counted per block and numbered by a prefix sum over the blocks; visit()
// then calls f(p, rank, kept) for every position, rank being the number of kept positions
// before p, as a sequential scan would give it, for any number of threads. keep must give the
// same answer both times (it is not stored: a flag per position would cost memory).
template <typename Keep>
class Ordered_compaction
{
public:
  Ordered_compaction(std::size_t n, const Keep& keep) : m_n(n), m_keep(keep), m_first((n + block - 1) / block + 1, 0)
  {
    parallel_for_blocks(m_first.size() - 1, [&](std::size_t b0, std::size_t b1) {
      for(std::size_t b = b0; b < b1; ++b)
      {
        std::size_t count = 0;
        for(std::size_t p = b * block, e = (std::min)(m_n, (b + 1) * block); p < e; ++p)
          count += m_keep(p) ? 1 : 0;
        m_first[b + 1] = count;
      }
    }, 1);
    for(std::size_t b = 1; b < m_first.size(); ++b)
      m_first[b] += m_first[b - 1];
  }

  // the number of kept positions
  std::size_t size() const { return m_first.back(); }

  template <typename Visit>
  void visit(const Visit& f) const
  {
    parallel_for_blocks(m_first.size() - 1, [&](std::size_t b0, std::size_t b1) {
      for(std::size_t b = b0; b < b1; ++b)
      {
        std::size_t rank = m_first[b];
        for(std::size_t p = b * block, e = (std::min)(m_n, (b + 1) * block); p < e; ++p)
        {
          const bool kept = m_keep(p);
          f(p, rank, kept);
          rank += kept ? 1 : 0;
        }
      }
    }, 1);
  }

private:
  static constexpr std::size_t block = std::size_t(1) << 14;
  std::size_t m_n;
  const Keep& m_keep;
  std::vector<std::size_t> m_first;
};

// A stable move of items towards the start of their own array (each item to a position at or
// before its own, in order: an ordered compaction in place), by blocks of items, in parallel
// where that is safe. move_block(b) moves block b's items in order; read_begin(b) is the
// lowest position block b reads, write_end(b) one past the highest it writes (both increasing
// in b). Blocks run in waves [a, c): a wave holds every block whose writes all lie below the
// lowest read of its first block, so no block overwrites an item that one of the same wave
// has not read yet; the blocks before a wave are done, and an item's new position lies before
// every later block's reads. The result is the sequential loop's for any number of threads.
// Why: the in-place moves that shrink a level's arrays were sequential; on two threads they
// took longer than on one (the items last written by the other core). A compaction that
// removes a fraction r of the items gives waves growing as r times their start, so on a
// large array only its first few blocks move one at a time.
template <typename ReadBegin, typename WriteEnd, typename MoveBlock>
void move_down_in_waves(std::size_t number_of_blocks, const ReadBegin& read_begin, const WriteEnd& write_end,
                        const MoveBlock& move_block)
{
  std::size_t a = 0;
  while(a < number_of_blocks)
  {
    const std::size_t lowest_read = read_begin(a);
    std::size_t c = a + 1;
    while(c < number_of_blocks && write_end(c) <= lowest_read)
      ++c;
    if(c == a + 1)
      move_block(a);
    else
      parallel_for_blocks(c - a, [&](std::size_t first, std::size_t last) {
        for(std::size_t b = first; b < last; ++b)
          move_block(a + b);
      }, 1);
    a = c;
  }
}

// The number of threads the parallel loops may use here (1 without TBB): the arena's, or the
// process-wide limit of a tbb::global_control set below the machine's default, which the arena
// does not report (under a limit of one thread the corner listing read the faces once per
// range of sources, all on one thread). An arena larger than the machine (a test's four
// threads on two cores) keeps its own number.
inline int available_threads()
{
#ifdef CGAL_LINKED_WITH_TBB
  const std::size_t limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  const int arena = tbb::this_task_arena::max_concurrency();
  const bool limited = limit > 0 && limit < std::size_t(tbb::info::default_concurrency());
  return limited && limit < std::size_t(arena) ? static_cast<int>(limit) : arena;
#else
  return 1;
#endif
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PARALLEL_H
