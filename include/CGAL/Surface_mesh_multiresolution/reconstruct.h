// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_RECONSTRUCT_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_RECONSTRUCT_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/channels.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_transform.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_weights.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Triangle_halfedges.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// Empties a mesh. Surface_mesh's clear() (and CGAL::clear()) drop the property maps the
// caller attached for the channels; clear_without_removing_property_maps() keeps them.
template <typename Mesh>
auto clear_keeping_properties(Mesh& m, int) -> decltype(m.clear_without_removing_property_maps(), void())
{
  m.clear_without_removing_property_maps();
}
template <typename Mesh>
void clear_keeping_properties(Mesh& m, long) { CGAL::clear(m); }

// Adds nv vertices, ne edges and nf faces to an empty mesh, their descriptors in vd, hd (one
// halfedge per edge) and fd: add_vertex(), add_edge(), add_face() for any mutable face graph;
// for a Surface_mesh one resize() of its property arrays (one push_back per element and
// property array was a third of building the dragon's mesh).
template <typename FaceGraph>
void create_elements(FaceGraph& out, std::size_t nv, std::size_t ne, std::size_t nf,
                     std::vector<typename boost::graph_traits<FaceGraph>::vertex_descriptor>& vd,
                     std::vector<typename boost::graph_traits<FaceGraph>::halfedge_descriptor>& hd,
                     std::vector<typename boost::graph_traits<FaceGraph>::face_descriptor>& fd)
{
  typedef boost::graph_traits<FaceGraph> GT;
  reserve(out, static_cast<typename GT::vertices_size_type>(nv), static_cast<typename GT::edges_size_type>(ne),
          static_cast<typename GT::faces_size_type>(nf));
  vd.resize(nv);
  hd.resize(ne);
  fd.resize(nf);
  for(auto& v : vd) v = add_vertex(out);
  for(auto& h : hd) h = halfedge(add_edge(out), out);
  for(auto& f : fd) f = add_face(out);
}

template <typename Point>
void create_elements(CGAL::Surface_mesh<Point>& out, std::size_t nv, std::size_t ne, std::size_t nf,
                     std::vector<typename CGAL::Surface_mesh<Point>::Vertex_index>& vd,
                     std::vector<typename CGAL::Surface_mesh<Point>::Halfedge_index>& hd,
                     std::vector<typename CGAL::Surface_mesh<Point>::Face_index>& fd)
{
  typedef CGAL::Surface_mesh<Point> SM;
  typedef typename SM::size_type size_type;
  CGAL_precondition(out.number_of_vertices() == 0 && out.number_of_removed_vertices() == 0);
  out.resize(static_cast<size_type>(nv), static_cast<size_type>(ne), static_cast<size_type>(nf));
  vd.resize(nv);
  hd.resize(ne);
  fd.resize(nf);
  for(std::size_t i = 0; i < nv; ++i) vd[i] = typename SM::Vertex_index(static_cast<size_type>(i));
  for(std::size_t i = 0; i < ne; ++i) hd[i] = out.halfedge(typename SM::Edge_index(static_cast<size_type>(i)));
  for(std::size_t i = 0; i < nf; ++i) fd[i] = typename SM::Face_index(static_cast<size_type>(i));
}

// The border halfedge out of v at the other end of the fan of faces that the border halfedge
// g (which ends at v) borders, reached by turning around v from twin(g). th: built by
// Triangle_halfedges::build_twins() (or build()) on the face array.
inline Index same_fan_border_halfedge(const Triangle_halfedges& th, Index g)
{
  Index h = th.twin[g];                                      // out of v, in a face
  for(std::size_t turns = 0; turns <= th.twin.size(); ++turns)
  {
    const Index into_v = Triangle_halfedges::prev_in_face(h);   // the halfedge before h in its face
    const Index t = th.twin[into_v];
    if(!th.has_face(t))
      return t;
    h = t;
  }
  throw std::runtime_error("the faces do not form a halfedge mesh: a fan around a vertex does not end");
}

