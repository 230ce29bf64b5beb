// SPDX-License-Identifier: GPL-3.0-or-later
// Approximation quality at equal vertex counts: at 25 %, 5 % and 1 % of the input's vertices,
// the adaptive reconstruction of the pyramid to that vertex budget with the paper's criterion
// (detail length) and with the approximation error, CGAL SMS edge_collapse with
// Garland-Heckbert plane policies, and meshopt_simplify (which, like the adaptive meshes,
// keeps input vertices). Errors are deterministic (AABB trees), in 1e-3 of the bounding-box
// diagonal: the RMS and the maximum distance from the input's vertices to the approximation,
// and a two-sided Hausdorff estimate: the largest distance from the vertices and from samples
// of every face (centroid and three inner points) of either mesh to the other. Unreferenced
// vertices are removed first.
// Usage: bench_quality [mesh files...]   (default: CGAL data meshes)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>

#include <meshoptimizer.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh> > > Tree;
namespace SMR = CGAL::Surface_mesh_multiresolution;
namespace SMS = CGAL::Surface_mesh_simplification;

struct Error { double rms = 0, max = 0, hausdorff = 0; std::size_t vertices = 0; };

// the largest distance from the vertices and face samples of `from` to the surface in `tree`
double one_sided(const Mesh& from, const Tree& tree)
{
  double d2 = 0;
  for(auto v : vertices(from))
    d2 = (std::max)(d2, CGAL::to_double(tree.squared_distance(from.point(v))));
  for(auto f : faces(from))
  {
    const auto h = halfedge(f, from);
    const K::Point_3 &a = from.point(source(h, from)), &b = from.point(target(h, from)), &c = from.point(target(next(h, from), from));
    for(const auto& w : {std::array<double, 3>{{1. / 3, 1. / 3, 1. / 3}}, std::array<double, 3>{{2. / 3, 1. / 6, 1. / 6}},
                         std::array<double, 3>{{1. / 6, 2. / 3, 1. / 6}}, std::array<double, 3>{{1. / 6, 1. / 6, 2. / 3}}})
    {
      const K::Point_3 p(w[0] * a.x() + w[1] * b.x() + w[2] * c.x(), w[0] * a.y() + w[1] * b.y() + w[2] * c.y(),
                         w[0] * a.z() + w[1] * b.z() + w[2] * c.z());
      d2 = (std::max)(d2, CGAL::to_double(tree.squared_distance(p)));
    }
  }
  return std::sqrt(d2);
}

Error error(const Mesh& input, const Tree& input_tree, const Mesh& approx, double diagonal)
{
  Error e;
  e.vertices = num_vertices(approx);
  Tree tree(faces(approx).first, faces(approx).second, approx);
  tree.accelerate_distance_queries();
  double sum = 0;
  for(auto v : vertices(input))
  {
    const double d = std::sqrt(CGAL::to_double(tree.squared_distance(input.point(v))));
    sum += d * d;
    e.max = (std::max)(e.max, d);
  }
  e.rms = std::sqrt(sum / double(num_vertices(input)));
  e.hausdorff = (std::max)(one_sided(input, tree), one_sided(approx, input_tree));
  e.rms *= 1e3 / diagonal; e.max *= 1e3 / diagonal; e.hausdorff *= 1e3 / diagonal;
  return e;
}

