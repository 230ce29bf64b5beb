// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_INDEXED_MESH_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_INDEXED_MESH_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/helpers.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>

#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {

template <typename K, typename VEF>
class SM_index_pmap;
class SM_Vertex_index;

namespace Surface_mesh_multiresolution {
namespace internal {

// Whether a mesh type and vertex index map are a Surface_mesh with its own vertex indices:
// rows are then the indices themselves on a mesh without removed elements
template <typename TriangleMesh, typename VertexIndexMap>
struct Is_surface_mesh_with_own_indices : std::false_type {};
template <typename Point>
struct Is_surface_mesh_with_own_indices<CGAL::Surface_mesh<Point>, CGAL::SM_index_pmap<Point, CGAL::SM_Vertex_index> >
  : std::true_type {};

// the number of vertices of a face graph, as vertices(g) lists them (found by ADL, so that
// classes with a member vertices() can call it)
template <typename FaceGraph>
std::size_t number_of_vertices_of(const FaceGraph& g) { return static_cast<std::size_t>(vertices(g).size()); }

template <typename TriangleMesh>
struct Indexed_mesh
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;

  std::vector<vertex_descriptor> vertices;   // row -> vertex
  std::vector<Index> triangles;              // 3 rows per face
  std::vector<Index> row_of;                 // get(vim, v) -> row

  std::size_t number_of_vertices() const { return vertices.size(); }

  template <typename VertexIndexMap>
  Index row(vertex_descriptor v, VertexIndexMap vim) const { return row_of[static_cast<std::size_t>(get(vim, v))]; }
};

// The message of the exception for face f, number face_number in faces(tm), found not to be
// a triangle of three distinct vertices (its rows in build_indexed_mesh()).
template <typename TriangleMesh>
std::string triangle_defect(const TriangleMesh& tm, typename boost::graph_traits<TriangleMesh>::face_descriptor f,
                            std::size_t face_number)
{
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor halfedge_descriptor;
  const halfedge_descriptor h0 = halfedge(f, tm);
  const halfedge_descriptor h1 = next(h0, tm), h2 = next(h1, tm);
  const std::string face = "face " + std::to_string(face_number) + " (in the order of faces(tm))";
  if(next(h2, tm) != h0)
  {
    std::size_t degree = 3;
    for(halfedge_descriptor h = next(h2, tm); h != h0 && degree < 1000000; h = next(h, tm))
      ++degree;
    return face + " is not a triangle: it has " + std::to_string(degree) + " vertices";
  }
  return face + " repeats a vertex";
}

// build_indexed_mesh() for a Surface_mesh without removed elements and with its own vertex
// indices: rows are the vertex indices and face f's triangle is at 3 f, so the vertices and
// the faces are read in parallel (the sequential loop over faces(tm) was 2-3 % of a dragon's
// decomposition on two threads, all of it on one). The same arrays and the same exception (the
// first defective face in the order of faces(tm)).
template <typename Point>
void build_indexed_surface_mesh(const CGAL::Surface_mesh<Point>& tm, Indexed_mesh<CGAL::Surface_mesh<Point> >& im)
{
  typedef CGAL::Surface_mesh<Point> Mesh;
  typedef typename Mesh::size_type size_type;
  const std::size_t nv = tm.number_of_vertices(), nf = tm.number_of_faces();
  im.vertices.resize(nv);
  im.row_of.resize(nv);
  parallel_for_blocks(nv, [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
    {
      im.vertices[i] = typename Mesh::Vertex_index(static_cast<size_type>(i));
      im.row_of[i] = static_cast<Index>(i);
    }
  });
  im.triangles.resize(3 * nf);
  const std::size_t bad = first_position_where(nf, [&](std::size_t f) {
    const typename Mesh::Halfedge_index h0 = tm.halfedge(typename Mesh::Face_index(static_cast<size_type>(f)));
    const typename Mesh::Halfedge_index h1 = tm.next(h0), h2 = tm.next(h1);
    const Index a = Index(tm.target(h2)), b = Index(tm.target(h0)), c = Index(tm.target(h1));
    Index* t = im.triangles.data() + 3 * f;
    t[0] = a;
    t[1] = b;
    t[2] = c;
    return tm.next(h2) != h0 || a == b || b == c || c == a;
  });
  if(bad < nf)
    throw std::invalid_argument(triangle_defect(tm, typename Mesh::Face_index(static_cast<size_type>(bad)), bad));
}

// Numbers the vertices and collects the triangles.
// \throws std::invalid_argument when a face is not a triangle or repeats a vertex.
template <typename TriangleMesh, typename VertexIndexMap>
void build_indexed_mesh(const TriangleMesh& tm, VertexIndexMap vim, Indexed_mesh<TriangleMesh>& im)
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor   vertex_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::halfedge_descriptor halfedge_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor     face_descriptor;