// For every border halfedge g (numbered from 3 nf), the border halfedge after it. Where every
// vertex has at most one border gap, the only border halfedge out of its target (one pass).
// At a vertex with several gaps (pinched between fans), the gaps are chained in a cycle as
// Euler::add_face() does: g_i, incoming at the i-th gap, goes on with the outgoing border
// halfedge of the next fan, so that the halfedges around the vertex form one cycle.
inline std::vector<Index> border_successors(const Triangle_halfedges& th, const std::vector<Index>& tri)
{
  const std::size_t nh = th.twin.size(), h0 = 3 * th.nf;
  std::vector<Index> border_out(th.n, invalid_index), next(nh - h0);
  bool pinched = false;
  for(std::size_t g = h0; g < nh && !pinched; ++g)
  {
    Index& b = border_out[th.source_in(tri, static_cast<Index>(g))];
    pinched = (b != invalid_index);
    b = static_cast<Index>(g);
  }
  if(!pinched)
  {
    for(std::size_t g = h0; g < nh; ++g)
      next[g - h0] = border_out[th.target_in(tri, static_cast<Index>(g))];
    return next;
  }
  std::vector<Index> offsets(th.n + 1, 0), incoming(nh - h0);   // border halfedges by target
  for(std::size_t g = h0; g < nh; ++g) ++offsets[th.target_in(tri, static_cast<Index>(g)) + 1];
  for(std::size_t v = 0; v < th.n; ++v) offsets[v + 1] += offsets[v];
  std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
  for(std::size_t g = h0; g < nh; ++g) incoming[fill[th.target_in(tri, static_cast<Index>(g))]++] = static_cast<Index>(g);
  for(std::size_t v = 0; v < th.n; ++v)
  {
    const std::size_t m = offsets[v + 1] - offsets[v];
    for(std::size_t i = 0; i < m; ++i)
      next[incoming[offsets[v] + i] - h0] = same_fan_border_halfedge(th, incoming[offsets[v] + (i + 1) % m]);
  }
  return next;
}

// Makes the empty mesh `out` the triangle mesh of `tri` (nv vertices, 3 rows per face, faces
// in this order); vd receives the vertex of each row. The halfedges are linked directly
// (set_next, set_target, set_face...) from the twins of Triangle_halfedges::build_twins(),
// border cycles included (also through pinched vertices). Why by hand: Euler::add_face()
// searches the halfedges around each corner for every face, which was 40 % of a
// reconstruction of the dragon (and fails on some orders of the faces around a pinched
// vertex); here every edge is known with its twin.
// \throws std::runtime_error if the faces are not those of a halfedge mesh (a directed edge
// in two faces), not possible for the levels of a pyramid that check_pyramid() accepts
template <typename FaceGraph>
void build_triangle_mesh(FaceGraph& out, std::size_t nv, const std::vector<Index>& tri,
                         std::vector<typename boost::graph_traits<FaceGraph>::vertex_descriptor>& vd)
{
  typedef boost::graph_traits<FaceGraph> GT;
  typedef typename GT::halfedge_descriptor halfedge_descriptor;
  typedef typename GT::face_descriptor     face_descriptor;
  Triangle_halfedges th;
  th.build_twins(nv, tri);
  if(th.repeated_directed_edge)
    throw std::runtime_error("the faces do not form a halfedge mesh: a directed edge is shared by two faces");
  const std::size_t nh = th.twin.size(), h0 = 3 * th.nf;
  const std::vector<Index> border_next = border_successors(th, tri);
  std::vector<halfedge_descriptor> edge_halfedge, hd(nh);
  std::vector<face_descriptor> fd;
  create_elements(out, nv, nh / 2, th.nf, vd, edge_halfedge, fd);
  std::size_t e = 0;
  for(std::size_t h = 0; h < nh; ++h)
    if(h < th.twin[h])
    {
      hd[h] = edge_halfedge[e++];
      hd[th.twin[h]] = opposite(hd[h], out);
    }
  for(std::size_t p = 0; p < th.nf; ++p)
  {
    set_halfedge(fd[p], hd[3 * p], out);
    for(std::size_t k = 3 * p; k < 3 * p + 3; ++k)
    {
      const Index next = Triangle_halfedges::next_in_face(static_cast<Index>(k));
      set_face(hd[k], fd[p], out);
      set_target(hd[k], vd[tri[next]], out);
      set_next(hd[k], hd[next], out);
      set_halfedge(vd[tri[next]], hd[k], out);
    }
  }
  // border halfedges last, so that a border vertex's halfedge is an incoming border halfedge
  for(std::size_t g = h0; g < nh; ++g)
  {
    const Index v = th.target_in(tri, static_cast<Index>(g));
    set_face(hd[g], GT::null_face(), out);
    set_target(hd[g], vd[v], out);
    set_next(hd[g], hd[border_next[g - h0]], out);
    set_halfedge(vd[v], hd[g], out);
  }
}

