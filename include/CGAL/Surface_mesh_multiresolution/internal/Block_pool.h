// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors

#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_BLOCK_POOL_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_BLOCK_POOL_H

#include <cstddef>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <map>
#include <mutex>
#include <new>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// Large blocks of memory kept for reuse while a pyramid is built.
// A decomposition builds the same arrays at every level (halfedges, candidate keys, weights,
// cotangents, quadrics), each about 0.84 times the size it had on the level before, and frees
// them before the next level. glibc's malloc maps every block of 32 MiB or more anew and unmaps
// it when freed (smaller blocks it reuses in its heap), so on a large mesh every level touched
// fresh pages again: the 3.1M-vertex subdivided horse took 2.0M page faults to decompose, 8 GB
// of first touches for a peak of 0.9 GB, and 12.8 s of system time on two threads (6 µs per
// fault on the reference machine). While at least one Block_pool_scope exists, such blocks
// (at least `default_kept_bytes`), freed through Pooled_allocator, are kept here. A request of
// 32 MiB or more takes the smallest kept block that holds it, its tail given back (realloc)
// when it is more than a quarter too large; where none holds it, the largest kept block grows
// to it (realloc, which glibc does with mremap: only the added pages are touched fresh) and
// kept blocks of as many bytes as it grew go back (the largest first), so that the memory held
// stays about that of the system allocator alone. A request from `default_reused_bytes` to
// 32 MiB takes the smallest kept block that holds it too, but one of 64 MiB or more only if it
// fills three quarters of it: cut down, such a block would be lost to the next level's large
// arrays, which then touch fresh pages (kept blocks under 64 MiB are cut down: kept whole
// until the end, the dragon's 35 MiB of level-0 quadrics raised its peak by as much).
// Everything kept is given back when the last scope ends. Measured and the variants tried:
// design notes, "Large blocks kept from level to level" (3.1M vertices 24.2-25.1 -> 21.7-22.5
// s, peak +0.9 %; the dragon unchanged, its arrays being smaller) and "Kept blocks grown, and
// not cut down by small arrays" (3.1M vertices: decomposition faults -29 %, 25.7-30.8 ->
// 21.1-23.2 s, peak +1.7 %).
// Why by hand: std::pmr's pools keep every block of every size class until released, and a
// process-wide setting of the allocator (mallopt, GLIBC_TUNABLES) is the user's to choose, not a
// library's. Every block comes from std::malloc with its size in a header, so that any block can
// serve any request that fits and be freed by std::free, whatever the scope at that time.
class Block_pool
{
public:
  // blocks kept when freed: those that glibc's malloc maps and unmaps on its own (from 32 MiB,
  // its largest threshold on 64-bit systems; smaller ones it reuses in its heap)
  static constexpr std::size_t default_kept_bytes = std::size_t(32) << 20;
  // requests that may take a kept block
  static constexpr std::size_t default_reused_bytes = std::size_t(1) << 20;
  static constexpr std::size_t header = 16;        // keeps malloc's 16-byte alignment

  static Block_pool& instance()
  {
    static Block_pool* pool = new Block_pool();     // never destroyed: arrays of static objects may be freed after it
    return *pool;
  }

