// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PYRAMID_CHECKS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PYRAMID_CHECKS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/collapse_selection.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_transform.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Triangle_halfedges.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The invariants of a pyramid, stated once. n_k is the number of rows of M_k, F_k its face
// array (3 rows of M_k per face), K the number of levels.
//  (1) channels: channel 0 has dimension 3, every dimension is in [1, 4096];
//  (2) rows: n_0 is the number of input vertices; odd_rows of level k are increasing and
//      below n_k; even_rows are the other rows, increasing; n_{k+1} = |even_rows_k|;
//      vertices(0) a permutation of 0..n_0-1 (the identity but for a pyramid in its own
//      order, Memory_order; the face order then a permutation of M_0's faces) and
//      vertices(k+1)[j] = vertices(k)[even_rows_k[j]];
//  (3) weights: the pyramid has weight positions (3 finite doubles per input vertex), or
//      every level stores its weights; stored weights are a CSR over n_k rows (offsets from 0,
//      non-decreasing, ending at the number of entries), columns below n_k, finite values;
//  (4) details: n_k * dimension finite doubles per channel; corrections at increasing
//      positions below n_k * dimension, finite; coarsest values: n_K * dimension finite doubles;
//  (5) collapse targets: one per odd row, an even row of M_k, no two the same;
//  (6) faces: F_K below n_K; |F_k| = |F_{k+1}| + 3 |removed faces|; removed positions
//      increasing below |F_k| / 3; removed faces hold rows of M_k, exactly one odd, with its
//      collapse target; renamed corners distinct, below |F_k|, not in a removed face,
//      renamed to an odd row whose collapse target is the corner's vertex in M_{k+1}; every
//      face of every F_k has three different corners and no directed edge is in two faces
//      (each M_k is a halfedge mesh);
//  (7) collapses: on M_k, every odd vertex o is joined to its target e by an edge, no two
//      odd vertices are neighbours (the independent set of the selection), a border vertex
//      collapses along a border edge, no two collapses cross (e next to o' and e' next to o)
//      and the link condition holds: the collapses are those decompose() may accept, which
//      the vertex splits of an adaptive reconstruction rely on.
// The checks touch every record once per level (the face checks replay the vertex splits and
// build each level's halfedges): O(size of the pyramid) apart from sorting each vertex's
// out-going edges.

inline bool strictly_increasing_below(const std::vector<Index>& v, std::size_t bound)
{
  for(std::size_t i = 0; i < v.size(); ++i)
    if(v[i] >= bound || (i > 0 && v[i] <= v[i - 1])) return false;
  return true;
}

template <typename Allocator>
bool all_below(const std::vector<Index, Allocator>& v, std::size_t bound)
{
  for(Index x : v) if(x >= bound) return false;
  return true;
}

template <typename Allocator>
bool all_finite(const std::vector<double, Allocator>& v)
{
  for(double x : v) if(!std::isfinite(x)) return false;
  return true;
}

