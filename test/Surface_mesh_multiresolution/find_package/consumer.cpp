// SPDX-License-Identifier: GPL-3.0-or-later
// Relaxes a regular tetrahedron's colours with the installed package: every vertex has the
// same neighbours, so one step of the uniform scheme gives each vertex the mean of the
// other three colours.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/boost/graph/generators.h>
#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace SMR = CGAL::Surface_mesh_multiresolution;

int main()
{
  Mesh m;
  CGAL::make_tetrahedron(K::Point_3(1, 1, 1), K::Point_3(1, -1, -1), K::Point_3(-1, 1, -1), K::Point_3(-1, -1, 1), m);
  auto value = m.add_property_map<Mesh::Vertex_index, double>("v:value", 0.).first;
  double x = 0;
  for(auto v : vertices(m)) value[v] = (x += 3);   // 3, 6, 9, 12: sum 30
  SMR::relax(m, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme::UNIFORM).relax_geometry(false)
                                 .vertex_attribute_maps(std::make_tuple(value)));
  x = 0;
  for(auto v : vertices(m))
  {
    x += 3;
    if(value[v] != (30 - x) / 3) { std::cerr << "unexpected value " << value[v] << "\n"; return 1; }
  }
#if defined(SMR_EXPECT_TBB) && !defined(CGAL_LINKED_WITH_TBB)
  std::cerr << "the installed package target was built with TBB but does not carry it\n";
  return 1;
#endif
  std::cout << "installed package OK\n";
  return 0;
}
