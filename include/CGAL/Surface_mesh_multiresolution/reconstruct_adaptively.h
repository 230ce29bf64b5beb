// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_RECONSTRUCT_ADAPTIVELY_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_RECONSTRUCT_ADAPTIVELY_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>
#include <CGAL/Surface_mesh_multiresolution/reconstruct.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_transform.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// What adaptive reconstruction needs of a pyramid: for every odd vertex, its level, its
// collapse target and its faces in M_k (the vertex split that re-inserts it), in input numbers
// (an adaptive mesh mixes the vertices of several levels).
struct Adaptive_hierarchy
{
  std::vector<Index> level_of;                 // per input number: the level where it is odd, or K (coarsest)
  std::vector<Index> target_of;                // per input number: collapse target (odd vertices)
  std::vector<Index> odd_number;               // per input number: its rank q among the odd vertices of its level
  std::vector<std::vector<Index> > star;       // per level, per odd row q: 3 input numbers per face of its star in M_k
  std::vector<std::vector<Index> > star_offsets;
  std::vector<Index> finest_faces;             // the face array of M_0 (input numbers)
};

// the faces of the star of every odd vertex of `lev` in M_k (F: M_k's face array, rows), in
// input numbers: the renamed ones and the removed ones (each holds one odd vertex)
inline void stars_of_level(const Pyramid_level& lev, const std::vector<Index>& F, std::vector<Index>& odd_index,
                           std::vector<Index>& star, std::vector<Index>& star_offsets)
{
  for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    odd_index[lev.odd_rows[q]] = static_cast<Index>(q);
  std::vector<std::vector<Index> > faces_of(lev.odd_rows.size());
  auto add_face = [&](Index q, const Index* t) {
    for(int i = 0; i < 3; ++i)
      faces_of[q].push_back(lev.vertices[t[i]]);
  };
  for(std::size_t q = 0; q < lev.renamed_corners.size(); ++q)
    add_face(odd_index[lev.renamed_vertices[q]], F.data() + 3 * std::size_t(lev.renamed_corners[q] / 3));
  for(std::size_t r = 0; r < lev.removed_face_positions.size(); ++r)
    for(int i = 0; i < 3; ++i)
    {
      const Index q = odd_index[lev.removed_faces[3 * r + i]];
      if(q != invalid_index)                                   // the one odd vertex of the face
      {
        add_face(q, lev.removed_faces.data() + 3 * r);
        break;
      }
    }
  star_offsets.assign(1, 0);
  for(const auto& f : faces_of)
  {
    star.insert(star.end(), f.begin(), f.end());
    star_offsets.push_back(static_cast<Index>(star.size()));
  }
  for(Index r : lev.odd_rows)
    odd_index[r] = invalid_index;
}

template <typename TriangleMesh>
void build_adaptive_hierarchy(const Pyramid<TriangleMesh>& pyr, Adaptive_hierarchy& h)
{
  const std::size_t K = pyr.number_of_levels(), n0 = pyr.number_of_input_vertices();
  h.level_of.assign(n0, static_cast<Index>(K));
  h.target_of.assign(n0, invalid_index);
  h.odd_number.assign(n0, invalid_index);
  h.star.assign(K, std::vector<Index>());
  h.star_offsets.assign(K, std::vector<Index>());
  std::vector<Index> F = pyr.coarse_faces(), odd_index(n0, invalid_index);
  for(std::size_t k = K; k-- > 0; )
  {
    const Pyramid_level& lev = pyr.levels()[k];
    expand_faces(lev, F);                                      // F is now M_k's face array
    for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    {
      const Index o = lev.vertices[lev.odd_rows[q]];
      h.level_of[o] = static_cast<Index>(k);
      h.target_of[o] = lev.vertices[lev.collapse_targets[q]];
      h.odd_number[o] = static_cast<Index>(q);
    }
    stars_of_level(lev, F, odd_index, h.star[k], h.star_offsets[k]);
  }
  h.finest_faces.swap(F);
}

// the vertices kept for a selection: the selected odd vertices and, level after level from
// the finest, every vertex of the star (and the target) of a kept vertex
template <typename TriangleMesh>
std::vector<unsigned char> dependency_closure(const Pyramid<TriangleMesh>& pyr, const Adaptive_hierarchy& h,
                                              const std::vector<std::vector<double> >& importance, double threshold)
{
  const std::size_t K = pyr.number_of_levels();
  std::vector<unsigned char> keep(pyr.number_of_input_vertices(), 0);
  for(Index g : pyr.vertices(K))
    keep[g] = 1;
  for(std::size_t k = 0; k < K; ++k)
  {
    const Pyramid_level& lev = pyr.levels()[k];
    for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    {
      const Index o = lev.vertices[lev.odd_rows[q]];
      if(importance[k][q] >= threshold)
        keep[o] = 1;
      if(!keep[o])
        continue;
      keep[h.target_of[o]] = 1;
      for(Index i = h.star_offsets[k][q]; i < h.star_offsets[k][q + 1]; ++i)
        keep[h.star[k][i]] = 1;
    }
  }
  return keep;
}

