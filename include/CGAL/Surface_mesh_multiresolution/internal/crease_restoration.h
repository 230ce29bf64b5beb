// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CREASE_RESTORATION_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CREASE_RESTORATION_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The last stage of denoise() for the geometry: the pyramid's passes leave sharp creases
// rounded; bilateral filtering of the face normals (Zheng et al. 2011: over the faces sharing
// a vertex with the face, the face itself left out, weights area x spatial Gaussian of the
// centroid distance (sigma_c: the mean distance between the centroids of edge-adjacent
// faces) x range Gaussian of the normal difference, sigma_s = 0.2) followed by vertex updates
// fitting the filtered normals (Sun et al. 2007, 10 of them, from the pyramid's result) makes
// them sharp again. On smooth curved parts it moves the surface away from the data instead, so
// the number of normal iterations stops (at most 40) before the result's RMS distance to the
// noisy input exceeds 1.02 times that of the pyramid's result: creases are restored where the
// data support them. Measured on the standard pairs (user manual, section Denoising).
// Why by hand: no Debian library provides mesh normal filtering.
class Crease_restoration
{
public:
  static constexpr double range_sigma = 0.2;
  static constexpr double allowed_drift = 1.02;
  static constexpr int max_normal_iterations = 40;
  static constexpr int vertex_iterations = 10;

  // F: the faces (3 rows each); noisy and x: 3 doubles per row; x is replaced by the result
  Crease_restoration(const std::vector<Index>& F, std::size_t n) : m_F(F), m_n(n) { build_rings(); }

  void run(const std::vector<double>& noisy, std::vector<double>& x)
  {
    const int e = geometry_scale_exponent(x.data(), x.size());   // exact: computed on 2^-e x
    std::vector<double> start(x.size()), data(noisy.size());
    for(std::size_t i = 0; i < x.size(); ++i) { start[i] = std::scalbn(x[i], -e); data[i] = std::scalbn(noisy[i], -e); }
    const double drift = distance(start, data);
    if(!(drift > 0.) || m_F.empty())
      return;
    face_geometry(start);
    std::vector<double> normals = m_normal, best = start, y;
    for(int it = 1; it <= max_normal_iterations; ++it)
    {
      filter_normals(normals);
      fit_vertices(start, normals, y);
      if(!(distance(y, data) <= allowed_drift * drift))
        break;
      best.swap(y);
    }
    for(std::size_t i = 0; i < x.size(); ++i)
      x[i] = std::scalbn(best[i], e);
  }

private:
  // faces of each vertex, and faces sharing a vertex with each face (CSR)
  void build_rings()
  {
    const std::size_t nf = m_F.size() / 3;
    m_vertex_offsets.assign(m_n + 1, 0);
    for(Index v : m_F) ++m_vertex_offsets[v + 1];
    for(std::size_t v = 0; v < m_n; ++v) m_vertex_offsets[v + 1] += m_vertex_offsets[v];
    m_vertex_faces.resize(m_F.size());
    std::vector<Index> fill(m_vertex_offsets.begin(), m_vertex_offsets.end() - 1);
    for(std::size_t i = 0; i < m_F.size(); ++i) m_vertex_faces[fill[m_F[i]]++] = static_cast<Index>(i / 3);
    m_ring_offsets.assign(1, 0);
    std::vector<Index> ring;
    for(std::size_t f = 0; f < nf; ++f)
    {
      ring.clear();
      for(int k = 0; k < 3; ++k)
      {
        const Index v = m_F[3 * f + k];
        ring.insert(ring.end(), m_vertex_faces.begin() + m_vertex_offsets[v], m_vertex_faces.begin() + m_vertex_offsets[v + 1]);
      }
      std::sort(ring.begin(), ring.end());
      ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      for(Index g : ring)
        if(g != f) m_ring.push_back(g);
      m_ring_offsets.push_back(static_cast<Index>(m_ring.size()));
    }
  }

