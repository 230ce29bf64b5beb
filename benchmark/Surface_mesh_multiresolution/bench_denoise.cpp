// SPDX-License-Identifier: GPL-3.0-or-later
// Denoising quality on noisy/clean pairs of the same connectivity: E_a, the mean angle between
// corresponding face normals (degrees), and E_v, the area-weighted RMS distance from the
// vertices to the clean surface (in mean edge lengths of the clean mesh). Rows: the noisy
// input, SMR::denoise (automatic, no parameter), the paper's soft thresholding of the five
// finest levels at the best of a few thresholds, and the peers at their best parameters:
// uniform Laplacian and Taubin smoothing (best iteration count), CGAL's
// Polygon_mesh_processing::smooth_shape (best time and iteration count) and bilateral normal
// filtering (best range sigma and normal iteration count), plus BNF's default run and its time. A peer's best is
// chosen against the clean mesh, separately for E_a and E_v: an upper bound of what a user
// gets. All rows are measured by this program.
// Usage: bench_denoise [noisy1 clean1 ...] [--synthetic mesh sigma ...] [--isotropic mesh sigma ...]
//   --synthetic: the clean mesh with Gaussian noise of deviation sigma (in mean edge lengths)
//   along the vertex normals (fixed seed), like the standard pairs.
//   --isotropic: the clean mesh with Gaussian noise of deviation sigma on each coordinate.
//   --timing mesh: times only (no clean mesh): SMR decompose + denoise + reconstruct and
//   BNF's default run on the mesh as it is, each the best of three runs.
//   --write DIR (before the meshes): writes NAME_noisy.ply, NAME_bnf.ply (BNF at its best
//   parameters for E_a) and NAME_smr.ply (SMR::denoise) of every pair into DIR, for figures.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/smooth_shape.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <utility>
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

// the best E_a and the best E_v of a family of results (each with its own parameter)
struct Best { Errors ea_best{1e30, 1e30}, ev_best{1e30, 1e30}; double ea_param = 0, ev_param = 0; };
template <typename F>
Best best(const std::vector<double>& params, const F& make, const Mesh& clean, const Tree& tree, double edge)
{
  Best b;
  for(double p : params)
  {
    const Errors e = errors(make(p), clean, tree, edge);
    if(e.ea < b.ea_best.ea) { b.ea_best = e; b.ea_param = p; }
    if(e.ev < b.ev_best.ev) { b.ev_best = e; b.ev_param = p; }
  }
  return b;
}

double mean_edge_length(const Mesh& m)
{
  double edge = 0;
  for(auto e : edges(m)) edge += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
  return edge / double(num_edges(m));
}

Mesh taubin(const Mesh& noisy, int steps)
{
  Mesh out = noisy;   // Taubin lambda|mu: a uniform step of 0.5 then one of -0.53
  for(int it = 0; it < steps; ++it)
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
  return out;
}

