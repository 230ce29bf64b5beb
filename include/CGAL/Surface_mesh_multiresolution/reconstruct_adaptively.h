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
#include <CGAL/Surface_mesh_multiresolution/Adaptive_criterion.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_transform.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>

#include <CGAL/Simple_cartesian.h>

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
  std::vector<Index> F = pyr.coarse_faces(), odd_index(n0, invalid_index), scratch;
  for(std::size_t k = K; k-- > 0; )
  {
    const Pyramid_level& lev = pyr.levels()[k];
    expand_faces(lev, F, scratch);                             // F is now M_k's face array
    for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    {
      const Index o = lev.vertices[lev.odd_rows[q]];
      h.level_of[o] = static_cast<Index>(k);
      h.target_of[o] = lev.vertices[lev.collapse_targets[q]];
      h.odd_number[o] = static_cast<Index>(q);
    }
    stars_of_level(lev, F, odd_index, h.star[k], h.star_offsets[k]);
  }
  // M_0's faces in input numbers, in the input's order (Memory_order: rows and faces may be
  // in the pyramid's own order)
  const std::vector<Index>& rows = pyr.vertices(0);
  if(!std::is_sorted(rows.begin(), rows.end()))
    for(Index& v : F)
      v = rows[v];
  faces_in_output_order(std::vector<Index>(), &Pyramid_access::face_order(pyr), F);
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

// squared distance from p to the triangle abc; a triangle without area is measured by its edges
inline double squared_distance_to_triangle(const double* p, const double* a, const double* b, const double* c)
{
  typedef CGAL::Simple_cartesian<double> SC;
  const SC::Point_3 P(p[0], p[1], p[2]), A(a[0], a[1], a[2]), B(b[0], b[1], b[2]), C(c[0], c[1], c[2]);
  double n[3];
  cross_of_differences(b, c, a, n);
  if(n[0] != 0. || n[1] != 0. || n[2] != 0.)
    return CGAL::squared_distance(P, SC::Triangle_3(A, B, C));
  return (std::min)({CGAL::squared_distance(P, SC::Segment_3(A, B)), CGAL::squared_distance(P, SC::Segment_3(B, C)),
                     CGAL::squared_distance(P, SC::Segment_3(C, A))});
}

