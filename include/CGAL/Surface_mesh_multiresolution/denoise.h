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
#include <CGAL/Surface_mesh_multiresolution/internal/crease_restoration.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_transform.h>
#include <CGAL/Surface_mesh_multiresolution/internal/relaxation_weights.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_weights.h>
#include <CGAL/Surface_mesh_multiresolution/decompose.h>
#include <CGAL/Surface_mesh_multiresolution/Denoising_visitor_base.h>
#include <CGAL/Surface_mesh_multiresolution/filter.h>
#include <CGAL/Surface_mesh_multiresolution/reconstruct.h>
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
  const double length = scaled_length(v, dim);
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
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{levels}
 *     \cgalParamDescription{the number of finest detail levels \f$ D_1 \ldots \f$ to threshold}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{the five finest\, or all if fewer}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{channel}
 *     \cgalParamDescription{the channel whose details are thresholded (0: the geometry)}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{`0`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
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
    const Detail_view d = pyr.details(j, c);
    for(std::size_t i = 0; i < d.size(); i += dim)
      internal::soft_shrink(d.data() + i, dim, t);
  }
}

/// \cond SKIP_IN_MANUAL
namespace internal {

// Rescaling of the noise seen in the residual d - R d = (I - R)^2 f of the finest details: for
// iid noise of deviation sigma, a residual component has deviation sigma times the norm of
// its row of (I - R)^2; this is the root mean square of that norm over the rows (about 1.5
// for uniform weights on a regular mesh), computed row by row with a scratch array
// (O(n valence^2)).
inline double residual_noise_factor(const Sparse_weights& w)
{
  const std::size_t n = w.number_of_rows();
  if(n == 0)
    return 1.;
  std::vector<double> row(n, 0.);   // row i of (I - R)^2
  std::vector<char> seen(n, 0);
  std::vector<Index> touched;
  double sum = 0.;
  for(std::size_t i = 0; i < n; ++i)
  {
    touched.clear();
    auto add = [&](Index j, double v) { if(!seen[j]) { seen[j] = 1; touched.push_back(j); } row[j] += v; };
    // (I - R)^2 = I - 2 R + R R
    add(static_cast<Index>(i), 1.);
    for(Index k = w.offsets[i]; k < w.offsets[i + 1]; ++k)
    {
      add(w.columns[k], -2. * w.values[k]);
      const Index j = w.columns[k];
      for(Index l = w.offsets[j]; l < w.offsets[j + 1]; ++l)
        add(w.columns[l], w.values[k] * w.values[l]);
    }
    for(Index j : touched) { sum += row[j] * row[j]; row[j] = 0.; seen[j] = 0; }
  }
  return std::sqrt(sum / double(n));
}

// Donoho's robust deviation: median absolute deviation / 0.6745 (x is reordered)
inline double median_absolute_deviation(std::vector<double>& x)
{
  if(x.empty())
    return 0.;
  const std::size_t mid = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + mid, x.end());
  const double median = x[mid];
  for(double& v : x) v = std::abs(v - median);
  std::nth_element(x.begin(), x.begin() + mid, x.end());
  return x[mid] / 0.6745;
}

// Unit vertex normals of M_0 (rows = input vertices) computed on the positions relaxed once
// with the level's weights: the noise of the input turns the plain normals around, one
// relaxation step makes them follow the surface. A vertex whose faces have no area gets a
// zero normal (its detail is then left as it is).
inline void smoothed_vertex_normals(const Sparse_weights& w, const std::vector<double>& x, const std::vector<Index>& F,
                                    std::vector<double>& normals)
{
  std::vector<double> scaled, y(x.size());
  w.apply(geometry_for_computations(x, scaled).data(), y.data(), 3);   // normals do not depend on the scale
  normals.assign(x.size(), 0.);
  for(std::size_t i = 0; i + 2 < F.size(); i += 3)
  {
    const double* a = &y[std::size_t(F[i]) * 3];
    const double* b = &y[std::size_t(F[i + 1]) * 3];
    const double* c = &y[std::size_t(F[i + 2]) * 3];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};   // 2 area x normal
    for(std::size_t k = 0; k < 3; ++k)
      for(std::size_t j = 0; j < 3; ++j)
        normals[std::size_t(F[i + k]) * 3 + j] += n[j];
  }
  for(std::size_t i = 0; i < normals.size(); i += 3)
  {
    const double l = std::sqrt(normals[i] * normals[i] + normals[i + 1] * normals[i + 1] + normals[i + 2] * normals[i + 2]);
    for(std::size_t j = 0; j < 3; ++j)
      normals[i + j] = (l > 0. && std::isfinite(l)) ? normals[i + j] / l : 0.;
  }
}