// The face array of M_level (rows of M_level): the vertex splits replayed from the coarsest mesh.
template <typename TriangleMesh>
void reconstruct_faces(const Pyramid<TriangleMesh>& pyr, std::size_t level, std::vector<Index>& F)
{
  F.clear();
  F.reserve(3 * pyr.number_of_faces(level));
  F = pyr.coarse_faces();
  std::vector<Index> scratch;
  scratch.reserve(3 * pyr.number_of_faces(level));
  for(std::size_t k = pyr.number_of_levels(); k-- > level; )
    expand_faces(pyr.levels()[k], F, scratch);
}

// The buffers of the values' reconstruction, reserved at their largest size by reserve(), so
// that the reconstruction allocates none of its large buffers itself (it may run on another
// thread: see run_beside(); the weights' builder and its rows' scratch still allocate there).
struct Values_workspace
{
  std::vector<std::vector<double> > values;   // per channel, rows of the current level
  std::vector<double> state, prediction;
  std::vector<unsigned char> is_odd;
  std::vector<Index> faces, scratch_faces;     // the face array of the current level, expand_faces()' scratch

  template <typename TriangleMesh>
  void reserve(const Pyramid<TriangleMesh>& pyr, std::size_t level)
  {
    const std::size_t nc = pyr.number_of_channels(), n = pyr.number_of_vertices(level);
    const std::size_t dim = *std::max_element(pyr.dimensions().begin(), pyr.dimensions().end());
    values.resize(nc);
    for(std::vector<double>& v : values)
      v.reserve(n * dim);
    state.reserve(n * dim);
    prediction.reserve(n * dim);
    is_odd.reserve(n);
    faces.reserve(3 * pyr.number_of_faces(level));
    scratch_faces.reserve(3 * pyr.number_of_faces(level));
  }
};

// The values of every channel in rows of M_level (ws.values[c][r * dim] is the value of
// pyr.vertices(level)[r]; at level 0 rows are the input's vertex numbers), rebuilt from the
// coarsest mesh by Eq. 6 and 7 level by level, in the rows of each level. The weights of
// each level are computed on its face array (Level_weights), which is rebuilt on the way:
// on return ws.faces holds M_level's (empty for a pyramid that stores its weights).
template <typename TriangleMesh>
void reconstruct_values(const Pyramid<TriangleMesh>& pyr, std::size_t level, Values_workspace& ws)
{
  const std::size_t nc = pyr.number_of_channels();
  Level_weights weights(pyr);
  weights.reserve(pyr, level);
  ws.values.resize(nc);
  for(std::size_t c = 0; c < nc; ++c)
    ws.values[c].assign(pyr.coarse_values()[c].begin(), pyr.coarse_values()[c].end());
  ws.faces.clear();
  if(weights.computed())
    ws.faces.assign(pyr.coarse_faces().begin(), pyr.coarse_faces().end());
  for(std::size_t k = pyr.number_of_levels(); k-- > level; )
  {
    const Pyramid_level& lev = pyr.levels()[k];
    if(weights.computed())
      expand_faces(lev, ws.faces, ws.scratch_faces);
    odd_row_flags(lev, ws.is_odd);
    if(nc == 1 && weights.rows_computable_as_applied(lev))
    {
      // one channel: each row is applied once, as it is computed
      const std::size_t dim = pyr.dimensions()[0];
      spread_to_level(lev, dim, ws.values[0].data(), ws.state);
      synthesize_level(lev, weights.rows_as_applied(lev, ws.faces), dim, lev.details[0].data(), lev.corrections[0], ws.is_odd,
                       ws.state, ws.prediction);
      ws.values[0].swap(ws.state);
      continue;
    }
    const Sparse_weights& w = weights.of(lev, ws.faces);
    for(std::size_t c = 0; c < nc; ++c)
    {
      const std::size_t dim = pyr.dimensions()[c];
      spread_to_level(lev, dim, ws.values[c].data(), ws.state);
      synthesize_level(lev, w, dim, lev.details[c].data(), lev.corrections[c], ws.is_odd, ws.state, ws.prediction);
      ws.values[c].swap(ws.state);
    }
  }
}

// the values of every channel and the face array of M_level, in its rows; with `faces` false,
// F is left empty (values only)
template <typename TriangleMesh>
void reconstruct_arrays(const Pyramid<TriangleMesh>& pyr, std::size_t level,
                        std::vector<std::vector<double> >& values, std::vector<Index>& F, bool faces = true)
{
  Values_workspace ws;
  reconstruct_values(pyr, level, ws);
  values.swap(ws.values);
  F.clear();
  if(faces && !ws.faces.empty())
    F.swap(ws.faces);
  else if(faces)
    reconstruct_faces(pyr, level, F);
}