  im.vertices.clear();
  im.triangles.clear();
  const std::size_t nv = static_cast<std::size_t>(vertices(tm).size());
  if(nv >= static_cast<std::size_t>(invalid_index))
    throw std::invalid_argument("the mesh has too many vertices (at most 2^32-2 are supported)");
  if constexpr(Is_surface_mesh_with_own_indices<TriangleMesh, VertexIndexMap>::value)
  {
    if(!tm.has_garbage())
    {
      build_indexed_surface_mesh(tm, im);
      return;
    }
  }
  im.vertices.reserve(nv);
  // num_vertices() bounds the index map's values (it also counts removed elements of a
  // Surface_mesh that were not garbage-collected)
  im.row_of.assign(static_cast<std::size_t>(num_vertices(tm)), invalid_index);
  for(vertex_descriptor v : vertices(tm))
  {
    const std::size_t id = static_cast<std::size_t>(get(vim, v));
    if(id >= im.row_of.size())
      im.row_of.resize(id + 1, invalid_index);
    im.row_of[id] = static_cast<Index>(im.vertices.size());
    im.vertices.push_back(v);
  }

  im.triangles.reserve(3 * static_cast<std::size_t>(faces(tm).size()));
  std::size_t face_number = 0;
  for(face_descriptor f : faces(tm))
  {
    const halfedge_descriptor h0 = halfedge(f, tm);
    const halfedge_descriptor h1 = next(h0, tm), h2 = next(h1, tm);
    if(next(h2, tm) != h0)
      throw std::invalid_argument(triangle_defect(tm, f, face_number));
    // the sources of h0, h1, h2 as the targets of h2, h0, h1 (a halfedge structure stores
    // targets: a source is the target of the opposite halfedge, one more scattered read)
    const Index a = im.row(target(h2, tm), vim), b = im.row(target(h0, tm), vim), c = im.row(target(h1, tm), vim);
    if(a == b || b == c || c == a)
      throw std::invalid_argument(triangle_defect(tm, f, face_number));
    im.triangles.push_back(a);
    im.triangles.push_back(b);
    im.triangles.push_back(c);
    ++face_number;
  }
}

// Writes the coordinates of the vertices, in the order of \`verts\`, as doubles; in parallel
// blocks when \`in_parallel\` (only for maps known to be safe to read from several threads).
// \throws std::invalid_argument naming the first vertex with a non-finite coordinate.
template <typename VertexDescriptor, typename VertexPointMap, typename GeomTraits>
void read_coordinates(const std::vector<VertexDescriptor>& verts, VertexPointMap vpm, const GeomTraits& gt,
                      std::vector<double>& xyz, bool in_parallel = false)
{
  const auto x = gt.compute_x_3_object();
  const auto y = gt.compute_y_3_object();
  const auto z = gt.compute_z_3_object();
  const std::size_t n = verts.size();
  xyz.resize(3 * n);
  const std::size_t bad = first_position_where(n, [&](std::size_t i) {
    const auto& p = get(vpm, verts[i]);
    double* out = xyz.data() + 3 * i;
    out[0] = CGAL::to_double(x(p));
    out[1] = CGAL::to_double(y(p));
    out[2] = CGAL::to_double(z(p));
    return !(std::isfinite(out[0]) && std::isfinite(out[1]) && std::isfinite(out[2]));
  }, in_parallel ? 8192 : (std::max)(n, std::size_t(1)));
  if(bad < n)
    throw std::invalid_argument("vertex " + std::to_string(bad) + " (in the order of vertices(tm)) has a non-finite coordinate");
}

// writes the points of xyz (3 doubles per vertex of \`verts\`); in parallel blocks when
// \`in_parallel\` (only for maps known to be safe to write from several threads, each vertex once)
template <typename VertexDescriptor, typename VertexPointMap, typename GeomTraits>
void write_coordinates(const std::vector<VertexDescriptor>& verts, VertexPointMap vpm, const GeomTraits& gt,
                       const std::vector<double>& xyz, bool in_parallel = false)
{
  const auto point = gt.construct_point_3_object();
  parallel_for_blocks(verts.size(), [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
      put(vpm, verts[i], point(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
  }, in_parallel ? 8192 : (std::max)(verts.size(), std::size_t(1)));
}

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_INDEXED_MESH_H
