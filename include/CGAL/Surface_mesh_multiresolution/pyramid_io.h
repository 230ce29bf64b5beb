// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_PYRAMID_IO_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_PYRAMID_IO_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/level_weights.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Pyramid_checks.h>
#include <CGAL/Surface_mesh_multiresolution/reconstruct.h>
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <istream>
#include <ostream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The binary pyramid format (little-endian, IEEE-754 doubles):
//   8 bytes  magic "SMRPYR01"
//   u32      format version (3; a pyramid that stores its weights, read from a file of format
//            1 or 2, is written in format 2)
//   u32      0x01020304 (byte-order check)
//   u64      payload size in bytes
//   payload  the pyramid's arrays, each as u64 length + elements
//   u64      FNV-1a 64-bit hash of the payload
// Payload of version 4: that of version 3, then the pyramid's own order (Memory_order): the
// input number of every row of M_0 and the input position of every face of M_0, each an empty
// array where it is the input's (a file of version 3 is read with both empty). The values of
// kind 1 below are by input number in both versions.
// Payload of version 3: u32 relaxation scheme, u64 number of input vertices n, the channel
// dimensions, u64 K, the weight positions (3 n), the face array of M_0, per level the odd rows
// and the collapse targets; then per channel a u8 kind and its data:
//   0 (channel 0 only): its values on M_0 are the weight positions, nothing more;
//   1: its values on M_0 (n x dimension): the details and corrections are those of their
//      analysis (the pyramid of decompose() or denoise());
//   2: the details and corrections of every level, then the coarsest values (a channel whose
//      details were edited: filters, a pyramid read in format 2).
// Everything else is derived at load with the decomposition's own code: the even rows and
// the vertices of every level, the removed faces and renamed corners of each level (the
// collapses replayed on the face arrays), the weights (Level_weights) and the details of
// the kinds 0 and 1 (bit for bit those written, on the machine that reads), each level's
// faces checked on the halfedges its weights are then computed on. A pyramid file is then
// 0.7-0.8 times the binary PLY of its input as CGAL writes it (7-8 times in format 2, which
// stored the weights and every level's details and records).
// Payload of version 2: u32 relaxation scheme, u64 number of input vertices, the channel
// dimensions, u64 K, then per level (rows of M_k): weights (offsets, columns, values), per channel the
// details and corrections, odd rows, collapse targets, removed face positions, removed faces,
// renamed corners, renamed vertices; then the coarsest faces (rows of M_K) and, per channel,
// the coarsest values. Even rows and vertex numbers are derived from the odd rows.
// Version 1 (input numbers in the records, vertex lists stored) is read and converted.
// The checksum only detects accidents: every file is checked against the invariants of
// check_pyramid() before it is accepted.
// Why by hand: no serialisation library is among the dependencies, and the format is
// a handful of arrays.
constexpr char pyramid_magic[9] = "SMRPYR01";
constexpr std::uint32_t pyramid_format_version = 4;

inline std::uint64_t fnv1a(const std::string& bytes)
{
  std::uint64_t h = 14695981039346656037ull;
  for(unsigned char c : bytes) { h ^= c; h *= 1099511628211ull; }
  return h;
}

class Byte_writer
{
public:
  template <typename T>
  void scalar(const T& x)
  {
    static_assert(std::is_trivially_copyable<T>::value, "");
    m_bytes.append(reinterpret_cast<const char*>(&x), sizeof(T));
  }
  template <typename T, typename Allocator>
  void array(const std::vector<T, Allocator>& v)
  {
    scalar(std::uint64_t(v.size()));
    if(!v.empty())
      m_bytes.append(reinterpret_cast<const char*>(v.data()), sizeof(T) * v.size());
  }
  void corrections(const std::vector<std::pair<Index, double> >& v)
  {
    scalar(std::uint64_t(v.size()));
    for(const auto& p : v) { scalar(p.first); scalar(p.second); }
  }
  const std::string& bytes() const { return m_bytes; }
private:
  std::string m_bytes;
};

