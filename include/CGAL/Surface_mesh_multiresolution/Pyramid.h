// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_PYRAMID_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_PYRAMID_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Sparse_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_scheme.h>

#include <stdexcept>
#include <string>
#include <algorithm>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {

/// \cond SKIP_IN_MANUAL
namespace internal {

// One level of the pyramid: what goes from M_k to M_{k+1} and back, in one numbering: the
// rows of M_k, its vertices in increasing input number. Row j of M_{k+1} is even_rows[j] of
// M_k. The invariants (checked by check_pyramid(), Pyramid_checks.h) are stated there.
struct Pyramid_level
{
  std::vector<Index> vertices;                 // input number of every row (increasing but in a pyramid of its own order, Memory_order); derived, not saved
  // lambda^k over the rows of M_k: stored only in pyramids read from files of format 1 or 2;
  // otherwise empty, and computed from the pyramid's weight_positions() (level_weights.h)
  Sparse_weights weights;
  std::vector<std::vector<double> > details;   // per channel: dimension doubles per row of M_k
  // Exactness: f = fl(R f + d) can differ from f by rounding; the few components where it
  // does carry an additive correction, so that reconstruction returns f bit for bit.
  std::vector<std::vector<std::pair<Index, double> > > corrections;   // per channel: (row * dimension + component, correction), increasing
  std::vector<Index> odd_rows;                 // rows of M_k removed to make M_{k+1} (increasing)
  std::vector<Index> even_rows;                // the other rows (increasing); derived, not saved
  std::vector<Index> collapse_targets;         // per odd row q: the (even) row the odd vertex collapsed into
  // faces: M_{k+1}'s face array is M_k's with the removed faces taken out (order kept), the
  // corners of the odd vertices renamed to their targets, and the rows renumbered
  std::vector<Index> removed_face_positions;   // positions in M_k's face array, increasing
  std::vector<Index> removed_faces;            // 3 rows of M_k per removed face
  std::vector<Index> renamed_corners;          // 3 * position in M_k's face array + corner
  std::vector<Index> renamed_vertices;         // the odd row at that corner in M_k

  std::size_t number_of_rows() const { return vertices.size(); }
};

// The package's builders (decompose(), read_pyramid(), denoise()) write into a pyramid
// through this class; users only read it (and edit details through fixed-size views).
struct Pyramid_access;

// What is known of a channel's details, corrections and coarsest values: nothing (they may
// have been edited), that they are the exact analysis of some values on M_0 (a decomposition's
// attribute channels, a denoised channel), or that they are the exact analysis of the
// pyramid's weight positions (a decomposition's geometry). IO::write_pyramid() then need not
// analyse a channel again to know whether its values suffice, nor, for the weight positions,
// reconstruct it. Any non-const access to a channel's details makes it UNKNOWN.
enum class Analysis_state : unsigned char { UNKNOWN = 0, OF_VALUES = 1, OF_WEIGHT_POSITIONS = 2 };

} // namespace internal
/// \endcond

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * a view of the details of one level and one channel of a pyramid: their values can be
 * changed, their number cannot (so that `reconstruct()` always finds one detail per vertex).
 * It behaves as a range of `double`.
 */
class Detail_view
{
public:
  /// an empty view
  Detail_view() = default;
  /// \cond SKIP_IN_MANUAL
  Detail_view(double* data, std::size_t size) : m_data(data), m_size(size) {}
  /// \endcond
  /// the number of doubles: the number of vertices of the level times the channel's dimension
  std::size_t size() const { return m_size; }
  /// whether the view holds no value
  bool empty() const { return m_size == 0; }
  /// the first value
  double* data() const { return m_data; }
  /// the first value
  double* begin() const { return m_data; }
  /// past the last value
  double* end() const { return m_data + m_size; }
  /// the `i`-th value (no range check)
  double& operator[](std::size_t i) const { return m_data[i]; }

private:
  double* m_data = nullptr;
  std::size_t m_size = 0;
};

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * a Burt-Adelson mesh pyramid (Roy et al., Section 3): the coarsest mesh \f$ M_K \f$ with the
 * values of all its channels, and for every level \f$ k < K \f$ the relaxation weights
 * \f$ \lambda^k \f$ on \f$ M_k \f$, the details \f$ D_{k+1} \f$ of every vertex of \f$ M_k \f$ and every
 * channel, and the records of the half-edge collapses that made \f$ M_{k+1} \f$.
 *
 * It is a self-contained value: copyable, savable (`IO::write_pyramid()`), and
 * `reconstruct()` needs nothing else. Vertices are named by their rank in `vertices(tm)`
 * of the decomposed mesh. Channel 0 is the geometry (3 doubles); channels 1 to N are the
 * attribute maps given to `decompose()`, in tuple order.
 *
 * Detail sets are numbered as in the paper: \f$ D_1 \f$ (the finest, one value per vertex of
 * \f$ M_0 \f$) to \f$ D_K \f$ (one per vertex of \f$ M_{K-1} \f$).
 *
 * \tparam TriangleMesh the type of the decomposed mesh
 */
