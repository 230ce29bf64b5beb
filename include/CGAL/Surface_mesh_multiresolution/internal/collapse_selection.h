// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_COLLAPSE_SELECTION_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_COLLAPSE_SELECTION_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/radix_sort.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Triangle_halfedges.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The selection of one level's half-edge collapses on index arrays (Section 3.1): the
// candidates in cost order, the link condition, the flip test and the greedy independent set.

// The link condition of CGAL::Euler::does_satisfy_link_condition() (CGAL 5.5) for the
// collapse of the edge of halfedge h = o -> e, on index arrays: every common neighbour of its
// ends is the apex of a face on the edge; no face on the edge has its two other edges on the
// border (isolated triangle); an interior edge joins no two border vertices, is not an edge of
// a tetrahedron and does not close a two-face pillow. Reads the 1-rings of o and e (contiguous)
// and twin(h); other twins only for edges between border vertices.
inline bool satisfies_link_condition(const Triangle_halfedges& th, Index h, Index o, Index e,
                                     const std::vector<unsigned char>& on_border)
{
  typedef Triangle_halfedges T;
  const Index t = th.twin[h];
  const Index o_begin = th.out_offsets[o], o_end = th.out_offsets[o + 1];
  const Index e_begin = th.out_offsets[e], e_end = th.out_offsets[e + 1];
  Index apex_top = invalid_index, apex_bottom = invalid_index;     // invalid: no face on that side
  for(Index k = o_begin; k != o_end; ++k)
    if(th.out[k] == h) { apex_top = th.out_apex[k]; break; }
  for(Index k = e_begin; k != e_end; ++k)
    if(th.out[k] == t) { apex_bottom = th.out_apex[k]; break; }
  const bool top = apex_top != invalid_index, bottom = apex_bottom != invalid_index;
  const Index* const e_first = th.out_target.data() + e_begin;
  const Index* const e_last = th.out_target.data() + e_end;
  for(Index k = o_begin; k != o_end; ++k)                // the 1-rings are short: a double loop beats any set
  {
    const Index c = th.out_target[k];
    if(c != e && c != apex_top && c != apex_bottom && std::find(e_first, e_last, c) != e_last)
      return false;
  }
  // a border edge joins two border vertices: the flags spare most twin lookups
  auto border_edge = [&](Index g, Index from, Index to) { return on_border[from] && on_border[to] && th.is_border_edge(g); };
  if(top && border_edge(T::next_in_face(h), e, apex_top) && border_edge(T::next_in_face(T::next_in_face(h)), apex_top, o))
    return false;
  if(bottom && border_edge(T::next_in_face(t), o, apex_bottom) && border_edge(T::next_in_face(T::next_in_face(t)), apex_bottom, e))
    return false;
  if(top && bottom)
  {
    if(on_border[o] && on_border[e])
      return false;
    // two interior vertices of valence 3 on an interior edge: a closed tetrahedron (the 1-ring
    // of each is a triangle whose edges all carry two faces)
    if(!on_border[o] && !on_border[e] && o_end - o_begin == 3 && e_end - e_begin == 3)
      return false;
    if(apex_top == apex_bottom)
      return false;
  }
  return true;
}

// Whether moving o onto e (the ends of a halfedge) turns a face around (or makes it
// degenerate): the faces at o that survive must keep the orientation of their normal.
inline bool does_collapse_flip_a_face(const Triangle_halfedges& th, Index o, Index e, const double* xyz)
{
  const double* po = xyz + 3 * std::size_t(o);
  const double* pe = xyz + 3 * std::size_t(e);
  for(Index k = th.out_offsets[o]; k < th.out_offsets[o + 1]; ++k)
  {
    const Index a = th.out_target[k], b = th.out_apex[k];  // face (o, a, b)
    if(b == invalid_index || a == e || b == e)
      continue;                                           // no face, or a face that disappears
    const double* pa = xyz + 3 * std::size_t(a);
    const double* pb = xyz + 3 * std::size_t(b);
    double before[3], after[3];
    cross_of_differences(pa, pb, po, before);
    cross_of_differences(pa, pb, pe, after);
    if(!(before[0] * after[0] + before[1] * after[1] + before[2] * after[2] > 0))
      return true;
  }
  return false;
}

// An accepted half-edge collapse o -> e, in the rows of its level.
struct Collapse { Index o, e; };

// candidate keys (Candidate_key below); every key of such an array is written before it is read
typedef Uninitialized_vector<std::uint64_t> Key_array;
// beside a Key_array, the low bits of each key's cost (Candidate_key::low_bits()), which order
// the runs of equal cost bits in sort_candidates()
typedef Uninitialized_vector<std::uint32_t> Low_bits;

// A candidate collapse in 8 bytes: the leading `cost_bits` bits of the order-preserving
// integer image of its cost (sign, exponent, mantissa), then its halfedge in the low
// `halfedge_bits` bits, as few as the level's halfedge numbers need. With 40 cost bits (28 of
// mantissa) two different costs rarely share a key; with the former fixed split (20 bits of
// mantissa) 15 % of the dragon's candidates did, and ordering them by their recomputed costs
// took 16 % of its decomposition. cost a < cost b implies cost_part(key(a)) <= cost_part(key(b)).
class Candidate_key
{
public:
  explicit Candidate_key(std::size_t number_of_halfedges)
  {
    while(m_halfedge_bits < 32 && (std::uint64_t(1) << m_halfedge_bits) < number_of_halfedges)
      ++m_halfedge_bits;
    m_cost_bits = (std::min)(40, 64 - m_halfedge_bits);
  }
  std::uint64_t operator()(double cost, Index h) const { return of_image(image(cost), h); }
  // the order-preserving integer image of a cost (not NaN): a < b iff image(a) < image(b)
  static std::uint64_t image(double cost)
  {
    cost += 0.;                                             // -0 -> +0: equal costs, equal keys
    std::uint64_t b;
    std::memcpy(&b, &cost, sizeof b);
    return (b >> 63) ? ~b : (b | (std::uint64_t(1) << 63));
  }
  std::uint64_t of_image(std::uint64_t image, Index h) const { return ((image >> (64 - m_cost_bits)) << m_halfedge_bits) | h; }
  // the bits of a cost's image that its key leaves out (the last 64 - cost_bits, at most 32):
  // with the cost bits of the key they order the costs exactly
  std::uint32_t low_bits_of_image(std::uint64_t image) const
  {
    return static_cast<std::uint32_t>(image & ((std::uint64_t(1) << (64 - m_cost_bits)) - 1));
  }
  std::uint32_t low_bits(double cost) const { return low_bits_of_image(image(cost)); }
  Index halfedge(std::uint64_t key) const { return static_cast<Index>(key & ((std::uint64_t(1) << m_halfedge_bits) - 1)); }
  // the leading 24 bits of a key (of its cost bits: at least 32), which cheapest_keys() selects on
  int leading_bits_shift() const { return m_cost_bits + m_halfedge_bits - 24; }
  std::uint64_t leading_bits(std::uint64_t key) const { return key >> leading_bits_shift(); }
  std::uint64_t cost_part(std::uint64_t key) const { return key >> m_halfedge_bits; }
  int halfedge_bits() const { return m_halfedge_bits; }
  int cost_bits() const { return m_cost_bits; }

private:
  int m_halfedge_bits = 0, m_cost_bits = 40;
};