class Byte_reader
{
public:
  explicit Byte_reader(const std::string& bytes) : m_bytes(bytes) {}
  template <typename T>
  bool scalar(T& x)
  {
    if(m_bytes.size() - m_pos < sizeof(T)) return false;
    std::memcpy(&x, m_bytes.data() + m_pos, sizeof(T));
    m_pos += sizeof(T);
    return true;
  }
  template <typename T, typename Allocator>
  bool array(std::vector<T, Allocator>& v)
  {
    std::uint64_t n;
    if(!scalar(n) || n > (m_bytes.size() - m_pos) / sizeof(T)) return false;
    v.resize(static_cast<std::size_t>(n));
    if(n > 0) std::memcpy(v.data(), m_bytes.data() + m_pos, sizeof(T) * n);
    m_pos += sizeof(T) * static_cast<std::size_t>(n);
    return true;
  }
  bool corrections(std::vector<std::pair<Index, double> >& v)
  {
    std::uint64_t n;
    if(!scalar(n) || n > (m_bytes.size() - m_pos) / (sizeof(Index) + sizeof(double))) return false;
    v.resize(static_cast<std::size_t>(n));
    for(auto& p : v) if(!scalar(p.first) || !scalar(p.second)) return false;
    return true;
  }
  bool at_end() const { return m_pos == m_bytes.size(); }
private:
  const std::string& m_bytes;
  std::size_t m_pos = 0;
};

// The records of a version 1 file name vertices by input number: their rows are found in
// the level's vertex list (stored in version 1). False if a number is not in the list.
inline bool rows_from_input_numbers(const std::vector<Index>& vertices, std::vector<Index>& v)
{
  for(Index& x : v)
  {
    const auto it = std::lower_bound(vertices.begin(), vertices.end(), x);
    if(it == vertices.end() || *it != x) return false;
    x = static_cast<Index>(it - vertices.begin());
  }
  return true;
}

// one level of the payload; `version` 1 has the vertex list and the even rows too
inline bool read_level(Byte_reader& r, std::uint32_t version, std::size_t nc, Pyramid_level& l)
{
  if(version == 1 && !r.array(l.vertices)) return false;
  if(!r.array(l.weights.offsets) || !r.array(l.weights.columns) || !r.array(l.weights.values)) return false;
  l.details.resize(nc);
  l.corrections.resize(nc);
  for(std::size_t c = 0; c < nc; ++c)
    if(!r.array(l.details[c]) || !r.corrections(l.corrections[c])) return false;
  if(!r.array(l.odd_rows) || (version == 1 && !r.array(l.even_rows)) || !r.array(l.collapse_targets)
     || !r.array(l.removed_face_positions) || !r.array(l.removed_faces) || !r.array(l.renamed_corners)
     || !r.array(l.renamed_vertices))
    return false;
  if(version == 1)   // input numbers to rows of M_k
  {
    std::vector<Index> v(l.vertices);
    if(!std::is_sorted(v.begin(), v.end()) || !rows_from_input_numbers(v, l.collapse_targets)
       || !rows_from_input_numbers(v, l.removed_faces) || !rows_from_input_numbers(v, l.renamed_vertices))
      return false;
  }
  return true;
}

// The payload of a pyramid file into `p`, then the checks; the reason of a refusal in `error`
template <typename TriangleMesh>
bool read_payload(const std::string& bytes, std::uint32_t version, Pyramid<TriangleMesh>& p, std::string& error)
{
  Byte_reader r(bytes);
  std::uint32_t scheme;
  std::uint64_t n0, levels;
  std::vector<std::uint64_t> dims;
  error = "truncated or malformed payload";
  if(!r.scalar(scheme) || scheme > 2 || !r.scalar(n0) || n0 >= invalid_index || !r.array(dims)) return false;
  if(dims.empty() || dims[0] != 3) return false;
  for(std::uint64_t d : dims) if(d == 0 || d > 4096) return false;
  if(!r.scalar(levels) || levels > n0) return false;
  Pyramid_access::set_relaxation_scheme(p, static_cast<Relaxation_scheme>(scheme));
  Pyramid_access::set_number_of_input_vertices(p, static_cast<std::size_t>(n0));
  Pyramid_access::dimensions(p).assign(dims.begin(), dims.end());
  std::vector<Pyramid_level>& L = Pyramid_access::levels(p);
  L.resize(static_cast<std::size_t>(levels));
  if(version >= 3)
    return read_payload_v3(r, p, error, version);
  for(Pyramid_level& l : L)
    if(!read_level(r, version, dims.size(), l)) return false;
  std::vector<Index> coarse_vertices;
  if(version == 1 && !r.array(coarse_vertices)) return false;
  if(!r.array(Pyramid_access::coarse_faces(p))) return false;
  if(version == 1 && (!std::is_sorted(coarse_vertices.begin(), coarse_vertices.end())
                      || !rows_from_input_numbers(coarse_vertices, Pyramid_access::coarse_faces(p))))
    return false;
  Pyramid_access::coarse_values(p).resize(dims.size());
  for(std::size_t c = 0; c < dims.size(); ++c)
    if(!r.array(Pyramid_access::coarse_values(p)[c])) return false;
  if(!r.at_end()) return false;
  std::vector<std::vector<Index> > stored;   // version 1: the vertex lists, which must be the derived ones
  for(const Pyramid_level& l : L) stored.push_back(l.vertices);
  error = derive_rows(p);
  if(error.empty() && version == 1)
  {
    for(std::size_t k = 0; k < L.size(); ++k)
      if(stored[k] != L[k].vertices) error = "level " + std::to_string(k) + ": vertex list inconsistent with the odd rows";
    if(coarse_vertices != p.vertices(p.number_of_levels())) error = "coarsest vertex list inconsistent with the odd rows";
  }
  if(error.empty())
    error = check_pyramid(p);
  return error.empty();
}

