// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_RELAXATION_WEIGHTS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_RELAXATION_WEIGHTS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Triangle_halfedges.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Sparse_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_row_rule.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_scheme.h>

#include <CGAL/assertions.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {

namespace internal {

// Second-order difference of the hinge of the edge (p1, p2) with the opposite vertices p3
// (triangle p1 p2 p3) and p4 (triangle p2 p1 p4), Guskov et al. 1999: unfolded isometrically
// into the plane, the jump of the normal derivative of the piecewise-linear interpolant
// across the edge, times the edge length L, is D_e = c1 f1 + c2 f2 + c3 f3 + c4 f4 with
//   c3 = cot(a1) + cot(b1) = L / h3,   c4 = cot(a2) + cot(b2) = L / h4,
//   c1 = -(cot(b1) + cot(b2)),          c2 = -(cot(a1) + cot(a2)),
// a1, b1 the angles at p1, p2 in the first triangle, a2, b2 in the second, h3, h4 the heights
// of p3, p4 over the edge. The coefficients are dimensionless (invariant under rigid motions
// and scaling), sum to 0 and annihilate every linear function on a planar hinge.
// Returns false (and leaves coef unspecified) when L = 0 or a height is below
// min_relative_height * L: such a hinge is left out of the SOD energy.
inline bool second_order_difference_coefficients(const double* p1, const double* p2, const double* p3, const double* p4,
                                                 double min_relative_height, double coef[4])
{
  double e[3], u[3], v[3];
  for(int c = 0; c < 3; ++c) { e[c] = p2[c] - p1[c]; u[c] = p3[c] - p1[c]; v[c] = p4[c] - p1[c]; }
  const double l2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  auto cross_norm = [](const double* x, const double* y) {
    double c[3];
    cross(x, y, c);
    return std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  };
  const double A3 = cross_norm(e, u), A4 = cross_norm(e, v);   // L h3, L h4
  if(!(l2 > 0.) || !(A3 >= min_relative_height * l2) || !(A4 >= min_relative_height * l2))
    return false;
  const double eu = e[0] * u[0] + e[1] * u[1] + e[2] * u[2];
  const double ev = e[0] * v[0] + e[1] * v[1] + e[2] * v[2];
  const double cot_a1 = eu / A3, cot_b1 = (l2 - eu) / A3;
  const double cot_a2 = ev / A4, cot_b2 = (l2 - ev) / A4;
  coef[0] = -(cot_b1 + cot_b2);
  coef[1] = -(cot_a1 + cot_a2);
  coef[2] = cot_a1 + cot_b1;
  coef[3] = cot_a2 + cot_b2;
  return true;
}

template <typename Point> class Surface_mesh_relaxation_rows;

// Computes the weights of one relaxation operator on an indexed triangle mesh.
// The topology (and, for SOD, the hinge structure) is kept, so that weights for new
// positions on the same connectivity cost only the numeric passes.
class Relaxation_weight_builder
{
  // computes the same rows on a Surface_mesh's halfedges, with the cotangents, normalisation
  // and border weights below
  template <typename Point> friend class Surface_mesh_relaxation_rows;

public:
  // cotangents are clamped to those of angles in [0.1, 179.9] degrees
  static constexpr double max_cotangent = 572.9572133543033;
  // a curvature row is used as is when its negative mass is at most half its positive mass
  static constexpr double max_negative_ratio = 0.5;
  // a hinge whose triangles are lower than this fraction of the hinge edge is left out of the SOD energy
  static constexpr double min_relative_hinge_height = 1e-3;
  // an SOD row is used when the sum of the absolute values of its weights is at most this
  static constexpr double max_sod_absolute_sum = 4.;

  // With apexes (the decomposition's selection reads them) the halfedges are built at once;
  // otherwise only when a scheme needs them (the hinges of SOD) or connectivity() is asked:
  // the curvature and uniform weights read the corners around each vertex only.
  // (with_ends: Triangle_halfedges::build(); SOD's hinges read the ends)
  void set_connectivity(std::size_t n, const std::vector<Index>& triangles, bool with_apexes = false, bool with_ends = true)
  {
    m_triangles = &triangles;
    m_n = n;
    m_has_halfedges = with_apexes;
    m_has_corners = false;
    m_paired = false;
    m_twin_pairs = false;
    if(with_apexes)
      m_mesh.build(n, triangles, true, with_ends);
  }

  // set_connectivity(n, triangles, true, with_ends) for the face array that one level of
  // collapses made from that of `before` (Triangle_halfedges::build_after_collapses(): the
  // same halfedges; `before` and `collapses` are freed)
  void set_connectivity_after_collapses(std::size_t n, const std::vector<Index>& triangles, Triangle_halfedges&& before,
                                        Collapsed_faces&& collapses, bool with_ends = true)
  {
    m_triangles = &triangles;
    m_n = n;
    m_has_halfedges = true;
    m_has_corners = false;
    m_paired = false;
    m_twin_pairs = false;
    m_mesh.build_after_collapses(std::move(before), std::move(collapses), n, triangles, true, with_ends);
  }

  // the halfedges, moved out (the builder has none afterwards)
  Triangle_halfedges take_connectivity()
  {
    m_has_halfedges = false;
    m_has_corners = false;
    m_paired = false;
    m_twin_pairs = false;
    Triangle_halfedges th = std::move(m_mesh);
    m_mesh = Triangle_halfedges();
    return th;
  }

  // the halfedges of the last connectivity set
  const Triangle_halfedges& connectivity()
  {
    halfedges();
    return m_mesh;
  }

