// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_ATTRIBUTE_TRAITS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_ATTRIBUTE_TRAITS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

#include <CGAL/IO/Color.h>
#include <CGAL/Kernel/global_functions.h>
#include <CGAL/number_utils.h>
#include <CGAL/Point_2.h>
#include <CGAL/Point_3.h>
#include <CGAL/Vector_2.h>
#include <CGAL/Vector_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * maps the value type `T` of an attribute channel to a fixed-size array of doubles and back.
 * Relaxation, details and thresholds all work on these arrays; `from_array()` turns a
 * computed array back into a value (clamping and rounding where `T` needs it).
 *
 * The package specialises it for `double`, `float`, `CGAL::Point_2<K>`, `CGAL::Vector_2<K>`,
 * `CGAL::Point_3<K>`, `CGAL::Vector_3<K>`, `std::array<double,N>`, `std::array<float,N>` and
 * `CGAL::IO::Color` (four components r, g, b, alpha in [0,255]; converted back by rounding to
 * the nearest integer and clamping to [0,255], so that no alpha value is lost).
 * Users specialise it for their own types.
 *
 * \cgalModels `AttributeTraits`
 */
template <typename T, typename Enable = void>
struct Attribute_traits;

/// \cond SKIP_IN_MANUAL

template <>
struct Attribute_traits<double>
{
  static constexpr std::size_t dimension = 1;
  static std::array<double, 1> to_array(const double& v) { return {{v}}; }
  static double from_array(const std::array<double, 1>& a) { return a[0]; }
};

template <>
struct Attribute_traits<float>
{
  static constexpr std::size_t dimension = 1;
  static std::array<double, 1> to_array(const float& v) { return {{double(v)}}; }
  static float from_array(const std::array<double, 1>& a) { return float(a[0]); }
};

template <typename K>
struct Attribute_traits<CGAL::Point_3<K> >
{
  static constexpr std::size_t dimension = 3;
  static std::array<double, 3> to_array(const CGAL::Point_3<K>& p)
  { return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}}; }
  static CGAL::Point_3<K> from_array(const std::array<double, 3>& a)
  { return CGAL::Point_3<K>(a[0], a[1], a[2]); }
};

template <typename K>
struct Attribute_traits<CGAL::Vector_3<K> >
{
  static constexpr std::size_t dimension = 3;
  static std::array<double, 3> to_array(const CGAL::Vector_3<K>& p)
  { return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}}; }
  static CGAL::Vector_3<K> from_array(const std::array<double, 3>& a)
  { return CGAL::Vector_3<K>(a[0], a[1], a[2]); }
};

template <typename K>
struct Attribute_traits<CGAL::Point_2<K> >
{
  static constexpr std::size_t dimension = 2;
  static std::array<double, 2> to_array(const CGAL::Point_2<K>& p)
  { return {{CGAL::to_double(p.x()), CGAL::to_double(p.y())}}; }
  static CGAL::Point_2<K> from_array(const std::array<double, 2>& a)
  { return CGAL::Point_2<K>(a[0], a[1]); }
};

template <typename K>
struct Attribute_traits<CGAL::Vector_2<K> >
{
  static constexpr std::size_t dimension = 2;
  static std::array<double, 2> to_array(const CGAL::Vector_2<K>& p)
  { return {{CGAL::to_double(p.x()), CGAL::to_double(p.y())}}; }
  static CGAL::Vector_2<K> from_array(const std::array<double, 2>& a)
  { return CGAL::Vector_2<K>(a[0], a[1]); }
};

template <std::size_t N>
struct Attribute_traits<std::array<double, N> >
{
  static constexpr std::size_t dimension = N;
  static std::array<double, N> to_array(const std::array<double, N>& v) { return v; }
  static std::array<double, N> from_array(const std::array<double, N>& a) { return a; }
};

template <std::size_t N>
struct Attribute_traits<std::array<float, N> >
{
  static constexpr std::size_t dimension = N;
  static std::array<double, N> to_array(const std::array<float, N>& v)
  {
    std::array<double, N> a;
    for(std::size_t i = 0; i < N; ++i) a[i] = double(v[i]);
    return a;
  }
  static std::array<float, N> from_array(const std::array<double, N>& a)
  {
    std::array<float, N> v;
    for(std::size_t i = 0; i < N; ++i) v[i] = float(a[i]);
    return v;
  }
};

template <>
struct Attribute_traits<CGAL::IO::Color>
{
  static constexpr std::size_t dimension = 4;
  static std::array<double, 4> to_array(const CGAL::IO::Color& c)
  { return {{double(c.red()), double(c.green()), double(c.blue()), double(c.alpha())}}; }
  static CGAL::IO::Color from_array(const std::array<double, 4>& a)
  {
    auto to_byte = [](double x) -> unsigned char {
      // NaN maps to 0 (the comparisons below are false for NaN)
      const double r = std::nearbyint(x);
      return static_cast<unsigned char>(r >= 255. ? 255. : (r > 0. ? r : 0.));
    };
    return CGAL::IO::Color(to_byte(a[0]), to_byte(a[1]), to_byte(a[2]), to_byte(a[3]));
  }
};

/// \endcond

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_ATTRIBUTE_TRAITS_H
