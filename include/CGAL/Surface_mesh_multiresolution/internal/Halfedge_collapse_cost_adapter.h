// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_HALFEDGE_COLLAPSE_COST_ADAPTER_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_HALFEDGE_COLLAPSE_COST_ADAPTER_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Triangle_halfedges.h>

#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_profile.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>

#include <boost/optional.hpp>

#include <iterator>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// Every use of Surface_mesh_simplification (SMS) goes through this header.
//
// A half-edge collapse source(h) -> target(h) is an SMS edge collapse whose placement is
// the target's position, so any SMS `GetCost` model scores it: cost(profile, p(target)).
// Policies that keep per-vertex state (`Update_tag` true: the Garland-Heckbert family) are
// driven through the protocol SMS's own driver uses, which is not documented API:
// initialize(tm, vpm, gt) once, then update_after_collapse(profile built before the
// collapse, kept vertex) after every collapse (quadrics accumulate over the levels).

template <typename T, typename = void>
struct Has_update_protocol : std::false_type {};
template <typename T>
struct Has_update_protocol<T, std::void_t<typename T::Update_tag> >
  : std::integral_constant<bool, T::Update_tag::value> {};

template <typename TriangleMesh, typename VertexPointMap, typename GeomTraits, typename GetCost>
class Halfedge_collapse_cost_adapter
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor     vertex_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor   halfedge_descriptor;
  typedef typename boost::property_traits<VertexPointMap>::value_type       Point;
  typedef typename GeomTraits::FT                                            FT;
  typedef typename CGAL::GetInitializedVertexIndexMap<TriangleMesh>::const_type   Vertex_index_map;
  typedef typename CGAL::GetInitializedHalfedgeIndexMap<TriangleMesh>::const_type Halfedge_index_map;
  typedef CGAL::Surface_mesh_simplification::Edge_profile<TriangleMesh, VertexPointMap, GeomTraits> Profile;
  static constexpr bool has_update = Has_update_protocol<GetCost>::value;

public:
  Halfedge_collapse_cost_adapter(TriangleMesh& tm, VertexPointMap vpm, const GeomTraits& gt, GetCost& get_cost)
    : m_tm(tm), m_vpm(vpm), m_gt(gt), m_get_cost(get_cost),
      m_vim(CGAL::get_initialized_vertex_index_map(tm)),
      m_him(CGAL::get_initialized_halfedge_index_map(tm)),
      m_has_border(!CGAL::is_closed(tm))
  {
    if constexpr(has_update)
      m_get_cost.initialize(m_tm, m_vpm, m_gt);
  }

  // cost of moving source(h) onto target(h); an empty optional if the policy refuses it
  Optional<double> cost(halfedge_descriptor h) const
  {
    // The Garland-Heckbert family (the policies with the update protocol) reads only v0, v1
    // and its quadrics from the profile (CGAL 5.5, GarlandHeckbert_policy_base::operator()),
    // so its profiles skip the collection of the border edges around v0 and v1: a seventh of
    // the decomposition of a mesh with holes (measured on the dragon).
    const Profile profile(h, m_tm, m_gt, m_vim, m_vpm, m_him, has_update ? false : m_has_border);
    const boost::optional<FT> c = m_get_cost(profile, boost::optional<Point>(profile.p1()));
    if(!c)
      return Optional<double>();
    return Optional<double>(CGAL::to_double(*c));
  }

  void before_collapse(halfedge_descriptor h)
  {
    if constexpr(has_update)
      m_pending.emplace(h, m_tm, m_gt, m_vim, m_vpm, m_him, m_has_border);
    CGAL_USE(h);
  }

  void after_collapse(vertex_descriptor kept)
  {
    if constexpr(has_update)
    {
      m_get_cost.update_after_collapse(*m_pending, kept);
      m_pending.reset();
    }
    CGAL_USE(kept);
  }

private:
  TriangleMesh& m_tm;
  VertexPointMap m_vpm;
  const GeomTraits& m_gt;
  GetCost& m_get_cost;
  Vertex_index_map m_vim;
  Halfedge_index_map m_him;
  bool m_has_border;
  boost::optional<Profile> m_pending;
};