  // The corners paired through the halfedges' twins: the pairing match_ring() finds on a
  // halfedge mesh (the decomposition's levels), without its search, read from the twins as the
  // rows need it (pair_corners()). The next build() on this connectivity uses it. Frees the
  // halfedges but the lists of outgoing halfedges, their targets (the rows read them) and the
  // twins (kept while the pairing is used: see keep_outgoing_lists_only()).
  void pair_corners_from_halfedges()
  {
    halfedges();
    for(Index_array* v : {&m_mesh.source, &m_mesh.target, &m_mesh.out_apex})
      Index_array().swap(*v);             // not read from here on: freed before the pairs are made
    corners();
    pair_corners();
  }

  // pair_corners_from_halfedges() and prepare_rows() without freeing any halfedge, in two
  // steps: allocate_paired_rows() allocates the cotangents (in the calling thread: see
  // run_beside()), then fill_paired_rows() pairs the corners and fills them, reading only the lists of
  // outgoing halfedges, the twins, the face array and xyz, which a decomposition's selection
  // only reads too, so that it runs beside it. apply_rows() may follow at once.
  void allocate_paired_rows(Relaxation_scheme scheme)
  {
    CGAL_precondition(scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE);
    halfedges();
    if(scheme != Relaxation_scheme::UNIFORM)
      m_cotangent.resize(m_triangles->size());   // first: the largest, it takes the largest block freed before it
    corners();
  }
  void fill_paired_rows(Relaxation_scheme scheme, const double* xyz)
  {
    pair_corners();
    if(scheme != Relaxation_scheme::UNIFORM)
      compute_cotangents(xyz);
  }

  // frees all of the halfedges but the vertices' lists of outgoing halfedges (out_offsets,
  // out, out_target) and, `with_twins` or while the corners are paired through them
  // (pair_corners()), the twins, once only those are read: the 1-ring
  // weights and the collapses of the face array after the selection (and the next level's
  // halfedges, which Triangle_halfedges::build_after_collapses() derives from these). The
  // targets stay for the rows' columns: read from the face array instead, each a cache miss at
  // the place of the corner's face, the dragon's decomposition took 0.70 s instead of 0.67 s
  // (two threads), for 1 MB more at its peak (release_weight_data() frees them).
  void keep_outgoing_lists_only(bool with_twins = false)
  {
    for(Index_array* v : {&m_mesh.source, &m_mesh.target, &m_mesh.out_apex})
      Index_array().swap(*v);             // (a chain of assignments would keep the capacities)
    point_at_corner_ends();
    if(!with_twins)
    {
      if(!m_twin_pairs)                   // (paired through the twins: they are the pairing, kept in place)
        Index_array().swap(m_mesh.twin);
    }
    else
    {
      // moved to a block of its own: the twins, allocated before the selection's large
      // arrays, would otherwise keep glibc from giving back the freed top of its heap (the
      // dragon's peak: 239 MB with them in place, 230 MB moved, 219 MB without twins kept)
      Index_array moved(m_mesh.twin.begin(), m_mesh.twin.end());
      m_mesh.twin.swap(moved);
    }
  }

  // Room for the corner lists of connectivities of up to n vertices and `corners` face
  // corners (3 per face): a sequence of growing connectivities (the levels of a
  // reconstruction, from the coarsest) then fills arrays allocated once at their largest size
  // instead of reallocating them, copying their contents and touching fresh pages, at every
  // doubling (the 1-ring schemes' arrays; the halfedges of SOD are built per level).
  void reserve(std::size_t n, std::size_t corners)
  {
    m_ring_offsets.reserve(n + 1);
    for(Index_array* v : {&m_out, &m_out_target, &m_out_apex})
      v->reserve(corners);
    m_cotangent.reserve(corners);
  }

  // frees what the weights were computed with (not the halfedges but their targets)
  void release_weight_data()
  {
    m_has_corners = false;
    m_paired = false;
    m_twin_pairs = false;
    Uninitialized_vector<double>().swap(m_cotangent);
    std::vector<Index>().swap(m_ring_offsets);
    for(Index_array* v : {&m_out, &m_out_target, &m_out_apex, &m_corner_twin})
      Index_array().swap(*v);
    Uninitialized_vector<unsigned char>().swap(m_apex_matched);
    Index_array().swap(m_mesh.out_target);    // (kept by keep_outgoing_lists_only() for the rows)
    m_listed = false;
    point_at_corner_ends();
  }

  // xyz: 3 doubles per row; fixed: nullptr or one flag per row (constrained vertices)
  // (Weights: Sparse_weights or Operator_weights)
  template <typename Weights>
  void build(Relaxation_scheme scheme, const double* xyz, const unsigned char* fixed,
             Weights& w, std::vector<Relaxation_row_rule>& rules)
  {
    const std::size_t n = m_n;
    rules.resize(n);
    w.offsets.resize(n + 1);
    w.offsets[0] = 0;
    if(scheme == Relaxation_scheme::SECOND_ORDER_DIFFERENCE)
    {
      halfedges();
      compute_cotangents(xyz);
      build_sod_rows(xyz, fixed, w, rules);
      return;
    }
    corners();
    if(scheme != Relaxation_scheme::UNIFORM)
      compute_cotangents(xyz);
    if(!m_paired)
      allocate_ring_pairs();
    // two passes over independent rows (parallel): the twins in every ring and the length of
    // every row, then the rows
    parallel_for_blocks(n, [&](std::size_t first, std::size_t last) {
      std::vector<std::pair<Index, Index> > sorted;   // long rings only
      for(std::size_t i = first; i < last; ++i)
      {
        rules[i] = m_paired ? rule_of_paired_ring(i, fixed) : match_ring(i, fixed, sorted);
        w.offsets[i + 1] = static_cast<Index>(ring_row_length(i, rules[i]));
      }
    });
    // the pairing depends on the connectivity only: the next build() on it (relax() rebuilds
    // the weights for new positions at every iteration) reads it instead of matching the rings
    m_paired = true;
    for(std::size_t i = 0; i < n; ++i)
      w.offsets[i + 1] += w.offsets[i];
    w.columns.resize(w.offsets[n]);
    w.values.resize(w.offsets[n]);
    parallel_for_blocks(n, [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
        ring_row(scheme, i, xyz, rules[i], w.columns.data() + w.offsets[i], w.values.data() + w.offsets[i]);
    });
  }

