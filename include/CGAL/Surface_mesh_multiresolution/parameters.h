// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_PARAMETERS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_PARAMETERS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/// \cond SKIP_IN_MANUAL
namespace internal_np {
#define CGAL_SMR_add_named_parameter(X, Y, Z) enum X { Y };
#include <CGAL/Surface_mesh_multiresolution/internal/parameters_interface.h>
#undef CGAL_SMR_add_named_parameter
} // namespace internal_np
/// \endcond

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * A sequence of named parameters that knows both CGAL's parameters and the ones of this
 * package, so that they chain in any order:
 * `SMR::parameters::relaxation_scheme(s).vertex_point_map(vpm).number_of_iterations(3)`.
 *
 * It derives from `CGAL::Named_function_parameters`, so every CGAL function accepts it.
 * CGAL functions whose overloads are told apart by the exact pack type (e.g. the IO
 * functions) need `parameters::to_cgal(np)`.
 */
template <typename T, typename Tag, typename Base = CGAL::internal_np::No_property>
struct Named_function_parameters
  : public CGAL::Named_function_parameters<T, Tag, Base>
{
  /// \cond SKIP_IN_MANUAL
  typedef CGAL::Named_function_parameters<T, Tag, Base>  Cgal_np;
  typedef Named_function_parameters<T, Tag, Base>        self;
  // `base` is deliberately not redeclared: CGAL's lookup walks the `base` chain.

  Named_function_parameters() : Cgal_np() {}
  Named_function_parameters(const T& v) : Cgal_np(v) {}
  Named_function_parameters(const T& v, const Base& b) : Cgal_np(v, b) {}

#define CGAL_add_named_parameter(X, Y, Z)                                         \
  template <typename K>                                                           \
  Named_function_parameters<K, CGAL::internal_np::X, self> Z(const K& k) const    \
  { return Named_function_parameters<K, CGAL::internal_np::X, self>(k, *this); }
#include <CGAL/STL_Extension/internal/parameters_interface.h>
#undef CGAL_add_named_parameter

#define CGAL_SMR_add_named_parameter(X, Y, Z)                                     \
  template <typename K>                                                           \
  Named_function_parameters<K, internal_np::X, self> Z(const K& k) const          \
  { return Named_function_parameters<K, internal_np::X, self>(k, *this); }
#include <CGAL/Surface_mesh_multiresolution/internal/parameters_interface.h>
#undef CGAL_SMR_add_named_parameter
  /// \endcond
};

namespace parameters {

/// \cond SKIP_IN_MANUAL
using CGAL::parameters::choose_parameter;
using CGAL::parameters::get_parameter;
using CGAL::parameters::get_parameter_reference;
using CGAL::parameters::is_default_parameter;

typedef Named_function_parameters<bool, CGAL::internal_np::all_default_t> Default_named_parameters;

inline Default_named_parameters default_values() { return Default_named_parameters(); }

#define CGAL_add_named_parameter(X, Y, Z)                                         \
  template <typename K>                                                           \
  Named_function_parameters<K, CGAL::internal_np::X> Z(const K& k)                \
  { return Named_function_parameters<K, CGAL::internal_np::X>(k); }
#include <CGAL/STL_Extension/internal/parameters_interface.h>
#undef CGAL_add_named_parameter

#define CGAL_SMR_add_named_parameter(X, Y, Z)                                     \
  template <typename K>                                                           \
  Named_function_parameters<K, internal_np::X> Z(const K& k)                      \
  { return Named_function_parameters<K, internal_np::X>(k); }
#include <CGAL/Surface_mesh_multiresolution/internal/parameters_interface.h>
#undef CGAL_SMR_add_named_parameter
/// \endcond

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * returns `np` seen as a plain `CGAL::Named_function_parameters`, for the few CGAL
 * functions whose overloads are told apart by the exact pack type (the IO functions,
 * `PMP::area(tm, np)`).
 */
template <typename T, typename Tag, typename Base>
const CGAL::Named_function_parameters<T, Tag, Base>&
to_cgal(const CGAL::Named_function_parameters<T, Tag, Base>& np) { return np; }

} // namespace parameters

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_PARAMETERS_H
