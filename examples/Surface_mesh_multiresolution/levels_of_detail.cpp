// SPDX-License-Identifier: GPL-3.0-or-later
// A chain of levels of detail in one pass: decompose a mesh, then extract adaptive meshes of
// 50 %, 25 %, 10 % and 1 % of its vertices that keep the input's vertices, chosen by their
// approximation error (Adaptive_criterion::APPROXIMATION_ERROR), and write them as
// lod_50.ply ... lod_1.ply. Prints each LOD's size and its largest and RMS distance from the
// input's vertices (in 1e-3 of the bounding-box diagonal); then a threshold LOD: every input
// vertex within 0.1 % of the diagonal.
// Usage: levels_of_detail [mesh]   (default: CGAL's bunny00.off)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh> > > Tree;
namespace SMR = CGAL::Surface_mesh_multiresolution;

// largest and RMS distance from the vertices of `input` to `lod`
void distances(const Mesh& input, const Mesh& lod, double& largest, double& rms)
{
  Tree tree(faces(lod).first, faces(lod).second, lod);
  tree.accelerate_distance_queries();
  largest = rms = 0.;
  for(auto v : vertices(input))
  {
    const double d2 = tree.squared_distance(input.point(v));
    largest = (std::max)(largest, std::sqrt(d2));
    rms += d2;
  }
  rms = std::sqrt(rms / double(num_vertices(input)));
}

int main(int argc, char** argv)
{
  const std::string filename = argc > 1 ? argv[1] : CGAL::data_file_path("meshes/bunny00.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || !CGAL::is_triangle_mesh(mesh) || is_empty(mesh)) {
    std::cerr << "Invalid input: " << filename << " (a non-empty triangle mesh is needed)\n"; return EXIT_FAILURE;
  }
  const CGAL::Bbox_3 b = CGAL::Polygon_mesh_processing::bbox(mesh);
  const double diagonal = std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) + CGAL::square(b.zmax() - b.zmin()));
  const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh);
  const std::size_t n = num_vertices(mesh);
  const std::vector<double> fractions = {0.5, 0.25, 0.1, 0.01};
  std::vector<std::size_t> counts;
  for(double f : fractions) counts.push_back(std::size_t(std::lround(f * double(n))));
  std::vector<Mesh> lods;
  const auto by_error = SMR::parameters::adaptive_criterion(SMR::Adaptive_criterion::APPROXIMATION_ERROR);
  SMR::extract_levels_of_detail(pyr, counts, lods, by_error);
  std::printf("%s: %zu vertices, %zu levels\n%-12s %9s %9s %14s %12s\n", filename.c_str(), n, pyr.number_of_levels(),
              "file", "vertices", "faces", "largest (1e-3)", "RMS (1e-3)");
  for(std::size_t i = 0; i < lods.size(); ++i)
  {
    const std::string out = "lod_" + std::to_string(int(std::lround(100 * fractions[i]))) + ".ply";
    if(!CGAL::IO::write_polygon_mesh(out, lods[i], CGAL::parameters::stream_precision(17))) {
      std::cerr << "cannot write " << out << "\n"; return EXIT_FAILURE;
    }
    double largest, rms;
    distances(mesh, lods[i], largest, rms);
    std::printf("%-12s %9zu %9zu %14.3f %12.4f\n", out.c_str(), std::size_t(num_vertices(lods[i])), std::size_t(num_faces(lods[i])),
                1e3 * largest / diagonal, 1e3 * rms / diagonal);
  }
  Mesh within;
  SMR::reconstruct_adaptively(pyr, within, 1e-3 * diagonal, by_error);
  double largest, rms;
  distances(mesh, within, largest, rms);
  std::printf("threshold 1e-3 of the diagonal: %zu vertices, largest distance %.3f (1e-3)\n", std::size_t(num_vertices(within)), 1e3 * largest / diagonal);
  return EXIT_SUCCESS;
}
