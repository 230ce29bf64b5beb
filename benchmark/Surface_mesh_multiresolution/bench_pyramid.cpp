// SPDX-License-Identifier: GPL-3.0-or-later
// Pyramid decomposition and reconstruction next to the simplifiers of CGAL (SMS
// edge_collapse with Garland-Heckbert plane policies), OpenMesh (Decimater with the
// Quadric and IndependentSets modules) and meshoptimizer (meshopt_simplify), each run to the
// coarsest vertex count of the pyramid. Every step is timed in this process (see timed());
// the memory of the decomposition is measured in a fresh process of this program.
//
// Usage: bench_pyramid [mesh files...]   (default: CGAL data meshes)
//        bench_pyramid --scaling FILE...    (1, 2, 4, ... threads; then the machine's own
//                                            speed-up on a stream, a gather and a computation)
//        bench_pyramid --sizes FILE N       (the mesh and N Loop subdivisions of it, as
//                                            subdivided and in a spatial order)
//        bench_pyramid --ratio PAIRS FILE...  (decomposition against meshopt_simplify, in
//                                            alternating pairs; all threads, then one)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModIndependentSetsT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <meshoptimizer.h>
#include "scan_io.h"   // smr_tool::order_spatially(), the tool's --spatial-order
#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/info.h>
#endif

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3>                      Mesh;
typedef OpenMesh::TriMesh_ArrayKernelT<>                    OM_mesh;
namespace SMR = CGAL::Surface_mesh_multiresolution;
namespace SMS = CGAL::Surface_mesh_simplification;

// Reads a triangle mesh; a non-manifold file (Stanford's dragon_vrip_res2/3/4) is read as a
// polygon soup and made manifold by CGAL's soup repair and orientation (non-manifold
// vertices duplicated). Unreferenced vertices (bun_zipper.ply has 1,113) are removed: they
// would count in the 1 % target.
bool read_mesh(const std::string& file, Mesh& mesh)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  if(!CGAL::IO::read_polygon_mesh(file, mesh))
  {
    std::vector<K::Point_3> points;
    std::vector<std::vector<std::size_t> > polygons;
    if(!CGAL::IO::read_polygon_soup(file, points, polygons)) return false;
    PMP::repair_polygon_soup(points, polygons);
    PMP::orient_polygon_soup(points, polygons);
    mesh.clear();
    PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  }
  if(!CGAL::is_triangle_mesh(mesh) || num_vertices(mesh) == 0) return false;
  PMP::remove_isolated_vertices(mesh);
  mesh.collect_garbage();
  return true;
}

// resident memory now, in MiB
double rss_mib()
{
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * double(sysconf(_SC_PAGESIZE)) / (1024. * 1024.);
}

struct Measure { double seconds = -1; long result = -1; };

// runs f in this process: its time and the number it returns (a vertex count). Best of up to
// 3 runs, repeated while the runs so far took less than 3 s: the same rule for every system
// (short runs on this virtual machine vary by up to 2x). Timings were taken in forked child
// processes before; there the first write to every heap page inherited from the parent is a
// copy-on-write fault, which slowed write-heavy steps (reconstruction: +70 %) far more than
// anything a user's process sees. Memory is measured in a fresh process (memory_mode()).
Measure timed(const std::function<long()>& f)
{
  Measure m;
  double total = 0.;
  for(int run = 0; run < 3 && total < 3.; ++run)
  {
    CGAL::Real_timer t;
    t.start();
    m.result = f();
    const double s = t.time();
    total += s;
    m.seconds = (run == 0) ? s : (std::min)(m.seconds, s);
  }
  return m;
}

// `bench_pyramid --memory FILE`, run in a fresh process: RSS before loading, after loading,
// and the peak while decomposing, in MiB
int memory_mode(const char* file)
{
  const double base = rss_mib();
  Mesh mesh;
  if(!read_mesh(file, mesh)) return 1;
  const double loaded = rss_mib();
  const auto pyr = SMR::decompose(mesh, SMR::parameters::minimum_number_of_vertices(std::size_t(mesh.number_of_vertices() / 100)));
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  std::printf("%f %f %f %zu\n", base, loaded, u.ru_maxrss / 1024., pyr.number_of_levels());
  return 0;
}

