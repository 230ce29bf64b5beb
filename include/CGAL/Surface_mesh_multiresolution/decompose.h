// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSE_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSE_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/channels.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Halfedge_collapse_cost_adapter.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/relaxation_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Decomposition_visitor_base.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Dynamic_property_map.h>

#include <algorithm>
#include <array>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The details of one channel on one level. Odd rows are predicted from a state where each
// odd vertex holds the value of the vertex it collapses into (known on M_{k+1}), even rows
// from the original values (Eq. 6 and 7 of the paper; with the curvature and uniform schemes
// an odd row only involves even vertices, so this is exactly Eq. 5). Where fl(R f + d)
// differs from f by rounding, a correction makes reconstruction exact.
inline void compute_details(const Sparse_weights& w, const Pyramid_level& level, const std::vector<Index>& target_rows,
                            const std::vector<double>& f, std::size_t dim,
                            std::vector<double>& details, std::vector<std::pair<Index, double> >& corrections)
{
  const std::size_t n = level.vertices.size();
  std::vector<double> state(f), prediction(n * dim);
  for(std::size_t q = 0; q < level.odd_rows.size(); ++q)
    std::copy(f.begin() + target_rows[q] * dim, f.begin() + (target_rows[q] + 1) * dim, state.begin() + level.odd_rows[q] * dim);
  w.apply_row_list(state.data(), prediction.data(), dim, level.odd_rows.data(), level.odd_rows.size());
  w.apply_row_list(f.data(), prediction.data(), dim, level.even_rows.data(), level.even_rows.size());
  details.resize(n * dim);
  corrections.clear();
  for(std::size_t k = 0; k < n * dim; ++k)
  {
    details[k] = f[k] - prediction[k];
    const double t = prediction[k] + details[k];
    if(t != f[k])
      corrections.emplace_back(static_cast<Index>(k), f[k] - t);
  }
}

// The details and corrections of one channel on one level from its values on all input
// vertices (global numbers): the analysis of compute_details() for a pyramid whose
// connectivity and weights are already known (re-analysis after a change of the values).
inline void analyse_level_values(const Pyramid_level& level, std::size_t dim, const std::vector<double>& v,
                                 std::vector<double>& details, std::vector<std::pair<Index, double> >& corrections)
{
  const std::size_t n = level.vertices.size();
  std::vector<double> f(n * dim);
  for(std::size_t r = 0; r < n; ++r)
    std::copy(v.begin() + std::size_t(level.vertices[r]) * dim, v.begin() + (std::size_t(level.vertices[r]) + 1) * dim,
              f.begin() + r * dim);
  std::vector<Index> target_rows(level.collapse_targets.size());
  for(std::size_t q = 0; q < target_rows.size(); ++q)
    target_rows[q] = static_cast<Index>(std::lower_bound(level.vertices.begin(), level.vertices.end(), level.collapse_targets[q])
                                        - level.vertices.begin());
  compute_details(level.weights, level, target_rows, f, dim, details, corrections);
}