  // unit normals, areas and centroids of the faces at positions p; sigma_c
  void face_geometry(const std::vector<double>& p)
  {
    const std::size_t nf = m_F.size() / 3;
    m_normal.assign(3 * nf, 0.);
    m_area.assign(nf, 0.);
    m_centroid.assign(3 * nf, 0.);
    for(std::size_t f = 0; f < nf; ++f)
    {
      const double* a = p.data() + 3 * std::size_t(m_F[3 * f]);
      const double* b = p.data() + 3 * std::size_t(m_F[3 * f + 1]);
      const double* c = p.data() + 3 * std::size_t(m_F[3 * f + 2]);
      double nrm[3];
      cross_of_differences(b, c, a, nrm);
      const double l = scaled_length(nrm, 3);
      m_area[f] = l / 2;
      for(int k = 0; k < 3; ++k)
      {
        m_normal[3 * f + k] = l > 0. ? nrm[k] / l : 0.;
        m_centroid[3 * f + k] = (a[k] + b[k] + c[k]) / 3;
      }
    }
    double sum = 0.;
    std::size_t pairs = 0;
    for(std::size_t f = 0; f < nf; ++f)
      for(Index i = m_ring_offsets[f]; i < m_ring_offsets[f + 1]; ++i)
      {
        const Index g = m_ring[i];
        int shared = 0;
        for(int a = 0; a < 3; ++a) for(int b = 0; b < 3; ++b) shared += (m_F[3 * f + a] == m_F[3 * std::size_t(g) + b]) ? 1 : 0;
        if(shared == 2)
        {
          sum += std::sqrt(squared_distance(&m_centroid[3 * f], &m_centroid[3 * std::size_t(g)]));
          ++pairs;
        }
      }
    m_sigma_c = (pairs > 0 && sum > 0.) ? sum / double(pairs) : 1.;
  }

  static double squared_distance(const double* a, const double* b)
  {
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
  }

  // one bilateral filtering step of the face normals
  void filter_normals(std::vector<double>& normals) const
  {
    const std::size_t nf = m_F.size() / 3;
    std::vector<double> out(normals.size());
    const double ic = 1. / (2. * m_sigma_c * m_sigma_c), is = 1. / (2. * range_sigma * range_sigma);
    for(std::size_t f = 0; f < nf; ++f)
    {
      double s[3] = {0., 0., 0.};
      for(Index i = m_ring_offsets[f]; i < m_ring_offsets[f + 1]; ++i)
      {
        const std::size_t g = m_ring[i];
        const double w = m_area[g] * std::exp(-squared_distance(&m_centroid[3 * f], &m_centroid[3 * g]) * ic)
                                   * std::exp(-squared_distance(&normals[3 * f], &normals[3 * g]) * is);
        for(int k = 0; k < 3; ++k) s[k] += w * normals[3 * g + k];
      }
      const double l = scaled_length(s, 3);
      for(int k = 0; k < 3; ++k) out[3 * f + k] = l > 0. ? s[k] / l : normals[3 * f + k];
    }
    normals.swap(out);
  }

  // vertex_iterations updates from `start`: x_v += mean over the faces f of v of n_f (n_f . (c_f - x_v))
  void fit_vertices(const std::vector<double>& start, const std::vector<double>& normals, std::vector<double>& y) const
  {
    const std::size_t nf = m_F.size() / 3;
    y = start;
    std::vector<double> c(3 * nf), next;
    for(int it = 0; it < vertex_iterations; ++it)
    {
      for(std::size_t f = 0; f < nf; ++f)
        for(int k = 0; k < 3; ++k)
          c[3 * f + k] = (y[3 * std::size_t(m_F[3 * f]) + k] + y[3 * std::size_t(m_F[3 * f + 1]) + k] + y[3 * std::size_t(m_F[3 * f + 2]) + k]) / 3;
      next = y;
      for(std::size_t v = 0; v < m_n; ++v)
      {
        const Index b = m_vertex_offsets[v], e = m_vertex_offsets[v + 1];
        if(b == e) continue;
        double d[3] = {0., 0., 0.};
        for(Index i = b; i < e; ++i)
        {
          const std::size_t f = m_vertex_faces[i];
          const double* nf3 = &normals[3 * f];
          const double p = nf3[0] * (c[3 * f] - y[3 * v]) + nf3[1] * (c[3 * f + 1] - y[3 * v + 1]) + nf3[2] * (c[3 * f + 2] - y[3 * v + 2]);
          for(int k = 0; k < 3; ++k) d[k] += p * nf3[k];
        }
        for(int k = 0; k < 3; ++k) next[3 * v + k] += d[k] / double(e - b);
      }
      y.swap(next);
    }
  }

  // RMS distance between two sets of positions
  double distance(const std::vector<double>& a, const std::vector<double>& b) const
  {
    double s = 0.;
    for(std::size_t v = 0; v < m_n; ++v) s += squared_distance(&a[3 * v], &b[3 * v]);
    return m_n > 0 ? std::sqrt(s / double(m_n)) : 0.;
  }

  const std::vector<Index>& m_F;
  std::size_t m_n;
  std::vector<Index> m_vertex_offsets, m_vertex_faces, m_ring_offsets, m_ring;
  std::vector<double> m_normal, m_area, m_centroid;
  double m_sigma_c = 1.;
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CREASE_RESTORATION_H