// whether the faces (3 vertex numbers below n each) have three different corners each and
// no directed edge twice: out-going edges counted by source, each vertex's targets sorted
inline bool is_halfedge_face_set(std::size_t n, const std::vector<Index>& F)
{
  std::vector<Index> offsets(n + 1, 0), targets(F.size());
  for(std::size_t f = 0; f + 2 < F.size(); f += 3)
  {
    if(F[f] == F[f + 1] || F[f + 1] == F[f + 2] || F[f] == F[f + 2])
      return false;
    for(int i = 0; i < 3; ++i) ++offsets[F[f + i] + 1];
  }
  for(std::size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
  std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
  for(std::size_t f = 0; f + 2 < F.size(); f += 3)
    for(int i = 0; i < 3; ++i)
      targets[fill[F[f + i]]++] = F[f + (i + 1) % 3];
  for(std::size_t v = 0; v < n; ++v)
  {
    std::sort(targets.begin() + offsets[v], targets.begin() + offsets[v + 1]);
    if(std::adjacent_find(targets.begin() + offsets[v], targets.begin() + offsets[v + 1]) != targets.begin() + offsets[v + 1])
      return false;
  }
  return true;
}

// whether a holds every number below a.size() once
inline bool is_permutation_of_first(const std::vector<Index>& a)
{
  std::vector<unsigned char> seen(a.size(), 0);
  for(Index x : a)
  {
    if(x >= a.size() || seen[x])
      return false;
    seen[x] = 1;
  }
  return true;
}

// (2): the even rows and the vertices of every level from the odd rows (what a file does not
// store) and level 0's vertex order (the input number of every row of M_0, a permutation;
// empty: the input's)
template <typename TriangleMesh>
std::string derive_rows(Pyramid<TriangleMesh>& pyr, const std::vector<Index>& vertex_order = std::vector<Index>())
{
  std::vector<Pyramid_level>& levels = Pyramid_access::levels(pyr);
  std::vector<Index> vertices(pyr.number_of_input_vertices());
  CGAL_precondition(vertex_order.empty() || vertex_order.size() == vertices.size());
  for(std::size_t i = 0; i < vertices.size(); ++i) vertices[i] = vertex_order.empty() ? static_cast<Index>(i) : vertex_order[i];
  for(std::size_t k = 0; k < levels.size(); ++k)
  {
    Pyramid_level& lev = levels[k];
    if(!strictly_increasing_below(lev.odd_rows, vertices.size()))
      return "level " + std::to_string(k) + ": odd rows not increasing or outside the level";
    lev.vertices = vertices;
    lev.even_rows.clear();
    std::size_t q = 0;
    for(Index r = 0; r < vertices.size(); ++r)
      if(q < lev.odd_rows.size() && lev.odd_rows[q] == r) ++q; else lev.even_rows.push_back(r);
    values_of_next_level(lev, 1, lev.vertices, vertices);
  }
  Pyramid_access::coarse_vertices(pyr) = vertices;
  return std::string();
}

// (3), (4), (5) for one level
inline std::string check_level_records(const Pyramid_level& lev, const std::vector<std::size_t>& dims, bool weights_required)
{
  const std::size_t n = lev.number_of_rows();
  const Sparse_weights& w = lev.weights;
  const bool stored = w.offsets.size() > 1 || !w.columns.empty() || !w.values.empty();
  if((weights_required || stored)
     && (w.offsets.size() != n + 1 || w.offsets[0] != 0 || w.offsets[n] != w.columns.size() || w.columns.size() != w.values.size()))
    return "weights of the wrong size";
  for(std::size_t i = 0; stored && i < n; ++i)
    if(w.offsets[i] > w.offsets[i + 1]) return "weight offsets decrease";
  if(stored && (!all_below(w.columns, n) || !all_finite(w.values)))
    return "a weight refers to a vertex outside the level or is not finite";
  if(lev.details.size() != dims.size() || lev.corrections.size() != dims.size())
    return "details of the wrong number of channels";
  for(std::size_t c = 0; c < dims.size(); ++c)
  {
    if(lev.details[c].size() != n * dims[c] || !all_finite(lev.details[c]))
      return "details of channel " + std::to_string(c) + " of the wrong size or not finite";
    for(std::size_t i = 0; i < lev.corrections[c].size(); ++i)
      if(lev.corrections[c][i].first >= n * dims[c] || !std::isfinite(lev.corrections[c][i].second)
         || (i > 0 && lev.corrections[c][i].first <= lev.corrections[c][i - 1].first))
        return "a correction of channel " + std::to_string(c) + " is outside the level, repeated or not finite";
  }
  std::vector<unsigned char> is_odd, target_seen(n, 0);
  odd_row_flags(lev, is_odd);
  if(lev.collapse_targets.size() != lev.odd_rows.size())
    return "not one collapse target per odd vertex";
  for(Index t : lev.collapse_targets)
  {
    if(t >= n || is_odd[t] || target_seen[t])
      return "a collapse target is outside the level, odd, or the target of two vertices";
    target_seen[t] = 1;
  }
  return std::string();
}

// (7) and the halfedge part of (6) for one level, on the halfedges of its face array F_k
// (built with apexes)
inline std::string check_level_halfedges(const Pyramid_level& lev, const Triangle_halfedges& th)
{
  if(th.repeated_directed_edge)                  // (a face that repeats a vertex has a loop edge)
    return "the faces of a level do not form a halfedge mesh";
  const std::size_t n = lev.number_of_rows();
  std::vector<unsigned char> on_border(n, 0);
  for(std::size_t h = 3 * th.nf; h < th.source.size(); ++h)
    on_border[th.source[h]] = on_border[th.target[h]] = 1;
  std::vector<unsigned char> is_odd;
  odd_row_flags(lev, is_odd);
  std::vector<Index> source_of_target(n, invalid_index);   // the odd vertex of each target
  for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    source_of_target[lev.collapse_targets[q]] = lev.odd_rows[q];
  // the collapses checked in parallel blocks; the refusal reported is that of the first
  // refused collapse, as a sequential loop finds it
  static const char* const why[] = {"", "two odd vertices are neighbours", "a collapse target is not a neighbour of its odd vertex",
                                    "a border vertex collapses off the border", "two collapses cross (each target next to the other's odd vertex)",
                                    "a collapse breaks the link condition"};
  auto refusal = [&](std::size_t q) {
    const Index o = lev.odd_rows[q], e = lev.collapse_targets[q];
    Index h = invalid_index;
    for(Index k = th.out_offsets[o]; k < th.out_offsets[o + 1]; ++k)
    {
      if(is_odd[th.out_target[k]])
        return 1;
      if(th.out_target[k] == e) h = th.out[k];
    }
    if(h == invalid_index) return 2;
    if(on_border[o] && !th.is_border_edge(h)) return 3;
    if(crosses_a_taken_collapse(th, o, e, [&](Index y) { return source_of_target[y] != invalid_index; },
                                [&](Index y) { return source_of_target[y]; }))
      return 4;
    return satisfies_link_condition(th, h, o, e, on_border) ? 0 : 5;
  };
  const std::size_t m = lev.odd_rows.size();
  const std::size_t first = first_position_where(m, [&](std::size_t q) { return refusal(q) != 0; });
  return first < m ? why[refusal(first)] : std::string();
}

// (6) but the halfedges, for one level: F holds F_{k+1} (rows of M_{k+1}) and receives F_k
// when the records allow its expansion
inline std::string check_records_and_expand_faces(const Pyramid_level& lev, std::vector<Index>& F)
{
  const std::size_t n = lev.number_of_rows(), removed = lev.removed_face_positions.size();
  const std::size_t faces = F.size() / 3 + removed;
  if(!strictly_increasing_below(lev.removed_face_positions, faces) || lev.removed_faces.size() != 3 * removed
     || !all_below(lev.removed_faces, n))
    return "removed faces out of order, of the wrong size or outside the level";
  if(lev.renamed_corners.size() != lev.renamed_vertices.size() || !all_below(lev.renamed_corners, 3 * faces)
     || !all_below(lev.renamed_vertices, n))
    return "renamed corners of the wrong size or outside the level";
  std::vector<unsigned char> is_odd;
  odd_row_flags(lev, is_odd);
  std::vector<Index> target_of(n, invalid_index);
  for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    target_of[lev.odd_rows[q]] = lev.collapse_targets[q];
  for(std::size_t r = 0; r < removed; ++r)
  {
    const Index* t = lev.removed_faces.data() + 3 * r;
    const int odd = int(is_odd[t[0]]) + int(is_odd[t[1]]) + int(is_odd[t[2]]);
    const Index o = is_odd[t[0]] ? t[0] : (is_odd[t[1]] ? t[1] : t[2]);
    if(odd != 1 || (t[0] != target_of[o] && t[1] != target_of[o] && t[2] != target_of[o]))
      return "a removed face does not hold one odd vertex and its collapse target";
  }
  std::vector<unsigned char> removed_at(faces, 0), renamed_at(3 * faces, 0);
  for(Index p : lev.removed_face_positions) removed_at[p] = 1;
  std::vector<Index> kept_before(faces + 1, 0);           // faces of F_k before p that are in F_{k+1}
  for(std::size_t p = 0; p < faces; ++p) kept_before[p + 1] = kept_before[p] + (removed_at[p] ? 0 : 1);
  for(std::size_t q = 0; q < lev.renamed_corners.size(); ++q)
  {
    const Index g = lev.renamed_corners[q], o = lev.renamed_vertices[q];
    if(removed_at[g / 3] || renamed_at[g] || !is_odd[o])
      return "a renamed corner is in a removed face, renamed twice, or not renamed to an odd vertex";
    renamed_at[g] = 1;
    const Index before = lev.even_rows[F[3 * std::size_t(kept_before[g / 3]) + g % 3]];   // its vertex in M_{k+1}
    if(before != target_of[o])
      return "a renamed corner did not hold the collapse target of its vertex";
  }
  expand_faces(lev, F);                                   // its other corners come from M_{k+1}: even
  return std::string();
}

// (6) and (7) for one level: F holds F_{k+1} (rows of M_{k+1}) and receives F_k
inline std::string check_and_expand_faces(const Pyramid_level& lev, std::vector<Index>& F)
{
  std::string why = check_records_and_expand_faces(lev, F);
  if(!why.empty())
    return why;
  Triangle_halfedges th;
  th.build(lev.number_of_rows(), F, true);
  return check_level_halfedges(lev, th);
}

// (1) to (5): the first invariant `pyr` breaks, in words; empty if it holds them all
template <typename TriangleMesh>
std::string check_pyramid_records(const Pyramid<TriangleMesh>& pyr)
{
  const std::vector<std::size_t>& dims = pyr.dimensions();
  if(dims.empty() || dims[0] != 3)
    return "channel 0 is not the geometry";
  for(std::size_t d : dims)
    if(d == 0 || d > 4096) return "a channel dimension is 0 or above 4096";
  const std::size_t K = pyr.number_of_levels();
  std::size_t n = pyr.number_of_input_vertices();
  const bool weights_required = pyr.weight_positions().empty();
  if(!weights_required && (pyr.weight_positions().size() != 3 * n || !all_finite(pyr.weight_positions())))
    return "weight positions of the wrong size or not finite";
  for(std::size_t k = 0; k < K; ++k)
  {
    const Pyramid_level& lev = pyr.levels()[k];
    if(lev.number_of_rows() != n || !strictly_increasing_below(lev.odd_rows, n)
       || lev.even_rows.size() + lev.odd_rows.size() != n || !strictly_increasing_below(lev.even_rows, n))
      return "level " + std::to_string(k) + ": rows inconsistent with the level above";
    const std::string why = check_level_records(lev, dims, weights_required);
    if(!why.empty())
      return "level " + std::to_string(k) + ": " + why;
    n = lev.even_rows.size();
  }
  if(pyr.vertices(K).size() != n || pyr.coarse_values().size() != dims.size())
    return "coarsest mesh inconsistent with the last level";
  for(std::size_t c = 0; c < dims.size(); ++c)
    if(pyr.coarse_values()[c].size() != n * dims[c] || !all_finite(pyr.coarse_values()[c]))
      return "coarsest values of channel " + std::to_string(c) + " of the wrong size or not finite";
  return std::string();
}

// (6) for F_K, on the rows (2)
template <typename TriangleMesh>
std::string check_coarsest_faces(const Pyramid<TriangleMesh>& pyr)
{
  const std::size_t n = pyr.vertices(pyr.number_of_levels()).size();
  const std::vector<Index>& F = pyr.coarse_faces();
  if(F.size() % 3 != 0 || !all_below(F, n) || !is_halfedge_face_set(n, F))
    return "the coarsest faces are not a halfedge mesh of the coarsest vertices";
  return std::string();
}

// (6) and (7) level by level, for analyse_levels() (level_weights.h) to check each level's
// faces before it computes weights on them
struct Level_faces_check
{
  std::string records(const Pyramid_level& lev, std::vector<Index>& F) const { return check_records_and_expand_faces(lev, F); }
  std::string halfedges(const Pyramid_level& lev, const Triangle_halfedges& th) const { return check_level_halfedges(lev, th); }
};

// (6) and (7), on the rows (2): the first invariant `pyr` breaks, in words; empty if it holds them all
template <typename TriangleMesh>
std::string check_pyramid_faces(const Pyramid<TriangleMesh>& pyr)
{
  const std::size_t K = pyr.number_of_levels();
  const std::string why = check_coarsest_faces(pyr);
  if(!why.empty())
    return why;
  std::vector<Index> F = pyr.coarse_faces();
  for(std::size_t k = K; k-- > 0; )
  {
    const std::string why = check_and_expand_faces(pyr.levels()[k], F);
    if(!why.empty())
      return "level " + std::to_string(k) + ": " + why;
  }
  return std::string();
}

// The first invariant `pyr` breaks, in words; empty if it holds them all. Expects the rows
// derived (derive_rows()) for pyramids read from a file.
template <typename TriangleMesh>
std::string check_pyramid(const Pyramid<TriangleMesh>& pyr)
{
  std::string why = check_pyramid_records(pyr);
  return why.empty() ? check_pyramid_faces(pyr) : why;
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_PYRAMID_CHECKS_H
