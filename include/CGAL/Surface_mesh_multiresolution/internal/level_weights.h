// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_LEVEL_WEIGHTS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_LEVEL_WEIGHTS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_transform.h>
#include <CGAL/Surface_mesh_multiresolution/internal/relaxation_weights.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Sparse_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The weights lambda^k of the levels of a pyramid. A pyramid keeps the positions its weights
// were computed from (Pyramid::weight_positions(): the input's, as every M_k is a subset of
// the input's vertices), not the weights: those of level k are computed again from the
// positions of M_k's vertices and M_k's face array, by the code and on the values that made
// them in decompose() (the positions scaled as there: geometry_scale_exponent() of all of
// them), so they are the same bit for bit and exact reconstruction holds. The weights were
// three quarters of a pyramid's memory and file. Levels may hold their weights
// (Pyramid_level::weights): after store_weights(), and in pyramids read from files of format
// 1 and 2, which have no positions.
class Level_weights
{
public:
  template <typename TriangleMesh>
  explicit Level_weights(const Pyramid<TriangleMesh>& pyr)
    : m_positions(pyr.weight_positions()), m_scheme(pyr.relaxation_scheme()),
      m_exponent(geometry_scale_exponent(m_positions.data(), m_positions.size()))
  {
    for(const Pyramid_level& lev : pyr.levels())
      m_all_stored = m_all_stored && stored(lev);
  }

  // room for the weights of the levels from the coarsest down to `level` (reconstruct()):
  // their arrays allocated once, at the size of M_level's
  template <typename TriangleMesh>
  void reserve(const Pyramid<TriangleMesh>& pyr, std::size_t level)
  {
    if(!computed())
      return;
    m_xyz.reserve(3 * pyr.number_of_vertices(level));
    if(m_scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE)   // SOD's rows read the halfedges, not the corner lists
      m_builder.reserve(pyr.number_of_vertices(level), 3 * pyr.number_of_faces(level));
  }

  // whether the level holds its weights (store_weights(), or a file of format 1 or 2)
  bool stored(const Pyramid_level& lev) const
  {
    return m_positions.empty() || lev.weights.offsets.size() == lev.number_of_rows() + 1;
  }

  // whether of() needs the face arrays of the levels (false: every level holds its weights)
  bool computed() const { return !m_all_stored; }

  // the weights of level `lev`, whose face array is F (rows of M_k; not read when the level
  // holds its weights); valid until the next call
  const Sparse_weights& of(const Pyramid_level& lev, const std::vector<Index>& F)
  {
    if(stored(lev))
      return lev.weights;
    m_builder.set_connectivity(lev.number_of_rows(), F);
    return computed_weights(lev);
  }

  // of() for a face array not yet known to form a halfedge mesh (a file's): F's halfedges are
  // built once, with apexes, for check(th) (the reason of a refusal in words, or empty), then
  // read by the weights, their corners paired from the twins as decompose() pairs them (the
  // same weights as of(), without its search in the rings: reading the dragon's pyramid built
  // every level's halfedges twice, once for the checks and once for the weights). nullptr
  // when check refuses.
  template <typename Check>
  const Sparse_weights* checked_of(const Pyramid_level& lev, const std::vector<Index>& F, const Check& check, std::string& error)
  {
    if(stored(lev))
    {
      Triangle_halfedges th;
      th.build(lev.number_of_rows(), F, true);
      error = check(th);
      return error.empty() ? &lev.weights : nullptr;
    }
    m_builder.set_connectivity(lev.number_of_rows(), F, true);
    error = check(m_builder.connectivity());
    if(!error.empty())
      return nullptr;
    if(m_scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE)   // SOD's hinges read the twins
    {
      m_builder.pair_corners_from_halfedges();
      m_builder.keep_outgoing_lists_only();
    }
    return &computed_weights(lev);
  }

  // The weights of a level computed row by row as they are applied, for a level whose rows
  // are each used once (the synthesis of a single channel: the odd rows, then the even ones):
  // apply_row_list() as Sparse_weights has it, with the same rows and sums, bit for bit,
  // without storing them (a reconstruction's weights were written and read again, 12 bytes per
  // entry, with a sequential prefix sum of the rows). Valid until the next call of the
  // Level_weights it comes from; each row applied at most once.
  class Rows_as_applied
  {
  public:
    Rows_as_applied(Relaxation_weight_builder& builder, Relaxation_scheme scheme, const double* xyz)
      : m_builder(&builder), m_scheme(scheme), m_xyz(xyz)
    {}

    void apply_row_list(const double* in, double* out, std::size_t dimension, const Index* rows, std::size_t count) const
    {
      m_builder->apply_rows(m_scheme, m_xyz, nullptr, rows, count,
                            [&](std::size_t i, const Index* col, const double* val, std::size_t length) {
        Sparse_weights::combine(col, val, length, in, out + i * dimension, dimension);
      });
    }

  private:
    Relaxation_weight_builder* m_builder;
    Relaxation_scheme m_scheme;
    const double* m_xyz;
  };

