// SPDX-License-Identifier: GPL-3.0-or-later
// Table 1 of Roy et al., redone: time to build the weights of each relaxation scheme and to
// apply them, next to a straightforward halfedge-traversal cotangent relaxation (the
// baseline) measured in the same run. Every time is the best of several repetitions.
//
// Usage: bench_relaxation [mesh files...]   (default: CGAL's largest data meshes)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Real_timer.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
namespace SMR = CGAL::Surface_mesh_multiresolution;

// best time of repeated runs (at least 3 runs and 0.3 s in all)
double best_time(const std::function<void()>& f)
{
  double best = 1e30, total = 0;
  for(int run = 0; run < 3 || (total < 0.3 && run < 1000); ++run)
  {
    CGAL::Real_timer t;
    t.start();
    f();
    t.stop();
    best = (std::min)(best, t.time());
    total += t.time();
  }
  return best;
}

// The baseline: what a straightforward implementation does, one vertex at a time, walking
// the halfedges of its 1-ring and recomputing the cotangents of the incident triangles
// (each cotangent twice over the mesh); border vertices are kept.
void baseline_cotangent_relaxation(const Mesh& m, std::vector<K::Point_3>& out)
{
  out.resize(m.number_of_vertices());
  auto cot = [](const K::Point_3& apex, const K::Point_3& a, const K::Point_3& b) {
    const K::Vector_3 u = a - apex, v = b - apex;
    const double s = std::sqrt(CGAL::cross_product(u, v).squared_length());
    return s > 0 ? (u * v) / s : 0.;
  };
  for(Mesh::Vertex_index v : m.vertices())
  {
    const K::Point_3& p = m.point(v);
    if(m.is_border(v)) { out[v.idx()] = p; continue; }
    double sx = 0, sy = 0, sz = 0, sw = 0;
    for(Mesh::Halfedge_index h : CGAL::halfedges_around_target(v, m))
    {
      const K::Point_3& q = m.point(m.source(h));
      const K::Point_3& a = m.point(m.target(m.next(h)));                 // opposite in face(h)
      const K::Point_3& b = m.point(m.target(m.next(m.opposite(h))));   // opposite in the other face
      const double w = cot(a, p, q) + cot(b, p, q);
      sx += w * q.x(); sy += w * q.y(); sz += w * q.z(); sw += w;
    }
    out[v.idx()] = sw != 0 ? K::Point_3(sx / sw, sy / sw, sz / sw) : p;
  }
}

// The floor of any relaxation that reads a Surface_mesh's rings: a walk around every vertex
// (opposite of next, as CGAL's circulators step) that only sums the neighbours' positions
// and divides by their number, with no weight, no validation and no border rule, in parallel
// over the vertices like relax(). baseline / floor bounds what baseline / relax() can reach.
void ring_walk_floor(const Mesh& m, std::vector<double>& out)
{
  out.resize(3 * m.number_of_vertices());
  auto walk = [&](std::size_t first, std::size_t last) {
    for(std::size_t i = first; i < last; ++i)
    {
      const Mesh::Halfedge_index h0 = m.halfedge(Mesh::Vertex_index(static_cast<Mesh::size_type>(i)));
      if(h0 == Mesh::null_halfedge())
        continue;
      double s[3] = {0, 0, 0};
      std::size_t d = 0;
      Mesh::Halfedge_index h = h0;
      do
      {
        const K::Point_3& q = m.point(m.source(h));
        s[0] += q.x(); s[1] += q.y(); s[2] += q.z();
        ++d;
        h = m.opposite(m.next(h));
      } while(h != h0 && d <= m.number_of_halfedges());
      for(int c = 0; c < 3; ++c) out[3 * i + c] = s[c] / double(d);
    }
  };
#ifdef CGAL_LINKED_WITH_TBB
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.number_of_vertices(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) { walk(r.begin(), r.end()); });
#else
  walk(0, m.number_of_vertices());
#endif
}

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  for(int i = 1; i < argc; ++i) files.push_back(argv[i]);
  if(files.empty())
    for(const char* f : {"meshes/bunny00.off", "meshes/refined_elephant.off", "meshes/armadillo.off", "meshes/nefertiti.off"})
      files.push_back(CGAL::data_file_path(f));

  int threads = 1;
