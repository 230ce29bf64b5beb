// SPDX-License-Identifier: GPL-3.0-or-later
// One side of compare_trees.sh: the decomposition and reconstruction of one copy of the package, compiled with
// the namespace CGAL renamed (-DCGAL=...) and its entry points named by SIDE(x), so that two
// copies (two trees of the package, with the CGAL headers they include) live in one program.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Real_timer.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <cstdint>
#include <cstring>
#include <memory>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace SMR = CGAL::Surface_mesh_multiresolution;

static std::unique_ptr<Mesh> mesh;
static std::unique_ptr<SMR::Pyramid<Mesh> > pyramid;   // the last decomposition's

extern "C" bool SIDE(load)(const char* file)
{
  mesh.reset(new Mesh);
  return CGAL::IO::read_polygon_mesh(file, *mesh) && !mesh->is_empty();
}

// the time of one decomposition to 1 %; `hash`: FNV-1a of the bits of every detail and coarse
// value of the pyramid (the two trees' pyramids compared bit for bit)
extern "C" double SIDE(decompose)(std::uint64_t* hash)
{
  CGAL::Real_timer timer;
  timer.start();
  pyramid.reset();
  pyramid.reset(new SMR::Pyramid<Mesh>(
      SMR::decompose(*mesh, SMR::parameters::minimum_number_of_vertices(mesh->number_of_vertices() / 100))));
  const double seconds = timer.time();
  const SMR::Pyramid<Mesh>& pyr = *pyramid;
  if(hash != nullptr)
  {
    std::uint64_t h = 14695981039346656037ull;
    auto add = [&h](double x) {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      for(int b = 0; b < 8; ++b) { h ^= (bits >> (8 * b)) & 0xff; h *= 1099511628211ull; }
    };
    for(std::size_t j = 1; j <= pyr.number_of_levels(); ++j)
      for(double x : pyr.details(j, 0)) add(x);
    for(double x : pyr.coarse_values()[0]) add(x);
    add(double(pyr.number_of_levels()));
    *hash = h;
  }
  return seconds;
}

// the time of the full reconstruction of the last decomposition's pyramid; `same`: whether it
// gives the input's positions back bit for bit
extern "C" double SIDE(reconstruct)(bool* same)
{
  Mesh out;
  CGAL::Real_timer timer;
  timer.start();
  SMR::reconstruct(*pyramid, out);
  const double seconds = timer.time();
  if(same != nullptr)
  {
    *same = out.number_of_vertices() == mesh->number_of_vertices();
    for(auto v : mesh->vertices())
      *same = *same && out.point(v) == mesh->point(v);
  }
  return seconds;
}