// The approximation error of every odd vertex o of every level (Adaptive_criterion::
// APPROXIMATION_ERROR). Every input vertex p is followed on a face of M_k (at first one of its
// own faces): when a vertex o of that face collapses into its target t, the faces of o's star
// give way to the fan (the faces of the star without t, o renamed t), p is measured against
// the fan and moves to its nearest fan face. Both ways: the centroids of the fan's faces are
// measured against the star. `largest[k][q]`: the largest of these distances, how far the
// collapse moves the surface from the input whichever vertex the input vertices were collapsed
// into (the threshold's error); `ranking[k][q]`: the order of a vertex budget, the root of the
// sum of the squared distances of the input vertices (each centroid counting for as many input
// vertices as the star holds), the collapse's share of the RMS error, plus 64 times the square
// of the largest. Measured (bench_quality, 8 meshes at 25 / 5 / 1 %): the sum alone gives
// 3-8 % lower RMS errors than `largest` alone, with about equal Hausdorff errors; the term of
// the largest distance cuts the Hausdorff errors by up to 69 % (horse at 5 %: 4.71 -> 1.45),
// the RMS errors change by -2 to +7 %. Weights 16 and 256 tried: 16 leaves three Hausdorff
// errors above meshopt's of 18 rows, 256 costs Laurana's 1 % mesh 10 % more RMS error. The
// faces of M_k hold at most one odd vertex each (the odd vertices are independent), so the
// input vertices are measured in parallel, each about 0.6 times per level.
template <typename TriangleMesh>
void approximation_errors(const Pyramid<TriangleMesh>& pyr, const Adaptive_hierarchy& h,
                          std::vector<std::vector<double> >& largest, std::vector<std::vector<double> >& ranking)
{
  const std::size_t K = pyr.number_of_levels(), n0 = pyr.number_of_input_vertices();
  std::vector<std::vector<double> > values;
  reconstruct_input_values(pyr, values);                    // exact input positions, by input number
  std::vector<double> scaled;
  const std::vector<double>& x = geometry_for_computations(values[0], scaled);
  const int e = geometry_scale_exponent(values[0].data(), values[0].size());
  auto distance_to = [&](const double* p, const Index* f) {
    return squared_distance_to_triangle(p, &x[3 * std::size_t(f[0])], &x[3 * std::size_t(f[1])], &x[3 * std::size_t(f[2])]);
  };
  // the faces of the fan of every odd vertex o of level k, once per level: those of its star
  // without its target t, o renamed t (the target alone if none)
  std::vector<Index> fans, fan_offsets;
  auto build_fans = [&](std::size_t k) {
    const Pyramid_level& lev = pyr.levels()[k];
    fans.clear();
    fan_offsets.assign(1, 0);
    for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    {
      const Index o = lev.vertices[lev.odd_rows[q]], t = h.target_of[o];
      const std::size_t begin = fans.size();
      for(Index i = h.star_offsets[k][q]; i + 2 < h.star_offsets[k][q + 1]; i += 3)
      {
        const Index* g = h.star[k].data() + i;
        if(g[0] == t || g[1] == t || g[2] == t) continue;  // removed by the collapse
        for(int j = 0; j < 3; ++j) fans.push_back(g[j] == o ? t : g[j]);
      }
      if(fans.size() == begin) fans.insert(fans.end(), {t, t, t});
      fan_offsets.push_back(static_cast<Index>(fans.size()));
    }
  };
  std::vector<Index> face_of(3 * n0, invalid_index);         // the face each input vertex is on
  for(std::size_t i = 0; i < h.finest_faces.size(); ++i)
  {
    const Index p = h.finest_faces[i];
    if(face_of[3 * std::size_t(p)] == invalid_index)
      std::copy(h.finest_faces.begin() + 3 * (i / 3), h.finest_faces.begin() + 3 * (i / 3) + 3, face_of.begin() + 3 * std::size_t(p));
  }
  std::vector<double> moved(n0);
  std::vector<Index> by(n0);
  largest.assign(K, std::vector<double>());
  ranking.assign(K, std::vector<double>());
  for(std::size_t k = 0; k < K; ++k)
  {
    const Pyramid_level& lev = pyr.levels()[k];
    build_fans(k);
    parallel_for_blocks(n0, [&](std::size_t first, std::size_t last) {
      for(std::size_t p = first; p < last; ++p)
      {
        Index* f = &face_of[3 * p];
        by[p] = invalid_index;
        if(f[0] == invalid_index) continue;                   // a vertex without faces
        Index o = invalid_index;
        for(int j = 0; j < 3; ++j)
          if(h.level_of[f[j]] == k) o = f[j];
        if(o == invalid_index) continue;                      // its face stays in M_{k+1}
        const Index q = h.odd_number[o];
        double best = std::numeric_limits<double>::infinity();
        Index nearest = fan_offsets[q];
        for(Index i = fan_offsets[q]; i < fan_offsets[q + 1]; i += 3)
        {
          const double d = distance_to(&x[3 * p], &fans[i]);
          if(d < best) { best = d; nearest = i; }
        }
        std::copy(fans.begin() + nearest, fans.begin() + nearest + 3, f);
        moved[p] = best;
        by[p] = q;
      }
    }, 4096);
    const std::size_t n_odd = lev.odd_rows.size();
    std::vector<double>& worst = largest[k];
    std::vector<double>& sum = ranking[k];
    worst.assign(n_odd, 0.);
    sum.assign(n_odd, 0.);
    std::vector<double> points(n_odd, 0.);
    for(std::size_t p = 0; p < n0; ++p)
      if(by[p] != invalid_index)
      {
        worst[by[p]] = (std::max)(worst[by[p]], moved[p]);
        sum[by[p]] += moved[p];
        points[by[p]] += 1.;
      }
    parallel_for_blocks(n_odd, [&](std::size_t first, std::size_t last) {   // the fan against the star
      for(std::size_t q = first; q < last; ++q)
      {
        double far = 0.;
        for(Index i = fan_offsets[q]; i < fan_offsets[q + 1]; i += 3)
        {
          double c[3];
          for(int j = 0; j < 3; ++j)
            c[j] = (x[3 * std::size_t(fans[i]) + j] + x[3 * std::size_t(fans[i + 1]) + j] + x[3 * std::size_t(fans[i + 2]) + j]) / 3;
          double near = std::numeric_limits<double>::infinity();
          for(Index r = h.star_offsets[k][q]; r + 2 < h.star_offsets[k][q + 1]; r += 3)
            near = (std::min)(near, distance_to(c, h.star[k].data() + r));
          far = (std::max)(far, near);
        }
        const double worst2 = (std::max)(worst[q], far);
        worst[q] = std::scalbn(std::sqrt(worst2), e);
        sum[q] = std::scalbn(std::sqrt(sum[q] + far * (std::max)(points[q], 1.) + 64. * worst2), e);
      }
    }, 1024);
  }
}

