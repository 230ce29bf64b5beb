// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PLANE_QUADRICS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PLANE_QUADRICS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Triangle_halfedges.h>

#include <CGAL/assertions.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The Garland-Heckbert plane quadrics of CGAL's `GarlandHeckbert_plane_policies` (CGAL 5.5,
// GarlandHeckbert_policy_base.h and GarlandHeckbert_functions.h), on index arrays: per vertex
// the sum of the plane quadrics of its faces (unit normal of the face, plane through it) and,
// for every border edge at the vertex, 100 times the quadric of the plane through that edge
// perpendicular to its face; after a collapse o -> e, Q_e becomes Q_o + Q_e. The cost of
// moving o onto e is (Q_o + Q_e)(p_e), evaluated as Q_o(p_e) + Q_e(p_e) (see cost()).
// Quadrics, positions and Q_v(p_v) are stored by row of the current level (the vertices of
// M_k in increasing input number), so that a cost reads contiguous records without any index
// translation.
// Why by hand: SMS evaluates the same numbers through an `Edge_profile` built per candidate on
// a halfedge mesh and stores 16 doubles per vertex; here a quadric is its 10 distinct
// coefficients, read directly from contiguous arrays (the decomposition needs no working
// halfedge mesh at all). Tested against SMS's cost on meshes with and without borders.
class Plane_quadrics
{
public:
  // coefficients of the symmetric 4x4 matrix, upper triangle row by row:
  // a00 a01 a02 a03 a11 a12 a13 a22 a23 a33
  static constexpr std::size_t size = 10;
  static constexpr double discontinuity_multiplier = 100.;   // CGAL's default

  // th: the connectivity of the input (rows = vertex numbers), the halfedges of the face array
  // `tri` (their ends need not be listed: see Triangle_halfedges::build()); xyz: 3 doubles per
  // vertex
  void initialize(const Triangle_halfedges& th, const std::vector<Index>& tri, const std::vector<double>& xyz)
  {
    initialize_with(th, [&tri](Index h) { return tri[h]; }, xyz);
  }
  // th with its ends listed
  void initialize(const Triangle_halfedges& th, const std::vector<double>& xyz)
  {
    CGAL_precondition(th.has_ends());
    initialize_with(th, [&th](Index h) { return th.source[h]; }, xyz);
  }

private:
  // source_of(h): the source of face halfedge h (the vertex at its corner of the face array)
  template <typename SourceOf>
  void initialize_with(const Triangle_halfedges& th, const SourceOf& source_of, const std::vector<double>& xyz)
  {
    m_xyz = xyz.data();
    // The plane (n, -n.p) of every face first, once per face (in parallel): each of a face's
    // three corners computed it before, with its square root and three divisions (a tenth of
    // the dragon's decomposition went to this function). 32 bytes per face, freed on return.
    Uninitialized_vector<double> planes(4 * th.nf);
    parallel_for_blocks(th.nf, [&](std::size_t first, std::size_t last) {
      for(std::size_t f = first; f < last; ++f)
        plane_of_face(source_of, static_cast<Index>(3 * f), planes.data() + 4 * f);
    });
    m_q.resize(size * th.n);                           // each row written whole by its own task below
    // Each vertex adds the quadrics of its faces and of the border edges at it in the order
    // of a loop over the faces (a face's plane, then the border edges of its halfedges h0,
    // h0 + 1, h0 + 2 as they come): the sums of that sequential loop, bit for bit, in parallel
    // over the vertices (their corners are listed in face order), summed in a local quadric
    // (the same additions in the same order) and stored once.
    const Index h0 = static_cast<Index>(3 * th.nf);
    parallel_for_blocks(th.n, [&](std::size_t first, std::size_t last) {
      double sum[size], face_quadric[size], edge_quadric[size];
      for(std::size_t v = first; v < last; ++v)
      {
        std::fill(sum, sum + size, 0.);
        for(Index k = th.out_offsets[v]; k < th.out_offsets[v + 1]; ++k)
        {
          const Index h = th.out[k];                       // v -> a in its face
          if(h >= h0)
            continue;                                      // a border halfedge: no face
          const Index into = Triangle_halfedges::prev_in_face(h);   // b -> v in the same face
          const bool border_out = !th.has_face(th.twin[h]), border_into = !th.has_face(th.twin[into]);
          outer(planes.data() + 4 * std::size_t(h / 3), face_quadric);
          if(h % 3 != 0 && border_into)                    // the face loop meets `into` before h
            add(sum, plane_of_border_edge(source_of, into, edge_quadric), discontinuity_multiplier);
          add(sum, face_quadric, 1.);
          if(border_out)
            add(sum, plane_of_border_edge(source_of, h, edge_quadric), discontinuity_multiplier);
          if(h % 3 == 0 && border_into)                    // ... or after it (h is the face's first halfedge)
            add(sum, plane_of_border_edge(source_of, into, edge_quadric), discontinuity_multiplier);
        }
        copy_values(sum, size, m_q.data() + size * v);
      }
    });
    evaluate_own_errors();
  }

public:
  // A new level: xyz holds the positions of its rows (the quadrics follow them, see next_level()).
  void begin_level(const std::vector<double>& xyz)
  {
    if(m_xyz != xyz.data() || !m_own_current)
    {
      m_xyz = xyz.data();
      evaluate_own_errors();
    }
  }

