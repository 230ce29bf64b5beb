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
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>

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
// them sharp again. How far to go is read from the data, with the RMS distance along the
// vertex normals from the noisy input to a result (p_k after k normal iterations, p_0 for the
// pyramid's result):
// - on piecewise smooth shapes with creases the filtered normals settle into flat patches and
//   the result stops moving: p_20 - p_10 <= 0.26 (p_10 - p_0) and p_40 - p_20 <= 0.15
//   (p_20 - p_0) (measured: at most 0.21 and 0.10 on the CAD models, at least 0.31 and 0.22 on
//   the others; curved shapes are mostly told apart after 20 iterations). Then 40 are
//   taken (they sharpen every crease; measured: fandisk 8.9 -> 3.6 degrees, impulsive noise
//   9.5 -> 3.9), and the result guides a filtering of the noisy input's own face normals
//   (guided normal filtering, Zhang et al. 2015: the same filter with the range Gaussian read
//   on the guide's normals, 20 steps, then the vertex fit from the pyramid's result), which
//   recovers what the passes smoothed away (fandisk 3.6 -> 2.9 degrees);
// - on curved shapes they keep flattening the surface into facets and the result keeps moving
//   away from the data. Then at most one mild iteration is taken, when it stays within 0.034
//   sigma of p_0 (sigma: the noise deviation estimated on the input), else none (measured
//   p_1 - p_0: 0.014-0.031 sigma where the step helps, Nicolo 0.031 the highest; 0.036 on the
//   elephant, where it changes nothing, and 0.039 on the armadillo, where it harms).
// Measured on the standard pairs and thresholds chosen between the two kinds of shapes (user
// manual, section Denoising). Why by hand: no Debian library provides mesh normal filtering.
class Crease_restoration
{
public:
  static constexpr double range_sigma = 0.2;
  static constexpr int normal_iterations = 40;
  static constexpr int vertex_iterations = 10;
  static constexpr int guided_iterations = 20;
  static constexpr double early_settled = 0.26; // (p_20 - p_10) / (p_10 - p_0) at most this, and
  static constexpr double settled = 0.15;       // (p_40 - p_20) / (p_20 - p_0) at most this: a creased shape
  static constexpr double mild_step = 0.034;    // p_1 - p_0 at most this times sigma: one iteration kept

  // F: the faces (3 rows each), n the number of rows
  Crease_restoration(const std::vector<Index>& F, std::size_t n) : m_F(F), m_n(n) { build_rings(); }