// reads a triangle mesh of 100 vertices or more without its unreferenced vertices (bun_zipper.ply
// has 1,113: they are not what the peers count); `diagonal`: that of its bounding box
bool load(const std::string& file, Mesh& mesh, double& diagonal)
{
  if(!CGAL::IO::read_polygon_mesh(file, mesh) || !CGAL::is_triangle_mesh(mesh) || num_vertices(mesh) < 100)
    return false;
  CGAL::Polygon_mesh_processing::remove_isolated_vertices(mesh);
  mesh.collect_garbage();
  const CGAL::Bbox_3 b = CGAL::Polygon_mesh_processing::bbox(mesh);
  diagonal = std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) + CGAL::square(b.zmax() - b.zmin()));
  return true;
}

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  for(int i = 1; i < argc; ++i) files.push_back(argv[i]);
  if(files.empty())
    for(const char* f : {"meshes/bunny00.off", "meshes/elephant.off", "meshes/armadillo.off", "meshes/elephant-with-holes.off"})
      files.push_back(CGAL::data_file_path(f));
  std::printf("Errors in 1e-3 of the bounding-box diagonal: RMS / max from the input vertices, H: two-sided Hausdorff (vertices and face samples both ways)\n\n");
  std::printf("| mesh | vertices | SMR adaptive, detail length | SMR adaptive, approximation error | CGAL SMS GH | meshopt_simplify | approx. error / meshopt (RMS, H) | approx. error / SMS (RMS, H) |\n");
  std::printf("|---|---:|---|---|---|---|---:|---:|\n");
  for(const std::string& file : files)
  {
    Mesh mesh;
    double diagonal = 0.;
    if(!load(file, mesh, diagonal))
    {
      std::cerr << "cannot read " << file << " as a triangle mesh: skipped\n";
      continue;
    }
    Tree tree(faces(mesh).first, faces(mesh).second, mesh);
    tree.accelerate_distance_queries();
    const std::size_t n = num_vertices(mesh);
    const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh, SMR::parameters::minimum_number_of_vertices(n / 200));
    std::vector<float> xyz;
    std::vector<unsigned int> indices;
    for(auto v : mesh.vertices()) xyz.insert(xyz.end(), {float(mesh.point(v).x()), float(mesh.point(v).y()), float(mesh.point(v).z())});
    for(auto f : mesh.faces())
      for(auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) indices.push_back(v.idx());
    const std::string name = file.substr(file.find_last_of('/') + 1);
    for(double fraction : {0.25, 0.05, 0.01})
    {
      const std::size_t target = (std::max)(std::size_t(4), std::size_t(std::lround(fraction * double(n))));
      Mesh by_detail, by_error, sms = mesh, mo;
      SMR::reconstruct_adaptively(pyr, by_detail, 0., SMR::parameters::target_number_of_vertices(target));
      SMR::reconstruct_adaptively(pyr, by_error, 0., SMR::parameters::target_number_of_vertices(target)
                                                       .adaptive_criterion(SMR::Adaptive_criterion::APPROXIMATION_ERROR));
      {
        SMS::GarlandHeckbert_plane_policies<Mesh, K> gh(sms);
        auto stop = [&sms, target](const auto&, const auto&, std::size_t, std::size_t) { return sms.number_of_vertices() <= target; };
        SMS::edge_collapse(sms, stop, CGAL::parameters::get_cost(gh.get_cost()).get_placement(gh.get_placement()));
        sms.collect_garbage();
      }
      {
        // meshoptimizer targets an index count; the count is lowered until the vertex count
        // is at most the target (it keeps input vertex positions)
        std::vector<unsigned int> out(indices.size());
        std::size_t index_target = 6 * target, count = 0, used_vertices = 0;
        for(int attempt = 0; attempt < 40; ++attempt)
        {
          count = meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(), xyz.size() / 3,
                                   3 * sizeof(float), index_target, 1.f);
          std::vector<char> seen(n, 0);
          used_vertices = 0;
          for(std::size_t i = 0; i < count; ++i) used_vertices += seen[out[i]] ? 0 : (seen[out[i]] = 1);
          if(used_vertices <= target) break;
          index_target = std::size_t(double(index_target) * (0.999 * double(target) / double(used_vertices)));
        }
        std::vector<Mesh::Vertex_index> vmap(n);
        std::vector<char> used(n, 0);
        for(std::size_t i = 0; i < count; ++i)
          if(!used[out[i]]) { used[out[i]] = 1; vmap[out[i]] = mo.add_vertex(mesh.point(Mesh::Vertex_index(out[i]))); }
        for(std::size_t i = 0; i + 2 < count; i += 3)
          mo.add_face(vmap[out[i]], vmap[out[i + 1]], vmap[out[i + 2]]);
      }
      const Error ed = error(mesh, tree, by_detail, diagonal), ea = error(mesh, tree, by_error, diagonal),
                  es = error(mesh, tree, sms, diagonal), em = error(mesh, tree, mo, diagonal);
      auto cell = [](const Error& e) {
        static char buffer[4][96];
        static int i = 0;
        i = (i + 1) % 4;
        std::snprintf(buffer[i], sizeof buffer[i], "%.2f / %.2f, H %.2f (%zu v)", e.rms, e.max, e.hausdorff, e.vertices);
        return buffer[i];
      };
      std::printf("| %s | %zu → %zu | %s | %s | %s | %s | %.2f, %.2f | %.2f, %.2f |\n", name.c_str(), n, target, cell(ed), cell(ea),
                  cell(es), cell(em), ea.rms / em.rms, ea.hausdorff / em.hausdorff, ea.rms / es.rms, ea.hausdorff / es.hausdorff);
      std::fflush(stdout);
    }
  }
  // the approximation error as a threshold: what it bounds
  std::printf("\nAdaptive_criterion::APPROXIMATION_ERROR with a threshold t (1e-3 of the diagonal): vertices kept, largest distance from the input vertices to the result / t, two-sided Hausdorff / t\n\n");
  std::printf("| mesh | t = 0.5 | t = 1 | t = 2 | t = 4 | t = 8 |\n|---|---|---|---|---|---|\n");
  for(const std::string& file : files)
  {
    Mesh mesh;
    double diagonal = 0.;
    if(!load(file, mesh, diagonal))
      continue;
    Tree tree(faces(mesh).first, faces(mesh).second, mesh);
    tree.accelerate_distance_queries();
    const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh, SMR::parameters::minimum_number_of_vertices(num_vertices(mesh) / 200));
    std::printf("| %s |", file.substr(file.find_last_of('/') + 1).c_str());
    for(double t : {0.5, 1., 2., 4., 8.})
    {
      Mesh out;
      SMR::reconstruct_adaptively(pyr, out, t * 1e-3 * diagonal, SMR::parameters::adaptive_criterion(SMR::Adaptive_criterion::APPROXIMATION_ERROR));
      const Error e = error(mesh, tree, out, diagonal);
      std::printf(" %zu v, %.2f, %.2f |", e.vertices, e.max / t, e.hausdorff / t);
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}