  // build() and Sparse_weights::apply() of its weights in one pass, for weights used once
  // (every step of relax() that moves the geometry): each row is computed into a scratch row
  // and handed at once to apply_row(i, columns, values, length), which may combine it with
  // Sparse_weights::combine() (the rows of build(), so the sums of apply(), bit for bit).
  // The rows are neither stored nor their offsets summed: a one-shot relaxation wrote and read
  // again 12 bytes per entry. The 1-ring schemes only (SOD rows are assembled sequentially).
  template <typename ApplyRow>
  void build_and_apply(Relaxation_scheme scheme, const double* xyz, const unsigned char* fixed, const ApplyRow& apply_row)
  {
    prepare_rows(scheme, xyz);
    apply_rows(scheme, xyz, fixed, nullptr, m_n, apply_row);
    m_paired = true;
  }

  // build_and_apply() in parts, for rows used once each but in several passes (the synthesis
  // of a level: its odd rows, then its even rows): prepare_rows() lists the corners and
  // computes the cotangents, apply_rows() computes the rows rows[0..count) (all rows when
  // `rows` is nullptr), pairing their rings, and hands each to apply_row(). Every row at most
  // once per prepare_rows().
  void prepare_rows(Relaxation_scheme scheme, const double* xyz)
  {
    CGAL_precondition(scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE);
    corners();
    if(scheme != Relaxation_scheme::UNIFORM)
      compute_cotangents(xyz);
  }

  template <typename ApplyRow>
  void apply_rows(Relaxation_scheme scheme, const double* xyz, const unsigned char* fixed, const Index* rows, std::size_t count,
                  const ApplyRow& apply_row)
  {
    if(!m_paired)
      allocate_ring_pairs();
    const bool twin_curvature = m_twin_pairs && scheme == Relaxation_scheme::CURVATURE;
    parallel_for_blocks(count, [&](std::size_t first, std::size_t last) {
      std::vector<std::pair<Index, Index> > sorted;   // long rings only
      std::vector<Index> col;
      std::vector<double> val;
      for(std::size_t q = first; q < last; ++q)
      {
        const std::size_t i = rows == nullptr ? q : std::size_t(rows[q]);
        if(twin_curvature && (fixed == nullptr || !fixed[i]))
        {
          const Index b = m_offs[i], e = m_offs[i + 1];
          if(b != e && m_outp[e - 1] < m_h0)          // corners only: no border halfedge out of i
          {
            if(col.size() < e - b)
            {
              col.resize(2 * (e - b));
              val.resize(2 * (e - b));
            }
            double positive, negative;                 // the row's masses, summed as it is computed
            if(closed_curvature_ring_row(b, e, col.data(), val.data(), positive, negative))
            {
              normalised_curvature_row(e - b, val.data(), positive, negative);
              apply_row(i, col.data(), val.data(), std::size_t(e - b));
              continue;
            }
          }
        }
        Relaxation_row_rule rule = m_paired ? rule_of_paired_ring(i, fixed) : match_ring(i, fixed, sorted);
        const std::size_t length = ring_row_length(i, rule);
        if(col.size() < length)
        {
          col.resize(2 * length);
          val.resize(2 * length);
        }
        ring_row(scheme, i, xyz, rule, col.data(), val.data());
        apply_row(i, col.data(), val.data(), length);
      }
    });
  }

private:
  // The pairs of pair_corners_from_halfedges(), on the corners listed by corners(): read from
  // the halfedges' twins where a row needs them (corner_has_twin(), apex_matched(),
  // twin_cotangent()), the twins being kept while the pairing is used. Why: the pairs were
  // written per corner in a pass of their own (a twin's read per corner, scattered), then read
  // again by the rows, which read the cotangents at the same scattered places: 6.6 % of the
  // instructions of the dragon's decomposition, and 5 bytes per corner at the level's peak.
  void pair_corners()
  {
    CGAL_precondition(m_has_halfedges && m_mesh.twin.size() == m_mesh.number_of_halfedges());
    m_twin_pairs = true;
    m_paired = true;
  }

  // the pairing of corner k (of the current corner lists): whether the edge of its halfedge
  // i -> a has a face across (a -> i), whether its apex b is matched (the edge b -> i has a
  // face across: some corner of i is paired with it), and the halfedge a -> i across, whose
  // cotangent the row adds (the corner's twin must exist)
  bool corner_has_twin(Index k) const
  {
    return m_twin_pairs ? m_mesh.twin[m_outp[k]] < m_h0 : m_corner_twin[k] != invalid_index;
  }
  bool apex_matched(Index k) const
  {
    return m_twin_pairs ? m_mesh.twin[Triangle_halfedges::prev_in_face(m_outp[k])] < m_h0 : m_apex_matched[k] != 0;
  }
  Index twin_cotangent(Index k) const
  {
    // (the twin of the corner's halfedge; through the pairs: the halfedge before the twin's
    // corner, i -> b in the face across, is a -> i)
    return m_twin_pairs ? m_mesh.twin[m_outp[k]] : Triangle_halfedges::prev_in_face(m_corner_twin[k]);
  }