  // noisy and x: 3 doubles per row; sigma: the noise deviation of the input; x is replaced by
  // the result. Returns the number of normal iterations taken.
  int run(const std::vector<double>& noisy, std::vector<double>& x, double sigma)
  {
    const int e = geometry_scale_exponent(x.data(), x.size());   // exact: computed on 2^-e x
    std::vector<double> start(x.size()), data(noisy.size());
    for(std::size_t i = 0; i < x.size(); ++i) { start[i] = std::scalbn(x[i], -e); data[i] = std::scalbn(noisy[i], -e); }
    sigma = std::scalbn(sigma, -e);
    if(!(sigma > 0.) || m_F.empty())
      return 0;
    face_geometry(start);
    const double p0 = normal_distance(start, data);
    std::vector<double> normals = m_normal, one, y;
    double p10 = 0., p20 = 0.;
    bool creased = true;
    for(int it = 1; it <= normal_iterations && creased; ++it)
    {
      filter_normals(normals);
      if(it == 1)
        fit_vertices(start, normals, one);
      else if(it == normal_iterations / 4)
        p10 = fit_and_measure(start, normals, data, y);
      else if(it == normal_iterations / 2)
      {
        p20 = fit_and_measure(start, normals, data, y);
        creased = p20 - p10 <= early_settled * (p10 - p0);   // curved shapes are told apart here already
      }
    }
    if(creased)
      creased = fit_and_measure(start, normals, data, y) - p20 <= settled * (p20 - p0);
    int taken = 0;
    const std::vector<double>* result = &start;
    std::vector<double> guided;
    if(creased)
    {
      guided_fit(start, data, y, guided);   // the restored shape guides the filtering of the input's normals
      result = &guided;
      taken = normal_iterations;
    }
    else if(normal_distance(one, data) <= p0 + mild_step * sigma) { result = &one; taken = 1; }
    for(std::size_t i = 0; i < x.size(); ++i)
      x[i] = std::scalbn((*result)[i], e);
    return taken;
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

  // unit normals, areas and centroids of the faces at positions p; the spatial weights
  // (area x Gaussian of the centroid distance, sigma_c the mean distance between the
  // centroids of edge-adjacent faces)
  void face_geometry(const std::vector<double>& p)
  {
    const std::size_t nf = m_F.size() / 3;
    face_normals(p, m_normal, &m_area);
    m_centroid.assign(3 * nf, 0.);
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k)
        m_centroid[3 * f + k] = (p[3 * std::size_t(m_F[3 * f]) + k] + p[3 * std::size_t(m_F[3 * f + 1]) + k] + p[3 * std::size_t(m_F[3 * f + 2]) + k]) / 3;
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
    const double sigma_c = (pairs > 0 && sum > 0.) ? sum / double(pairs) : 1.;
    const double ic = 1. / (2. * sigma_c * sigma_c);
    m_spatial.resize(m_ring.size());
    for(std::size_t f = 0; f < nf; ++f)
      for(Index i = m_ring_offsets[f]; i < m_ring_offsets[f + 1]; ++i)
      {
        const std::size_t g = m_ring[i];
        m_spatial[i] = m_area[g] * std::exp(-squared_distance(&m_centroid[3 * f], &m_centroid[3 * g]) * ic);
      }
  }

  // unit normals (zero for a face without area) and, if asked, areas of the faces at positions p
  void face_normals(const std::vector<double>& p, std::vector<double>& normals, std::vector<double>* areas = nullptr) const
  {
    const std::size_t nf = m_F.size() / 3;
    normals.assign(3 * nf, 0.);
    if(areas != nullptr) areas->assign(nf, 0.);
    for(std::size_t f = 0; f < nf; ++f)
    {
      double nrm[3];
      cross_of_differences(&p[3 * std::size_t(m_F[3 * f + 1])], &p[3 * std::size_t(m_F[3 * f + 2])], &p[3 * std::size_t(m_F[3 * f])], nrm);
      const double l = scaled_length(nrm, 3);
      if(areas != nullptr) (*areas)[f] = l / 2;
      for(int k = 0; k < 3; ++k) normals[3 * f + k] = l > 0. ? nrm[k] / l : 0.;
    }
  }

  // Guided filtering of the noisy face normals (the joint bilateral filter of guided normal
  // filtering, Zhang et al. 2015), the range Gaussian read on the guide's normals, which are
  // fixed, so that the weights are computed once; guided_iterations steps, then the vertices
  // fitted from `start`.
  void guided_fit(const std::vector<double>& start, const std::vector<double>& data, const std::vector<double>& guide,
                  std::vector<double>& y) const
  {
    const std::size_t nf = m_F.size() / 3;
    std::vector<double> g, normals;
    face_normals(guide, g);
    face_normals(data, normals);
    std::vector<double> weight(m_ring.size());
    const double is = 1. / (2. * range_sigma * range_sigma);
    parallel_for_blocks(nf, [&](std::size_t first, std::size_t last) {
      for(std::size_t f = first; f < last; ++f)
        for(Index i = m_ring_offsets[f]; i < m_ring_offsets[f + 1]; ++i)
          weight[i] = m_spatial[i] * std::exp(-squared_distance(&g[3 * f], &g[3 * std::size_t(m_ring[i])]) * is);
    }, 2048);
    for(int it = 0; it < guided_iterations; ++it)
      average_over_rings(normals, [&](std::size_t, Index i) { return weight[i]; });
    fit_vertices(start, normals, y);
  }

