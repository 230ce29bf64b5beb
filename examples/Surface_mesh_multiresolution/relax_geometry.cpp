// SPDX-License-Identifier: GPL-3.0-or-later
// Fig. 2 of Roy et al.: one relaxation step of each scheme on a real mesh. The uniform
// Laplacian drifts tangentially (it evens out the triangles); the curvature and SOD
// schemes move vertices along the normal only. Writes relaxed_<scheme>.ply.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
namespace SMR = CGAL::Surface_mesh_multiresolution;
namespace PMP = CGAL::Polygon_mesh_processing;

// mean angle (degrees) between the normals of adjacent faces: lower is smoother
double roughness(const Mesh& m)
{
  auto fn = get(CGAL::dynamic_face_property_t<K::Vector_3>(), m);
  PMP::compute_face_normals(m, fn);
  double sum = 0; std::size_t n = 0;
  for(auto e : edges(m))
    if(!is_border(e, m)) {
      const double c = get(fn, face(halfedge(e, m), m)) * get(fn, face(opposite(halfedge(e, m), m), m));
      sum += std::acos((std::max)(-1., (std::min)(1., c))) * 180 / CGAL_PI; ++n;
    }
  return n ? sum / n : 0;
}

int main(int argc, char** argv)
{
  const std::string filename = argc > 1 ? argv[1] : CGAL::data_file_path("meshes/mannequin-devil.off");
  const unsigned int iterations = argc > 2 ? std::stoi(argv[2]) : 1;
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || !CGAL::is_triangle_mesh(mesh)) {
    std::cerr << "Invalid input: " << filename << "\n"; return EXIT_FAILURE;
  }
  auto normal = get(CGAL::dynamic_vertex_property_t<K::Vector_3>(), mesh);
  PMP::compute_vertex_normals(mesh, normal);
  double edge = 0;
  for(auto e : edges(mesh)) edge += std::sqrt(CGAL::squared_distance(mesh.point(source(e, mesh)), mesh.point(target(e, mesh))));
  edge /= num_edges(mesh);

  std::cout << filename << ": " << num_vertices(mesh) << " vertices, " << iterations << " step(s), roughness "
            << roughness(mesh) << " deg\n\n scheme     tangential drift  normal move  roughness (deg)\n"
            << "            (mean / mean edge length)\n";
  const std::pair<const char*, SMR::Relaxation_scheme> schemes[] = {{"uniform", SMR::Relaxation_scheme::UNIFORM},
    {"SOD", SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE}, {"curvature", SMR::Relaxation_scheme::CURVATURE}};
  for(const auto& s : schemes) {
    Mesh r = mesh;
    SMR::relax(r, SMR::parameters::relaxation_scheme(s.second).number_of_iterations(iterations));
    double tangential = 0, normal_move = 0;
    for(auto v : vertices(mesh)) {
      const K::Vector_3 d = r.point(v) - mesh.point(v);
      const double dn = d * get(normal, v);
      normal_move += std::abs(dn);
      tangential += std::sqrt((std::max)(0., d.squared_length() - dn * dn));
    }
    std::cout << " " << std::left << std::setw(10) << s.first << std::right << std::fixed << std::setprecision(4)
              << std::setw(12) << tangential / num_vertices(mesh) / edge << std::setw(14)
              << normal_move / num_vertices(mesh) / edge << std::setw(14) << std::setprecision(2) << roughness(r) << "\n";
    CGAL::IO::write_polygon_mesh(std::string("relaxed_") + s.first + ".ply", r, CGAL::parameters::stream_precision(17));
  }
  return EXIT_SUCCESS;
}