  // the arrays match_ring() pairs the corners in, for every corner listed
  void allocate_ring_pairs()
  {
    const std::size_t rows = m_has_halfedges ? m_mesh.out.size() : m_out.size();
    if(m_corner_twin.size() != rows)
    {
      m_corner_twin.resize(rows);
      m_apex_matched.resize(rows);
    }
  }

  void halfedges()
  {
    if(!m_has_halfedges)
      m_mesh.build(m_n, *m_triangles, false);
    m_has_halfedges = true;
  }

  // ---- the 1-ring schemes on corners ---------------------------------------------------
  // Vertex i's corners are its face halfedges i -> a (m_outp[k], target_of_corner(k) = a, with
  // the vertex before, apex_of_corner(k) = b: the face holds b -> i -> a), in face order. The
  // twin of i -> a is the corner m of i whose face holds a -> i (apex_of_corner(m) = a): both faces' angles
  // opposite the edge give its cotangent weight. The rows list the neighbours in the order of
  // Triangle_halfedges (the face halfedges, then the border ones): the same weights as a walk
  // on the halfedges, without building twins for the whole mesh (a third of the time of a
  // one-shot relaxation was that build).
  // Lists the corners if needed and points m_offs and m_outp at the lists read (set again at
  // every call, so that a copied builder reads its own arrays)
  void corners()
  {
    if(!m_has_corners)
    {
      if(!m_has_halfedges)
        list_face_halfedges_by_source(m_n, *m_triangles, true, m_ring_offsets, m_out, m_out_target, m_out_apex);
      m_has_corners = true;
    }
    // the halfedges list the corners where they are built (then the border halfedges, skipped)
    m_offs = m_has_halfedges ? m_mesh.out_offsets.data() : m_ring_offsets.data();
    m_outp = m_has_halfedges ? m_mesh.out.data() : m_out.data();
    m_listed = !m_has_halfedges && m_out_apex.size() == m_out.size();
    m_h0 = static_cast<Index>(m_triangles->size());
    point_at_corner_ends();
  }

  // the targets and apexes of the corners read, where lists of them are alive (contiguous per
  // ring), else nullptr (then read from the face array)
  void point_at_corner_ends()
  {
    // a list of the halfedges', where it is alive (freed lists are empty)
    auto alive = [&](const Index_array& list) -> const Index* {
      return m_has_halfedges && !m_mesh.out.empty() && list.size() == m_mesh.out.size() ? list.data() : nullptr;
    };
    m_targets = m_listed ? m_out_target.data() : alive(m_mesh.out_target);
    m_apexes = m_listed ? m_out_apex.data() : alive(m_mesh.out_apex);
  }

  // the vertex after and the vertex before corner k in its face: from the corner lists when
  // they were listed with them, or from the halfedges' lists while those are kept (contiguous
  // per ring: reading them from the face array was a fifth of a reconstruction's weight
  // build), else from the face array
  Index target_of_corner(Index k) const
  {
    if(m_targets != nullptr)
      return m_targets[k];
    return (*m_triangles)[Triangle_halfedges::next_in_face(m_outp[k])];
  }
  Index apex_of_corner(Index k) const
  {
    if(m_apexes != nullptr)
      return m_apexes[k];
    return (*m_triangles)[Triangle_halfedges::prev_in_face(m_outp[k])];
  }

  // the end of vertex i's corners (a row of the halfedges ends with its border halfedges)
  Index corners_end(std::size_t i) const
  {
    Index e = m_offs[i + 1];
    while(e > m_offs[i] && m_outp[e - 1] >= m_h0)
      --e;
    return e;
  }

