// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_ROW_RULE_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_ROW_RULE_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

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

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_ROW_RULE_H