// Bilateral normal filtering (Zheng, Fu, Au, Tai 2011), local iterative scheme, the
// feature-preserving peer: the face normals are filtered `normal_iterations` times, each the
// normalised sum over the faces sharing a vertex with the face (the face itself excluded) of
// area x spatial Gaussian of the centroid distance (sigma_c: the mean distance between the
// centroids of edge-adjacent faces) x range Gaussian of the normal difference (sigma_s) x
// normal; then `vertex_iterations` vertex updates fit the filtered normals (Sun et al. 2007):
// x_v += mean over the faces f of v of n_f (n_f . (c_f - x_v)). Written here on index arrays
// (no Debian package provides it); the reference implementation's defaults are sigma_s 0.35,
// 20 normal and 10 vertex iterations.
Mesh bilateral_normal_filtering(const Mesh& noisy, double sigma_s, int normal_iterations, int vertex_iterations)
{
  typedef std::array<double, 3> V3;
  auto sub = [](const V3& a, const V3& b) { return V3{{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; };
  auto dot = [](const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const std::size_t nv = num_vertices(noisy), nf = num_faces(noisy);
  std::vector<V3> x(nv);
  for(auto v : vertices(noisy)) x[v.idx()] = {{noisy.point(v).x(), noisy.point(v).y(), noisy.point(v).z()}};
  std::vector<std::array<std::size_t, 3> > F;
  std::vector<std::vector<std::size_t> > faces_of(nv);
  for(auto f : faces(noisy))
  {
    std::array<std::size_t, 3> t;
    int k = 0;
    for(auto v : vertices_around_face(halfedge(f, noisy), noisy)) t[k++] = v.idx();
    for(std::size_t v : t) faces_of[v].push_back(F.size());
    F.push_back(t);
  }
  std::vector<V3> n(nf), c(nf);
  std::vector<double> area(nf);
  auto geometry = [&] {
    for(std::size_t f = 0; f < nf; ++f)
    {
      const V3 u = sub(x[F[f][1]], x[F[f][0]]), w = sub(x[F[f][2]], x[F[f][0]]);
      V3 cr{{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]}};
      const double l = std::sqrt(dot(cr, cr));
      area[f] = l / 2;
      n[f] = l > 0 ? V3{{cr[0] / l, cr[1] / l, cr[2] / l}} : V3{{0, 0, 0}};
      for(int i = 0; i < 3; ++i) c[f][i] = (x[F[f][0]][i] + x[F[f][1]][i] + x[F[f][2]][i]) / 3;
    }
  };
  geometry();
  // neighbourhoods: the faces sharing a vertex, without the face itself
  std::vector<std::vector<std::size_t> > ring(nf);
  double sigma_c = 0;
  std::size_t pairs = 0;
  for(std::size_t f = 0; f < nf; ++f)
  {
    for(std::size_t v : F[f]) ring[f].insert(ring[f].end(), faces_of[v].begin(), faces_of[v].end());
    std::sort(ring[f].begin(), ring[f].end());
    ring[f].erase(std::unique(ring[f].begin(), ring[f].end()), ring[f].end());
    ring[f].erase(std::remove(ring[f].begin(), ring[f].end(), f), ring[f].end());
    for(std::size_t g : ring[f])
    {
      int shared = 0;
      for(std::size_t a : F[f]) for(std::size_t b : F[g]) shared += (a == b);
      if(shared == 2) { const V3 d = sub(c[f], c[g]); sigma_c += std::sqrt(dot(d, d)); ++pairs; }
    }
  }
  sigma_c = pairs > 0 ? sigma_c / double(pairs) : 1.;
  std::vector<V3> m(nf);
  for(int it = 0; it < normal_iterations; ++it)
  {
    for(std::size_t f = 0; f < nf; ++f)
    {
      V3 s{{0, 0, 0}};
      for(std::size_t g : ring[f])
      {
        const V3 dc = sub(c[f], c[g]), dn = sub(n[f], n[g]);
        const double wgt = area[g] * std::exp(-dot(dc, dc) / (2 * sigma_c * sigma_c)) * std::exp(-dot(dn, dn) / (2 * sigma_s * sigma_s));
        for(int i = 0; i < 3; ++i) s[i] += wgt * n[g][i];
      }
      const double l = std::sqrt(dot(s, s));
      m[f] = l > 0 ? V3{{s[0] / l, s[1] / l, s[2] / l}} : n[f];
    }
    n.swap(m);
  }
  for(int it = 0; it < vertex_iterations; ++it)
  {
    for(std::size_t f = 0; f < nf; ++f)
      for(int i = 0; i < 3; ++i) c[f][i] = (x[F[f][0]][i] + x[F[f][1]][i] + x[F[f][2]][i]) / 3;
    std::vector<V3> y = x;
    for(std::size_t v = 0; v < nv; ++v)
    {
      if(faces_of[v].empty()) continue;
      V3 d{{0, 0, 0}};
      for(std::size_t f : faces_of[v])
      {
        const double p = dot(n[f], sub(c[f], x[v]));
        for(int i = 0; i < 3; ++i) d[i] += p * n[f][i];
      }
      for(int i = 0; i < 3; ++i) y[v][i] += d[i] / double(faces_of[v].size());
    }
    x.swap(y);
  }
  Mesh out = noisy;
  for(auto v : vertices(out)) out.point(v) = K::Point_3(x[v.idx()][0], x[v.idx()][1], x[v.idx()][2]);
  return out;
}

std::string output_folder;   // --write

void write_result(const std::string& name, const char* suffix, const Mesh& m)
{
  if(output_folder.empty()) return;
  std::string stem;   // the name with its extension dropped, spaces and signs as underscores
  for(char c : name.substr(0, name.rfind(".obj"))) stem += std::isalnum(static_cast<unsigned char>(c)) || c == '.' ? c : '_';
  if(!CGAL::IO::write_polygon_mesh(output_folder + "/" + stem + suffix, m, CGAL::parameters::use_binary_mode(true)))
    std::cerr << "cannot write " << output_folder << "/" << stem << suffix << "\n";
}

void evaluate(const std::string& name, const Mesh& noisy, const Mesh& clean)
{
  Tree tree(faces(clean).first, faces(clean).second, clean);
  tree.accelerate_distance_queries();
  const double edge = mean_edge_length(clean);
  const Errors e0 = errors(noisy, clean, tree, edge);

  const auto t0 = std::chrono::steady_clock::now();
  SMR::Pyramid<Mesh> pyr = std::getenv("SMR_UNIFORM") ? SMR::decompose(noisy, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme::UNIFORM)) : SMR::decompose(noisy);
  const auto t1 = std::chrono::steady_clock::now();
  SMR::Pyramid<Mesh> p = pyr;
  if(std::getenv("SMR_PASSES")) SMR::denoise(p, CGAL::parameters::number_of_iterations(unsigned(std::atoi(std::getenv("SMR_PASSES"))))); else SMR::denoise(p);
  Mesh dn;
  SMR::reconstruct(p, dn);
  const auto t2 = std::chrono::steady_clock::now();
  const Errors e1 = errors(dn, clean, tree, edge);
  const double sigma = SMR::estimate_noise(pyr);
  const Best st = best({0.5, 1., 1.5, 2., 3., 4.}, [&](double c) {
    SMR::Pyramid<Mesh> q = pyr; SMR::soft_threshold(q, c * sigma); Mesh out; SMR::reconstruct(q, out); return out; }, clean, tree, edge);
  const Best lap = best({1, 2, 3, 5, 8, 12, 20}, [&](double n) {
    Mesh out = noisy;
    SMR::relax(out, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme::UNIFORM).number_of_iterations(unsigned(n)));
    return out; }, clean, tree, edge);
  const Best tau = best({2, 5, 10, 20, 40, 80}, [&](double n) { return taubin(noisy, int(n)); }, clean, tree, edge);
  // smooth_shape: time has the unit of a squared length (mass matrix ~ area); grid in edge^2,
  // one or three iterations (encoded as c + 1000 * (iterations - 1))
  const Best ss = best({0.25, 1., 4., 16., 2000.25, 2001., 2004.}, [&](double c) {
    Mesh out = noisy;
    const unsigned int iterations = c > 1000 ? 3u : 1u;
    const double time = (c > 1000 ? c - 2000 : c) * edge * edge;
    PMP::smooth_shape(out, time, CGAL::parameters::number_of_iterations(iterations));
    return out; }, clean, tree, edge);
  // BNF: best over range sigma x normal iterations (10 vertex iterations), and its default run, timed
  const std::vector<std::pair<double, int> > grid = {{0.2, 5}, {0.2, 20}, {0.2, 50}, {0.35, 5}, {0.35, 20}, {0.35, 50},
                                                     {0.5, 5}, {0.5, 20}, {0.5, 50}};
  const Best bnf = best({0, 1, 2, 3, 4, 5, 6, 7, 8}, [&](double i) {
    return bilateral_normal_filtering(noisy, grid[std::size_t(i)].first, grid[std::size_t(i)].second, 10); }, clean, tree, edge);
  const auto t3 = std::chrono::steady_clock::now();
  const Mesh bnf_default = bilateral_normal_filtering(noisy, 0.35, 20, 10);
  const auto t4 = std::chrono::steady_clock::now();
  const Errors eb = errors(bnf_default, clean, tree, edge);
  write_result(name, "_noisy.ply", noisy);
  write_result(name, "_smr.ply", dn);
  if(!output_folder.empty())
    write_result(name, "_bnf.ply", bilateral_normal_filtering(noisy, grid[std::size_t(bnf.ea_param)].first, grid[std::size_t(bnf.ea_param)].second, 10));
  std::printf("| %s | %.2f / %.3f | %.3f | **%.2f / %.3f** | %.2f / %.3f | %.2f / %.3f | %.2f / %.3f | %.2f / %.3f | %.2f / %.3f (s %.2f, %d it) | %.2f / %.3f | %.2f s | %.2f s |\n",
              name.c_str(), e0.ea, e0.ev, sigma / edge, e1.ea, e1.ev, st.ea_best.ea, st.ev_best.ev,
              lap.ea_best.ea, lap.ev_best.ev, tau.ea_best.ea, tau.ev_best.ev, ss.ea_best.ea, ss.ev_best.ev,
              bnf.ea_best.ea, bnf.ev_best.ev, grid[std::size_t(bnf.ea_param)].first, grid[std::size_t(bnf.ea_param)].second,
              eb.ea, eb.ev,
              std::chrono::duration<double>(t2 - t1).count() + std::chrono::duration<double>(t1 - t0).count(),
              std::chrono::duration<double>(t4 - t3).count());
  std::fflush(stdout);
}