  // Pairs the corners of vertex i (m_corner_twin[k]: the halfedge out of i in the face across
  // the edge of corner k, or invalid_index; m_apex_matched[m]: whether corner m is some
  // corner's twin; first come, first served where a directed edge repeats; constrained rows
  // too) and returns FIXED, BORDER or SCHEME. Rings longer than 32
  // corners are searched through a sorted copy (`sorted`, scratch), so that a vertex of valence
  // D costs D log D, not D^2. (Local pointers and a bit mask: stores through the byte flags
  // would otherwise make the compiler reload every array's address in the inner loop.)
  Relaxation_row_rule match_ring(std::size_t i, const unsigned char* fixed, std::vector<std::pair<Index, Index> >& sorted)
  {
    const Index b = m_offs[i], e = corners_end(i);
    if(b == e)
      return Relaxation_row_rule::FIXED;
    Index* twin_of = m_corner_twin.data();
    unsigned char* matched = m_apex_matched.data();
    bool border = false;
    if(e - b <= 32)
    {
      Index ring_target[32], ring_apex[32];
      for(Index k = b; k < e; ++k)
      {
        ring_target[k - b] = target_of_corner(k);
        ring_apex[k - b] = apex_of_corner(k);
      }
      const Index* target = ring_target - b;
      const Index* apex = ring_apex - b;
      // the twin of corner k is the corner whose apex is k's target: unique in a halfedge
      // mesh, found without branches; a second claim on a corner (a directed edge listed
      // twice) falls back to the search below, first come, first served
      std::uint32_t used = 0;
      bool repeated = false;
      for(Index k = b; k < e; ++k)
      {
        const Index a = target[k];
        Index twin = invalid_index;
        for(Index m = e; m-- > b; )
          twin = apex[m] == a ? m : twin;
        twin_of[k] = twin;                // a position for now: a halfedge below
        if(twin == invalid_index)
          border = true;
        else
        {
          repeated = repeated || ((used >> (twin - b)) & 1u);
          used |= std::uint32_t(1) << (twin - b);
        }
      }
      if(repeated)
      {
        used = 0;
        border = false;
        for(Index k = b; k < e; ++k)
        {
          const Index a = target[k];
          Index twin = invalid_index;
          for(Index m = b; m < e; ++m)
            if(apex[m] == a && !((used >> (m - b)) & 1u)) { twin = m; break; }
          twin_of[k] = twin;
          if(twin == invalid_index)
            border = true;
          else
            used |= std::uint32_t(1) << (twin - b);
        }
      }
      for(Index m = b; m < e; ++m)
        matched[m] = static_cast<unsigned char>((used >> (m - b)) & 1u);
      border = border || used != (e - b == 32 ? ~std::uint32_t(0) : (std::uint32_t(1) << (e - b)) - 1);
      for(Index k = b; k < e; ++k)
        if(twin_of[k] != invalid_index)
          twin_of[k] = m_outp[twin_of[k]];
    }
    else
    {
      sorted.clear();
      for(Index m = b; m < e; ++m)
      {
        sorted.emplace_back(apex_of_corner(m), m);
        matched[m] = 0;
      }
      std::sort(sorted.begin(), sorted.end());
      for(Index k = b; k < e; ++k)
      {
        const Index a = target_of_corner(k);
        Index twin = invalid_index;
        for(auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(a, Index(0)));
            it != sorted.end() && it->first == a; ++it)
          if(!matched[it->second]) { twin = it->second; break; }
        twin_of[k] = twin == invalid_index ? invalid_index : m_outp[twin];
        if(twin == invalid_index)
          border = true;
        else
          matched[twin] = 1;
      }
      for(Index m = b; m < e && !border; ++m)
        border = !matched[m];
    }
    if(fixed != nullptr && fixed[i])                      // (paired all the same: a later build may read the pairing)
      return Relaxation_row_rule::FIXED;
    return border ? Relaxation_row_rule::BORDER : Relaxation_row_rule::SCHEME;
  }

  // FIXED, BORDER or SCHEME from the pairing of pair_corners_from_halfedges()
  Relaxation_row_rule rule_of_paired_ring(std::size_t i, const unsigned char* fixed) const
  {
    const Index b = m_offs[i], e = corners_end(i);
    if(b == e || (fixed != nullptr && fixed[i]))
      return Relaxation_row_rule::FIXED;
    if(m_twin_pairs)
    {
      // A corner's apex b is unmatched exactly when the twin of b -> i is a border halfedge,
      // i -> b, which the row lists after its corners (and every border halfedge out of i is
      // such a twin): one test instead of a twin's read per corner
      if(e != m_offs[i + 1])
        return Relaxation_row_rule::BORDER;
      for(Index k = b; k < e; ++k)
        if(!corner_has_twin(k))
          return Relaxation_row_rule::BORDER;
      return Relaxation_row_rule::SCHEME;
    }
    for(Index k = b; k < e; ++k)
      if(!corner_has_twin(k) || !apex_matched(k))
        return Relaxation_row_rule::BORDER;
    return Relaxation_row_rule::SCHEME;
  }

  std::size_t ring_row_length(std::size_t i, Relaxation_row_rule rule) const
  {
    if(rule == Relaxation_row_rule::FIXED)
      return 1;
    const Index b = m_offs[i], e = corners_end(i);
    if(rule != Relaxation_row_rule::BORDER)
      return e - b;
    std::size_t count = 0;
    for(Index k = b; k < e; ++k)
      count += (corner_has_twin(k) ? 0 : 1) + (apex_matched(k) ? 0 : 1);
    return count;
  }

  // the border neighbours of i: targets of corners without a twin, then apexes of corners
  // that are nobody's twin (the border halfedges out of i, in Triangle_halfedges' order)
  std::size_t ring_border_columns(std::size_t i, Index* col) const
  {
    const Index b = m_offs[i], e = corners_end(i);
    std::size_t count = 0;
    for(Index k = b; k < e; ++k)
      if(!corner_has_twin(k))
        col[count++] = target_of_corner(k);
    for(Index m = b; m < e; ++m)
      if(!apex_matched(m))
        col[count++] = apex_of_corner(m);
    return count;
  }

  void uniform_ring_row(std::size_t i, Index* col, double* val) const
  {
    const Index b = m_offs[i], e = corners_end(i);
    const double v = 1. / double(e - b);
    for(Index k = b; k < e; ++k)
    {
      *col++ = target_of_corner(k);
      *val++ = v;
    }
  }

  // row i of a 1-ring scheme, of ring_row_length(i, rule) entries; rule: FIXED, BORDER or
  // SCHEME from the pairing, refined by the normalisation of a curvature row
  void ring_row(Relaxation_scheme scheme, std::size_t i, const double* xyz, Relaxation_row_rule& rule, Index* col, double* val) const
  {
    if(rule == Relaxation_row_rule::FIXED)
    {
      *col = static_cast<Index>(i);
      *val = 1.;
    }
    else if(rule == Relaxation_row_rule::BORDER)
      border_weights(scheme, i, xyz, ring_border_columns(i, col), col, val);
    else if(scheme == Relaxation_scheme::UNIFORM)
      uniform_ring_row(i, col, val);
    else
      rule = curvature_ring_row(i, col, val);
  }