// The last step of sort_candidates(): the runs of keys of equal cost bits of c[0..n), sorted by
// those bits, put in the order of tie_order() (see there).
template <typename TieOrder>
void order_runs_of_equal_cost_bits(std::uint64_t* c, std::size_t n, const Candidate_key& key, const TieOrder& tie_order)
{
  // Runs of equal cost bits are ordered by their exact costs, then halfedges (tie_order()).
  // They are not rare everywhere: the symmetric stencils of a subdivided mesh make exact ties
  // common (11 of the 19 million keys sorted while decomposing a Loop-subdivided horse of 3.1M
  // vertices lie in runs). In parallel over fixed blocks, each owning the runs that start in
  // it (found before anything is written); a block first reads the orders of all its runs'
  // keys in one loop (independent loads whose cache misses overlap), then sorts each run.
  // Every run is sorted whole by one task.
  constexpr std::size_t run_block = std::size_t(1) << 15;
  const std::size_t run_blocks = (n + run_block - 1) / run_block;
  std::vector<std::size_t> run_start(run_blocks + 1, n);
  parallel_for_blocks(run_blocks, [&](std::size_t first, std::size_t last) {
    for(std::size_t b = first; b < last; ++b)
    {
      std::size_t i = b * run_block;
      while(i > 0 && i < n && key.cost_part(c[i]) == key.cost_part(c[i - 1]))
        ++i;
      run_start[b] = i;
    }
  }, 1);
  parallel_for_blocks(run_blocks, [&](std::size_t first, std::size_t last) {
    std::vector<std::pair<std::uint64_t, Index> > members;  // (tie order, field)
    std::vector<std::size_t> runs;                          // begin and end of each run, in c
    for(std::size_t b = first; b < last; ++b)
    {
      members.clear();
      runs.clear();
      for(std::size_t i = run_start[b], end = run_start[b + 1]; i < end;)
      {
        std::size_t j = i + 1;
        while(j < end && key.cost_part(c[j]) == key.cost_part(c[i]))
          ++j;
        if(j - i > 1)
        {
          runs.push_back(i);
          runs.push_back(j);
          for(std::size_t q = i; q < j; ++q)
            members.emplace_back(0, key.halfedge(c[q]));
        }
        i = j;
      }
      for(std::pair<std::uint64_t, Index>& m : members)
        m.first = tie_order(m.second);
      for(std::size_t r = 0, m = 0; r < runs.size(); r += 2)
      {
        const std::size_t i = runs[r], j = runs[r + 1];
        std::sort(members.begin() + m, members.begin() + m + (j - i));   // (cost, h): equal costs keep increasing h
        for(std::size_t q = i; q < j; ++q, ++m)
          c[q] = (key.cost_part(c[q]) << key.halfedge_bits()) | members[m].second;
      }
    }
  }, 1);
}

// Sorts candidate keys (any input order) by increasing cost, equal costs in increasing
// halfedge. Keys of equal cost bits are ordered by tie_order(x), x their low `halfedge_bits`
// field (the halfedge, or a name of it: sort_front()): (Candidate_key::low_bits() of the cost
// << 32) | halfedge, the order of the exact costs, then of the halfedges. Why by hand: a
// comparison sort of the 6n candidates was the largest part of the decomposition (16 % of the dragon's), and candidates holding their costs took 16
// bytes each. This is a stable LSD radix sort on the cost bits of the keys (passes of 10 bits,
// a pass skipped when all candidates share its digit), then a sort by tie_order() inside each
// run of equal cost bits, which makes the order total (that of the exact costs) whatever the
// input order. Deterministic: the same order for any number of threads.
template <typename TieOrder>
void sort_candidates(std::uint64_t* c, std::size_t n, const Candidate_key& key, const TieOrder& tie_order)
{
  radix_sort_bits(c, n, key.halfedge_bits(), key.cost_bits());
  order_runs_of_equal_cost_bits(c, n, key, tie_order);
}

// The rule of the greedy independent set (Section 3.1: "selecting one odd vertex and locking
// all adjacent vertices"), on M_k: a candidate o -> e is taken when o is free (not in the closed
// 1-ring of a taken source), e is the target of no taken collapse, no taken o' -> e' crosses it
// (e a neighbour of o' and e' one of o), the link condition holds and no face flips; its
// source's closed 1-ring is then locked. The target may lie in the 1-ring of another source:
// the paper asks no more, and a rule that also locked e (free ends only) took 14.6 % of the
// dragon's vertices on its first level instead of 16.2 % (50 levels instead of 42 to the
// coarsest mesh, 6.1 n instead of 5.2 n vertices processed down to 1 %). Why the tests made
// on M_k still hold when the collapses are made together, in any order: no face holds two odd
// vertices (their stars are disjoint), so every face is renamed or removed by one collapse at
// most, and the star of o is not changed by another collapse o' -> e'; that collapse only makes
// e' a neighbour of the vertices of the 1-ring of o' (e among them when e is in it), and e the
// neighbour of the 1-ring of o' if e = e'. So o and e gain a common neighbour (which the link
// condition forbids) only for a shared target, which is refused, or for crossed collapses, which
// are refused too (o and o' then share the neighbours e and e'; were e and e' not joined, the
// two collapses would give their new edge four faces). The same holds for any subset of a
// level's collapses, which the vertex splits of an adaptive reconstruction rely on.
enum Selection_lock : unsigned char { in_a_taken_star = 1, taken_target = 2 };

// Whether o -> e crosses a taken collapse o' -> e': e a neighbour of o' and e' one of o.
// `is_taken_target(y)`: whether y is the target of a taken collapse, `source_of(y)` its source.
template <typename IsTakenTarget, typename SourceOf>
bool crosses_a_taken_collapse(const Triangle_halfedges& th, Index o, Index e, const IsTakenTarget& is_taken_target,
                              const SourceOf& source_of)
{
  for(Index k = th.out_offsets[o]; k < th.out_offsets[o + 1]; ++k)
  {
    const Index y = th.out_target[k];
    if(y == e || !is_taken_target(y))
      continue;
    const Index s = source_of(y);
    for(Index q = th.out_offsets[s]; q < th.out_offsets[s + 1]; ++q)
      if(th.out_target[q] == e)
        return true;
  }
  return false;
}

// A sorted candidate replaced by the ends of its halfedge, source in the high 32 bits
// (candidate_ends()): what the greedy loop reads first of every candidate.
inline std::uint64_t ends_of_candidate(Index o, Index e) { return (std::uint64_t(o) << 32) | e; }
inline Index source_of_ends(std::uint64_t ends) { return static_cast<Index>(ends >> 32); }
inline Index target_of_ends(std::uint64_t ends) { return static_cast<Index>(ends & 0xffffffffu); }

// Replaces the sorted candidate keys from position `first` on by the ends of their halfedges
// (ends_of_candidate()), in parallel. Why: the greedy loop read the two ends of every candidate
// at random places of the level's halfedge arrays, one candidate after the other; four fifths
// of the candidates it scans are refused on these ends alone (a source in a taken star), so
// those loads were most of its time on large meshes, where it is the decomposition's largest
// sequential part. Here they are independent loads in parallel blocks, and the loop streams
// the ends. Only for halfedge structures without a repeated directed edge, where the ends name
// the halfedge (take_greedily() finds it in the source's ring). The ends are th's lists, or,
// where th was built without them, read from its face array `faces` and the twins
// (Triangle_halfedges::source_of()).
inline void candidate_ends(const Triangle_halfedges& th, const Candidate_key& key, Key_array& candidates, std::size_t first,
                           const std::vector<Index>* faces = nullptr)
{
  CGAL_precondition(!th.repeated_directed_edge);
  CGAL_precondition(th.has_ends() || faces != nullptr);
  parallel_for_blocks(candidates.size() - first, [&](std::size_t b, std::size_t e) {
    for(std::size_t i = first + b; i < first + e; ++i)
    {
      const Index h = key.halfedge(candidates[i]);
      candidates[i] = ends_of_candidate(th.source_of(h, faces), th.target_of(h, faces));
    }
  });
}

