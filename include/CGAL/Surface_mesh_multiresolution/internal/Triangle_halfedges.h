// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_TRIANGLE_HALFEDGES_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_TRIANGLE_HALFEDGES_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>

#include <CGAL/assertions.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <type_traits>
#include <utility>
#include <stdexcept>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The counting pass of list_face_halfedges_by_source(): offsets[v + 1] = the number of
// corners of vertex v in `tri` (offsets[0] = 0), each of `ranges` ranges of vertices counted
// by a call of for_ranges()' function, which reads every corner.
template <typename ForRanges>
void count_face_halfedges_by_source(std::size_t n, const std::vector<Index>& tri, std::vector<Index>& offsets,
                                    std::size_t ranges, const ForRanges& for_ranges)
{
  const Index h0 = static_cast<Index>(tri.size());
  offsets.assign(n + 1, 0);
  for_ranges([&](Index lo, Index span) {
    Index* const count = offsets.data() + 1;               // (raw pointers: see the scatter in list_face_halfedges_by_source())
    const Index* const corners = tri.data();
    if(ranges == 1)                                        // every source in range: no test per corner
      for(Index h = 0; h < h0; ++h)
        ++count[corners[h]];
    else
      for(Index h = 0; h < h0; ++h)
        if(corners[h] - lo < span)                         // (unsigned: below lo wraps around)
          ++count[corners[h]];
  });
}

// The same count in this thread, one range: a caller may run it beside other work (its
// ranges all read every corner, so that on two threads the count took as long as on one).
inline void count_face_halfedges_by_source(std::size_t n, const std::vector<Index>& tri, std::vector<Index>& offsets)
{
  count_face_halfedges_by_source(n, tri, offsets, 1, [n](const auto& f) { f(Index(0), static_cast<Index>(n)); });
}

// The face halfedges of a triangle array (halfedge 3f+k from corner k to corner k+1 of face
// f) listed by source in CSR, by a counting sort, so in face order: the corners around every
// vertex, with the vertex after each corner in its face (out_target) and, `with_apexes`, the
// vertex before it (out_apex). A vertex's row is out[offsets[v]] .. out[offsets[v + 1] - 1].
// In parallel over ranges of source vertices: each range's task reads the whole face array
// (a stream) and counts, then writes, only the corners of its sources, in face order, so the
// lists are those of the sequential sort for any number of tasks (no atomics; with one
// histogram per task the memory would grow with the tasks times the vertices). `room`, when
// given (n entries), leaves room[v] places at the end of v's row, not written here.
// `counted`: offsets already holds the counts (count_face_halfedges_by_source()).
inline void list_face_halfedges_by_source(std::size_t n, const std::vector<Index>& tri, bool with_apexes,
                                          std::vector<Index>& offsets, Index_array& out,
                                          Index_array& out_target, Index_array& out_apex,
                                          const std::vector<Index>* room = nullptr, bool counted = false)
{
  const Index h0 = static_cast<Index>(tri.size());
  // a range per thread (at most 8: each reads all corners), one more per 2^15 corners
  const std::size_t ranges = (std::min)({std::size_t(available_threads()), std::size_t(8), std::size_t(h0 >> 15) + 1});
  auto for_ranges = [&](const auto& f) {
    parallel_for_blocks(ranges, [&](std::size_t first, std::size_t last) {
      for(std::size_t r = first; r < last; ++r)
        f(static_cast<Index>(n * r / ranges), static_cast<Index>(n * (r + 1) / ranges - n * r / ranges));
    }, 1);
  };
  if(!counted)
    count_face_halfedges_by_source(n, tri, offsets, ranges, for_ranges);
  CGAL_precondition(offsets.size() == n + 1 && offsets[0] == 0);
  for(std::size_t i = 0; i < n; ++i)
    offsets[i + 1] += offsets[i] + (room ? (*room)[i] : Index(0));
  out.resize(offsets[n]);
  out_target.resize(offsets[n]);
  out_apex.resize(with_apexes ? offsets[n] : 0);
  std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
  // face by face, its three corners from its three vertices read once, the cases (apexes or
  // not, one range or several) compiled apart: the loop over the corners, which found a
  // corner's next and previous vertices by remainders of its number and tested both cases at
  // every corner, took up to twice as long (the dragon's 2.6M corners, one thread: 0.042-0.055 s
  // against 0.029 s), and this sort was a sixth of a reconstruction
  // (Raw pointers: through the vectors, every store made the compiler load their data
  // pointers again, which a store to an Index could have changed.)
  auto scatter = [&](Index lo, Index span, auto apexes, auto one_range) {
    Index* const to_out = out.data();
    Index* const to_target = out_target.data();
    Index* const to_apex = out_apex.data();
    Index* const next_slot = fill.data();
    const Index* const corners = tri.data();
    auto put = [&](Index v, Index h, Index next, Index apex) {
      if(!decltype(one_range)::value && v - lo >= span)   // (unsigned: below lo wraps around)
        return;
      const Index k = next_slot[v]++;
      to_out[k] = h;
      to_target[k] = next;
      if(decltype(apexes)::value)
        to_apex[k] = apex;
    };
    for(Index f = 0; f < h0; f += 3)
    {
      const Index a = corners[f], b = corners[f + 1], c = corners[f + 2];
      put(a, f, b, c);
      put(b, f + 1, c, a);
      put(c, f + 2, a, b);
    }
  };
  typedef std::true_type yes;
  typedef std::false_type no;
  for_ranges([&](Index lo, Index span) {
    if(ranges == 1)
      with_apexes ? scatter(lo, span, yes(), yes()) : scatter(lo, span, no(), yes());
    else
      with_apexes ? scatter(lo, span, yes(), no()) : scatter(lo, span, no(), no());
  });
}

