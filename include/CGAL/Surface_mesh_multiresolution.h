// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_H

/// \file Surface_mesh_multiresolution.h
/// Includes every public header of the package.

#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Attribute_traits.h>
#include <CGAL/Surface_mesh_multiresolution/Memory_order.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_scheme.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_row_rule.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_operator.h>
#include <CGAL/Surface_mesh_multiresolution/relax.h>
#include <CGAL/Surface_mesh_multiresolution/Decomposition_visitor_base.h>
#include <CGAL/Surface_mesh_multiresolution/Denoising_visitor_base.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>
#include <CGAL/Surface_mesh_multiresolution/decompose.h>
#include <CGAL/Surface_mesh_multiresolution/reconstruct.h>
#include <CGAL/Surface_mesh_multiresolution/Adaptive_criterion.h>
#include <CGAL/Surface_mesh_multiresolution/reconstruct_adaptively.h>
#include <CGAL/Surface_mesh_multiresolution/pyramid_io.h>
#include <CGAL/Surface_mesh_multiresolution/filter.h>
#include <CGAL/Surface_mesh_multiresolution/denoise.h>

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_H
