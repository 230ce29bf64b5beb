// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_ADAPTIVE_CRITERION_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_ADAPTIVE_CRITERION_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * what decides, in `reconstruct_adaptively()`, which odd vertices are kept.
 */
enum class Adaptive_criterion
{
  /// the paper's rule (Section 4.3): a vertex is kept when its detail length in the guiding
  /// channel reaches the threshold; the detail measures how far the vertex is from its relaxed
  /// prediction (curvature), in the channel's units
  DETAIL_LENGTH,
  /// a vertex is kept when removing it would move the surface by the threshold or more, a
  /// distance in model units: the largest distance from the input vertices it stands for
  /// (itself and those collapsed into it at finer levels) to the faces that replace its star
  /// when it collapses (geometry only)
  APPROXIMATION_ERROR
};

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_ADAPTIVE_CRITERION_H
