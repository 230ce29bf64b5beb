// SPDX-License-Identifier: GPL-3.0-or-later
// Section 3 of Roy et al.: decompose a mesh (and its colours, if any) into a pyramid, print
// level / vertices / faces / mean detail length per channel, write chosen levels as PLY,
// then rebuild level 0 and print its largest difference to the input (0: exact).
// Usage: decompose_reconstruct [mesh] [level ...]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Real_timer.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh/IO/PLY.h>
#include <fstream>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef CGAL::IO::Color                                     Color;
namespace SMR = CGAL::Surface_mesh_multiresolution;

int main(int argc, char** argv)
{
  const std::string filename = argc > 1 ? argv[1] : CGAL::data_file_path("meshes/bunny00.off");
  Mesh mesh;
  std::ifstream ply(filename, std::ios::binary);   // a PLY's colours: read_PLY keeps them (as "v:color"), read_polygon_mesh not
  const bool is_ply = filename.size() > 4 && filename.compare(filename.size() - 4, 4, ".ply") == 0;
  if(!(is_ply ? CGAL::IO::read_PLY(ply, mesh) : CGAL::IO::read_polygon_mesh(filename, mesh)) || !CGAL::is_triangle_mesh(mesh)
     || faces(mesh).empty()) {
    std::cerr << "Invalid input: " << filename << " (a triangle mesh with faces is needed)\n"; return EXIT_FAILURE;
  }
  auto [color, has_color] = mesh.property_map<Mesh::Vertex_index, Color>("v:color");
  if(!has_color)   // colours are a channel like any other: paint a height ramp if the input has none
    color = mesh.add_property_map<Mesh::Vertex_index, Color>("v:color").first;
  if(!has_color) {
    const CGAL::Bbox_3 b = CGAL::bbox_3(mesh.points().begin(), mesh.points().end());
    for(auto v : vertices(mesh))
      color[v] = Color(static_cast<unsigned char>(255 * (mesh.point(v).z() - b.zmin()) / (b.zmax() - b.zmin())), 80, 160);
  }
  CGAL::Real_timer timer; timer.start();
  const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh, SMR::parameters::vertex_attribute_maps(std::make_tuple(color)));
  const double t_decompose = timer.time();
  const std::size_t K = pyr.number_of_levels();

  std::printf("%s: %zu vertices, decomposed into %zu levels in %.3f s\n\n level  vertices    faces  mean |D| geometry  mean |D| colour\n",
              filename.c_str(), std::size_t(num_vertices(mesh)), K, t_decompose);
  for(std::size_t k = 0; k <= K; ++k) {
    std::printf("%6zu %9zu %8zu", k, pyr.number_of_vertices(k), pyr.number_of_faces(k));
    if(k >= 1)
      for(std::size_t c = 0; c < 2; ++c) {   // the details D_k live on the vertices of M_{k-1}
        const std::vector<double> lengths = pyr.detail_lengths(k, c);
        double sum = 0;
        for(double l : lengths) sum += l;
        std::printf("  %16.3g", sum / lengths.size());
      }
    std::printf("\n");
  }
  std::vector<std::size_t> levels;
  for(int i = 2; i < argc; ++i) levels.push_back(std::stoul(argv[i]));
  if(levels.empty()) levels = {K / 3, 2 * K / 3, K};
  Mesh out;
  auto out_color = out.add_property_map<Mesh::Vertex_index, Color>("v:color").first;
  for(std::size_t k : levels) {
    if(k > K) continue;
    SMR::reconstruct(pyr, out, SMR::parameters::level(k).vertex_attribute_maps(std::make_tuple(out_color)));
    CGAL::IO::write_polygon_mesh("level_" + std::to_string(k) + ".ply", out, CGAL::parameters::stream_precision(17));
  }
  timer.reset();
  SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(out_color)));
  const double t_reconstruct = timer.time();
  double max_difference = 0; std::size_t colour_differences = 0;
  auto it = vertices(out).begin();
  for(auto v : vertices(mesh)) {
    max_difference = (std::max)(max_difference, std::sqrt(CGAL::squared_distance(mesh.point(v), out.point(*it))));
    colour_differences += (color[v] != out_color[*it]);
    ++it;
  }
  std::printf("\nlevel 0 rebuilt in %.3f s: largest vertex difference to the input %g, colours different: %zu\n",
              t_reconstruct, max_difference, colour_differences);
  return max_difference == 0 && colour_differences == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