// The noise deviation seen in the details d of M_0 (rows = input vertices) of a channel.
// Geometry (normals given): the normal components of the residual d - R d (the smooth part
// R d of the details, about the curvature times the squared edge length, is taken out; it is
// signal, not noise). Other channels: all components of that residual.
// `factor` is residual_noise_factor(w), which depends on the weights only.
inline double noise_of_finest_details(const Sparse_weights& w, double factor, const std::vector<double>& d, std::size_t dim,
                                      const std::vector<double>* normals)
{
  std::vector<double> smooth(d.size());
  w.apply(d.data(), smooth.data(), dim);
  std::vector<double> x;
  if(normals != nullptr)
  {
    x.resize(d.size() / 3);
    for(std::size_t i = 0; i < x.size(); ++i)
    {
      double s = 0.;
      for(std::size_t j = 0; j < 3; ++j)
        s += (d[i * 3 + j] - smooth[i * 3 + j]) * (*normals)[i * 3 + j];
      x[i] = s;
    }
  }
  else
  {
    x.resize(d.size());
    for(std::size_t i = 0; i < x.size(); ++i)
      x[i] = d[i] - smooth[i];
  }
  return median_absolute_deviation(x) / factor;
}

// The finest level of the pyramid with uniform weights on its connectivity (rows of M_0 =
// input vertices): on a noisy mesh the cotangent and SOD weights follow the noise, the
// uniform ones do not. Used to measure and to remove noise.
template <typename TriangleMesh>
void uniform_finest_level(const Pyramid<TriangleMesh>& pyr, const std::vector<double>& positions, const std::vector<Index>& F,
                          Pyramid_level& finest)
{
  const Pyramid_level& level = pyr.levels()[0];   // what the analysis and synthesis of M_0 read
  finest = Pyramid_level();
  finest.vertices = level.vertices;
  finest.odd_rows = level.odd_rows;
  finest.even_rows = level.even_rows;
  finest.collapse_targets = level.collapse_targets;
  std::vector<double> scaled;
  Relaxation_weight_builder builder;
  std::vector<Relaxation_row_rule> rules;
  builder.set_connectivity(positions.size() / 3, F);
  builder.build(Relaxation_scheme::UNIFORM, geometry_for_computations(positions, scaled).data(), nullptr, finest.weights, rules);
}

// one step of denoise(): every detail moved towards its soft-thresholded value (Eq. 8) with `gain`
inline void shrink_details_towards_threshold(std::vector<double>& d, std::size_t dim, double t, double gain)
{
  std::vector<double> shrunk(dim);
  for(std::size_t i = 0; i < d.size(); i += dim)
  {
    double* v = d.data() + i;
    copy_values(v, dim, shrunk.data());
    soft_shrink(shrunk.data(), dim, t);
    for(std::size_t k = 0; k < dim; ++k)
      v[k] += gain * (shrunk[k] - v[k]);
  }
}

