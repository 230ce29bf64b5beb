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
#include <CGAL/Surface_mesh_multiresolution/internal/collapse_cost_models.h>
#include <CGAL/Surface_mesh_multiresolution/internal/collapse_selection.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_transform.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/relaxation_weights.h>
#include <CGAL/Surface_mesh_multiresolution/internal/spatial_order.h>
#include <CGAL/Surface_mesh_multiresolution/Decomposition_visitor_base.h>
#include <CGAL/Surface_mesh_multiresolution/Memory_order.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The cost of moving row o onto row e, with the model's hint that such a cost will be read
// soon where it has one (prefetch_cost_operands())
template <typename CostModel>
struct Cost_of_rows
{
  Optional<double> operator()(Index o, Index e) const { return model.cost(o, e); }
  void prefetch_target(Index e) const { prefetch_cost_operands(model, e, 0); }
  // the costs of moving o onto its neighbours (candidate_keys()), where the model has them
  // (Plane_quadrics::costs_from()); without, candidate_keys() calls the cost above
  template <typename Model = CostModel>
  auto costs_from(Index o) const -> decltype(std::declval<const Model&>().costs_from(o)) { return model.costs_from(o); }
  const CostModel& model;
};

// The decomposition as a driver over named steps (in the manner of SMS's collect(); loop();):
// this class holds the state that goes from one level to the next, all of it in the rows of
// the current level M_k (its vertices in increasing input number): the input number of every
// row, the values of every channel, the face array and the cost model's quadrics. Per level:
//   connectivity()          the halfedges of M_k's face array
//   select()                the greedy independent set of half-edge collapses
//   record_rows_and_targets odd and even rows, collapse targets
//   analyse_channels()      the weights on M_k and the details of every channel (Eq. 5)
//   collapse_face_array()   the faces of M_{k+1}, with the records that undo the collapses
//   move_to_next_level()    rows, values and quadrics of M_{k+1}
// then coarsest_mesh(). The pyramid's levels are filled as they are made.
template <typename TriangleMesh, typename CostModel, typename Visitor>
class Decomposition
{
public:
  // values and faces in the vertex order `vertex_order` (the input number of every row of M_0;
  // empty: the input's numbering)
  Decomposition(Pyramid<TriangleMesh>& pyr, std::vector<std::vector<double> >&& values, std::vector<Index>&& faces,
                std::vector<Index>&& vertex_order, CostModel& cost_model, Relaxation_scheme scheme, Visitor& visitor)
    : m_pyr(pyr), m_values(std::move(values)), m_faces(std::move(faces)), m_cost(cost_model), m_scheme(scheme),
      m_visitor(visitor)
  {
    const std::size_t n0 = m_values[0].size() / 3;
    m_rows_to_vertices = std::move(vertex_order);
    if(m_rows_to_vertices.size() != n0)
    {
      m_rows_to_vertices.resize(n0);
      std::iota(m_rows_to_vertices.begin(), m_rows_to_vertices.end(), Index(0));
    }
    m_scaled = &geometry_for_computations(m_values[0], m_scaled_xyz) != &m_values[0];
  }

  void run(std::size_t max_levels, std::size_t min_vertices)
  {
    while(levels().size() < max_levels && rows() > min_vertices)
      if(!decompose_level(rows() - min_vertices))
        break;
    coarsest_mesh();
    m_visitor.on_finished(levels().size());
  }

private:
  std::vector<Pyramid_level>& levels() { return Pyramid_access::levels(m_pyr); }
  std::size_t rows() const { return m_rows_to_vertices.size(); }
  // the positions the geometric computations read (scaled into a safe range: geometry_for_computations())
  const std::vector<double>& xyz() const { return m_scaled ? m_scaled_xyz : m_values[0]; }

