// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_SCHEME_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_SCHEME_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * the relaxation operators of Roy et al., Section 2. Each one gives, for every vertex \f$ i \f$,
 * weights \f$ \lambda_{ij} \f$ with \f$ \sum_j \lambda_{ij} = 1 \f$ that depend on the geometry only;
 * the relaxed value of any channel \f$ f \f$ is \f$ R f(v_i) = \sum_j \lambda_{ij} f(v_j) \f$ (Eq. 3).
 * The border rule and the rules for degenerate configurations are given in the user manual
 * (section "Robustness rules").
 */
enum class Relaxation_scheme
{
  /// the normalised cotangent weights of Eq. 2 (Meyer et al.), over the 1-ring
  CURVATURE,
  /// Guskov et al.'s minimiser of the squared second-order differences over the 1-ring with flaps (Eq. 1)
  SECOND_ORDER_DIFFERENCE,
  /// the uniform Laplacian, \f$ \lambda_{ij} = 1/\mathrm{valence}(i) \f$
  UNIFORM
};

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_SCHEME_H