// Version 3: the records of level k replayed on its face array F (rows of M_k, all below its
// number of rows), which becomes M_{k+1}'s: as collapse_face_array() makes them in
// decompose() (a removed face holds an odd vertex and its target; the other corners of odd
// vertices are renamed, in the order of the odd rows, then of the corners). An error in words
// where the odd rows and targets cannot be those of a level.
inline std::string replay_collapses(Pyramid_level& lev, std::vector<Index>& F)
{
  const std::size_t n = lev.number_of_rows();
  if(lev.collapse_targets.size() != lev.odd_rows.size())
    return "not one collapse target per odd vertex";
  std::vector<unsigned char> is_odd;
  odd_row_flags(lev, is_odd);
  std::vector<Index> target_of(n, invalid_index), rank(n, invalid_index);
  for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
  {
    const Index t = lev.collapse_targets[q];
    if(t >= n || is_odd[t])
      return "a collapse target is outside the level or odd";
    target_of[lev.odd_rows[q]] = t;
    rank[lev.odd_rows[q]] = static_cast<Index>(q);
  }
  std::vector<Index> next_row(n, invalid_index);
  for(std::size_t j = 0; j < lev.even_rows.size(); ++j)
    next_row[lev.even_rows[j]] = static_cast<Index>(j);
  lev.removed_face_positions.clear();
  lev.removed_faces.clear();
  std::vector<std::pair<Index, Index> > renamed;   // (rank of the odd row, corner), in corner order
  std::size_t write = 0;
  for(std::size_t p = 0; p < F.size() / 3; ++p)
  {
    Index* t = F.data() + 3 * p;
    int odd = -1;
    for(int i = 0; i < 3; ++i)
      if(is_odd[t[i]])
      {
        if(odd >= 0)
          return "a face holds two odd vertices";
        odd = i;
      }
    if(odd >= 0)
    {
      const Index e = target_of[t[odd]];
      if(t[0] == e || t[1] == e || t[2] == e)
      {
        lev.removed_face_positions.push_back(static_cast<Index>(p));
        lev.removed_faces.insert(lev.removed_faces.end(), t, t + 3);
        continue;
      }
      renamed.emplace_back(rank[t[odd]], static_cast<Index>(3 * p + odd));
      t[odd] = e;
    }
    for(int i = 0; i < 3; ++i)
      F[3 * write + i] = next_row[t[i]];
    ++write;
  }
  F.resize(3 * write);
  // in the order of the odd rows, then of the corners: a counting sort by rank (stable)
  std::vector<Index> first(lev.odd_rows.size() + 1, 0);
  for(const auto& r : renamed)
    ++first[r.first + 1];
  for(std::size_t q = 0; q < lev.odd_rows.size(); ++q)
    first[q + 1] += first[q];
  lev.renamed_corners.resize(renamed.size());
  lev.renamed_vertices.resize(renamed.size());
  for(const auto& r : renamed)
  {
    const Index at = first[r.first]++;
    lev.renamed_corners[at] = r.second;
    lev.renamed_vertices[at] = lev.odd_rows[r.first];
  }
  return std::string();
}

// whether two arrays of doubles hold the same bits (-0.0 is not 0.0)
inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

inline bool same_bits(const Corrections& a, const Corrections& b)
{
  if(a.size() != b.size()) return false;
  for(std::size_t i = 0; i < a.size(); ++i)
    if(a[i].first != b[i].first || std::memcmp(&a[i].second, &b[i].second, sizeof(double)) != 0) return false;
  return true;
}

