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
#include <CGAL/Surface_mesh_multiresolution/Pyramid.h>

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

// The binary pyramid format, version 1 (little-endian, IEEE-754 doubles):
//   8 bytes  magic "SMRPYR01"
//   u32      format version (1)
//   u32      0x01020304 (byte-order check)
//   u64      payload size in bytes
//   payload  the pyramid's arrays, each as u64 length + elements
//   u64      FNV-1a 64-bit hash of the payload
// Why by hand: no serialisation library is among the dependencies, and the format is
// a handful of arrays.
constexpr char pyramid_magic[9] = "SMRPYR01";
constexpr std::uint32_t pyramid_format_version = 1;

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
  template <typename T>
  void array(const std::vector<T>& v)
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
  template <typename T>
  bool array(std::vector<T>& v)
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

inline bool all_finite(const std::vector<double>& v)
{
  for(double x : v) if(!std::isfinite(x)) return false;
  return true;
}

inline bool increasing_below(const std::vector<Index>& v, std::size_t bound)
{
  for(std::size_t i = 0; i < v.size(); ++i)
    if(v[i] >= bound || (i > 0 && v[i] <= v[i - 1])) return false;
  return true;
}

inline bool all_below(const std::vector<Index>& v, std::size_t bound)
{
  for(Index x : v) if(x >= bound) return false;
  return true;
}

} // namespace internal

namespace IO {

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * writes `pyr` to `os` in the package's versioned binary format (a header, the sizes of
 * all arrays and a checksum of the content). Open the stream in binary mode.
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
  for(const internal::Pyramid_level& l : pyr.levels())
  {
    w.array(l.vertices);
    w.array(l.weights.offsets);
    w.array(l.weights.columns);
    w.array(l.weights.values);
    for(std::size_t c = 0; c < dims.size(); ++c) { w.array(l.details[c]); w.corrections(l.corrections[c]); }
    w.array(l.odd_rows);
    w.array(l.even_rows);
    w.array(l.collapse_targets);
    w.array(l.removed_face_positions);
    w.array(l.removed_faces);
    w.array(l.renamed_corners);
    w.array(l.renamed_vertices);
  }
  w.array(pyr.coarse_vertices());
  w.array(pyr.coarse_faces());
  for(std::size_t c = 0; c < dims.size(); ++c) w.array(pyr.coarse_values()[c]);

  const std::uint32_t byte_order = 0x01020304u;
  const std::uint64_t size = w.bytes().size(), hash = internal::fnv1a(w.bytes());
  os.write(internal::pyramid_magic, 8);
  os.write(reinterpret_cast<const char*>(&internal::pyramid_format_version), 4);
  os.write(reinterpret_cast<const char*>(&byte_order), 4);
  os.write(reinterpret_cast<const char*>(&size), 8);
  os.write(w.bytes().data(), static_cast<std::streamsize>(size));
  os.write(reinterpret_cast<const char*>(&hash), 8);
  return os.good();
}

/*!
 * \ingroup PkgSurfaceMeshMultiresolutionRef
 * reads a pyramid written by `write_pyramid()`. A truncated, corrupted or inconsistent
 * file, or one of another format version, makes it return `false` and leaves `pyr`
 * unchanged: no partial pyramid is ever produced.
 */