// Makes the cost policy for the working copy `work`: default Garland-Heckbert plane policies.
template <typename GetCost, typename TriangleMesh, bool stateful = Has_update_protocol<GetCost>::value>
struct Get_cost_holder
{
  GetCost policy;   // stateless: the user's object
  template <typename UserCost>
  Get_cost_holder(const UserCost& user, TriangleMesh&) : policy(user) {}
};

template <typename GetCost, typename TriangleMesh>
struct Get_cost_holder<GetCost, TriangleMesh, true>
{
  GetCost policy;   // stateful: a fresh object of the same type bound to the working copy
  template <typename UserCost>
  Get_cost_holder(const UserCost&, TriangleMesh& work) : policy(work) {}
};

// The cost model of the decomposition for any SMS `GetCost`: a working copy of the input
// (a halfedge mesh of the input's type) on which the policy reads its `Edge_profile`s and
// whose collapses follow the accepted ones, so that stateful policies see the quadrics they
// expect. The selection itself runs on index arrays; this model only answers
// cost(o, e) and applies collapse(o, e), for rows o and e of the current level.
// (The default plane quadrics are evaluated without a working copy: Plane_quadrics.h.)
template <typename TriangleMesh, typename GeomTraits, typename GetCost>
class Sms_collapse_cost
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor   vertex_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type Work_point_map;
  typedef Halfedge_collapse_cost_adapter<TriangleMesh, Work_point_map, GeomTraits, GetCost> Adapter;

public:
  template <typename VertexPointMap, typename VertexIndexMap, typename UserCost>
  Sms_collapse_cost(const TriangleMesh& tm, VertexPointMap vpm, VertexIndexMap vim, const Indexed_mesh<TriangleMesh>& im,
                    const GeomTraits& gt, const UserCost& user)
  {
    std::vector<std::pair<vertex_descriptor, vertex_descriptor> > v2v;
    CGAL::copy_face_graph(tm, m_work, CGAL::parameters::vertex_point_map(vpm).vertex_to_vertex_output_iterator(std::back_inserter(v2v)));
    m_wpm = get(CGAL::vertex_point, m_work);
    m_wv.resize(im.number_of_vertices());
    for(const auto& p : v2v)
      m_wv[im.row(p.first, vim)] = p.second;
    m_holder = std::make_unique<Get_cost_holder<GetCost, TriangleMesh> >(user, m_work);
    m_adapter = std::make_unique<Adapter>(m_work, m_wpm, gt, m_holder->policy);
  }

  void initialize(const Triangle_halfedges&, const std::vector<Index>&, const std::vector<double>&) {}
  void begin_level(const std::vector<Index>& rows_to_vertices, const std::vector<double>&) { m_rows = &rows_to_vertices; }

  Optional<double> cost(Index o, Index e) const { return m_adapter->cost(work_halfedge((*m_rows)[o], (*m_rows)[e])); }

  void collapse(Index ro, Index re)
  {
    const Index o = (*m_rows)[ro], e = (*m_rows)[re];
    const halfedge_descriptor h = work_halfedge(o, e);
    const auto pe = get(m_wpm, m_wv[e]);
    m_adapter->before_collapse(h);
    const vertex_descriptor kept = CGAL::Euler::collapse_edge(edge(h, m_work), m_work);
    put(m_wpm, kept, pe);
    m_wv[e] = kept;
    m_adapter->after_collapse(kept);
  }

  // a level's accepted collapses, in order (each edits the working copy, which then holds
  // M_{k+1}: the rows of the next level need nothing more)
  template <typename Collapses>
  void next_level(const Collapses& accepted, const std::vector<Index>&, const std::vector<Index>&)
  {
    for(const auto& c : accepted)
      collapse(c.o, c.e);
  }

private:
  halfedge_descriptor work_halfedge(Index o, Index e) const
  {
    const auto he = halfedge(m_wv[o], m_wv[e], m_work);
    CGAL_assertion(he.second);
    return he.first;
  }

  TriangleMesh m_work;
  Work_point_map m_wpm;
  std::vector<vertex_descriptor> m_wv;   // input vertex number -> vertex of the working copy
  const std::vector<Index>* m_rows = nullptr;   // row of the current level -> input vertex number
  std::unique_ptr<Get_cost_holder<GetCost, TriangleMesh> > m_holder;
  std::unique_ptr<Adapter> m_adapter;
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_HALFEDGE_COLLAPSE_COST_ADAPTER_H
