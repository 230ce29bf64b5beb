// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSITION_VISITOR_BASE_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSITION_VISITOR_BASE_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

#include <cstddef>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * a visitor of `decompose()` that does nothing: derive from it and override what you need
 * (progress bars, logs, early inspection). The library itself never prints.
 */
struct Decomposition_visitor_base
{
  /// called before level `k` (from \f$ M_k \f$ to \f$ M_{k+1} \f$) is built; `vertices` is \f$ |M_k| \f$.
  /// Return `false` to cancel: `decompose()` then stops and returns the pyramid of the levels
  /// built so far (valid and exact, \f$ M_k \f$ its coarsest mesh). A visitor whose
  /// `on_level_started()` returns `void` never cancels.
  bool on_level_started(std::size_t k, std::size_t vertices) { (void)k; (void)vertices; return true; }
  /// called when level `k` is built: `removed` vertices were collapsed
  void on_level_finished(std::size_t k, std::size_t removed) { (void)k; (void)removed; }
  /// called once at the end with the number of levels \f$ K \f$
  void on_finished(std::size_t levels) { (void)levels; }
};

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSITION_VISITOR_BASE_H