#ifdef CGAL_LINKED_WITH_TBB
// The machine's own speed-up at the thread counts of --scaling, on three plain loops over
// arrays larger than the caches (16M doubles): a stream (b = 2a + 1: memory bandwidth), a
// gather (b[i] = a[idx[i]], random indices: memory latency) and a computation (40 dependent
// multiply-adds per value: the cores). The decomposition and the reconstruction are a mix of
// the three; their speed-ups are read against these ceilings. Counts alternate in rounds.
void machine_ceilings(const std::vector<int>& counts, int rounds)
{
  const std::size_t n = std::size_t(1) << 24;
  std::vector<double> a(n), b(n);
  std::vector<std::uint32_t> idx(n);
  std::uint64_t s = 88172645463325252ull;                  // xorshift64: the same pseudo-random indices every run
  for(std::size_t i = 0; i < n; ++i)
  {
    s ^= s << 13; s ^= s >> 7; s ^= s << 17;
    idx[i] = std::uint32_t(s % n);
    a[i] = double(i);
  }
  auto loop = [&](std::size_t count, const auto& body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1 << 14), [&](const tbb::blocked_range<std::size_t>& r) {
      for(std::size_t i = r.begin(); i < r.end(); ++i) body(i);
    });
  };
  const char* names[3] = {"stream (bandwidth)", "gather (latency)", "compute (cores)"};
  std::vector<std::vector<double> > best(3, std::vector<double>(counts.size(), 1e30));
  for(int round = 0; round < rounds; ++round)
    for(std::size_t c = 0; c < counts.size(); ++c)
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(counts[c]));
      for(int k = 0; k < 3; ++k)
      {
        CGAL::Real_timer timer;
        timer.start();
        if(k == 0)
          loop(n, [&](std::size_t i) { b[i] = 2. * a[i] + 1.; });
        else if(k == 1)
          loop(n, [&](std::size_t i) { b[i] = a[idx[i]]; });
        else
          loop(n / 8, [&](std::size_t i) {
            double x = a[i];
            for(int j = 0; j < 40; ++j) x = x * 1.0000001 + 0.5;
            b[i] = x;
          });
        best[k][c] = (std::min)(best[k][c], timer.time());
      }
    }
  std::printf("\n| machine loop | threads | time (s) | speed-up |\n|---|---:|---:|---:|\n");
  for(int k = 0; k < 3; ++k)
    for(std::size_t c = 0; c < counts.size(); ++c)
      std::printf("| %s | %d | %.3f | %.2f |\n", names[k], counts[c], best[k][c], best[k][0] / best[k][c]);
  std::printf("(checksum %.1f)\n", b[n / 3]);
}
#endif

// `bench_pyramid --scaling FILE...`: decomposition and reconstruction times for 1, 2, 4, ...
// threads up to the machine's, and whether every pyramid is bit-identical to the 1-thread one.
// The thread counts alternate in rounds (1, 2, ..., then 1, 2, ... again) and each keeps its
// best time: on a shared machine whose speed drifts within a minute, measuring one thread
// count after the other moved the speed-up by 15 % between runs.
int scaling_mode(int argc, char** argv)
{
#ifdef CGAL_LINKED_WITH_TBB
  const int available = tbb::info::default_concurrency();
  constexpr int rounds = 5;
  std::vector<int> counts;
  for(int t = 1; t <= available; t = (t == available ? available + 1 : (std::min)(2 * t, available)))
    counts.push_back(t);
  std::printf("| mesh | vertices | threads | decompose (s) | speed-up | reconstruct (s) | speed-up | identical to 1 thread |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---|\n");
  for(int i = 2; i < argc; ++i)
  {
    Mesh mesh;
    if(!read_mesh(argv[i], mesh)) continue;
    const std::size_t n = mesh.number_of_vertices();
    std::vector<double> best_d(counts.size(), 1e30), best_r(counts.size(), 1e30);
    std::vector<std::vector<double> > values(counts.size());   // all details and coarse values, to compare bit for bit
    for(int round = 0; round < rounds; ++round)
      for(std::size_t c = 0; c < counts.size(); ++c)
      {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(counts[c]));
        CGAL::Real_timer timer;
        timer.start();
        const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh, SMR::parameters::minimum_number_of_vertices(n / 100));
        best_d[c] = (std::min)(best_d[c], timer.time());
        Mesh out;
        timer.reset();
        SMR::reconstruct(pyr, out);
        best_r[c] = (std::min)(best_r[c], timer.time());
        if(round == 0)
        {
          for(std::size_t j = 1; j <= pyr.number_of_levels(); ++j)
            values[c].insert(values[c].end(), pyr.details(j, 0).begin(), pyr.details(j, 0).end());
          values[c].insert(values[c].end(), pyr.coarse_values()[0].begin(), pyr.coarse_values()[0].end());
        }
      }
    const std::string name = std::string(argv[i]).substr(std::string(argv[i]).find_last_of('/') + 1);
    for(std::size_t c = 0; c < counts.size(); ++c)
      std::printf("| %s | %zu | %d | %.3f | %.2f | %.3f | %.2f | %s |\n", name.c_str(), n, counts[c], best_d[c], best_d[0] / best_d[c],
                  best_r[c], best_r[0] / best_r[c], values[c] == values[0] ? "yes" : "NO");
    std::fflush(stdout);
  }
  machine_ceilings(counts, rounds);
  return 0;