// the payload of version 3 (see above): the values of every channel whose details are those
// of its analysis, the details of the others. A channel whose analysis state is known
// (Pyramid::analysis_states(): a decomposition's, a file's, a denoised channel) is not analysed
// again to tell; when every channel is the analysis of the weight positions, nothing is
// reconstructed but the face array of M_0 (a decomposed geometry: the dragon's file in 0.1 s
// instead of 1.3 s).
template <typename TriangleMesh>
void write_payload_v3(const Pyramid<TriangleMesh>& pyr, Byte_writer& w)
{
  const std::size_t nc = pyr.number_of_channels();
  const std::vector<Analysis_state>& known = pyr.analysis_states();
  auto state = [&](std::size_t c) { return c < known.size() ? known[c] : Analysis_state::UNKNOWN; };
  std::vector<std::size_t> unknown;
  for(std::size_t c = 0; c < nc; ++c)
    if(state(c) == Analysis_state::UNKNOWN)
      unknown.push_back(c);
  bool values_needed = !unknown.empty();
  for(std::size_t c = 0; c < nc; ++c)
    values_needed = values_needed || state(c) == Analysis_state::OF_VALUES;
  Values_workspace ws;
  if(values_needed)
  {
    reconstruct_values(pyr, 0, ws);             // exact; ws.faces: the face array of M_0, unless weights are stored
    values_by_input_number(pyr, ws.values);      // (what analyse_levels() and the file take)
  }
  if(ws.faces.empty())
    reconstruct_faces(pyr, 0, ws.faces);
  std::vector<unsigned char> analysed(nc, 1);
  if(!unknown.empty())
    analyse_levels(pyr, unknown, ws.values, [&](std::size_t k, std::size_t c, const std::vector<double>& d, const Corrections& corr) {
      const Pyramid_level& lev = pyr.levels()[k];
      analysed[c] = analysed[c] && same_bits(d, lev.details[c]) && same_bits(corr, lev.corrections[c]);
    });
  for(std::size_t c : unknown)
    analysed[c] = analysed[c] && same_bits(coarsest_values(pyr, pyr.dimensions()[c], ws.values[c]), pyr.coarse_values()[c]);

  w.array(pyr.weight_positions());
  w.array(ws.faces);
  for(const Pyramid_level& l : pyr.levels())
  {
    w.array(l.odd_rows);
    w.array(l.collapse_targets);
  }
  for(std::size_t c = 0; c < nc; ++c)
  {
    const std::uint8_t kind = !analysed[c] ? 2
                            : (c == 0 && (state(0) == Analysis_state::OF_WEIGHT_POSITIONS
                                          || same_bits(ws.values[0], pyr.weight_positions())) ? 0 : 1);
    w.scalar(kind);
    if(kind == 1)
      w.array(ws.values[c]);
    if(kind == 2)
    {
      for(const Pyramid_level& l : pyr.levels()) { w.array(l.details[c]); w.corrections(l.corrections[c]); }
      w.array(pyr.coarse_values()[c]);
    }
  }
  const std::vector<Index>& rows = pyr.vertices(0);   // version 4: the pyramid's own order, if any
  w.array(std::is_sorted(rows.begin(), rows.end()) ? std::vector<Index>() : rows);
  w.array(Pyramid_access::face_order(pyr));
}

