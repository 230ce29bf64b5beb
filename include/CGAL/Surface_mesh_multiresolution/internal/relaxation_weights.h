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
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Sparse_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_scheme.h>

#include <CGAL/assertions.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * says which rule produced the weights of one vertex (one row of a relaxation operator);
 * see the user manual, section "Robustness rules".
 */
enum class Relaxation_row_rule : unsigned char
{
  /// the weights of the chosen scheme (Eq. 1, Eq. 2 or the uniform Laplacian)
  SCHEME,
  /// curvature scheme whose negative cotangent weights outweighed the positive ones: negative weights dropped
  CLAMPED_CURVATURE,
  /// second-order-difference scheme without a usable hinge, or ill-conditioned: curvature weights used instead
  CURVATURE_FALLBACK,
  /// no usable weight at all (degenerate neighbourhood): uniform weights over the neighbours
  UNIFORM_FALLBACK,
  /// border vertex: relaxed along the border curve only
  BORDER,
  /// constrained or isolated vertex: \f$ R f(v_i) = f(v_i) \f$
  FIXED
};

namespace internal {

// Connectivity of an indexed triangle mesh needed by the weights, computed once per
// connectivity from the triangle array alone (no halfedge walk): sorted 1-rings in CSR,
// the CSR slot of every directed face edge and of its twin, and the faces on each edge.
struct One_ring_topology
{
  std::size_t n = 0;
  std::vector<Index> offsets, neighbors;     // 1-ring of each row, sorted
  std::vector<Index> corner_slot;            // 3F: slot of b in row a for the face edge a->b
  std::vector<Index> corner_twin;            // 3F: slot of a in row b
  std::vector<Index> slot_opposite;          // per slot (a,b): third vertex of the face holding a->b, or invalid
  std::vector<unsigned char> slot_faces;     // per slot: number of faces on the undirected edge (1: border)

  Index slot(Index a, Index b) const
  {
    const Index* first = neighbors.data() + offsets[a];
    const Index* last = neighbors.data() + offsets[a + 1];
    const Index* it = std::lower_bound(first, last, b);
    CGAL_assertion(it != last && *it == b);
    return static_cast<Index>(it - neighbors.data());
  }

  bool is_border_slot(Index s) const { return slot_faces[s] < 2; }

  void build(std::size_t nv, const std::vector<Index>& triangles)
  {
    n = nv;
    const std::size_t nf = triangles.size() / 3;
    // counting sort of both directions of every face edge, then sort + unique per row
    std::vector<Index> start(n + 1, 0);
    for(std::size_t k = 0; k < 3 * nf; ++k)
      start[triangles[k] + 1] += 2;
    for(std::size_t i = 0; i < n; ++i)
      start[i + 1] += start[i];
    std::vector<Index> fill(start.begin(), start.end() - 1), raw(start[n]);
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k)
      {
        const Index a = triangles[3 * f + k], b = triangles[3 * f + (k + 1) % 3];
        raw[fill[a]++] = b;
        raw[fill[b]++] = a;
      }
    offsets.assign(n + 1, 0);
    neighbors.clear();
    neighbors.reserve(raw.size() / 2 + n);
    for(std::size_t i = 0; i < n; ++i)
    {
      Index* first = raw.data() + start[i];
      Index* last = raw.data() + start[i + 1];
      std::sort(first, last);
      last = std::unique(first, last);
      neighbors.insert(neighbors.end(), first, last);
      offsets[i + 1] = static_cast<Index>(neighbors.size());
    }
    corner_slot.resize(3 * nf);
    corner_twin.resize(3 * nf);
    slot_opposite.assign(neighbors.size(), invalid_index);
    slot_faces.assign(neighbors.size(), 0);
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k)
      {
        const Index a = triangles[3 * f + k], b = triangles[3 * f + (k + 1) % 3], c = triangles[3 * f + (k + 2) % 3];
        const Index s = slot(a, b), t = slot(b, a);
        corner_slot[3 * f + k] = s;
        corner_twin[3 * f + k] = t;
        slot_opposite[s] = c;
        ++slot_faces[s];
        ++slot_faces[t];
      }
  }
};

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
    const double cx = x[1] * y[2] - x[2] * y[1], cy = x[2] * y[0] - x[0] * y[2], cz = x[0] * y[1] - x[1] * y[0];
    return std::sqrt(cx * cx + cy * cy + cz * cz);
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

