// SPDX-License-Identifier: GPL-3.0-or-later
// Fig. 5 of Roy et al.: low-pass (zero the 6 finest detail levels), stop-band (zero D_6..D_9)
// and enhancement (D_6..D_9 times 2) of one pyramid, without a new decomposition.
// Usage: filter_bands [mesh] (the paper uses the Venus head: ../shared/data/venus-original.off.xz, decompressed)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <algorithm>
#include <cstdio>
#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
namespace SMR = CGAL::Surface_mesh_multiresolution;

int main(int argc, char** argv)
{
  const std::string filename = argc > 1 ? argv[1] : CGAL::data_file_path("meshes/armadillo.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(filename, mesh) || !CGAL::is_triangle_mesh(mesh) || faces(mesh).empty()) {
    std::cerr << "Invalid input: " << filename << "\n"; return EXIT_FAILURE;
  }
  const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh);
  const std::size_t K = pyr.number_of_levels();
  // the paper's bands on a 50k-vertex head; fewer levels: the same bands, clamped
  const std::size_t a = (std::min)(std::size_t(6), K), b = (std::min)(std::size_t(9), K);
  std::printf("%s: %zu vertices, %zu levels; bands: low-pass D1..D%zu, stop-band and enhancement D%zu..D%zu\n",
              filename.c_str(), std::size_t(num_vertices(mesh)), K, a, a, b);

  SMR::Pyramid<Mesh> low = pyr, stop = pyr, enhanced = pyr;   // filters work on copies
  SMR::low_pass(low, a);
  SMR::stop_band(stop, a, b);
  SMR::enhance(enhanced, a, b, 2.);
  const std::pair<const char*, const SMR::Pyramid<Mesh>*> results[] = {
    {"filter_input.ply", &pyr}, {"filter_low_pass.ply", &low}, {"filter_stop_band.ply", &stop}, {"filter_enhanced.ply", &enhanced}};
  for(const auto& r : results) {
    Mesh out;
    SMR::reconstruct(*r.second, out);
    double moved = 0;
    auto it = vertices(out).begin();
    for(auto v : vertices(mesh)) moved = (std::max)(moved, std::sqrt(CGAL::squared_distance(mesh.point(v), out.point(*it++))));
    std::printf("  %-24s largest vertex move %g\n", r.first, moved);
    CGAL::IO::write_polygon_mesh(r.first, out, CGAL::parameters::stream_precision(17));
  }
  return EXIT_SUCCESS;
}
