// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_MEMORY_ORDER_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_MEMORY_ORDER_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * the order in which `decompose()` keeps the vertices and faces of a pyramid (named parameter
 * `memory_order`). It changes the speed, not the results that reach the user: `reconstruct()`
 * writes every level with its vertices in increasing input number and level 0 with the input's
 * faces in the input's order, exactly as without it. It does change the pyramid (the rows of every
 * level, hence `vertices(k)`, which then lists input numbers in that order, and the details in the
 * same order) and the floating-point sums of its weights, so two orders give two pyramids, both
 * exact.
 */
enum class Memory_order
{
  /// `SPATIAL` when the input's numbering is scattered (the median span of a face's vertex numbers
  /// above \f$ 32\sqrt{n} \f$) and the mesh has at least 262,144 vertices, else `INPUT`
  AUTOMATIC,
  /// the input's numbering and face order
  INPUT,
  /// faces in the Morton order of their centroids, vertices numbered in the order those faces first name them
  SPATIAL
};

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_MEMORY_ORDER_H