// the rest of a version 3 payload after K (see above) into `p`, whose scheme, number of input
// vertices, dimensions and number of levels are set; then every derived array
template <typename TriangleMesh>
bool read_payload_v3(Byte_reader& r, Pyramid<TriangleMesh>& p, std::string& error, std::uint32_t version = 3)
{
  const std::size_t n0 = p.number_of_input_vertices(), nc = p.number_of_channels();
  std::vector<Pyramid_level>& L = Pyramid_access::levels(p);
  std::vector<double>& positions = Pyramid_access::weight_positions(p);
  std::vector<Index> F;
  if(!r.array(positions) || positions.size() != 3 * n0 || !r.array(F) || F.size() % 3 != 0 || !all_below(F, n0))
    return false;
  for(Pyramid_level& l : L)
    if(!r.array(l.odd_rows) || !r.array(l.collapse_targets)) return false;
  std::vector<std::vector<double> > values(nc);
  std::vector<std::size_t> analysed;
  std::vector<Analysis_state> states(nc, Analysis_state::UNKNOWN);
  for(std::size_t c = 0; c < nc; ++c)
  {
    std::uint8_t kind;
    if(!r.scalar(kind) || kind > 2 || (kind == 0 && c != 0)) return false;
    if(kind < 2)
      states[c] = kind == 0 ? Analysis_state::OF_WEIGHT_POSITIONS : Analysis_state::OF_VALUES;
    if(kind == 0)
      values[0] = positions;
    else if(kind == 1 && (!r.array(values[c]) || values[c].size() != n0 * p.dimensions()[c]))
      return false;
    if(kind < 2)
    {
      analysed.push_back(c);
      continue;
    }
    for(Pyramid_level& l : L)
    {
      l.details.resize(nc);
      l.corrections.resize(nc);
      if(!r.array(l.details[c]) || !r.corrections(l.corrections[c])) return false;
    }
    Pyramid_access::coarse_values(p).resize(nc);
    if(!r.array(Pyramid_access::coarse_values(p)[c])) return false;
  }
  // version 4: the pyramid's own order (Memory_order), empty where it is the input's
  std::vector<Index> vertex_order;
  std::vector<Index>& face_order = Pyramid_access::face_order(p);
  face_order.clear();
  if(version >= 4 && (!r.array(vertex_order) || !r.array(face_order))) return false;
  if(!r.at_end()) return false;
  if(!(vertex_order.empty() || (vertex_order.size() == n0 && is_permutation_of_first(vertex_order)))
     || !(face_order.empty() || (3 * face_order.size() == F.size() && is_permutation_of_first(face_order))))
  {
    error = "the pyramid's vertex or face order is not a permutation of the input's";
    return false;
  }
  error = derive_rows(p, vertex_order);
  for(std::size_t k = 0; k < L.size() && error.empty(); ++k)
  {
    error = replay_collapses(L[k], F);
    if(!error.empty())
      error = "level " + std::to_string(k) + ": " + error;
  }
  if(!error.empty())
    return false;
  Pyramid_access::coarse_faces(p).swap(F);
  for(std::size_t c : analysed)
    if(!all_finite(values[c]))
    {
      error = "values of channel " + std::to_string(c) + " not finite";
      return false;
    }
  for(Pyramid_level& l : L)
  {
    l.details.resize(nc);
    l.corrections.resize(nc);
  }
  Pyramid_access::coarse_values(p).resize(nc);
  // the faces must form halfedge meshes before weights are computed on them: each level's
  // are checked, on the halfedges its weights are then computed on, before its analysis
  if(analysed.empty())
    error = check_pyramid_faces(p);
  else
  {
    error = check_coarsest_faces(p);
    if(error.empty())
      error = analyse_levels(p, analysed, values, [&](std::size_t k, std::size_t c, std::vector<double>& d, Corrections& corr) {
        L[k].details[c].swap(d);
        L[k].corrections[c].swap(corr);
      }, Level_faces_check());
  }
  if(!error.empty())
    return false;
  for(std::size_t c : analysed)
    Pyramid_access::coarse_values(p)[c] = coarsest_values(p, p.dimensions()[c], values[c]);
  error = check_pyramid_records(p);
  if(!error.empty())
    return false;
  Pyramid_access::analysis_states(p) = states;   // what a file of version 3 says of its channels
  return true;
}

} // namespace internal