// The place in the output of each row whose input number is verts[r]: its rank among verts
// (the output lists vertices in increasing input number); empty when verts increase (the
// identity). n0: the number of input vertices.
inline std::vector<Index> output_places(const std::vector<Index>& verts, std::size_t n0)
{
  if(std::is_sorted(verts.begin(), verts.end()))
    return std::vector<Index>();
  std::vector<Index> rank(n0 + 1, 0);
  for(Index g : verts)
    rank[g + 1] = 1;
  for(std::size_t g = 0; g < n0; ++g)
    rank[g + 1] += rank[g];
  std::vector<Index> place(verts.size());
  for(std::size_t r = 0; r < verts.size(); ++r)
    place[r] = rank[verts[r]];
  return place;
}

// F (rows) renamed to the output's places (output_places(); none: unchanged) and, with a face
// order (the input position of each face: a level-0 face array of a pyramid in its own order),
// its faces put at their input positions
inline void faces_in_output_order(const std::vector<Index>& place, const std::vector<Index>* face_order, std::vector<Index>& F)
{
  if(!place.empty())
    parallel_for_blocks(F.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
        F[i] = place[F[i]];
    });
  if(face_order != nullptr && !face_order->empty())
  {
    CGAL_precondition(face_order->size() * 3 == F.size());
    std::vector<Index> G(F.size());
    parallel_for_blocks(face_order->size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t p = first; p < last; ++p)
        copy_values(F.data() + 3 * p, 3, G.data() + 3 * std::size_t((*face_order)[p]));
    });
    F.swap(G);
  }
}

// values of every channel in the rows of M_0 put by input number (values[c][g * dim]: the
// value of input vertex g), whatever the order of the pyramid's rows (Memory_order)
template <typename TriangleMesh>
void values_by_input_number(const Pyramid<TriangleMesh>& pyr, std::vector<std::vector<double> >& values)
{
  const std::vector<Index>& rows = pyr.vertices(0);
  if(std::is_sorted(rows.begin(), rows.end()))
    return;                                                  // rows are the input numbers
  for(std::size_t c = 0; c < values.size(); ++c)
  {
    const std::size_t dim = pyr.dimensions()[c];
    if(values[c].size() != rows.size() * dim)
      continue;                                              // a channel not given (empty)
    std::vector<double> by_input(values[c].size());
    parallel_for_blocks(rows.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t r = first; r < last; ++r)
        copy_values(values[c].data() + r * dim, dim, by_input.data() + std::size_t(rows[r]) * dim);
    });
    values[c].swap(by_input);
  }
}

// the values of every channel on M_0 by input number (values_by_input_number())
template <typename TriangleMesh>
void reconstruct_input_values(const Pyramid<TriangleMesh>& pyr, std::vector<std::vector<double> >& values)
{
  std::vector<Index> no_faces;
  reconstruct_arrays(pyr, 0, values, no_faces, false);
  values_by_input_number(pyr, values);
}