#ifdef CGAL_LINKED_WITH_TBB
  threads = tbb::info::default_concurrency();
#endif
  std::printf("Times are the best of repeated runs; rates in millions of vertices per second. Threads available: %d.\n\n", threads);
  std::printf("| mesh | vertices | baseline build+apply | curvature build | curvature apply (1 thread) | curvature apply (%d threads) "
              "| SOD build | SOD apply (1 thread) | uniform build | curvature build+apply / baseline | baseline / curvature apply (1 thread) "
              "| SOD / curvature (build+apply) | 20 steps, fixed weights: baseline / curvature "
              "| curvature apply (1 thread) / copy of the bytes it reads | relax() one step (%d threads) | baseline / relax() "
              "| baseline / curvature build | ring-walk floor (%d threads) | baseline / floor |\n",
              threads, threads, threads);
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for(const std::string& file : files)
  {
    Mesh m;
    if(!CGAL::IO::read_polygon_mesh(file, m) || !CGAL::is_triangle_mesh(m))
    {
      std::cerr << "cannot read " << file << " as a triangle mesh: skipped\n";
      continue;
    }
    const double n = double(m.number_of_vertices());
    std::vector<K::Point_3> base_out;
    const double t_base = best_time([&] { baseline_cotangent_relaxation(m, base_out); });

    std::vector<double> xyz, out;
    for(auto v : m.vertices()) xyz.insert(xyz.end(), {m.point(v).x(), m.point(v).y(), m.point(v).z()});

    double t_build[3], t_apply1[3], t_apply_n[3];
    const SMR::Relaxation_scheme schemes[3] = {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE,
                                               SMR::Relaxation_scheme::UNIFORM};
    for(int s = 0; s < 3; ++s)
    {
      SMR::Relaxation_operator<Mesh> R;
      t_build[s] = best_time([&] { R = SMR::relaxation_operator(m, SMR::parameters::relaxation_scheme(schemes[s])); });
      {
#ifdef CGAL_LINKED_WITH_TBB
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
#endif
        t_apply1[s] = best_time([&] { R.apply(xyz, out, 3); });
      }
      t_apply_n[s] = best_time([&] { R.apply(xyz, out, 3); });
    }
    // memory-bandwidth bound: a plain copy (one thread) of as many bytes as the curvature apply
    // reads (weights 8 + columns 4 bytes per entry, row offsets, the input coordinates)
    double t_copy = 0;
    {
      const SMR::Relaxation_operator<Mesh> R = SMR::relaxation_operator(m);
      const std::size_t bytes = R.weights().size() * 12 + (std::size_t(n) + 1) * 4 + xyz.size() * sizeof(double);
      std::vector<char> from(bytes, 1), to(bytes, 0);
      t_copy = best_time([&] { std::memcpy(to.data(), from.data(), bytes); from[to[bytes / 2] % bytes] += 1; });
    }
    // relax(): what a user calls for one step (index view of the mesh, weights applied as they
    // are computed, positions written back); each repetition relaxes the copy once more
    Mesh relaxed = m;
    const double t_relax = best_time([&] { SMR::relax(relaxed); });
    std::vector<double> floor_out;
    const double t_floor = best_time([&] { ring_walk_floor(m, floor_out); });
    auto rate = [n](double t) { return n / t / 1e6; };
    std::string name = file.substr(file.find_last_of('/') + 1);
    std::printf("| %s | %.0f | %.2f | %.2f | %.1f | %.1f | %.2f | %.1f | %.2f | %.2fx | %.1fx | %.2f | %.1fx | %.2f | %.2f | %.2fx | %.2fx | %.2f | %.2fx |\n", name.c_str(), n,
                rate(t_base), rate(t_build[0]), rate(t_apply1[0]), rate(t_apply_n[0]), rate(t_build[1]), rate(t_apply1[1]),
                rate(t_build[2]), t_base / (t_build[0] + t_apply1[0]), t_base / t_apply1[0],
                (t_build[1] + t_apply1[1]) / (t_build[0] + t_apply1[0]), 20 * t_base / (t_build[0] + 20 * t_apply1[0]),
                t_apply1[0] / t_copy, rate(t_relax), t_base / t_relax, t_base / t_build[0], rate(t_floor), t_base / t_floor);
    std::fflush(stdout);
  }
  return 0;
}
