// SPDX-License-Identifier: GPL-3.0-or-later
// Fig. 6c of Roy et al.: threshold reconstruction of a coloured mesh, guided by the geometry
// and by the colours, to the same vertex budget: colour guidance keeps the vertices where the
// colour changes. For each it prints the RMS distance from the input's vertices to the result
// and the RMS difference between each input vertex's colour and the result's colour there
// (interpolated on the nearest face). Usage: adaptive_reconstruction [coloured mesh] [fraction
// of vertices kept]
// (the paper's kind of data: ../shared/data/frag_115.ply.xz, decompressed; without a file, a
// CGAL mesh with a synthetic colour pattern)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh/IO/PLY.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <fstream>
#include <cmath>
#include <cstdio>
#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef CGAL::IO::Color                                     Color;
namespace SMR = CGAL::Surface_mesh_multiresolution;
namespace PMP = CGAL::Polygon_mesh_processing;
typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh> > > Tree;

int main(int argc, char** argv)
{
  const std::string filename = argc > 1 ? argv[1] : CGAL::data_file_path("meshes/elephant.off");
  const double fraction = argc > 2 ? std::stod(argv[2]) : 0.25;
  Mesh mesh;
  std::ifstream ply(filename, std::ios::binary);   // a PLY's colours: read_PLY keeps them (as "v:color"), read_polygon_mesh not
  const bool is_ply = filename.size() > 4 && filename.compare(filename.size() - 4, 4, ".ply") == 0;
  if(!(is_ply ? CGAL::IO::read_PLY(ply, mesh) : CGAL::IO::read_polygon_mesh(filename, mesh)) || !CGAL::is_triangle_mesh(mesh)
     || faces(mesh).empty()) {
    std::cerr << "Invalid input: " << filename << " (a triangle mesh with faces is needed)\n"; return EXIT_FAILURE;
  }
  auto [color, has_color] = mesh.property_map<Mesh::Vertex_index, Color>("v:color");
  if(!has_color) {   // a checkerboard of colours in space
    color = mesh.add_property_map<Mesh::Vertex_index, Color>("v:color").first;
    const CGAL::Bbox_3 b = CGAL::bbox_3(mesh.points().begin(), mesh.points().end());
    const double cell = (b.xmax() - b.xmin()) / 5;
    for(auto v : vertices(mesh)) {
      const K::Point_3& p = mesh.point(v);
      const int parity = int(std::floor((p.x() - b.xmin()) / cell) + std::floor((p.y() - b.ymin()) / cell)
                             + std::floor((p.z() - b.zmin()) / cell)) % 2;
      color[v] = parity ? Color(240, 200, 40) : Color(30, 60, 160);
    }
  }
  const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh, SMR::parameters::vertex_attribute_maps(color));
  const std::size_t budget = std::size_t(fraction * num_vertices(mesh));
  std::printf("%s: %zu vertices, budget %zu\n", filename.c_str(), std::size_t(num_vertices(mesh)), budget);
  for(std::size_t guide : {0, 1}) {
    Mesh out;
    auto out_color = out.add_property_map<Mesh::Vertex_index, Color>("v:color").first;
    const double t = SMR::reconstruct_adaptively(pyr, out, 0., SMR::parameters::target_number_of_vertices(budget)
                                                                 .channel(guide).vertex_attribute_maps(out_color));
    // every input vertex against the result: distance, and colour interpolated at the nearest point
    Tree tree;
    PMP::build_AABB_tree(out, tree);
    double distance2 = 0, colour2 = 0;
    for(auto v : vertices(mesh)) {
      const auto loc = PMP::locate_with_AABB_tree(mesh.point(v), tree, out);
      distance2 += CGAL::squared_distance(mesh.point(v), PMP::construct_point(loc, out));
      const auto h = halfedge(loc.first, out);
      const Mesh::Vertex_index corner[3] = {source(h, out), target(h, out), target(next(h, out), out)};
      for(int c = 0; c < 3; ++c) {
        double interpolated = 0;
        for(int j = 0; j < 3; ++j) interpolated += loc.second[j] * double(out_color[corner[j]][c]);
        colour2 += CGAL::square(interpolated - double(color[v][c]));
      }
    }
    const double n = double(num_vertices(mesh));
    const char* name = guide == 0 ? "adaptive_geometry.ply" : "adaptive_colour.ply";
    std::printf("  %-22s threshold %-10.3g %7zu vertices, RMS distance %.3g, RMS colour difference %.1f (of 255)\n", name, t,
                std::size_t(num_vertices(out)), std::sqrt(distance2 / n), std::sqrt(colour2 / (3 * n)));
    CGAL::IO::write_polygon_mesh(name, out, CGAL::parameters::stream_precision(17));
  }
  return EXIT_SUCCESS;
}
