// SPDX-License-Identifier: GPL-3.0-or-later
// Fig. 3 of Roy et al.: colours relaxed over a surface with weights that come from the
// geometry only (Eq. 3). A swirl is painted on a regular sphere (or the input's own
// colours are used), relaxed 1 and 20 times; writes colors_<k>.ply with the colours.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/bounding_box.h>
#include <CGAL/subdivision_method_3.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <cmath>
#include <fstream>
#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef CGAL::IO::Color                                     Color;
namespace SMR = CGAL::Surface_mesh_multiresolution;

int main(int argc, char** argv)
{
  const bool own_mesh = argc > 1;
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(own_mesh ? argv[1] : CGAL::data_file_path("meshes/sphere.off"), mesh)
     || !CGAL::is_triangle_mesh(mesh)) {
    std::cerr << "Invalid input\n"; return EXIT_FAILURE;
  }
  auto [color, created] = mesh.add_property_map<Mesh::Vertex_index, Color>("v:color");
  if(!own_mesh) {   // a regular sphere of 10,242 vertices, as in the paper's swirl model
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(3));
    for(auto v : vertices(mesh)) mesh.point(v) = CGAL::ORIGIN + (mesh.point(v) - CGAL::ORIGIN) / std::sqrt((mesh.point(v) - CGAL::ORIGIN).squared_length());
  }
  if(created || !own_mesh) {
    K::Iso_cuboid_3 box = CGAL::bounding_box(mesh.points().begin(), mesh.points().end());
    for(auto v : vertices(mesh)) {   // swirl stripes around the z axis
      const K::Vector_3 d = mesh.point(v) - CGAL::midpoint(box.min(), box.max());
      const double a = 3 * std::atan2(d.y(), d.x()) + 8 * d.z() / (box.zmax() - box.zmin());
      color[v] = Color(static_cast<unsigned char>(127.5 + 127.4 * std::sin(a)),
                       static_cast<unsigned char>(127.5 + 127.4 * std::sin(a + 2.1)),
                       static_cast<unsigned char>(127.5 + 127.4 * std::sin(a + 4.2)));
    }
  }
  auto variance = [&]() {
    double mean[3] = {0, 0, 0}, var = 0;
    for(auto v : vertices(mesh)) { mean[0] += color[v].r(); mean[1] += color[v].g(); mean[2] += color[v].b(); }
    for(double& m : mean) m /= num_vertices(mesh);
    for(auto v : vertices(mesh)) var += CGAL::square(color[v].r() - mean[0]) + CGAL::square(color[v].g() - mean[1]) + CGAL::square(color[v].b() - mean[2]);
    return var / num_vertices(mesh);
  };
  const auto R = SMR::relaxation_operator(mesh);   // weights computed once, applied 20 times
  CGAL::IO::write_PLY("colors_0.ply", mesh);
  std::cout << num_vertices(mesh) << " vertices\niteration  colour variance\n        0  " << variance() << "\n";
  for(int it = 1; it <= 20; ++it) {
    R.apply(mesh, SMR::parameters::relax_geometry(false).vertex_attribute_maps(std::make_tuple(color)));
    if(it == 1 || it % 5 == 0) std::cout << "       " << (it < 10 ? " " : "") << it << "  " << variance() << "\n";
    if(it == 1 || it == 20) CGAL::IO::write_PLY("colors_" + std::to_string(it) + ".ply", mesh);
  }
  return EXIT_SUCCESS;
}
