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
#include <CGAL/Surface_mesh_multiresolution/internal/Pyramid_checks.h>
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

// The binary pyramid format, version 2 (little-endian, IEEE-754 doubles):
//   8 bytes  magic "SMRPYR01"
//   u32      format version (2)
//   u32      0x01020304 (byte-order check)
//   u64      payload size in bytes
//   payload  the pyramid's arrays, each as u64 length + elements
//   u64      FNV-1a 64-bit hash of the payload
// Payload: u32 relaxation scheme, u64 number of input vertices, the channel dimensions,
// u64 K, then per level (rows of M_k): weights (offsets, columns, values), per channel the
// details and corrections, odd rows, collapse targets, removed face positions, removed faces,
// renamed corners, renamed vertices; then the coarsest faces (rows of M_K) and, per channel,
// the coarsest values. Even rows and vertex numbers are derived from the odd rows.
// Version 1 (input numbers in the records, vertex lists stored) is read and converted.
// The checksum only detects accidents: every file is checked against the invariants of
// check_pyramid() before it is accepted.
// Why by hand: no serialisation library is among the dependencies, and the format is
// a handful of arrays.
constexpr char pyramid_magic[9] = "SMRPYR01";
constexpr std::uint32_t pyramid_format_version = 2;

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
 * reads a pyramid written by `write_pyramid()` (format version 2, or version 1, which is
 * converted). Files are untrusted input: besides the header, sizes and checksum, the content
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
    error = "pyramid format version " + std::to_string(version) + " is not supported (versions 1 and 2 are)";
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
