// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_DENOISE_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_DENOISE_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/filter.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

template <typename TriangleMesh, typename NamedParameters>
std::size_t chosen_channel(const Pyramid<TriangleMesh>& pyr, const NamedParameters& np, const char* function)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const std::size_t c = choose_parameter(get_parameter(np, internal_np::channel), std::size_t(0));
  if(c >= pyr.number_of_channels())
    throw std::invalid_argument(std::string(function) + ": channel " + std::to_string(c) + " does not exist (the pyramid has "
                                + std::to_string(pyr.number_of_channels()) + ")");
  return c;
}

// Eq. 8 on one vector of dimension dim: zero if |v| <= t, else v - t v/|v|
inline void soft_shrink(double* v, std::size_t dim, double t)
{
  double length = 0.;
  for(std::size_t k = 0; k < dim; ++k) length += v[k] * v[k];
  length = std::sqrt(length);
  const double factor = length > t ? 1. - t / length : 0.;
  for(std::size_t k = 0; k < dim; ++k) v[k] *= factor;
}

// the number of finest detail levels a function acts on: `levels` (default min(5, K))
template <typename TriangleMesh, typename NamedParameters>
std::size_t chosen_levels(const Pyramid<TriangleMesh>& pyr, const NamedParameters& np, const char* function)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const std::size_t K = pyr.number_of_levels();
  const std::size_t n = choose_parameter(get_parameter(np, internal_np::levels), (std::min)(std::size_t(5), K));
  if(n > K)
    throw std::invalid_argument(std::string(function) + ": " + std::to_string(n) + " levels asked, the pyramid has "
                                + std::to_string(K));
  return n;
}

} // namespace internal

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * soft thresholding of the details (Roy et al., Section 4.2, Eq. 8): every detail \f$ d \f$
 * (a vector of the channel's dimension; a number for scalar channels) becomes 0 if
 * \f$ |d| \le t \f$ and \f$ d - t\, d/|d| \f$ otherwise.
 *
 * \param pyr the pyramid, modified
 * \param t the threshold, \f$ t \ge 0 \f$ (\f$ t = 0 \f$ changes nothing, \f$ t = \infty \f$ zeroes the details)
 * \param np optional \ref smr_namedparameters "Named Parameters": `levels` (std::size_t: the number of finest
 *        detail levels \f$ D_1 \ldots \f$ to threshold; default the five finest, or all if fewer) and
 *        `channel` (std::size_t; default 0, the geometry)
 * \throws std::invalid_argument if `t` is negative or NaN, or the levels or the channel do not exist
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
void soft_threshold(Pyramid<TriangleMesh>& pyr, double t, const NamedParameters& np = parameters::default_values())
{
  if(!(t >= 0.))
    throw std::invalid_argument("soft_threshold: the threshold must be non-negative, it is " + std::to_string(t));
  const std::size_t c = internal::chosen_channel(pyr, np, "soft_threshold");
  const std::size_t n = internal::chosen_levels(pyr, np, "soft_threshold");
  const std::size_t dim = pyr.channel_dimension(c);
  for(std::size_t j = 1; j <= n; ++j)
  {
    std::vector<double>& d = pyr.details(j, c);
    for(std::size_t i = 0; i < d.size(); i += dim)
      internal::soft_shrink(d.data() + i, dim, t);
  }
}

/// \cond SKIP_IN_MANUAL
namespace internal {

// The details of a smooth surface are not zero: relaxation shrinks curved regions, so a
// detail carries a smooth part (about the curvature times the squared edge length, along
// the normal) besides the noise. The smooth part is estimated by relaxing the details
// themselves with the level's weights; the residual d - R d is what noise looks like.
// For iid noise of deviation sigma, a residual component has deviation
// sigma * sqrt((1 - lambda_ii)^2 + sum_{j != i} lambda_ij^2), about 1.08 sigma on regular meshes.
template <typename TriangleMesh>
void smooth_part_of_details(const Pyramid<TriangleMesh>& pyr, std::size_t j, std::size_t c, std::vector<double>& smooth)
{
  const std::vector<double>& d = pyr.details(j, c);
  const std::size_t dim = pyr.channel_dimension(c);
  smooth.resize(d.size());
  pyr.levels()[j - 1].weights.apply(d.data(), smooth.data(), dim);
}

template <typename TriangleMesh>
double residual_deviation_factor(const Pyramid<TriangleMesh>& pyr, std::size_t j)
{
  const Sparse_weights& w = pyr.levels()[j - 1].weights;
  double sum = 0.;
  for(std::size_t i = 0; i < w.number_of_rows(); ++i)
  {
    double s = 0., diagonal = 0.;
    for(Index k = w.offsets[i]; k < w.offsets[i + 1]; ++k)
      if(w.columns[k] == i) diagonal += w.values[k]; else s += w.values[k] * w.values[k];
    sum += (1. - diagonal) * (1. - diagonal) + s;
  }
  return w.number_of_rows() > 0 ? std::sqrt(sum / double(w.number_of_rows())) : 1.;
}

} // namespace internal
/// \endcond

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * estimates the standard deviation \f$ \sigma \f$ of the noise of a channel from its finest
 * details \f$ D_1 \f$: the median absolute deviation of their components divided by 0.6745
 * (Donoho's robust estimator; exact for Gaussian noise, insensitive to the few large details
 * of features). The smooth part of the details (relaxation shrinks curved regions, so even a
 * noise-free surface has details, about the curvature times the squared edge length) is
 * taken out first: the estimator sees the residual \f$ d - R d \f$ of the details relaxed with
 * the level's own weights, rescaled to the deviation of one vertex's noise.
 * \param pyr the pyramid
 * \param np optional: `channel` (default 0, the geometry)
 * \returns 0 for a pyramid without levels
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
double estimate_noise(const Pyramid<TriangleMesh>& pyr, const NamedParameters& np = parameters::default_values())
{
  const std::size_t c = internal::chosen_channel(pyr, np, "estimate_noise");
  if(pyr.number_of_levels() == 0 || pyr.details(1, c).empty())
    return 0.;
  std::vector<double> x;
  internal::smooth_part_of_details(pyr, 1, c, x);
  const std::vector<double>& d = pyr.details(1, c);
  for(std::size_t i = 0; i < x.size(); ++i) x[i] = d[i] - x[i];
  const std::size_t mid = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + mid, x.end());
  const double median = x[mid];
  for(double& v : x) v = std::abs(v - median);
  std::nth_element(x.begin(), x.begin() + mid, x.end());
  return x[mid] / 0.6745 / internal::residual_deviation_factor(pyr, 1);
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * denoises a pyramid with no parameter to tune. On the five finest detail levels of the
 * channel, each detail \f$ d \f$ is split into its smooth part \f$ R d \f$ (the details relaxed
 * with the level's weights: what a noise-free curved surface has) and a residual; the
 * residual is soft-thresholded (Eq. 8) at the universal threshold
 * \f$ t = \sigma \sqrt{2 \ln n} \f$ (Donoho and Johnstone), \f$ \sigma \f$ from
 * `estimate_noise()`, \f$ n \f$ the number of input vertices. Thresholding the details
 * themselves (`soft_threshold()`, the paper's rule) also removes the smooth part and shrinks
 * curved regions.
 * \param pyr the pyramid, modified
 * \param np optional: `levels` and `channel` as for `soft_threshold()`
 * \returns the threshold used
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
double denoise(Pyramid<TriangleMesh>& pyr, const NamedParameters& np = parameters::default_values())
{
  if(pyr.number_of_levels() == 0)
    return 0.;
  const std::size_t c = internal::chosen_channel(pyr, np, "denoise");
  const std::size_t n = internal::chosen_levels(pyr, np, "denoise");
  const double sigma = estimate_noise(pyr, np);
  const double t = sigma * std::sqrt(2. * std::log((std::max)(double(pyr.number_of_vertices(0)), 2.)));
  const std::size_t dim = pyr.channel_dimension(c);
  std::vector<double> smooth;
  for(std::size_t j = 1; j <= n; ++j)
  {
    internal::smooth_part_of_details(pyr, j, c, smooth);
    std::vector<double>& d = pyr.details(j, c);
    for(std::size_t i = 0; i < d.size(); ++i)
      d[i] -= smooth[i];
    for(std::size_t i = 0; i < d.size(); i += dim)
      internal::soft_shrink(d.data() + i, dim, t);   // Eq. 8 on the residual
    for(std::size_t i = 0; i < d.size(); ++i)
      d[i] += smooth[i];
  }
  return t;
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_DENOISE_H