  bool decompose_level(std::size_t budget)
  {
    const std::size_t k = levels().size();
    // a visitor whose on_level_started() returns a bool cancels with false (void: never)
    if constexpr(std::is_same<decltype(m_visitor.on_level_started(k, rows())), bool>::value)
    {
      if(!m_visitor.on_level_started(k, rows()))
        return false;
    }
    else
      m_visitor.on_level_started(k, rows());
    connectivity(k);
    select(budget);
    if(m_accepted.empty())
    {
      std::vector<std::vector<double> >().swap(m_details);
      return false;
    }
    levels().emplace_back();
    Pyramid_level& level = levels().back();
    record_rows_and_targets(level);
    analyse_channels(level);
    collapse_face_array(level);
    m_halfedges_before = m_builder.take_connectivity();
    m_halfedges_before.keep_twins_only();
    m_builder = Relaxation_weight_builder();   // a level's halfedges follow its size
    move_to_next_level(level);
    m_visitor.on_level_finished(k, level.odd_rows.size());
    return true;
  }

  void connectivity(std::size_t k)
  {
    // with apexes: the selection's tests read them; after the first level, derived from the
    // halfedges of the level before and its collapses
    if(k == 0)
    {
      m_builder.set_connectivity(rows(), m_faces, true, halfedge_ends());
      m_cost.initialize(m_builder.connectivity(), m_faces, xyz());   // on M_0, rows are the input's vertex numbers
    }
    else
      m_builder.set_connectivity_after_collapses(rows(), m_faces, std::move(m_halfedges_before), std::move(m_collapsed),
                                                 halfedge_ends());
    m_cost.begin_level(m_rows_to_vertices, xyz());
  }

  // Whether the halfedges list their sources and targets (Triangle_halfedges::build()): the
  // selection and the 1-ring weights read a halfedge's ends from the face array and the twins
  // (select_collapses() is given the faces), SOD's hinges from these lists. Without them the
  // halfedges take 16 bytes per face less, at the peak of a level (level 0, or the weights'
  // arrays beside the greedy loop): the 3.1M-vertex horse's peak 1706 -> 1668 MB (1676 -> 1588 MB in
  // the input's order), the dragon's 230 -> 226 MB.
  bool halfedge_ends() const { return m_scheme == Relaxation_scheme::SECOND_ORDER_DIFFERENCE; }

  void select(std::size_t budget)
  {
    const Triangle_halfedges& th = m_builder.connectivity();
    if(m_scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE)
    {
      // The weights' corner pairs and cotangents, and the predictions of every channel, depend
      // on M_k and its values only (predict_with_rows_once()): they are computed beside the
      // taking of the candidates, which is sequential below four threads (the task's parallel
      // loops go on on both threads once the taking is done), on every level. Allocated here,
      // in this thread, once the candidates are sorted (where the front's arrays were freed;
      // allocated before the front, the 3.1M-vertex horse's peak rose from 2.46 to 2.51 times
      // its mesh)
      select_collapses(th, xyz().data(), Cost_of_rows<CostModel>{m_cost}, budget, m_on_border, m_locked,
                       m_source_of_target, m_accepted, 0, [&](const auto& take) {
                         m_builder.allocate_paired_rows(m_scheme);
                         allocate_predictions();
                         run_beside(take, [&] {
                           m_builder.fill_paired_rows(m_scheme, xyz().data());
                           predict();
                         });
                         m_builder.release_weight_data();
                       }, &m_faces);
    }
    else
      select_collapses(th, xyz().data(), Cost_of_rows<CostModel>{m_cost}, budget, m_on_border, m_locked,
                       m_source_of_target, m_accepted, 0, Run_in_place(), &m_faces);
    // in increasing o (the sources are distinct): an ordered compaction of the rows, not a sort
    m_target_of.assign(rows(), invalid_index);
    for(const Collapse& c : m_accepted)
      m_target_of[c.o] = c.e;
    auto is_source = [&](std::size_t r) { return m_target_of[r] != invalid_index; };
    const Ordered_compaction sources(rows(), is_source);
    m_accepted.resize(sources.size());
    sources.visit([&](std::size_t r, std::size_t rank, bool source) {
      if(source)
        m_accepted[rank] = Collapse{static_cast<Index>(r), m_target_of[r]};
    });
    if(m_scheme == Relaxation_scheme::SECOND_ORDER_DIFFERENCE)   // SOD's hinges read the twins
      return;
    m_builder.keep_outgoing_lists_only(true);       // the twins too: the next level's halfedges read them
  }