  Relaxation_row_rule curvature_ring_row(std::size_t i, Index* col, double* val) const
  {
    const Index b = m_offs[i], e = corners_end(i);
    for(Index k = b; k < e; ++k)
    {
      col[k - b] = target_of_corner(k);
      val[k - b] = m_cotangent[m_outp[k]] + m_cotangent[twin_cotangent(k)];
    }
    return normalised_curvature_row(e - b, val);
  }

  // The row of rule_of_paired_ring(), ring_row_length() and curvature_ring_row() in one pass,
  // for a vertex whose corners b..e are its whole row (paired through the twins, curvature):
  // false as soon as a corner has no twin (a BORDER row: the caller takes the general path),
  // else the cotangent sums of curvature_ring_row(), the same additions, and the row's
  // positive and negative masses (normalised_curvature_row()'s sums, in the same order).
  // Why: those three passes and the normalisation's first each found the row's end or read
  // its twins and weights again (the dragon's decomposition, one thread: 6.32 -> 6.07 G
  // instructions).
  bool closed_curvature_ring_row(Index b, Index e, Index* col, double* val, double& positive, double& negative) const
  {
    const Index* const out = m_outp;
    const Index* const twin = m_mesh.twin.data();
    const double* const cot = m_cotangent.data();
    const Index h0 = m_h0;
    positive = negative = 0.;
    for(Index k = b; k < e; ++k)
    {
      const Index h = out[k], t = twin[h];
      if(t >= h0)
        return false;
      col[k - b] = target_of_corner(k);
      const double w = cot[h] + cot[t];
      val[k - b] = w;
      add_to_masses(w, positive, negative);
    }
    return true;
  }

  // SOD rows have lengths known only once assembled: one sequential pass into an upper bound
  template <typename Weights>
  void build_sod_rows(const double* xyz, const unsigned char* fixed, Weights& w, std::vector<Relaxation_row_rule>& rules)
  {
    const std::size_t n = m_n;
    compute_hinge_coefficients(xyz);
    m_local_position.assign(n, invalid_index);
    const std::size_t capacity = 3 * m_mesh.out.size() + n;
    w.columns.resize(capacity);
    w.values.resize(capacity);
    std::size_t size = 0;
    for(std::size_t i = 0; i < n; ++i)
    {
      Index* col = w.columns.data() + size;
      double* val = w.values.data() + size;
      Relaxation_row_rule rule = structural_rule(i, fixed);
      std::size_t length = 0;
      if(rule == Relaxation_row_rule::FIXED)
      {
        *col = static_cast<Index>(i);
        *val = 1.;
        length = 1;
      }
      else if(rule == Relaxation_row_rule::BORDER)
        length = border_row(Relaxation_scheme::SECOND_ORDER_DIFFERENCE, i, xyz, col, val);
      else if(!(length = sod_row(i, col, val)))
      {
        rule = curvature_row(i, col, val);
        if(rule == Relaxation_row_rule::SCHEME)
          rule = Relaxation_row_rule::CURVATURE_FALLBACK;
        length = row_length(i, rule);
      }
      rules[i] = rule;
      size += length;
      w.offsets[i + 1] = static_cast<Index>(size);
    }
    w.columns.resize(size);
    w.values.resize(size);
  }

  Index degree(std::size_t i) const { return m_mesh.out_offsets[i + 1] - m_mesh.out_offsets[i]; }

  // FIXED, BORDER, or SCHEME for the rows whose weights depend on the scheme
  Relaxation_row_rule structural_rule(std::size_t i, const unsigned char* fixed) const
  {
    if(degree(i) == 0 || (fixed != nullptr && fixed[i]))
      return Relaxation_row_rule::FIXED;
    for(Index k = m_mesh.out_offsets[i]; k < m_mesh.out_offsets[i + 1]; ++k)
      if(m_mesh.is_border_edge(m_mesh.out[k]))
        return Relaxation_row_rule::BORDER;
    return Relaxation_row_rule::SCHEME;
  }

  // length of a row of the 1-ring schemes (curvature and its fallbacks, uniform)
  std::size_t row_length(std::size_t i, Relaxation_row_rule rule) const
  {
    if(rule == Relaxation_row_rule::FIXED)
      return 1;
    if(rule != Relaxation_row_rule::BORDER)
      return degree(i);
    std::size_t count = 0;
    for(Index k = m_mesh.out_offsets[i]; k < m_mesh.out_offsets[i + 1]; ++k)
      count += m_mesh.is_border_edge(m_mesh.out[k]) ? 1 : 0;
    return count;
  }

  static double clamped_cotangent(double dot, double double_area)
  {
    if(double_area > 0.)
    {
      const double c = dot / double_area;
      return c > max_cotangent ? max_cotangent : (c < -max_cotangent ? -max_cotangent : c);
    }
    return dot > 0. ? max_cotangent : (dot < 0. ? -max_cotangent : 0.);
  }