template <typename TriangleMesh>
class Pyramid
{
public:
  /// the mesh type
  typedef TriangleMesh Triangle_mesh;

  /// an empty pyramid (no vertex, no level)
  Pyramid() = default;

  /// \f$ K \f$: the number of detail sets, and of levels above the input
  std::size_t number_of_levels() const { return m_levels.size(); }

  /// \f$ |M_k| \f$ for \f$ 0 \le k \le K \f$
  std::size_t number_of_vertices(std::size_t k) const
  {
    check_mesh_level(k);
    return k < m_levels.size() ? m_levels[k].vertices.size() : m_coarse_vertices.size();
  }

  /// the number of faces of \f$ M_k \f$ for \f$ 0 \le k \le K \f$
  std::size_t number_of_faces(std::size_t k) const
  {
    check_mesh_level(k);
    std::size_t f = m_coarse_faces.size() / 3;
    for(std::size_t l = m_levels.size(); l > k; --l)
      f += m_levels[l - 1].removed_face_positions.size();
    return f;
  }

  /// 1 (the geometry) + the number of attribute channels
  std::size_t number_of_channels() const { return m_dimensions.size(); }

  /// the number of doubles of one value of channel `c` (3 for the geometry)
  std::size_t channel_dimension(std::size_t c) const { check_channel(c); return m_dimensions[c]; }

  /// the relaxation scheme of the weights
  Relaxation_scheme relaxation_scheme() const { return m_scheme; }

  /// the global numbers (ranks in the input) of the vertices of \f$ M_k \f$, in the order of the pyramid's rows:
  /// increasing, but for a pyramid decomposed in its own order (`Memory_order`)
  const std::vector<std::uint32_t>& vertices(std::size_t k) const
  {
    check_mesh_level(k);
    return k < m_levels.size() ? m_levels[k].vertices : m_coarse_vertices;
  }

  /*!
   * the details \f$ D_j \f$ of channel `c`, \f$ 1 \le j \le K \f$: `channel_dimension(c)` doubles
   * for every vertex of \f$ M_{j-1} \f$, in the order of `vertices(j-1)`. Their values can be
   * modified (filtering), their number cannot; `reconstruct()` uses them as they are.
   */
  Detail_view details(std::size_t j, std::size_t c)
  {
    check_detail_level(j);
    check_channel(c);
    if(c < m_analysed.size())
      m_analysed[c] = internal::Analysis_state::UNKNOWN;   // the details may change from here on
    std::vector<double>& d = m_levels[j - 1].details[c];
    return Detail_view(d.data(), d.size());
  }

  /// read access to the details \f$ D_j \f$ of channel `c`
  const std::vector<double>& details(std::size_t j, std::size_t c) const
  {
    check_detail_level(j);
    check_channel(c);
    return m_levels[j - 1].details[c];
  }

  /*!
   * the length of the detail of every vertex of \f$ M_{j-1} \f$ in channel `c` (the
   * Euclidean norm of its `channel_dimension(c)` values; the absolute value for a scalar
   * channel), in the order of `vertices(j-1)`, \f$ 1 \le j \le K \f$. Computed without overflow or
   * underflow: finite details have finite lengths.
   */
  std::vector<double> detail_lengths(std::size_t j, std::size_t c) const
  {
    const std::vector<double>& d = details(j, c);
    const std::size_t dim = m_dimensions[c];
    std::vector<double> lengths(d.size() / dim);
    for(std::size_t r = 0; r < lengths.size(); ++r)
      lengths[r] = internal::scaled_length(d.data() + r * dim, dim);
    return lengths;
  }

  /// the input numbers of the vertices removed between \f$ M_{j-1} \f$ and \f$ M_j \f$ (the odd vertices of \f$ D_j \f$), increasing, \f$ 1 \le j \le K \f$
  std::vector<std::uint32_t> odd_vertices(std::size_t j) const
  {
    check_detail_level(j);
    return input_numbers(m_levels[j - 1], m_levels[j - 1].odd_rows);
  }

  /// the input number of the vertex each odd vertex of \f$ D_j \f$ was collapsed into (in the order of `odd_vertices(j)`), \f$ 1 \le j \le K \f$
  std::vector<std::uint32_t> collapse_targets(std::size_t j) const
  {
    check_detail_level(j);
    return input_numbers(m_levels[j - 1], m_levels[j - 1].collapse_targets);
  }

