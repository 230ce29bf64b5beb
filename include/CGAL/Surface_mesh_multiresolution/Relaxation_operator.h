// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_OPERATOR_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_OPERATOR_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/channels.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Sparse_weights.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/internal/relaxation_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_scheme.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {


/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * the weights \f$ \lambda_{ij} \f$ of a relaxation operator on one triangle mesh, stored once
 * (compressed sparse rows) so that they can be applied any number of times to any channel:
 * \f$ R f(v_i) = \sum_j \lambda_{ij} f(v_j) \f$ (Eq. 3 of Roy et al.).
 *
 * Rows are the vertices of the mesh in the order of `vertices(tm)` at construction time
 * (`vertex(i)`). Every row sums to 1 (partition of unity) and every weight is finite.
 * Objects are created by `relaxation_operator()`; they do not refer to the mesh afterwards
 * except through the stored vertex descriptors, which must stay valid for `apply(tm, np)`.
 *
 * \tparam TriangleMesh a model of `FaceListGraph`
 */
template <typename TriangleMesh>
class Relaxation_operator
{
public:
  /// the mesh type
  typedef TriangleMesh Triangle_mesh;
  /// the vertex descriptor of the mesh
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;

  /// creates an empty operator (no rows)
  Relaxation_operator() = default;

  /// the scheme that produced the weights
  Relaxation_scheme scheme() const { return m_scheme; }
  /// the number of rows, that is of vertices
  std::size_t number_of_vertices() const { return m_vertices.size(); }
  /// the vertex of row `i`
  vertex_descriptor vertex(std::size_t i) const { return m_vertices[i]; }
  /// the vertices, in row order
  const std::vector<vertex_descriptor>& vertices() const { return m_vertices; }
  /// the compressed-sparse-row offsets (`number_of_vertices()+1` entries): row `i` holds the entries `row_offsets()[i]` to `row_offsets()[i+1]-1`
  const std::vector<std::uint32_t>& row_offsets() const { return m_weights.offsets; }
  /// the column (row index of the neighbour \f$ j \f$) of every entry
  const std::vector<std::uint32_t>& column_indices() const { return m_weights.columns; }
  /// the weight \f$ \lambda_{ij} \f$ of every entry
  const std::vector<double>& weights() const { return m_weights.values; }
  /// the rule that produced row `i`
  Relaxation_row_rule row_rule(std::size_t i) const { return m_rules[i]; }
  /// the number of rows produced by `rule`
  std::size_t number_of_rows_with_rule(Relaxation_row_rule rule) const
  { return static_cast<std::size_t>(std::count(m_rules.begin(), m_rules.end(), rule)); }

  /*!
   * computes `out` \f$ = R\f$ `in` where `in` and `out` hold `dimension` doubles per row,
   * rows in the order of `vertices()`. `in` and `out` must not overlap.
   */
  void apply(const double* in, double* out, std::size_t dimension) const
  {
    m_weights.apply(in, out, dimension);
  }

  /*!
   * computes `out` \f$ = R\f$ `in` for `dimension` doubles per row; `out` is resized.
   * \throws std::invalid_argument if `in.size()` is not `dimension * number_of_vertices()`
   */
  void apply(const std::vector<double>& in, std::vector<double>& out, std::size_t dimension) const
  {
    if(dimension == 0 || in.size() != dimension * number_of_vertices())
      throw std::invalid_argument("Relaxation_operator::apply: the input holds " + std::to_string(in.size())
                                  + " values, expected " + std::to_string(dimension) + " per vertex for "
                                  + std::to_string(number_of_vertices()) + " vertices");
    if(&in == &out)
    {
      std::vector<double> tmp(in.size());
      m_weights.apply(in.data(), tmp.data(), dimension);
      out.swap(tmp);
      return;
    }
    out.resize(in.size());
    m_weights.apply(in.data(), out.data(), dimension);
  }