// The selection loop of select_collapses(): candidates in order, each accepted if the rule
// above admits it; the first `considered` candidates, more (half as many again
// each time) while fewer than `minimum` are accepted. `candidates` holds the first `sorted` of
// the `all` candidates in order; sort_rest() appends the others, in order, when they are needed.
// `as_ends`: the candidates are given by their ends (candidate_ends()), else as keys.
template <typename SortRest>
void take_greedily(const Triangle_halfedges& th, const double* xyz, const Key_array& candidates,
                   std::size_t sorted, std::size_t all, const SortRest& sort_rest, const Candidate_key& key, std::size_t budget,
                   const std::vector<unsigned char>& on_border, std::vector<unsigned char>& locked,
                   Index_array& source_of_target, std::vector<Collapse>& accepted, std::size_t considered, std::size_t minimum,
                   bool as_ends = false)
{
  CGAL_precondition(as_ends || th.has_ends());            // by halfedge: their ends are listed
  // The candidates come in cost order, that is at random places of the level's arrays: on a
  // mesh larger than the cache each test waits for a dozen misses. Why by hand: the loop keeps
  // a window of the next candidates whose ends were free when first seen and prefetches, in
  // steps, what their tests read (ring offsets and twin, then the rings, then o's neighbours'
  // positions), so that these misses overlap with the decisions before them. The decisions are
  // those of the plain loop: only cache hints are added, every candidate is checked again when
  // its turn comes. Given by their ends, the candidates' halfedges are found in the rings
  // the window prefetches.
  // `locked`: the Selection_lock flags of every vertex (all 0 on entry); `source_of_target`:
  // at least th.n entries, the source of each taken target (others not read)
  auto may_take = [&](Index o, Index e) { return !(locked[o] & in_a_taken_star) && !(locked[e] & taken_target); };
  struct Pending { Index h, o, e; };
  constexpr std::size_t window = 16, ring_step = window / 2, position_step = 3, gather_ahead = 32;
  Pending pending[window];
  std::size_t head = 0, count = 0, scan = 0;
  std::size_t nc = (std::min)(all, considered);
  if(nc > sorted)
  {
    sort_rest();
    sorted = all;
  }
  auto prefetch_ring = [&](Index v) {
    prefetch(th.out.data() + th.out_offsets[v]);
    prefetch(th.out_target.data() + th.out_offsets[v]);
    prefetch(th.out_apex.data() + th.out_offsets[v]);
  };
  while(accepted.size() < budget)
  {
    // refill the window with candidates that may be taken now
    while(count < window && scan < nc)
    {
      if(scan + gather_ahead < nc)
      {
        const std::uint64_t later = candidates[scan + gather_ahead];
        if(as_ends)
        {
          prefetch(locked.data() + source_of_ends(later));
          prefetch(locked.data() + target_of_ends(later));
        }
        else
        {
          prefetch(th.source.data() + key.halfedge(later));
          prefetch(th.target.data() + key.halfedge(later));
        }
      }
      const std::uint64_t c = candidates[scan++];
      const Index h = as_ends ? invalid_index : key.halfedge(c);
      const Index o = as_ends ? source_of_ends(c) : th.source[h];
      const Index e = as_ends ? target_of_ends(c) : th.target[h];
      if(!may_take(o, e))
        continue;
      pending[(head + count++) % window] = Pending{h, o, e};
      prefetch(th.out_offsets.data() + o);
      prefetch(th.out_offsets.data() + e);
      if(!as_ends)
        prefetch(th.twin.data() + h);
    }
    if(count == 0 && scan == nc && nc < all && accepted.size() < minimum)
    {
      nc = (std::min)(all, nc + (nc + 1) / 2);              // too few accepted under the cap: look further
      if(nc > sorted)
      {
        sort_rest();                                        // the candidates past the sorted prefix (rare)
        sorted = all;
      }
      continue;
    }
    if(count == 0)
      break;
    if(count > ring_step)
    {
      const Pending& p = pending[(head + ring_step) % window];
      prefetch_ring(p.o);
      prefetch_ring(p.e);
    }
    if(count > position_step)
    {
      Pending& p = pending[(head + position_step) % window];
      prefetch(xyz + 3 * std::size_t(p.o));
      for(Index k = th.out_offsets[p.o]; k < th.out_offsets[p.o + 1]; ++k)
      {
        prefetch(xyz + 3 * std::size_t(th.out_target[k]));
        if(p.h == invalid_index && th.out_target[k] == p.e)
        {
          p.h = th.out[k];                                  // (given by its ends)
          prefetch(th.twin.data() + p.h);
        }
      }
    }
    Pending c = pending[head];
    head = (head + 1) % window;
    --count;
    if(!may_take(c.o, c.e))
      continue;
    if((locked[c.e] & in_a_taken_star)                    // e in the 1-ring of a taken source: a crossing?
       && crosses_a_taken_collapse(th, c.o, c.e, [&](Index y) { return (locked[y] & taken_target) != 0; },
                                   [&](Index y) { return source_of_target[y]; }))
      continue;
    if(c.h == invalid_index)                                // given by its ends, not found ahead (a short window)
      for(Index k = th.out_offsets[c.o]; k < th.out_offsets[c.o + 1] && c.h == invalid_index; ++k)
        if(th.out_target[k] == c.e)
          c.h = th.out[k];
    if(!satisfies_link_condition(th, c.h, c.o, c.e, on_border) || does_collapse_flip_a_face(th, c.o, c.e, xyz))
      continue;
    locked[c.o] |= in_a_taken_star;
    for(Index k = th.out_offsets[c.o]; k < th.out_offsets[c.o + 1]; ++k)
      locked[th.out_target[k]] |= in_a_taken_star;
    locked[c.e] |= taken_target;
    source_of_target[c.e] = c.o;
    accepted.push_back(Collapse{c.o, c.e});
  }
}