// The kept vertices for a budget of `target` vertices with faces (vertices without faces are
// always kept and not counted): the odd vertices in decreasing importance, each with its
// dependencies (depth first; every vertex added once); one whose dependencies would exceed the
// budget is skipped (what it added is taken back) and the next ones are tried, until the
// budget is met exactly or every vertex was tried. One pass (O(n log n) for the sort, each
// vertex added or taken back at most once per try). `threshold` receives the importance of the
// last vertex kept (infinity when none).
template <typename TriangleMesh>
std::vector<unsigned char> keep_for_budget(const Pyramid<TriangleMesh>& pyr, const Adaptive_hierarchy& h,
                                           const std::vector<std::vector<double> >& importance, std::size_t target,
                                           double& threshold)
{
  const std::size_t K = pyr.number_of_levels(), n0 = pyr.number_of_input_vertices();
  std::vector<unsigned char> has_face(n0, 0);
  for(Index v : h.finest_faces) has_face[v] = 1;
  std::vector<std::pair<double, Index> > odd;                 // (importance, input number)
  for(std::size_t k = 0; k < K; ++k)
    for(std::size_t q = 0; q < importance[k].size(); ++q)
      odd.emplace_back(importance[k][q], pyr.levels()[k].vertices[pyr.levels()[k].odd_rows[q]]);
  std::stable_sort(odd.begin(), odd.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<unsigned char> keep(n0, 0);
  std::vector<Index> pending, added;
  std::size_t count = 0;
  auto add = [&](Index v) {
    if(keep[v]) return;
    keep[v] = 1;
    count += has_face[v];
    pending.push_back(v);
    added.push_back(v);
  };
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
  for(Index g : pyr.vertices(K))
    add(g);
  close();
  threshold = std::numeric_limits<double>::infinity();
  for(std::size_t i = 0; i < odd.size() && count < target; ++i)
  {
    if(keep[odd[i].second])
      continue;
    added.clear();
    add(odd[i].second);
    close();
    if(count <= target)
      threshold = odd[i].first;
    else
      for(Index v : added) { keep[v] = 0; count -= has_face[v]; }   // over the budget: taken back
  }
  return keep;
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

// What every adaptive reconstruction of one pyramid shares: the hierarchy, the importance of
// every odd vertex under the chosen criterion (and the ranking a vertex budget uses), the exact
// values of every input vertex (computed on first use); then any number of outputs.
template <typename TriangleMesh>
class Adaptive_reconstruction
{
public:
  template <typename NamedParameters>
  Adaptive_reconstruction(const Pyramid<TriangleMesh>& pyr, const NamedParameters& np, const char* function) : m_pyr(pyr)
  {
    using parameters::choose_parameter;
    using parameters::get_parameter;
    const std::size_t guide = choose_parameter(get_parameter(np, internal_np::channel), std::size_t(0));
    if(guide >= pyr.number_of_channels())
      throw std::invalid_argument(std::string(function) + ": channel " + std::to_string(guide) + " does not exist");
    const Adaptive_criterion criterion = choose_parameter(get_parameter(np, internal_np::adaptive_criterion),
                                                          Adaptive_criterion::DETAIL_LENGTH);
    if(criterion == Adaptive_criterion::APPROXIMATION_ERROR && guide != 0)
      throw std::invalid_argument(std::string(function) + ": the approximation error is measured on the geometry (channel 0)");
    m_drop_isolated = choose_parameter(get_parameter(np, internal_np::remove_isolated_vertices), false);
    build_adaptive_hierarchy(pyr, m_h);
    if(criterion == Adaptive_criterion::APPROXIMATION_ERROR)
      approximation_errors(pyr, m_h, m_importance, m_ranking);
    else
      m_importance = odd_vertex_importance(pyr, guide);
  }

  std::vector<unsigned char> keep_above(double threshold) const
  {
    return without_isolated(dependency_closure(m_pyr, m_h, m_importance, threshold));
  }

  // `threshold` receives the importance of the last vertex kept
  std::vector<unsigned char> keep_for(std::size_t vertices, double& threshold) const
  {
    return without_isolated(keep_for_budget(m_pyr, m_h, m_ranking.empty() ? m_importance : m_ranking, vertices, threshold));
  }

  // the kept vertices with their faces and exact values into `out`
  template <typename OutputMesh, typename NamedParameters>
  void write(const std::vector<unsigned char>& keep, OutputMesh& out, const NamedParameters& np)
  {
    std::vector<Index> verts;
    std::vector<Index> F = adaptive_faces(m_pyr, m_h, keep, verts);
    if(m_values.empty())
      reconstruct_input_values(m_pyr, m_values);                 // values only, by input number
    write_output_mesh(m_pyr, verts, [&](std::vector<Index>& faces) { faces.swap(F); },
                      [&](std::vector<std::vector<double> >& values) {
                        values.resize(m_values.size());
                        for(std::size_t c = 0; c < m_values.size(); ++c)
                        {
                          const std::size_t dim = m_pyr.dimensions()[c];
                          values[c].resize(verts.size() * dim);
                          for(std::size_t r = 0; r < verts.size(); ++r)
                            copy_values(m_values[c].data() + std::size_t(verts[r]) * dim, dim, values[c].data() + r * dim);
                        }
                      },
                      out, np);
  }

private:
  std::vector<unsigned char> without_isolated(std::vector<unsigned char> keep) const
  {
    if(m_drop_isolated)
    {
      std::vector<unsigned char> has_face(keep.size(), 0);
      for(Index v : m_h.finest_faces) has_face[v] = 1;
      for(std::size_t v = 0; v < keep.size(); ++v) keep[v] = keep[v] && has_face[v];
    }
    return keep;
  }

  const Pyramid<TriangleMesh>& m_pyr;
  Adaptive_hierarchy m_h;
  std::vector<std::vector<double> > m_importance, m_ranking;   // ranking: for a vertex budget, if not the importance
  std::vector<std::vector<double> > m_values;
  bool m_drop_isolated = false;
};

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
 * With `adaptive_criterion(Adaptive_criterion::APPROXIMATION_ERROR)` a vertex is kept when its
 * removal would move the surface by `threshold` or more (model units): every input vertex
 * left out is then within `threshold` of the faces that replaced it at the last collapse that
 * removed it (measured: the distance from the input vertices to `out` stays below about
 * 1.5 `threshold`, see the user manual).
 *
 * \param pyr the pyramid
 * \param out receives the mesh; emptied first (on `Surface_mesh`, its property maps are kept)
 * \param threshold the detail length or the distance, \f$ \ge 0 \f$: 0 rebuilds the input mesh, \f$ \infty \f$ the coarsest
 * \param np an optional sequence of \ref smr_namedparameters "Named Parameters" among the ones listed below
 *
 * \cgalNamedParamsBegin
 *   \cgalParamNBegin{channel}
 *     \cgalParamDescription{the guiding channel (0: the geometry\, c: the c-th attribute map given to `decompose()`)}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{`0`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{adaptive_criterion}
 *     \cgalParamDescription{what a vertex is kept for: `Adaptive_criterion::DETAIL_LENGTH` (the paper's rule; `threshold` a detail length in the guiding channel) or `Adaptive_criterion::APPROXIMATION_ERROR` (`threshold` a distance in model units; geometry only)}
 *     \cgalParamType{`Adaptive_criterion`}
 *     \cgalParamDefault{`Adaptive_criterion::DETAIL_LENGTH`}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{target_number_of_vertices}
 *     \cgalParamDescription{if given\, `threshold` is ignored and vertices are kept in decreasing importance of the criterion\, each with its dependencies\, skipping those whose dependencies would exceed the budget\, until `out` has exactly this number of vertices with faces or no vertex fits; never fewer than the coarsest mesh}
 *     \cgalParamType{std::size_t}
 *     \cgalParamDefault{not given: `threshold` is used}
 *   \cgalParamNEnd
 *   \cgalParamNBegin{remove_isolated_vertices}
 *     \cgalParamDescription{if `true`\, input vertices without faces are left out of `out` (otherwise they are kept\, at their input positions\, and not counted in a vertex budget)}
 *     \cgalParamType{bool}
 *     \cgalParamDefault{`false`}
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
 * \returns the threshold used (with a vertex budget: the importance of the last vertex kept, infinity when none)
 * \throws std::invalid_argument if `threshold` is negative or NaN, the channel does not exist, or the
 *         approximation error is asked with an attribute channel as guide
 */
template <typename TriangleMesh, typename OutputMesh, typename NamedParameters = parameters::Default_named_parameters>
double reconstruct_adaptively(const Pyramid<TriangleMesh>& pyr, OutputMesh& out, double threshold,
                              const NamedParameters& np = parameters::default_values())
{
  using parameters::get_parameter;
  if(!(threshold >= 0.))
    throw std::invalid_argument("reconstruct_adaptively: the threshold must be non-negative");
  internal::Adaptive_reconstruction<TriangleMesh> adaptive(pyr, np, "reconstruct_adaptively");
  std::vector<unsigned char> keep;
  const auto target = get_parameter(np, internal_np::target_number_of_vertices);
  if constexpr(!std::is_same<std::decay_t<decltype(target)>, CGAL::internal_np::Param_not_found>::value)
    keep = adaptive.keep_for(std::size_t(target), threshold);
  else
    keep = adaptive.keep_above(threshold);
  adaptive.write(keep, out, np);
  return threshold;
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * a chain of levels of detail in one pass: `outputs[i]` receives the adaptive reconstruction of
 * `pyr` to `vertex_counts[i]` vertices, as `reconstruct_adaptively()` with
 * `target_number_of_vertices(vertex_counts[i])` gives it, with the hierarchy, the importance of
 * every vertex and the exact values computed once for the whole chain.
 *
 * \param pyr the pyramid
 * \param vertex_counts the vertex budgets (any order)
 * \param outputs resized to as many meshes as budgets; each emptied first
 * \param np the named parameters of `reconstruct_adaptively()` but `target_number_of_vertices`:
 *        `adaptive_criterion`, `channel`, `remove_isolated_vertices`, `vertex_point_map`,
 *        `geom_traits`, and `vertex_attribute_maps` with a single budget only (the maps belong
 *        to one output mesh)
 * \throws std::invalid_argument as `reconstruct_adaptively()`, and if `vertex_attribute_maps` is
 *         given with several budgets
 */
template <typename TriangleMesh, typename OutputMesh, typename NamedParameters = parameters::Default_named_parameters>
void extract_levels_of_detail(const Pyramid<TriangleMesh>& pyr, const std::vector<std::size_t>& vertex_counts,
                              std::vector<OutputMesh>& outputs, const NamedParameters& np = parameters::default_values())
{
  using parameters::get_parameter;
  const auto maps = get_parameter(np, internal_np::vertex_attribute_maps);
  if constexpr(!std::is_same<std::decay_t<decltype(maps)>, CGAL::internal_np::Param_not_found>::value)
    if(vertex_counts.size() > 1)
      throw std::invalid_argument("extract_levels_of_detail: vertex_attribute_maps are maps of one mesh; give one budget per call");
  internal::Adaptive_reconstruction<TriangleMesh> adaptive(pyr, np, "extract_levels_of_detail");
  outputs.resize(vertex_counts.size());
  for(std::size_t i = 0; i < vertex_counts.size(); ++i)
  {
    double threshold = 0.;
    adaptive.write(adaptive.keep_for(vertex_counts[i], threshold), outputs[i], np);
  }
}

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_RECONSTRUCT_ADAPTIVELY_H
