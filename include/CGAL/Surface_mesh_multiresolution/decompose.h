// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSE_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSE_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/channels.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Halfedge_collapse_cost_adapter.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Plane_quadrics.h>
#include <CGAL/Surface_mesh_multiresolution/internal/relaxation_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Decomposition_visitor_base.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The details of one channel on one level. Odd rows are predicted from a state where each
// odd vertex holds the value of the vertex it collapses into (known on M_{k+1}), even rows
// from the original values (Eq. 6 and 7 of the paper; with the curvature and uniform schemes
// an odd row only involves even vertices, so this is exactly Eq. 5). Where fl(R f + d)
// differs from f by rounding, a correction makes reconstruction exact.
inline void compute_details(const Sparse_weights& w, const Pyramid_level& level, const std::vector<Index>& target_rows,
                            const std::vector<double>& f, std::size_t dim,
                            std::vector<double>& details, std::vector<std::pair<Index, double> >& corrections)
{
  const std::size_t n = level.vertices.size();
  std::vector<double> state(f), prediction(n * dim);
  for(std::size_t q = 0; q < level.odd_rows.size(); ++q)
    copy_values(f.data() + target_rows[q] * dim, dim, state.data() + level.odd_rows[q] * dim);
  w.apply_row_list(state.data(), prediction.data(), dim, level.odd_rows.data(), level.odd_rows.size());
  w.apply_row_list(f.data(), prediction.data(), dim, level.even_rows.data(), level.even_rows.size());
  details.resize(n * dim);
  corrections.clear();
  for(std::size_t k = 0; k < n * dim; ++k)
  {
    details[k] = f[k] - prediction[k];
    const double t = prediction[k] + details[k];
    if(t != f[k])
      corrections.emplace_back(static_cast<Index>(k), f[k] - t);
  }
}

// The details and corrections of one channel on one level from its values on all input
// vertices (global numbers): the analysis of compute_details() for a pyramid whose
// connectivity and weights are already known (re-analysis after a change of the values).
// target_rows: collapse_target_rows() of the level (callers analysing a level repeatedly
// compute them once).
inline void analyse_level_values(const Pyramid_level& level, const std::vector<Index>& target_rows, std::size_t dim,
                                 const std::vector<double>& v, std::vector<double>& details,
                                 std::vector<std::pair<Index, double> >& corrections)
{
  const std::size_t n = level.vertices.size();
  std::vector<double> f(n * dim);
  for(std::size_t r = 0; r < n; ++r)
    copy_values(v.data() + std::size_t(level.vertices[r]) * dim, dim, f.data() + r * dim);
  compute_details(level.weights, level, target_rows, f, dim, details, corrections);
}

inline void analyse_level_values(const Pyramid_level& level, std::size_t dim, const std::vector<double>& v,
                                 std::vector<double>& details, std::vector<std::pair<Index, double> >& corrections)
{
  std::vector<Index> target_rows;
  collapse_target_rows(level, target_rows);
  analyse_level_values(level, target_rows, dim, v, details, corrections);
}

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
  std::uint64_t operator()(double cost, Index h) const
  {
    cost += 0.;                                             // -0 -> +0: equal costs, equal keys
    std::uint64_t b;
    std::memcpy(&b, &cost, sizeof b);
    b = (b >> 63) ? ~b : (b | (std::uint64_t(1) << 63));
    return ((b >> (64 - m_cost_bits)) << m_halfedge_bits) | h;
  }
  Index halfedge(std::uint64_t key) const { return static_cast<Index>(key & ((std::uint64_t(1) << m_halfedge_bits) - 1)); }
  std::uint64_t cost_part(std::uint64_t key) const { return key >> m_halfedge_bits; }
  int halfedge_bits() const { return m_halfedge_bits; }
  int cost_bits() const { return m_cost_bits; }

private:
  int m_halfedge_bits = 0, m_cost_bits = 40;
};