// The importance of every odd vertex of every level: its detail length in the guiding
// channel and, for an attribute guide, its geometry detail length brought to the guide's
// scale by the ratio of the median finest detail lengths of the two channels.
template <typename TriangleMesh>
std::vector<std::vector<double> > odd_vertex_importance(const Pyramid<TriangleMesh>& pyr, std::size_t guide)
{
  const std::size_t K = pyr.number_of_levels();
  auto median = [](std::vector<double> x) {
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    return x[x.size() / 2];
  };
  double geometry_scale = 0.;
  if(guide != 0 && K > 0 && pyr.number_of_vertices(0) > 0)
  {
    const double lg = median(pyr.detail_lengths(1, 0)), lc = median(pyr.detail_lengths(1, guide));
    geometry_scale = lg > 0. ? lc / lg : 0.;
    if(!std::isfinite(geometry_scale))
      geometry_scale = 0.;
  }
  std::vector<std::vector<double> > importance(K);
  for(std::size_t k = 0; k < K; ++k)
  {
    const std::vector<double> lengths = pyr.detail_lengths(k + 1, guide);
    std::vector<double> geometry;
    if(guide != 0)
      geometry = pyr.detail_lengths(k + 1, 0);
    for(Index r : pyr.levels()[k].odd_rows)
      importance[k].push_back(guide != 0 ? (std::max)(lengths[r], geometry_scale * geometry[r]) : lengths[r]);
  }
  return importance;
}