  // in parallel: the odd rows are the sources (m_target_of[r] set), the even rows the others
  void record_rows_and_targets(Pyramid_level& level)
  {
    level.vertices = m_rows_to_vertices;
    level.odd_rows.resize(m_accepted.size());
    level.collapse_targets.resize(m_accepted.size());
    parallel_for_blocks(m_accepted.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
      {
        level.odd_rows[i] = m_accepted[i].o;
        level.collapse_targets[i] = m_accepted[i].e;
      }
    });
    auto is_even = [&](std::size_t r) { return m_target_of[r] == invalid_index; };
    const Ordered_compaction even(rows(), is_even);
    level.even_rows.resize(even.size());
    even.visit([&](std::size_t r, std::size_t rank, bool kept) {
      if(kept)
        level.even_rows[rank] = static_cast<Index>(r);
    });
  }

  void analyse_channels(Pyramid_level& level)
  {
    // the weights are not kept: reconstruct() computes them again from the same positions
    // (Level_weights), which costs less than holding them. The 1-ring schemes compute each
    // row as it is applied, to every channel (predict_with_rows_once()), beside the selection
    // (select()); SOD's rows are assembled first (sequentially), then applied.
    if(m_scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE)
    {
      level.details = std::move(m_details);
      details_in_place(m_values, level.details, level.corrections);
      return;
    }
    m_builder.build(m_scheme, xyz().data(), nullptr, m_weights, m_rules);
    m_builder.release_weight_data();       // before the analysis' arrays: the peak memory is level 0's
    const std::size_t nc = m_values.size();
    level.details.resize(nc);
    level.corrections.resize(nc);
    for(std::size_t c = 0; c < nc; ++c)
      analyse_level(level, m_weights, m_pyr.dimensions()[c], m_values[c], level.details[c], level.corrections[c]);
    m_weights = Sparse_weights();
  }

  // every channel's predictions (predict_with_rows_once()), in the arrays of its details,
  // allocated in the calling thread (see run_beside())
  void allocate_predictions()
  {
    m_details.resize(m_values.size());
    for(std::size_t c = 0; c < m_values.size(); ++c)
      m_details[c].resize(m_values[c].size());
  }
  void predict()
  {
    predict_with_rows_once([&](const auto& apply_row) {
      m_builder.apply_rows(m_scheme, xyz().data(), nullptr, nullptr, rows(), apply_row);
    }, m_pyr.dimensions(), m_values, m_details);
  }

  void collapse_face_array(Pyramid_level& level);
  void take_out_removed_faces(Pyramid_level& level);

  void move_to_next_level(const Pyramid_level& level)
  {
    // (the rows' arrays are reduced in place and this one is kept: see keep_values_of_next_level());
    // the faces of M_{k+1} hold even rows only, so the entries of odd rows are not read
    std::vector<Index>& next_row = m_target_of;
    parallel_for_blocks(level.even_rows.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t j = first; j < last; ++j)
        next_row[level.even_rows[j]] = static_cast<Index>(j);
    });
    m_cost.next_level(m_accepted, level.even_rows, next_row);   // reads M_k's positions: before they move
    parallel_for_blocks(m_faces.size(), [&](std::size_t first, std::size_t last) {
      for(std::size_t i = first; i < last; ++i)
        m_faces[i] = next_row[m_faces[i]];
    });
    for(std::size_t c = 0; c < m_values.size(); ++c)
      keep_values_of_next_level(level, m_pyr.dimensions()[c], m_values[c]);
    if(m_scaled)
      keep_values_of_next_level(level, 3, m_scaled_xyz);
    keep_values_of_next_level(level, 1, m_rows_to_vertices);
    // the pages of what these arrays no longer use go back (their capacity stays level 0's),
    // and all of m_target_of's until select() fills it again, past the next level's peak
    for(std::vector<double>& values : m_values)
      release_unused_capacity(values);
    release_unused_capacity(m_scaled_xyz);
    release_unused_capacity(m_rows_to_vertices);
    release_unused_capacity(m_faces);
    m_target_of.clear();
    release_unused_capacity(m_target_of);
  }

  void coarsest_mesh()
  {
    Pyramid_access::coarse_vertices(m_pyr) = m_rows_to_vertices;
    m_faces.shrink_to_fit();                    // reduced in place from level 0's size
    Pyramid_access::coarse_faces(m_pyr) = std::move(m_faces);
    for(std::vector<double>& v : m_values)
      v.shrink_to_fit();                        // reduced in place from level 0's size
    Pyramid_access::coarse_values(m_pyr) = std::move(m_values);
  }

  Pyramid<TriangleMesh>& m_pyr;
  std::vector<std::vector<double> > m_values;   // per channel, rows of M_k
  std::vector<Index> m_faces;                   // the face array of M_k, rows of M_k
  std::vector<Index> m_rows_to_vertices;        // input number of every row of M_k
  bool m_scaled = false;                        // whether the positions needed a scale (geometry_for_computations())
  std::vector<double> m_scaled_xyz;             // the scaled positions, rows of M_k
  CostModel& m_cost;
  Relaxation_scheme m_scheme;
  Visitor& m_visitor;
  Relaxation_weight_builder m_builder;
  Sparse_weights m_weights;                     // lambda^k of the current level
  std::vector<Relaxation_row_rule> m_rules;
  std::vector<unsigned char> m_on_border, m_locked;
  std::vector<std::vector<double> > m_details;  // per channel, rows of M_k: the predictions (predict()), then the level's details
  Index_array m_source_of_target;               // selection scratch, kept across the levels
  std::vector<Collapse> m_accepted;
  std::vector<Index> m_target_of;               // the target of each accepted collapse's source, else invalid_index
  // what the next level's halfedges are derived from (Triangle_halfedges::build_after_collapses()):
  // M_k's halfedges (their twins) and the faces the level removed and kept
  Triangle_halfedges m_halfedges_before;
  Collapsed_faces m_collapsed;
  std::vector<unsigned char> m_face_removed;    // per face of M_k: 0 if kept, else 1 + the corner where its collapsed halfedge starts
};

