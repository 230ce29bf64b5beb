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

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// What adaptive reconstruction needs of a pyramid: for every odd vertex, its level, its
// collapse target, its faces in M_k (the vertex split that re-inserts it) and its detail
// length in the guiding channels.
struct Adaptive_hierarchy
{
  std::vector<Index> level_of;                 // per global number: the level where it is odd, or K (coarsest)
  std::vector<Index> target_of;                // per global number: collapse target (odd vertices)
  std::vector<std::vector<Index> > star;       // per level, per odd row q: 3 global numbers per face of its star in M_k
  std::vector<std::vector<Index> > star_offsets;
};

template <typename TriangleMesh>
void build_adaptive_hierarchy(const Pyramid<TriangleMesh>& pyr, Adaptive_hierarchy& h)
{
  const std::size_t K = pyr.number_of_levels(), n0 = pyr.number_of_input_vertices();
  h.level_of.assign(n0, static_cast<Index>(K));
  h.target_of.assign(n0, invalid_index);
  h.star.assign(K, std::vector<Index>());
  h.star_offsets.assign(K, std::vector<Index>());
  std::vector<Index> F = pyr.coarse_faces(), G, odd_index(n0, invalid_index);
  for(std::size_t k = K; k-- > 0; )
  {
    const Pyramid_level& lev = pyr.levels()[k];
    expand_faces(lev, F);                                      // F is now M_k's face array
    for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    {
      const Index o = lev.vertices[lev.odd_rows[q]];
      h.level_of[o] = static_cast<Index>(k);
      h.target_of[o] = lev.collapse_targets[q];
      odd_index[o] = static_cast<Index>(q);
    }
    // the faces of the star of each odd vertex: the renamed ones and the removed ones
    std::vector<std::vector<Index> > faces_of(lev.odd_rows.size());
    for(std::size_t q = 0; q < lev.renamed_corners.size(); ++q)
    {
      const Index p = lev.renamed_corners[q] / 3;
      faces_of[odd_index[lev.renamed_vertices[q]]].insert(faces_of[odd_index[lev.renamed_vertices[q]]].end(),
                                                          F.begin() + 3 * p, F.begin() + 3 * p + 3);
    }
    for(std::size_t r = 0; r < lev.removed_face_positions.size(); ++r)
      for(int i = 0; i < 3; ++i)
      {
        const Index v = lev.removed_faces[3 * r + i];
        if(h.level_of[v] == k && odd_index[v] != invalid_index)   // the one odd vertex of the face
        {
          faces_of[odd_index[v]].insert(faces_of[odd_index[v]].end(), lev.removed_faces.begin() + 3 * r,
                                        lev.removed_faces.begin() + 3 * r + 3);
          break;
        }
      }
    h.star_offsets[k].assign(1, 0);
    for(const auto& f : faces_of)
    {
      h.star[k].insert(h.star[k].end(), f.begin(), f.end());
      h.star_offsets[k].push_back(static_cast<Index>(h.star[k].size()));
    }
    for(Index r : lev.odd_rows)
      odd_index[lev.vertices[r]] = invalid_index;
  }
}

