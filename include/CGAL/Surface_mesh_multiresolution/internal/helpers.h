// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_HELPERS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_HELPERS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// "no vertex / no face / no halfedge" in the index arrays
constexpr Index invalid_index = (std::numeric_limits<Index>::max)();

inline void cross(const double* a, const double* b, double* out)
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// (q - p) x (r - p)
inline void cross_of_differences(const double* q, const double* r, const double* p, double* out)
{
  const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
  cross(u, v, out);
}

// Copies the `dim` values of one vertex. Why by hand: std::copy of 3 doubles was a memmove
// call each (6 % of a decomposition).
template <typename T>
inline void copy_values(const T* from, std::size_t dim, T* to)
{
  if(dim == 3)
  {
    to[0] = from[0]; to[1] = from[1]; to[2] = from[2];
    return;
  }
  for(std::size_t c = 0; c < dim; ++c)
    to[c] = from[c];
}

// The Euclidean length of a vector of `dim` doubles without overflow or underflow of the
// squares (lengths of details of coordinates near 1e300 or 1e-300): the components are
// scaled by a power of two near their largest magnitude first. A power of two scales exactly,
// so lengths of ordinary values are the plain sqrt(sum of squares) bit for bit.
inline double scaled_length(const double* v, std::size_t dim)
{
  double m = 0.;
  for(std::size_t k = 0; k < dim; ++k)
    m = (std::max)(m, std::abs(v[k]));
  if(!(m > 0.) || !std::isfinite(m))
    return m;
  const int e = std::ilogb(m);
  if(e > -500 && e < 500)                          // squares cannot overflow or underflow
  {
    double s = 0.;
    for(std::size_t k = 0; k < dim; ++k) s += v[k] * v[k];
    return std::sqrt(s);
  }
  double s = 0.;
  for(std::size_t k = 0; k < dim; ++k)
  {
    const double x = std::scalbn(v[k], -e);
    s += x * x;
  }
  return std::scalbn(std::sqrt(s), e);
}

// The exponent e such that scaling `values` by 2^-e brings their largest magnitude near 1, or
// 0 when the values are in a range where the geometric computations (cross products, squared
// lengths, quadrics: products of up to four coordinates) can neither overflow nor lose their
// small terms to underflow. Scaling by a power of two is exact (std::scalbn, also for
// subnormal values): weights, costs and normals, which are invariant under scaling (costs
// scale by a constant factor), come out bit for bit the same as without scaling wherever no
// scaling was needed.
inline int geometry_scale_exponent(const double* values, std::size_t count)
{
  double m = 0.;
  for(std::size_t i = 0; i < count; ++i)
    m = (std::max)(m, std::abs(values[i]));
  if(!(m > 0.) || !std::isfinite(m))
    return 0;
  const int e = std::ilogb(m);
  return (e > -60 && e < 60) ? 0 : e;
}

// the coordinates scaled by 2^-geometry_scale_exponent() (a copy only where a scale is needed)
inline const std::vector<double>& geometry_for_computations(const std::vector<double>& xyz, std::vector<double>& scaled)
{
  const int e = geometry_scale_exponent(xyz.data(), xyz.size());
  if(e == 0)
    return xyz;
  scaled.resize(xyz.size());
  for(std::size_t i = 0; i < xyz.size(); ++i)
    scaled[i] = std::scalbn(xyz[i], -e);
  return scaled;
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_HELPERS_H