// Writes the vertices `verts` (input numbers of the rows) with their values and the faces
// into `out`, emptied first, with the channel maps of `np`; the output lists the vertices in
// increasing input number and, with `face_order` (level 0 of a pyramid in its own order), the
// faces in the input's order. compute_faces(F) gives the faces
// (rows of verts), compute_values(values) the values of every channel in rows of verts
// (values[c][r * dim] is the value of verts[r]); the output's connectivity and the values are
// computed at the same time (with TBB), they are independent. With `keep_connectivity`,
// `out` already has these vertices (in the order of vertices(out)) and these faces: only the
// positions and channel values are written.
// \throws std::invalid_argument if the maps do not match the pyramid's channels, or if
// `keep_connectivity` is asked and `out` does not have the level's numbers of elements
template <typename TriangleMesh, typename OutputMesh, typename NamedParameters, typename ComputeFaces, typename ComputeValues>
void write_output_mesh(const Pyramid<TriangleMesh>& pyr, const std::vector<Index>& verts,
                       const ComputeFaces& compute_faces, const ComputeValues& compute_values,
                       OutputMesh& out, const NamedParameters& np, bool keep_connectivity = false, std::size_t number_of_faces = 0,
                       const std::vector<Index>* face_order = nullptr)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef typename boost::graph_traits<OutputMesh>::vertex_descriptor vertex_descriptor;
  typedef typename GetGeomTraits<OutputMesh, NamedParameters>::type     Geom_traits;
  typedef typename GetVertexPointMap<OutputMesh, NamedParameters>::type Vertex_point_map;

  const auto maps = as_tuple(choose_parameter(get_parameter(np, internal_np::vertex_attribute_maps), std::tuple<>()));
  typedef std::decay_t<decltype(maps)> Maps;
  constexpr std::size_t nmaps = std::tuple_size<Maps>::value;
  if(nmaps > 0)
  {
    if(nmaps + 1 != pyr.number_of_channels())
      throw std::invalid_argument("reconstruct: " + std::to_string(nmaps) + " attribute maps given, the pyramid has "
                                  + std::to_string(pyr.number_of_channels() - 1) + " attribute channels");
    for_each_channel(maps, [&](const auto& map, auto c) {
      constexpr std::size_t dim = Channel_traits<std::decay_t<decltype(map)> >::dimension;
      if(dim != pyr.dimensions()[decltype(c)::value + 1])
        throw std::invalid_argument("reconstruct: attribute map " + std::to_string(decltype(c)::value + 1) + " has dimension "
                                    + std::to_string(dim) + ", the pyramid's channel has "
                                    + std::to_string(pyr.dimensions()[decltype(c)::value + 1]));
    });
  }
  const Geom_traits gt = choose_parameter<Geom_traits>(get_parameter(np, CGAL::internal_np::geom_traits));
  Vertex_point_map vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                          get_property_map(CGAL::vertex_point, out));

  const std::vector<Index> place = output_places(verts, pyr.number_of_input_vertices());
  std::vector<vertex_descriptor> ordered;
  ordered.reserve(verts.size());
  std::vector<std::vector<double> > values;
  const auto point = gt.construct_point_3_object();
  if(keep_connectivity)
  {
    if(std::size_t(num_vertices(out)) != verts.size() || std::size_t(num_faces(out)) != number_of_faces)
      throw std::invalid_argument("reconstruct: keep_connectivity asked, but the output mesh has " + std::to_string(num_vertices(out))
                                  + " vertices and " + std::to_string(num_faces(out)) + " faces, the level has "
                                  + std::to_string(verts.size()) + " and " + std::to_string(number_of_faces));
    for(vertex_descriptor v : vertices(out))
      ordered.push_back(v);
    compute_values(values);
  }
  else
    run_beside([&] {
      std::vector<Index> F;
      compute_faces(F);
      faces_in_output_order(place, face_order, F);
      clear_keeping_properties(out, 0);
      build_triangle_mesh(out, verts.size(), F, ordered);
    }, [&] { compute_values(values); });
  if(!place.empty())
  {
    std::vector<vertex_descriptor> by_row(ordered.size());
    for(std::size_t r = 0; r < by_row.size(); ++r)
      by_row[r] = ordered[place[r]];
    ordered.swap(by_row);
  }
  for(std::size_t r = 0; r < verts.size(); ++r)
    put(vpm, ordered[r], point(values[0][3 * r], values[0][3 * r + 1], values[0][3 * r + 2]));
  // channels, written through the same traits as they were read
  for_each_channel(maps, [&](const auto& map, auto c) {
    constexpr std::size_t dim = Channel_traits<std::decay_t<decltype(map)> >::dimension;
    write_channel(map, ordered, values[decltype(c)::value + 1].data(), dim, 0);
  });
}

} // namespace internal

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * rebuilds the mesh \f$ M_k \f$ of level \f$ k \f$ = `level` of a pyramid into `out` (Roy et al.,
 * Section 3.3): vertex splits re-insert the odd vertices of each level, odd vertices are
 * predicted from their even neighbours (Eq. 6) and even vertices from the intermediate mesh
 * (Eq. 7), each plus its details, from the coarsest mesh down to level \f$ k \f$.
 *
 * With unmodified details, level 0 is the decomposed mesh exactly: the same vertices in the
 * same order with the same coordinates and attribute values (equal as doubles), the same
 * faces; level \f$ k \f$ is \f$ M_k \f$ as it was during the decomposition.
 *
 * \tparam TriangleMesh a model of `MutableFaceGraph`
 * \tparam NamedParameters a sequence of \ref smr_namedparameters "Named Parameters"
 * \param pyr the pyramid
 * \param out receives \f$ M_k \f$; it is emptied first (on `Surface_mesh`, its property maps are kept)
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{level}
 *     \cgalParamDescription{the level \f$ k \f$ to rebuild\, \f$ 0 \le k \le K \f$}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{`0`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_attribute_maps}
 *     \cgalParamDescription{property maps of `out` receiving the attribute channels\, of the same value types and in the same order as given to `decompose()`}
 *     \cgalParamDefault{no attribute channel is written}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_point_map}
 *     \cgalParamDescription{a property map associating points to the vertices of `out`}
 *     \cgalParamDefault{`boost::get(CGAL::vertex_point\, out)`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{geom_traits}
 *     \cgalParamDescription{an instance of a geometric traits class}
 *     \cgalParamDefault{a `CGAL::Kernel_traits` compatible with the point type}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{keep_connectivity}
 *     \cgalParamDescription{if `true`\, `out` already holds \f$ M_k \f$'s connectivity with its vertices in the
 *                           order `reconstruct()` writes them (increasing input number): the result of an earlier `reconstruct()` of the same level of
 *                           this pyramid or of a copy of it (filtered\, thresholded). Only the positions and the
 *                           attribute values are written; no vertex split is replayed and no element is created,
 *                           which makes re-filtering several times faster}
 *     \cgalParamType{bool}
 *     \cgalParamDefault{`false`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 *
 * \throws std::invalid_argument if `level` is above \f$ K \f$, or the attribute maps do not match the pyramid's
 *         channels, or `keep_connectivity` is `true` and `out` does not have the level's numbers of vertices and faces
 */
template <typename TriangleMesh, typename OutputMesh, typename NamedParameters = parameters::Default_named_parameters>
void reconstruct(const Pyramid<TriangleMesh>& pyr, OutputMesh& out, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const std::size_t level = choose_parameter(get_parameter(np, internal_np::level), std::size_t(0));
  if(level > pyr.number_of_levels())
    throw std::invalid_argument("reconstruct: level " + std::to_string(level) + " does not exist (the pyramid has levels 0 to "
                                + std::to_string(pyr.number_of_levels()) + ")");
  const bool keep_connectivity = choose_parameter(get_parameter(np, internal_np::keep_connectivity), false);
  internal::Values_workspace ws;
  ws.reserve(pyr, level);                      // here: the values may be computed on another thread
  internal::write_output_mesh(pyr, pyr.vertices(level),
                              [&](std::vector<internal::Index>& F) { internal::reconstruct_faces(pyr, level, F); },
                              [&](std::vector<std::vector<double> >& values) {
                                internal::reconstruct_values(pyr, level, ws);
                                values.swap(ws.values);
                              },
                              out, np, keep_connectivity, keep_connectivity ? pyr.number_of_faces(level) : 0,
                              level == 0 ? &internal::Pyramid_access::face_order(pyr) : nullptr);
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * computes the relaxation weights \f$ \lambda^k \f$ of every level of `pyr` and keeps them in
 * it (`store` true), or frees them (`store` false).
 *
 * A pyramid holds the positions its weights are computed from, not the weights, which would
 * take most of its memory (about 12 bytes per neighbour of every vertex of every level):
 * every reconstruction computes them again, level by level, the same bit for bit, and that
 * is most of its time. A program that reconstructs one pyramid many times (filters tried
 * interactively, several levels of detail, adaptive reconstructions) stores them once;
 * reconstructions then cost what the synthesis costs (the dragon, 437k vertices: about 5
 * times faster, for about 190 MB). `IO::write_pyramid()` does not save them.
 */
template <typename TriangleMesh>
void store_weights(Pyramid<TriangleMesh>& pyr, bool store = true)
{
  std::vector<internal::Pyramid_level>& levels = internal::Pyramid_access::levels(pyr);
  if(pyr.weight_positions().empty())
    return;                                   // a pyramid of a format 1 or 2 file: its levels hold their weights
  if(!store)
  {
    for(internal::Pyramid_level& lev : levels)
      lev.weights = internal::Sparse_weights();
    return;
  }
  internal::Level_weights weights(pyr);
  if(!weights.computed())
    return;
  std::vector<internal::Index> F = pyr.coarse_faces(), scratch;
  for(std::size_t k = levels.size(); k-- > 0; )
  {
    internal::expand_faces(levels[k], F, scratch);
    if(!weights.stored(levels[k]))
      levels[k].weights = weights.of(levels[k], F);
  }
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_RECONSTRUCT_H