#else
  (void)argc; (void)argv;
  std::printf("built without TBB: no scaling to measure\n");
  return 0;
#endif
}

// meshopt_simplify's input arrays, built outside the timing
struct Meshopt_input
{
  std::vector<float> xyz;
  std::vector<unsigned int> indices;

  explicit Meshopt_input(const Mesh& mesh)
  {
    for(auto v : mesh.vertices()) xyz.insert(xyz.end(), {float(mesh.point(v).x()), float(mesh.point(v).y()), float(mesh.point(v).z())});
    for(auto f : mesh.faces())
      for(auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) indices.push_back(v.idx());
  }

  // meshopt_simplify to about `target` vertices; the vertex count it reached
  long simplify(long target) const
  {
    // meshoptimizer targets an index count: faces ~ 2 x vertices on a closed mesh
    std::vector<unsigned int> out(indices.size());
    const std::size_t count = meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(), xyz.size() / 3,
                                               3 * sizeof(float), std::size_t(6 * target), 1.f);
    std::vector<char> used(xyz.size() / 3, 0);
    long nv = 0;
    for(std::size_t i = 0; i < count; ++i) if(!used[out[i]]) { used[out[i]] = 1; ++nv; }
    return nv;
  }
};

// meshopt_simplify to about `target` vertices (its arrays built outside the timing)
Measure meshopt_to(const Mesh& mesh, long target)
{
  const Meshopt_input input(mesh);
  return timed([&] { return input.simplify(target); });
}

