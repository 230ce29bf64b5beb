// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_COLLAPSE_COST_MODELS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_COLLAPSE_COST_MODELS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Halfedge_collapse_cost_adapter.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Plane_quadrics.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Triangle_halfedges.h>

#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>

#include <type_traits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The two cost models of the decomposition's half-edge collapses, side by side. Both have
// the interface the decomposition drives, in the rows of the current level M_k:
//
//   Model(tm, vpm, vim, indexed_mesh, gt, user_get_cost)   once, on the input
//   initialize(halfedges_of_M0, faces_of_M0, xyz_of_M0)     once, on M_0 (rows = input numbers;
//                                                          the halfedges' ends need not be listed)
//   begin_level(rows_to_vertices, xyz)                      per level: input number and
//                                                           position of every row of M_k
//   cost(o, e)                                              Optional<double>: the cost of
//                                                           moving row o onto row e (empty: refused)
//   next_level(accepted, even_rows, next_row)               a level's accepted collapses
//                                                           ({o, e} each) made; even_rows:
//                                                           the rows of M_k that stay, in
//                                                           increasing order (the rows of
//                                                           M_{k+1}), next_row: the row of
//                                                           M_{k+1} of every even row of M_k
//
// - Plane_quadric_collapse_cost: CGAL's default GarlandHeckbert_plane_policies, evaluated on
//   index arrays (Plane_quadrics.h): no halfedge mesh, quadrics stored by row.
// - Sms_collapse_cost: any other SMS `GetCost`, through SMS edge profiles on a working copy
//   of the input that follows the accepted collapses (Halfedge_collapse_cost_adapter.h).
// Collapse_cost_model<TriangleMesh, GeomTraits, GetCost> picks the one for a policy.

template <typename GetCost>
struct Is_plane_quadric_policy : std::false_type {};
template <typename TriangleMesh, typename GeomTraits>
struct Is_plane_quadric_policy<CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<TriangleMesh, GeomTraits> >
  : std::true_type {};

struct Plane_quadric_collapse_cost : Plane_quadrics
{
  template <typename TriangleMesh, typename VertexPointMap, typename VertexIndexMap, typename GeomTraits, typename UserCost>
  Plane_quadric_collapse_cost(const TriangleMesh&, VertexPointMap, VertexIndexMap, const Indexed_mesh<TriangleMesh>&,
                              const GeomTraits&, const UserCost&) {}

  void begin_level(const std::vector<Index>&, const std::vector<double>& xyz) { Plane_quadrics::begin_level(xyz); }
};

template <typename TriangleMesh, typename GeomTraits, typename GetCost>
using Collapse_cost_model = std::conditional_t<Is_plane_quadric_policy<GetCost>::value, Plane_quadric_collapse_cost,
                                               Sms_collapse_cost<TriangleMesh, GeomTraits, GetCost> >;

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_COLLAPSE_COST_MODELS_H