// What one level of half-edge collapses did to a face array (decompose(): M_k to M_{k+1}), for
// Triangle_halfedges::build_after_collapses().
struct Collapsed_faces
{
  // per face: its number after if kept, else removed_face + the corner where its collapsed
  // halfedge starts (one array: one cache miss per neighbour read)
  Index_array face_after;
  static constexpr Index removed_face = Index(1) << 31;
  static bool is_removed(Index a) { return (a & removed_face) != 0; }
  static Index collapsed_corner(Index a) { return a & ~removed_face; }
};

// Index-based halfedge structure of a triangle mesh, built from its triangle array alone
// (no walk on the mesh): halfedge 3f+k goes from corner k to corner k+1 of face f; the
// halfedges of border edges that have no face are numbered after them. The outgoing
// halfedges of every vertex are listed in CSR (in face order, so deterministic), with
// their targets: the 1-ring of each vertex. Used by the relaxation weights, the
// decomposition's selection and collapses, the quadrics and the output of a reconstruction.
// Why by hand: the weights of every level of a pyramid need twins, next and 1-rings on
// contiguous arrays; walking a FaceGraph's halfedges (or a hash of edges) is several times
// slower than this counting sort.
struct Triangle_halfedges
{
  std::size_t n = 0, nf = 0;
  Index_array source, target, twin;            // per halfedge (source and target: only when built with_ends, see build())
  // outgoing halfedges of each vertex (face halfedges, then border ones): out[k] for
  // out_offsets[v] <= k < out_offsets[v + 1], with their targets and the third vertex of their
  // face (invalid_index for a border halfedge; only when built `with_apexes`), so that a
  // vertex's 1-ring and the faces around it are read from three contiguous ranges
  std::vector<Index> out_offsets;
  Index_array out, out_target, out_apex;
  // whether a directed edge is listed twice (or a face repeats a vertex): no halfedge mesh
  // has these faces; the pairing is then first come, first served
  bool repeated_directed_edge = false;

private:
  std::vector<Index> m_sorted_first;                 // per vertex: where its sorted ring starts in m_sorted (long rings only)
  std::vector<std::pair<Index, Index> > m_sorted;    // (target, position in out) of the long rings

public:

