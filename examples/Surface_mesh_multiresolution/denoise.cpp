// SPDX-License-Identifier: GPL-3.0-or-later
// Fig. 6b of Roy et al.: denoising by soft thresholding with no parameter to choose. With a
// clean mesh of the same connectivity (e.g. ../shared/data/gd_Fandisk0.3_{Noisy,Original}.obj.xz,
// decompressed) it prints E_a (mean angle between corresponding face normals, degrees) and
// E_v (RMS vertex distance to the clean surface, in mean edge lengths) before and after.
// Usage: denoise [noisy mesh [clean mesh]]   (default: CGAL's fandisk.off with added noise)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Random.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <cmath>
#include <cstdio>
#include <iostream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh> > > Tree;
namespace SMR = CGAL::Surface_mesh_multiresolution;
namespace PMP = CGAL::Polygon_mesh_processing;

void report(const char* name, const Mesh& m, const Mesh& clean, double edge)
{
  auto n1 = get(CGAL::dynamic_face_property_t<K::Vector_3>(), m);
  auto n2 = get(CGAL::dynamic_face_property_t<K::Vector_3>(), clean);
  PMP::compute_face_normals(m, n1);
  PMP::compute_face_normals(clean, n2);
  double ea = 0, ev = 0;
  auto f2 = faces(clean).begin();
  for(auto f : faces(m)) ea += std::acos((std::max)(-1., (std::min)(1., get(n1, f) * get(n2, *f2++)))) * 180 / CGAL_PI;
  Tree tree(faces(clean).first, faces(clean).second, clean);
  for(auto v : vertices(m)) ev += tree.squared_distance(m.point(v));
  std::printf("  %-9s E_a %6.2f deg   E_v %.3f mean edges\n", name, ea / num_faces(m), std::sqrt(ev / num_vertices(m)) / edge);
}

int main(int argc, char** argv)
{
  Mesh noisy, clean;
  const std::string filename = argc > 1 ? argv[1] : CGAL::data_file_path("meshes/fandisk.off");
  if(!CGAL::IO::read_polygon_mesh(filename, noisy) || !CGAL::is_triangle_mesh(noisy) || faces(noisy).empty()) {
    std::cerr << "Invalid input: " << filename << "\n"; return EXIT_FAILURE;
  }
  double edge = 0;
  for(auto e : edges(noisy)) edge += std::sqrt(CGAL::squared_distance(noisy.point(source(e, noisy)), noisy.point(target(e, noisy))));
  edge /= num_edges(noisy);
  const bool have_clean = argc > 2 ? CGAL::IO::read_polygon_mesh(argv[2], clean) : argc == 1;
  if(argc == 1) {   // the default: CGAL's fandisk with Gaussian noise of 0.3 mean edge lengths along the normals
    clean = noisy;
    auto normal = get(CGAL::dynamic_vertex_property_t<K::Vector_3>(), noisy);
    PMP::compute_vertex_normals(noisy, normal);
    CGAL::Random rng(1);
    for(auto v : vertices(noisy)) {
      const double g = std::sqrt(-2 * std::log(1 - rng.get_double())) * std::cos(2 * CGAL_PI * rng.get_double());
      noisy.point(v) = noisy.point(v) + 0.3 * edge * g * get(normal, v);
    }
  }
  SMR::Pyramid<Mesh> pyr = SMR::decompose(noisy);
  const double sigma = SMR::estimate_noise(pyr);
  const double t = SMR::denoise(pyr);
  Mesh denoised;
  SMR::reconstruct(pyr, denoised);
  std::printf("%s: %zu vertices, noise estimate %.3g (%.2f mean edges), threshold %.3g\n", filename.c_str(),
              std::size_t(num_vertices(noisy)), sigma, sigma / edge, t);
  if(have_clean && num_faces(clean) == num_faces(noisy)) {
    report("noisy", noisy, clean, edge);
    report("denoised", denoised, clean, edge);
  }
  CGAL::IO::write_polygon_mesh("noisy.ply", noisy, CGAL::parameters::stream_precision(17));
  CGAL::IO::write_polygon_mesh("denoised.ply", denoised, CGAL::parameters::stream_precision(17));
  return EXIT_SUCCESS;
}