// The collapses on the face array, recording how to undo them. The faces of two accepted
// collapses are disjoint (no face holds two odd vertices), so they are rewritten in place, in
// parallel: each collapse counts its removed and renamed faces, then writes its records at its
// place in the order of the accepted collapses (the records of a sequential loop).
template <typename TriangleMesh, typename CostModel, typename Visitor>
void Decomposition<TriangleMesh, CostModel, Visitor>::collapse_face_array(Pyramid_level& level)
{
  const Triangle_halfedges& th = m_builder.connectivity();
  const std::size_t na = m_accepted.size();
  std::vector<Index> first_renamed(na + 1, 0);
  m_face_removed.assign(m_faces.size() / 3, 0);
  // One pass over the faces of each source o: a face that holds e is removed (its flag says
  // where its collapsed halfedge starts), the others have o renamed e and are counted. The
  // second pass lists the renamed corners in order, telling them by the flags (a byte per
  // face) instead of reading the faces' corners again (two scattered reads per face: the
  // count and the records each read them, 6 % of a decomposition).
  parallel_for_blocks(na, [&](std::size_t first, std::size_t last) {
    Index* const faces = m_faces.data();
    unsigned char* const removed = m_face_removed.data();
    for(std::size_t i = first; i < last; ++i)
    {
      const Collapse& c = m_accepted[i];
      Index renamed = 0;
      for(Index q = th.out_offsets[c.o]; q < th.out_offsets[c.o + 1]; ++q)
      {
        const Index g = th.out[q];                         // o -> a in face g / 3, o at corner g % 3
        if(!th.has_face(g))
          continue;
        const Index prev = Triangle_halfedges::prev_in_face(g);
        const bool e_after_o = faces[Triangle_halfedges::next_in_face(g)] == c.e;   // (no other collapse renames these corners)
        if(e_after_o || faces[prev] == c.e)                // the face holds e: removed, its collapsed halfedge starts at o or at e
          removed[g / 3] = static_cast<unsigned char>(1 + (e_after_o ? g % 3 : prev % 3));
        else
        {
          faces[g] = c.e;
          ++renamed;
        }
      }
      first_renamed[i + 1] = renamed;
    }
  }, 1024);
  std::partial_sum(first_renamed.begin(), first_renamed.end(), first_renamed.begin());
  level.renamed_corners.resize(first_renamed[na]);
  level.renamed_vertices.resize(first_renamed[na]);
  parallel_for_blocks(na, [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
    {
      const Collapse& c = m_accepted[i];
      Index renamed = first_renamed[i];
      for(Index q = th.out_offsets[c.o]; q < th.out_offsets[c.o + 1]; ++q)
      {
        const Index g = th.out[q];
        if(th.has_face(g) && m_face_removed[g / 3] == 0)
        {
          level.renamed_corners[renamed] = g;
          level.renamed_vertices[renamed++] = c.o;
        }
      }
    }
  }, 1024);
  take_out_removed_faces(level);
}