  /// \cond SKIP_IN_MANUAL
  typedef internal::Index Index;
  // read access for the package's algorithms; writing goes through internal::Pyramid_access
  const std::vector<internal::Pyramid_level>& levels() const { return m_levels; }
  const std::vector<Index>& coarse_faces() const { return m_coarse_faces; }
  const std::vector<std::vector<double> >& coarse_values() const { return m_coarse_values; }
  const std::vector<std::size_t>& dimensions() const { return m_dimensions; }
  std::size_t number_of_input_vertices() const { return m_number_of_input_vertices; }
  // the positions (3 per input vertex) every level's weights are computed from: the input's
  // (empty where the levels store their weights: pyramids of format 1 and 2 files)
  const std::vector<double>& weight_positions() const { return m_weight_positions; }
  // per channel: whether its details, corrections and coarsest values are known to be the
  // exact analysis of values on M_0 (Analysis_state); empty: nothing known
  const std::vector<internal::Analysis_state>& analysis_states() const { return m_analysed; }
  /// \endcond

private:
  friend struct internal::Pyramid_access;

  static std::vector<std::uint32_t> input_numbers(const internal::Pyramid_level& lev, const std::vector<Index>& rows)
  {
    std::vector<std::uint32_t> out;
    out.reserve(rows.size());
    for(Index r : rows)
      out.push_back(lev.vertices[r]);
    return out;
  }

  void check_mesh_level(std::size_t k) const
  {
    if(k > m_levels.size())
      throw std::invalid_argument("mesh level " + std::to_string(k) + " does not exist: the pyramid has levels 0 to "
                                  + std::to_string(m_levels.size()));
  }
  void check_detail_level(std::size_t j) const
  {
    if(j < 1 || j > m_levels.size())
      throw std::invalid_argument("detail level " + std::to_string(j) + " does not exist: the pyramid has D_1 to D_"
                                  + std::to_string(m_levels.size()));
  }
  void check_channel(std::size_t c) const
  {
    if(c >= m_dimensions.size())
      throw std::invalid_argument("channel " + std::to_string(c) + " does not exist: the pyramid has "
                                  + std::to_string(m_dimensions.size()) + " channels");
  }

  Relaxation_scheme m_scheme = Relaxation_scheme::CURVATURE;
  std::size_t m_number_of_input_vertices = 0;
  std::vector<std::size_t> m_dimensions{3};
  std::vector<internal::Pyramid_level> m_levels;
  std::vector<Index> m_coarse_vertices;                 // input numbers of the rows of M_K (derived, not saved)
  std::vector<Index> m_coarse_faces;                    // 3 rows of M_K per face
  std::vector<std::vector<double> > m_coarse_values;    // per channel, rows of M_K
  std::vector<double> m_weight_positions;               // 3 per input vertex (level_weights.h)
  std::vector<internal::Analysis_state> m_analysed;     // per channel (analysis_states())
  std::vector<Index> m_face_order;                      // per face of M_0: its input position (Memory_order); empty: the input's order
};

/// \cond SKIP_IN_MANUAL
namespace internal {

struct Pyramid_access
{
  template <typename TM> static std::vector<Pyramid_level>& levels(Pyramid<TM>& p) { return p.m_levels; }
  template <typename TM> static std::vector<Index>& coarse_vertices(Pyramid<TM>& p) { return p.m_coarse_vertices; }
  template <typename TM> static std::vector<Index>& coarse_faces(Pyramid<TM>& p) { return p.m_coarse_faces; }
  template <typename TM> static std::vector<std::vector<double> >& coarse_values(Pyramid<TM>& p) { return p.m_coarse_values; }
  template <typename TM> static std::vector<std::size_t>& dimensions(Pyramid<TM>& p) { return p.m_dimensions; }
  template <typename TM> static std::vector<double>& weight_positions(Pyramid<TM>& p) { return p.m_weight_positions; }
  template <typename TM> static void set_number_of_input_vertices(Pyramid<TM>& p, std::size_t n) { p.m_number_of_input_vertices = n; }
  template <typename TM> static void set_relaxation_scheme(Pyramid<TM>& p, Relaxation_scheme s) { p.m_scheme = s; }
  template <typename TM> static std::vector<Analysis_state>& analysis_states(Pyramid<TM>& p) { return p.m_analysed; }
  template <typename TM> static std::vector<Index>& face_order(Pyramid<TM>& p) { return p.m_face_order; }
  template <typename TM> static const std::vector<Index>& face_order(const Pyramid<TM>& p) { return p.m_face_order; }
  // the state of channel c (every channel UNKNOWN first if no state is held)
  template <typename TM> static void set_analysis_state(Pyramid<TM>& p, std::size_t c, Analysis_state a)
  {
    p.m_analysed.resize(p.number_of_channels(), Analysis_state::UNKNOWN);
    p.m_analysed[c] = a;
  }
};

} // namespace internal
/// \endcond

} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_PYRAMID_H