  static double squared_distance(const double* a, const double* b)
  {
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
  }

  // one bilateral filtering step of the face normals (the spatial weights do not change)
  void filter_normals(std::vector<double>& normals) const
  {
    const double is = 1. / (2. * range_sigma * range_sigma);
    average_over_rings(normals, [&](std::size_t f, Index i) {
      return m_spatial[i] * std::exp(-squared_distance(&normals[3 * f], &normals[3 * std::size_t(m_ring[i])]) * is);
    });
  }

  // every face normal replaced by the normalised sum over its ring of weight(f, i) times the
  // normal of the ring's i-th face (kept when the sum vanishes); the weights read the old normals
  template <typename Weight>
  void average_over_rings(std::vector<double>& normals, const Weight& weight) const
  {
    const std::size_t nf = m_F.size() / 3;
    std::vector<double> out(normals.size());
    parallel_for_blocks(nf, [&](std::size_t first, std::size_t last) {
      for(std::size_t f = first; f < last; ++f)
      {
        double s[3] = {0., 0., 0.};
        for(Index i = m_ring_offsets[f]; i < m_ring_offsets[f + 1]; ++i)
        {
          const double w = weight(f, i);
          for(int k = 0; k < 3; ++k) s[k] += w * normals[3 * std::size_t(m_ring[i]) + k];
        }
        const double l = scaled_length(s, 3);
        for(int k = 0; k < 3; ++k) out[3 * f + k] = l > 0. ? s[k] / l : normals[3 * f + k];
      }
    }, 2048);
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
      parallel_for_blocks(m_n, [&](std::size_t first, std::size_t last) {
        for(std::size_t v = first; v < last; ++v)
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
      });
      y.swap(next);
    }
  }

  // y: the fit of `normals` from `start`; returns its normal_distance to `data`
  double fit_and_measure(const std::vector<double>& start, const std::vector<double>& normals, const std::vector<double>& data,
                         std::vector<double>& y) const
  {
    fit_vertices(start, normals, y);
    return normal_distance(y, data);
  }

  // RMS over the rows of the distance from `data` to the plane through y with y's vertex
  // normal (area weighted): how far the noisy input is from a result, without the tangential
  // moves of the vertices. Rows without a normal are left out.
  double normal_distance(const std::vector<double>& y, const std::vector<double>& data) const
  {
    std::vector<double> vn(3 * m_n, 0.);
    for(std::size_t f = 0; f < m_F.size() / 3; ++f)
    {
      double nrm[3];
      cross_of_differences(&y[3 * std::size_t(m_F[3 * f + 1])], &y[3 * std::size_t(m_F[3 * f + 2])], &y[3 * std::size_t(m_F[3 * f])], nrm);
      for(int k = 0; k < 3; ++k)
        for(int j = 0; j < 3; ++j) vn[3 * std::size_t(m_F[3 * f + k]) + j] += nrm[j];
    }
    double s = 0.;
    std::size_t rows = 0;
    for(std::size_t v = 0; v < m_n; ++v)
    {
      const double l = scaled_length(&vn[3 * v], 3);
      if(!(l > 0.)) continue;
      double p = 0.;
      for(int j = 0; j < 3; ++j) p += vn[3 * v + j] / l * (data[3 * v + j] - y[3 * v + j]);
      s += p * p;
      ++rows;
    }
    return rows > 0 ? std::sqrt(s / double(rows)) : 0.;
  }

  const std::vector<Index>& m_F;
  std::size_t m_n;
  std::vector<Index> m_vertex_offsets, m_vertex_faces, m_ring_offsets, m_ring;
  std::vector<double> m_normal, m_area, m_centroid, m_spatial;
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CREASE_RESTORATION_H
