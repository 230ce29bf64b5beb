// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors

// List of the named parameters of Surface_mesh_multiresolution.
// No include guard on purpose: this file is included several times with different
// definitions of CGAL_SMR_add_named_parameter(X, Y, Z), exactly like
// <CGAL/STL_Extension/internal/parameters_interface.h>.
//   X: tag type, Y: tag value, Z: function name
// Parameters whose meaning already exists in CGAL (vertex_point_map, geom_traits,
// number_of_iterations, vertex_is_constrained_map, visitor, get_cost, ...) are NOT
// repeated here: the package reads CGAL's own tags.
CGAL_SMR_add_named_parameter(relaxation_scheme_t, relaxation_scheme, relaxation_scheme)
CGAL_SMR_add_named_parameter(relax_geometry_t, relax_geometry, relax_geometry)
CGAL_SMR_add_named_parameter(vertex_attribute_maps_t, vertex_attribute_maps, vertex_attribute_maps)
CGAL_SMR_add_named_parameter(minimum_number_of_vertices_t, minimum_number_of_vertices, minimum_number_of_vertices)
CGAL_SMR_add_named_parameter(number_of_levels_t, number_of_levels, number_of_levels)
CGAL_SMR_add_named_parameter(level_t, level, level)
CGAL_SMR_add_named_parameter(levels_t, levels, levels)
CGAL_SMR_add_named_parameter(channel_t, channel, channel)
CGAL_SMR_add_named_parameter(target_number_of_vertices_t, target_number_of_vertices, target_number_of_vertices)
CGAL_SMR_add_named_parameter(keep_connectivity_t, keep_connectivity, keep_connectivity)
CGAL_SMR_add_named_parameter(adaptive_criterion_t, adaptive_criterion, adaptive_criterion)
CGAL_SMR_add_named_parameter(remove_isolated_vertices_t, remove_isolated_vertices, remove_isolated_vertices)
CGAL_SMR_add_named_parameter(memory_order_t, memory_order, memory_order)