  // whether rows_as_applied() serves `lev` (weights computed, a 1-ring scheme)
  bool rows_computable_as_applied(const Pyramid_level& lev) const
  {
    return !stored(lev) && m_scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE;
  }

  // the weights of `lev` (rows_computable_as_applied()), whose face array is F, row by row
  Rows_as_applied rows_as_applied(const Pyramid_level& lev, const std::vector<Index>& F)
  {
    CGAL_precondition(rows_computable_as_applied(lev));
    m_builder.set_connectivity(lev.number_of_rows(), F);
    scale_positions(lev);
    m_builder.prepare_rows(m_scheme, m_xyz.data());
    return Rows_as_applied(m_builder, m_scheme, m_xyz.data());
  }

private:
  // m_xyz: the positions of `lev`'s rows, scaled as decompose() scales them
  void scale_positions(const Pyramid_level& lev)
  {
    const std::size_t n = lev.number_of_rows();
    m_xyz.resize(3 * n);
    parallel_for_blocks(n, [&](std::size_t first, std::size_t last) {
      for(std::size_t r = first; r < last; ++r)
        for(std::size_t c = 0; c < 3; ++c)
        {
          const double x = m_positions[3 * std::size_t(lev.vertices[r]) + c];
          m_xyz[3 * r + c] = m_exponent == 0 ? x : std::scalbn(x, -m_exponent);
        }
    });
  }

  // the weights of `lev` on the connectivity set in the builder
  const Sparse_weights& computed_weights(const Pyramid_level& lev)
  {
    scale_positions(lev);
    m_builder.build(m_scheme, m_xyz.data(), nullptr, m_weights, m_rules);
    return m_weights;
  }

  const std::vector<double>& m_positions;
  Relaxation_scheme m_scheme;
  int m_exponent;
  bool m_all_stored = true;
  std::vector<double> m_xyz;
  Relaxation_weight_builder m_builder;
  Sparse_weights m_weights;
  std::vector<Relaxation_row_rule> m_rules;
};

// No check of the face arrays: analyse_levels() on a pyramid that holds its invariants
struct Trusted_faces {};

// The analysis (Eq. 5) of the channels `channels` at every level from their values x[c] on M_0
// (rows = input numbers; x[c] may be empty for the other channels). The values of M_k are
// those of its vertices (every level is a subset of the input's vertices), so the levels are
// taken from the coarsest, their face arrays rebuilt on the way for their weights.
// done(k, c, details, corrections) receives the result of each level and channel.
// With a FacesCheck other than Trusted_faces (a file's pyramid, the invariants (6) and (7) of
// Pyramid_checks.h to check), check.records(lev, F) receives F_{k+1} and expands it into F_k
// and check.halfedges(lev, th) receives the halfedges of F_k, before level k's weights are
// computed on them; the first refusal is returned, in words, and the levels below are not
// analysed. Empty when every level was analysed.
template <typename TriangleMesh, typename Done, typename FacesCheck = Trusted_faces>
std::string analyse_levels(const Pyramid<TriangleMesh>& pyr, const std::vector<std::size_t>& channels,
                           const std::vector<std::vector<double> >& x, const Done& done,
                           const FacesCheck& check = FacesCheck())
{
  constexpr bool trusted = std::is_same<FacesCheck, Trusted_faces>::value;
  Level_weights weights(pyr);
  std::vector<Index> F, scratch;
  if(weights.computed() || !trusted)
    F = pyr.coarse_faces();
  std::vector<double> f, details;
  Corrections corrections;
  for(std::size_t k = pyr.number_of_levels(); k-- > 0; )
  {
    const Pyramid_level& level = pyr.levels()[k];
    const Sparse_weights* w = nullptr;
    if constexpr(trusted)
    {
      if(weights.computed())
        expand_faces(level, F, scratch);
      w = &weights.of(level, F);
    }
    else
    {
      std::string error = check.records(level, F);
      if(error.empty())
        w = weights.checked_of(level, F, [&](const Triangle_halfedges& th) { return check.halfedges(level, th); }, error);
      if(w == nullptr)
        return "level " + std::to_string(k) + ": " + error;
    }
    for(std::size_t c : channels)
    {
      const std::size_t dim = pyr.dimensions()[c];
      f.resize(level.vertices.size() * dim);
      for(std::size_t r = 0; r < level.vertices.size(); ++r)
        copy_values(x[c].data() + std::size_t(level.vertices[r]) * dim, dim, f.data() + r * dim);
      analyse_level(level, *w, dim, f, details, corrections);
      done(k, c, details, corrections);
    }
  }
  return std::string();
}

// the values x (dim per input vertex) of the vertices of M_K
template <typename TriangleMesh>
std::vector<double> coarsest_values(const Pyramid<TriangleMesh>& pyr, std::size_t dim, const std::vector<double>& x)
{
  const std::vector<Index>& vertices = pyr.vertices(pyr.number_of_levels());
  std::vector<double> f(vertices.size() * dim);
  for(std::size_t r = 0; r < vertices.size(); ++r)
    copy_values(x.data() + std::size_t(vertices[r]) * dim, dim, f.data() + r * dim);
  return f;
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_LEVEL_WEIGHTS_H