// Channel c of the pyramid analysed again from its new values x on M_0 (in M_0's rows): the
// details, corrections and coarsest values then describe x exactly.
template <typename TriangleMesh>
void analyse_again(Pyramid<TriangleMesh>& pyr, std::size_t c, const std::vector<double>& x)
{
  std::vector<std::vector<double> > values(pyr.number_of_channels());
  values[c] = x;
  values_by_input_number(pyr, values);   // (what analyse_levels() reads; the rows may be in the pyramid's own order)
  std::vector<Pyramid_level>& levels = Pyramid_access::levels(pyr);
  analyse_levels(pyr, {c}, values, [&](std::size_t k, std::size_t, std::vector<double>& d, Corrections& corrections) {
    levels[k].details[c].swap(d);
    levels[k].corrections[c].swap(corrections);
  });
  Pyramid_access::coarse_values(pyr)[c] = coarsest_values(pyr, pyr.channel_dimension(c), values[c]);
  Pyramid_access::set_analysis_state(pyr, c, Analysis_state::OF_VALUES);
}

} // namespace internal
/// \endcond

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * estimates the standard deviation \f$ \sigma \f$ of the noise of a channel from its finest
 * details with Donoho's robust estimator: the median absolute deviation divided by 0.6745
 * (exact for Gaussian noise, insensitive to the few large details of features).
 *
 * The finest level is analysed with uniform weights on its connectivity (the cotangent and SOD
 * weights of a noisy mesh follow the noise and hide part of it). The smooth part of the
 * details is taken out: relaxation shrinks curved regions, so even a noise-free surface has
 * details (about the curvature times the squared edge length, along the normal); the
 * estimator sees the residual \f$ d - R d = (I - R)^2 f \f$, rescaled by the exact factor
 * that \f$ (I - R)^2 \f$ applies to independent noise. For the geometry (channel 0) it uses
 * the component of that residual along the vertex normal (normals of the input relaxed
 * once): the result is the deviation of the noise along the normal, in the units of the
 * coordinates. For the other channels it uses all components.
 *
 * Measured on the standard noisy/clean pairs (Gaussian noise along the normals of 0.2 to 0.7
 * mean edge lengths): within 4 % of the deviation of `noisy - clean` up to 0.4 edges.
 * \param pyr the pyramid
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{channel}
 *     \cgalParamDescription{the channel whose noise is estimated (0: the geometry)}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{`0`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 * \returns 0 for a pyramid without levels
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
double estimate_noise(const Pyramid<TriangleMesh>& pyr, const NamedParameters& np = parameters::default_values())
{
  const std::size_t c = internal::chosen_channel(pyr, np, "estimate_noise");
  if(pyr.number_of_levels() == 0 || pyr.details(1, c).empty())
    return 0.;
  std::vector<std::vector<double> > values;
  std::vector<internal::Index> F;
  internal::reconstruct_arrays(pyr, 0, values, F);
  internal::Pyramid_level finest;
  internal::uniform_finest_level(pyr, values[0], F, finest);
  std::vector<double> d, normals;
  std::vector<std::pair<internal::Index, double> > corrections;
  const std::size_t dim = pyr.channel_dimension(c);
  internal::analyse_level(finest, finest.weights, dim, values[c], d, corrections);
  if(c == 0)
    internal::smoothed_vertex_normals(finest.weights, values[0], F, normals);
  return internal::noise_of_finest_details(finest.weights, internal::residual_noise_factor(finest.weights), d, dim,
                                          c == 0 ? &normals : nullptr);
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * denoises one channel of a pyramid with no parameter to tune.
 *
 * The finest level is analysed and synthesised again and again (Eq. 5 to 7 on \f$ M_0 \f$ and
 * \f$ M_1 \f$) with uniform weights on the finest connectivity: on a noisy mesh the
 * cotangent and SOD weights follow the noise, the uniform ones do not. Each pass has two
 * steps, like Taubin's \f$ \lambda | \mu \f$ smoothing: every detail \f$ d \f$ of
 * \f$ D_1 \f$ is moved towards its soft-thresholded value \f$ \delta_t(d) \f$ (Eq. 8) with a
 * gain \f$ \lambda = 0.5 \f$, then away from it with \f$ \mu = -0.53 \f$; the second step
 * undoes the shrinkage of the first on smooth curved parts. The threshold is the universal
 * threshold \f$ t = \sigma \sqrt{2 \ln n} \f$ of Donoho and Johnstone, with \f$ \sigma \f$
 * estimated as in `estimate_noise()` on the current details at every step: as the noise goes
 * down so does the threshold, and details of features, which stay above it, are kept (at most
 * moved by \f$ t \f$). Noise-level details are smoothed; the process settles by itself (the
 * result changes little between 30 and 70 passes on the standard noisy/clean pairs).
 *
 * For the geometry, a last stage restores sharp creases that the passes leave rounded:
 * bilateral filtering of the face normals (range \f$ \sigma = 0.2 \f$) and vertex updates that
 * fit them. Where the filtered normals settle into flat patches (the result stops moving away
 * from the noisy input between 20 and 40 normal iterations: a shape with creases), 40
 * iterations are taken; on curved shapes, which the filter would flatten into facets, at most
 * one (see the user manual, section Denoising).
 *
 * Afterwards the pyramid describes the denoised channel at every level (all levels are
 * analysed again from the result with the pyramid's own weights), so `reconstruct()` gives it
 * back exactly and filters, adaptive reconstruction and `IO::write_pyramid()` see the denoised
 * data.
 *
 * \param pyr the pyramid, modified
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{channel}
 *     \cgalParamDescription{the channel to denoise (0: the geometry)}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{`0`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{number_of_iterations}
 *     \cgalParamDescription{the number of passes (0 changes nothing)}
 *     \cgalParamType{unsigned int}
 *     \cgalParamDefault{`30`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{visitor}
 *     \cgalParamDescription{reports progress per pass and can cancel (the pyramid is then left unchanged and 0 is returned)}
 *     \cgalParamType{a class with the functions of `Denoising_visitor_base`}
 *     \cgalParamDefault{`Denoising_visitor_base()`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 * \returns the threshold of the first step (0 for a pyramid without levels, without passes, or when the visitor cancels)
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
double denoise(Pyramid<TriangleMesh>& pyr, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  if(pyr.number_of_levels() == 0)
    return 0.;
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                             Denoising_visitor_base>::type Visitor;
  const std::size_t c = internal::chosen_channel(pyr, np, "denoise");
  const unsigned int passes = choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 30u);
  Visitor visitor = choose_parameter<Visitor>(get_parameter(np, CGAL::internal_np::visitor));
  if(passes == 0)
    return 0.;
  const std::size_t dim = pyr.channel_dimension(c);
  const std::size_t n0 = pyr.number_of_input_vertices();
  const double universal = std::sqrt(2. * std::log((std::max)(double(n0), 2.)));

  std::vector<std::vector<double> > values;
  std::vector<internal::Index> F;
  internal::reconstruct_arrays(pyr, 0, values, F);
  std::vector<double>& x = values[c];   // the channel on M_0
  const std::vector<double> noisy = (c == 0) ? x : std::vector<double>();
  // the finest level with uniform weights on its connectivity (rows of M_0 = input vertices)
  internal::Pyramid_level finest;
  internal::uniform_finest_level(pyr, values[0], F, finest);
  std::vector<double> d, normals, state, prediction;
  internal::Corrections corrections;
  std::vector<unsigned char> is_odd;
  internal::odd_row_flags(finest, is_odd);
  const double factor = internal::residual_noise_factor(finest.weights);   // the weights do not change
  double first_threshold = -1.;
  for(unsigned int step = 0; step < 2 * passes; ++step)
  {
    if(step % 2 == 0 && !visitor.on_pass(step / 2, passes))
      return 0.;                                     // cancelled: the pyramid is untouched
    internal::analyse_level(finest, finest.weights, dim, x, d, corrections);
    if(c == 0 && step % 2 == 0)   // the normals turn slowly: those of the first step of a pass serve both
      internal::smoothed_vertex_normals(finest.weights, x, F, normals);
    const double t = universal * internal::noise_of_finest_details(finest.weights, factor, d, dim, c == 0 ? &normals : nullptr);
    if(first_threshold < 0.)
      first_threshold = t;
    internal::shrink_details_towards_threshold(d, dim, t, step % 2 == 0 ? 0.5 : -0.53);
    // M_0 from M_1 (whose values are those of x) and the new details
    state = x;
    internal::odd_values_from_targets(finest, dim, state.data());
    internal::synthesize_level(finest, finest.weights, dim, d.data(), {}, is_odd, state, prediction);
    x.swap(state);
  }
  if(c == 0)                            // the geometry: sharp creases back where the data support them
    internal::Crease_restoration(F, n0).run(noisy, x, first_threshold / universal);
  visitor.on_finished(passes);
  internal::analyse_again(pyr, c, x);   // the pyramid now describes the result at every level
  return first_threshold;
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_DENOISE_H
