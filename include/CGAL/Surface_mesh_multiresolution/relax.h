// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAX_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAX_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/channels.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/relaxation_weights.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Surface_mesh_relaxation_rows.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_operator.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_scheme.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/property_map.h>

#include <tuple>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// Rows read from the mesh's own halfedges where its type allows it (Surface_mesh); none here
template <typename TriangleMesh>
struct Mesh_relaxation_rows
{
  explicit Mesh_relaxation_rows(const TriangleMesh&) {}
  static bool usable(const TriangleMesh&) { return false; }
  void check_faces() const {}
  void compute_cotangents(const double*) {}
  void release() {}
  template <typename ApplyRow>
  bool apply_rows(Relaxation_scheme, const double*, const unsigned char*, const ApplyRow&) const { return false; }
};

template <typename Point>
struct Mesh_relaxation_rows<CGAL::Surface_mesh<Point> > : Surface_mesh_relaxation_rows<Point>
{
  explicit Mesh_relaxation_rows(const CGAL::Surface_mesh<Point>& m) : Surface_mesh_relaxation_rows<Point>(m) {}
};

// Everything relax() and relaxation_operator() share: the validated index view of the mesh,
// its coordinates, the constrained flags and the weight builder. With `one_shot` (one set of
// weights, used once: computed as they are applied) on a mesh whose halfedges give the rows
// (Mesh_relaxation_rows), the index view is built only if those rows cannot be used.
template <typename TriangleMesh, typename NamedParameters>
struct Relaxation_setup
{
  typedef typename GetGeomTraits<TriangleMesh, NamedParameters>::type Geom_traits;
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  typedef typename GetInitializedVertexIndexMap<TriangleMesh, NamedParameters>::const_type Vertex_index_map;

  Indexed_mesh<TriangleMesh> mesh;    // (only its vertices while the rows come from the halfedges)
  std::vector<double> xyz;
  std::vector<unsigned char> fixed;   // empty: no constrained vertex
  Relaxation_weight_builder builder;
  Relaxation_scheme scheme;
  Geom_traits gt;

  Relaxation_setup(const TriangleMesh& tm, const NamedParameters& np, bool one_shot = false)
    : m_tm(tm), m_vim(CGAL::get_initialized_vertex_index_map(tm, np)), m_rows(tm)
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    typedef typename GetVertexPointMap<TriangleMesh, NamedParameters>::const_type Vertex_point_map;
    typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::vertex_is_constrained_t, NamedParameters,
              Static_boolean_property_map<vertex_descriptor, false> >::type Vertex_constraint_map;

    gt = choose_parameter<Geom_traits>(get_parameter(np, CGAL::internal_np::geom_traits));
    const Vertex_point_map vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                                  get_const_property_map(CGAL::vertex_point, tm));
    const Vertex_constraint_map vcm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_is_constrained),
                                                       Static_boolean_property_map<vertex_descriptor, false>());
    scheme = choose_parameter(get_parameter(np, internal_np::relaxation_scheme), Relaxation_scheme::CURVATURE);

    m_on_halfedges = one_shot && scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE && m_rows.usable(tm);
    if(m_on_halfedges)
    {
      if(scheme == Relaxation_scheme::UNIFORM)
        m_rows.check_faces();               // (the curvature's cotangent pass checks them)
      mesh.vertices.assign(vertices(tm).begin(), vertices(tm).end());
    }
    else
      build_index_view();
    // the mesh's own points of floating-point coordinates are read in parallel (other maps and
    // number types, e.g. reference-counted exact numbers: one thread, as their users may expect)
    read_coordinates(mesh.vertices, vpm, gt, xyz,
                     std::is_floating_point<typename Geom_traits::FT>::value
                       && std::is_same<Vertex_point_map, typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type>::value);
    if(!std::is_same<Vertex_constraint_map, Static_boolean_property_map<vertex_descriptor, false> >::value)
    {
      fixed.resize(mesh.number_of_vertices());
      for(std::size_t i = 0; i < fixed.size(); ++i)
        fixed[i] = get(vcm, mesh.vertices[i]) ? 1 : 0;
    }
  }

  // the flags of the constrained rows, or nullptr
  const unsigned char* constrained() const { return fixed.empty() ? nullptr : fixed.data(); }

  // the weights on the coordinates brought to a safe range (geometry_for_computations(): exact, weights unchanged)
  template <typename Weights>
  void build(Weights& w, std::vector<Relaxation_row_rule>& rules)
  {
    builder.build(scheme, geometry_for_computations(xyz, m_scaled).data(), constrained(), w, rules);
  }

  // The rows of the weights of the current coordinates handed to apply_row(i, columns,
  // values, length) as they are computed (Relaxation_weight_builder::build_and_apply()), from
  // the halfedges where they can be read there; the same rows either way. Not for SOD.
  template <typename ApplyRow>
  void build_and_apply(const ApplyRow& apply_row)
  {
    const double* g = geometry_for_computations(xyz, m_scaled).data();
    if(m_on_halfedges)
    {
      if(scheme != Relaxation_scheme::UNIFORM)
        m_rows.compute_cotangents(g);
      if(m_rows.apply_rows(scheme, g, constrained(), apply_row))
        return;
      m_on_halfedges = false;               // rows the two paths could pair differently: every row again
      m_rows.release();
      build_index_view();
    }
    builder.build_and_apply(scheme, g, constrained(), apply_row);
  }