// `bench_pyramid --ratio PAIRS FILE...`: the decomposition to 1 % against meshopt_simplify to
// the same vertex count, in pairs run one after the other (decompose, then meshopt), PAIRS
// pairs per thread count (all threads, then one). Why: the main table times each system once
// in turn, a minute apart on the dragon, and this shared machine's speed drifts by 10-30 %
// within minutes; the pairs see the same state. Printed: the best time of each, the ratio of
// the bests, and the median of the pairs' own ratios.
int ratio_mode(int argc, char** argv)
{
  const int pairs = (std::max)(1, std::atoi(argv[2]));
  std::vector<int> counts;
#ifdef CGAL_LINKED_WITH_TBB
  counts.push_back(tbb::info::default_concurrency());
  if(counts[0] != 1)
    counts.push_back(1);
#else
  counts.push_back(1);
#endif
  std::printf("| mesh | vertices | threads | pairs | decompose, best (s) | meshopt_simplify, best (s) | ratio of bests | median ratio of the pairs |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for(int i = 3; i < argc; ++i)
  {
    Mesh mesh;
    if(!read_mesh(argv[i], mesh))
    {
      std::cerr << "cannot read " << argv[i] << " as a triangle mesh: skipped\n";
      continue;
    }
    const std::size_t n = mesh.number_of_vertices();
    const Meshopt_input input(mesh);
    const std::string name = std::string(argv[i]).substr(std::string(argv[i]).find_last_of('/') + 1);
    for(int threads : counts)
    {
#ifdef CGAL_LINKED_WITH_TBB
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
#endif
      double best_d = 1e30, best_m = 1e30;
      std::vector<double> ratios;
      long target = 0;
      for(int r = 0; r < pairs; ++r)
      {
        CGAL::Real_timer t;
        t.start();
        const auto p = SMR::decompose(mesh, SMR::parameters::minimum_number_of_vertices(n / 100));
        const double d = t.time();
        target = long(p.number_of_vertices(p.number_of_levels()));
        t.reset();
        input.simplify(target);
        const double m = t.time();
        best_d = (std::min)(best_d, d);
        best_m = (std::min)(best_m, m);
        ratios.push_back(d / m);
      }
      std::sort(ratios.begin(), ratios.end());
      const double median = ratios.size() % 2 ? ratios[ratios.size() / 2]
                                              : 0.5 * (ratios[ratios.size() / 2 - 1] + ratios[ratios.size() / 2]);
      std::printf("| %s | %zu | %d | %d | %.3f | %.3f | %.2f | %.2f |\n", name.c_str(), n, threads, pairs, best_d, best_m,
                  best_d / best_m, median);
      std::fflush(stdout);
    }
  }
  return 0;
}


// The same mesh in the order `smr --spatial-order` gives a file (smr_tool::order_spatially():
// the order a decomposition keeps of its own, Memory_order::SPATIAL: faces in the Morton order
// of their centroids, vertices by first use): the memory order of a locality-ordered file. Loop subdivision appends each level's new
// vertices and faces after the old ones, so neighbours of the subdivided meshes lie far apart
// in memory.
Mesh spatially_ordered(const Mesh& mesh)
{
  smr_tool::Soup soup;
  CGAL::Polygon_mesh_processing::polygon_mesh_to_polygon_soup(mesh, soup.points, soup.polygons);
  smr_tool::order_spatially(soup);
  Mesh out;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, out);
  return out;
}

// `bench_pyramid --sizes FILE N`: the mesh and its 1..N Loop subdivisions (4x the vertices
// each), decomposed to 1 % and simplified by meshopt_simplify to the same count: time per
// vertex against size, for each mesh as subdivided and spatially ordered
int sizes_mode(const char* file, int subdivisions)
{
  Mesh mesh;
  if(!read_mesh(file, mesh)) return 1;
  std::printf("| mesh | vertices | SMR decompose (s) | µs per vertex | per vertex / unsubdivided | meshopt_simplify (s) | µs per vertex | per vertex / unsubdivided | decompose / meshopt |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  double first_smr[2] = {0, 0}, first_mo[2] = {0, 0};
  const std::string name = std::string(file).substr(std::string(file).find_last_of('/') + 1);
  for(int s = 0; s <= subdivisions; ++s)
  {
    if(s > 0)
      CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(1));
    for(int ordered = 0; ordered < 2; ++ordered)
    {
      const Mesh m = ordered ? spatially_ordered(mesh) : Mesh();
      const Mesh& input = ordered ? m : mesh;
      const long n = long(input.number_of_vertices());
      long target = 0;
      const Measure dec = timed([&] {
        const auto p = SMR::decompose(input, SMR::parameters::minimum_number_of_vertices(std::size_t(n / 100)));
        return target = long(p.number_of_vertices(p.number_of_levels()));
      });
      const Measure mo = meshopt_to(input, target);
      const double smr_us = 1e6 * dec.seconds / double(n), mo_us = 1e6 * mo.seconds / double(n);
      if(s == 0) { first_smr[ordered] = smr_us; first_mo[ordered] = mo_us; }
      std::printf("| %s, %d Loop subdivision%s%s | %ld | %.3f | %.2f | %.2f | %.3f (%ld v) | %.2f | %.2f | %.2f |\n", name.c_str(), s,
                  s == 1 ? "" : "s", ordered ? ", spatially ordered" : "", n, dec.seconds, smr_us, smr_us / first_smr[ordered],
                  mo.seconds, mo.result, mo_us, mo_us / first_mo[ordered], dec.seconds / mo.seconds);
      std::fflush(stdout);
    }
  }
  return 0;
}

