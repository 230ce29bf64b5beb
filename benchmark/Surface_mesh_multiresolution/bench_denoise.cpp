// SPDX-License-Identifier: GPL-3.0-or-later
// Denoising quality on noisy/clean pairs of the same connectivity (e.g. the GuidedDenoising
// set in ../shared/data): E_a, the mean angle between corresponding face normals (degrees),
// and E_v, the area-weighted RMS distance from the vertices to the clean surface (in mean
// edge lengths), for the noisy input, SMR::denoise (automatic threshold), SMR soft
// thresholding at the best of a few thresholds, and uniform Laplacian and Taubin smoothing
// at their best iteration counts (chosen against the clean mesh: an upper bound of what a
// user gets).
// Usage: bench_denoise noisy1 clean1 [noisy2 clean2 ...]
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh> > > Tree;
namespace SMR = CGAL::Surface_mesh_multiresolution;
namespace PMP = CGAL::Polygon_mesh_processing;

struct Errors { double ea, ev; };

Errors errors(const Mesh& m, const Mesh& clean, const Tree& tree, double edge)
{
  auto n1 = get(CGAL::dynamic_face_property_t<K::Vector_3>(), m);
  auto n2 = get(CGAL::dynamic_face_property_t<K::Vector_3>(), clean);
  PMP::compute_face_normals(m, n1);
  PMP::compute_face_normals(clean, n2);
  double ea = 0;
  auto f2 = faces(clean).begin();
  for(auto f : faces(m))
    ea += std::acos((std::max)(-1., (std::min)(1., get(n1, f) * get(n2, *f2++)))) * 180. / CGAL_PI;
  // area weight of a vertex: a third of the area of its faces in m
  std::vector<double> w(num_vertices(m), 0.);
  for(auto f : faces(m))
  {
    const auto h = halfedge(f, m);
    const double a = std::sqrt(CGAL::squared_area(m.point(source(h, m)), m.point(target(h, m)), m.point(target(next(h, m), m))));
    for(auto v : vertices_around_face(h, m)) w[v.idx()] += a / 3;
  }
  double sum = 0, total = 0;
  for(auto v : vertices(m)) { sum += w[v.idx()] * CGAL::to_double(tree.squared_distance(m.point(v))); total += w[v.idx()]; }
  return {ea / num_faces(m), std::sqrt(sum / total) / edge};
}

// the best (lowest E_a) of a family of results, with its parameter
template <typename F>
std::pair<Errors, double> best(const std::vector<double>& params, const F& make, const Mesh& clean, const Tree& tree, double edge)
{
  std::pair<Errors, double> b{{1e30, 1e30}, 0};
  for(double p : params)
  {
    const Errors e = errors(make(p), clean, tree, edge);
    if(e.ea < b.first.ea) b = {e, p};
  }
  return b;
}

int main(int argc, char** argv)
{
  std::printf("| model | noisy E_a / E_v | SMR denoise (auto) | SMR soft threshold, best t (x sigma) | uniform Laplacian, best steps | Taubin, best steps |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for(int i = 1; i + 1 < argc; i += 2)
  {
    Mesh noisy, clean;
    if(!CGAL::IO::read_polygon_mesh(argv[i], noisy) || !CGAL::IO::read_polygon_mesh(argv[i + 1], clean)
       || num_vertices(noisy) != num_vertices(clean) || num_faces(noisy) != num_faces(clean))
    { std::cerr << "cannot read the pair " << argv[i] << " " << argv[i + 1] << "\n"; continue; }
    Tree tree(faces(clean).first, faces(clean).second, clean);
    tree.accelerate_distance_queries();
    double edge = 0;
    for(auto e : edges(clean)) edge += std::sqrt(CGAL::squared_distance(clean.point(source(e, clean)), clean.point(target(e, clean))));
    edge /= num_edges(clean);

    const Errors e0 = errors(noisy, clean, tree, edge);
    const SMR::Pyramid<Mesh> pyr = SMR::decompose(noisy);
    SMR::Pyramid<Mesh> p = pyr;
    SMR::denoise(p);
    Mesh dn;
    SMR::reconstruct(p, dn);
    const Errors e1 = errors(dn, clean, tree, edge);
    const double sigma = SMR::estimate_noise(pyr);
    const auto st = best({0.5, 1., 1.5, 2., 3., 4.}, [&](double c) {
      SMR::Pyramid<Mesh> q = pyr; SMR::soft_threshold(q, c * sigma); Mesh out; SMR::reconstruct(q, out); return out; }, clean, tree, edge);
    const auto lap = best({1, 2, 3, 5, 8, 12, 20}, [&](double n) {
      Mesh out = noisy;
      SMR::relax(out, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme::UNIFORM).number_of_iterations(unsigned(n)));
      return out; }, clean, tree, edge);
    const auto taubin = best({2, 5, 10, 20, 40, 80}, [&](double n) {
      Mesh out = noisy;   // Taubin lambda|mu: a uniform step of 0.5 then one of -0.53
      for(int it = 0; it < int(n); ++it)
        for(double f : {0.5, -0.53})
        {
          const auto R = SMR::relaxation_operator(out, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme::UNIFORM));
          std::vector<double> x, r;
          for(auto v : vertices(out)) x.insert(x.end(), {out.point(v).x(), out.point(v).y(), out.point(v).z()});
          R.apply(x, r, 3);
          std::size_t k = 0;
          for(auto v : vertices(out)) { out.point(v) = K::Point_3(x[k] + f * (r[k] - x[k]), x[k + 1] + f * (r[k + 1] - x[k + 1]),
                                                                  x[k + 2] + f * (r[k + 2] - x[k + 2])); k += 3; }
        }
      return out; }, clean, tree, edge);
    std::string name = argv[i];
    name = name.substr(name.find_last_of('/') + 1);
    std::printf("| %s | %.2f / %.3f | %.2f / %.3f | %.2f / %.3f (%.1f) | %.2f / %.3f (%.0f) | %.2f / %.3f (%.0f) |\n", name.c_str(),
                e0.ea, e0.ev, e1.ea, e1.ev, st.first.ea, st.first.ev, st.second, lap.first.ea, lap.first.ev, lap.second,
                taubin.first.ea, taubin.first.ev, taubin.second);
    std::fflush(stdout);
  }
  return 0;
}