// Computes the weights of one relaxation operator on an indexed triangle mesh.
// The topology (and, for SOD, the hinge structure) is kept, so that weights for new
// positions on the same connectivity cost only the numeric passes.
class Relaxation_weight_builder
{
public:
  // cotangents are clamped to those of angles in [0.1, 179.9] degrees
  static constexpr double max_cotangent = 572.9572133543033;
  // a curvature row is used as is when its negative mass is at most half its positive mass
  static constexpr double max_negative_ratio = 0.5;
  // a hinge whose triangles are lower than this fraction of the hinge edge is left out of the SOD energy
  static constexpr double min_relative_hinge_height = 1e-3;
  // an SOD row is used when the sum of the absolute values of its weights is at most this
  static constexpr double max_sod_absolute_sum = 4.;

  void set_connectivity(std::size_t n, const std::vector<Index>& triangles)
  {
    m_triangles = &triangles;
    m_topology.build(n, triangles);
    m_hinges.clear();
    m_hinge_pattern_built = false;
  }

  const One_ring_topology& topology() const { return m_topology; }

  // xyz: 3 doubles per row; fixed: nullptr or one flag per row (constrained vertices)
  void build(Relaxation_scheme scheme, const double* xyz, const unsigned char* fixed,
             Sparse_weights& w, std::vector<Relaxation_row_rule>& rules)
  {
    const std::size_t n = m_topology.n;
    w.clear();
    w.columns.reserve(scheme == Relaxation_scheme::SECOND_ORDER_DIFFERENCE ? 3 * m_topology.neighbors.size()
                                                                            : m_topology.neighbors.size());
    w.values.reserve(w.columns.capacity());
    w.offsets.reserve(n + 1);
    rules.assign(n, Relaxation_row_rule::SCHEME);

    if(scheme != Relaxation_scheme::UNIFORM)
      accumulate_cotangents(xyz);
    if(scheme == Relaxation_scheme::SECOND_ORDER_DIFFERENCE)
      accumulate_second_order_differences(xyz);

    for(std::size_t i = 0; i < n; ++i)
    {
      const Index b = m_topology.offsets[i], e = m_topology.offsets[i + 1];
      if(b == e || (fixed != nullptr && fixed[i]))
      {
        push(w, static_cast<Index>(i), 1.);
        rules[i] = Relaxation_row_rule::FIXED;
      }
      else if(is_border_vertex(i))
      {
        border_row(scheme, i, xyz, w);
        rules[i] = Relaxation_row_rule::BORDER;
      }
      else if(scheme == Relaxation_scheme::UNIFORM)
        uniform_row(i, w);
      else if(scheme == Relaxation_scheme::CURVATURE)
        rules[i] = curvature_row(i, w);
      else
      {
        if(!sod_row(i, w))
        {
          const Relaxation_row_rule r = curvature_row(i, w);
          rules[i] = (r == Relaxation_row_rule::SCHEME) ? Relaxation_row_rule::CURVATURE_FALLBACK : r;
        }
      }
      w.offsets.push_back(static_cast<Index>(w.columns.size()));
    }
  }

private:
  static void push(Sparse_weights& w, Index j, double v) { w.columns.push_back(j); w.values.push_back(v); }