// the face array of M_{k+1}: the removed faces taken out (order kept), recorded by position
// (an ordered compaction of the faces: the records in parallel, the kept faces in place)
template <typename TriangleMesh, typename CostModel, typename Visitor>
void Decomposition<TriangleMesh, CostModel, Visitor>::take_out_removed_faces(Pyramid_level& level)
{
  const std::size_t number_of_faces = m_faces.size() / 3;
  auto removed = [&](std::size_t p) { return m_face_removed[p] != 0; };
  const Ordered_compaction removed_faces(number_of_faces, removed);
  const std::size_t nr = removed_faces.size();
  level.removed_face_positions.resize(nr);
  level.removed_faces.resize(3 * nr);
  m_collapsed.face_after.resize(number_of_faces);
  constexpr std::size_t move_block = 4096;
  const std::size_t move_blocks = (number_of_faces + move_block - 1) / move_block;
  std::vector<std::size_t> kept_before(move_blocks + 1);   // per block of faces: the kept faces before it
  kept_before[move_blocks] = number_of_faces - nr;
  removed_faces.visit([&](std::size_t p, std::size_t rank, bool is_removed) {
    const Index* t = m_faces.data() + 3 * p;
    if(p % move_block == 0)
      kept_before[p / move_block] = p - rank;
    if(is_removed)
    {
      level.removed_face_positions[rank] = static_cast<Index>(p);
      copy_values(t, 3, level.removed_faces.data() + 3 * rank);
      m_collapsed.face_after[p] = Collapsed_faces::removed_face + (m_face_removed[p] - 1u);
    }
    else
      m_collapsed.face_after[p] = static_cast<Index>(p - rank);
  });
  // the kept faces moved down in place, in order (face p to p - rank <= p), the array's
  // capacity kept: a new array per level (zero-filled first) was mapped and touched anew on
  // large meshes. A block of faces writes below the faces it reads, into blocks before it,
  // which may not have read theirs yet: in parallel waves (move_down_in_waves()).
  Index* faces = m_faces.data();
  move_down_in_waves(move_blocks,
                     [&](std::size_t b) { return b * move_block; },
                     [&](std::size_t b) { return kept_before[b + 1]; },
                     [&](std::size_t b) {
                       std::size_t to = kept_before[b];
                       for(std::size_t p = b * move_block, e = (std::min)(number_of_faces, (b + 1) * move_block); p < e; ++p)
                         if(m_face_removed[p] == 0)
                         {
                           if(to != p)
                             copy_values(faces + 3 * p, 3, faces + 3 * to);
                           ++to;
                         }
                     });
  m_faces.resize(3 * (number_of_faces - nr));
}