// The selection of take_greedily() in parallel rounds, with the same result: a candidate is
// taken by the greedy loop iff the rule above admits it given the earlier taken candidates.
// Every earlier candidate o' -> e' that can refuse o -> e has o' in the closed 1-ring of o
// (o in the star of o') or of e (e = e', or e a neighbour of o'). Why by hand: the greedy
// loop was the decomposition's largest sequential part. The candidates are decided a window
// at a time by deterministic reservations (Blelloch, Fineman, Gibbons and Shun, "Internally
// deterministic parallel algorithms can be fast", PPoPP 2012): in each round every undecided
// candidate not yet blocked writes its position (atomic minimum) on its source o; one whose
// closed 1-rings of o and e hold no smaller position has no undecided candidate before it
// that could refuse it, so it is decided now (tested, taken if admitted); taken candidates
// then write their position on the locks of their source's closed 1-ring and on their
// target. Locks hold the smallest position of the candidates that took them, and a candidate
// is refused only by locks of smaller positions: what a later candidate takes never changes an
// earlier one's decision. The earliest undecided candidate is decided in every round. Same
// decisions as the loop for any number of threads (a test compares them), the same tests made
// (only candidates with a free source and a target not taken at their turn are tested).
template <typename SortRest>
void take_greedily_in_rounds(const Triangle_halfedges& th, const double* xyz, const Key_array& candidates,
                             std::size_t sorted, std::size_t all, const SortRest& sort_rest, const Candidate_key& key, std::size_t budget,
                             const std::vector<unsigned char>& on_border, Index_array& source_of_target,
                             std::vector<Collapse>& accepted, std::size_t considered, std::size_t minimum, std::size_t window,
                             const std::vector<Index>* faces = nullptr)
{
  CGAL_precondition(th.has_ends() || faces != nullptr);   // the ends of a halfedge: listed, or from the faces
  constexpr Index none = invalid_index;
  constexpr std::size_t grain = 512;
  std::unique_ptr<std::atomic<Index>[]> lock(new std::atomic<Index>[th.n]), reserve(new std::atomic<Index>[th.n]),
                                        target_lock(new std::atomic<Index>[th.n]);
  // source_of_target (at least th.n entries) is written with target_lock and read rounds later
  parallel_for_blocks(th.n, [&](std::size_t first, std::size_t last) {
    for(std::size_t v = first; v < last; ++v)
    {
      lock[v].store(none, std::memory_order_relaxed);
      reserve[v].store(none, std::memory_order_relaxed);
      target_lock[v].store(none, std::memory_order_relaxed);
    }
  });
  auto write_min = [](std::atomic<Index>& a, Index p) {
    Index current = a.load(std::memory_order_relaxed);
    while(p < current && !a.compare_exchange_weak(current, p, std::memory_order_relaxed)) {}
  };
  auto for_closed_ring = [&](Index o, const auto& f) {
    f(o);
    for(Index k = th.out_offsets[o]; k < th.out_offsets[o + 1]; ++k)
      f(th.out_target[k]);
  };
  struct Pending { Index p, h, o, e; };
  enum : unsigned char { undecided = 0, taken = 1, rejected = 2, blocked = 3 };
  std::vector<Pending> pending, still;
  std::vector<unsigned char> state;
  std::vector<Pending> taken_here;
  std::size_t nc = (std::min)(all, considered), scan = 0;
  if(nc > sorted)
  {
    sort_rest();
    sorted = all;
  }
  while(accepted.size() < budget)
  {
    if(scan == nc)
    {
      if(nc < all && accepted.size() < minimum)
      {
        nc = (std::min)(all, nc + (nc + 1) / 2);              // too few accepted under the cap: look further
        if(nc > sorted)
        {
          sort_rest();
          sorted = all;
        }
        continue;
      }
      break;
    }
    const std::size_t count = (std::min)(nc - scan, window);
    pending.resize(count);
    parallel_for_blocks(count, [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
      {
        const Index h = key.halfedge(candidates[scan + i]);
        pending[i] = Pending{static_cast<Index>(scan + i), h, th.source_of(h, faces), th.target_of(h, faces)};
      }
    }, grain);
    scan += count;
    taken_here.clear();
    while(!pending.empty())
    {
      const std::size_t np = pending.size();
      state.assign(np, undecided);
      // one parallel pass over the pending candidates not blocked (f(i, candidate))
      auto for_unblocked = [&](const auto& f) {
        parallel_for_blocks(np, [&](std::size_t first, std::size_t last) {
          for(std::size_t i = first; i < last; ++i)
            if(state[i] != blocked)
              f(i, pending[i]);
        }, grain);
      };
      for_unblocked([&](std::size_t i, const Pending& c) {   // blocked by an earlier taken one, or reserves its source
        if(lock[c.o].load(std::memory_order_relaxed) < c.p || target_lock[c.e].load(std::memory_order_relaxed) < c.p)
          state[i] = blocked;
        else
          write_min(reserve[c.o], c.p);
      });
      for_unblocked([&](std::size_t i, const Pending& c) {   // decided when no earlier undecided source is near
        bool ready = true;
        auto first_here = [&](Index v) { ready = ready && reserve[v].load(std::memory_order_relaxed) >= c.p; };
        for_closed_ring(c.o, first_here);
        for_closed_ring(c.e, first_here);
        if(ready)
          state[i] = !(lock[c.e].load(std::memory_order_relaxed) < c.p     // e in an earlier taken star: a crossing?
                       && crosses_a_taken_collapse(th, c.o, c.e,
                                                   [&](Index y) { return target_lock[y].load(std::memory_order_relaxed) < c.p; },
                                                   [&](Index y) { return source_of_target[y]; }))
                     && satisfies_link_condition(th, c.h, c.o, c.e, on_border) && !does_collapse_flip_a_face(th, c.o, c.e, xyz)
                   ? taken : rejected;
      });
      for_unblocked([&](std::size_t i, const Pending& c) {   // reservations cleared, locks taken
        reserve[c.o].store(none, std::memory_order_relaxed);
        if(state[i] == taken)
        {
          for_closed_ring(c.o, [&](Index v) { write_min(lock[v], c.p); });
          target_lock[c.e].store(c.p, std::memory_order_relaxed);   // one taker per target (they would conflict)
          source_of_target[c.e] = c.o;
        }
      });
      still.clear();
      for(std::size_t i = 0; i < np; ++i)
        if(state[i] == undecided)
          still.push_back(pending[i]);
        else if(state[i] == taken)
          taken_here.push_back(pending[i]);
      pending.swap(still);
    }
    std::sort(taken_here.begin(), taken_here.end(), [](const Pending& a, const Pending& b) { return a.p < b.p; });
    for(std::size_t i = 0; i < taken_here.size() && accepted.size() < budget; ++i)
      accepted.push_back(Collapse{taken_here[i].o, taken_here[i].e});
  }
}

// A hint that cost(o, e) will be read soon, for cost models that have one
// (Plane_quadrics::prefetch_target()); none for the others.
template <typename CostOfRows>
auto prefetch_cost_operands(const CostOfRows& cost, Index e, int) -> decltype(cost.prefetch_target(e), void())
{
  cost.prefetch_target(e);
}
template <typename CostOfRows>
void prefetch_cost_operands(const CostOfRows&, Index, long) {}

// the costs of moving row o onto rows e, for the whole 1-ring of o (candidate_keys()):
// `cost.costs_from(o)` where it exists, else `cost(o, e)`; NaN for a refused collapse
template <typename CostOfRows>
auto costs_from_source(const CostOfRows& cost, Index o, int) -> decltype(cost.costs_from(o))
{
  return cost.costs_from(o);
}

template <typename CostOfRows>
auto costs_from_source(const CostOfRows& cost, Index o, long)
{
  return [&cost, o](Index e) {
    const Optional<double> oc = cost(o, e);
    return oc ? *oc : std::numeric_limits<double>::quiet_NaN();
  };
}

// the cost of the candidate o -> e of halfedge h, o on the border or not (cost_from_o:
// costs_from_source() of o); NaN, refused, where a border vertex would leave the border
// (border vertices move along the border only)
template <typename CostFrom>
double candidate_cost(const Triangle_halfedges& th, bool border, Index h, Index e, const CostFrom& cost_from_o)
{
  return border && !th.is_border_edge(h) ? std::numeric_limits<double>::quiet_NaN() : cost_from_o(e);
}

// the key of a refused candidate: none (its cost bits would be a NaN's)
constexpr std::uint64_t refused_candidate = ~std::uint64_t(0);

// Keeps the keys x of `c` for which keep(x) holds, in their order, and their low bits in `low`
// (if given)
template <typename Keep>
void keep_keys(Key_array& c, Low_bits* low, const Keep& keep)
{
  std::size_t w = 0;
  for(std::size_t i = 0; i < c.size(); ++i)
    if(keep(c[i]))
    {
      if(low != nullptr)
        (*low)[w] = (*low)[i];
      c[w++] = c[i];
    }
  c.resize(w);
  if(low != nullptr)
    low->resize(w);
}

// A limit on the leading bits (Candidate_key::leading_bits()) of the keys of `c` under which
// at least `wanted` of them lie, estimated from a sample of the keys, or ~0 where `c` is too
// short to sample (32,768 keys). The sample is every s-th key (sample_stride()), s a prime
// (17 to 127) near the cube root of the number of keys: a fixed choice (deterministic), prime
// so that it does not keep to some corners of rings of 6 (regular meshes list their rings in a
// repeating pattern), and of the size that balances the cost of a sampled key (its read and
// selection, about 30 ns on the dragon) against that of the front's margin (a key more to
// sort, about 45 ns). The
// sample rank is the wanted one plus three standard deviations of a binomial count and 8, so
// that the front of cheapest_keys() is a few percent larger than `wanted` and rarely smaller
// (cheapest_keys() then selects exactly).
inline std::size_t sample_stride(std::size_t n)
{
  std::size_t stride = 17;
  for(std::size_t s : {31, 61, 127})
    if(2 * s * s * s < n)
      stride = s;
  return stride;
}