  bool is_border_vertex(std::size_t i) const
  {
    for(Index s = m_topology.offsets[i]; s < m_topology.offsets[i + 1]; ++s)
      if(m_topology.is_border_slot(s))
        return true;
    return false;
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

  // m_slot_weight[s] = cot(alpha) + cot(beta) for the edge of slot s (one term on border edges)
  void accumulate_cotangents(const double* xyz)
  {
    const std::vector<Index>& tri = *m_triangles;
    const std::size_t nf = tri.size() / 3;
    m_slot_weight.assign(m_topology.neighbors.size(), 0.);
    for(std::size_t f = 0; f < nf; ++f)
    {
      const double* p[3] = {xyz + 3 * std::size_t(tri[3 * f]), xyz + 3 * std::size_t(tri[3 * f + 1]),
                            xyz + 3 * std::size_t(tri[3 * f + 2])};
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
        // angle at corner k+2, opposite the edge p[k] -> p[k+1]: between -e[k+1] and e[k+2]
        const double* u = e[(k + 1) % 3];
        const double* v = e[(k + 2) % 3];
        const double dot = -(u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
        const double cot = clamped_cotangent(dot, double_area);
        m_slot_weight[m_topology.corner_slot[3 * f + k]] += cot;
        m_slot_weight[m_topology.corner_twin[3 * f + k]] += cot;
      }
    }
  }

  void uniform_row(std::size_t i, Sparse_weights& w) const
  {
    const Index b = m_topology.offsets[i], e = m_topology.offsets[i + 1];
    const double v = 1. / double(e - b);
    for(Index s = b; s < e; ++s)
      push(w, m_topology.neighbors[s], v);
  }

  Relaxation_row_rule curvature_row(std::size_t i, Sparse_weights& w) const
  {
    const Index b = m_topology.offsets[i], e = m_topology.offsets[i + 1];
    double positive = 0., negative = 0.;
    for(Index s = b; s < e; ++s)
    {
      const double x = m_slot_weight[s];
      if(x > 0.) positive += x; else negative -= x;
    }
    if(positive > 0. && negative <= max_negative_ratio * positive)
    {
      const double inv = 1. / (positive - negative);
      for(Index s = b; s < e; ++s)
        push(w, m_topology.neighbors[s], m_slot_weight[s] * inv);
      return Relaxation_row_rule::SCHEME;
    }
    if(positive > 0.)
    {
      const double inv = 1. / positive;
      for(Index s = b; s < e; ++s)
        push(w, m_topology.neighbors[s], m_slot_weight[s] > 0. ? m_slot_weight[s] * inv : 0.);
      return Relaxation_row_rule::CLAMPED_CURVATURE;
    }
    uniform_row(i, w);
    return Relaxation_row_rule::UNIFORM_FALLBACK;
  }

  // Border vertices move along the border curve: weights over the border neighbours,
  // inversely proportional to the edge lengths (linear interpolation by arc length, which
  // reproduces straight borders; this is also the minimiser of the curve's second-order
  // difference at the vertex), uniform for the UNIFORM scheme or when an edge has zero length.
  void border_row(Relaxation_scheme scheme, std::size_t i, const double* xyz, Sparse_weights& w) const
  {
    const Index b = m_topology.offsets[i], e = m_topology.offsets[i + 1];
    const std::size_t first = w.columns.size();
    double total = 0.;
    bool uniform = (scheme == Relaxation_scheme::UNIFORM);
    for(Index s = b; s < e; ++s)
    {
      if(!m_topology.is_border_slot(s))
        continue;
      const Index j = m_topology.neighbors[s];
      double l = 0.;
      for(int c = 0; c < 3; ++c)
        l += (xyz[3 * j + c] - xyz[3 * i + c]) * (xyz[3 * j + c] - xyz[3 * i + c]);
      l = std::sqrt(l);
      if(!(l > 0.))
        uniform = true;
      const double x = uniform ? 1. : 1. / l;
      push(w, j, x);
      total += x;
    }
    const std::size_t count = w.columns.size() - first;
    for(std::size_t k = first; k < w.columns.size(); ++k)
      w.values[k] = uniform ? 1. / double(count) : w.values[k] / total;
  }

  // ---- second-order differences (see second_order_difference_coefficients()) ----
  void build_hinges()
  {
    const std::vector<Index>& tri = *m_triangles;
    const std::size_t nf = tri.size() / 3;
    m_hinges.clear();
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k)
      {
        const Index a = tri[3 * f + k], b = tri[3 * f + (k + 1) % 3], c = tri[3 * f + (k + 2) % 3];
        if(a > b)
          continue;                                   // each undirected edge once
        const Index d = m_topology.slot_opposite[m_topology.corner_twin[3 * f + k]];
        if(d == invalid_index || d == c)
          continue;                                   // border edge (or a doubled triangle): no hinge
        m_hinges.push_back({{a, b, c, d}});
      }
    // pattern of the SOD rows: every pair of vertices sharing a hinge
    const std::size_t n = m_topology.n;
    std::vector<Index> start(n + 1, 0);
    for(const auto& h : m_hinges)
      for(int i = 0; i < 4; ++i)
        start[h[i] + 1] += 3;
    for(std::size_t i = 0; i < n; ++i)
      start[i + 1] += start[i];
    std::vector<Index> fill(start.begin(), start.end() - 1), raw(start[n]);
    for(const auto& h : m_hinges)
      for(int i = 0; i < 4; ++i)
        for(int k = 0; k < 4; ++k)
          if(k != i)
            raw[fill[h[i]]++] = h[k];
    m_sod_offsets.assign(n + 1, 0);
    m_sod_columns.clear();
    for(std::size_t i = 0; i < n; ++i)
    {
      Index* first = raw.data() + start[i];
      Index* last = raw.data() + start[i + 1];
      std::sort(first, last);
      last = std::unique(first, last);
      m_sod_columns.insert(m_sod_columns.end(), first, last);
      m_sod_offsets[i + 1] = static_cast<Index>(m_sod_columns.size());
    }
    m_hinge_slots.resize(12 * m_hinges.size());
    for(std::size_t h = 0; h < m_hinges.size(); ++h)
    {
      int q = 0;
      for(int i = 0; i < 4; ++i)
        for(int k = 0; k < 4; ++k)
          if(k != i)
          {
            const Index* first = m_sod_columns.data() + m_sod_offsets[m_hinges[h][i]];
            const Index* last = m_sod_columns.data() + m_sod_offsets[m_hinges[h][i] + 1];
            m_hinge_slots[12 * h + q++] = static_cast<Index>(std::lower_bound(first, last, m_hinges[h][k]) - m_sod_columns.data());
          }
    }
    m_hinge_pattern_built = true;
  }