int main(int argc, char** argv)
{
  if(argc == 3 && std::string(argv[1]) == "--memory")
    return memory_mode(argv[2]);
  if(argc >= 3 && std::string(argv[1]) == "--scaling")
    return scaling_mode(argc, argv);
  if(argc == 4 && std::string(argv[1]) == "--sizes")
    return sizes_mode(argv[2], std::atoi(argv[3]));
  if(argc >= 4 && std::string(argv[1]) == "--ratio")
    return ratio_mode(argc, argv);
  std::vector<std::string> files;
  for(int i = 1; i < argc; ++i) files.push_back(argv[i]);
  if(files.empty())
    for(const char* f : {"meshes/bunny00.off", "meshes/refined_elephant.off", "meshes/armadillo.off"})
      files.push_back(CGAL::data_file_path(f));

  std::printf("| mesh | vertices | mesh RSS (MiB) | target | SMR decompose (s) | SMR reconstruct (s) | re-filter (s; M v/s) | SMS edge_collapse (s) "
              "| OpenMesh decimater (s) | meshopt_simplify (s) | decompose / SMS | reconstruct / decompose | decompose / meshopt "
              "| µs per vertex | decompose peak RSS (MiB, mesh included) | peak / mesh RSS |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::vector<std::string> storage_rows;   // the second table, printed after the first
  for(const std::string& file : files)
  {
    Mesh mesh;
    if(!read_mesh(file, mesh))
    {
      std::cerr << "cannot read " << file << " as a triangle mesh: skipped\n";
      continue;
    }
    // memory: measured by this program in a fresh process (see memory_mode())
    double base = 0, loaded = 0, peak = 0;
    {
      const std::string command = std::string("'") + argv[0] + "' --memory '" + file + "'";
      if(FILE* p = popen(command.c_str(), "r"))
      {
        if(std::fscanf(p, "%lf %lf %lf", &base, &loaded, &peak) != 3) base = loaded = peak = 0;
        pclose(p);
      }
    }
    const double mesh_rss = loaded - base;
    const long n = long(mesh.number_of_vertices());

    // the pyramid (kept in the parent too, for the reconstruction and the target count)
    const SMR::Pyramid<Mesh> pyr = SMR::decompose(mesh, SMR::parameters::minimum_number_of_vertices(std::size_t(n / 100)));
    const long target = long(pyr.number_of_vertices(pyr.number_of_levels()));
    const Measure dec = timed([&] {
      const auto p = SMR::decompose(mesh, SMR::parameters::minimum_number_of_vertices(std::size_t(n / 100)));
      return long(p.number_of_vertices(p.number_of_levels()));
    });
    const Measure rec = timed([&] { Mesh out; SMR::reconstruct(pyr, out); return long(out.number_of_vertices()); });
    // re-filtering: new gains on D_2..D_4 and a values-only reconstruction into the mesh of an
    // earlier reconstruction (keep_connectivity), ten times
    Mesh previous;
    SMR::reconstruct(pyr, previous);
    auto refiltering = [&](SMR::Pyramid<Mesh>& p) {
      CGAL::Real_timer t;
      t.start();
      for(int i = 0; i < 10; ++i)
      {
        for(std::size_t j = 2; j <= (std::min)(std::size_t(4), p.number_of_levels()); ++j)
          SMR::scale_details(p, j, i % 2 == 0 ? 2. : 0.5);
        SMR::reconstruct(p, previous, SMR::parameters::keep_connectivity(true));
      }
      return long(1e6 * t.time() / 10);   // microseconds per re-filtering
    };
    const Measure refilter = timed([&] {
      SMR::Pyramid<Mesh> p = pyr;   // (copied outside the loop: filtering is in place)
      return refiltering(p);
    });
    const Measure sms = timed([&] {
      Mesh m = mesh;
      SMS::GarlandHeckbert_plane_policies<Mesh, K> gh(m);
      auto stop = [&m, target](const auto&, const auto&, std::size_t, std::size_t) { return long(m.number_of_vertices()) <= target; };
      SMS::edge_collapse(m, stop, CGAL::parameters::get_cost(gh.get_cost()).get_placement(gh.get_placement()));
      return long(m.number_of_vertices());
    });
    // the peers' own mesh structures are built outside the timing
    OM_mesh om;
    {
      std::vector<OM_mesh::VertexHandle> vh;
      for(auto v : mesh.vertices()) vh.push_back(om.add_vertex(OM_mesh::Point(mesh.point(v).x(), mesh.point(v).y(), mesh.point(v).z())));
      for(auto f : mesh.faces())
      {
        std::vector<OM_mesh::VertexHandle> t;
        for(auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) t.push_back(vh[v.idx()]);
        om.add_face(t);
      }
    }
    const Measure omd = timed([&] {
      OM_mesh m = om;
      OpenMesh::Decimater::DecimaterT<OM_mesh> decimater(m);
      OpenMesh::Decimater::ModQuadricT<OM_mesh>::Handle quadric;
      OpenMesh::Decimater::ModIndependentSetsT<OM_mesh>::Handle independent;
      decimater.add(quadric);
      decimater.add(independent);
      decimater.initialize();
      // the independent-sets module locks the neighbourhood of each collapse for one pass:
      // passes are repeated until the target is reached or a pass removes nothing
      std::size_t live = m.n_vertices(), removed = 1;
      while(live > std::size_t(target) && removed > 0)
      {
        for(auto v : m.vertices()) m.status(v).set_locked(false);   // the module never unlocks by itself
        removed = decimater.decimate_to(std::size_t(target));
        live -= removed;
      }
      m.garbage_collection();
      return long(m.n_vertices());
    });
    const Measure mo = meshopt_to(mesh, target);
    std::string name = file.substr(file.find_last_of('/') + 1);
    const double refilter_s = 1e-6 * double(refilter.result);

    // the saved pyramid against the input's binary PLY, and the weights kept (store_weights())
    std::string ply_bytes, pyramid_bytes;
    {
      std::ostringstream ply(std::ios::binary);
      CGAL::IO::write_PLY(ply, mesh, CGAL::parameters::use_binary_mode(true));
      ply_bytes = ply.str();
    }
    const Measure write = timed([&] {
      std::ostringstream out(std::ios::binary);
      SMR::IO::write_pyramid(out, pyr);
      pyramid_bytes = out.str();
      return long(pyramid_bytes.size());
    });
    const Measure read = timed([&] {
      SMR::Pyramid<Mesh> p;
      std::istringstream in(pyramid_bytes, std::ios::binary);
      return SMR::IO::read_pyramid(in, p) ? long(p.number_of_levels()) : -1L;
    });
    SMR::Pyramid<Mesh> stored = pyr;
    CGAL::Real_timer store_timer;
    store_timer.start();
    SMR::store_weights(stored);
    const double store_s = store_timer.time();
    const Measure rec_stored = timed([&] { Mesh out; SMR::reconstruct(stored, out); return long(out.number_of_vertices()); });
    const Measure refilter_stored = timed([&] { return refiltering(stored); });
    char row[512];
    std::snprintf(row, sizeof(row), "| %s | %.1f | %.1f | %.2f | %.3f | %.3f | %.3f | %.3f | %.3f; %.1f |",
                  name.c_str(), 1e-6 * double(ply_bytes.size()), 1e-6 * double(pyramid_bytes.size()),
                  double(pyramid_bytes.size()) / double(ply_bytes.size()), write.seconds, read.seconds, store_s,
                  rec_stored.seconds, 1e-6 * double(refilter_stored.result), double(n) / double(refilter_stored.result));
    storage_rows.push_back(row);
    std::printf("| %s | %ld | %.1f | %ld | %.3f | %.3f | %.3f; %.1f | %.3f (%ld v) | %.3f (%ld v) | %.3f (%ld v) | %.2f | %.3f | %.1f | %.2f | %.1f | %.2f |\n",
                name.c_str(), n, mesh_rss, target, dec.seconds, rec.seconds, refilter_s, 1e-6 * double(n) / refilter_s, sms.seconds, sms.result, omd.seconds, omd.result,
                mo.seconds, mo.result, dec.seconds / sms.seconds, rec.seconds / dec.seconds, dec.seconds / mo.seconds,
                1e6 * dec.seconds / double(n), peak - base, (peak - base) / mesh_rss);
    std::fflush(stdout);
  }
  std::printf("\n| mesh | binary PLY (MB) | pyramid file (MB) | file / PLY | write (s) | read (s) | store_weights (s) "
              "| reconstruct, weights stored (s) | re-filter, weights stored (s; M v/s) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for(const std::string& row : storage_rows)
    std::printf("%s\n", row.c_str());
  return 0;
}