inline std::uint64_t sampled_limit(const Key_array& c, const Candidate_key& key, std::uint64_t refused, std::size_t wanted)
{
  const std::size_t n = c.size();
  if(n < (std::size_t(1) << 15))
    return ~std::uint64_t(0);
  const std::size_t stride = sample_stride(n);
  std::vector<std::uint64_t> sample;
  sample.reserve(n / stride + 1);
  for(std::size_t i = stride / 2; i < n; i += stride)   // keys stride / 2 + j stride
    if(c[i] != refused)
      sample.push_back(key.leading_bits(c[i]));
  const double expected = double(wanted) / double(stride);   // the wanted key's rank among the samples
  const std::size_t rank = static_cast<std::size_t>(expected + 3. * std::sqrt(expected) + 8.);
  if(rank >= sample.size())
    return ~std::uint64_t(0);
  std::nth_element(sample.begin(), sample.begin() + std::ptrdiff_t(rank), sample.end());
  return sample[rank];
}

// The keys of `c` in fixed blocks (cheapest_keys()): f(b, first, last) for every block b, in
// parallel
constexpr std::size_t front_block = std::size_t(1) << 18;

template <typename F>
void for_key_blocks(std::size_t n, const F& f)
{
  for_fixed_blocks(n, front_block, f);
}

// The radix select of cheapest_keys(): the leading bits of the rank-th cheapest key of `c`
// (1-based), found by a histogram of the first 12 of them in fixed blocks, then one of the next
// 12 inside the bucket holding that key. kept[b]: the keys of block b not refused, `total`
// their sum; offset[b + 1] - offset[b]: the keys of block b at or under the limit (set only
// when 2 rank < total, else ~0 is returned: every key is wanted).
inline std::uint64_t select_front_limit(const Key_array& c, const Candidate_key& key, std::uint64_t refused, std::size_t rank,
                                        std::vector<std::size_t>& kept, std::vector<std::size_t>& offset, std::size_t& total)
{
  constexpr int digit_bits = 12;
  constexpr std::size_t buckets = std::size_t(1) << digit_bits;
  const std::size_t blocks = kept.size();
  const int shift2 = key.leading_bits_shift(), shift1 = shift2 + digit_bits;   // the two digits of the leading bits
  const std::uint64_t mask = buckets - 1;
  std::vector<std::size_t> hist1(blocks * buckets), hist2(blocks * buckets);
  for_key_blocks(c.size(), [&](std::size_t b, std::size_t first, std::size_t last) {
    std::size_t* h = hist1.data() + b * buckets;
    std::size_t k = 0;
    for(std::size_t i = first; i < last; ++i)
      if(c[i] != refused) { ++h[(c[i] >> shift1) & mask]; ++k; }
    kept[b] = k;
  });
  total = 0;
  for(std::size_t k : kept)
    total += k;
  if(2 * rank >= total)
    return ~std::uint64_t(0);
  // the bucket of the wanted-th key (1-based), first by the leading digit, then by the next
  auto bucket_of_rank = [&](const std::vector<std::size_t>& hist, std::size_t& before) {
    for(std::size_t v = 0; v < buckets; ++v)
    {
      std::size_t in = 0;
      for(std::size_t b = 0; b < blocks; ++b)
        in += hist[b * buckets + v];
      if(before + in >= rank)
        return static_cast<std::uint64_t>(v);
      before += in;
    }
    return static_cast<std::uint64_t>(buckets - 1);            // not reached: rank <= total
  };
  std::size_t below = 0;
  const std::uint64_t d1 = bucket_of_rank(hist1, below);
  for_key_blocks(c.size(), [&](std::size_t b, std::size_t first, std::size_t last) {
    std::size_t* h = hist2.data() + b * buckets;
    for(std::size_t i = first; i < last; ++i)
      if(c[i] != refused && ((c[i] >> shift1) & mask) == d1)
        ++h[(c[i] >> shift2) & mask];
  });
  const std::uint64_t d2 = bucket_of_rank(hist2, below);
  for(std::size_t b = 0; b < blocks; ++b)
  {
    std::size_t in = 0;
    for(std::size_t v = 0; v < d1; ++v)
      in += hist1[b * buckets + v];
    for(std::size_t v = 0; v <= d2; ++v)
      in += hist2[b * buckets + v];
    offset[b + 1] = offset[b] + in;
  }
  return (d1 << digit_bits) | d2;
}

// The cheapest candidate keys of `c`, in their order in `c`, without the `refused` ones: the
// keys whose leading 24 bits (Candidate_key::leading_bits()) are at most `limit`, at least
// the `wanted` cheapest (all keys, limit = ~0, when wanted is at least half of them; `c` is
// then emptied). A true prefix of the sorted order, runs of equal cost bits included, whatever
// the order inside it; `total`: the number of keys not refused. The other keys stay in `c`
// (keys_above() extracts them). The limit is sampled (sampled_limit()), then checked by a
// count of the keys under it, which also numbers each block's part of the front; where the
// sample fell short (or `c` is short), it is that of the wanted-th cheapest key, found by a
// radix select (select_front_limit()). Then the front is scattered
// in block order: parallel and deterministic. Why by hand: std::nth_element over the 6 n
// candidates was sequential (10 % of the dragon's decomposition on two threads). Why sampled:
// the histograms' increments of nearby keys (similar costs: the same bucket) waited on each
// other; the count is a comparison per key. The front is a new array of about n keys, `c` is
// left as it is (compacting the rest in place and moving the front before it were sequential
// passes over the 6 n keys: a third of the select's time). `low` (if given): the low bits of
// every key of `c`, whose front's are then written to `front_low` (and `low` is emptied with `c`).
// `kept_total` (if known): the number of keys of `c` not refused, which the count then takes
// instead of counting them. (A refused key, ~0, has all its leading bits set, which no key of
// a cost that is not NaN has: +inf's are 0xfff000. So a limit that is some key's leading
// bits keeps the refused keys out without testing them.)
constexpr std::size_t unknown_total = ~std::size_t(0);

inline Key_array cheapest_keys(Key_array& c, const Candidate_key& key, std::uint64_t refused,
                               std::size_t wanted, std::size_t& total, std::uint64_t& limit,
                               Low_bits* low = nullptr, Low_bits* front_low = nullptr,
                               std::size_t kept_total = unknown_total)
{
  const std::size_t n = c.size();
  const std::size_t blocks = (n + front_block - 1) / front_block;
  const int shift = key.leading_bits_shift();
  const std::size_t rank = (std::max)(wanted, std::size_t(1));
  std::vector<std::size_t> kept(blocks), offset(blocks + 1, 0);
  limit = sampled_limit(c, key, refused, wanted);
  bool counted = false;
  if(limit != ~std::uint64_t(0))
  {
    // the keys under the sampled limit, per block (refused keys are above it)
    CGAL_assertion(limit < (refused >> shift));
    std::vector<std::size_t> under(blocks);
    for_key_blocks(n, [&](std::size_t b, std::size_t first, std::size_t last) {
      const std::uint64_t* keys = c.data();
      const std::uint64_t lim = limit;
      std::size_t u = 0;
      for(std::size_t i = first; i < last; ++i)
        u += (keys[i] >> shift) <= lim;
      under[b] = u;
    });
    // (a caller that does not know the keys not refused has them counted here: tests only)
    total = kept_total != unknown_total ? kept_total
                                        : n - std::size_t(std::count(c.begin(), c.end(), refused));
    for(std::size_t b = 0; b < blocks; ++b)
      offset[b + 1] = offset[b] + under[b];
    counted = 2 * rank < total && offset[blocks] >= rank;
  }
  if(!counted && (limit == ~std::uint64_t(0) || 2 * rank < total))   // (else all keys are wanted)
    limit = select_front_limit(c, key, refused, rank, kept, offset, total);
  if(2 * rank >= total)
  {
    limit = ~std::uint64_t(0);
    keep_keys(c, low, [&](std::uint64_t x) { return x != refused; });   // the order kept
    Key_array all;
    all.swap(c);
    if(low != nullptr)
      front_low->swap(*low);
    return all;
  }
  CGAL_assertion(limit < (refused >> shift));         // a key's leading bits (sampled or selected)
  Key_array front(offset[blocks]);
  if(low != nullptr)
    front_low->resize(front.size());
  // local pointers, copied in the lambda: through its captured references, every store into the
  // front made the compiler load the arrays' addresses again
  const std::uint64_t* const keys_at = c.data();
  std::uint64_t* const front_at = front.data();
  const std::uint32_t* const low_at = low != nullptr ? low->data() : nullptr;
  std::uint32_t* const front_low_at = low != nullptr ? front_low->data() : nullptr;
  for_key_blocks(n, [&](std::size_t b, std::size_t first, std::size_t last) {
    const std::uint64_t* keys = keys_at;
    std::uint64_t* to = front_at;
    const std::uint32_t* low_bits = low_at;
    std::uint32_t* to_low = front_low_at;
    const int s = shift;
    const std::uint64_t lim = limit;
    std::size_t w = offset[b];
    for(std::size_t i = first; i < last; ++i)
    {
      const std::uint64_t x = keys[i];
      if((x >> s) <= lim)                                // (refused keys are above the limit)
      {
        if(low_bits != nullptr)
          to_low[w] = low_bits[i];
        to[w++] = x;
      }
    }
  });
  return front;
}