  void accumulate_second_order_differences(const double* xyz)
  {
    if(!m_hinge_pattern_built)
      build_hinges();
    m_sod_sum.assign(m_sod_columns.size(), 0.);
    for(std::size_t h = 0; h < m_hinges.size(); ++h)
    {
      const double* p1 = xyz + 3 * std::size_t(m_hinges[h][0]);
      const double* p2 = xyz + 3 * std::size_t(m_hinges[h][1]);
      const double* p3 = xyz + 3 * std::size_t(m_hinges[h][2]);
      const double* p4 = xyz + 3 * std::size_t(m_hinges[h][3]);
      double coef[4];
      if(!second_order_difference_coefficients(p1, p2, p3, p4, min_relative_hinge_height, coef))
        continue;
      int q = 0;
      for(int i = 0; i < 4; ++i)
        for(int k = 0; k < 4; ++k)
          if(k != i)
            m_sod_sum[m_hinge_slots[12 * h + q++]] -= coef[i] * coef[k];
    }
  }

  // lambda_ij = -sum_e c_ei c_ej / sum_e c_ei^2; the denominator equals the row sum of the
  // numerators (the coefficients of a hinge sum to 0), which is used so that the weights sum to 1.
  bool sod_row(std::size_t i, Sparse_weights& w) const
  {
    const Index b = m_sod_offsets[i], e = m_sod_offsets[i + 1];
    double sum = 0., abs_sum = 0.;
    for(Index s = b; s < e; ++s) { sum += m_sod_sum[s]; abs_sum += std::abs(m_sod_sum[s]); }
    if(!(sum > 0.) || !std::isfinite(sum) || !(abs_sum <= max_sod_absolute_sum * sum))
      return false;
    const double inv = 1. / sum;
    for(Index s = b; s < e; ++s)
      push(w, m_sod_columns[s], m_sod_sum[s] * inv);
    return true;
  }

  const std::vector<Index>* m_triangles = nullptr;
  One_ring_topology m_topology;
  std::vector<double> m_slot_weight;
  // SOD
  bool m_hinge_pattern_built = false;
  std::vector<std::array<Index, 4> > m_hinges;
  std::vector<Index> m_sod_offsets, m_sod_columns, m_hinge_slots;
  std::vector<double> m_sod_sum;
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_RELAXATION_WEIGHTS_H