  /*!
   * relaxes, in place and with the stored weights, the channels of `tm` selected by `np`:
   * the geometry (unless `relax_geometry(false)`) and every map of `vertex_attribute_maps`,
   * `number_of_iterations` times. The weights are not recomputed; `relax()` recomputes them.
   *
   * \tparam NamedParameters a sequence of \ref smr_namedparameters "Named Parameters"
   * \param tm the mesh the operator was built on (same vertices, in the same order)
   * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
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
   *     \cgalParamDescription{the attribute channels to relax (a tuple of vertex property maps, or one map)}
   *     \cgalParamDefault{no attribute channel}
   *   \cgalParamNEnd
   *   \cgalParamNBegin{vertex_point_map}
   *     \cgalParamDescription{a writable property map associating points to the vertices of `tm`}
   *     \cgalParamDefault{`boost::get(CGAL::vertex_point\, tm)`}
   *   \cgalParamNEnd
   *   \cgalParamNBegin{geom_traits}
   *     \cgalParamDescription{an instance of a geometric traits class}
   *     \cgalParamDefault{a `CGAL::Kernel_traits` compatible with the point type}
   *   \cgalParamNEnd
   * \cgalNamedParamsEnd
   *
   * \throws std::invalid_argument if `tm` does not have `number_of_vertices()` vertices, or a
   *         channel value is not finite
   */
  template <typename NamedParameters = parameters::Default_named_parameters>
  void apply(TriangleMesh& tm, const NamedParameters& np = parameters::default_values()) const
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    typedef typename GetGeomTraits<TriangleMesh, NamedParameters>::type     Geom_traits;
    typedef typename GetVertexPointMap<TriangleMesh, NamedParameters>::type Vertex_point_map;

    if(internal::number_of_vertices_of(tm) != number_of_vertices())
      throw std::invalid_argument("Relaxation_operator::apply: the mesh has " + std::to_string(internal::number_of_vertices_of(tm))
                                  + " vertices, the operator " + std::to_string(number_of_vertices()));
    const Geom_traits gt = choose_parameter<Geom_traits>(get_parameter(np, CGAL::internal_np::geom_traits));
    Vertex_point_map vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                            get_property_map(CGAL::vertex_point, tm));
    const internal::Relaxed_channels<NamedParameters> channels(np);
    const bool geometry = channels.geometry;
    const unsigned int iterations = channels.iterations;
    const auto& maps = channels.maps;
    constexpr std::size_t attribute_dimension = internal::Relaxed_channels<NamedParameters>::attribute_dimension;

    std::vector<double> xyz, attributes, tmp;
    if(geometry)
      internal::read_coordinates(m_vertices, vpm, gt, xyz);
    if(attribute_dimension > 0)
      internal::read_channels(maps, m_vertices, attributes);
    for(unsigned int it = 0; it < iterations; ++it)
    {
      if(geometry)
        apply(xyz, xyz, 3);
      if(attribute_dimension > 0)
        apply(attributes, attributes, attribute_dimension);
    }
    if(geometry)
      internal::write_coordinates(m_vertices, vpm, gt, xyz);
    if(attribute_dimension > 0)
      internal::write_channels(maps, m_vertices, attributes);
  }

  /// \cond SKIP_IN_MANUAL
  internal::Operator_weights& sparse_weights() { return m_weights; }
  const internal::Operator_weights& sparse_weights() const { return m_weights; }
  std::vector<vertex_descriptor>& vertices_ref() { return m_vertices; }
  std::vector<Relaxation_row_rule>& rules_ref() { return m_rules; }
  void set_scheme(Relaxation_scheme s) { m_scheme = s; }
  /// \endcond

private:
  Relaxation_scheme m_scheme = Relaxation_scheme::CURVATURE;
  std::vector<vertex_descriptor> m_vertices;
  internal::Operator_weights m_weights;
  std::vector<Relaxation_row_rule> m_rules;
};

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_RELAXATION_OPERATOR_H
