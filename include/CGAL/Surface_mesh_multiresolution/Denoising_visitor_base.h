// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_DENOISING_VISITOR_BASE_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_DENOISING_VISITOR_BASE_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * a visitor of `denoise()` that does nothing and never cancels: derive from it and override
 * what you need (progress bars, a cancel button). The library itself never prints.
 */
struct Denoising_visitor_base
{
  /// called before pass `pass` (from 0) of `passes`; return `false` to cancel `denoise()`,
  /// which then leaves the pyramid unchanged
  bool on_pass(unsigned int pass, unsigned int passes) { (void)pass; (void)passes; return true; }
  /// called once the passes are done, before the levels are analysed again from the result
  void on_finished(unsigned int passes) { (void)passes; }
};

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_DENOISING_VISITOR_BASE_H