  void* allocate(std::size_t bytes)
  {
    if(bytes > (std::numeric_limits<std::size_t>::max)() - header)
      throw std::bad_alloc();
    if(bytes >= m_reuse_from)
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      if(m_scopes > 0 && !m_kept.empty())
      {
        const auto it = m_kept.lower_bound(bytes);
        const bool large = bytes >= m_keep_from;
        if(it != m_kept.end() && (large || it->first < 2 * m_keep_from || it->first - bytes <= it->first / 4))
        {
          // the smallest kept block that holds it, the tail given back when it is more than a
          // quarter too large; for a request under m_keep_from (an array the system allocator
          // would serve from its heap), not a block of twice m_keep_from or more that it would
          // cut down (see above)
          void* block = it->second;
          const std::size_t kept = it->first;
          m_kept.erase(it);
          ++m_reuses;
          return kept - bytes > kept / 4 ? shrink(block, bytes) : block;
        }
        if(large && it == m_kept.end())
        {
          // none holds it: the largest kept block grows to it (realloc: mremap, its pages
          // kept; the new ones only are touched fresh), and kept blocks of as many bytes as
          // it grew go back (the largest first), so that what the process holds does not grow
          const auto last = std::prev(m_kept.end());
          void* block = last->second;
          const std::size_t kept = last->first;
          m_kept.erase(last);
          char* raw = static_cast<char*>(std::realloc(start(block), bytes + header));
          if(raw == nullptr)
          {
            std::free(start(block));                // could not grow: a fresh block below
            release(bytes);
          }
          else
          {
            *reinterpret_cast<std::size_t*>(raw) = bytes;
            ++m_reuses;
            release(bytes - kept);
            return raw + header;
          }
        }
      }
    }
    char* raw = static_cast<char*>(std::malloc(bytes + header));
    if(raw == nullptr)
      throw std::bad_alloc();
    *reinterpret_cast<std::size_t*>(raw) = bytes;
    return raw + header;
  }

  void deallocate(void* block) noexcept
  {
    if(block == nullptr)
      return;
    const std::size_t bytes = size(block);
    if(bytes >= m_keep_from)
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      if(m_scopes > 0)
      {
        try
        {
          m_kept.emplace(bytes, block);
          return;
        }
        catch(const std::bad_alloc&)
        {
        }                                           // no room for the entry: the block goes back
      }
    }
    std::free(start(block));
  }

  void enter()
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    ++m_scopes;
  }

  void leave()
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    if(--m_scopes > 0)
      return;
    for(const auto& kept : m_kept)
      std::free(start(kept.second));
    m_kept.clear();
  }

  // other sizes than the defaults (tests: the reuse of blocks by small meshes); no scope may exist
  void set_sizes(std::size_t keep_from, std::size_t reuse_from)
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_keep_from = keep_from;
    m_reuse_from = reuse_from;
  }

  // the number of bytes kept for reuse (tests)
  std::size_t kept_bytes()
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    std::size_t total = 0;
    for(const auto& kept : m_kept)
      total += kept.first;
    return total;
  }

  // how many requests took a kept block so far (tests)
  std::size_t reuses()
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_reuses;
  }

  // the usable size of a block of allocate()
  static std::size_t size(const void* block) { return *reinterpret_cast<const std::size_t*>(static_cast<const char*>(block) - header); }

private:
  Block_pool() = default;
  // the first `bytes` of a block, the rest given back (realloc shrinks in place: the pages
  // kept are those already touched); the block as it was if realloc fails
  static void* shrink(void* block, std::size_t bytes)
  {
    char* raw = static_cast<char*>(std::realloc(start(block), bytes + header));
    if(raw == nullptr)
      return block;                                 // the block as it was
    *reinterpret_cast<std::size_t*>(raw) = bytes;
    return raw + header;
  }
  static void* start(void* block) { return static_cast<char*>(block) - header; }

  // gives back kept blocks of at least `bytes` bytes in all, the largest first (m_mutex held)
  void release(std::size_t bytes)
  {
    for(std::size_t released = 0; released < bytes && !m_kept.empty();)
    {
      const auto last = std::prev(m_kept.end());
      released += last->first;
      std::free(start(last->second));
      m_kept.erase(last);
    }
  }

  std::mutex m_mutex;
  std::size_t m_scopes = 0, m_reuses = 0;
  std::size_t m_keep_from = default_kept_bytes;      // blocks kept when freed: from this size on
  std::size_t m_reuse_from = default_reused_bytes;   // requests that look for a kept block: from this size on
  std::multimap<std::size_t, void*> m_kept;        // size -> block
};

// Keeps freed large blocks for reuse while it exists (Block_pool); scopes may nest and
// overlap across threads.
class Block_pool_scope
{
public:
  Block_pool_scope() { Block_pool::instance().enter(); }
  ~Block_pool_scope() { Block_pool::instance().leave(); }
  Block_pool_scope(const Block_pool_scope&) = delete;
  Block_pool_scope& operator=(const Block_pool_scope&) = delete;
};

// The allocator of the package's large arrays (Uninitialized_vector): the blocks of Block_pool.
template <typename T>
struct Pooled_allocator
{
  typedef T value_type;
  static_assert(alignof(T) <= Block_pool::header, "Pooled_allocator aligns to 16 bytes");

  Pooled_allocator() noexcept = default;
  template <typename U>
  Pooled_allocator(const Pooled_allocator<U>&) noexcept {}

  T* allocate(std::size_t n)
  {
    if(n > (std::numeric_limits<std::size_t>::max)() / sizeof(T))
      throw std::bad_array_new_length();
    return static_cast<T*>(Block_pool::instance().allocate(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t) noexcept { Block_pool::instance().deallocate(p); }

  template <typename U>
  bool operator==(const Pooled_allocator<U>&) const noexcept { return true; }
  template <typename U>
  bool operator!=(const Pooled_allocator<U>&) const noexcept { return false; }
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_BLOCK_POOL_H