namespace IO {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * writes `pyr` to `os` in the package's versioned binary format (a header, the sizes of
 * all arrays and a checksum of the content). Open the stream in binary mode. The file holds
 * the input positions, the face array of \f$ M_0 \f$, the collapses of every level and, for
 * every channel, its values on \f$ M_0 \f$ where its details are those of their analysis
 * (the pyramid of `decompose()` or `denoise()`), its details otherwise (edited by a filter):
 * the rest is computed again when the file is read, bit for bit (0.7 to 0.8 times the size of
 * the input's binary PLY file). A channel whose details may have been edited since its
 * analysis (accessed through the non-const `Pyramid::details()`) is analysed again to tell.
 * \returns `true` if the stream is good after writing
 */
template <typename TriangleMesh>
bool write_pyramid(std::ostream& os, const Pyramid<TriangleMesh>& pyr)
{
  internal::Byte_writer w;
  w.scalar(std::uint32_t(pyr.relaxation_scheme()));
  w.scalar(std::uint64_t(pyr.number_of_input_vertices()));
  std::vector<std::uint64_t> dims(pyr.dimensions().begin(), pyr.dimensions().end());
  w.array(dims);
  w.scalar(std::uint64_t(pyr.number_of_levels()));
  // format 3 derives the weights from the positions; a pyramid that stores its weights (read
  // from a file of format 1 or 2) is written in format 2
  const std::uint32_t version = pyr.weight_positions().empty() ? 2 : internal::pyramid_format_version;
  if(version == internal::pyramid_format_version)
    internal::write_payload_v3(pyr, w);
  else
  {
    for(const internal::Pyramid_level& l : pyr.levels())
    {
      w.array(l.weights.offsets);
      w.array(l.weights.columns);
      w.array(l.weights.values);
      for(std::size_t c = 0; c < dims.size(); ++c) { w.array(l.details[c]); w.corrections(l.corrections[c]); }
      w.array(l.odd_rows);
      w.array(l.collapse_targets);
      w.array(l.removed_face_positions);
      w.array(l.removed_faces);
      w.array(l.renamed_corners);
      w.array(l.renamed_vertices);
    }
    w.array(pyr.coarse_faces());
    for(std::size_t c = 0; c < dims.size(); ++c) w.array(pyr.coarse_values()[c]);
  }

  const std::uint32_t byte_order = 0x01020304u;
  const std::uint64_t size = w.bytes().size(), hash = internal::fnv1a(w.bytes());
  os.write(internal::pyramid_magic, 8);
  os.write(reinterpret_cast<const char*>(&version), 4);
  os.write(reinterpret_cast<const char*>(&byte_order), 4);
  os.write(reinterpret_cast<const char*>(&size), 8);
  os.write(w.bytes().data(), static_cast<std::streamsize>(size));
  os.write(reinterpret_cast<const char*>(&hash), 8);
  return os.good();
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * reads a pyramid written by `write_pyramid()` (format version 4, or versions 1 to 3 of
 * earlier releases, whose pyramids keep the weights they store). The derived arrays (records
 * of the collapses, weights, details of unedited channels) are computed again: reading costs
 * about a third of a decomposition. Files are untrusted input: besides the header, sizes and checksum, the content
 * is checked against every invariant of a pyramid (indices within their levels, collapse
 * records consistent with the faces, every level a halfedge mesh, finite numbers...), so that
 * a pyramid this function accepts is safe in every function of the package. A truncated,
 * corrupted or inconsistent file makes it return `false`, with the reason in `error`, and
 * leaves `pyr` unchanged: no partial pyramid is ever produced.
 */
template <typename TriangleMesh>
bool read_pyramid(std::istream& is, Pyramid<TriangleMesh>& pyr, std::string& error)
{
  char magic[8];
  std::uint32_t version = 0, byte_order = 0;
  std::uint64_t size = 0, hash = 0;
  error = "not a pyramid file (no SMRPYR01 header)";
  if(!is.read(magic, 8) || std::memcmp(magic, internal::pyramid_magic, 8) != 0) return false;
  if(!is.read(reinterpret_cast<char*>(&version), 4) || version < 1 || version > internal::pyramid_format_version)
  {
    error = "pyramid format version " + std::to_string(version) + " is not supported (versions 1 to 4 are)";
    return false;
  }
  error = "truncated header or foreign byte order";
  if(!is.read(reinterpret_cast<char*>(&byte_order), 4) || byte_order != 0x01020304u) return false;
  if(!is.read(reinterpret_cast<char*>(&size), 8) || size > (std::uint64_t(1) << 40)) return false;
  std::string bytes;
  error = "truncated file";
  // grow with the data actually read, so that a corrupted size cannot allocate much
  while(bytes.size() < size)
  {
    const std::size_t chunk = static_cast<std::size_t>((std::min<std::uint64_t>)(size - bytes.size(), 1u << 24));
    const std::size_t old = bytes.size();
    bytes.resize(old + chunk);
    if(!is.read(&bytes[old], static_cast<std::streamsize>(chunk))) return false;
  }
  if(!is.read(reinterpret_cast<char*>(&hash), 8)) return false;
  if(hash != internal::fnv1a(bytes))
  {
    error = "checksum mismatch (corrupted file)";
    return false;
  }
  Pyramid<TriangleMesh> p;
  if(!internal::read_payload(bytes, version, p, error))
  {
    error = "inconsistent pyramid: " + error;
    return false;
  }
  pyr = std::move(p);
  error.clear();
  return true;
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * reads a pyramid as `read_pyramid(is, pyr, error)` does, without the reason of a refusal.
 */
template <typename TriangleMesh>
bool read_pyramid(std::istream& is, Pyramid<TriangleMesh>& pyr)
{
  std::string error;
  return read_pyramid(is, pyr, error);
}

} // namespace IO
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_PYRAMID_IO_H