  // the (clamped) cotangents of the angles of the triangle t[0] t[1] t[2] opposite its
  // halfedges t[k] -> t[k+1], k = 0, 1, 2
  static void face_cotangents(const Index* t, const double* xyz, double cot[3])
  {
    const double* p[3] = {xyz + 3 * std::size_t(t[0]), xyz + 3 * std::size_t(t[1]), xyz + 3 * std::size_t(t[2])};
    double e[3][3];   // e[k] = p[k+1] - p[k]
    for(int k = 0; k < 3; ++k)
      for(int c = 0; c < 3; ++c)
        e[k][c] = p[(k + 1) % 3][c] - p[k][c];
    const double cx = e[0][1] * e[2][2] - e[0][2] * e[2][1];
    const double cy = e[0][2] * e[2][0] - e[0][0] * e[2][2];
    const double cz = e[0][0] * e[2][1] - e[0][1] * e[2][0];
    const double double_area = std::sqrt(cx * cx + cy * cy + cz * cz);   // shared by the three angles
    for(int k = 0; k < 3; ++k)
    {
      // angle at corner k+2, opposite the halfedge p[k] -> p[k+1]: between -e[k+1] and e[k+2]
      const double* u = e[(k + 1) % 3];
      const double* v = e[(k + 2) % 3];
      cot[k] = clamped_cotangent(-(u[0] * v[0] + u[1] * v[1] + u[2] * v[2]), double_area);
    }
  }

  // m_cotangent[h] = cotangent of the angle opposite the face halfedge h in its face
  void compute_cotangents(const double* xyz)
  {
    const std::vector<Index>& tri = *m_triangles;
    const std::size_t nf = tri.size() / 3;
    m_cotangent.resize(3 * nf);
    parallel_for_blocks(nf, [&](std::size_t first, std::size_t last) {
      for(std::size_t f = first; f < last; ++f)
        face_cotangents(tri.data() + 3 * f, xyz, m_cotangent.data() + 3 * f);
    });
  }

  double edge_cotangent_weight(Index h) const
  {
    const Index t = m_mesh.twin[h];
    return (m_mesh.has_face(h) ? m_cotangent[h] : 0.) + (m_mesh.has_face(t) ? m_cotangent[t] : 0.);
  }

  // writes degree(i) entries
  Relaxation_row_rule curvature_row(std::size_t i, Index* col, double* val) const
  {
    const Index b = m_mesh.out_offsets[i], e = m_mesh.out_offsets[i + 1];
    for(Index k = b; k < e; ++k)
    {
      col[k - b] = m_mesh.out_target[k];
      val[k - b] = edge_cotangent_weight(m_mesh.out[k]);
    }
    return normalised_curvature_row(e - b, val);
  }

  // the cotangent weights val[0..d) of a row normalised (Eq. 2): as they are while the negative
  // mass is at most half the positive one, else without the negative weights, else uniform
  static Relaxation_row_rule normalised_curvature_row(std::size_t d, double* val)
  {
    double positive = 0., negative = 0.;
    for(std::size_t k = 0; k < d; ++k)
      add_to_masses(val[k], positive, negative);
    return normalised_curvature_row(d, val, positive, negative);
  }

  // a weight added to the positive or to the negative mass of its row
  static void add_to_masses(double w, double& positive, double& negative)
  {
    if(w > 0.) positive += w; else negative -= w;
  }

  // the same, the masses of val[0..d) summed by the caller (add_to_masses(), in the row's order)
  static Relaxation_row_rule normalised_curvature_row(std::size_t d, double* val, double positive, double negative)
  {
    if(positive > 0. && negative <= max_negative_ratio * positive)
    {
      const double inv = 1. / (positive - negative);
      for(std::size_t k = 0; k < d; ++k)
        val[k] *= inv;
      return Relaxation_row_rule::SCHEME;
    }
    if(positive > 0.)
    {
      const double inv = 1. / positive;
      for(std::size_t k = 0; k < d; ++k)
        val[k] = val[k] > 0. ? val[k] * inv : 0.;
      return Relaxation_row_rule::CLAMPED_CURVATURE;
    }
    for(std::size_t k = 0; k < d; ++k)
      val[k] = 1. / double(d);
    return Relaxation_row_rule::UNIFORM_FALLBACK;
  }

  // Border vertices move along the border curve: weights over the border neighbours,
  // inversely proportional to the edge lengths (linear interpolation by arc length, which
  // reproduces straight borders; this is also the minimiser of the curve's second-order
  // difference at the vertex), uniform for the UNIFORM scheme or when an edge has zero length.
  std::size_t border_row(Relaxation_scheme scheme, std::size_t i, const double* xyz, Index* col, double* val) const
  {
    std::size_t count = 0;
    for(Index k = m_mesh.out_offsets[i]; k < m_mesh.out_offsets[i + 1]; ++k)
      if(m_mesh.is_border_edge(m_mesh.out[k]))
        col[count++] = m_mesh.out_target[k];
    border_weights(scheme, i, xyz, count, col, val);
    return count;
  }

  // the weights of border row i over its `count` border neighbours col[0..count)
  static void border_weights(Relaxation_scheme scheme, std::size_t i, const double* xyz, std::size_t count,
                             const Index* col, double* val)
  {
    double total = 0.;
    bool uniform = (scheme == Relaxation_scheme::UNIFORM);
    for(std::size_t k = 0; k < count; ++k)
    {
      const std::size_t j = col[k];
      double l = 0.;
      for(int c = 0; c < 3; ++c)
        l += (xyz[3 * j + c] - xyz[3 * i + c]) * (xyz[3 * j + c] - xyz[3 * i + c]);
      l = std::sqrt(l);
      if(!(l > 0.))
        uniform = true;
      val[k] = uniform ? 1. : 1. / l;
      total += val[k];
    }
    for(std::size_t k = 0; k < count; ++k)
      val[k] = uniform ? 1. / double(count) : val[k] / total;
  }