template <typename TriangleMesh>
bool read_pyramid(std::istream& is, Pyramid<TriangleMesh>& pyr)
{
  char magic[8];
  std::uint32_t version = 0, byte_order = 0;
  std::uint64_t size = 0, hash = 0;
  if(!is.read(magic, 8) || std::memcmp(magic, internal::pyramid_magic, 8) != 0) return false;
  if(!is.read(reinterpret_cast<char*>(&version), 4) || version != internal::pyramid_format_version) return false;
  if(!is.read(reinterpret_cast<char*>(&byte_order), 4) || byte_order != 0x01020304u) return false;
  if(!is.read(reinterpret_cast<char*>(&size), 8) || size > (std::uint64_t(1) << 40)) return false;
  std::string bytes;
  // grow with the data actually read, so that a corrupted size cannot allocate much
  while(bytes.size() < size)
  {
    const std::size_t chunk = static_cast<std::size_t>((std::min<std::uint64_t>)(size - bytes.size(), 1u << 24));
    const std::size_t old = bytes.size();
    bytes.resize(old + chunk);
    if(!is.read(&bytes[old], static_cast<std::streamsize>(chunk))) return false;
  }
  if(!is.read(reinterpret_cast<char*>(&hash), 8) || hash != internal::fnv1a(bytes)) return false;

  Pyramid<TriangleMesh> p;
  internal::Byte_reader r(bytes);
  std::uint32_t scheme;
  std::uint64_t n0, levels;
  std::vector<std::uint64_t> dims;
  if(!r.scalar(scheme) || scheme > 2 || !r.scalar(n0) || n0 >= internal::invalid_index || !r.array(dims)) return false;
  if(dims.empty() || dims[0] != 3) return false;
  for(std::uint64_t d : dims) if(d == 0 || d > 4096) return false;
  if(!r.scalar(levels) || levels > n0) return false;
  p.set_relaxation_scheme(static_cast<Relaxation_scheme>(scheme));
  p.number_of_input_vertices() = static_cast<std::size_t>(n0);
  p.dimensions().assign(dims.begin(), dims.end());
  const std::size_t nc = dims.size();
  p.levels().resize(static_cast<std::size_t>(levels));
  for(internal::Pyramid_level& l : p.levels())
  {
    if(!r.array(l.vertices) || !r.array(l.weights.offsets) || !r.array(l.weights.columns) || !r.array(l.weights.values))
      return false;
    l.details.resize(nc);
    l.corrections.resize(nc);
    for(std::size_t c = 0; c < nc; ++c)
      if(!r.array(l.details[c]) || !r.corrections(l.corrections[c])) return false;
    if(!r.array(l.odd_rows) || !r.array(l.even_rows) || !r.array(l.collapse_targets) || !r.array(l.removed_face_positions)
       || !r.array(l.removed_faces) || !r.array(l.renamed_corners) || !r.array(l.renamed_vertices))
      return false;
  }
  if(!r.array(p.coarse_vertices()) || !r.array(p.coarse_faces())) return false;
  p.coarse_values().resize(nc);
  for(std::size_t c = 0; c < nc; ++c)
    if(!r.array(p.coarse_values()[c])) return false;
  if(!r.at_end()) return false;

  // consistency: every index in range, every size as reconstruct() expects
  if(!internal::increasing_below(p.coarse_vertices(), n0) || p.coarse_faces().size() % 3 != 0
     || !internal::all_below(p.coarse_faces(), n0))
    return false;
  for(std::size_t c = 0; c < nc; ++c)
    if(p.coarse_values()[c].size() != p.coarse_vertices().size() * dims[c] || !internal::all_finite(p.coarse_values()[c]))
      return false;
  std::size_t faces_above = p.coarse_faces().size() / 3;
  for(std::size_t k = p.levels().size(); k-- > 0; )
  {
    const internal::Pyramid_level& l = p.levels()[k];
    const std::size_t nk = l.vertices.size();
    const std::size_t faces_here = faces_above + l.removed_face_positions.size();
    const internal::Sparse_weights& w = l.weights;
    if(!internal::increasing_below(l.vertices, n0) || w.offsets.size() != nk + 1 || w.offsets[0] != 0
       || w.offsets[nk] != w.columns.size() || w.columns.size() != w.values.size() || !internal::all_below(w.columns, nk)
       || !internal::all_finite(w.values))
      return false;
    for(std::size_t i = 0; i < nk; ++i)
      if(w.offsets[i] > w.offsets[i + 1]) return false;
    for(std::size_t c = 0; c < nc; ++c)
    {
      if(l.details[c].size() != nk * dims[c] || !internal::all_finite(l.details[c])) return false;
      for(const auto& cr : l.corrections[c])
        if(cr.first >= nk * dims[c] || !std::isfinite(cr.second)) return false;
    }
    if(!internal::increasing_below(l.odd_rows, nk) || !internal::increasing_below(l.even_rows, nk)
       || l.odd_rows.size() + l.even_rows.size() != nk || l.collapse_targets.size() != l.odd_rows.size()
       || !internal::all_below(l.collapse_targets, n0) || !internal::increasing_below(l.removed_face_positions, faces_here)
       || l.removed_faces.size() != 3 * l.removed_face_positions.size() || !internal::all_below(l.removed_faces, n0)
       || l.renamed_corners.size() != l.renamed_vertices.size() || !internal::all_below(l.renamed_corners, 3 * faces_here)
       || !internal::all_below(l.renamed_vertices, n0))
      return false;
    if(k + 1 < p.levels().size() ? p.levels()[k + 1].vertices.size() + l.odd_rows.size() != nk
                                 : p.coarse_vertices().size() + l.odd_rows.size() != nk)
      return false;
    faces_above = faces_here;
  }
  if(p.levels().empty() ? p.coarse_vertices().size() != n0 : p.levels()[0].vertices.size() != n0)
    return false;
  pyr = std::move(p);
  return true;
}

} // namespace IO
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_PYRAMID_IO_H