// Keeps in `c`, in their order, the keys past the front of cheapest_keys() (leading bits above
// `limit`, refused keys left out), and their low bits in `low` (if given)
inline void keys_above(Key_array& c, const Candidate_key& key, std::uint64_t refused, std::uint64_t limit,
                       Low_bits* low = nullptr)
{
  keep_keys(c, low, [&](std::uint64_t x) { return x != refused && key.leading_bits(x) > limit; });
}

// The keys of the candidate collapses of one level, every halfedge o -> e of M_k in the order
// of the vertices' lists of outgoing halfedges, `refused_candidate` for those that would move a border
// vertex off the border and those the cost model refuses; `low_bits` (if given, one per
// candidate, in the same order): the low bits of each candidate's cost (Candidate_key::low_bits());
// `refused_count` (if given): the number of refused candidates (cheapest_keys()' kept_total
// is the others). Computed in parallel (TBB), vertex by vertex (the quadric of o is read once for its 1-ring,
// Plane_quadrics::costs_from(); those of its neighbours are near in memory), each into its own
// slot. The operands of the cost of the candidate `cost_prefetch_distance` places ahead are
// prefetched: on the dragon the costs waited on the loads of Q_e and p_e (46 % of their
// samples), one after the other.
constexpr Index cost_prefetch_distance = 16;

template <typename CostOfRows>
Key_array candidate_keys(const Triangle_halfedges& th, const CostOfRows& cost,
                         const std::vector<unsigned char>& on_border, const Candidate_key& key,
                         std::uint32_t* low_bits = nullptr, std::size_t* refused_count = nullptr)
{
  Key_array candidates(th.number_of_halfedges());
  std::atomic<std::size_t> refused_keys(0);
  parallel_for_blocks(th.n, [&](std::size_t first, std::size_t last) {
    // local copies of the key and of the arrays' addresses: read through references, they were
    // loaded again after every store of a key or of its low bits (a store to an unsigned int
    // may change an int of the key or an Index of the lists)
    const Candidate_key local_key = key;
    const Index* const offsets = th.out_offsets.data();
    const Index* const out = th.out.data();
    const Index* const out_target = th.out_target.data();
    std::uint64_t* const keys = candidates.data();
    std::uint32_t* const low = low_bits;
    const Index end = offsets[last];
    std::size_t refused_here = 0;
    for(std::size_t o = first; o < last; ++o)
    {
      const auto cost_from_o = costs_from_source(cost, static_cast<Index>(o), 0);
      const bool border = on_border[o] != 0;
      for(Index k = offsets[o], row_end = offsets[o + 1]; k < row_end; ++k)
      {
        if(k + cost_prefetch_distance < end)
          prefetch_cost_operands(cost, out_target[k + cost_prefetch_distance], 0);
        const Index h = out[k];
        const double c = candidate_cost(th, border, h, out_target[k], cost_from_o);
        if(std::isnan(c))
        {
          keys[k] = refused_candidate;
          ++refused_here;
        }
        else
        {
          const std::uint64_t image = Candidate_key::image(c);
          keys[k] = local_key.of_image(image, h);
          if(low != nullptr)
            low[k] = local_key.low_bits_of_image(image);
        }
      }
    }
    refused_keys.fetch_add(refused_here, std::memory_order_relaxed);
  }, 1024);
  if(refused_count != nullptr)
    *refused_count = refused_keys.load();
  return candidates;
}

// The rows of a level in fixed blocks (sampled_candidate_limit(), candidate_front()):
// f(b, first, last) for every block b of rows [first, last), in parallel
constexpr std::size_t row_block = std::size_t(1) << 12;

template <typename F>
void for_row_blocks(std::size_t n, const F& f)
{
  for_fixed_blocks(n, row_block, f);
}

// A limit on the leading bits of the keys candidate_keys() would compute under which at least
// `wanted` of them lie, estimated from the keys of a sample of whole rows, or ~0 where there are
// too few candidates to sample (32,768). The rows sampled are every r-th, r a prime near twice
// sample_stride() of the candidates: about three times as many candidates as sampled_limit()'s
// sample, in a third of the time of that many scattered ones (0.008 against 0.025 s over the
// dragon's levels, one thread: a row reads its quadric and its neighbours once for all its
// candidates); a row's candidates have related costs, so the rank taken is the expected
// one plus three standard deviations of a binomial count over rows of two candidates (with
// rows of one, the dragon's front fell short on one level; of six, the fronts were 20 % larger
// than wanted: more to sort). In parallel over the sampled rows, each writing its keys at its
// place, found by a prefix sum of their lengths.
template <typename CostOfRows>
std::uint64_t sampled_candidate_limit(const Triangle_halfedges& th, const CostOfRows& cost,
                                      const std::vector<unsigned char>& on_border, const Candidate_key& key, std::size_t wanted)
{
  const std::size_t nh = th.number_of_halfedges();
  if(nh < (std::size_t(1) << 15) || th.n == 0)
    return ~std::uint64_t(0);
  const std::size_t stride = sample_stride(nh);
  const std::size_t r = stride == 17 ? 37 : (stride == 31 ? 61 : (stride == 61 ? 127 : 251));
  const std::size_t rows = (th.n + r - 1) / r;               // the rows j r
  std::vector<std::size_t> place(rows + 1, 0);
  for(std::size_t j = 0; j < rows; ++j)
    place[j + 1] = place[j] + (th.out_offsets[j * r + 1] - th.out_offsets[j * r]);
  std::vector<std::uint64_t> sample(place[rows]);
  parallel_for_blocks(rows, [&](std::size_t first, std::size_t last) {
    for(std::size_t j = first; j < last; ++j)
    {
      const Index o = static_cast<Index>(j * r);
      const auto cost_from_o = costs_from_source(cost, o, 0);
      const bool border = on_border[o] != 0;
      for(Index k = th.out_offsets[o], i = 0; k < th.out_offsets[o + 1]; ++k, ++i)
      {
        const double c = candidate_cost(th, border, th.out[k], th.out_target[k], cost_from_o);
        sample[place[j] + i] = std::isnan(c) ? refused_candidate : key.leading_bits(key(c, th.out[k]));
      }
    }
  }, 64);
  const double expected = double(wanted) * double(sample.size()) / double(nh);   // the wanted key's rank among the samples
  sample.erase(std::remove(sample.begin(), sample.end(), refused_candidate), sample.end());
  const std::size_t rank = static_cast<std::size_t>(expected + 3. * std::sqrt(2. * expected) + 16.);
  if(rank >= sample.size())
    return ~std::uint64_t(0);
  std::nth_element(sample.begin(), sample.begin() + std::ptrdiff_t(rank), sample.end());
  return sample[rank];
}