// The smallest threshold (among the importances, or infinity) whose dependency closure has at
// most `target` vertices. The closure grows as the threshold goes down, so the odd vertices are
// added in decreasing importance, each with its dependencies (depth first; every vertex is
// added once), and the count is read after each group of equal importance: one pass
// (O(n log n) for the sort), where a bisection over the thresholds would build about 20
// closures of the whole input.
template <typename TriangleMesh>
double threshold_for_budget(const Pyramid<TriangleMesh>& pyr, const Adaptive_hierarchy& h,
                            const std::vector<std::vector<double> >& importance, std::size_t target)
{
  const std::size_t K = pyr.number_of_levels();
  std::vector<std::pair<double, Index> > odd;                 // (importance, input number)
  for(std::size_t k = 0; k < K; ++k)
    for(std::size_t q = 0; q < importance[k].size(); ++q)
      odd.emplace_back(importance[k][q], pyr.levels()[k].vertices[pyr.levels()[k].odd_rows[q]]);
  std::sort(odd.begin(), odd.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<unsigned char> keep(pyr.number_of_input_vertices(), 0);
  std::vector<Index> pending;
  std::size_t count = 0;
  auto add = [&](Index v) {
    if(keep[v]) return;
    keep[v] = 1;
    ++count;
    pending.push_back(v);
  };
  for(Index g : pyr.vertices(K))
    add(g);
  auto close = [&] {                                          // the dependencies of what was added
    while(!pending.empty())
    {
      const Index v = pending.back();
      pending.pop_back();
      const Index k = h.level_of[v];
      if(k == K)
        continue;                                             // a vertex of the coarsest mesh
      const Index q = h.odd_number[v];
      add(h.target_of[v]);
      for(Index i = h.star_offsets[k][q]; i < h.star_offsets[k][q + 1]; ++i)
        add(h.star[k][i]);
    }
  };
  close();
  double best = std::numeric_limits<double>::infinity();
  for(std::size_t i = 0; i < odd.size() && count <= target; )
  {
    std::size_t j = i;
    for(; j < odd.size() && odd[j].first == odd[i].first; ++j)
      add(odd[j].second);
    close();
    if(count <= target)
      best = odd[i].first;
    i = j;
  }
  return best;
}

// The faces of the adaptive mesh, in rows of the kept vertices (increasing input numbers):
// the faces of M_0 with every vertex that is not kept replaced by the kept vertex it collapses
// into (through its collapse targets, level after level), the faces that lose a corner taken
// out. The dependency closure makes this the mesh the vertex splits of the kept vertices give
// from the coarsest mesh (tested equal), in M_0's face order, in one pass over M_0's faces
// with no search (the vertex splits on a hash map of edges took 2.7 s for half the dragon).
template <typename TriangleMesh>
std::vector<Index> adaptive_faces(const Pyramid<TriangleMesh>& pyr, const Adaptive_hierarchy& h,
                                  const std::vector<unsigned char>& keep, std::vector<Index>& kept_vertices)
{
  const std::size_t K = pyr.number_of_levels();
  std::vector<Index> rep(keep.size(), invalid_index);          // the kept vertex a vertex stands for
  for(Index g : pyr.vertices(K))
    rep[g] = g;
  for(std::size_t k = K; k-- > 0; )
  {
    const Pyramid_level& lev = pyr.levels()[k];
    for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    {
      const Index o = lev.vertices[lev.odd_rows[q]];
      rep[o] = keep[o] ? o : rep[lev.vertices[lev.collapse_targets[q]]];
    }
  }
  kept_vertices.clear();
  std::vector<Index> row_of(keep.size(), invalid_index);
  for(Index g = 0; g < keep.size(); ++g)
    if(keep[g])
    {
      row_of[g] = static_cast<Index>(kept_vertices.size());
      kept_vertices.push_back(g);
    }
  std::vector<Index> F;
  const std::vector<Index>& F0 = h.finest_faces;
  for(std::size_t i = 0; i + 2 < F0.size(); i += 3)
  {
    const Index a = rep[F0[i]], b = rep[F0[i + 1]], c = rep[F0[i + 2]];
    if(a != b && b != c && a != c)
      F.insert(F.end(), {row_of[a], row_of[b], row_of[c]});
  }
  return F;
}

} // namespace internal

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * threshold reconstruction (Roy et al., Section 4.3): rebuilds into `out` a mesh that holds
 * the coarsest mesh's vertices and only the odd vertices whose detail length reaches
 * `threshold` in the guiding channel, plus every vertex they depend on at coarser levels
 * (the vertices of the faces their vertex split needs), so that `out` is always a valid
 * triangle mesh of the input's topology. Every vertex of `out` has its exact input position
 * and attribute values (the details of the pyramid are used as they are).
 *
 * The guiding channel is `channel` (default 0, the geometry). As the paper says, the geometry
 * is always considered: with an attribute channel as guide, a vertex is also kept when its
 * geometry detail, brought to the guide's scale by the ratio of the median finest detail
 * lengths of the two channels, reaches `threshold`.
 *
 * \param pyr the pyramid
 * \param out receives the mesh; emptied first (on `Surface_mesh`, its property maps are kept)
 * \param threshold the detail length, \f$ \ge 0 \f$: 0 rebuilds the input mesh, \f$ \infty \f$ the coarsest
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{channel}
 *     \cgalParamDescription{the guiding channel (0: the geometry\, c: the c-th attribute map given to `decompose()`)}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{`0`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{target_number_of_vertices}
 *     \cgalParamDescription{if given\, the threshold is chosen (and `threshold` ignored) so that `out` has as many vertices as possible but at most this number\, or is the coarsest mesh}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{not given: `threshold` is used}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{vertex_attribute_maps}
 *     \cgalParamDescription{property maps of `out` receiving the attribute channels\, as for `reconstruct()`}
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
 * \cgalNamedParamsEnd
 * \returns the threshold used
 * \throws std::invalid_argument if `threshold` is negative or NaN, or the channel does not exist
 */
template <typename TriangleMesh, typename OutputMesh, typename NamedParameters = parameters::Default_named_parameters>
double reconstruct_adaptively(const Pyramid<TriangleMesh>& pyr, OutputMesh& out, double threshold,
                              const NamedParameters& np = parameters::default_values())
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef internal::Index Index;
  if(!(threshold >= 0.))
    throw std::invalid_argument("reconstruct_adaptively: the threshold must be non-negative");
  const std::size_t guide = choose_parameter(get_parameter(np, internal_np::channel), std::size_t(0));
  if(guide >= pyr.number_of_channels())
    throw std::invalid_argument("reconstruct_adaptively: channel " + std::to_string(guide) + " does not exist");

  // importance, budget search, dependency closure, vertex splits, values
  const std::vector<std::vector<double> > importance = internal::odd_vertex_importance(pyr, guide);
  internal::Adaptive_hierarchy h;
  internal::build_adaptive_hierarchy(pyr, h);
  const auto target = get_parameter(np, internal_np::target_number_of_vertices);
  if constexpr(!std::is_same<std::decay_t<decltype(target)>, CGAL::internal_np::Param_not_found>::value)
    threshold = internal::threshold_for_budget(pyr, h, importance, std::size_t(target));
  const std::vector<unsigned char> keep = internal::dependency_closure(pyr, h, importance, threshold);
  std::vector<Index> verts;
  std::vector<Index> F = internal::adaptive_faces(pyr, h, keep, verts);
  // exact values of the kept vertices: those of the full reconstruction
  internal::write_output_mesh(pyr, verts, [&](std::vector<Index>& faces) { faces.swap(F); },
                              [&](std::vector<std::vector<double> >& values) {
                                std::vector<Index> no_faces;
                                internal::reconstruct_arrays(pyr, 0, values, no_faces, false);   // values only
                                for(std::size_t c = 0; c < values.size(); ++c)   // level 0's rows are the input numbers
                                {
                                  const std::size_t dim = pyr.dimensions()[c];
                                  for(std::size_t r = 0; r < verts.size(); ++r)
                                    internal::copy_values(values[c].data() + std::size_t(verts[r]) * dim, dim, values[c].data() + r * dim);
                                  values[c].resize(verts.size() * dim);
                                }
                              },
                              out, np);
  return threshold;
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_RECONSTRUCT_ADAPTIVELY_H
