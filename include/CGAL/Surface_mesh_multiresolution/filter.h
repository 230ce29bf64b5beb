// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_FILTER_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_FILTER_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

inline void check_detail_range(std::size_t a, std::size_t b, std::size_t K, const char* function)
{
  if(a < 1 || a > b || b > K)
    throw std::invalid_argument(std::string(function) + ": detail levels " + std::to_string(a) + " to " + std::to_string(b)
                                + " are not a range within D_1 to D_" + std::to_string(K));
}

} // namespace internal

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * multiplies the details \f$ D_j \f$ (`level` = \f$ j \f$, \f$ 1 \le j \le K \f$, \f$ D_1 \f$ the finest) of
 * one channel, or of all channels, by `gain` (Roy et al., Section 4.1). `reconstruct()`
 * then gives the filtered mesh; the pyramid needs no new decomposition to be filtered again
 * (filter a copy to keep the original).
 *
 * \param pyr the pyramid, modified
 * \param level the detail level \f$ j \f$
 * \param gain the factor: 0 removes the band, 1 keeps it, more than 1 enhances it
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{channel}
 *     \cgalParamDescription{the channel to scale (0: the geometry)}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{every channel}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 * \throws std::invalid_argument if `level` or the channel does not exist, or `gain` is not finite
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
void scale_details(Pyramid<TriangleMesh>& pyr, std::size_t level, double gain,
                   const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  if(!std::isfinite(gain))
    throw std::invalid_argument("scale_details: the gain is not finite");
  internal::check_detail_range(level, level, pyr.number_of_levels(), "scale_details");
  const std::size_t all = (std::numeric_limits<std::size_t>::max)();
  const std::size_t channel = choose_parameter(get_parameter(np, internal_np::channel), all);
  if(channel != all && channel >= pyr.number_of_channels())
    throw std::invalid_argument("scale_details: channel " + std::to_string(channel) + " does not exist (the pyramid has "
                                + std::to_string(pyr.number_of_channels()) + ")");
  for(std::size_t c = 0; c < pyr.number_of_channels(); ++c)
    if(channel == all || channel == c)
      for(double& d : pyr.details(level, c))
        d *= gain;
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * low-pass filter (Fig. 5b of the paper): zeroes the details \f$ D_1 \f$ to \f$ D_j \f$ of every channel.
 * \throws std::invalid_argument if \f$ j \f$ is not in \f$ [1, K] \f$
 */
template <typename TriangleMesh>
void low_pass(Pyramid<TriangleMesh>& pyr, std::size_t j)
{
  internal::check_detail_range(1, j, pyr.number_of_levels(), "low_pass");
  for(std::size_t l = 1; l <= j; ++l)
    scale_details(pyr, l, 0.);
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * stop-band filter (Fig. 5c of the paper): zeroes the details \f$ D_a \f$ to \f$ D_b \f$ of every channel.
 * \throws std::invalid_argument unless \f$ 1 \le a \le b \le K \f$
 */
template <typename TriangleMesh>
void stop_band(Pyramid<TriangleMesh>& pyr, std::size_t a, std::size_t b)
{
  internal::check_detail_range(a, b, pyr.number_of_levels(), "stop_band");
  for(std::size_t l = a; l <= b; ++l)
    scale_details(pyr, l, 0.);
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * enhancement filter (Fig. 5d of the paper, `gain` = 2 on \f$ D_6 \f$ to \f$ D_9 \f$): multiplies
 * the details \f$ D_a \f$ to \f$ D_b \f$ of every channel by `gain`.
 * \throws std::invalid_argument unless \f$ 1 \le a \le b \le K \f$ and `gain` is finite
 */
template <typename TriangleMesh>
void enhance(Pyramid<TriangleMesh>& pyr, std::size_t a, std::size_t b, double gain)
{
  internal::check_detail_range(a, b, pyr.number_of_levels(), "enhance");
  for(std::size_t l = a; l <= b; ++l)
    scale_details(pyr, l, gain);
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_FILTER_H