// The front of cheapest_keys() for the keys of candidate_keys() (the keys whose leading bits
// are at most `limit`, refused ones left out), computed without the keys of the other
// candidates, ready to be sorted by sort_renamed_front(): each front key names its place in
// the front instead of its halfedge (sort_front()), `halfedge` the halfedge of each place,
// `low` the low bits of its cost and, `ends` given, its ends (ends_of_candidate()). `total`:
// the number of candidates not refused. Returns the size of the front: at least `wanted`
// unless the limit fell short (sorted_candidates() then selects from all keys; the arrays are
// then not written). Why: the keys of all the 6 n candidates (8 bytes each, and 4 of low
// bits) were written, then read twice by cheapest_keys() (its count and its scatter), for a
// front of about n of them, and candidate_ends() read the ends of the front's halfedges again
// at random places of the face array; here each block of rows keeps its front in a buffer of
// its own (joined in block order: deterministic) with the ends, which its rows give.
// a candidate of the front of candidate_front(): its key, its ends, the low bits of its cost
struct Front_entry { std::uint64_t key, ends; std::uint32_t low; };

template <typename CostOfRows>
std::size_t candidate_front(const Triangle_halfedges& th, const CostOfRows& cost, const std::vector<unsigned char>& on_border,
                            const Candidate_key& key, std::uint64_t limit, std::size_t wanted, Key_array& front, Low_bits& low,
                            Index_array& halfedge, Key_array* ends, std::size_t& total, Uninitialized_vector<Front_entry>& arena)
{
  typedef Front_entry Entry;
  const std::size_t blocks = (th.n + row_block - 1) / row_block;
  // Each block writes its front into its slice of `arena`, a third of an entry per candidate
  // (8 bytes: the size of the level's cotangents, which the caller allocates once it has freed
  // the arena; with a buffer per block, from the heap, the dragon's peak rose by 12 MB, the
  // cotangents touching fresh pages); a block whose front outgrows its slice goes on in a vector
  // of its own (`spilled`).
  std::vector<std::size_t> slice(blocks + 1, 0);
  for(std::size_t b = 0; b < blocks; ++b)
    slice[b + 1] = slice[b] + (th.out_offsets[(std::min)(th.n, (b + 1) * row_block)] - th.out_offsets[b * row_block]) / 3 + 64;
  arena.resize(slice[blocks]);
  std::vector<Uninitialized_vector<Entry> > spilled(blocks);
  std::vector<std::size_t> count(blocks), kept(blocks);
  for_row_blocks(th.n, [&](std::size_t b, std::size_t first, std::size_t last) {
    // local copies: see candidate_keys(); the block's front is written through a pointer
    const Candidate_key local_key = key;
    const int shift = local_key.leading_bits_shift();
    const std::uint64_t lim = limit;
    const Index* const offsets = th.out_offsets.data();
    const Index* const out = th.out.data();
    const Index* const out_target = th.out_target.data();
    const Index end = offsets[last];
    Entry* const begin = arena.data() + slice[b];
    Entry* to = begin;
    Entry* to_end = arena.data() + slice[b + 1];
    Uninitialized_vector<Entry>& spill = spilled[b];
    std::size_t not_refused = 0;
    for(std::size_t o = first; o < last; ++o)
    {
      const auto cost_from_o = costs_from_source(cost, static_cast<Index>(o), 0);
      const bool border = on_border[o] != 0;
      const Index row_begin = offsets[o], row_end = offsets[o + 1];
      if(std::size_t(to_end - to) < std::size_t(row_end - row_begin))
      {
        const std::size_t written = std::size_t(to - (spill.empty() ? begin : spill.data()));
        if(spill.empty())
        {
          spill.resize(2 * written + (row_end - row_begin));
          std::copy(begin, to, spill.data());
        }
        else
          spill.resize(2 * spill.size() + (row_end - row_begin));
        to = spill.data() + written;
        to_end = spill.data() + spill.size();
      }
      for(Index k = row_begin; k < row_end; ++k)
      {
        if(k + cost_prefetch_distance < end)
          prefetch_cost_operands(cost, out_target[k + cost_prefetch_distance], 0);
        const Index h = out[k], e = out_target[k];
        const double c = candidate_cost(th, border, h, e, cost_from_o);
        if(std::isnan(c))
          continue;
        ++not_refused;
        const std::uint64_t image = Candidate_key::image(c);
        const std::uint64_t x = local_key.of_image(image, h);
        // written in any case, kept when under the limit: the test's outcome is a coin toss
        // with odds of one in six, which a branch mispredicted
        *to = Entry{x, ends_of_candidate(static_cast<Index>(o), e), local_key.low_bits_of_image(image)};
        to += (x >> shift) <= lim;
      }
    }
    count[b] = std::size_t(to - (spill.empty() ? begin : spill.data()));
    kept[b] = not_refused;
  });
  std::vector<std::size_t> offset(blocks + 1, 0);
  total = 0;
  for(std::size_t b = 0; b < blocks; ++b)
  {
    offset[b + 1] = offset[b] + count[b];
    total += kept[b];
  }
  const std::size_t size = offset[blocks];
  if(size < (std::max)(wanted, std::size_t(1)))
    return size;
  front.resize(size);
  low.resize(size);
  halfedge.resize(size);
  if(ends != nullptr)
    ends->resize(size);
  parallel_for_blocks(blocks, [&](std::size_t first, std::size_t last) {
    for(std::size_t b = first; b < last; ++b)
    {
      const Entry* const entries = spilled[b].empty() ? arena.data() + slice[b] : spilled[b].data();
      for(std::size_t j = 0, i = offset[b]; j < count[b]; ++j, ++i)
      {
        const Entry& x = entries[j];
        halfedge[i] = key.halfedge(x.key);
        front[i] = (key.cost_part(x.key) << key.halfedge_bits()) | i;   // i < size <= the halfedges: it fits
        low[i] = x.low;
        if(ends != nullptr)
          (*ends)[i] = x.ends;
      }
      Uninitialized_vector<Entry>().swap(spilled[b]);
    }
  }, 1);
  return size;
}

// The sort of sort_front() once the keys name their places (`halfedge`: the halfedge of each
// place); the sorted keys then name their halfedges again or, `ends` given, are replaced by
// the ends of their places (as candidate_ends() would replace them)
inline void sort_renamed_front(Key_array& c, const Low_bits& low, const Index_array& halfedge, const Candidate_key& key,
                               const Key_array* ends = nullptr)
{
  const std::size_t n = c.size();
  sort_candidates(c.data(), n, key, [&](Index i) { return (std::uint64_t(low[i]) << 32) | halfedge[i]; });
  parallel_for_blocks(n, [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
      c[i] = ends != nullptr ? (*ends)[key.halfedge(c[i])]
                             : (key.cost_part(c[i]) << key.halfedge_bits()) | halfedge[key.halfedge(c[i])];
  });
}

// Sorts keys whose low bits are given, one per key in the same order (sort_candidates()).
// While sorted, each key names its place in `c` instead of its halfedge, so that the runs of
// equal cost bits find their low bits and halfedges in two arrays written in order. Why: the
// runs' costs were computed again before, two quadrics and a position read at random places
// per key, which was most of the sort's time on the Loop-subdivided horse of 3.1M vertices
// (2.2 of its 15.8 s on two threads); low bits kept per halfedge instead (no renaming) were
// scattered writes over the 6 n candidates: 0.6 s more in the keys there for 1.5 s less in the
// sort, against 0.16 s more for these.
inline void sort_front(Key_array& c, const Low_bits& low, const Candidate_key& key)
{
  const std::size_t n = c.size();
  Index_array halfedge(n);
  parallel_for_blocks(n, [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
    {
      halfedge[i] = key.halfedge(c[i]);
      c[i] = (key.cost_part(c[i]) << key.halfedge_bits()) | i;   // i < n <= the halfedges: it fits
    }
  });
  sort_renamed_front(c, low, halfedge, key);
}