// Sorts candidate keys (any input order) by increasing cost, equal costs in increasing
// halfedge; cost(h) gives the cost of halfedge h again (the same double: it is a
// deterministic function). Why by hand: a comparison sort of the 6n candidates was the largest
// part of the decomposition (16 % of the dragon's), and candidates holding their costs took 16
// bytes each. This is a stable LSD radix sort on the cost bits of the keys (passes of 10 bits,
// a pass skipped when all candidates share its digit), then a comparison sort by the exact
// costs and halfedges inside each run of equal cost bits (rare), which makes the order total
// whatever the input order. Deterministic: the same order for any number of threads.
template <typename CostOfHalfedge>
void sort_candidates(std::vector<std::uint64_t>& c, const Candidate_key& key, const CostOfHalfedge& cost)
{
  const std::size_t n = c.size();
  constexpr int digit_bits = 10;
  constexpr std::size_t buckets = std::size_t(1) << digit_bits;
  constexpr std::uint64_t mask = buckets - 1;
  const int digits = (key.cost_bits() + digit_bits - 1) / digit_bits;
  // each pass is a stable counting sort, split into fixed blocks of candidates: a block counts
  // its digits, then writes its candidates after those of the smaller digits and of the same
  // digit in the blocks before it. A stable sort has one result, whatever the blocks and threads.
  constexpr std::size_t block = std::size_t(1) << 16;
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<std::size_t> count(blocks * buckets);
  std::vector<std::uint64_t> scratch(n);
  std::uint64_t* from = c.data();
  std::uint64_t* to = scratch.data();
  for(int d = 0; d < digits; ++d)
  {
    const int shift = key.halfedge_bits() + d * digit_bits;
    parallel_for_blocks(blocks, [&](std::size_t first, std::size_t last) {
      for(std::size_t b = first; b < last; ++b)
      {
        std::size_t* hist = count.data() + b * buckets;
        std::fill(hist, hist + buckets, std::size_t(0));
        for(std::size_t i = b * block; i < (std::min)(n, (b + 1) * block); ++i)
          ++hist[(from[i] >> shift) & mask];
      }
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
    parallel_for_blocks(blocks, [&](std::size_t first, std::size_t last) {
      for(std::size_t b = first; b < last; ++b)
      {
        std::size_t* pos = count.data() + b * buckets;
        for(std::size_t i = b * block; i < (std::min)(n, (b + 1) * block); ++i)
          to[pos[(from[i] >> shift) & mask]++] = from[i];
      }
    }, 1);
    std::swap(from, to);
  }
  if(from != c.data())
    std::copy(from, from + n, c.data());
  scratch = std::vector<std::uint64_t>();
  std::vector<std::pair<double, Index> > run;
  for(std::size_t i = 0; i < n;)
  {
    std::size_t j = i + 1;
    while(j < n && key.cost_part(c[j]) == key.cost_part(c[i]))
      ++j;
    if(j - i > 1)
    {
      run.clear();
      for(std::size_t q = i; q < j; ++q)
      {
        const Index h = key.halfedge(c[q]);
        run.emplace_back(cost(h), h);
      }
      std::sort(run.begin(), run.end());                  // (cost, h): equal costs keep increasing h
      for(std::size_t q = i; q < j; ++q)
        c[q] = (key.cost_part(c[q]) << key.halfedge_bits()) | run[q - i].second;
    }
    i = j;
  }
}

// The greedy independent set of half-edge collapses of one level (Section 3.1): every
// halfedge o -> e of M_k (connectivity th, rows) is a candidate, except those that would move
// a border vertex off the border; candidates are taken in increasing cost (ties: halfedge
// number, so the order is total and the result does not depend on threads); a candidate is
// accepted when both ends are free, the link condition holds and no face flips, and then o
// and its 1-ring are locked. Since accepted collapses have disjoint closed 1-rings around o
// and lock e, all tests can be made on M_k: no collapse changes the 1-ring of another.
// `cost(o, e)` takes rows; xyz: 3 doubles per row. The candidates live only here, so the
// temporary memory of a level follows its size.
template <typename CostOfRows>
void select_collapses(const Triangle_halfedges& th, const double* xyz, const CostOfRows& cost, std::size_t budget,
                      std::vector<unsigned char>& on_border, std::vector<unsigned char>& locked, std::vector<Collapse>& accepted)
{
  const Index nh = static_cast<Index>(th.source.size());
  on_border.assign(th.n, 0);
  for(Index h = static_cast<Index>(3 * th.nf); h < nh; ++h)   // the border halfedges come last
    on_border[th.source[h]] = on_border[th.target[h]] = 1;
  // the cost of a candidate halfedge, NaN for a refused collapse
  auto cost_of_edge = [&](Index h, Index o, Index e) {
    if(on_border[o] && !th.is_border_edge(h))               // border vertices move along the border only
      return std::numeric_limits<double>::quiet_NaN();
    const Optional<double> oc = cost(o, e);
    return oc ? *oc : std::numeric_limits<double>::quiet_NaN();
  };
  auto cost_of = [&](Index h) { return cost_of_edge(h, th.source[h], th.target[h]); };
  // keys in parallel (TBB), vertex by vertex (the quadric and position of o are read once
  // for its 1-ring, those of its neighbours are near in memory), each into its own slot;
  // refused collapses dropped
  const Candidate_key key(nh);
  constexpr std::uint64_t refused = ~std::uint64_t(0);     // no key: its cost bits would be a NaN's
  std::vector<std::uint64_t> candidates(nh);
  parallel_for_blocks(th.n, [&](std::size_t first, std::size_t last) {
    for(std::size_t o = first; o < last; ++o)
      for(Index k = th.out_offsets[o]; k < th.out_offsets[o + 1]; ++k)
      {
        const Index h = th.out[k];
        const double c = cost_of_edge(h, static_cast<Index>(o), th.out_target[k]);
        candidates[k] = std::isnan(c) ? refused : key(c, h);
      }
  }, 1024);
  candidates.erase(std::remove(candidates.begin(), candidates.end(), refused), candidates.end());
  sort_candidates(candidates, key, cost_of);
  locked.assign(th.n, 0);
  accepted.clear();
  // The candidates come in cost order, that is at random places of the level's arrays: on a
  // mesh larger than the cache each test waits for a dozen misses. Why by hand: the loop keeps
  // a window of the next candidates whose ends were free when first seen and prefetches, in
  // steps, what their tests read (ring offsets and twin, then the rings, then o's neighbours'
  // positions), so that these misses overlap with the decisions before them. The decisions are
  // those of the plain loop: only cache hints are added, every candidate is checked again when
  // its turn comes.
  struct Pending { Index h, o, e; };
  constexpr std::size_t window = 16, ring_step = window / 2, position_step = 3, gather_ahead = 32;
  Pending pending[window];
  std::size_t head = 0, count = 0, scan = 0;
  const std::size_t nc = candidates.size();
  auto prefetch_ring = [&](Index v) {
    prefetch(th.out.data() + th.out_offsets[v]);
    prefetch(th.out_target.data() + th.out_offsets[v]);
    prefetch(th.out_apex.data() + th.out_offsets[v]);
  };
  while(accepted.size() < budget)
  {
    // refill the window with candidates whose ends are free now
    while(count < window && scan < nc)
    {
      if(scan + gather_ahead < nc)
      {
        const Index later = key.halfedge(candidates[scan + gather_ahead]);
        prefetch(th.source.data() + later);
        prefetch(th.target.data() + later);
      }
      const Index h = key.halfedge(candidates[scan++]), o = th.source[h], e = th.target[h];
      if(locked[o] || locked[e])
        continue;
      pending[(head + count++) % window] = Pending{h, o, e};
      prefetch(th.out_offsets.data() + o);
      prefetch(th.out_offsets.data() + e);
      prefetch(th.twin.data() + h);
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
      const Pending& p = pending[(head + position_step) % window];
      prefetch(xyz + 3 * std::size_t(p.o));
      for(Index k = th.out_offsets[p.o]; k < th.out_offsets[p.o + 1]; ++k)
        prefetch(xyz + 3 * std::size_t(th.out_target[k]));
    }
    const Pending c = pending[head];
    head = (head + 1) % window;
    --count;
    if(locked[c.o] || locked[c.e])
      continue;
    if(!satisfies_link_condition(th, c.h, c.o, c.e, on_border) || does_collapse_flip_a_face(th, c.o, c.e, xyz))
      continue;
    locked[c.o] = 1;
    for(Index k = th.out_offsets[c.o]; k < th.out_offsets[c.o + 1]; ++k)
      locked[th.out_target[k]] = 1;
    accepted.push_back(Collapse{c.o, c.e});
  }
}

// The collapse model: the plane quadrics on index arrays for CGAL's Garland-Heckbert plane
// policies (the default), any other SMS policy through a working halfedge mesh.
template <typename GetCost>
struct Is_plane_quadric_policy : std::false_type {};
template <typename TriangleMesh, typename GeomTraits>
struct Is_plane_quadric_policy<CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<TriangleMesh, GeomTraits> >
  : std::true_type {};

struct Plane_quadric_collapse_cost : Plane_quadrics
{
  template <typename TriangleMesh, typename VertexPointMap, typename VertexIndexMap, typename GeomTraits, typename UserCost>
  Plane_quadric_collapse_cost(const TriangleMesh&, VertexPointMap, VertexIndexMap, const Indexed_mesh<TriangleMesh>&,
                              const GeomTraits&, const UserCost&) {}

  void begin_level(const std::vector<Index>& rows_to_vertices, const std::vector<double>& xyz)
  {
    m_rows = &rows_to_vertices;
    Plane_quadrics::begin_level(xyz);
  }
  // the quadrics of the vertices still alive, by row of the next level
  void end_level(const std::vector<unsigned char>& alive)
  {
    const std::vector<Index>& rows = *m_rows;
    retain(rows.size(), [&](std::size_t r) { return alive[rows[r]] != 0; });
  }

private:
  const std::vector<Index>* m_rows = nullptr;
};

} // namespace internal

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * decomposes `tm` into a Burt-Adelson mesh pyramid (Roy et al., Section 3).
 *
 * Level \f$ k \f$ goes from \f$ M_k \f$ (\f$ M_0 \f$ = `tm`) to \f$ M_{k+1} \f$: a greedy independent
 * set of half-edge collapses \f$ o \to e \f$ is chosen in increasing Garland-Heckbert cost
 * \f$ (Q_o + Q_e)(p_e) \f$ (any SMS cost policy through `get_cost`; quadrics accumulate over the
 * levels); a collapse is accepted when both ends are free, the link condition holds and no
 * face flips, and the closed 1-ring of \f$ o \f$ is then locked. Border vertices only collapse
 * along border edges. The relaxation weights \f$ \lambda^k \f$ are computed on \f$ M_k \f$, the
 * details of every vertex and every channel are stored, then the odd vertices are collapsed
 * (the kept vertex keeps its position, so every \f$ M_k \f$ is a subset of the input's vertices).
 * Levels stop at `number_of_levels`, when `minimum_number_of_vertices` is reached, or when
 * a level would remove nothing.
 *
 * \tparam TriangleMesh a model of `MutableFaceGraph` and `HalfedgeListGraph`, default constructible
 * \tparam NamedParameters a sequence of \ref smr_namedparameters "Named Parameters"
 * \param tm the input triangle mesh (not modified)
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{relaxation_scheme}
 *     \cgalParamDescription{the relaxation operator of the subdivision step}
 *     \cgalParamType{`Relaxation_scheme`}
 *     \cgalParamDefault{`Relaxation_scheme::CURVATURE`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_attribute_maps}
 *     \cgalParamDescription{the attribute channels decomposed with the geometry (a tuple of vertex property maps; see `relax()`)}
 *     \cgalParamDefault{no attribute channel}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{minimum_number_of_vertices}
 *     \cgalParamDescription{no level goes below this number of vertices}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{`4`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{number_of_levels}
 *     \cgalParamDescription{the maximal number of levels}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{unlimited}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{get_cost}
 *     \cgalParamDescription{the cost of a half-edge collapse: any model of the SMS concept `GetCost`, evaluated with the target's position as placement}
 *     \cgalParamType{a model of `GetCost`}
 *     \cgalParamDefault{`CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<TriangleMesh\, GeomTraits>`}
 *     \cgalParamExtra{the default plane policies are evaluated on index arrays (the same quadrics, no halfedge mesh); any other policy reads SMS edge profiles on a working copy of the mesh, and one with per-vertex state (the rest of the Garland-Heckbert family) is re-created there with its default parameters}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_point_map}
 *     \cgalParamDescription{a property map associating points to the vertices of `tm`}
 *     \cgalParamDefault{`boost::get(CGAL::vertex_point\, tm)`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{geom_traits}
 *     \cgalParamDescription{an instance of a geometric traits class}
 *     \cgalParamType{a class model of `Kernel`}
 *     \cgalParamDefault{a `CGAL::Kernel_traits` compatible with the point type}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{visitor}
 *     \cgalParamDescription{reports progress per level}
 *     \cgalParamType{a class with the functions of `Decomposition_visitor_base`}
 *     \cgalParamDefault{`Decomposition_visitor_base()`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 *
 * \throws std::invalid_argument if a face is not a triangle, or a coordinate or attribute value is not finite
 * \returns the pyramid; `reconstruct()` with unmodified details gives back `tm` exactly
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
Pyramid<TriangleMesh> decompose(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef typename GetGeomTraits<TriangleMesh, NamedParameters>::type     Geom_traits;
  typedef typename GetVertexPointMap<TriangleMesh, NamedParameters>::const_type Vertex_point_map;
  typedef CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<TriangleMesh, Geom_traits> Default_cost;
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::get_cost_policy_t, NamedParameters,
                                                             Default_cost>::type Get_cost_param;
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                             Decomposition_visitor_base>::type Visitor;
  typedef internal::Index Index;

  const Geom_traits gt = choose_parameter<Geom_traits>(get_parameter(np, CGAL::internal_np::geom_traits));
  const Vertex_point_map vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                                get_const_property_map(CGAL::vertex_point, tm));
  const Relaxation_scheme scheme = choose_parameter(get_parameter(np, internal_np::relaxation_scheme), Relaxation_scheme::CURVATURE);
  const std::size_t min_vertices = choose_parameter(get_parameter(np, internal_np::minimum_number_of_vertices), std::size_t(4));
  const std::size_t max_levels = choose_parameter(get_parameter(np, internal_np::number_of_levels),
                                                  (std::numeric_limits<std::size_t>::max)());
  Visitor visitor = choose_parameter<Visitor>(get_parameter(np, CGAL::internal_np::visitor));
  const auto maps = internal::as_tuple(choose_parameter(get_parameter(np, internal_np::vertex_attribute_maps), std::tuple<>()));
  typedef std::decay_t<decltype(maps)> Maps;

  Pyramid<TriangleMesh> pyr;
  pyr.set_relaxation_scheme(scheme);

  // validated index view of the input, and the values of every channel (they never change:
  // each M_k keeps a subset of the input's vertices with their values)
  internal::Indexed_mesh<TriangleMesh> im;
  internal::build_indexed_mesh(tm, CGAL::get_initialized_vertex_index_map(tm, np), im);
  const std::size_t n0 = im.number_of_vertices();
  pyr.number_of_input_vertices() = n0;
  std::vector<std::vector<double> > values(1 + std::tuple_size<Maps>::value);
  pyr.dimensions().assign(1, 3);
  internal::read_coordinates(im.vertices, vpm, gt, values[0]);
  internal::for_each_channel(maps, [&](const auto& map, auto c) {
    constexpr std::size_t dim = internal::Channel_traits<std::decay_t<decltype(map)> >::dimension;
    values[decltype(c)::value + 1].resize(n0 * dim);
    internal::read_channel(map, im.vertices, decltype(c)::value + 1, values[decltype(c)::value + 1].data(), dim, 0);
    pyr.dimensions().push_back(dim);
  });
  const std::size_t nc = values.size();

  // the collapse costs: plane quadrics on index arrays for the default policy, a working
  // halfedge mesh for any other SMS policy
  typedef std::conditional_t<internal::Is_plane_quadric_policy<Get_cost_param>::value,
                             internal::Plane_quadric_collapse_cost,
                             internal::Sms_collapse_cost<TriangleMesh, Geom_traits, Get_cost_param> > Cost_model;
  Cost_model cost_model(tm, vpm, CGAL::get_initialized_vertex_index_map(tm, np), im, gt,
                        get_parameter(np, CGAL::internal_np::get_cost_policy));
  // the face array of the current level, in input vertex numbers
  std::vector<Index> F;
  F.swap(im.triangles);
  im = internal::Indexed_mesh<TriangleMesh>();   // not needed any more

  std::vector<unsigned char> alive(n0, 1);
  std::vector<Index> row_of(n0, internal::invalid_index);
  std::size_t live = n0;
  std::vector<Index> rows_to_vertices;
  std::vector<unsigned char> on_border, locked;
  std::vector<internal::Collapse> accepted;
  std::vector<std::pair<Index, std::array<Index, 3> > > removed;

  while(pyr.levels().size() < max_levels && live > min_vertices)
  {
    const std::size_t k = pyr.levels().size();
    visitor.on_level_started(k, live);

    // ---- M_k on index arrays: rows (its vertices in increasing input number), faces in rows, positions
    if(k == 0)
      for(Index g = 0; g < n0; ++g)
        rows_to_vertices.push_back(g);
    else                                          // M_k's vertices: M_{k-1}'s that are still alive (in order)
      rows_to_vertices.erase(std::remove_if(rows_to_vertices.begin(), rows_to_vertices.end(), [&](Index g) { return !alive[g]; }),
                             rows_to_vertices.end());
    const std::size_t nk = rows_to_vertices.size();
    for(std::size_t r = 0; r < nk; ++r)
      row_of[rows_to_vertices[r]] = static_cast<Index>(r);
    // the temporary arrays of a level live in its iteration: their memory follows the level's size
    std::vector<Index> tri_rows(F.size());
    internal::parallel_for_blocks(F.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
        tri_rows[i] = row_of[F[i]];
    });
    std::vector<double> xyz(3 * nk), f;
    for(std::size_t r = 0; r < nk; ++r)
      internal::copy_values(values[0].data() + 3 * std::size_t(rows_to_vertices[r]), 3, xyz.data() + 3 * r);
    internal::Relaxation_weight_builder builder;
    builder.set_connectivity(nk, tri_rows, true);   // with apexes: the selection's tests read them
    const internal::Triangle_halfedges& th = builder.connectivity();
    if(k == 0)
      cost_model.initialize(th, values[0]);   // on M_0, rows are the input's vertex numbers
    cost_model.begin_level(rows_to_vertices, xyz);

    // ---- select the odd vertices (greedy independent set of half-edge collapses)
    internal::select_collapses(th, xyz.data(),
                               [&](Index o, Index e) { return cost_model.cost(o, e); },
                               live - min_vertices, on_border, locked, accepted);
    if(accepted.empty())
      break;

    // ---- the level's vertices, weights and details, on M_k
    pyr.levels().emplace_back();
    internal::Pyramid_level& level = pyr.levels().back();
    level.vertices = rows_to_vertices;
    std::sort(accepted.begin(), accepted.end(), [](const internal::Collapse& a, const internal::Collapse& b) { return a.o < b.o; });
    std::vector<Index> target_rows;
    target_rows.reserve(accepted.size());
    level.odd_rows.reserve(accepted.size());
    level.collapse_targets.reserve(accepted.size());
    for(const internal::Collapse& c : accepted)
    {
      level.odd_rows.push_back(c.o);
      level.collapse_targets.push_back(rows_to_vertices[c.e]);
      target_rows.push_back(c.e);
    }
    level.even_rows.reserve(nk - accepted.size());
    {
      std::size_t q = 0;
      for(Index r = 0; r < nk; ++r)
      {
        if(q < level.odd_rows.size() && level.odd_rows[q] == r) { ++q; continue; }
        level.even_rows.push_back(r);
      }
    }
    level.details.resize(nc);
    level.corrections.resize(nc);
    for(std::size_t c = 0; c < nc; ++c)
    {
      const std::size_t dim = pyr.dimensions()[c];
      if(c == 0)
      {
        std::vector<Relaxation_row_rule> rules;
        builder.build(scheme, xyz.data(), nullptr, level.weights, rules);
        internal::compute_details(level.weights, level, target_rows, xyz, dim, level.details[c], level.corrections[c]);
        continue;
      }
      f.resize(nk * dim);
      for(std::size_t r = 0; r < nk; ++r)
        internal::copy_values(values[c].data() + std::size_t(rows_to_vertices[r]) * dim, dim, f.data() + r * dim);
      internal::compute_details(level.weights, level, target_rows, f, dim, level.details[c], level.corrections[c]);
    }

    // ---- collapse on the face array, recording how to undo it. The faces of two accepted
    // collapses are disjoint (no face holds two odd vertices), so they are rewritten in place,
    // in parallel: each collapse counts its removed and renamed faces, then writes its records
    // at its place in the order of `accepted` (the records of a sequential loop).
    const std::size_t na = accepted.size();
    std::vector<Index> first_renamed(na + 1, 0), first_removed(na + 1, 0);
    auto holds_target = [&](Index q, Index e_row) { return th.out_target[q] == e_row || th.out_apex[q] == e_row; };
    internal::parallel_for_blocks(na, [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
      {
        const internal::Collapse& c = accepted[i];
        for(Index q = th.out_offsets[c.o]; q < th.out_offsets[c.o + 1]; ++q)
          if(th.out_apex[q] != internal::invalid_index)    // a face (o, a, b)
            ++(holds_target(q, c.e) ? first_removed : first_renamed)[i + 1];
      }
    }, 1024);
    std::partial_sum(first_renamed.begin(), first_renamed.end(), first_renamed.begin());
    std::partial_sum(first_removed.begin(), first_removed.end(), first_removed.begin());
    removed.resize(first_removed[na]);
    level.renamed_corners.resize(first_renamed[na]);
    level.renamed_vertices.resize(first_renamed[na]);
    internal::parallel_for_blocks(na, [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
      {
        const internal::Collapse& c = accepted[i];
        const Index o = rows_to_vertices[c.o], e = rows_to_vertices[c.e];
        Index renamed = first_renamed[i], gone = first_removed[i];
        for(Index q = th.out_offsets[c.o]; q < th.out_offsets[c.o + 1]; ++q)
        {
          if(th.out_apex[q] == internal::invalid_index)   // no face (the same test as the count)
            continue;
          const Index g = th.out[q];                      // o -> a in face g / 3, o at corner g % 3
          const Index p = g / 3;
          Index* t = F.data() + 3 * std::size_t(p);
          if(holds_target(q, c.e))
            removed[gone++] = std::make_pair(p, std::array<Index, 3>{{t[0], t[1], t[2]}});
          else
          {
            level.renamed_corners[renamed] = g;
            level.renamed_vertices[renamed++] = o;
            t[g % 3] = e;
          }
        }
      }
    }, 1024);
    for(const internal::Collapse& c : accepted)
    {
      cost_model.collapse(c.o, c.e);
      alive[rows_to_vertices[c.o]] = 0;
      --live;
    }
    cost_model.end_level(alive);
    // the face array of M_{k+1}: the removed faces taken out
    std::sort(removed.begin(), removed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::size_t write = 0, next_removed = 0;
    const std::size_t number_of_faces = F.size() / 3;
    for(std::size_t p = 0; p < number_of_faces; ++p)
    {
      if(next_removed < removed.size() && removed[next_removed].first == p) { ++next_removed; continue; }
      if(write != p)
        internal::copy_values(F.data() + 3 * p, 3, F.data() + 3 * write);
      ++write;
    }
    F.resize(3 * write);
    F.shrink_to_fit();
    level.removed_face_positions.reserve(removed.size());
    level.removed_faces.reserve(3 * removed.size());
    for(const auto& r : removed)
    {
      level.removed_face_positions.push_back(r.first);
      level.removed_faces.insert(level.removed_faces.end(), r.second.begin(), r.second.end());
    }
    visitor.on_level_finished(k, accepted.size());
  }

  // ---- the coarsest mesh
  for(Index g = 0; g < n0; ++g)
    if(alive[g])
      pyr.coarse_vertices().push_back(g);
  pyr.coarse_faces() = F;
  pyr.coarse_values().resize(nc);
  for(std::size_t c = 0; c < nc; ++c)
  {
    const std::size_t dim = pyr.dimensions()[c];
    for(Index g : pyr.coarse_vertices())
      pyr.coarse_values()[c].insert(pyr.coarse_values()[c].end(), values[c].begin() + std::size_t(g) * dim,
                                    values[c].begin() + (std::size_t(g) + 1) * dim);
  }
  visitor.on_finished(pyr.levels().size());
  return pyr;
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSE_H
