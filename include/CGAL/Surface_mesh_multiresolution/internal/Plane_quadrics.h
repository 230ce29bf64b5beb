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
// moving o onto e is (Q_o + Q_e)(p_e). Quadrics and positions are stored by row of the
// current level (the vertices of M_k in increasing input number), so that the cost of a
// candidate reads two contiguous records without any index translation.
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

  // th: the connectivity of the input (rows = vertex numbers), xyz: 3 doubles per vertex
  void initialize(const Triangle_halfedges& th, const std::vector<double>& xyz)
  {
    m_xyz = xyz.data();
    m_q.resize(size * th.n);                           // each row zeroed by its own task below
    // Each vertex adds the quadrics of its faces and of the border edges at it in the order
    // of a loop over the faces (a face's plane, then the border edges of its halfedges h0,
    // h0 + 1, h0 + 2 as they come): the sums of that sequential loop, bit for bit, in parallel
    // over the vertices (their corners are listed in face order); each face's plane is
    // computed by each of its three corners.
    const Index h0 = static_cast<Index>(3 * th.nf);
    parallel_for_blocks(th.n, [&](std::size_t first, std::size_t last) {
      double face_quadric[size], edge_quadric[size];
      for(std::size_t v = first; v < last; ++v)
      {
        const Index row = static_cast<Index>(v);
        std::fill(m_q.data() + size * v, m_q.data() + size * (v + 1), 0.);
        for(Index k = th.out_offsets[v]; k < th.out_offsets[v + 1]; ++k)
        {
          const Index h = th.out[k];                       // v -> a in its face
          if(h >= h0)
            continue;                                      // a border halfedge: no face
          const Index into = Triangle_halfedges::prev_in_face(h);   // b -> v in the same face
          const bool border_out = !th.has_face(th.twin[h]), border_into = !th.has_face(th.twin[into]);
          plane_of_face(th, h - h % 3, face_quadric);
          if(h % 3 != 0 && border_into)                    // the face loop meets `into` before h
            add(row, plane_of_border_edge(th, into, edge_quadric), discontinuity_multiplier);
          add(row, face_quadric, 1.);
          if(border_out)
            add(row, plane_of_border_edge(th, h, edge_quadric), discontinuity_multiplier);
          if(h % 3 == 0 && border_into)                    // ... or after it (h is the face's first halfedge)
            add(row, plane_of_border_edge(th, into, edge_quadric), discontinuity_multiplier);
        }
      }
    });
  }

  // a new level: xyz holds the positions of its rows (the quadrics follow them, see retain())
  void begin_level(const std::vector<double>& xyz) { m_xyz = xyz.data(); }

  // cost of moving row o onto row e
  Optional<double> cost(Index o, Index e) const
  {
    const double* a = quadric(o);
    const double* b = quadric(e);
    const double* x = point(e);
    double s[size];
    for(std::size_t i = 0; i < size; ++i)
      s[i] = a[i] + b[i];
    return Optional<double>(evaluate(s, x));
  }

  void collapse(Index o, Index e)
  {
    const double* a = quadric(o);
    double* b = m_q.data() + size * std::size_t(e);
    for(std::size_t i = 0; i < size; ++i)
      b[i] = a[i] + b[i];
  }

  // keeps the quadrics of the rows for which keep(row) holds, in order: the rows of the next
  // level (the memory follows the level's size; gathered in parallel into a vector of that size)
  template <typename Keep>
  void retain(std::size_t rows, const Keep& keep)
  {
    std::vector<Index> kept;
    for(std::size_t r = 0; r < rows; ++r)
      if(keep(r))
        kept.push_back(static_cast<Index>(r));
    Uninitialized_vector<double> q(size * kept.size());
    parallel_for_blocks(kept.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t j = first; j < last; ++j)
        copy_values(m_q.data() + size * kept[j], size, q.data() + size * j);
    });
    m_q.swap(q);
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

  // the quadric of the plane of the face whose first halfedge is h0; CGAL takes
  // p = target(h), q = target(next(h)), r = source(h) of the face's halfedge
  void plane_of_face(const Triangle_halfedges& th, Index h0, double* out) const
  {
    const double* p = point(th.target[h0]);
    const double* q = point(th.target[h0 + 1]);
    const double* r = point(th.source[h0]);
    double n[3];
    cross_of_differences(q, r, p, n);
    normalize(n);
    outer(n, p, out);
  }

  // the quadric of the plane through the border edge source(h) -> target(h) (a face halfedge
  // without a face across), perpendicular to its face
  const double* plane_of_border_edge(const Triangle_halfedges& th, Index h, double* out) const
  {
    const double* ep = point(th.target[h]);
    const double* eq = point(th.target[Triangle_halfedges::next_in_face(h)]);
    const double* er = point(th.source[h]);
    double fn[3], edge[3], en[3];
    cross_of_differences(eq, er, ep, fn);
    for(int c = 0; c < 3; ++c) edge[c] = ep[c] - er[c];
    cross(edge, fn, en);
    normalize(en);
    outer(en, ep, out);
    return out;
  }

  // as CGAL: a zero vector stays zero (degenerate face: no plane, no quadric)
  static void normalize(double* n)
  {
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if(l != 0.)
      for(int c = 0; c < 3; ++c) n[c] /= l;
  }

  // the quadric of the plane with normal n through x: (n, -n.x)(n, -n.x)^T
  static void outer(const double* n, const double* x, double* out)
  {
    const double r[4] = {n[0], n[1], n[2], -(n[0] * x[0] + n[1] * x[1] + n[2] * x[2])};
    std::size_t k = 0;
    for(int i = 0; i < 4; ++i)
      for(int j = i; j < 4; ++j)
        out[k++] = r[i] * r[j];
  }

  void add(Index v, const double* quadric, double factor)
  {
    double* q = m_q.data() + size * std::size_t(v);
    for(std::size_t i = 0; i < size; ++i)
      q[i] += factor * quadric[i];
  }

  const double* m_xyz = nullptr;  // 3 per row
  Uninitialized_vector<double> m_q;   // 10 coefficients per row
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PLANE_QUADRICS_H