// The cheapest candidate collapses of one level, sorted (at least `wanted` of them, unless there
// are fewer): increasing cost, ties by halfedge number, so that the order is total and does not
// depend on threads. `total`: the number of candidates; `limit`: the leading bits of the
// largest key returned (the rest comes from sort_candidate_rest()). on_border: one flag per
// row, set here. `as_ends`: if given and true, the candidates may come back as their ends
// (candidate_ends()); it is set to false where they come back as keys.
template <typename CostOfRows>
Key_array sorted_candidates(const Triangle_halfedges& th, const CostOfRows& cost,
                            std::vector<unsigned char>& on_border, Candidate_key& key,
                            std::size_t wanted, std::size_t& total, std::uint64_t& limit,
                            const std::vector<Index>* faces = nullptr, bool* as_ends = nullptr)
{
  CGAL_precondition(th.has_ends() || faces != nullptr);   // the ends of a halfedge: listed, or from the faces
  const Index nh = static_cast<Index>(th.number_of_halfedges());
  on_border.assign(th.n, 0);
  for(Index h = static_cast<Index>(3 * th.nf); h < nh; ++h)   // the border halfedges come last
    on_border[th.source_of(h, faces)] = on_border[th.target_of(h, faces)] = 1;
  key = Candidate_key(nh);
  // Only the cheapest `wanted` are sorted (the level considers them first; of about 6 n
  // candidates it takes n), with every candidate that shares their leading cost bits (the
  // exact costs order runs of equal cost bits): a true prefix of the full order; the rest is
  // computed again and sorted if ever needed (sort_candidate_rest(): a few small levels of a
  // decomposition). Dragon: 18 % of a decomposition in the sort before the partial sort; its
  // std::nth_element then took 10 % on two threads, sequential. The front is computed under a
  // sampled limit, the other keys never stored (candidate_front()); where the sample fell
  // short or could not be taken (few candidates), every key is computed and the front is
  // selected from them (cheapest_keys()). The front is the same either way.
  limit = sampled_candidate_limit(th, cost, on_border, key, wanted);
  if(limit != ~std::uint64_t(0))
  {
    Uninitialized_vector<Front_entry> arena;                // freed last, with the front sorted (candidate_front())
    Key_array front, ends;
    Low_bits low;
    Index_array halfedge;
    const bool with_ends = as_ends != nullptr && *as_ends;
    if(candidate_front(th, cost, on_border, key, limit, wanted, front, low, halfedge, with_ends ? &ends : nullptr, total, arena)
       >= (std::max)(wanted, std::size_t(1)))
    {
      sort_renamed_front(front, low, halfedge, key, with_ends ? &ends : nullptr);
      return front;
    }
  }
  if(as_ends != nullptr)
    *as_ends = false;
  Low_bits low(nh), front_low;                              // low: written for every candidate not refused
  std::size_t refused = 0;
  Key_array candidates = candidate_keys(th, cost, on_border, key, low.data(), &refused);
  Key_array front = cheapest_keys(candidates, key, refused_candidate, wanted, total, limit, &low, &front_low,
                                  candidates.size() - refused);
  Key_array().swap(candidates);
  Low_bits().swap(low);
  sort_front(front, front_low, key);
  return front;
}

// Appends to the sorted front of sorted_candidates() the other candidates, sorted (their
// leading cost bits are all above `limit`).
template <typename CostOfRows>
void sort_candidate_rest(const Triangle_halfedges& th, const CostOfRows& cost, const std::vector<unsigned char>& on_border,
                         const Candidate_key& key, std::uint64_t limit, Key_array& candidates)
{
  Low_bits low(th.number_of_halfedges());
  Key_array rest = candidate_keys(th, cost, on_border, key, low.data());
  keys_above(rest, key, refused_candidate, limit, &low);
  sort_front(rest, low, key);
  candidates.insert(candidates.end(), rest.begin(), rest.end());
}

// The greedy independent set of half-edge collapses of one level (Section 3.1): the
// candidates of sorted_candidates() are taken in order, each accepted when the rule of
// take_greedily() admits it (a free source, a target not taken, no crossing, the link condition,
// no face flipped), and then o and its 1-ring are locked. All tests are made on M_k (why they
// hold for the collapses together: the rule's comment). `cost(o, e)` takes rows; xyz: 3
// doubles per row. The candidates live only here, so the temporary memory of a level follows
// its size. At most `budget` collapses are accepted. `locked` and `source_of_target` are
// scratch, kept by the caller so that the levels reuse their memory (a fresh array per level
// showed in the dragon's profile as page faults and its growth loop, about 1 % of the samples). `window`: 0 chooses the loop below four
// threads and parallel rounds (take_greedily_in_rounds(), windows of the level's n / 64
// candidates, at least 4096) from four on; `sequential_selection` forces the loop, any other
// value the rounds with windows of that many candidates. The accepted collapses are the same.
// `run_taking(take)` calls take(), the loop or the rounds once the candidates are sorted: a
// caller may run other work beside it (the loop is sequential); Run_in_place just calls it.
// `faces`: the face array th was built from, where the ends of a halfedge are read when th
// does not list them (Triangle_halfedges::build() without ends); may be null otherwise.
constexpr std::size_t sequential_selection = ~std::size_t(0);

struct Run_in_place
{
  template <typename Take>
  void operator()(const Take& take) const { take(); }
};

template <typename CostOfRows, typename RunTaking = Run_in_place>
void select_collapses(const Triangle_halfedges& th, const double* xyz, const CostOfRows& cost, std::size_t budget,
                      std::vector<unsigned char>& on_border, std::vector<unsigned char>& locked, Index_array& source_of_target,
                      std::vector<Collapse>& accepted, std::size_t window = 0, const RunTaking& run_taking = RunTaking(),
                      const std::vector<Index>* faces = nullptr)
{
  if(source_of_target.size() < th.n)
    source_of_target.resize(th.n);                        // the first level's size: the next levels reuse it
  // The rounds do more work than the loop (reservations, three passes): on two threads they
  // took as long as the loop (dragon, level 0: 0.12 s both), on one 40 % longer; they are used
  // from four threads on, where the loop would be the largest sequential part
  if(window == 0)
    window = available_threads() >= 4 ? (std::max)(std::size_t(4096), th.n / 64) : sequential_selection;
  // the loop reads the candidates' ends (given with the front, else candidate_ends()), the
  // rounds their halfedges
  const bool as_ends = window == sequential_selection && !th.repeated_directed_edge;
  bool given_as_ends = as_ends;
  Candidate_key key(0);
  std::size_t all = 0;
  std::uint64_t limit = 0;
  Key_array candidates = sorted_candidates(th, cost, on_border, key, th.n, all, limit, faces, &given_as_ends);
  const std::size_t sorted = candidates.size();
  accepted.clear();
  // Only the th.n cheapest candidates (of about 6 th.n) are considered, unless fewer than
  // th.n / 16 collapses are accepted among them: a level then leaves an expensive collapse to a
  // coarser level, where its cost is compared with costlier ones, instead of taking it because
  // its ends happen to be free. Measured (bench_quality, adaptive meshes at 25 / 5 / 1 %): RMS
  // error 4-11 % lower; 7 more levels on the bunny and the dragon, dragon decomposition +15 %
  // (1.29 -> 1.47-1.53 s, one process; +4 % when first measured).
  if(window == sequential_selection)
    locked.assign(th.n, 0);
  if(as_ends && !given_as_ends)
    candidate_ends(th, key, candidates, 0, faces);
  auto sort_rest = [&] {
    const std::size_t first = candidates.size();
    sort_candidate_rest(th, cost, on_border, key, limit, candidates);
    if(as_ends)
      candidate_ends(th, key, candidates, first, faces);
  };
  run_taking([&] {
    if(window == sequential_selection)
      take_greedily(th, xyz, candidates, sorted, all, sort_rest, key, budget, on_border, locked, source_of_target, accepted,
                    th.n, th.n / 16 + 1, as_ends);
    else
      take_greedily_in_rounds(th, xyz, candidates, sorted, all, sort_rest, key, budget, on_border, source_of_target, accepted,
                              th.n, th.n / 16 + 1, window, faces);
  });
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_COLLAPSE_SELECTION_H