// The values of every channel of the input, validated (channel 0: the coordinates)
template <typename TriangleMesh, typename VertexPointMap, typename GeomTraits, typename Maps>
std::vector<std::vector<double> > read_input_values(const Indexed_mesh<TriangleMesh>& im, VertexPointMap vpm, const GeomTraits& gt,
                                                     const Maps& maps, std::vector<std::size_t>& dimensions)
{
  std::vector<std::vector<double> > values(1 + std::tuple_size<Maps>::value);
  dimensions.assign(1, 3);
  read_coordinates(im.vertices, vpm, gt, values[0]);
  for_each_channel(maps, [&](const auto& map, auto c) {
    constexpr std::size_t dim = Channel_traits<std::decay_t<decltype(map)> >::dimension;
    values[decltype(c)::value + 1].resize(im.number_of_vertices() * dim);
    read_channel(map, im.vertices, decltype(c)::value + 1, values[decltype(c)::value + 1].data(), dim, 0);
    dimensions.push_back(dim);
  });
  return values;
}

} // namespace internal

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * decomposes `tm` into a Burt-Adelson mesh pyramid (Roy et al., Section 3).
 *
 * Level \f$ k \f$ goes from \f$ M_k \f$ (\f$ M_0 \f$ = `tm`) to \f$ M_{k+1} \f$: a greedy independent
 * set of half-edge collapses \f$ o \to e \f$ is chosen in increasing Garland-Heckbert cost
 * \f$ (Q_o + Q_e)(p_e) \f$ (any SMS cost policy through `get_cost`; quadrics accumulate over the
 * levels); among the \f$ n \f$ cheapest candidates of a level of \f$ n \f$ vertices (more while
 * fewer than \f$ n/16 \f$ are accepted), a collapse is accepted when \f$ o \f$ is free (not in the
 * closed 1-ring of an accepted source), \f$ e \f$ is the target of no accepted collapse, no accepted
 * \f$ o' \to e' \f$ crosses it (\f$ e \f$ a neighbour of \f$ o' \f$ and \f$ e' \f$ one of \f$ o \f$), the link
 * condition holds and no face flips; the closed 1-ring of \f$ o \f$ is then locked. Border vertices only collapse
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
 *     \cgalParamExtra{the default plane policies are evaluated on index arrays (the same quadrics, no halfedge mesh); any other policy reads SMS edge profiles on a working copy of the mesh, and one with per-vertex state (the rest of the Garland-Heckbert family) is re-created there with its default parameters}
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
 *   \cgalParamNBegin{memory_order}
 *     \cgalParamDescription{the order of the pyramid's vertices and faces: the input's, or a spatial order of its own,
 *                           which makes large meshes whose numbering is scattered decompose faster (see `Memory_order`)}
 *     \cgalParamType{`CGAL::Surface_mesh_multiresolution::Memory_order`}
 *     \cgalParamDefault{`Memory_order::AUTOMATIC`}
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
  typedef typename GetGeomTraits<TriangleMesh, NamedParameters>::type     Geom_traits;
  typedef typename GetVertexPointMap<TriangleMesh, NamedParameters>::const_type Vertex_point_map;
  typedef CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<TriangleMesh, Geom_traits> Default_cost;
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::get_cost_policy_t, NamedParameters,
                                                             Default_cost>::type Get_cost_param;
  typedef typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                             Decomposition_visitor_base>::type Visitor;
  typedef internal::Collapse_cost_model<TriangleMesh, Geom_traits, Get_cost_param> Cost_model;

  const Geom_traits gt = choose_parameter<Geom_traits>(get_parameter(np, CGAL::internal_np::geom_traits));
  const Vertex_point_map vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                                get_const_property_map(CGAL::vertex_point, tm));
  const Relaxation_scheme scheme = choose_parameter(get_parameter(np, internal_np::relaxation_scheme), Relaxation_scheme::CURVATURE);
  const std::size_t min_vertices = choose_parameter(get_parameter(np, internal_np::minimum_number_of_vertices), std::size_t(4));
  const std::size_t max_levels = choose_parameter(get_parameter(np, internal_np::number_of_levels),
                                                  (std::numeric_limits<std::size_t>::max)());
  Visitor visitor = choose_parameter<Visitor>(get_parameter(np, CGAL::internal_np::visitor));
  const auto maps = internal::as_tuple(choose_parameter(get_parameter(np, internal_np::vertex_attribute_maps), std::tuple<>()));

  // the levels reuse the large blocks the levels before them freed (internal::Block_pool)
  const internal::Block_pool_scope reuse_blocks;
  Pyramid<TriangleMesh> pyr;
  internal::Pyramid_access::set_relaxation_scheme(pyr, scheme);
  // validated index view of the input, the values of every channel, the collapse costs
  // (plane quadrics on index arrays for the default policy, a working halfedge mesh for any
  // other SMS policy)
  internal::Indexed_mesh<TriangleMesh> im;
  internal::build_indexed_mesh(tm, CGAL::get_initialized_vertex_index_map(tm, np), im);
  internal::Pyramid_access::set_number_of_input_vertices(pyr, im.number_of_vertices());
  std::vector<std::vector<double> > values
    = internal::read_input_values(im, vpm, gt, maps, internal::Pyramid_access::dimensions(pyr));
  Cost_model cost_model(tm, vpm, CGAL::get_initialized_vertex_index_map(tm, np), im, gt,
                        get_parameter(np, CGAL::internal_np::get_cost_policy));
  std::vector<internal::Index> faces;
  faces.swap(im.triangles);
  auto input_vertices = std::move(im.vertices);
  im = internal::Indexed_mesh<TriangleMesh>();   // not needed any more
  // the pyramid's own order (Memory_order): values and faces permuted once, the rows of M_0 in it
  std::vector<internal::Index> vertex_order;
  const Memory_order order = choose_parameter(get_parameter(np, internal_np::memory_order), Memory_order::AUTOMATIC);
  if(order == Memory_order::SPATIAL
     || (order == Memory_order::AUTOMATIC && values[0].size() / 3 >= internal::automatic_spatial_order_size
         && internal::numbering_is_scattered(values[0].size() / 3, faces)))
  {
    std::vector<internal::Index>& face_order = internal::Pyramid_access::face_order(pyr);
    internal::spatial_order(values[0], faces, vertex_order, face_order);
    if(!vertex_order.empty())
    {
      for(std::size_t c = 0; c < values.size(); ++c)
        internal::permute_values(vertex_order, pyr.dimensions()[c], values[c]);
      internal::permute_faces(vertex_order, face_order, faces);
    }
  }
  internal::Decomposition<TriangleMesh, Cost_model, Visitor> decomposition(pyr, std::move(values), std::move(faces),
                                                                           std::move(vertex_order), cost_model, scheme, visitor);
  decomposition.run(max_levels, min_vertices);
  // the positions the weights derive from, read again (validated above): no copy of them is
  // held through the first level, where a decomposition's memory peaks
  internal::read_coordinates(input_vertices, vpm, gt, internal::Pyramid_access::weight_positions(pyr));
  // every channel is the analysis of its input values, the geometry of the weight positions
  for(std::size_t c = 0; c < pyr.number_of_channels(); ++c)
    internal::Pyramid_access::set_analysis_state(pyr, c, c == 0 ? internal::Analysis_state::OF_WEIGHT_POSITIONS
                                                                : internal::Analysis_state::OF_VALUES);
  return pyr;
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_DECOMPOSE_H