  // Cost of moving row o onto row e: (Q_o + Q_e)(p_e), evaluated as Q_o(p_e) + Q_e(p_e) with
  // Q_e(p_e) from begin_level(). Equal in exact arithmetic; the rounding differs from SMS's
  // (which sums the matrices first) by an ulp or so. Why: a candidate then reads p_e and one
  // double of e (the costs of every level's 6 n candidates read Q_e, 80 bytes at a random row,
  // beside p_e: two to three cache lines instead of one to two).
  Optional<double> cost(Index o, Index e) const
  {
    CGAL_assertion(m_own_current);                     // begin_level() after next_level()
    return Optional<double>(evaluate(quadric(o), point(e)) + m_own[e]);
  }

  // The costs of moving row o onto rows e, Q_o read once: candidate_keys() computes the costs of
  // a whole 1-ring in a row, where a call per halfedge (not inlined there) read Q_o again for
  // every neighbour. The same operations as cost(): the same bits (a test compares).
  // (The arrays' addresses are copied in: read through the quadrics' object, the compiler
  // loaded them again after every key the loop stored.)
  class Costs_from
  {
  public:
    Costs_from(const Plane_quadrics& q, Index o) : m_xyz(q.m_xyz), m_own(q.m_own.data())
    {
      CGAL_assertion(q.m_own_current);
      const double* a = q.quadric(o);
      for(std::size_t i = 0; i < size; ++i)
        m_a[i] = a[i];
    }
    double operator()(Index e) const
    {
      return evaluate(m_a, m_xyz + 3 * std::size_t(e)) + m_own[e];
    }

  private:
    const double* m_xyz;
    const double* m_own;
    double m_a[size];
  };
  Costs_from costs_from(Index o) const { return Costs_from(*this, o); }

  // a hint that cost(., e) will be read soon (candidate_keys()): the cache lines of p_e (24
  // bytes: one or two) and of Q_e(p_e)
  void prefetch_target(Index e) const
  {
    prefetch(point(e));
    prefetch(point(e) + 2);
    prefetch(m_own.data() + e);
  }

  // The quadrics of the next level M_{k+1}, after a level's accepted collapses ({o, e} each),
  // in place: Q_e += Q_o at every target e (in parallel: the selection locks the closed 1-ring
  // of each source, so no target is taken twice nor is any source's, and no source is
  // written), then the rows of M_{k+1} moved down, row j of M_{k+1} from the row
  // r = even_rows[j] >= j of M_k, with Q_r(p_r) evaluated at once, p_r read in M_k's positions
  // (begin_level() keeps it when M_{k+1}'s positions are those values moved down in place in
  // the same array, as the decomposition moves them). `next_row` (next_row[r] = j for the even
  // rows of M_k) is not read here. The pages the arrays no longer use go back (their capacity
  // stays). Why in place: a new array of M_{k+1}'s rows, written in one pass that read every
  // target's source through an array of a source per row, was a second copy of the quadrics
  // at the level's end, 80 bytes per row: the peak of the dragon's decomposition rose by 35 MB
  // where no other array of the level had freed as much before it, and on the 3.1M-vertex
  // horse the freed array of the level before (250 MB) stayed kept for reuse (Block_pool)
  // through the next level's peak.
  template <typename Collapses>
  void next_level(const Collapses& accepted, const std::vector<Index>& even_rows, const std::vector<Index>& /* next_row */)
  {
    const std::size_t n = even_rows.size();
    double* const q = m_q.data();
    parallel_for_blocks(accepted.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
      {
        double* e = q + size * std::size_t(accepted[i].e);
        const double* o = q + size * std::size_t(accepted[i].o);
        for(std::size_t c = 0; c < size; ++c)
          e[c] += o[c];                                     // add_quadric(): Q_o + Q_e
      }
    });
    // in blocks of rows of M_{k+1}, in parallel waves (move_down_in_waves()): block b writes
    // rows [b B, (b + 1) B) and reads from row even_rows[b B] on; Q_r(p_r) of M_k is not read
    // again, so own[j] is written in place too
    constexpr std::size_t block = 4096;
    double* const own = m_own.data();
    const Index* const even = even_rows.data();
    move_down_in_waves((n + block - 1) / block,
                       [&](std::size_t b) { return std::size_t(even[b * block]); },
                       [&](std::size_t b) { return (std::min)(n, (b + 1) * block); },
                       [&](std::size_t b) {
                         for(std::size_t j = b * block, end = (std::min)(n, (b + 1) * block); j < end; ++j)
                         {
                           const std::size_t r = even[j];
                           if(r != j)
                             std::copy(q + size * r, q + size * (r + 1), q + size * j);
                           own[j] = evaluate(q + size * j, point(static_cast<Index>(r)));
                         }
                       });
    m_q.resize(size * n);
    m_own.resize(n);
    release_unused_capacity(m_q);
    release_unused_capacity(m_own);
    m_own_current = true;
  }

  // x^T Q x for the homogeneous point (x, 1)
  static double evaluate(const double* s, const double* x)
  {
    return x[0] * (s[0] * x[0] + 2. * (s[1] * x[1] + s[2] * x[2] + s[3]))
         + x[1] * (s[4] * x[1] + 2. * (s[5] * x[2] + s[6]))
         + x[2] * (s[7] * x[2] + 2. * s[8])
         + s[9];
  }

  const double* quadric(Index v) const { return m_q.data() + size * std::size_t(v); }

