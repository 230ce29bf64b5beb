// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Helpers shared by the tests: procedural meshes (deterministic, no files) and access to
// CGAL's data set (libcgal-demo), which the tests that need it skip cleanly without.

#ifndef SMR_TEST_UTILS_H
#define SMR_TEST_UTILS_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/subdivision_method_3.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace smr_test {

typedef CGAL::Exact_predicates_inexact_constructions_kernel        Kernel;
typedef Kernel::Point_3                                             Point_3;
typedef Kernel::Vector_3                                            Vector_3;
typedef CGAL::Surface_mesh<Point_3>                                 Mesh;
typedef CGAL::Polyhedron_3<Kernel, CGAL::Polyhedron_items_with_id_3> Polyhedron;

template <typename TM>
TM mesh_from_soup(const std::vector<Point_3>& points, const std::vector<std::array<std::size_t, 3> >& triangles)
{
  TM tm;
  std::vector<Point_3> p = points;
  std::vector<std::vector<std::size_t> > polygons;
  for(const auto& t : triangles)
    polygons.push_back({t[0], t[1], t[2]});
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(p, polygons, tm);
  return tm;
}

// Loop-subdivided icosahedron projected onto the unit sphere (10*4^k+2 vertices)
template <typename TM>
TM icosphere(int subdivisions)
{
  TM tm;
  CGAL::make_icosahedron(tm, Point_3(0, 0, 0), 1.0);
  CGAL::Subdivision_method_3::Loop_subdivision(tm, CGAL::parameters::number_of_iterations(subdivisions));
  for(auto v : vertices(tm))
  {
    const Point_3 p = get(CGAL::vertex_point, tm, v);
    const double l = std::sqrt(CGAL::to_double(Vector_3(CGAL::ORIGIN, p).squared_length()));
    put(get(CGAL::vertex_point, tm), v, Point_3(p.x() / l, p.y() / l, p.z() / l));
  }
  return tm;
}

// (n+1)x(n+1) vertices on the unit square, alternating diagonals; interior vertices moved
// by up to `jitter` grid steps in x and y. Embedded in 3D by the affine map
// (x, y) -> origin + x u + y v, so that the plane is not axis-aligned.
template <typename TM>
TM planar_grid(int n, double jitter, unsigned int seed = 7,
               const Point_3& origin = Point_3(0.3, -0.2, 0.5),
               const Vector_3& u = Vector_3(0.8, 0.36, 0.48), const Vector_3& v = Vector_3(-0.6, 0.48, 0.64))
{
  CGAL::Random rng(seed);
  std::vector<Point_3> points;
  std::vector<std::array<std::size_t, 3> > triangles;
  const double h = 1.0 / n;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
    {
      double x = i * h, y = j * h;
      if(i > 0 && i < n && j > 0 && j < n)
      {
        x += rng.get_double(-jitter, jitter) * h;
        y += rng.get_double(-jitter, jitter) * h;
      }
      points.push_back(origin + x * u + y * v);
    }
  auto id = [n](int i, int j) { return std::size_t(j * (n + 1) + i); };
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      if((i + j) % 2 == 0)
      {
        triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
      else
      {
        triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return mesh_from_soup<TM>(points, triangles);
}

// Path of a file of CGAL's data set, or "" when libcgal-demo's data was not extracted.
inline std::string cgal_data_file(const std::string& name)
{
#ifdef CGAL_DATA_DIR
  const std::string path = std::string(CGAL_DATA_DIR) + "/" + name;
  if(std::ifstream(path).good())
    return path;
#endif
  (void)name;
  return std::string();
}

template <typename TM>
bool read_cgal_mesh(const std::string& name, TM& tm)
{
  const std::string path = cgal_data_file(name);
  return !path.empty() && CGAL::IO::read_polygon_mesh(path, tm) && CGAL::is_triangle_mesh(tm);
}

template <typename TM>
std::vector<Point_3> positions_in_order(const TM& tm)
{
  std::vector<Point_3> out;
  for(auto v : vertices(tm))
    out.push_back(get(CGAL::vertex_point, tm, v));
  return out;
}

template <typename TM>
bool is_border_vertex(typename boost::graph_traits<TM>::vertex_descriptor v, const TM& tm)
{
  for(auto h : CGAL::halfedges_around_target(v, tm))
    if(CGAL::is_border_edge(h, tm))
      return true;
  return false;
}

} // namespace smr_test

#endif // SMR_TEST_UTILS_H
