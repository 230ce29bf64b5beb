// SPDX-License-Identifier: GPL-3.0-or-later
// The whole pipeline of Roy et al. on one mesh: decompose (geometry + colours), filter
// (low-pass, stop-band, enhancement: Fig. 5), denoise (Fig. 6b), adaptive reconstruction
// guided by the geometry and by the colours (Fig. 6c). Prints a summary, writes PLY files.
// Usage: pipeline [mesh]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh/IO/PLY.h>
#include <fstream>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef CGAL::IO::Color                                     Color;
namespace SMR = CGAL::Surface_mesh_multiresolution;

// rebuilds `pyr` (adaptively if `target` > 0), writes it, prints one line of the summary
void output(const SMR::Pyramid<Mesh>& pyr, const Mesh& input, double edge, const std::string& name,
            std::size_t target = 0, std::size_t guide = 0)
{
  Mesh out;
  auto color = out.add_property_map<Mesh::Vertex_index, Color>("v:color").first;
  if(target > 0)
    SMR::reconstruct_adaptively(pyr, out, 0., SMR::parameters::target_number_of_vertices(target).channel(guide)
                                                 .vertex_attribute_maps(color));
  else
    SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(color));
  double moved = 0;
  if(target == 0) {   // same vertices in the same order: mean displacement
    auto it = vertices(out).begin();
    for(auto v : vertices(input)) moved += std::sqrt(CGAL::squared_distance(input.point(v), out.point(*it++)));
    moved /= num_vertices(input) * edge;
  }
  if(target == 0)
    std::printf(" %-28s %9zu %9zu %12.4f\n", name.c_str(), std::size_t(num_vertices(out)), std::size_t(num_faces(out)), moved);
  else     // other vertices than the input's: no displacement to report
    std::printf(" %-28s %9zu %9zu %12s\n", name.c_str(), std::size_t(num_vertices(out)), std::size_t(num_faces(out)), "-");
  CGAL::IO::write_polygon_mesh(name + ".ply", out, CGAL::parameters::stream_precision(17));
}

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
  if(!has_color) {   // no colours in the file: stripes across the model, to guide the adaptive step
    color = mesh.add_property_map<Mesh::Vertex_index, Color>("v:color").first;
    const CGAL::Bbox_3 b = CGAL::bbox_3(mesh.points().begin(), mesh.points().end());
    for(auto v : vertices(mesh))
      color[v] = int(6 * (mesh.point(v).x() - b.xmin()) / (b.xmax() - b.xmin())) % 2 ? Color(230, 60, 40) : Color(40, 90, 220);
  }
  double edge = 0;
  for(auto e : edges(mesh)) edge += std::sqrt(CGAL::squared_distance(mesh.point(source(e, mesh)), mesh.point(target(e, mesh))));
  edge /= num_edges(mesh);

  const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh, SMR::parameters::vertex_attribute_maps(color));
  const std::size_t K = pyr.number_of_levels();
  std::printf("%s: %zu vertices, %zu levels (coarsest %zu vertices)\n\n %-28s %9s %9s %12s\n", filename.c_str(),
              std::size_t(num_vertices(mesh)), K, pyr.number_of_vertices(K), "result", "vertices", "faces", "moved/edge");
  output(pyr, mesh, edge, "reconstructed");                                  // exact: moved 0
  SMR::Pyramid<Mesh> p = pyr;  SMR::low_pass(p, 3);          output(p, mesh, edge, "low_pass_D1-D3");
  p = pyr;                     SMR::stop_band(p, 4, 6);      output(p, mesh, edge, "stop_band_D4-D6");
  p = pyr;                     SMR::enhance(p, 4, 6, 2.);    output(p, mesh, edge, "enhance_D4-D6_x2");
  p = pyr;  const double t = SMR::denoise(p);               output(p, mesh, edge, "denoised");
  const std::size_t budget = num_vertices(mesh) / 10;
  output(pyr, mesh, edge, "adaptive_geometry_10pc", budget, 0);
  output(pyr, mesh, edge, "adaptive_colour_10pc", budget, 1);
  std::printf("\nnoise estimate %.3g (%.3g mean edges), denoising threshold %.3g\n", SMR::estimate_noise(pyr),
              SMR::estimate_noise(pyr) / edge, t);
  return EXIT_SUCCESS;
}