  // the number of halfedges, face and border ones (from the twins: source and target are not
  // listed when built without ends)
  std::size_t number_of_halfedges() const
  {
    CGAL_assertion(source.empty() || source.size() == twin.size());
    return twin.size();
  }
  // whether source and target are listed (build()'s `with_ends`)
  bool has_ends() const { return source.size() == twin.size(); }
  static Index next_in_face(Index h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static Index prev_in_face(Index h) { return h % 3 == 0 ? h + 2 : h - 1; }
  bool has_face(Index h) const { return h < 3 * nf; }
  bool is_border_edge(Index h) const { return !has_face(h) || !has_face(twin[h]); }
  // the third vertex of the face of h (h must have a face)
  Index opposite_vertex(Index h) const { return target[next_in_face(h)]; }
  // the ends of halfedge h read from the face array tri and the twins alone (after build() or
  // build_twins()): a border halfedge runs against its twin
  Index source_in(const std::vector<Index>& tri, Index h) const { return has_face(h) ? tri[h] : tri[next_in_face(twin[h])]; }
  Index target_in(const std::vector<Index>& tri, Index h) const { return has_face(h) ? tri[next_in_face(h)] : tri[twin[h]]; }
  // the ends of halfedge h, listed or (built without ends) read from the face array `tri` it
  // was built from, which may then not be null
  Index source_of(Index h, const std::vector<Index>* tri) const { return has_ends() ? source[h] : source_in(*tri, h); }
  Index target_of(Index h, const std::vector<Index>* tri) const { return has_ends() ? target[h] : target_in(*tri, h); }

  // tri: 3 vertex numbers (< nv) per face. Without `with_ends`, source and target stay empty
  // (16 bytes per face less: the decomposition reads the ends of a halfedge from its face array
  // and the twins, source_in() and target_in()), unless a directed edge repeats (the greedy loop
  // then reads halfedges, not ends: take_greedily()).
  // \throws std::invalid_argument when the halfedges (up to 6 per face) cannot be numbered by Index
  void build(std::size_t nv, const std::vector<Index>& tri, bool with_apexes = false, bool with_ends = true)
  {
    // room for border halfedges beside the face halfedges, so that add_border_halfedges()
    // widens the rows in place
    const std::size_t room = halfedges_with_border_room(tri.size());
    for(Index_array* v : {&out, &out_target})
      v->reserve(room);
    if(with_apexes)
      out_apex.reserve(room);
    pair_face_halfedges(nv, tri, with_apexes);
    add_source_target_and_borders(tri, with_apexes, with_ends || repeated_directed_edge);
  }

  // The halfedges of the face array `tri` of nv rows that one level of half-edge collapses
  // made from the face array of `before` (decompose(): M_{k+1} from M_k): the same arrays as
  // build(nv, tri, with_apexes), the twins derived from those of `before` instead of matched
  // in the rings again. `before` needs its twins. The collapses follow the selection's rule
  // (take_greedily()): sources pairwise non-adjacent, targets even and distinct, no two
  // collapses crossed, the link condition on every collapse; so every face holds at most one
  // odd vertex. The twin of a halfedge of a kept face is its twin before, or, when that lies
  // in a removed face, the twin of the removed face's third edge (the two edges the collapse
  // merges). No directed edge is repeated after the collapses when none was before (so
  // build() would pair the same twins): a repeated edge would hold a renamed halfedge, o -> v
  // renamed e -> v beside a face's e -> v (or v -> o beside v -> e): v is a common neighbour
  // of o and e, so the apex of a removed face on the edge o e (the link condition), which held
  // o -> v or e -> v (v -> o or v -> e) already; two renamed halfedges give a shared target or
  // two crossed collapses. Why: matching every level's twins in the rings again was 7 % of a
  // decomposition (dragon, one thread); this pass reads the faces in order, and with the twins
  // kept to the next level glibc keeps its heap from level to level instead of trimming it and
  // faulting fresh pages (the dragon 1.00-1.05 -> 0.73-0.82 s, its page faults 198k -> 112k;
  // design notes). `before` and `c` are freed once read. Falls back to
  // build() (and returns false) when `before` repeats a directed edge or when the collapses
  // do not follow the rule (a removed face entered through its collapsed edge, or next to
  // another across its third edge); returns true otherwise.
  // \throws std::invalid_argument as build()
  bool build_after_collapses(Triangle_halfedges&& before, Collapsed_faces&& c, std::size_t nv,
                             const std::vector<Index>& tri, bool with_apexes = false, bool with_ends = true)
  {
    const std::size_t nf_before = before.nf;
    if(before.repeated_directed_edge || before.twin.size() < 3 * nf_before)
    {
      before = Triangle_halfedges();
      c = Collapsed_faces();
      build(nv, tri, with_apexes, with_ends);
      return false;
    }
    const std::size_t room = halfedges_with_border_room(tri.size());
    for(Index_array* v : {&out, &out_target})
      v->reserve(room);
    if(with_apexes)
      out_apex.reserve(room);
    n = nv;
    nf = tri.size() / 3;
    twin.reserve(room);
    twin.resize(tri.size());
    m_sorted_first = std::vector<Index>();
    m_sorted = std::vector<std::pair<Index, Index> >();
    const Index h0_before = static_cast<Index>(3 * nf_before);
    std::atomic<bool> failed(false);
    // the rows' lengths are counted beside the twins (from the face array only): the count
    // does not gain from threads (see list_face_halfedges_by_source()). Its array is allocated
    // here, in this thread (see run_beside()).
    out_offsets.reserve(n + 1);
    run_beside([&] {
      parallel_for_blocks(nf_before, [&](std::size_t first, std::size_t last) {
        // raw pointers: the writes to twin would otherwise make the compiler reload every array
        const Index* const after = c.face_after.data();
        const Index* const twin_before = before.twin.data();
        Index* const twins = twin.data();
        CGAL_assertion_code(const Index* const faces = tri.data();)
        bool bad = false;
        for(std::size_t f = first; f < last; ++f)
        {
          const Index af = after[f];
          if(Collapsed_faces::is_removed(af))
            continue;
          for(Index corner = 0; corner < 3; ++corner)
          {
            // across a removed face (o, e, x), the twin of its third edge. It is never entered
            // through its collapsed edge o e (no face holds two odd vertices), and the twin of
            // its third edge lies in a kept face or on the border: beyond e x, a face (x, e, o')
            // removed by o' -> x would cross o -> e, by o' -> e share its target, and o' = x
            // would neighbour o; beyond x o, a removed face holds o and e, the other face on o e
            // with the same apex x, which the link condition refuses
            Index t = twin_before[3 * f + corner];
            Index at = t < h0_before ? after[t / 3] : invalid_index;
            if(t < h0_before && Collapsed_faces::is_removed(at))
            {
              const Index r = t / 3, collapsed = Collapsed_faces::collapsed_corner(at), entered = t % 3;
              t = entered == collapsed ? h0_before : twin_before[3 * r + (3 - entered - collapsed)];
              at = t < h0_before ? after[t / 3] : invalid_index;
              if(entered == collapsed || (t < h0_before && Collapsed_faces::is_removed(at)))
              {
                bad = true;                                  // (the whole is built again below)
                t = h0_before;
              }
            }
            const Index g = 3 * af + corner, into = t < h0_before ? 3 * at + t % 3 : invalid_index;
            CGAL_assertion(into == invalid_index || (faces[into] == faces[next_in_face(g)] && faces[next_in_face(into)] == faces[g]));
            twins[g] = into;
          }
        }
        if(bad)
          failed.store(true, std::memory_order_relaxed);
      }, 4096);
    }, [&] { count_face_halfedges_by_source(n, tri, out_offsets); });
    // freed before the rows are listed: the memory of this build peaks no higher than build()'s
    before = Triangle_halfedges();
    c = Collapsed_faces();
    if(failed.load())
    {
      build(nv, tri, with_apexes, with_ends);
      return false;
    }
    repeated_directed_edge = false;
    // The twins come first, so the border halfedges are known before the rows are listed:
    // each row is listed with room for its own at its end (build() widens the rows after
    // the fact, a sequential move of the three row arrays that was a twentieth of a
    // decomposition on two threads for the dragon, whose holes every level keeps).
    const Index_array border_twins = face_halfedges_without_twin();
    std::vector<Index> slot;                         // per row: its border halfedges, then where the next one goes
    if(!border_twins.empty())
    {
      slot.assign(n, 0);
      for(Index h : border_twins)
        ++slot[tri[next_in_face(h)]];                // the border halfedge leaves the target of its twin
    }
    list_face_halfedges_by_source(n, tri, with_apexes, out_offsets, out, out_target, out_apex,
                                  border_twins.empty() ? nullptr : &slot, true);
    if(with_ends)
      set_ends(tri, border_twins.size());
    else
      clear_ends();
    if(!border_twins.empty())
    {
      for(std::size_t v = 0; v < n; ++v)
        slot[v] = out_offsets[v + 1] - slot[v];
      write_border_halfedges(tri, border_twins, slot, with_apexes);
    }
    return true;
  }

  // frees all but the twins (what build_after_collapses() reads of the halfedges before)
  void keep_twins_only()
  {
    for(Index_array* v : {&source, &target, &out, &out_target, &out_apex})
      Index_array().swap(*v);
    std::vector<Index>().swap(out_offsets);
  }

  // The twins alone, for a mesh's halfedges to be linked (build_triangle_mesh()): twin[h] for
  // the face halfedges, then the border halfedges numbered as build() numbers them; source,
  // target and the lists of outgoing halfedges are left empty (source_in() and target_in()
  // give the ends). The rings are listed with their apexes, so that each twin is found in
  // its own ring (the search in the neighbour's ring, a cache miss per edge, and the widened
  // rows of the border halfedges were three quarters of the build that linking an output mesh
  // made; the memory touched is about 40 % less).
  // \throws std::invalid_argument as build()
  void build_twins(std::size_t nv, const std::vector<Index>& tri)
  {
    pair_face_halfedges(nv, tri, true);
    for(Index_array* v : {&source, &target, &out, &out_target, &out_apex})
      Index_array().swap(*v);
    std::vector<Index>().swap(out_offsets);
    m_sorted_first = std::vector<Index>();
    m_sorted = std::vector<std::pair<Index, Index> >();
    const std::size_t h0 = 3 * nf;
    auto without_twin = [&](std::size_t h) { return twin[h] == invalid_index; };
    const Ordered_compaction borders(h0, without_twin);
    twin.resize(h0 + borders.size());
    borders.visit([&](std::size_t h, std::size_t rank, bool border) {
      if(border)                                     // (h's own entry: read by without_twin(h) before)
      {
        twin[h0 + rank] = static_cast<Index>(h);
        twin[h] = static_cast<Index>(h0 + rank);
      }
    });
  }

private:
  // Capacity for the h0 face halfedges and room for border halfedges after them (1/16 more):
  // those of most meshes are then appended without a reallocation that copies the arrays
  // (capacity that is never written costs address space, not memory).
  static std::size_t halfedges_with_border_room(std::size_t h0) { return h0 + h0 / 16 + 1024; }

  // The end of build(), once the face halfedges are listed and paired: the border halfedges
  // numbered, the ends of every halfedge, the border rows.
  void add_source_target_and_borders(const std::vector<Index>& tri, bool with_apexes, bool with_ends = true)
  {
    const Index_array border_twins = face_halfedges_without_twin();
    if(with_ends)
      set_ends(tri, border_twins.size());
    else
      clear_ends();
    if(!border_twins.empty())                        // closed mesh: the rows are the face halfedges
      add_border_halfedges(tri, border_twins, with_apexes);
    m_sorted_first = std::vector<Index>();
    m_sorted = std::vector<std::pair<Index, Index> >();
  }

  // the face halfedges without a twin, in increasing order: border halfedge 3 nf + i is the twin of the i-th
  Index_array face_halfedges_without_twin() const
  {
    auto without_twin = [&](std::size_t h) { return twin[h] == invalid_index; };
    const Ordered_compaction borders(3 * nf, without_twin);
    Index_array border_twins(borders.size());
    borders.visit([&](std::size_t h, std::size_t rank, bool border) {
      if(border)
        border_twins[rank] = static_cast<Index>(h);
    });
    return border_twins;
  }

  void clear_ends()
  {
    for(Index_array* v : {&source, &target})
      Index_array().swap(*v);
  }

  // source and target of the face halfedges; the arrays sized for `border_halfedges` more
  void set_ends(const std::vector<Index>& tri, std::size_t border_halfedges)
  {
    const std::size_t h0 = 3 * nf, nh = h0 + border_halfedges;
    source.resize(nh);
    target.resize(nh);
    parallel_for_blocks(nf, [&](std::size_t first, std::size_t last) {
      for(std::size_t f = first; f < last; ++f)            // face by face: no remainder per halfedge
      {
        const Index a = tri[3 * f], b = tri[3 * f + 1], c = tri[3 * f + 2];
        source[3 * f] = a;
        source[3 * f + 1] = b;
        source[3 * f + 2] = c;
        target[3 * f] = b;
        target[3 * f + 1] = c;
        target[3 * f + 2] = a;
      }
    }, 4096);
  }

  // The border halfedges (twins of `border_twins`, in order) numbered after the face
  // halfedges, each listed in its source's row at slot[source], which it advances; their ends
  // written where the arrays of ends are kept (set_ends())
  void write_border_halfedges(const std::vector<Index>& tri, const Index_array& border_twins, std::vector<Index>& slot,
                              bool with_apexes)
  {
    const Index h0 = static_cast<Index>(3 * nf);
    twin.resize(h0 + border_twins.size());
    const bool ends = !source.empty();
    Index g = h0;
    for(Index h : border_twins)
    {
      const Index from = tri[next_in_face(h)], to = tri[h];   // g runs against the face halfedge h
      if(ends)
      {
        source[g] = from;
        target[g] = to;
      }
      twin[g] = h;
      twin[h] = g;
      const Index k = slot[from]++;
      out[k] = g;
      out_target[k] = to;
      if(with_apexes)
        out_apex[k] = invalid_index;                 // no face
      ++g;
    }
  }

  // The first steps of build() and build_twins(): the outgoing face halfedges listed by
  // source, the long rings sorted, the face halfedges paired (twin, invalid_index for a border
  // edge; repeated_directed_edge set).
  void pair_face_halfedges(std::size_t nv, const std::vector<Index>& tri, bool with_apexes)
  {
    if(tri.size() / 3 >= std::size_t(invalid_index) / 6)
      throw std::invalid_argument("the mesh has too many faces (at most (2^32-1)/6 are supported)");
    n = nv;
    nf = tri.size() / 3;
    twin.reserve(halfedges_with_border_room(tri.size()));
    list_face_halfedges_by_source(n, tri, with_apexes, out_offsets, out, out_target, out_apex);
    sort_long_rings();
    repeated_directed_edge = !match_twins_by_smaller_end();
    if(repeated_directed_edge)
      match_twins_first_come(tri);
  }

  // Rings longer than long_ring are also listed sorted by target, so that finding a target
  // in them (twins, repeated edges) is a binary search: a vertex of valence D (the centre of
  // a fan-triangulated polygon, a crafted file) then costs D log D, not D^2. Shorter rings
  // are searched in place, and meshes without long rings pay one pass over the degrees.
  static constexpr Index long_ring = 32;

  void sort_long_rings()
  {
    m_sorted_first.clear();
    m_sorted.clear();
    std::size_t total = 0;
    for(std::size_t v = 0; v < n; ++v)
      total += (out_offsets[v + 1] - out_offsets[v] > long_ring) ? out_offsets[v + 1] - out_offsets[v] : 0;
    if(total == 0)
      return;
    m_sorted_first.assign(n, invalid_index);
    m_sorted.reserve(total);
    for(std::size_t v = 0; v < n; ++v)
      if(out_offsets[v + 1] - out_offsets[v] > long_ring)
      {
        m_sorted_first[v] = static_cast<Index>(m_sorted.size());
        for(Index k = out_offsets[v]; k < out_offsets[v + 1]; ++k)
          m_sorted.emplace_back(out_target[k], k);
        std::sort(m_sorted.end() - (out_offsets[v + 1] - out_offsets[v]), m_sorted.end());   // by target, then ring order
      }
  }

  // the positions k of v's ring with out_target[k] == a, in ring order, passed to f until it returns true
  template <typename F>
  void for_each_in_ring(Index v, Index a, const F& f) const
  {
    if(!m_sorted_first.empty() && m_sorted_first[v] != invalid_index)
    {
      const auto first = m_sorted.begin() + m_sorted_first[v];
      const auto last = first + (out_offsets[v + 1] - out_offsets[v]);
      for(auto it = std::lower_bound(first, last, std::make_pair(a, Index(0))); it != last && it->first == a; ++it)
        if(f(it->second)) return;
      return;
    }
    for(Index k = out_offsets[v]; k < out_offsets[v + 1]; ++k)
      if(out_target[k] == a && f(k)) return;
  }

  // whether v's ring lists a target twice
  bool ring_repeats_a_target(Index v) const
  {
    if(!m_sorted_first.empty() && m_sorted_first[v] != invalid_index)
    {
      const auto first = m_sorted.begin() + m_sorted_first[v];
      const auto last = first + (out_offsets[v + 1] - out_offsets[v]);
      return std::adjacent_find(first, last, [](const auto& x, const auto& y) { return x.first == y.first; }) != last;
    }
    for(Index k = out_offsets[v]; k < out_offsets[v + 1]; ++k)
      for(Index j = out_offsets[v]; j < k; ++j)
        if(out_target[j] == out_target[k]) return true;
    return false;
  }

  // twin of a -> b: b's outgoing halfedge towards a. Each edge {a, b} is matched once, by its
  // smaller end (vertex by vertex, in parallel: the 1-rings searched are those of the
  // neighbours of consecutive vertices, near in memory for meshes whose vertex order has some
  // locality), which writes both twins; no two blocks write the same twin. With apexes, b -> a
  // is found in a's own ring instead: it is the halfedge before a's corner in the face whose
  // apex (seen from a) is b, so each vertex writes the twins of its outgoing halfedges from
  // its ring alone, already in cache (the search in b's ring was a cache miss per edge: 9 % of
  // a decomposition); long rings still search b's. Returns false when a directed edge is
  // listed twice (or a loop): the matching is then ambiguous.
  bool match_twins_by_smaller_end()
  {
    // filled in parallel (a border halfedge's twin stays invalid_index): assign() was a
    // sequential fill, with the first-touch page faults of the array, at every level
    twin.resize(3 * nf);
    parallel_for_blocks(twin.size(), [&](std::size_t first, std::size_t last) {
      std::fill(twin.data() + first, twin.data() + last, invalid_index);
    }, 65536);
    std::atomic<bool> ambiguous(false);
    const bool apexes = !out_apex.empty();
    parallel_for_blocks(n, [&](std::size_t first, std::size_t last) {
      // raw pointers: the writes to twin would otherwise make the compiler reload every array
      const Index* const offsets = out_offsets.data();
      const Index* const targets = out_target.data();
      const Index* const apex = out_apex.data();
      const Index* const halfedges = out.data();
      Index* const twins = twin.data();
      bool repeated = false;
      for(std::size_t a = first; a < last; ++a)
      {
        const Index begin = offsets[a], end = offsets[a + 1];
        if(apexes && end - begin <= long_ring)
        {
          // A target repeats exactly when two corners find the same first corner q of apex b
          // (equal targets make the same search) or neither finds one (then compared in pairs
          // below, among the corners without a face across): the test of
          // ring_repeats_a_target() without its pass over every pair of corners
          std::uint32_t claimed = 0, unmatched = 0;
          for(Index k = begin; k != end; ++k)
          {
            const Index b = targets[k];
            repeated = repeated || b == a;
            Index q = begin;
            while(q != end && apex[q] != b)
              ++q;
            if(q == end)
              unmatched |= std::uint32_t(1) << (k - begin);
            else
            {
              const std::uint32_t bit = std::uint32_t(1) << (q - begin);
              repeated = repeated || (claimed & bit) != 0;
              claimed |= bit;
              twins[halfedges[k]] = prev_in_face(halfedges[q]);   // the halfedge b -> a of that face
            }
          }
          for(Index k = begin; unmatched != 0 && k != end; ++k)
            if((unmatched >> (k - begin)) & 1u)
              for(Index j = begin; j < k; ++j)
                if(((unmatched >> (j - begin)) & 1u) && targets[j] == targets[k])
                  repeated = true;
          continue;
        }
        repeated = repeated || ring_repeats_a_target(static_cast<Index>(a));
        for(Index k = begin; k != end; ++k)
        {
          const Index b = out_target[k];
          if(b <= a)
          {
            repeated = repeated || b == a;
            if(!apexes || b == a || out_offsets[b + 1] - out_offsets[b] > long_ring)
              continue;                              // matched from b (or a loop)
          }
          // a long ring: b -> a searched in b's ring (both twins written when b's ring is long
          // too or has no apexes; a short ring with apexes writes its own)
          for_each_in_ring(b, static_cast<Index>(a), [&](Index q) {
            twin[out[k]] = out[q];
            if(!apexes || out_offsets[b + 1] - out_offsets[b] > long_ring)
              twin[out[q]] = out[k];
            return true;
          });
        }
      }
      if(repeated)
        ambiguous.store(true, std::memory_order_relaxed);
    }, 4096);
    return !ambiguous.load();
  }

  // the pairing of an ambiguous face set: sequential, first come first served
  void match_twins_first_come(const std::vector<Index>& tri)
  {
    const Index h0 = static_cast<Index>(3 * nf);
    std::fill(twin.begin(), twin.end(), invalid_index);
    for(Index h = 0; h < h0; ++h)
    {
      if(twin[h] != invalid_index)
        continue;
      const Index a = tri[h], b = tri[next_in_face(h)];
      for_each_in_ring(b, a, [&](Index k) {
        if(out[k] == h || twin[out[k]] != invalid_index)
          return false;
        twin[h] = out[k];
        twin[out[k]] = h;
        return true;
      });
    }
  }

  // border halfedges, numbered after the face halfedges: each vertex's row gets them at its end
  // (border_twins: the face halfedges without a twin, in increasing order)
  void add_border_halfedges(const std::vector<Index>& tri, const Index_array& border_twins, bool with_apexes)
  {
    const Index h0 = static_cast<Index>(3 * nf);
    const std::size_t nh = h0 + border_twins.size();
    std::vector<Index> extra(n + 1, 0);
    for(Index h : border_twins)
      ++extra[tri[next_in_face(h)] + 1];             // target(h) needs a border halfedge towards source(h)
    std::vector<Index> face_off;
    face_off.swap(out_offsets);
    out_offsets.assign(n + 1, 0);
    for(std::size_t i = 0; i < n; ++i)
    {
      extra[i + 1] += extra[i];
      out_offsets[i + 1] = face_off[i + 1] + extra[i + 1];
    }
    // The rows widened in place: the rows between two vertices with border halfedges move
    // by the same shift (the border halfedges before them), so they move as one block, the
    // last block first (a row only moves towards the end). A fresh widened copy of each
    // array was a fifth of the page faults of a decomposition. The border places are written
    // by write_border_halfedges().
    auto widen = [&](Index_array& a) {
      a.resize(nh);                                  // within the capacity reserved by build(), if the borders fit
      std::size_t last = n;                          // rows [first, last) share the shift
      while(last > 0)
      {
        const std::size_t shift = extra[last - 1];
        std::size_t first = last - 1;
        while(first > 0 && extra[first - 1] == shift)
          --first;
        if(shift > 0)
          std::memmove(a.data() + face_off[first] + shift, a.data() + face_off[first],
                       (face_off[last] - face_off[first]) * sizeof(Index));
        last = first;
      }
    };
    widen(out);
    widen(out_target);
    if(with_apexes)
      widen(out_apex);
    std::vector<Index> fill(n);
    for(std::size_t i = 0; i < n; ++i)
      fill[i] = out_offsets[i] + (face_off[i + 1] - face_off[i]);
    write_border_halfedges(tri, border_twins, fill, with_apexes);
  }
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_TRIANGLE_HALFEDGES_H