int main(int argc, char** argv)
{
  std::printf("E_a (degrees) / E_v (mean edge lengths); peers and soft thresholding at their best parameter per metric\n\n");
  std::printf("| model | noisy | sigma est. (edges) | SMR denoise (auto) | SMR soft threshold D_1..D_5, best t | uniform Laplacian, best | Taubin, best | CGAL smooth_shape, best | bilateral normal filtering, best (E_a's parameters) | BNF default | SMR decompose + denoise + reconstruct time | BNF default time |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for(int i = 1; i < argc; )
  {
    if(std::strcmp(argv[i], "--timing") == 0 && i + 1 < argc)
    {
      Mesh m;
      if(!CGAL::IO::read_polygon_mesh(argv[i + 1], m) || !CGAL::is_triangle_mesh(m))
      { std::cerr << "cannot read " << argv[i + 1] << "\n"; i += 2; continue; }
      double ours = 1e30, bnf = 1e30;
      for(int run = 0; run < 3; ++run)
      {
        const auto t0 = std::chrono::steady_clock::now();
        SMR::Pyramid<Mesh> pyr = SMR::decompose(m);
        SMR::denoise(pyr);
        Mesh out;
        SMR::reconstruct(pyr, out);
        const auto t1 = std::chrono::steady_clock::now();
        bilateral_normal_filtering(m, 0.35, 20, 10);
        const auto t2 = std::chrono::steady_clock::now();
        ours = (std::min)(ours, std::chrono::duration<double>(t1 - t0).count());
        bnf = (std::min)(bnf, std::chrono::duration<double>(t2 - t1).count());
      }
      std::string name = argv[i + 1];
      std::printf("timing %s (%zu vertices): SMR decompose + denoise + reconstruct %.2f s, BNF default %.2f s, ratio %.2f\n",
                  name.substr(name.find_last_of('/') + 1).c_str(), std::size_t(num_vertices(m)), ours, bnf, ours / bnf);
      i += 2;
      continue;
    }
    if(std::strcmp(argv[i], "--write") == 0 && i + 1 < argc)
    {
      output_folder = argv[i + 1];
      i += 2;
      continue;
    }
    const bool along_normals = std::strcmp(argv[i], "--synthetic") == 0;
    if((along_normals || std::strcmp(argv[i], "--isotropic") == 0) && i + 2 < argc)
    {
      Mesh clean;
      const double s = std::atof(argv[i + 2]);
      if(!CGAL::IO::read_polygon_mesh(argv[i + 1], clean) || !CGAL::is_triangle_mesh(clean) || !(s >= 0))
      { std::cerr << "cannot read " << argv[i + 1] << "\n"; i += 3; continue; }
      const double edge = mean_edge_length(clean);
      auto vn = get(CGAL::dynamic_vertex_property_t<K::Vector_3>(), clean);
      PMP::compute_vertex_normals(clean, vn);
      Mesh noisy = clean;
      std::mt19937 rng(12345);
      std::normal_distribution<double> g(0., s * edge);
      for(auto v : vertices(noisy))
        noisy.point(v) = noisy.point(v) + (along_normals ? g(rng) * get(vn, v) : K::Vector_3(g(rng), g(rng), g(rng)));
      std::string name = argv[i + 1];
      name = name.substr(name.find_last_of('/') + 1) + (along_normals ? " + noise " : " + isotropic noise ") + argv[i + 2];
      evaluate(name, noisy, clean);
      i += 3;
      continue;
    }
    if(i + 1 >= argc) break;
    Mesh noisy, clean;
    if(!CGAL::IO::read_polygon_mesh(argv[i], noisy) || !CGAL::IO::read_polygon_mesh(argv[i + 1], clean)
       || num_vertices(noisy) != num_vertices(clean) || num_faces(noisy) != num_faces(clean))
    { std::cerr << "cannot read the pair " << argv[i] << " " << argv[i + 1] << "\n"; i += 2; continue; }
    std::string name = argv[i];
    evaluate(name.substr(name.find_last_of('/') + 1), noisy, clean);
    i += 2;
  }
  return 0;
}