private:
  void build_index_view()
  {
    build_indexed_mesh(m_tm, m_vim, mesh);
    builder.set_connectivity(mesh.number_of_vertices(), mesh.triangles);
  }

  const TriangleMesh& m_tm;
  Vertex_index_map m_vim;
  Mesh_relaxation_rows<TriangleMesh> m_rows;
  bool m_on_halfedges = false;
  std::vector<double> m_scaled;
};

} // namespace internal

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * computes the weights of a relaxation operator on `tm` (Roy et al., Section 2), to be
 * applied any number of times to any channel with `Relaxation_operator::apply()`.
 *
 * \tparam TriangleMesh a model of `FaceListGraph`
 * \tparam NamedParameters a sequence of \ref smr_namedparameters "Named Parameters"
 * \param tm a triangle mesh; borders, several components, isolated vertices and degenerate
 *        triangles are valid (see the user manual, "Robustness rules")
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{relaxation_scheme}
 *     \cgalParamDescription{the weights: normalised cotangents (Eq. 2)\, second-order differences (Eq. 1) or uniform}
 *     \cgalParamType{`CGAL::Surface_mesh_multiresolution::Relaxation_scheme`}
 *     \cgalParamDefault{`Relaxation_scheme::CURVATURE`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_point_map}
 *     \cgalParamDescription{a property map associating points to the vertices of `tm`}
 *     \cgalParamType{a class model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::%vertex_descriptor`
 *                    as key type and `%Point_3` as value type}
 *     \cgalParamDefault{`boost::get(CGAL::vertex_point\, tm)`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{geom_traits}
 *     \cgalParamDescription{an instance of a geometric traits class}
 *     \cgalParamType{a class model of `Kernel`}
 *     \cgalParamDefault{a `CGAL::Kernel_traits` compatible with the point type}
 *     \cgalParamExtra{the weights are computed in double precision; exact-construction kernels are not supported}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_is_constrained_map}
 *     \cgalParamDescription{a property map telling which vertices are constrained: their row is
 *                           \f$ R f(v_i) = f(v_i) \f$}
 *     \cgalParamType{a class model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::%vertex_descriptor`
 *                    as key type and `bool` as value type}
 *     \cgalParamDefault{no vertex is constrained}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_index_map}
 *     \cgalParamDescription{a property map associating to each vertex of `tm` a unique index between `0` and `num_vertices(tm) - 1`}
 *     \cgalParamType{a class model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::%vertex_descriptor`
 *                    as key type and `std::size_t` as value type}
 *     \cgalParamDefault{an automatically indexed internal map}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 *
 * \throws std::invalid_argument if a face is not a triangle or a vertex has a non-finite coordinate
 * \returns the operator, rows in the order of `vertices(tm)`
 * \sa `relax()`
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
Relaxation_operator<TriangleMesh>
relaxation_operator(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  internal::Relaxation_setup<TriangleMesh, NamedParameters> setup(tm, np);
  Relaxation_operator<TriangleMesh> R;
  R.set_scheme(setup.scheme);
  setup.build(R.sparse_weights(), R.rules_ref());
  R.vertices_ref() = std::move(setup.mesh.vertices);
  return R;
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * relaxes in place the geometry and/or the attribute channels of `tm`:
 * \f$ f(v_i) \leftarrow \sum_j \lambda_{ij} f(v_j) \f$ for every vertex at once (Eq. 3 of Roy et al.),
 * `number_of_iterations` times.
 *
 * The weights come from the geometry only. When the geometry is relaxed, the weights are
 * recomputed from the current positions before every iteration (each iteration is one
 * relaxation step of the current mesh); otherwise they are computed once. Attribute channels
 * relaxed together with the geometry use the weights of the same iteration.
 *
 * \tparam TriangleMesh a model of `FaceListGraph`
 * \tparam NamedParameters a sequence of \ref smr_namedparameters "Named Parameters"
 * \param tm a triangle mesh
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters": the ones of
 *        `relaxation_operator()` and those listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{number_of_iterations}
 *     \cgalParamDescription{the number of relaxation steps}
 *     \cgalParamType{unsigned int}
 *     \cgalParamDefault{`1`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{relax_geometry}
 *     \cgalParamDescription{whether the vertex positions are relaxed}
 *     \cgalParamType{bool}
 *     \cgalParamDefault{`true`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_attribute_maps}
 *     \cgalParamDescription{the attribute channels to relax\, e.g. `std::make_tuple(color_map\, uv_map)`; a single map is accepted too}
 *     \cgalParamType{a `std::tuple` of class models of `ReadWritePropertyMap` with `boost::graph_traits<TriangleMesh>::%vertex_descriptor`
 *                    as key type and a value type for which `Attribute_traits` is specialised}
 *     \cgalParamDefault{no attribute channel}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{relaxation_scheme}
 *     \cgalParamDescription{as for `relaxation_operator()`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_point_map}
 *     \cgalParamDescription{as for `relaxation_operator()`; the map must be writable}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{geom_traits}
 *     \cgalParamDescription{as for `relaxation_operator()`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_is_constrained_map}
 *     \cgalParamDescription{as for `relaxation_operator()`: constrained vertices keep their position and values}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_index_map}
 *     \cgalParamDescription{as for `relaxation_operator()`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 *
 * \throws std::invalid_argument if a face is not a triangle, or a coordinate or an attribute value is not finite
 * \sa `relaxation_operator()`
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
void relax(TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef typename GetVertexPointMap<TriangleMesh, NamedParameters>::type Vertex_point_map;
  typedef typename GetGeomTraits<TriangleMesh, NamedParameters>::type Geom_traits;

  const internal::Relaxed_channels<NamedParameters> channels(np);
  const bool geometry = channels.geometry;
  const unsigned int iterations = channels.iterations;
  const auto& maps = channels.maps;
  constexpr std::size_t attribute_dimension = internal::Relaxed_channels<NamedParameters>::attribute_dimension;
  // A single step reads its rows from the mesh's own halfedges where it has them; several
  // steps build the index view, whose ring pairing the next steps read (ten steps on the
  // dragon: 0.33-0.36 s, against 0.69 s walking the halfedges at every step)
  internal::Relaxation_setup<TriangleMesh, NamedParameters> setup(tm, np, iterations == 1);
  Vertex_point_map vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                          get_property_map(CGAL::vertex_point, tm));

  std::vector<double> attributes, tmp;
  if(attribute_dimension > 0)
    internal::read_channels(maps, setup.mesh.vertices, attributes);   // validates before anything is written
  if(iterations == 0 || (!geometry && attribute_dimension == 0))
    return;

  if((geometry || iterations == 1) && setup.scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE)
  {
    // every step's weights are used once (new weights for the moved geometry, or one step):
    // applied as they are computed, not stored
    std::vector<double> next_xyz(geometry ? setup.xyz.size() : 0);
    tmp.resize(attributes.size());
    for(unsigned int it = 0; it < iterations; ++it)
    {
      const double* x = setup.xyz.data();
      const double* a = attributes.data();
      double* y = next_xyz.data();
      double* b = tmp.data();
      setup.build_and_apply([&](std::size_t i, const internal::Index* col, const double* val, std::size_t length) {
        if(geometry)
          internal::Sparse_weights::combine(col, val, length, x, y + 3 * i, 3);
        if(attribute_dimension > 0)
          internal::Sparse_weights::combine(col, val, length, a, b + attribute_dimension * i, attribute_dimension);
      });
      if(geometry)
        setup.xyz.swap(next_xyz);
      attributes.swap(tmp);
    }
  }
  else
  {
    internal::Sparse_weights w;
    std::vector<Relaxation_row_rule> rules;
    for(unsigned int it = 0; it < iterations; ++it)
    {
      if(it == 0 || geometry)
        setup.build(w, rules);
      if(geometry)
      {
        tmp.resize(setup.xyz.size());
        w.apply(setup.xyz.data(), tmp.data(), 3);
        setup.xyz.swap(tmp);
      }
      if(attribute_dimension > 0)
      {
        tmp.resize(attributes.size());
        w.apply(attributes.data(), tmp.data(), attribute_dimension);
        attributes.swap(tmp);
      }
    }
  }
  if(geometry)
    internal::write_coordinates(setup.mesh.vertices, vpm, setup.gt, setup.xyz,
                                std::is_floating_point<typename Geom_traits::FT>::value
                                  && std::is_same<Vertex_point_map, typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type>::value);
  if(attribute_dimension > 0)
    internal::write_channels(maps, setup.mesh.vertices, attributes);
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAX_H