template <typename TriangleMesh, typename VertexPointMap, typename GeomTraits>
bool does_collapse_flip_a_face(typename boost::graph_traits<TriangleMesh>::halfedge_descriptor h,
                               const TriangleMesh& tm, VertexPointMap vpm, const GeomTraits& gt)
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor   vertex_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor halfedge_descriptor;
  const auto cross = gt.construct_cross_product_vector_3_object();
  const auto dot = gt.compute_scalar_product_3_object();
  const auto vector = gt.construct_vector_3_object();
  const vertex_descriptor o = source(h, tm), e = target(h, tm);
  const auto& po = get(vpm, o);
  const auto& pe = get(vpm, e);
  for(halfedge_descriptor hh : halfedges_around_target(o, tm))   // hh : b -> o
  {
    if(is_border(hh, tm))
      continue;
    const vertex_descriptor a = target(next(hh, tm), tm), b = source(hh, tm);
    if(a == e || b == e)
      continue;                                                  // this face disappears
    const auto& pa = get(vpm, a);
    const auto& pb = get(vpm, b);
    if(!(dot(cross(vector(po, pa), vector(po, pb)), cross(vector(pe, pa), vector(pe, pb))) > 0))
      return true;
  }
  return false;
}

} // namespace internal

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * decomposes `tm` into a Burt-Adelson mesh pyramid (Roy et al., Section 3).
 *
 * Level \f$ k \f$ goes from \f$ M_k \f$ (\f$ M_0 \f$ = `tm`) to \f$ M_{k+1} \f$: a greedy independent
 * set of half-edge collapses \f$ o \to e \f$ is chosen in increasing Garland-Heckbert cost
 * \f$ (Q_o + Q_e)(p_e) \f$ (any SMS cost policy through `get_cost`; quadrics accumulate over the
 * levels); a collapse is accepted when both ends are free, the link condition holds and no
 * face flips, and the closed 1-ring of \f$ o \f$ is then locked. Border vertices only collapse
 * along border edges. The relaxation weights \f$ \lambda^k \f$ are computed on \f$ M_k \f$, the
 * details of every vertex and every channel are stored, then the odd vertices are collapsed
 * (the kept vertex keeps its position, so every \f$ M_k \f$ is a subset of the input's vertices).
 * Levels stop at `number_of_levels`, when `minimum_number_of_vertices` is reached, or when
 * a level would remove nothing.
 *
 * \tparam TriangleMesh a model of `MutableFaceGraph` and `HalfedgeListGraph`, default constructible
 * \tparam NamedParameters a sequence of \ref smr_namedparameters "Named Parameters"
 * \param tm the input triangle mesh (not modified)
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{relaxation_scheme}
 *     \cgalParamDescription{the relaxation operator of the subdivision step}
 *     \cgalParamType{`Relaxation_scheme`}
 *     \cgalParamDefault{`Relaxation_scheme::CURVATURE`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_attribute_maps}
 *     \cgalParamDescription{the attribute channels decomposed with the geometry (a tuple of vertex property maps; see `relax()`)}
 *     \cgalParamDefault{no attribute channel}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{minimum_number_of_vertices}
 *     \cgalParamDescription{no level goes below this number of vertices}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{`4`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{number_of_levels}
 *     \cgalParamDescription{the maximal number of levels}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{unlimited}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{get_cost}
 *     \cgalParamDescription{the cost of a half-edge collapse: any model of the SMS concept `GetCost`, evaluated with the target's position as placement}
 *     \cgalParamType{a model of `GetCost`}
 *     \cgalParamDefault{`CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<TriangleMesh\, GeomTraits>`}
 *     \cgalParamExtra{a policy with per-vertex state (the Garland-Heckbert family) is re-created with its default parameters on the package's working copy of the mesh}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_point_map}
 *     \cgalParamDescription{a property map associating points to the vertices of `tm`}
 *     \cgalParamDefault{`boost::get(CGAL::vertex_point\, tm)`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{geom_traits}
 *     \cgalParamDescription{an instance of a geometric traits class}
 *     \cgalParamType{a class model of `Kernel`}
 *     \cgalParamDefault{a `CGAL::Kernel_traits` compatible with the point type}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{visitor}
 *     \cgalParamDescription{reports progress per level}
 *     \cgalParamType{a class with the functions of `Decomposition_visitor_base`}
 *     \cgalParamDefault{`Decomposition_visitor_base()`}
 *   \cgalParamNEnd
 * \cgalNamedParamsEnd
 *
 * \throws std::invalid_argument if a face is not a triangle, or a coordinate or attribute value is not finite
 * \returns the pyramid; `reconstruct()` with unmodified details gives back `tm` exactly
 */
template <typename TriangleMesh, typename NamedParameters = parameters::Default_named_parameters>
Pyramid<TriangleMesh> decompose(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor   vertex_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor     face_descriptor;
  typedef typename GetGeomTraits<TriangleMesh, NamedParameters>::type     Geom_traits;
  typedef typename GetVertexPointMap<TriangleMesh, NamedParameters>::const_type Vertex_point_map;
  typedef typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type Work_point_map;
  typedef CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<TriangleMesh, Geom_traits> Default_cost;
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::get_cost_policy_t, NamedParameters,
                                                             Default_cost>::type Get_cost_param;
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                             Decomposition_visitor_base>::type Visitor;
  typedef internal::Index Index;

  const Geom_traits gt = choose_parameter<Geom_traits>(get_parameter(np, CGAL::internal_np::geom_traits));
  const Vertex_point_map vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                                get_const_property_map(CGAL::vertex_point, tm));
  const Relaxation_scheme scheme = choose_parameter(get_parameter(np, internal_np::relaxation_scheme), Relaxation_scheme::CURVATURE);
  const std::size_t min_vertices = choose_parameter(get_parameter(np, internal_np::minimum_number_of_vertices), std::size_t(4));
  const std::size_t max_levels = choose_parameter(get_parameter(np, internal_np::number_of_levels),
                                                  (std::numeric_limits<std::size_t>::max)());
  Visitor visitor = choose_parameter<Visitor>(get_parameter(np, CGAL::internal_np::visitor));
  const auto maps = internal::as_tuple(choose_parameter(get_parameter(np, internal_np::vertex_attribute_maps), std::tuple<>()));
  typedef std::decay_t<decltype(maps)> Maps;

  Pyramid<TriangleMesh> pyr;
  pyr.set_relaxation_scheme(scheme);

  // validated index view of the input, and the values of every channel (they never change:
  // each M_k keeps a subset of the input's vertices with their values)
  internal::Indexed_mesh<TriangleMesh> im;
  internal::build_indexed_mesh(tm, CGAL::get_initialized_vertex_index_map(tm, np), im);
  const std::size_t n0 = im.number_of_vertices();
  pyr.number_of_input_vertices() = n0;
  std::vector<std::vector<double> > values(1 + std::tuple_size<Maps>::value);
  pyr.dimensions().assign(1, 3);
  internal::read_coordinates(im.vertices, vpm, gt, values[0]);
  internal::for_each_channel(maps, [&](const auto& map, auto c) {
    constexpr std::size_t dim = internal::Channel_traits<std::decay_t<decltype(map)> >::dimension;
    values[decltype(c)::value + 1].resize(n0 * dim);
    internal::read_channel(map, im.vertices, decltype(c)::value + 1, values[decltype(c)::value + 1].data(), dim, 0);
    pyr.dimensions().push_back(dim);
  });
  const std::size_t nc = values.size();

  // the working copy, whose vertices know their global number
  TriangleMesh work;
  std::vector<std::pair<vertex_descriptor, vertex_descriptor> > v2v;
  CGAL::copy_face_graph(tm, work, CGAL::parameters::vertex_point_map(vpm).vertex_to_vertex_output_iterator(std::back_inserter(v2v)));
  Work_point_map wpm = get(CGAL::vertex_point, work);
  auto gid = get(CGAL::dynamic_vertex_property_t<Index>(), work);
  {
    const auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    for(const auto& p : v2v)
      put(gid, p.second, im.row(p.first, vim));
  }
  // the face array of the current level, in global numbers, and where each face sits in it
  auto fpos = get(CGAL::dynamic_face_property_t<Index>(), work);
  std::vector<Index> F;
  std::vector<face_descriptor> face_at;
  for(face_descriptor f : faces(work))
  {
    put(fpos, f, static_cast<Index>(face_at.size()));
    face_at.push_back(f);
    for(vertex_descriptor v : vertices_around_face(halfedge(f, work), work))
      F.push_back(get(gid, v));
  }

  internal::Get_cost_holder<Get_cost_param, TriangleMesh> cost_holder(get_parameter(np, CGAL::internal_np::get_cost_policy), work);
  internal::Halfedge_collapse_cost_adapter<TriangleMesh, Work_point_map, Geom_traits, Get_cost_param>
      adapter(work, wpm, gt, cost_holder.policy);

  std::vector<unsigned char> alive(n0, 1);
  std::vector<Index> row_of(n0, internal::invalid_index);
  std::vector<unsigned char> locked(n0, 0);
  std::size_t live = n0;
  internal::Relaxation_weight_builder builder;
  std::vector<Index> tri_rows;
  std::vector<double> f;
  // one candidate per halfedge (six per vertex), the largest temporary memory of a level:
  // sorted in place (an index array sorted through the costs was 25 % slower on the dragon,
  // (cost, index) pairs next to the candidates took 16 more bytes each)
  struct Candidate { double cost; Index rank; halfedge_descriptor h; };   // rank: position before sorting
  struct Collapse { Index o, e; halfedge_descriptor h; };   // an accepted collapse o -> e
  std::vector<Candidate> candidates;
  std::vector<unsigned char> cost_ok;
  std::vector<unsigned char> on_border(n0, 0);

  while(pyr.levels().size() < max_levels && live > min_vertices)
  {
    const std::size_t k = pyr.levels().size();
    visitor.on_level_started(k, live);

    // ---- select the odd vertices (greedy independent set of half-edge collapses)
    // border vertices, once per level (is_border(v) walks around v)
    std::fill(on_border.begin(), on_border.end(), 0);
    for(halfedge_descriptor h : halfedges(work))
      if(is_border(h, work))
        on_border[get(gid, source(h, work))] = on_border[get(gid, target(h, work))] = 1;
    candidates.clear();
    for(halfedge_descriptor h : halfedges(work))
    {
      const Index go = get(gid, source(h, work));
      if(on_border[go] && !is_border_edge(h, work))
        continue;                                     // border vertices move along the border only
      candidates.push_back(Candidate{0., static_cast<Index>(candidates.size()), h});
    }
    // the costs only read the mesh and the quadrics: evaluated in parallel (TBB), each into its own slot
    cost_ok.assign(candidates.size(), 0);
    internal::parallel_for_blocks(candidates.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
      {
        const internal::Optional<double> c = adapter.cost(candidates[i].h);
        if(c) { candidates[i].cost = *c; cost_ok[i] = 1; }
      }
    }, 2048);
    // increasing cost; equal costs in the (deterministic) order of halfedges(work)
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(), [&cost_ok](const Candidate& c) { return !cost_ok[c.rank]; }),
                     candidates.end());
    internal::parallel_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {   // a total order
      return a.cost < b.cost || (a.cost == b.cost && a.rank < b.rank);
    });
    std::fill(locked.begin(), locked.end(), 0);
    std::vector<Collapse> accepted;
    const std::size_t budget = live - min_vertices;
    for(const Candidate& candidate : candidates)
    {
      if(accepted.size() >= budget)
        break;
      const Collapse c{get(gid, source(candidate.h, work)), get(gid, target(candidate.h, work)), candidate.h};
      if(locked[c.o] || locked[c.e])
        continue;
      if(!CGAL::Euler::does_satisfy_link_condition(edge(c.h, work), work))
        continue;
      if(internal::does_collapse_flip_a_face(c.h, work, wpm, gt))
        continue;
      locked[c.o] = 1;
      for(vertex_descriptor w : vertices_around_target(source(c.h, work), work))
        locked[get(gid, w)] = 1;
      accepted.push_back(c);
    }
    if(accepted.empty())
      break;

    // ---- the level's vertices, weights and details, on M_k
    pyr.levels().emplace_back();
    internal::Pyramid_level& level = pyr.levels().back();
    for(Index g = 0; g < n0; ++g)
      if(alive[g])
      {
        row_of[g] = static_cast<Index>(level.vertices.size());
        level.vertices.push_back(g);
      }
    std::sort(accepted.begin(), accepted.end(), [](const Collapse& a, const Collapse& b) { return a.o < b.o; });
    std::vector<Index> target_rows;
    for(const Collapse& c : accepted)
    {
      level.odd_rows.push_back(row_of[c.o]);
      level.collapse_targets.push_back(c.e);
      target_rows.push_back(row_of[c.e]);
    }
    {
      std::size_t q = 0;
      for(Index r = 0; r < level.vertices.size(); ++r)
      {
        if(q < level.odd_rows.size() && level.odd_rows[q] == r) { ++q; continue; }
        level.even_rows.push_back(r);
      }
    }
    const std::size_t nk = level.vertices.size();
    tri_rows.resize(F.size());
    for(std::size_t i = 0; i < F.size(); ++i)
      tri_rows[i] = row_of[F[i]];
    level.details.resize(nc);
    level.corrections.resize(nc);
    for(std::size_t c = 0; c < nc; ++c)
    {
      const std::size_t dim = pyr.dimensions()[c];
      f.resize(nk * dim);
      for(std::size_t r = 0; r < nk; ++r)
        std::copy(values[c].begin() + std::size_t(level.vertices[r]) * dim,
                  values[c].begin() + (std::size_t(level.vertices[r]) + 1) * dim, f.begin() + r * dim);
      if(c == 0)
      {
        std::vector<Relaxation_row_rule> rules;
        builder.set_connectivity(nk, tri_rows);
        builder.build(scheme, f.data(), nullptr, level.weights, rules);
      }
      internal::compute_details(level.weights, level, target_rows, f, dim, level.details[c], level.corrections[c]);
    }

    // ---- collapse, recording how to undo it on the face array
    std::vector<std::pair<Index, std::array<Index, 3> > > removed;
    for(const Collapse& c : accepted)
    {
      const halfedge_descriptor h = c.h;
      for(halfedge_descriptor hh : halfedges_around_target(source(h, work), work))
      {
        if(is_border(hh, work))
          continue;
        const Index p = get(fpos, face(hh, work));
        const Index* t = F.data() + 3 * std::size_t(p);
        if(t[0] == c.e || t[1] == c.e || t[2] == c.e)
          removed.push_back(std::make_pair(p, std::array<Index, 3>{{t[0], t[1], t[2]}}));
        else
        {
          const int corner = (t[0] == c.o) ? 0 : ((t[1] == c.o) ? 1 : 2);
          level.renamed_corners.push_back(3 * p + corner);
          level.renamed_vertices.push_back(c.o);
        }
      }
      const auto pe = get(wpm, target(h, work));
      adapter.before_collapse(h);
      const vertex_descriptor kept = CGAL::Euler::collapse_edge(edge(h, work), work);
      put(wpm, kept, pe);
      put(gid, kept, c.e);
      adapter.after_collapse(kept);
      alive[c.o] = 0;
      --live;
    }
    // the face array of M_{k+1}
    for(std::size_t q = 0; q < level.renamed_corners.size(); ++q)
    {
      const Index idx = level.renamed_corners[q];
      const std::size_t odd = std::lower_bound(accepted.begin(), accepted.end(), level.renamed_vertices[q],
                                               [](const Collapse& a, Index o) { return a.o < o; }) - accepted.begin();
      F[idx] = accepted[odd].e;
    }
    std::sort(removed.begin(), removed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::size_t write = 0, next_removed = 0;
    for(std::size_t p = 0; p < face_at.size(); ++p)
    {
      if(next_removed < removed.size() && removed[next_removed].first == p) { ++next_removed; continue; }
      if(write != p)
      {
        std::copy(F.begin() + 3 * p, F.begin() + 3 * p + 3, F.begin() + 3 * write);
        face_at[write] = face_at[p];
      }
      put(fpos, face_at[write], static_cast<Index>(write));
      ++write;
    }
    F.resize(3 * write);
    face_at.resize(write);
    for(const auto& r : removed)
    {
      level.removed_face_positions.push_back(r.first);
      level.removed_faces.insert(level.removed_faces.end(), r.second.begin(), r.second.end());
    }
    visitor.on_level_finished(k, accepted.size());
  }

  // ---- the coarsest mesh
  for(Index g = 0; g < n0; ++g)
    if(alive[g])
      pyr.coarse_vertices().push_back(g);
  pyr.coarse_faces() = F;
  pyr.coarse_values().resize(nc);
  for(std::size_t c = 0; c < nc; ++c)
  {
    const std::size_t dim = pyr.dimensions()[c];
    for(Index g : pyr.coarse_vertices())
      pyr.coarse_values()[c].insert(pyr.coarse_values()[c].end(), values[c].begin() + std::size_t(g) * dim,
                                    values[c].begin() + (std::size_t(g) + 1) * dim);
  }
  visitor.on_finished(pyr.levels().size());
  return pyr;
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSE_H