  // ---- second-order differences (see second_order_difference_coefficients()) ----------
  // The hinge of an interior edge is stored at its canonical halfedge e (the smaller of the
  // two): v1 = source(e), v2 = target(e), v3 opposite e in its face, v4 opposite twin(e).
  void compute_hinge_coefficients(const double* xyz)
  {
    const std::size_t h0 = 3 * m_mesh.nf;
    m_hinge.resize(h0);
    m_hinge_valid.assign(h0, 0);
    for(Index e = 0; e < h0; ++e)
    {
      const Index t = m_mesh.twin[e];
      if(!(t > e) || !m_mesh.has_face(t))
        continue;
      const Index v[4] = {m_mesh.source[e], m_mesh.target[e], m_mesh.opposite_vertex(e), m_mesh.opposite_vertex(t)};
      if(v[2] == v[3])
        continue;                                    // a doubled triangle has no hinge
      m_hinge_valid[e] = second_order_difference_coefficients(xyz + 3 * std::size_t(v[0]), xyz + 3 * std::size_t(v[1]),
                                                              xyz + 3 * std::size_t(v[2]), xyz + 3 * std::size_t(v[3]),
                                                              min_relative_hinge_height, m_hinge[e].data());
    }
  }

  // adds the contribution of the hinge of the edge of h to the row of its vertex number `position`
  void add_hinge(Index h, int position_if_canonical, int position_otherwise)
  {
    const Index t = m_mesh.twin[h];
    if(!m_mesh.has_face(h) || !m_mesh.has_face(t))
      return;
    const Index e = (std::min)(h, t);
    if(!m_hinge_valid[e])
      return;
    const int k = (e == h) ? position_if_canonical : position_otherwise;
    const Index v[4] = {m_mesh.source[e], m_mesh.target[e], m_mesh.opposite_vertex(e), m_mesh.opposite_vertex(m_mesh.twin[e])};
    const std::array<double, 4>& c = m_hinge[e];
    for(int m = 0; m < 4; ++m)
    {
      if(m == k)
        continue;
      const double x = -c[k] * c[m];
      // the entry of v[m] in the row (first seen, first listed): a position per vertex, reset
      // after each row, so that a vertex of high valence costs linear, not quadratic, time
      Index& q = m_local_position[v[m]];
      if(q == invalid_index)
      {
        q = static_cast<Index>(m_local_columns.size());
        m_local_columns.push_back(v[m]);
        m_local_values.push_back(x);
      }
      else
        m_local_values[q] += x;
    }
  }

  // lambda_ij = -sum_e c_ei c_ej / sum_e c_ei^2 over the hinges that hold i: the edges at i
  // and the edges opposite i. The denominator equals the row sum of the numerators (the
  // coefficients of a hinge sum to 0), which is used so that the weights sum to 1.
  std::size_t sod_row(std::size_t i, Index* col, double* val)
  {
    m_local_columns.clear();
    m_local_values.clear();
    for(Index k = m_mesh.out_offsets[i]; k < m_mesh.out_offsets[i + 1]; ++k)
    {
      const Index h = m_mesh.out[k];            // i -> j: i is v1 of h's hinge, v2 of its twin's
      add_hinge(h, 0, 1);
      if(m_mesh.has_face(h))                     // the edge opposite i in the face of h: i is v3 or v4
        add_hinge(Triangle_halfedges::next_in_face(h), 2, 3);
    }
    for(Index c : m_local_columns)
      m_local_position[c] = invalid_index;
    double sum = 0., abs_sum = 0.;
    for(double x : m_local_values) { sum += x; abs_sum += std::abs(x); }
    if(!(sum > 0.) || !std::isfinite(sum) || !(abs_sum <= max_sod_absolute_sum * sum))
      return 0;
    const double inv = 1. / sum;
    for(std::size_t q = 0; q < m_local_columns.size(); ++q)
    {
      col[q] = m_local_columns[q];
      val[q] = m_local_values[q] * inv;
    }
    return m_local_columns.size();
  }

  const std::vector<Index>* m_triangles = nullptr;
  std::size_t m_n = 0;
  bool m_has_halfedges = false, m_has_corners = false, m_paired = false, m_listed = false;
  bool m_twin_pairs = false;   // paired through the halfedges' twins (pair_corners(); implies m_paired), else through the arrays below
  Triangle_halfedges m_mesh;
  // the corners around every vertex (corners()) and their pairing (match_ring())
  std::vector<Index> m_ring_offsets;
  // written for every corner before they are read (match_ring(); allocate_ring_pairs())
  Index_array m_out, m_out_target, m_out_apex, m_corner_twin;
  Uninitialized_vector<unsigned char> m_apex_matched;
  // the corner lists read: the halfedges' where they are built, else the ones above
  const Index* m_offs = nullptr;
  const Index* m_outp = nullptr;
  const Index* m_targets = nullptr;   // point_at_corner_ends()
  const Index* m_apexes = nullptr;
  Index m_h0 = 0;
  Uninitialized_vector<double> m_cotangent;      // every face corner's written by compute_cotangents()
  std::vector<std::array<double, 4> > m_hinge;
  std::vector<unsigned char> m_hinge_valid;
  std::vector<Index> m_local_columns;
  std::vector<double> m_local_values;
  std::vector<Index> m_local_position;   // per vertex: its entry in the SOD row being assembled, or invalid_index
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_RELAXATION_WEIGHTS_H