private:
  const double* point(Index v) const { return m_xyz + 3 * std::size_t(v); }

  // m_own[v] = Q_v(p_v) for every row v, once per level (read by cost())
  void evaluate_own_errors()
  {
    const std::size_t n = m_q.size() / size;
    m_own.resize(n);
    parallel_for_blocks(n, [&](std::size_t first, std::size_t last) {
      for(std::size_t v = first; v < last; ++v)
        m_own[v] = evaluate(quadric(static_cast<Index>(v)), point(static_cast<Index>(v)));
    });
    m_own_current = true;
  }

  // the plane (n, -n.p) of the face whose first halfedge is h0 (n: its unit normal); CGAL
  // takes p = target(h), q = target(next(h)), r = source(h) of the face's halfedge (the
  // target of a face halfedge is the source of the next: source_of() as in initialize_with())
  template <typename SourceOf>
  void plane_of_face(const SourceOf& source_of, Index h0, double* plane) const
  {
    const double* p = point(source_of(h0 + 1));
    const double* q = point(source_of(h0 + 2));
    const double* r = point(source_of(h0));
    cross_of_differences(q, r, p, plane);
    normalize(plane);
    set_offset(plane, p);
  }

  // the quadric of the plane through the border edge source(h) -> target(h) (a face halfedge
  // without a face across), perpendicular to its face
  template <typename SourceOf>
  const double* plane_of_border_edge(const SourceOf& source_of, Index h, double* out) const
  {
    const Index next = Triangle_halfedges::next_in_face(h);
    const double* ep = point(source_of(next));
    const double* eq = point(source_of(Triangle_halfedges::next_in_face(next)));
    const double* er = point(source_of(h));
    double fn[3], edge[3], en[4];
    cross_of_differences(eq, er, ep, fn);
    for(int c = 0; c < 3; ++c) edge[c] = ep[c] - er[c];
    cross(edge, fn, en);
    normalize(en);
    set_offset(en, ep);
    outer(en, out);
    return out;
  }

  // as CGAL: a zero vector stays zero (degenerate face: no plane, no quadric)
  static void normalize(double* n)
  {
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if(l != 0.)
      for(int c = 0; c < 3; ++c) n[c] /= l;
  }

  // plane[3] = -n.x for the normal n = plane[0..2] and a point x of the plane
  static void set_offset(double* plane, const double* x)
  {
    plane[3] = -(plane[0] * x[0] + plane[1] * x[1] + plane[2] * x[2]);
  }

  // the quadric of the plane r = (n, -n.x) (n: its unit normal, x: a point of it): r r^T
  static void outer(const double* r, double* out)
  {
    std::size_t k = 0;
    for(int i = 0; i < 4; ++i)
      for(int j = i; j < 4; ++j)
        out[k++] = r[i] * r[j];
  }

  static void add(double* sum, const double* quadric, double factor)
  {
    for(std::size_t i = 0; i < size; ++i)
      sum[i] += factor * quadric[i];
  }

  const double* m_xyz = nullptr;  // 3 per row
  Uninitialized_vector<double> m_q;   // 10 coefficients per row
  Uninitialized_vector<double> m_own; // per row v: Q_v(p_v) (evaluate_own_errors())
  bool m_own_current = false;         // whether m_own follows the quadrics and positions
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PLANE_QUADRICS_H