// the vertices kept for a selection: the selected odd vertices and, level after level from
// the finest, every vertex of the star (and the target) of a kept vertex
template <typename TriangleMesh>
std::vector<unsigned char> dependency_closure(const Pyramid<TriangleMesh>& pyr, const Adaptive_hierarchy& h,
                                              const std::vector<std::vector<double> >& importance, double threshold)
{
  const std::size_t K = pyr.number_of_levels();
  std::vector<unsigned char> keep(pyr.number_of_input_vertices(), 0);
  for(Index g : pyr.coarse_vertices())
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

inline std::uint64_t edge_key(Index a, Index b) { return (std::uint64_t(a) << 32) | b; }

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
 * \param np optional \ref smr_namedparameters "Named Parameters": `channel` (the guide), `target_number_of_vertices`
 *        (std::size_t: if given, the threshold is chosen, and `threshold` ignored, so that `out` has as many
 *        vertices as possible but at most this number, or the coarsest mesh), `vertex_attribute_maps`,
 *        `vertex_point_map` and `geom_traits` as for `reconstruct()`
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
  const std::size_t K = pyr.number_of_levels();

  // importance of every odd vertex: its detail length in the guide (and the scaled geometry)
  auto detail_length = [&](std::size_t j, std::size_t c, Index row) {
    const std::size_t dim = pyr.channel_dimension(c);
    const double* d = pyr.details(j, c).data() + std::size_t(row) * dim;
    double s = 0.;
    for(std::size_t k = 0; k < dim; ++k) s += d[k] * d[k];
    return std::sqrt(s);
  };
  double geometry_scale = 0.;
  if(guide != 0 && K > 0)
  {
    std::vector<double> lg, lc;
    for(Index r = 0; r < pyr.number_of_vertices(0); ++r) { lg.push_back(detail_length(1, 0, r)); lc.push_back(detail_length(1, guide, r)); }
    std::nth_element(lg.begin(), lg.begin() + lg.size() / 2, lg.end());
    std::nth_element(lc.begin(), lc.begin() + lc.size() / 2, lc.end());
    geometry_scale = lg[lg.size() / 2] > 0. ? lc[lc.size() / 2] / lg[lg.size() / 2] : 0.;
  }
  std::vector<std::vector<double> > importance(K);
  std::vector<double> all;
  for(std::size_t k = 0; k < K; ++k)
    for(Index r : pyr.levels()[k].odd_rows)
    {
      double x = detail_length(k + 1, guide, r);
      if(guide != 0) x = (std::max)(x, geometry_scale * detail_length(k + 1, 0, r));
      importance[k].push_back(x);
      all.push_back(x);
    }

  internal::Adaptive_hierarchy h;
  internal::build_adaptive_hierarchy(pyr, h);
  const auto target = get_parameter(np, internal_np::target_number_of_vertices);
  if constexpr(!std::is_same<std::decay_t<decltype(target)>, CGAL::internal_np::Param_not_found>::value)
  {
    // the smallest threshold whose closure fits: the closure shrinks as the threshold grows
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    all.push_back(std::numeric_limits<double>::infinity());
    auto count = [&](double t) {
      const auto keep = internal::dependency_closure(pyr, h, importance, t);
      return std::size_t(std::count(keep.begin(), keep.end(), 1));
    };
    std::size_t lo = 0, hi = all.size() - 1;                 // count(all[hi]) is the coarsest mesh
    while(lo < hi)
    {
      const std::size_t mid = (lo + hi) / 2;
      if(count(all[mid]) <= std::size_t(target)) hi = mid; else lo = mid + 1;
    }
    threshold = all[lo];
  }
  const std::vector<unsigned char> keep = internal::dependency_closure(pyr, h, importance, threshold);

  // vertex splits of the kept odd vertices, coarse to fine, on a face list indexed by edges
  std::vector<Index> F = pyr.coarse_faces();
  std::unordered_map<std::uint64_t, Index> face_of_edge;
  face_of_edge.reserve(3 * F.size());
  for(Index f = 0; f < F.size() / 3; ++f)
    for(int i = 0; i < 3; ++i)
      face_of_edge[internal::edge_key(F[3 * f + i], F[3 * f + (i + 1) % 3])] = f;
  for(std::size_t k = K; k-- > 0; )
  {
    const internal::Pyramid_level& lev = pyr.levels()[k];
    for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    {
      const Index o = lev.vertices[lev.odd_rows[q]];
      if(!keep[o])
        continue;
      const Index e = h.target_of[o];
      for(Index i = h.star_offsets[k][q]; i < h.star_offsets[k][q + 1]; i += 3)
      {
        const Index* t = h.star[k].data() + i;
        const int c = (t[0] == o) ? 0 : ((t[1] == o) ? 1 : 2);
        const Index a = t[(c + 1) % 3], b = t[(c + 2) % 3];
        if(a == e || b == e)
        {
          // a face removed by the collapse: back in
          const Index f = static_cast<Index>(F.size() / 3);
          F.insert(F.end(), t, t + 3);
          for(int j = 0; j < 3; ++j)
            face_of_edge[internal::edge_key(t[j], t[(j + 1) % 3])] = f;
        }
        else
        {
          // the face (e, a, b) of the coarser mesh becomes (o, a, b)
          const auto it = face_of_edge.find(internal::edge_key(a, b));
          CGAL_assertion(it != face_of_edge.end());
          const Index f = it->second;
          for(int j = 0; j < 3; ++j)
            if(F[3 * f + j] == e) F[3 * f + j] = o;
          face_of_edge.erase(internal::edge_key(e, a));
          face_of_edge.erase(internal::edge_key(b, e));
          face_of_edge[internal::edge_key(o, a)] = f;
          face_of_edge[internal::edge_key(b, o)] = f;
        }
      }
    }
  }

  // exact values of the kept vertices: those of the full reconstruction
  std::vector<Index> verts;
  for(Index g = 0; g < keep.size(); ++g)
    if(keep[g]) verts.push_back(g);
  internal::write_output_mesh(pyr, verts, [&](std::vector<Index>& faces) { faces.swap(F); },
                              [&](std::vector<std::vector<double> >& values) {
                                std::vector<Index> no_faces;
                                internal::reconstruct_arrays(pyr, 0, values, no_faces, false);   // values only: the faces are built above
                                for(std::size_t c = 0; c < values.size(); ++c)   // level 0's rows are the global numbers: keep those of verts
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
