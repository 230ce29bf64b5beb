// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The mesh pyramid of Roy et al., Section 3: downsampling, decomposition, exact reconstruction.

#include <catch2/catch.hpp>

#include <smr_test_utils.h>

#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <cstring>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#endif
#include <vector>

namespace SMR = CGAL::Surface_mesh_multiresolution;
namespace PMP = CGAL::Polygon_mesh_processing;
using smr_test::Mesh;
using smr_test::Polyhedron;
using smr_test::Point_3;
using smr_test::Vector_3;

namespace {

typedef std::array<std::size_t, 3> Triangle;

// oriented faces as vertex ranks, each rotated to start at its smallest rank
template <typename TM>
std::multiset<Triangle> face_set(const TM& tm)
{
  std::map<typename boost::graph_traits<TM>::vertex_descriptor, std::size_t> rank;
  for(auto v : vertices(tm)) rank.emplace(v, rank.size());
  std::multiset<Triangle> out;
  for(auto f : faces(tm))
  {
    std::vector<std::size_t> t;
    for(auto v : vertices_around_face(halfedge(f, tm), tm)) t.push_back(rank[v]);
    REQUIRE(t.size() == 3);
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert({{t[0], t[1], t[2]}});
  }
  return out;
}

template <typename TM>
int euler_characteristic(const TM& tm)
{
  return int(vertices(tm).size()) - int(edges(tm).size()) + int(faces(tm).size());
}

template <typename TM>
std::size_t number_of_borders(const TM& tm)
{
  std::vector<typename boost::graph_traits<TM>::halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(tm, std::back_inserter(cycles));
  return cycles.size();
}

template <typename TM>
void check_exact_round_trip(const TM& tm, const SMR::Pyramid<TM>& pyr)
{
  TM out;
  SMR::reconstruct(pyr, out);
  REQUIRE(CGAL::is_valid_polygon_mesh(out) == CGAL::is_valid_polygon_mesh(tm));   // isolated vertices make both "invalid"
  CHECK(smr_test::positions_in_order(out) == smr_test::positions_in_order(tm));   // bit for bit, same order
  CHECK(face_set(out) == face_set(tm));
}

// every level: a valid mesh with the Euler characteristic and border count of the input,
// its vertices at their input positions, its odd vertices pairwise non-adjacent, and
// collapsing them (o -> e, in any order) gives the next level exactly
template <typename TM>
void check_levels(const TM& tm, const SMR::Pyramid<TM>& pyr)
{
  const auto input = smr_test::positions_in_order(tm);
  const int chi = euler_characteristic(tm);
  const std::size_t borders = number_of_borders(tm);
  std::vector<TM> levels(pyr.number_of_levels() + 1);
  for(std::size_t k = 0; k <= pyr.number_of_levels(); ++k)
  {
    INFO("level " << k);
    SMR::reconstruct(pyr, levels[k], SMR::parameters::level(k));
    const TM& m = levels[k];
    REQUIRE(CGAL::is_valid_polygon_mesh(m));
    CHECK(CGAL::is_triangle_mesh(m));
    CHECK(vertices(m).size() == pyr.number_of_vertices(k));
    CHECK(faces(m).size() == pyr.number_of_faces(k));
    CHECK(euler_characteristic(m) == chi);
    CHECK(number_of_borders(m) == borders);
    const auto pos = smr_test::positions_in_order(m);
    const auto& ids = pyr.vertices(k);
    for(std::size_t r = 0; r < ids.size(); ++r)
      REQUIRE(pos[r] == input[ids[r]]);
  }
  for(std::size_t j = 1; j <= pyr.number_of_levels(); ++j)
  {
    INFO("detail level " << j);
    TM m = levels[j - 1];
    const auto& ids = pyr.vertices(j - 1);
    std::map<std::size_t, typename boost::graph_traits<TM>::vertex_descriptor> vertex_of;
    std::size_t r = 0;
    for(auto v : vertices(m)) vertex_of[ids[r++]] = v;
    const auto odd = pyr.odd_vertices(j);
    REQUIRE(!odd.empty());
    std::set<std::size_t> odd_set(odd.begin(), odd.end());
    for(std::size_t o : odd)
      for(auto w : CGAL::vertices_around_target(vertex_of[o], m))
      {
        std::size_t g = 0;
        for(const auto& p : vertex_of) if(p.second == w) g = p.first;
        CHECK(odd_set.count(g) == 0);   // independent set
      }
    CHECK(pyr.number_of_vertices(j) + odd.size() == pyr.number_of_vertices(j - 1));

    // collapsing the odd vertices of M_{j-1} into their targets, first to last and last to
    // first, gives M_j: the same faces, named by the vertices' ranks in the input
    const auto targets = pyr.collapse_targets(j);
    CHECK(std::set<std::size_t>(targets.begin(), targets.end()).size() == targets.size());   // no shared target
    const TM level_mesh = m;
    for(const bool reversed : {false, true})
    {
      INFO((reversed ? "last collapse first" : "first collapse first"));
      m = level_mesh;                                       // a copy: its handles named again, in order
      vertex_of.clear();
      r = 0;
      for(auto v : vertices(m)) vertex_of[ids[r++]] = v;
      std::map<typename boost::graph_traits<TM>::vertex_descriptor, std::size_t> gid;
      for(const auto& p : vertex_of) gid[p.second] = p.first;
      for(std::size_t i = 0; i < odd.size(); ++i)
      {
        const std::size_t q = reversed ? odd.size() - 1 - i : i;
        const auto o = vertex_of[odd[q]], e = vertex_of[targets[q]];
        typename boost::graph_traits<TM>::halfedge_descriptor h = boost::graph_traits<TM>::null_halfedge();
        for(auto hh : CGAL::halfedges_around_source(o, m)) if(target(hh, m) == e) h = hh;
        REQUIRE(h != boost::graph_traits<TM>::null_halfedge());
        REQUIRE(CGAL::Euler::does_satisfy_link_condition(edge(h, m), m));
        const auto kept = CGAL::Euler::collapse_edge(edge(h, m), m);
        gid[kept] = targets[q];
        vertex_of[targets[q]] = kept;
      }
      auto named_faces = [](const TM& mesh, const std::function<std::size_t(typename boost::graph_traits<TM>::vertex_descriptor)>& name) {
        std::multiset<Triangle> out;
        for(auto f : faces(mesh))
        {
          std::vector<std::size_t> t;
          for(auto v : vertices_around_face(halfedge(f, mesh), mesh)) t.push_back(name(v));
          std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
          out.insert({{t[0], t[1], t[2]}});
        }
        return out;
      };
      std::map<typename boost::graph_traits<TM>::vertex_descriptor, std::size_t> next_gid;
      std::size_t rr = 0;
      for(auto v : vertices(levels[j])) next_gid[v] = pyr.vertices(j)[rr++];
      CHECK(named_faces(m, [&](auto v) { return gid[v]; }) == named_faces(levels[j], [&](auto v) { return next_gid[v]; }));
    }
  }
}

} // namespace

TEMPLATE_TEST_CASE("decompose then reconstruct is exact", "[pyramid][roundtrip]", Mesh, Polyhedron)
{
  SECTION("closed sphere")
  {
    const TestType tm = smr_test::icosphere<TestType>(3);
    const auto pyr = SMR::decompose(tm);
    CHECK(pyr.number_of_levels() > 5);
    CHECK(pyr.number_of_vertices(pyr.number_of_levels()) <= 10);
    check_exact_round_trip(tm, pyr);
    check_levels(tm, pyr);
  }
  SECTION("plane with a border, every scheme")
  {
    const TestType tm = smr_test::planar_grid<TestType>(12, 0.3);
    for(auto s : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE, SMR::Relaxation_scheme::UNIFORM})
    {
      const auto pyr = SMR::decompose(tm, SMR::parameters::relaxation_scheme(s));
      CHECK(pyr.number_of_levels() > 3);
      check_exact_round_trip(tm, pyr);
    }
    check_levels(tm, SMR::decompose(tm));
  }
}

TEST_CASE("exact round trip with colours and several channels", "[pyramid][roundtrip][channels]")
{
  Mesh m = smr_test::icosphere<Mesh>(3);
  auto color = m.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  auto temp = m.add_property_map<Mesh::Vertex_index, double>("v:temperature").first;
  auto uv = m.add_property_map<Mesh::Vertex_index, smr_test::Kernel::Point_2>("v:uv").first;
  for(auto v : vertices(m))
  {
    const Point_3 p = m.point(v);
    color[v] = CGAL::IO::Color(static_cast<unsigned char>(127 + 120 * p.x()), static_cast<unsigned char>(127 + 120 * p.y()),
                               static_cast<unsigned char>(127 + 120 * p.z()), 200);
    temp[v] = 1e-3 * p.x() * p.y() - 273.15;   // values of very different magnitudes
    uv[v] = smr_test::Kernel::Point_2(std::atan2(p.y(), p.x()), 1e6 * p.z());
  }
  const auto pyr = SMR::decompose(m, SMR::parameters::vertex_attribute_maps(std::make_tuple(color, temp, uv)));
  CHECK(pyr.number_of_channels() == 4);
  CHECK(pyr.channel_dimension(1) == 4);
  CHECK(pyr.channel_dimension(2) == 1);
  CHECK(pyr.channel_dimension(3) == 2);
  Mesh out;
  auto oc = out.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  auto ot = out.add_property_map<Mesh::Vertex_index, double>("v:temperature").first;
  auto ouv = out.add_property_map<Mesh::Vertex_index, smr_test::Kernel::Point_2>("v:uv").first;
  SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(oc, ot, ouv)));
  REQUIRE(num_vertices(out) == num_vertices(m));
  CHECK(smr_test::positions_in_order(out) == smr_test::positions_in_order(m));
  for(auto v : vertices(m))
  {
    CHECK(oc[v] == color[v]);
    CHECK(ot[v] == temp[v]);
    CHECK(ouv[v] == uv[v]);
  }
  // the reconstruction kept the property maps of `out` and can be repeated
  SMR::reconstruct(pyr, out, SMR::parameters::level(2).vertex_attribute_maps(std::make_tuple(oc, ot, ouv)));
  CHECK(num_vertices(out) == pyr.number_of_vertices(2));
  CHECK(out.property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").second);
  // into a mesh holding removed, uncollected elements: a valid mesh, the input exactly
  CGAL::Euler::remove_center_vertex(halfedge(*vertices(out).begin(), out), out);
  REQUIRE(out.has_garbage());
  SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(oc, ot, ouv)));
  REQUIRE(CGAL::is_valid_polygon_mesh(out));
  CHECK_FALSE(out.has_garbage());
  CHECK(smr_test::positions_in_order(out) == smr_test::positions_in_order(m));
  CHECK(face_set(out) == face_set(m));
  for(auto v : vertices(m))
    CHECK(oc[v] == color[v]);
  // wrong attribute maps are refused
  REQUIRE_THROWS_AS(SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(oc, ot))), std::invalid_argument);
  REQUIRE_THROWS_AS(SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(ot, oc, ouv))), std::invalid_argument);
  REQUIRE_THROWS_AS(SMR::reconstruct(pyr, out, SMR::parameters::level(pyr.number_of_levels() + 1)), std::invalid_argument);
}

TEST_CASE("exact round trip on real meshes of CGAL's data set", "[pyramid][roundtrip][data]")
{
  // closed, with holes, several components, genus > 0, sharp features, colours (COFF)
  const char* names[] = {"meshes/elephant.off", "meshes/elephant-with-holes.off", "meshes/mech-holes-shark.off",
                         "meshes/blobby_3cc.off", "meshes/fandisk.off", "meshes/knot1.off", "meshes/cow.off",
                         "meshes/cactus.off", "meshes/dino.off", "meshes/head.off"};
  std::size_t tested = 0;
  for(const char* name : names)
  {
    Mesh m;
    if(!smr_test::read_cgal_mesh(name, m))
      continue;
    INFO(name);
    auto color = m.property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color");
    if(color.second)
    {
      const auto pyr = SMR::decompose(m, SMR::parameters::vertex_attribute_maps(std::make_tuple(color.first)));
      Mesh out;
      auto oc = out.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
      SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(oc)));
      CHECK(smr_test::positions_in_order(out) == smr_test::positions_in_order(m));
      CHECK(face_set(out) == face_set(m));
      for(auto v : vertices(m)) CHECK(oc[v] == color.first[v]);
    }
    else
    {
      const auto pyr = SMR::decompose(m);
      CHECK(pyr.number_of_levels() > 3);
      check_exact_round_trip(m, pyr);
    }
    ++tested;
  }
  if(tested == 0)
    WARN("CGAL's data set (libcgal-demo) is not installed: skipped");
  else
    CHECK(tested == 10);
}

TEST_CASE("levels are valid meshes on real data with borders and components", "[pyramid][levels][data]")
{
  for(const char* name : {"meshes/elephant-with-holes.off", "meshes/blobby_3cc.off", "meshes/knot1.off"})
  {
    Mesh m;
    if(!smr_test::read_cgal_mesh(name, m)) { WARN("CGAL data set missing: skipped"); return; }
    INFO(name);
    check_levels(m, SMR::decompose(m));
  }
}

TEST_CASE("the downsampling removes a sixteenth of the vertices or more per level and stops where asked", "[pyramid][downsampling]")
{
  const Mesh m = smr_test::icosphere<Mesh>(4);
  const auto pyr = SMR::decompose(m);
  for(std::size_t k = 0; k + 1 < pyr.number_of_levels() && pyr.number_of_vertices(k) > 500; ++k)
  {
    const double ratio = double(pyr.number_of_vertices(k + 1)) / double(pyr.number_of_vertices(k));
    CHECK(ratio <= 1. - 1. / 16);   // the cheapest collapses, at least a sixteenth of the vertices
    CHECK(ratio > 0.5);   // ... but at most every other vertex
  }
  const auto limited = SMR::decompose(m, SMR::parameters::number_of_levels(3));
  CHECK(limited.number_of_levels() == 3);
  for(std::size_t k = 0; k <= 3; ++k) CHECK(limited.number_of_vertices(k) == pyr.number_of_vertices(k));
  const auto floor = SMR::decompose(m, SMR::parameters::minimum_number_of_vertices(std::size_t(1000)));
  CHECK(floor.number_of_vertices(floor.number_of_levels()) == 1000);
  CHECK(floor.number_of_vertices(floor.number_of_levels() - 1) > 1000);
  check_exact_round_trip(m, floor);
  // the coarsest mesh's arrays, reduced level by level in place, hold its size only
  const std::size_t top = floor.number_of_levels();
  CHECK(floor.coarse_faces().size() == 3 * floor.number_of_faces(top));
  CHECK(floor.coarse_faces().capacity() < 2 * floor.coarse_faces().size());
  CHECK(floor.coarse_values()[0].size() == 3 * floor.number_of_vertices(top));
  CHECK(floor.coarse_values()[0].capacity() < 2 * floor.coarse_values()[0].size());
}

TEST_CASE("tiny and degenerate inputs", "[pyramid][edge]")
{
  SECTION("a tetrahedron cannot be decimated: 0 levels, reconstruct returns it")
  {
    Mesh tet;
    CGAL::make_tetrahedron(Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(0, 1, 0), Point_3(0, 0, 1), tet);
    const auto pyr = SMR::decompose(tet, SMR::parameters::minimum_number_of_vertices(std::size_t(0)));
    CHECK(pyr.number_of_levels() == 0);
    CHECK(pyr.number_of_vertices(0) == 4);
    check_exact_round_trip(tet, pyr);
  }
  SECTION("a single triangle")
  {
    Mesh tri;
    CGAL::make_triangle(Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(0, 1, 0), tri);
    const auto pyr = SMR::decompose(tri, SMR::parameters::minimum_number_of_vertices(std::size_t(0)));
    CHECK(pyr.number_of_levels() == 0);
    check_exact_round_trip(tri, pyr);
  }
  SECTION("an empty mesh")
  {
    Mesh empty, out;
    const auto pyr = SMR::decompose(empty);
    CHECK(pyr.number_of_levels() == 0);
    SMR::reconstruct(pyr, out);
    CHECK(num_vertices(out) == 0);
  }
  SECTION("isolated vertices and a degenerate (zero-area) triangle are kept")
  {
    Mesh m = smr_test::icosphere<Mesh>(2);
    m.add_vertex(Point_3(5, 5, 5));
    // a zero-area triangle: a vertex moved onto the middle of an edge of its link
    const Mesh::Vertex_index v(20);
    const Mesh::Halfedge_index h = next(halfedge(v, m), m);   // an edge of the link of v
    m.point(v) = CGAL::midpoint(m.point(source(h, m)), m.point(target(h, m)));
    const auto pyr = SMR::decompose(m);
    CHECK(pyr.number_of_levels() > 3);
    check_exact_round_trip(m, pyr);
    CHECK(pyr.vertices(pyr.number_of_levels()).back() == num_vertices(m) - 1);   // the isolated vertex reaches the top
  }
}

TEST_CASE("decomposition is deterministic: runs with all threads, with four (parallel selection) and with one are identical", "[pyramid][determinism]")
{
  const Mesh m = smr_test::icosphere<Mesh>(5);   // 10,242 vertices: large enough for the parallel loops
  const auto a = SMR::decompose(m);
  auto c = a;
#ifdef CGAL_LINKED_WITH_TBB
  {
    tbb::task_arena four(4);   // four threads (even on fewer cores): the selection runs in parallel rounds
    four.execute([&] {
      CHECK(SMR::internal::available_threads() == 4);
      c = SMR::decompose(m);
    });
  }
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);   // b: sequential
  CHECK(SMR::internal::available_threads() == 1);   // the process-wide limit, which the arena does not report
#endif
  const auto b = SMR::decompose(m);
  const SMR::Pyramid<Mesh>* runs[] = {&a, &c};
  for(const SMR::Pyramid<Mesh>* x : runs)
  {
    REQUIRE(x->number_of_levels() == b.number_of_levels());
    for(std::size_t k = 0; k < b.number_of_levels(); ++k)
    {
      CHECK(x->levels()[k].vertices == b.levels()[k].vertices);
      CHECK(x->levels()[k].odd_rows == b.levels()[k].odd_rows);
      CHECK(x->levels()[k].collapse_targets == b.levels()[k].collapse_targets);
      CHECK(x->weight_positions() == b.weight_positions());
      CHECK(x->levels()[k].details[0] == b.levels()[k].details[0]);
      CHECK(x->levels()[k].removed_faces == b.levels()[k].removed_faces);
      CHECK(x->levels()[k].corrections[0] == b.levels()[k].corrections[0]);
    }
    CHECK(x->coarse_faces() == b.coarse_faces());
  }
}

TEST_CASE("levels that reuse the blocks of the levels before them build the same pyramid", "[pyramid][memory]")
{
  // blocks from 4 KiB are kept and reused (32 MiB by default: a mesh of about a million vertices)
  Mesh m = smr_test::icosphere<Mesh>(4);
  auto scalar = m.add_property_map<Mesh::Vertex_index, double>("v:scalar", 0.).first;
  for(auto v : vertices(m))
    scalar[v] = std::sin(3. * m.point(v).x()) + m.point(v).z();
  const auto expected = SMR::decompose(m, SMR::parameters::vertex_attribute_maps(scalar));
  SMR::internal::Block_pool& pool = SMR::internal::Block_pool::instance();
  pool.set_sizes(4096, 4096);
  const std::size_t reuses = pool.reuses();
  const auto reused = SMR::decompose(m, SMR::parameters::vertex_attribute_maps(scalar));
  const std::size_t left = pool.kept_bytes(), taken = pool.reuses() - reuses;
  pool.set_sizes(SMR::internal::Block_pool::default_kept_bytes, SMR::internal::Block_pool::default_reused_bytes);
  CHECK(taken > 4 * expected.number_of_levels());    // several arrays per level took a block of the level before
  CHECK(left == 0);                                  // nothing is held once decompose() returns
  REQUIRE(reused.number_of_levels() == expected.number_of_levels());
  REQUIRE(expected.number_of_levels() > 5);
  for(std::size_t k = 0; k < expected.number_of_levels(); ++k)
  {
    const auto& a = reused.levels()[k];
    const auto& b = expected.levels()[k];
    CHECK(a.odd_rows == b.odd_rows);
    CHECK(a.collapse_targets == b.collapse_targets);
    CHECK(a.details == b.details);
    CHECK(a.corrections == b.corrections);
    CHECK(a.removed_faces == b.removed_faces);
    CHECK(a.renamed_corners == b.renamed_corners);
  }
  CHECK(reused.coarse_faces() == expected.coarse_faces());
  CHECK(reused.coarse_values() == expected.coarse_values());
  check_exact_round_trip(m, reused);
}

namespace {

// a copy of m with vertex v numbered number[v], the faces in the same order with the same
// first corners
Mesh renumbered(const Mesh& m, const std::vector<std::size_t>& number)
{
  std::vector<Mesh::Vertex_index> old_of(num_vertices(m));
  for(auto v : vertices(m))
    old_of[number[v]] = v;
  Mesh r;
  for(auto v : old_of)
    r.add_vertex(m.point(v));
  auto st = r.add_property_map<Mesh::Vertex_index, double>("v:scalar").first;
  auto sm = m.property_map<Mesh::Vertex_index, double>("v:scalar").first;
  for(auto v : vertices(m))
    st[Mesh::Vertex_index(number[v])] = sm[v];
  for(auto f : faces(m))
  {
    std::vector<Mesh::Vertex_index> c;
    for(auto v : vertices_around_face(halfedge(f, m), m))
      c.push_back(Mesh::Vertex_index(number[v]));
    const auto g = r.add_face(c);
    REQUIRE(g != Mesh::null_face());
    REQUIRE(target(halfedge(g, r), r) == Mesh::Vertex_index(number[target(halfedge(f, m), m)]));
  }
  return r;
}

// b is a's pyramid with every input vertex v named number[v]: the same levels, details and
// corrections bit for bit, the same collapses and face records
void check_same_pyramid_renumbered(const SMR::Pyramid<Mesh>& a, const SMR::Pyramid<Mesh>& b, const std::vector<std::size_t>& number)
{
  REQUIRE(a.number_of_levels() == b.number_of_levels());
  REQUIRE(a.number_of_levels() > 3);
  auto rows_of_b = [&](std::size_t k) {
    std::vector<std::size_t> r(number.size(), std::size_t(-1));
    for(std::size_t i = 0; i < b.vertices(k).size(); ++i)
      r[b.vertices(k)[i]] = i;
    return r;
  };
  for(std::size_t k = 0; k <= a.number_of_levels(); ++k)
  {
    REQUIRE(a.vertices(k).size() == b.vertices(k).size());
    const std::vector<std::size_t> row_b = rows_of_b(k);
    std::vector<std::size_t> to_b(a.vertices(k).size());   // row of a -> row of b
    for(std::size_t i = 0; i < to_b.size(); ++i)
    {
      to_b[i] = row_b[number[a.vertices(k)[i]]];
      REQUIRE(to_b[i] != std::size_t(-1));
    }
    if(k == a.number_of_levels())
    {
      for(std::size_t c = 0; c < a.number_of_channels(); ++c)
      {
        const std::size_t d = a.channel_dimension(c);
        for(std::size_t i = 0; i < to_b.size(); ++i)
          CHECK(std::memcmp(&a.coarse_values()[c][d * i], &b.coarse_values()[c][d * to_b[i]], 8 * d) == 0);
      }
      std::vector<std::size_t> faces_a;
      for(auto v : a.coarse_faces()) faces_a.push_back(to_b[v]);
      CHECK(faces_a == std::vector<std::size_t>(b.coarse_faces().begin(), b.coarse_faces().end()));
      break;
    }
    const auto& la = a.levels()[k];
    const auto& lb = b.levels()[k];
    for(std::size_t c = 0; c < a.number_of_channels(); ++c)
    {
      const std::size_t d = a.channel_dimension(c);
      std::size_t differing = 0;
      for(std::size_t i = 0; i < to_b.size(); ++i)
        differing += std::memcmp(&la.details[c][d * i], &lb.details[c][d * to_b[i]], 8 * d) != 0;
      CHECK(differing == 0);
      // (position, bits of the correction): a zero correction's sign is meaningful (-0.0)
      auto bits = [](double x) { std::uint64_t u; std::memcpy(&u, &x, sizeof u); return u; };
      std::vector<std::pair<std::size_t, std::uint64_t> > corrections_a, corrections_b;
      for(const auto& x : la.corrections[c])
        corrections_a.emplace_back(d * to_b[x.first / d] + x.first % d, bits(x.second));
      for(const auto& x : lb.corrections[c])
        corrections_b.emplace_back(x.first, bits(x.second));
      std::sort(corrections_a.begin(), corrections_a.end());
      CHECK(std::is_sorted(lb.corrections[c].begin(), lb.corrections[c].end()));
      CHECK(corrections_a == corrections_b);
    }
    std::map<std::size_t, std::size_t> target_a, target_b;   // odd vertex -> target, b's input numbers
    for(std::size_t q = 0; q < la.odd_rows.size(); ++q)
      target_a[number[la.vertices[la.odd_rows[q]]]] = number[la.vertices[la.collapse_targets[q]]];
    for(std::size_t q = 0; q < lb.odd_rows.size(); ++q)
      target_b[lb.vertices[lb.odd_rows[q]]] = lb.vertices[lb.collapse_targets[q]];
    CHECK(target_a == target_b);
    CHECK(la.removed_face_positions == lb.removed_face_positions);
    std::vector<std::size_t> removed_a;
    for(auto v : la.removed_faces) removed_a.push_back(to_b[v]);
    CHECK(removed_a == std::vector<std::size_t>(lb.removed_faces.begin(), lb.removed_faces.end()));
    std::map<std::size_t, std::size_t> renamed_a, renamed_b;   // corner -> odd vertex, b's rows
    for(std::size_t q = 0; q < la.renamed_corners.size(); ++q)
      renamed_a[la.renamed_corners[q]] = to_b[la.renamed_vertices[q]];
    for(std::size_t q = 0; q < lb.renamed_corners.size(); ++q)
      renamed_b[lb.renamed_corners[q]] = lb.renamed_vertices[q];
    CHECK(renamed_a == renamed_b);
  }
}

} // namespace

// Nothing decompose() computes depends on how the input numbers its vertices (rings are
// listed in face order, candidates are named by halfedge, ties never broken by vertex number):
// renumbering the input renames the pyramid's vertices and changes no bit of anything else
// (design notes: what a locality reordering of the vertices may rely on)
TEST_CASE("the pyramid does not depend on how the input numbers its vertices", "[pyramid][determinism]")
{
  Mesh grid = smr_test::planar_grid<Mesh>(30, 0.3);   // borders
  CGAL::Random rng(11);
  for(auto v : vertices(grid))
    grid.point(v) = grid.point(v) + Vector_3(0, 0, rng.get_double(-.05, .05));
  Mesh meshes[] = {smr_test::icosphere<Mesh>(3), grid};   // Loop subdivision numbers new vertices by edge
  for(Mesh& m : meshes)
  {
    auto scalar = m.add_property_map<Mesh::Vertex_index, double>("v:scalar").first;
    for(auto v : vertices(m))   // a channel of dimension 1 with corrections
      scalar[v] = 1e-3 * m.point(v).x() * m.point(v).y() - 273.15 + 1e5 * m.point(v).z();
    std::vector<std::size_t> shuffled(num_vertices(m)), reversed(num_vertices(m));
    std::iota(shuffled.begin(), shuffled.end(), std::size_t(0));
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(5));
    for(std::size_t i = 0; i < reversed.size(); ++i)
      reversed[i] = reversed.size() - 1 - i;
    for(const SMR::Relaxation_scheme scheme : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM,
                                               SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE})
    {
      const auto a = SMR::decompose(m, SMR::parameters::relaxation_scheme(scheme).vertex_attribute_maps(std::make_tuple(scalar)));
      std::size_t corrections = 0;
      for(const auto& l : a.levels())
        corrections += l.corrections[0].size() + l.corrections[1].size();
      CHECK(corrections > 0);
      for(const auto* number : {&shuffled, &reversed})
      {
        const Mesh r = renumbered(m, *number);
        auto rs = r.property_map<Mesh::Vertex_index, double>("v:scalar").first;
        const auto b = SMR::decompose(r, SMR::parameters::relaxation_scheme(scheme).vertex_attribute_maps(std::make_tuple(rs)));
        check_same_pyramid_renumbered(a, b, *number);
        check_exact_round_trip(r, b);
      }
    }
  }
}

// A pyramid in a spatial order of its own (Memory_order::SPATIAL, as AUTOMATIC gives a large
// mesh whose numbering is scattered) gives the user what a pyramid in the input's order gives:
// level 0 is the input exactly (its vertex order, positions, channel values and face order),
// every level lists its vertices in increasing input number at their input positions, files
// and adaptive reconstructions keep that, and the pyramid is the same on 1 and 4 threads.
TEST_CASE("a pyramid in its own memory order gives the input's outputs exactly", "[pyramid][order]")
{
  typedef SMR::internal::Index Index;
  // the order test: a grid as generated is in order, the same grid renumbered at random is not
  {
    const Mesh big = smr_test::planar_grid<Mesh>(100, 0.3);
    std::vector<std::size_t> shuffled(num_vertices(big));
    std::iota(shuffled.begin(), shuffled.end(), std::size_t(0));
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(3));
    auto triangles = [](const Mesh& m) {
      std::vector<Index> t;
      for(auto f : faces(m))
        for(auto v : vertices_around_face(halfedge(f, m), m))
          t.push_back(Index(v));
      return t;
    };
    std::vector<Index> t = triangles(big), u = t;
    for(Index& v : u)
      v = Index(shuffled[v]);
    CHECK(!SMR::internal::numbering_is_scattered(num_vertices(big), t));
    CHECK(SMR::internal::numbering_is_scattered(num_vertices(big), u));
    // the spatial order is a pair of permutations; coordinates whose extent overflows give none
    std::vector<double> xyz;
    for(auto v : vertices(big))
      for(int c = 0; c < 3; ++c)
        xyz.push_back(big.point(v)[c]);
    std::vector<Index> vo, fo;
    SMR::internal::spatial_order(xyz, u, vo, fo);
    CHECK(SMR::internal::is_permutation_of_first(vo));
    CHECK(SMR::internal::is_permutation_of_first(fo));
    REQUIRE(vo.size() == num_vertices(big));
    REQUIRE(3 * fo.size() == u.size());
    xyz[0] = -1.7e308;
    xyz[3] = 1.7e308;
    SMR::internal::spatial_order(xyz, u, vo, fo);
    CHECK((vo.empty() && fo.empty()));
  }
  Mesh grid = smr_test::planar_grid<Mesh>(30, 0.3);   // borders
  CGAL::Random rng(13);
  for(auto v : vertices(grid))
    grid.point(v) = grid.point(v) + Vector_3(0, 0, rng.get_double(-.05, .05));
  Mesh meshes[] = {smr_test::icosphere<Mesh>(3), grid};
  for(Mesh& m0 : meshes)
  {
    auto scalar0 = m0.add_property_map<Mesh::Vertex_index, double>("v:scalar").first;
    for(auto v : vertices(m0))
      scalar0[v] = 1e-3 * m0.point(v).x() * m0.point(v).y() - 273.15 + 1e5 * m0.point(v).z();
    std::vector<std::size_t> shuffled(num_vertices(m0));
    std::iota(shuffled.begin(), shuffled.end(), std::size_t(0));
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(7));
    const Mesh m = renumbered(m0, shuffled);
    auto scalar = m.property_map<Mesh::Vertex_index, double>("v:scalar").first;
    const auto np = SMR::parameters::memory_order(SMR::Memory_order::SPATIAL).vertex_attribute_maps(std::make_tuple(scalar));
    const SMR::Pyramid<Mesh> pyr = SMR::decompose(m, np);
    REQUIRE(pyr.number_of_levels() > 3);
    const auto& v0 = pyr.vertices(0);
    CHECK(!std::is_sorted(v0.begin(), v0.end()));            // rows in the pyramid's own order
    CHECK(SMR::internal::is_permutation_of_first(std::vector<Index>(v0.begin(), v0.end())));
    // level 0: the input, its vertices, values and faces in the input's order
    auto faces_in_order = [](const Mesh& x) {
      std::vector<std::size_t> f;
      for(auto h : faces(x))
        for(auto v : vertices_around_face(halfedge(h, x), x))
          f.push_back(std::size_t(v));
      return f;
    };
    {
      Mesh out;
      auto out_scalar = out.add_property_map<Mesh::Vertex_index, double>("v:scalar").first;
      SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(out_scalar)));
      CHECK(smr_test::positions_in_order(out) == smr_test::positions_in_order(m));
      CHECK(faces_in_order(out) == faces_in_order(m));
      bool same_values = true;
      for(auto v : vertices(m))
        same_values = same_values && out_scalar[v] == scalar[v];
      CHECK(same_values);
    }
    // every level: vertices in increasing input number at their input positions; writing the
    // values again on the same connectivity gives the same mesh
    const auto input = smr_test::positions_in_order(m);
    for(std::size_t k : {std::size_t(1), std::size_t(3), pyr.number_of_levels()})
    {
      INFO("level " << k);
      Mesh lk;
      SMR::reconstruct(pyr, lk, SMR::parameters::level(k));
      std::vector<Index> ids(pyr.vertices(k).begin(), pyr.vertices(k).end());
      std::sort(ids.begin(), ids.end());
      const auto pos = smr_test::positions_in_order(lk);
      REQUIRE(pos.size() == ids.size());
      bool at_input = true;
      for(std::size_t r = 0; r < ids.size(); ++r)
        at_input = at_input && pos[r] == input[ids[r]];
      CHECK(at_input);
      CHECK(CGAL::is_valid_polygon_mesh(lk));
      Mesh again = lk;
      for(auto v : vertices(again))
        again.point(v) = Point_3(0, 0, 0);
      SMR::reconstruct(pyr, again, SMR::parameters::level(k).keep_connectivity(true));
      CHECK(smr_test::positions_in_order(again) == pos);
    }
    // the adaptive reconstruction that keeps every vertex is the input, in its order
    {
      Mesh all;
      SMR::reconstruct_adaptively(pyr, all, 0.);
      CHECK(smr_test::positions_in_order(all) == smr_test::positions_in_order(m));
      CHECK(faces_in_order(all) == faces_in_order(m));
    }
    // a file keeps the order: the same rows, the input back exactly
    {
      std::stringstream file;
      REQUIRE(SMR::IO::write_pyramid(file, pyr));
      SMR::Pyramid<Mesh> back;
      std::string error;
      REQUIRE(SMR::IO::read_pyramid(file, back, error));
      for(std::size_t k = 0; k <= pyr.number_of_levels(); ++k)
        CHECK(back.vertices(k) == pyr.vertices(k));
      Mesh out;
      SMR::reconstruct(back, out);
      CHECK(smr_test::positions_in_order(out) == smr_test::positions_in_order(m));
      CHECK(faces_in_order(out) == faces_in_order(m));
    }
#ifdef CGAL_LINKED_WITH_TBB
    // the same pyramid on 1 and 4 threads
    {
      tbb::task_arena four(4);
      SMR::Pyramid<Mesh> p4;
      four.execute([&] { p4 = SMR::decompose(m, np); });
      REQUIRE(p4.number_of_levels() == pyr.number_of_levels());
      bool same = p4.vertices(0) == pyr.vertices(0);
      for(std::size_t j = 1; j <= pyr.number_of_levels(); ++j)
        for(std::size_t c = 0; c < 2; ++c)
          same = same && std::memcmp(p4.details(j, c).data(), pyr.details(j, c).data(), 8 * pyr.details(j, c).size()) == 0;
      CHECK(same);
    }
#endif
    // AUTOMATIC keeps a small mesh in the input's order
    const SMR::Pyramid<Mesh> automatic = SMR::decompose(m);
    CHECK(std::is_sorted(automatic.vertices(0).begin(), automatic.vertices(0).end()));
    // denoising works in M_0's rows and analyses its result again by input number: the result
    // of the input's order but for rounding (the sums run in another order; on these nearly
    // noiseless meshes the thresholds sit among the details, so a few of them change), and the
    // pyramid describes it exactly
    {
      SMR::Pyramid<Mesh> spatial = pyr, in_input_order = automatic;
      SMR::denoise(spatial);
      SMR::denoise(in_input_order);
      Mesh ds, di, again;
      SMR::reconstruct(spatial, ds);
      SMR::reconstruct(in_input_order, di);
      const auto ps = smr_test::positions_in_order(ds), pi = smr_test::positions_in_order(di);
      REQUIRE(ps.size() == pi.size());
      double largest = 0., moved = 0.;
      for(std::size_t i = 0; i < ps.size(); ++i)
      {
        largest = (std::max)(largest, std::sqrt(CGAL::squared_distance(ps[i], pi[i])));
        moved = (std::max)(moved, std::sqrt(CGAL::squared_distance(pi[i], input[i])));
      }
      INFO("largest difference " << largest << ", largest denoising move " << moved);
      CHECK(moved > 0.);
      CHECK(largest < 0.5 * moved);   // (values analysed in the wrong order move vertices far more)
      SMR::reconstruct(spatial, again, SMR::parameters::level(0));
      CHECK(smr_test::positions_in_order(again) == ps);
    }
  }
}

TEST_CASE("other SMS cost policies drive the downsampling", "[pyramid][cost]")
{
  const Mesh m = smr_test::icosphere<Mesh>(3);
  const auto el = SMR::decompose(m, CGAL::parameters::get_cost(CGAL::Surface_mesh_simplification::Edge_length_cost<Mesh>()));
  CHECK(el.number_of_levels() > 3);
  check_exact_round_trip(m, el);
  const auto lt = SMR::decompose(m, SMR::parameters::get_cost(CGAL::Surface_mesh_simplification::LindstromTurk_cost<Mesh>()));
  check_exact_round_trip(m, lt);
}

TEST_CASE("the visitor sees every level", "[pyramid][visitor]")
{
  struct Counting_visitor : SMR::Decomposition_visitor_base
  {
    std::vector<std::size_t>* started; std::size_t* removed; std::size_t* finished;
    void on_level_started(std::size_t, std::size_t n) { started->push_back(n); }
    void on_level_finished(std::size_t, std::size_t r) { *removed += r; }
    void on_finished(std::size_t k) { *finished = k; }
  };
  std::vector<std::size_t> started; std::size_t removed = 0, finished = 0;
  const Mesh m = smr_test::icosphere<Mesh>(2);
  const auto pyr = SMR::decompose(m, SMR::parameters::visitor(Counting_visitor{{}, &started, &removed, &finished}));
  CHECK(finished == pyr.number_of_levels());
  CHECK(removed == num_vertices(m) - pyr.number_of_vertices(pyr.number_of_levels()));
  REQUIRE(started.size() >= pyr.number_of_levels());
  for(std::size_t k = 0; k < pyr.number_of_levels(); ++k) CHECK(started[k] == pyr.number_of_vertices(k));
}

TEST_CASE("a visitor cancels the decomposition: the levels built so far form an exact pyramid", "[pyramid][visitor]")
{
  struct Cancelling_visitor : SMR::Decomposition_visitor_base
  {
    std::size_t stop_at = 0;
    bool on_level_started(std::size_t k, std::size_t) { return k < stop_at; }
  };
  const Mesh m = smr_test::icosphere<Mesh>(3);
  const auto full = SMR::decompose(m);
  REQUIRE(full.number_of_levels() > 3);
  const auto two = SMR::decompose(m, SMR::parameters::visitor(Cancelling_visitor{{}, 2}));
  REQUIRE(two.number_of_levels() == 2);
  for(std::size_t k = 0; k <= 2; ++k)          // the same levels as the full decomposition
    CHECK(two.vertices(k) == full.vertices(k));
  check_exact_round_trip(m, two);
  const auto none = SMR::decompose(m, SMR::parameters::visitor(Cancelling_visitor{{}, 0}));
  CHECK(none.number_of_levels() == 0);
  check_exact_round_trip(m, none);
}

TEST_CASE("decompose rejects bad input", "[pyramid][input]")
{
  Mesh quad;
  CGAL::make_quad(Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(1, 1, 0), Point_3(0, 1, 0), quad);
  REQUIRE_THROWS_WITH(SMR::decompose(quad), Catch::Contains("not a triangle"));
  Mesh m = smr_test::icosphere<Mesh>(1);
  m.point(Mesh::Vertex_index(3)) = Point_3(0, 0, std::numeric_limits<double>::quiet_NaN());
  REQUIRE_THROWS_WITH(SMR::decompose(m), Catch::Contains("vertex 3"));
  const Mesh s = smr_test::icosphere<Mesh>(1);
  const auto pyr = SMR::decompose(s);
  REQUIRE_THROWS_AS(pyr.details(0, 0), std::invalid_argument);
  REQUIRE_THROWS_AS(pyr.details(1, 1), std::invalid_argument);
  REQUIRE_THROWS_AS(pyr.number_of_vertices(pyr.number_of_levels() + 1), std::invalid_argument);
}

TEST_CASE("persistence: write, read, reconstruct is exact; corrupt files are refused", "[pyramid][io]")
{
  Mesh m = smr_test::planar_grid<Mesh>(12, 0.3);
  auto color = m.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  for(auto v : vertices(m)) color[v] = CGAL::IO::Color(static_cast<unsigned char>(v.idx() % 256), 7, 99);
  const auto pyr = SMR::decompose(m, SMR::parameters::vertex_attribute_maps(std::make_tuple(color)));
  std::stringstream ss(std::ios::in | std::ios::out | std::ios::binary);
  REQUIRE(SMR::IO::write_pyramid(ss, pyr));
  const std::string bytes = ss.str();

  SMR::Pyramid<Mesh> back;
  std::istringstream in(bytes, std::ios::binary);
  REQUIRE(SMR::IO::read_pyramid(in, back));
  CHECK(back.number_of_levels() == pyr.number_of_levels());
  Mesh out;
  auto oc = out.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  SMR::reconstruct(back, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(oc)));
  CHECK(smr_test::positions_in_order(out) == smr_test::positions_in_order(m));
  CHECK(face_set(out) == face_set(m));
  for(auto v : vertices(m)) CHECK(oc[v] == color[v]);

  // every truncation and a flipped bit anywhere are refused, leaving the target untouched
  const SMR::Pyramid<Mesh> untouched = SMR::decompose(smr_test::icosphere<Mesh>(1));
  for(std::size_t cut : {std::size_t(0), std::size_t(5), std::size_t(20), bytes.size() / 2, bytes.size() - 1})
  {
    SMR::Pyramid<Mesh> p = untouched;
    std::istringstream t(bytes.substr(0, cut), std::ios::binary);
    CHECK_FALSE(SMR::IO::read_pyramid(t, p));
    CHECK(p.number_of_vertices(0) == untouched.number_of_vertices(0));
  }
  CGAL::Random rng(5);
  for(int trial = 0; trial < 50; ++trial)
  {
    std::string corrupt = bytes;
    const std::size_t at = std::size_t(rng.get_int(0, int(corrupt.size())));
    corrupt[at] = static_cast<char>(corrupt[at] ^ (1 << rng.get_int(0, 8)));
    SMR::Pyramid<Mesh> p = untouched;
    std::istringstream t(corrupt, std::ios::binary);
    CHECK_FALSE(SMR::IO::read_pyramid(t, p));
    CHECK(p.number_of_levels() == untouched.number_of_levels());
  }
  std::istringstream garbage(std::string(1000, 'x'), std::ios::binary);
  SMR::Pyramid<Mesh> p;
  CHECK_FALSE(SMR::IO::read_pyramid(garbage, p));
}

TEST_CASE("pyramid files: what analysis gives is derived at load, edited details are kept, sizes are those of the format", "[pyramid][io]")
{
  Mesh m = smr_test::icosphere<Mesh>(4);
  CGAL::Random rng(11);
  for(auto v : vertices(m))
    m.point(v) = m.point(v) + 0.01 * Vector_3(rng.get_double(-1, 1), rng.get_double(-1, 1), rng.get_double(-1, 1));
  auto color = m.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  for(auto v : vertices(m)) color[v] = CGAL::IO::Color(static_cast<unsigned char>(v.idx() % 256), 7, 99);
  const auto maps = SMR::parameters::vertex_attribute_maps(std::make_tuple(color));
  const SMR::Pyramid<Mesh> pyr = SMR::decompose(m, maps);
  const std::size_t n = num_vertices(m), nf = num_faces(m);
  auto bytes_of = [](const SMR::Pyramid<Mesh>& p) {
    std::stringstream ss(std::ios::in | std::ios::out | std::ios::binary);
    REQUIRE(SMR::IO::write_pyramid(ss, p));
    return ss.str();
  };
  // the array sizes of format 3: positions, the faces of M_0, the collapses (fewer than n),
  // the colour's values, and per channel or level a few words of header
  const std::size_t derived_size = 24 * n + 12 * nf + 8 * n + 8 * pyr.channel_dimension(1) * n + 64 * (pyr.number_of_levels() + 4);
  // everything read back bit for bit; the reconstructions agree bit for bit
  auto round_trip = [&](const SMR::Pyramid<Mesh>& p, std::size_t at_most) {
    const std::string bytes = bytes_of(p);
    CHECK(bytes.size() <= at_most);
    SMR::Pyramid<Mesh> back;
    std::istringstream in(bytes, std::ios::binary);
    std::string error;
    REQUIRE(SMR::IO::read_pyramid(in, back, error));
    REQUIRE(back.number_of_levels() == p.number_of_levels());
    for(std::size_t j = 1; j <= p.number_of_levels(); ++j)
      for(std::size_t c = 0; c < 2; ++c)
      {
        CHECK(std::memcmp(back.details(j, c).data(), p.details(j, c).data(), 8 * p.details(j, c).size()) == 0);
        CHECK(back.levels()[j - 1].corrections[c] == p.levels()[j - 1].corrections[c]);
        CHECK(back.levels()[j - 1].renamed_corners == p.levels()[j - 1].renamed_corners);
        CHECK(back.levels()[j - 1].removed_faces == p.levels()[j - 1].removed_faces);
      }
    CHECK(back.coarse_faces() == p.coarse_faces());
    CHECK(back.coarse_values() == p.coarse_values());
    Mesh a, b;
    SMR::reconstruct(p, a);
    SMR::reconstruct(back, b);
    CHECK(smr_test::positions_in_order(a) == smr_test::positions_in_order(b));
    CHECK(bytes_of(back) == bytes);
    // the writer skips the analysis of channels whose state is known (decomposed, read,
    // denoised): forgetting the states (any non-const access to the details) makes it analyse
    // every channel again, and the file is the same
    SMR::Pyramid<Mesh> forgotten = p;
    for(std::size_t c = 0; c < p.number_of_channels(); ++c)
      forgotten.details(1, c);
    for(SMR::internal::Analysis_state state : forgotten.analysis_states())
      CHECK(state == SMR::internal::Analysis_state::UNKNOWN);
    CHECK(bytes_of(forgotten) == bytes);
  };
  using State = SMR::internal::Analysis_state;
  REQUIRE(pyr.analysis_states().size() == 2);
  CHECK(pyr.analysis_states()[0] == State::OF_WEIGHT_POSITIONS);
  CHECK(pyr.analysis_states()[1] == State::OF_VALUES);
  round_trip(pyr, derived_size);
  // a denoised geometry is stored by its values (it is what its analysis gives)
  SMR::Pyramid<Mesh> denoised = pyr;
  SMR::denoise(denoised, SMR::parameters::number_of_iterations(3u));
  CHECK(denoised.analysis_states()[0] == State::OF_VALUES);
  round_trip(denoised, derived_size + 24 * n);
  // edited geometry details are stored as they are: larger, exact
  SMR::Pyramid<Mesh> enhanced = pyr;
  SMR::scale_details(enhanced, 1, 2., SMR::parameters::channel(std::size_t(0)));
  CHECK(enhanced.analysis_states()[0] == State::UNKNOWN);
  CHECK(enhanced.analysis_states()[1] == State::OF_VALUES);
  std::size_t details = 0;
  for(std::size_t j = 1; j <= pyr.number_of_levels(); ++j)
    details += 8 * pyr.details(j, 0).size() + 12 * pyr.levels()[j - 1].corrections[0].size() + 16;
  round_trip(enhanced, derived_size + details + 8 * pyr.coarse_values()[0].size());
  CHECK(bytes_of(enhanced).size() > derived_size);
}

TEST_CASE("stored weights are the relaxation operators of the levels and change no reconstruction", "[pyramid][weights]")
{
  const Mesh m = smr_test::planar_grid<Mesh>(14, 0.3);   // borders and interior vertices
  for(SMR::Relaxation_scheme scheme : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM,
                                       SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE})
  {
    SMR::Pyramid<Mesh> pyr = SMR::decompose(m, SMR::parameters::relaxation_scheme(scheme));
    REQUIRE(pyr.number_of_levels() > 3);
    std::vector<Mesh> before(pyr.number_of_levels() + 1);
    for(std::size_t k = 0; k <= pyr.number_of_levels(); ++k)
      SMR::reconstruct(pyr, before[k], SMR::parameters::level(k));
    std::stringstream file_before(std::ios::in | std::ios::out | std::ios::binary);
    REQUIRE(SMR::IO::write_pyramid(file_before, pyr));
    // of an enhanced pyramid, whose reconstruction is no input position: the rows computed
    // as they are applied (one channel) give the stored weights' sums, bit for bit
    {
      SMR::Pyramid<Mesh> enhanced = pyr;
      SMR::enhance(enhanced, 1, 2, 1.5);
      Mesh as_applied, stored;
      SMR::reconstruct(enhanced, as_applied);
      SMR::store_weights(enhanced);
      SMR::reconstruct(enhanced, stored);
      CHECK(smr_test::positions_in_order(as_applied) == smr_test::positions_in_order(stored));
      CHECK(smr_test::positions_in_order(as_applied) != smr_test::positions_in_order(m));
    }

    SMR::store_weights(pyr);
    CHECK(SMR::internal::check_pyramid(pyr).empty());
    for(std::size_t k = 0; k < pyr.number_of_levels(); ++k)
    {
      // lambda^k is the relaxation operator of M_k (Eq. 2, Eq. 1 or the uniform Laplacian)
      const auto R = SMR::relaxation_operator(before[k], SMR::parameters::relaxation_scheme(scheme));
      const auto& w = pyr.levels()[k].weights;
      // (the pyramid's arrays and the operator's have different allocators: compared entry by entry)
      CHECK(std::equal(w.offsets.begin(), w.offsets.end(), R.row_offsets().begin(), R.row_offsets().end()));
      CHECK(std::equal(w.columns.begin(), w.columns.end(), R.column_indices().begin(), R.column_indices().end()));
      CHECK(std::equal(w.values.begin(), w.values.end(), R.weights().begin(), R.weights().end()));
    }
    for(std::size_t k = 0; k <= pyr.number_of_levels(); ++k)
    {
      Mesh after;
      SMR::reconstruct(pyr, after, SMR::parameters::level(k));
      CHECK(smr_test::positions_in_order(after) == smr_test::positions_in_order(before[k]));
    }
    std::stringstream file_after(std::ios::in | std::ios::out | std::ios::binary);
    REQUIRE(SMR::IO::write_pyramid(file_after, pyr));
    CHECK(file_after.str() == file_before.str());   // not saved
    SMR::store_weights(pyr, false);
    CHECK(pyr.levels()[0].weights.values.empty());
    Mesh again;
    SMR::reconstruct(pyr, again);
    CHECK(smr_test::positions_in_order(again) == smr_test::positions_in_order(m));
  }
}

// The decomposition applies every row of a 1-ring scheme to the values themselves, beside the
// selection (predict_with_rows_once()): an odd row reads only its neighbours, which are even.
// Eq. 5 as analyse_level() computes it, odd rows applied to the state where the odd vertices
// hold their targets' values, must give the same details and corrections bit for bit.
// The rows of a level whose corners are paired through the twins are computed in one pass
// where the vertex has no border halfedge (closed_curvature_ring_row()), in the general one
// elsewhere: the mesh with holes has both, and obtuse corners whose rows fall back.
TEST_CASE("every level's details are those of Eq. 5 with the odd rows applied to the state of the collapses", "[pyramid][weights]")
{
  std::vector<Mesh> meshes(1, smr_test::planar_grid<Mesh>(24, 0.3));   // borders and interior vertices
  Mesh holes;
  if(smr_test::read_cgal_mesh("meshes/elephant-with-holes.off", holes))
    meshes.push_back(holes);
  else
    WARN("CGAL's data set (libcgal-demo) is not installed: the grid only");
  for(const Mesh& m0 : meshes)
  for(SMR::Relaxation_scheme scheme : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM})
  {
    Mesh m = m0;
    auto temp = m.add_property_map<Mesh::Vertex_index, double>("v:temperature").first;
    for(auto v : vertices(m))
      temp[v] = std::sin(7. * m.point(v).x()) * 1e3 - 273.15 * m.point(v).y();
    INFO("mesh of " << num_vertices(m) << " vertices, scheme " << int(scheme));
    SMR::Pyramid<Mesh> pyr = SMR::decompose(m, SMR::parameters::relaxation_scheme(scheme).vertex_attribute_maps(std::make_tuple(temp)));
    REQUIRE(pyr.number_of_levels() > 3);
    SMR::store_weights(pyr);
    const auto input = smr_test::positions_in_order(m);
    for(std::size_t k = 0; k < pyr.number_of_levels(); ++k)
    {
      INFO("level " << k);
      const auto& lev = pyr.levels()[k];
      const auto& ids = pyr.vertices(k);
      std::vector<double> xyz, t;
      for(std::size_t id : ids)
      {
        xyz.insert(xyz.end(), {input[id].x(), input[id].y(), input[id].z()});
        t.push_back(temp[Mesh::Vertex_index(static_cast<Mesh::size_type>(id))]);
      }
      std::size_t c = 0;
      for(const std::vector<double>* f : {&xyz, &t})
      {
        std::vector<double> details;
        SMR::internal::Corrections corrections;
        SMR::internal::analyse_level(lev, lev.weights, pyr.channel_dimension(c), *f, details, corrections);
        REQUIRE(details.size() == lev.details[c].size());
        CHECK(std::memcmp(details.data(), lev.details[c].data(), details.size() * sizeof(double)) == 0);   // bit for bit
        CHECK(corrections == lev.corrections[c]);
        ++c;
      }
    }
  }
}

TEST_CASE("the cost adapter gives the Garland-Heckbert cost of an independent quadric evaluation", "[pyramid][cost]")
{
  Mesh m = smr_test::icosphere<Mesh>(2);
  CGAL::Random rng(2);
  for(auto v : vertices(m)) m.point(v) = m.point(v) + Vector_3(rng.get_double(-.05, .05), rng.get_double(-.05, .05), 0);
  typedef boost::property_map<Mesh, CGAL::vertex_point_t>::type VPM;
  typedef CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<Mesh, smr_test::Kernel> GH;
  const smr_test::Kernel gt;
  GH gh(m);
  SMR::internal::Halfedge_collapse_cost_adapter<Mesh, VPM, smr_test::Kernel, GH> adapter(m, get(CGAL::vertex_point, m), gt, gh);
  // Q_v = sum over the faces at v of p p^T, p = (n, -n.x) with n the unit face normal (closed mesh: no border term)
  std::vector<std::array<double, 16> > Q(num_vertices(m));
  for(auto& q : Q) q.fill(0.);
  for(auto f : faces(m))
  {
    std::vector<Point_3> p;
    for(auto v : vertices_around_face(halfedge(f, m), m)) p.push_back(m.point(v));
    Vector_3 n = CGAL::cross_product(p[1] - p[0], p[2] - p[0]);
    n = n / std::sqrt(n.squared_length());
    const double plane[4] = {n.x(), n.y(), n.z(), -(n * (p[0] - CGAL::ORIGIN))};
    for(auto v : vertices_around_face(halfedge(f, m), m))
      for(int i = 0; i < 4; ++i) for(int j = 0; j < 4; ++j) Q[v.idx()][4 * i + j] += plane[i] * plane[j];
  }
  std::size_t checked = 0;
  for(auto h : halfedges(m))
  {
    const Point_3 x = m.point(target(h, m));
    const double xh[4] = {x.x(), x.y(), x.z(), 1.};
    double expected = 0.;
    for(int i = 0; i < 4; ++i) for(int j = 0; j < 4; ++j)
      expected += xh[i] * (Q[source(h, m).idx()][4 * i + j] + Q[target(h, m).idx()][4 * i + j]) * xh[j];
    const auto c = adapter.cost(h);
    REQUIRE(bool(c));
    // the cost of moving o onto e is Q_o(p_e) (Q_e(p_e) = 0); tolerance: rounding of sums of ~12 products of size 1
    CHECK(*c == Approx(expected).epsilon(1e-9).margin(1e-12));
    ++checked;
  }
  CHECK(checked == halfedges(m).size());
}

TEST_CASE("the index-based plane quadrics give SMS's Garland-Heckbert cost, borders included", "[pyramid][cost]")
{
  typedef boost::property_map<Mesh, CGAL::vertex_point_t>::type VPM;
  typedef CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<Mesh, smr_test::Kernel> GH;
  CGAL::Random rng(11);
  for(int shape = 0; shape < 2; ++shape)
  {
    Mesh m = shape == 0 ? smr_test::planar_grid<Mesh>(9, 0.2) : smr_test::icosphere<Mesh>(2);
    for(auto v : vertices(m))
      m.point(v) = m.point(v) + Vector_3(rng.get_double(-.03, .03), rng.get_double(-.03, .03), rng.get_double(-.03, .03));
    const smr_test::Kernel gt;
    GH gh(m);
    SMR::internal::Halfedge_collapse_cost_adapter<Mesh, VPM, smr_test::Kernel, GH> adapter(m, get(CGAL::vertex_point, m), gt, gh);
    SMR::internal::Indexed_mesh<Mesh> im;
    SMR::internal::build_indexed_mesh(m, get(CGAL::vertex_index, m), im);
    std::vector<double> xyz;
    SMR::internal::read_coordinates(im.vertices, get(CGAL::vertex_point, m), gt, xyz);
    SMR::internal::Triangle_halfedges th;
    th.build(im.number_of_vertices(), im.triangles, true);
    SMR::internal::Plane_quadrics quadrics;
    quadrics.initialize(th, xyz);
    std::size_t checked = 0, border = 0;
    double largest = 0.;
    for(auto h : halfedges(m))
    {
      const auto expected = adapter.cost(h);
      const auto c = quadrics.cost(im.row(source(h, m), get(CGAL::vertex_index, m)), im.row(target(h, m), get(CGAL::vertex_index, m)));
      REQUIRE(bool(expected));
      REQUIRE(bool(c));
      CHECK(*c == Approx(*expected).epsilon(1e-9).margin(1e-12));
      largest = (std::max)(largest, *expected);
      border += is_border_edge(h, m) ? 1 : 0;
      ++checked;
    }
    CHECK(checked == halfedges(m).size());
    CHECK(largest > 1e-4);                      // the noise makes the costs non-trivial
    CHECK((shape == 0) == (border > 0));        // the grid's border quadrics were compared too
  }
}

namespace {
// the input of a decomposition as its first level sees it: rows, positions, halfedges with
// apexes and the plane quadrics
struct Input_quadrics
{
  explicit Input_quadrics(const Mesh& m)
  {
    SMR::internal::build_indexed_mesh(m, get(CGAL::vertex_index, m), im);
    SMR::internal::read_coordinates(im.vertices, get(CGAL::vertex_point, m), smr_test::Kernel(), xyz);
    th.build(im.number_of_vertices(), im.triangles, true);
    quadrics.initialize(th, xyz);
  }
  Input_quadrics(const Input_quadrics&) = delete;   // the quadrics point into xyz
  SMR::internal::Indexed_mesh<Mesh> im;
  std::vector<double> xyz;
  SMR::internal::Triangle_halfedges th;
  SMR::internal::Plane_quadrics quadrics;
};
} // namespace

TEST_CASE("candidate keys are the same with and without the cost model's prefetch hint", "[pyramid][cost]")
{
  typedef SMR::internal::Index Index;
  // a cost with the hint (as decompose() hands the plane quadrics over) counts its calls and
  // checks that they name rows; the keys must be those of the same cost without it
  struct Hinted_cost
  {
    SMR::internal::Optional<double> operator()(Index o, Index e) const { return quadrics.cost(o, e); }
    void prefetch_target(Index e) const
    {
      quadrics.prefetch_target(e);
      ++*hints;
      if(e >= rows) ++*bad_hints;
    }
    const SMR::internal::Plane_quadrics& quadrics;
    std::size_t rows;
    std::atomic<std::size_t>* hints;
    std::atomic<std::size_t>* bad_hints;
  };
  CGAL::Random rng(5);
  Mesh m = smr_test::icosphere<Mesh>(4);                     // 2,562 vertices: several blocks of candidates
  for(auto v : vertices(m))
    m.point(v) = m.point(v) + Vector_3(rng.get_double(-.01, .01), rng.get_double(-.01, .01), rng.get_double(-.01, .01));
  const Input_quadrics in(m);
  const SMR::internal::Triangle_halfedges& th = in.th;
  const SMR::internal::Plane_quadrics& quadrics = in.quadrics;
  // rows flagged as on a border (every seventh): their candidates along interior edges are
  // refused, which the keys must agree on and candidate_keys() must count
  std::vector<unsigned char> on_border(th.n, 0);
  for(std::size_t v = 0; v < th.n; v += 7)
    on_border[v] = 1;
  const SMR::internal::Candidate_key key(static_cast<Index>(th.source.size()));
  std::atomic<std::size_t> hints(0), bad_hints(0);
  const Hinted_cost hinted{quadrics, th.n, &hints, &bad_hints};
  const auto with_hint = SMR::internal::candidate_keys(th, hinted, on_border, key);
  const auto without = SMR::internal::candidate_keys(th, [&](Index o, Index e) { return quadrics.cost(o, e); }, on_border, key);
  CHECK(std::vector<std::uint64_t>(with_hint.begin(), with_hint.end()) == std::vector<std::uint64_t>(without.begin(), without.end()));
  // the quadrics' costs of a whole 1-ring (Q_o read once) are those of cost(o, e), bit for bit,
  // and the low bits kept per candidate are those of its cost
  struct Ring_cost
  {
    SMR::internal::Optional<double> operator()(Index o, Index e) const { return q.cost(o, e); }
    SMR::internal::Plane_quadrics::Costs_from costs_from(Index o) const { return q.costs_from(o); }
    const SMR::internal::Plane_quadrics& q;
  };
  std::vector<std::uint32_t> low(th.source.size());
  std::size_t refused_count = 0;
  const auto by_ring = SMR::internal::candidate_keys(th, Ring_cost{quadrics}, on_border, key, low.data(), &refused_count);
  CHECK(std::vector<std::uint64_t>(by_ring.begin(), by_ring.end()) == std::vector<std::uint64_t>(without.begin(), without.end()));
  CHECK(refused_count == std::size_t(std::count(by_ring.begin(), by_ring.end(), SMR::internal::refused_candidate)));
  CHECK(refused_count > 0);
  std::size_t low_checked = 0;
  for(std::size_t o = 0; o < th.n; ++o)
    for(Index k = th.out_offsets[o]; k < th.out_offsets[o + 1]; ++k)
      if(by_ring[k] != SMR::internal::refused_candidate)
      {
        const double c = *quadrics.cost(static_cast<Index>(o), th.out_target[k]);
        CHECK(low[k] == key.low_bits(c));
        CHECK(by_ring[k] == key(c, th.out[k]));
        ++low_checked;
      }
  CHECK(low_checked > 0);
  CHECK(hints.load() > 0);                                   // the hint was taken
  CHECK(hints.load() <= th.source.size());                   // at most one per candidate
  CHECK(bad_hints.load() == 0);
}

TEST_CASE("the quadrics of the next level are those of the kept rows plus their sources', with their own errors", "[pyramid][cost]")
{
  typedef SMR::internal::Index Index;
  typedef SMR::internal::Plane_quadrics Plane_quadrics;
  const Index none = SMR::internal::invalid_index;
  CGAL::Random rng(8);
  Mesh m = smr_test::icosphere<Mesh>(5);                     // 10,242 vertices: the passes run in parallel blocks
  for(auto v : vertices(m))
    m.point(v) = m.point(v) + Vector_3(rng.get_double(-.01, .01), rng.get_double(-.01, .01), rng.get_double(-.01, .01));
  Input_quadrics in(m);
  const std::size_t n = in.th.n, size = Plane_quadrics::size;
  // the level's collapses, selected as decompose() selects them
  std::vector<unsigned char> on_border, locked;
  SMR::internal::Index_array source_of_target;
  std::vector<SMR::internal::Collapse> accepted;
  SMR::internal::select_collapses(in.th, in.xyz.data(), [&](Index o, Index e) { return in.quadrics.cost(o, e); },
                                  std::size_t(-1), on_border, locked, source_of_target, accepted);
  REQUIRE(accepted.size() > 1000);
  // expected: M_k's quadrics with Q_e += Q_o made one collapse after the other, then the even
  // rows kept in order
  std::vector<double> q(in.quadrics.quadric(0), in.quadrics.quadric(0) + size * n);
  std::vector<Index> target_of(n, none), even, next_row(n, none);
  std::vector<std::size_t> is_target(n, 0);
  for(const SMR::internal::Collapse& c : accepted)
  {
    for(std::size_t i = 0; i < size; ++i)
      q[size * c.e + i] = q[size * c.o + i] + q[size * c.e + i];
    target_of[c.o] = c.e;
    is_target[c.e] = 1;
  }
  for(std::size_t v = 0; v < n; ++v)
    if(target_of[v] == none)
    {
      next_row[v] = static_cast<Index>(even.size());
      even.push_back(static_cast<Index>(v));
    }
  in.quadrics.next_level(accepted, even, next_row);
  // M_{k+1}'s positions: the even rows' moved down in place, as the decomposition moves them
  for(std::size_t j = 0; j < even.size(); ++j)
    for(int c = 0; c < 3; ++c)
      in.xyz[3 * j + c] = in.xyz[3 * std::size_t(even[j]) + c];
  in.xyz.resize(3 * even.size());
  in.quadrics.begin_level(in.xyz);
  std::size_t different = 0, targets = 0, wrong_costs = 0;
  for(std::size_t j = 0; j < even.size(); ++j)
  {
    const double* got = in.quadrics.quadric(static_cast<Index>(j));
    for(std::size_t i = 0; i < size; ++i)
      different += got[i] == q[size * even[j] + i] ? 0 : 1;
    targets += is_target[even[j]];
    // the cost of moving another row a onto j: Q_a(p_j) + Q_j(p_j), the latter from next_level()
    const Index a = static_cast<Index>((j + 1) % even.size());
    const double* p = in.xyz.data() + 3 * j;
    const double expected = Plane_quadrics::evaluate(in.quadrics.quadric(a), p) + Plane_quadrics::evaluate(q.data() + size * even[j], p);
    wrong_costs += *in.quadrics.cost(a, static_cast<Index>(j)) == expected ? 0 : 1;
  }
  CHECK(targets == accepted.size());                         // every target is an even row, compared
  CHECK(different == 0);
  CHECK(wrong_costs == 0);
}

TEST_CASE("the front computed under a sampled limit is a prefix of the full order of the candidates and gives their ends", "[pyramid][cost]")
{
  typedef SMR::internal::Index Index;
  CGAL::Random rng(12);
  // 40,962 and 10,201 vertices: enough candidates to be sampled (the grid with its border)
  std::vector<Mesh> meshes{smr_test::icosphere<Mesh>(6), smr_test::planar_grid<Mesh>(100, 0.3)};
  for(Mesh& m : meshes)
  {
    for(auto v : vertices(m))
      m.point(v) = m.point(v) + Vector_3(rng.get_double(-.01, .01), rng.get_double(-.01, .01), rng.get_double(-.01, .01));
    const Input_quadrics in(m);
    const SMR::internal::Triangle_halfedges& th = in.th;
    REQUIRE(th.number_of_halfedges() >= (std::size_t(1) << 15));
    struct Ring_cost
    {
      SMR::internal::Optional<double> operator()(Index o, Index e) const { return q.cost(o, e); }
      SMR::internal::Plane_quadrics::Costs_from costs_from(Index o) const { return q.costs_from(o); }
      const SMR::internal::Plane_quadrics& q;
    };
    const Ring_cost cost{in.quadrics};
    // as decompose() asks (n), fewer, and half of the candidates: fronts larger than the third
    // of its rows' candidates that a block's slice holds, so that blocks go on in vectors of
    // their own
    for(const std::size_t wanted : {std::size_t(th.n), std::size_t(th.n / 8), th.number_of_halfedges() / 2})
    {
      std::vector<unsigned char> on_border;
      SMR::internal::Candidate_key key(0);
      std::size_t total = 0;
      std::uint64_t limit = 0;
      bool as_ends = true;
      const SMR::internal::Key_array ends = SMR::internal::sorted_candidates(th, cost, on_border, key, wanted, total, limit, nullptr, &as_ends);
      CHECK(as_ends);                                        // the sampled front held the wanted candidates
      // the same candidates as keys (the rounds' and the rest's form)
      std::size_t total2 = 0;
      std::uint64_t limit2 = 0;
      const SMR::internal::Key_array front = SMR::internal::sorted_candidates(th, cost, on_border, key, wanted, total2, limit2);
      CHECK(total2 == total);
      CHECK(limit2 == limit);
      REQUIRE(front.size() == ends.size());
      REQUIRE(front.size() >= wanted);
      // expected: every candidate's key (candidate_keys()), the refused ones out, sorted whole
      std::vector<std::uint32_t> low(th.number_of_halfedges());
      SMR::internal::Key_array all = SMR::internal::candidate_keys(th, cost, on_border, key, low.data());
      SMR::internal::Low_bits all_low(low.begin(), low.end());
      SMR::internal::keep_keys(all, &all_low, [](std::uint64_t x) { return x != SMR::internal::refused_candidate; });
      CHECK(all.size() == total);
      SMR::internal::sort_front(all, all_low, key);
      REQUIRE(all.size() >= front.size());
      std::size_t wrong_keys = 0, wrong_ends = 0, over_limit = 0;
      for(std::size_t i = 0; i < front.size(); ++i)
      {
        wrong_keys += front[i] == all[i] ? 0 : 1;
        const Index h = key.halfedge(all[i]);
        wrong_ends += SMR::internal::source_of_ends(ends[i]) == th.source[h] && SMR::internal::target_of_ends(ends[i]) == th.target[h] ? 0 : 1;
        over_limit += key.leading_bits(front[i]) <= limit ? 0 : 1;
      }
      CHECK(wrong_keys == 0);
      CHECK(wrong_ends == 0);
      CHECK(over_limit == 0);
      if(front.size() < all.size())                          // a true prefix: what follows lies over the limit
        CHECK(key.leading_bits(all[front.size()]) > limit);
      // the rest, sorted apart, completes the order
      SMR::internal::Key_array joined = front;
      SMR::internal::sort_candidate_rest(th, cost, on_border, key, limit, joined);
      REQUIRE(joined.size() == all.size());
      std::size_t wrong_order = 0;
      for(std::size_t i = 0; i < all.size(); ++i)
        wrong_order += joined[i] == all[i] ? 0 : 1;
      CHECK(wrong_order == 0);
      // a limit under the wanted rank: the front falls short, which sorted_candidates() then
      // selects exactly (as it does where no sample is taken)
      SMR::internal::Key_array short_front;
      SMR::internal::Low_bits short_low;
      SMR::internal::Index_array short_halfedge;
      SMR::internal::Uninitialized_vector<SMR::internal::Front_entry> arena;
      std::size_t short_total = 0;
      const std::uint64_t below = key.leading_bits(all[wanted / 2]);
      CHECK(SMR::internal::candidate_front(th, cost, on_border, key, below, wanted, short_front, short_low, short_halfedge, nullptr,
                                           short_total, arena) < wanted);
      CHECK(short_total == total);
    }
  }
  // too few candidates to sample: no limit, the exact selection
  const Input_quadrics small(smr_test::icosphere<Mesh>(3));
  std::vector<unsigned char> on_border(small.th.n, 0);
  CHECK(SMR::internal::sampled_candidate_limit(small.th, [&](Index o, Index e) { return small.quadrics.cost(o, e); }, on_border,
                                               SMR::internal::Candidate_key(small.th.number_of_halfedges()), small.th.n)
        == ~std::uint64_t(0));
}

namespace {
// the Garland-Heckbert plane policies under another type: decompose() then drives them
// through SMS edge profiles on a working halfedge mesh instead of its index-based quadrics
struct Wrapped_plane_policies : CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<Mesh, smr_test::Kernel>
{
  explicit Wrapped_plane_policies(Mesh& m) : CGAL::Surface_mesh_simplification::GarlandHeckbert_plane_policies<Mesh, smr_test::Kernel>(m) {}
};
} // namespace

TEST_CASE("the default quadrics on index arrays and SMS's policies on a working mesh build the same pyramid", "[pyramid][cost]")
{
  Mesh m = smr_test::planar_grid<Mesh>(14, 0.2);
  CGAL::Random rng(4);
  for(auto v : vertices(m))
    m.point(v) = m.point(v) + Vector_3(rng.get_double(-.02, .02), rng.get_double(-.02, .02), rng.get_double(-.05, .05));
  const auto a = SMR::decompose(m);
  Mesh dummy;
  const auto b = SMR::decompose(m, CGAL::parameters::get_cost(Wrapped_plane_policies(dummy)));
  REQUIRE(a.number_of_levels() > 3);
  REQUIRE(a.number_of_levels() == b.number_of_levels());
  for(std::size_t k = 0; k < a.number_of_levels(); ++k)
  {
    CHECK(a.levels()[k].vertices == b.levels()[k].vertices);
    CHECK(a.levels()[k].odd_rows == b.levels()[k].odd_rows);
    CHECK(a.levels()[k].collapse_targets == b.levels()[k].collapse_targets);
    CHECK(a.levels()[k].removed_faces == b.levels()[k].removed_faces);
  }
  CHECK(a.coarse_faces() == b.coarse_faces());
  check_exact_round_trip(m, b);
}

// two planar grids that touch at one corner: the halfedge mesh is valid, the corner has two border gaps
Mesh pinched_grids()
{
  Mesh m;
  const int n = 6;
  std::vector<Mesh::Vertex_index> a(n * n), b(n * n);
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j)
    {
      a[i * n + j] = m.add_vertex(Point_3(i, j, 0.1 * std::sin(i + 2. * j)));
      b[i * n + j] = (i == 0 && j == 0) ? a[0] : m.add_vertex(Point_3(-i, -j, 0.1 * std::cos(2. * i + j)));
    }
  for(const auto* grid : {&a, &b})
    for(int i = 0; i + 1 < n; ++i)
      for(int j = 0; j + 1 < n; ++j)
      {
        const auto& g = *grid;
        const bool flip = (grid == &b);   // the mirrored grid keeps a consistent orientation
        std::vector<Mesh::Vertex_index> t1{g[i * n + j], g[(i + 1) * n + j], g[(i + 1) * n + j + 1]};
        std::vector<Mesh::Vertex_index> t2{g[i * n + j], g[(i + 1) * n + j + 1], g[i * n + j + 1]};
        if(flip) { std::swap(t1[1], t1[2]); std::swap(t2[1], t2[2]); }
        REQUIRE(CGAL::Euler::add_face(t1, m) != Mesh::null_face());
        REQUIRE(CGAL::Euler::add_face(t2, m) != Mesh::null_face());
      }
  return m;
}

TEST_CASE("a vertex pinched between two fans survives decomposition and reconstruction", "[pyramid][input]")
{
  const Mesh m = pinched_grids();
  REQUIRE(CGAL::is_valid_polygon_mesh(m));
  const auto pyr = SMR::decompose(m);
  REQUIRE(pyr.number_of_levels() > 0);
  check_exact_round_trip(m, pyr);
  for(std::size_t k = 0; k <= pyr.number_of_levels(); ++k)
  {
    Mesh level;
    SMR::reconstruct(pyr, level, SMR::parameters::level(k));
    CHECK(CGAL::is_valid_polygon_mesh(level));
    CHECK(faces(level).size() == pyr.number_of_faces(k));
  }
}

TEST_CASE("the candidates' radix sort orders by (cost, halfedge) like a comparison sort", "[pyramid][cost]")
{
  CGAL::Random rng(8);
  for(int trial = 0; trial < 7; ++trial)
  {
    // trial 6: more candidates than one block of the parallel passes (sort and front selection)
    std::vector<double> cost_of(trial == 0 ? 1 : trial == 6 ? 300000 : 20000);
    for(double& cost : cost_of)
    {
      switch(rng.get_int(0, 6))
      {
        case 0: cost = 0.; break;
        case 1: cost = -0.; break;
        case 2: cost = 1e-3 * rng.get_int(0, 5); break;                      // exact ties
        case 3: cost = -std::ldexp(rng.get_double(), rng.get_int(-60, 3)); break;
        case 4: cost = trial == 3 ? std::numeric_limits<double>::infinity() : 1.; break;
        default: cost = std::ldexp(1. + 1e-12 * rng.get_int(0, 3), rng.get_int(-40, 10)); break;   // equal keys, different costs
      }
    }
    // the split of the key follows the number of halfedges: 15 halfedge bits here, 31 (and only
    // 33 cost bits) when the level is declared to have 2^31 halfedges
    const SMR::internal::Candidate_key key((trial == 4 || trial == 5) ? (std::size_t(1) << 31) : cost_of.size());
    CHECK(key.halfedge_bits() == ((trial == 4 || trial == 5) ? 31 : (trial == 0 ? 0 : trial == 6 ? 19 : 15)));
    std::vector<std::uint64_t> c;
    std::vector<SMR::internal::Index> expected;
    for(std::size_t i = 0; i < cost_of.size(); ++i)
    {
      c.push_back(key(cost_of[i], static_cast<SMR::internal::Index>(i)));
      REQUIRE(key.halfedge(c.back()) == i);
      expected.push_back(static_cast<SMR::internal::Index>(i));
    }
    std::sort(expected.begin(), expected.end(), [&](auto a, auto b) { return cost_of[a] < cost_of[b] || (cost_of[a] == cost_of[b] && a < b); });
    if(trial % 2 == 1 || trial == 6)   // the input order does not matter
      std::shuffle(c.begin(), c.end(), std::mt19937(trial));
    // runs of equal cost bits: by the bits of the cost the key leaves out, then by halfedge
    auto tie_order = [&](SMR::internal::Index h) { return (std::uint64_t(key.low_bits(cost_of[h])) << 32) | h; };
    // the front of cheapest_keys() (refused keys mixed in) is a true prefix of the order:
    // sorting it and the rest (keys_above()) apart gives the full order, and it holds at least
    // the wanted keys
    constexpr std::uint64_t refused = ~std::uint64_t(0);
    for(std::size_t wanted : {std::size_t(0), std::size_t(1), cost_of.size() / 7, cost_of.size() / 2, cost_of.size()})
    {
      SMR::internal::Key_array m;
      for(std::size_t i = 0; i < c.size(); ++i)
      {
        if(i % 5 == 2)
          m.push_back(refused);
        m.push_back(c[i]);
      }
      std::size_t total = 0;
      std::uint64_t limit = 0;
      SMR::internal::Key_array m3 = m;
      SMR::internal::Key_array front = SMR::internal::cheapest_keys(m, key, refused, wanted, total, limit);
      CHECK(total == c.size());
      // told the number of keys not refused (sorted_candidates(): candidate_keys() counts the
      // refused ones), it counts only those under the limit: the same front, total and limit
      std::size_t total3 = 0;
      std::uint64_t limit3 = 0;
      const SMR::internal::Key_array front3
        = SMR::internal::cheapest_keys(m3, key, refused, wanted, total3, limit3, nullptr, nullptr, c.size());
      CHECK(front3 == front);
      CHECK(total3 == total);
      CHECK(limit3 == limit);
      CHECK(front.size() >= (std::min)(wanted, c.size()));
      for(std::uint64_t x : front)
        REQUIRE(key.leading_bits(x) <= limit);
      SMR::internal::keys_above(m, key, refused, limit);
      REQUIRE(front.size() + m.size() == c.size());
      SMR::internal::sort_candidates(front.data(), front.size(), key, tie_order);
      SMR::internal::sort_candidates(m.data(), m.size(), key, tie_order);
      front.insert(front.end(), m.begin(), m.end());
      for(std::size_t i = 0; i < front.size(); ++i)
        REQUIRE(key.halfedge(front[i]) == expected[i]);
      // the same with the low bits carried beside the keys (sorted_candidates()): the front's
      // low bits follow its keys, and sort_front() gives the same order
      SMR::internal::Key_array m2;
      SMR::internal::Low_bits low2;
      for(std::size_t i = 0; i < c.size(); ++i)
      {
        if(i % 5 == 2)
        {
          m2.push_back(refused);
          low2.push_back(0);
        }
        m2.push_back(c[i]);
        low2.push_back(key.low_bits(cost_of[key.halfedge(c[i])]));
      }
      SMR::internal::Low_bits front_low;
      SMR::internal::Key_array front2 = SMR::internal::cheapest_keys(m2, key, refused, wanted, total, limit, &low2, &front_low);
      REQUIRE(front_low.size() == front2.size());
      for(std::size_t i = 0; i < front2.size(); ++i)
        REQUIRE(front_low[i] == key.low_bits(cost_of[key.halfedge(front2[i])]));
      SMR::internal::keys_above(m2, key, refused, limit, &low2);
      REQUIRE(low2.size() == m2.size());
      SMR::internal::sort_front(front2, front_low, key);
      SMR::internal::sort_front(m2, low2, key);
      front2.insert(front2.end(), m2.begin(), m2.end());
      REQUIRE(front2.size() == expected.size());
      for(std::size_t i = 0; i < front2.size(); ++i)
        REQUIRE(key.halfedge(front2[i]) == expected[i]);
    }
    SMR::internal::sort_candidates(c.data(), c.size(), key, tie_order);
    REQUIRE(c.size() == expected.size());
    for(std::size_t i = 0; i < c.size(); ++i)
      REQUIRE(key.halfedge(c[i]) == expected[i]);
  }
}


TEST_CASE("the radix sort on a bit field is a stable sort by that field", "[pyramid][cost][order]")
{
  // fields of several widths and places, the top one reaching bit 63 (the spatial order's);
  // few distinct field values (long runs of ties: stability) and many (every pass moves keys);
  // more keys than a block of the sort's passes
  std::mt19937_64 rng(11);
  struct Field { int shift, bits; std::uint64_t values; };
  for(const Field f : {Field{23, 41, ~std::uint64_t(0)}, Field{23, 41, 7}, Field{5, 20, 1000}, Field{0, 64, ~std::uint64_t(0)},
                       Field{40, 3, 8}, Field{12, 30, 1}})
    for(std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(1000), std::size_t(200000)})
    {
      const std::uint64_t field_mask = f.bits == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << f.bits) - 1;
      std::vector<std::uint64_t> keys(n);
      for(std::uint64_t& k : keys)
      {
        const std::uint64_t value = (f.values == ~std::uint64_t(0) ? rng() : rng() % f.values) & field_mask;
        const std::uint64_t below = f.shift == 0 ? 0 : rng() & ((std::uint64_t(1) << f.shift) - 1);
        k = (value << f.shift) | below;                 // the bits above the field are zero
      }
      std::vector<std::uint64_t> expected = keys;
      std::stable_sort(expected.begin(), expected.end(),
                       [&](std::uint64_t a, std::uint64_t b) { return ((a >> f.shift) & field_mask) < ((b >> f.shift) & field_mask); });
      SMR::internal::radix_sort_bits(keys.data(), n, f.shift, f.bits);
      REQUIRE(keys == expected);
    }
}

// Eq. 5's last step against its definition, on more values than one block of the parallel
// pass: detail d = f - p (or -p where that overflows, a non-finite prediction taken as 0), a
// correction exactly where fl(p + d) misses f (sign of zero included), listed in increasing
// position, and f recovered bit for bit by the synthesis' rule; the same lists for any number
// of threads, and with the predictions read from the details array itself (in place).
TEST_CASE("details and corrections: one pass gives Eq. 5's details and every needed correction, in order", "[pyramid][weights]")
{
  const std::size_t n = 100000;   // several blocks of 2^14 values
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1., 1.);
  std::vector<double> f(n), p(n);
  for(std::size_t k = 0; k < n; ++k)
  {
    // plain values, values whose detail rounds (large f, small p), overflows, a non-finite
    // prediction and signed zeros, spread over all blocks
    switch(k % 7)
    {
    case 0: f[k] = 1e16 * unit(rng); p[k] = 0.1 + unit(rng); break;
    case 1: f[k] = 1.7e308; p[k] = -1.7e308; break;
    case 2: f[k] = -0.0; p[k] = 0.; break;
    case 3: f[k] = unit(rng); p[k] = std::numeric_limits<double>::infinity(); break;
    default: f[k] = unit(rng); p[k] = unit(rng); break;
    }
  }
  auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; };
  auto same_details = [&](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  auto same_corrections = [&](const SMR::internal::Corrections& a, const SMR::internal::Corrections& b) {
    bool same = a.size() == b.size();
    for(std::size_t i = 0; same && i < a.size(); ++i)
      same = a[i].first == b[i].first && same_bits(a[i].second, b[i].second);
    return same;
  };
  auto check = [&](const std::vector<double>& details, const SMR::internal::Corrections& corrections) {
    std::size_t next = 0;
    bool definition = true, exact = true, ordered = true;
    for(std::size_t k = 0; k < n; ++k)
    {
      const double pk = std::isfinite(p[k]) ? p[k] : 0.;
      double d = f[k] - pk;
      if(!std::isfinite(d)) d = -pk;
      definition = definition && same_bits(details[k], d);
      const double t = pk + details[k];
      const bool needed = t != f[k] || std::signbit(t) != std::signbit(f[k]);
      double v = t;
      if(next < corrections.size() && corrections[next].first == k)
      {
        v = SMR::internal::apply_correction(t, corrections[next].second);
        ++next;
      }
      else if(needed)
        ordered = false;                                    // a needed correction missing (or out of order)
      exact = exact && same_bits(v, f[k]);
    }
    CHECK(definition);
    CHECK(exact);
    CHECK(ordered);
    CHECK(next == corrections.size());                      // no correction that is not needed
  };
  std::vector<double> details(n);
  SMR::internal::Corrections corrections;
  SMR::internal::details_and_corrections(f, [&](std::size_t k) { return p[k]; }, details.data(), corrections);
  CHECK(corrections.size() >= 2 * (n / 7));                 // at least the overflows and the zeros
  check(details, corrections);
  // predictions read from the array the details are written to
  std::vector<double> in_place(p);
  SMR::internal::Corrections corrections_in_place;
  const double* const d = in_place.data();
  SMR::internal::details_and_corrections(f, [d](std::size_t k) { return d[k]; }, in_place.data(), corrections_in_place);
  CHECK(same_details(in_place, details));
  CHECK(same_corrections(corrections_in_place, corrections));
#ifdef CGAL_LINKED_WITH_TBB
  for(int threads : {1, 3})
  {
    tbb::task_arena arena(threads);
    std::vector<double> details_t(n);
    SMR::internal::Corrections corrections_t;
    arena.execute([&] { SMR::internal::details_and_corrections(f, [&](std::size_t k) { return p[k]; }, details_t.data(), corrections_t); });
    CHECK(same_details(details_t, details));
    CHECK(same_corrections(corrections_t, corrections));
  }
#endif
}

TEST_CASE("the spatial order's permutations, and pages given back, keep the arrays' values", "[pyramid][order]")
{
  typedef SMR::internal::Index Index;
  // the spatial order's permutations (gathered, then copied back into the same array): values
  // v[i] = v before at vertex_order[i], blocks of 1 and 3; faces in the face order, their
  // corners renamed to places in the vertex order
  std::mt19937 rng(5);
  for(const std::size_t n : {std::size_t(1), std::size_t(2), std::size_t(1000), std::size_t(50000)})
    for(int kind = 0; kind < 3; ++kind)
    {
      std::vector<Index> from(n);
      std::iota(from.begin(), from.end(), Index(0));
      if(kind == 1)
        std::shuffle(from.begin(), from.end(), rng);
      else if(kind == 2)
        std::rotate(from.begin(), from.begin() + std::ptrdiff_t(n / 2), from.end());
      for(const std::size_t dim : {std::size_t(1), std::size_t(3)})
      {
        std::vector<double> a(n * dim), expected(n * dim);
        for(std::size_t i = 0; i < a.size(); ++i)
          a[i] = double(i) * 0.5 - 7.;
        for(std::size_t i = 0; i < n; ++i)
          for(std::size_t c = 0; c < dim; ++c)
            expected[i * dim + c] = a[std::size_t(from[i]) * dim + c];
        const double* memory = a.data();
        SMR::internal::permute_values(from, dim, a);
        REQUIRE(a == expected);
        CHECK(a.data() == memory);                       // the array keeps its memory
      }
      // faces (a, a+1, a+2) mod n in a shuffled face order
      std::vector<Index> tri(3 * n), face_order(n);
      for(std::size_t f = 0; f < n; ++f)
        for(int c = 0; c < 3; ++c)
          tri[3 * f + c] = Index((f + c) % n);
      std::iota(face_order.begin(), face_order.end(), Index(0));
      std::shuffle(face_order.begin(), face_order.end(), rng);
      std::vector<Index> place(n);
      for(std::size_t i = 0; i < n; ++i)
        place[from[i]] = Index(i);
      std::vector<Index> expected_tri(3 * n);
      for(std::size_t p = 0; p < n; ++p)
        for(int c = 0; c < 3; ++c)
          expected_tri[3 * p + c] = place[tri[3 * std::size_t(face_order[p]) + c]];
      SMR::internal::permute_faces(from, face_order, tri);
      REQUIRE(tri == expected_tri);
    }
  // an array reduced in place keeps its values and its capacity when the pages of the rest go
  // back, and can be written again past its size
  for(const std::size_t kept : {std::size_t(0), std::size_t(1), std::size_t(4096), std::size_t(300000)})
  {
    std::vector<double> v(1 << 20);
    for(std::size_t i = 0; i < v.size(); ++i)
      v[i] = double(i) + 0.25;
    const std::size_t capacity = v.capacity();
    v.resize(kept);
    SMR::internal::release_unused_capacity(v);
    REQUIRE(v.size() == kept);
    REQUIRE(v.capacity() == capacity);
    for(std::size_t i = 0; i < kept; ++i)
      REQUIRE(v[i] == double(i) + 0.25);
    v.resize(kept + 1000, -1.);
    for(std::size_t i = kept; i < v.size(); ++i)
      REQUIRE(v[i] == -1.);
  }
}

TEST_CASE("the front of the candidates holds the wanted cheapest ones when their sample misleads", "[pyramid][cost]")
{
  // 40,000 keys: the sampled ones (every s-th from the (s / 2)-th) are the cheapest, so the
  // sampled limit passes too few keys for a wanted quarter; the exact selection takes over. And
  // a sample that does not mislead (costs in a shuffled order) gives a front a little larger
  // than wanted, with the same prefix property.
  const std::size_t n = 40000, s = SMR::internal::sample_stride(n);
  REQUIRE(s >= 8);
  const SMR::internal::Candidate_key key(n);
  constexpr std::uint64_t refused = ~std::uint64_t(0);
  for(bool misleading : {true, false})
  {
    std::vector<double> cost_of(n);
    for(std::size_t i = 0; i < n; ++i)
      cost_of[i] = i % s == s / 2 ? 1. + double((i * 7919) % n) / double(n) : 1000. + double((i * 7919) % n);
    SMR::internal::Key_array c;
    for(std::size_t i = 0; i < n; ++i)
      c.push_back(key(cost_of[i], static_cast<SMR::internal::Index>(i)));
    if(!misleading)
      std::shuffle(c.begin(), c.end(), std::mt19937(3));
    std::vector<std::uint64_t> sorted(c.begin(), c.end());
    std::sort(sorted.begin(), sorted.end());
    const std::size_t wanted = n / 4;
    const std::uint64_t exact_limit = key.leading_bits(sorted[wanted - 1]);
    std::size_t total = 0;
    std::uint64_t limit = 0;
    SMR::internal::Key_array rest = c;
    SMR::internal::Key_array front = SMR::internal::cheapest_keys(rest, key, refused, wanted, total, limit);
    CHECK(total == n);
    REQUIRE(front.size() >= wanted);
    CHECK(limit >= exact_limit);
    if(misleading)
      CHECK(limit == exact_limit);                       // selected exactly
    else
    {
      CHECK(limit > exact_limit);                        // sampled: a few percent more
      CHECK(front.size() < wanted + wanted / 4);
    }
    // a true prefix: every front key is below every other key, and the front is in c's order
    SMR::internal::keys_above(rest, key, refused, limit);
    REQUIRE(front.size() + rest.size() == n);
    const std::uint64_t largest_in_front = *std::max_element(front.begin(), front.end());
    for(std::uint64_t x : rest)
      REQUIRE(x > largest_in_front);
    std::size_t q = 0;
    for(std::uint64_t x : c)
      if(q < front.size() && front[q] == x)
        ++q;
    CHECK(q == front.size());
  }
}

TEST_CASE("the front of the candidates keeps a run of equal costs whole", "[pyramid][cost]")
{
  // 50,000 keys of one cost (a flat region: exact ties), every third one refused: the sampled
  // limit is that cost's, so the front is every key not refused, in its order
  const std::size_t n = 50000;
  const SMR::internal::Candidate_key key(n);
  constexpr std::uint64_t refused = ~std::uint64_t(0);
  SMR::internal::Key_array c;
  std::size_t not_refused = 0;
  for(std::size_t i = 0; i < n; ++i)
  {
    c.push_back(i % 3 == 1 ? refused : key(0.25, static_cast<SMR::internal::Index>(i)));
    not_refused += i % 3 == 1 ? 0 : 1;
  }
  for(std::size_t wanted : {std::size_t(1), n / 10})
  {
    SMR::internal::Key_array rest = c;
    std::size_t total = 0;
    std::uint64_t limit = 0;
    const SMR::internal::Key_array front = SMR::internal::cheapest_keys(rest, key, refused, wanted, total, limit);
    CHECK(total == not_refused);
    REQUIRE(front.size() == not_refused);
    std::size_t q = 0;
    for(std::uint64_t x : c)
      if(x != refused)
        REQUIRE(front[q++] == x);
    SMR::internal::keys_above(rest, key, refused, limit);
    CHECK(rest.empty());
  }
}
TEST_CASE("the index-based link condition agrees with CGAL's on every edge", "[pyramid][link]")
{
  std::vector<Mesh> meshes;
  meshes.push_back(smr_test::icosphere<Mesh>(1));
  meshes.push_back(smr_test::planar_grid<Mesh>(6, 0.2));
  {
    Mesh t;
    CGAL::make_tetrahedron(Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(0, 1, 0), Point_3(0, 0, 1), t);
    meshes.push_back(t);
  }
  {
    // a triangle split at its centre: an interior vertex of valence 3 next to border vertices of valence 3
    Mesh t;
    const auto a = t.add_vertex(Point_3(0, 0, 0)), b = t.add_vertex(Point_3(1, 0, 0)), c = t.add_vertex(Point_3(0, 1, 0));
    const auto o = t.add_vertex(Point_3(0.3, 0.3, 0));
    t.add_face(a, b, o); t.add_face(b, c, o); t.add_face(c, a, o);
    meshes.push_back(t);
  }
  {
    Mesh t;   // an octahedron's upper half: a square pyramid with its base open, and the same closed by two triangles
    std::vector<Mesh::Vertex_index> v;
    for(const Point_3& p : {Point_3(1, 0, 0), Point_3(0, 1, 0), Point_3(-1, 0, 0), Point_3(0, -1, 0), Point_3(0, 0, 1)}) v.push_back(t.add_vertex(p));
    for(int i = 0; i < 4; ++i) t.add_face(v[i], v[(i + 1) % 4], v[4]);
    meshes.push_back(t);
    t.add_face(v[0], v[2], v[1]);
    t.add_face(v[0], v[3], v[2]);
    meshes.push_back(t);
  }
  for(const Mesh& m : meshes)
  {
    REQUIRE(CGAL::is_valid_polygon_mesh(m));
    SMR::internal::Indexed_mesh<Mesh> im;
    SMR::internal::build_indexed_mesh(m, get(CGAL::vertex_index, m), im);
    SMR::internal::Triangle_halfedges th;
    th.build(im.number_of_vertices(), im.triangles, true);
    std::vector<unsigned char> on_border(th.n, 0);
    for(std::size_t h = 3 * th.nf; h < th.source.size(); ++h)
      on_border[th.source[h]] = on_border[th.target[h]] = 1;
    std::size_t compared = 0, refused = 0;
    for(SMR::internal::Index h = 0; h < th.source.size(); ++h)
    {
      const auto he = halfedge(im.vertices[th.source[h]], im.vertices[th.target[h]], m);
      REQUIRE(he.second);
      const bool expected = CGAL::Euler::does_satisfy_link_condition(edge(he.first, m), m);
      CHECK(SMR::internal::satisfies_link_condition(th, h, th.source[h], th.target[h], on_border) == expected);
      refused += expected ? 0 : 1;
      ++compared;
    }
    CHECK(compared == halfedges(m).size());
    INFO("refused: " << refused);
  }
}

// build_twins() (the twins alone, for linking an output mesh) against build() on the same
// faces: the same twins, border halfedges numbered alike, their ends read from the faces
void check_twins_only(const SMR::internal::Triangle_halfedges& th, const std::vector<SMR::internal::Index>& tri)
{
  SMR::internal::Triangle_halfedges twins;
  twins.build_twins(th.n, tri);
  CHECK(twins.repeated_directed_edge == th.repeated_directed_edge);
  CHECK(twins.source.empty());
  CHECK(twins.out.empty());
  REQUIRE(twins.twin.size() == th.twin.size());
  for(SMR::internal::Index h = 0; h < th.twin.size(); ++h)
  {
    CHECK(twins.twin[h] == th.twin[h]);
    CHECK(twins.source_in(tri, h) == th.source[h]);
    CHECK(twins.target_in(tri, h) == th.target[h]);
  }
}

TEST_CASE("Triangle_halfedges pairs the halfedges of the mesh, also when a directed edge repeats", "[pyramid][link]")
{
  typedef SMR::internal::Index Index;
  std::vector<Mesh> meshes;
  meshes.push_back(smr_test::icosphere<Mesh>(2));
  meshes.push_back(smr_test::planar_grid<Mesh>(7, 0.2));
  {
    Mesh two = smr_test::icosphere<Mesh>(1);                 // two components, one with a border
    Mesh grid = smr_test::planar_grid<Mesh>(4, 0.1);
    CGAL::copy_face_graph(grid, two);
    meshes.push_back(two);
  }
  for(bool hub_first : {true, false})                        // fans with a centre of valence 100 (long rings, sorted)
  {
    Mesh fan;
    const auto first = hub_first ? fan.add_vertex(Point_3(0, 0, 1)) : Mesh::Vertex_index();
    std::vector<Mesh::Vertex_index> rim;
    for(int i = 0; i < 100; ++i) rim.push_back(fan.add_vertex(Point_3(std::cos(0.0628 * i), std::sin(0.0628 * i), 0)));
    const auto centre = hub_first ? first : fan.add_vertex(Point_3(0, 0, 1));
    for(int i = 0; i < 99; ++i) fan.add_face(centre, rim[i], rim[i + 1]);   // open: one border gap at the centre
    meshes.push_back(fan);
  }
  for(const Mesh& m : meshes)
  {
    SMR::internal::Indexed_mesh<Mesh> im;
    SMR::internal::build_indexed_mesh(m, get(CGAL::vertex_index, m), im);
    SMR::internal::Triangle_halfedges th;
    th.build(im.number_of_vertices(), im.triangles, true);
    CHECK(th.source.size() == halfedges(m).size());
    std::size_t border = 0;
    for(Index h = 0; h < th.source.size(); ++h)
    {
      REQUIRE(th.twin[h] != SMR::internal::invalid_index);
      CHECK(th.twin[th.twin[h]] == h);
      CHECK(th.source[th.twin[h]] == th.target[h]);
      CHECK(th.target[th.twin[h]] == th.source[h]);
      const auto he = halfedge(im.vertices[th.source[h]], im.vertices[th.target[h]], m);
      REQUIRE(he.second);
      CHECK(th.has_face(h) == !is_border(he.first, m));
      border += th.has_face(h) ? 0 : 1;
    }
    CHECK(border == std::size_t(std::count_if(halfedges(m).begin(), halfedges(m).end(), [&](auto h) { return is_border(h, m); })));
    // the 1-ring lists: targets and the third corner of each face
    for(Index v = 0; v < th.n; ++v)
      for(Index k = th.out_offsets[v]; k < th.out_offsets[v + 1]; ++k)
      {
        const Index h = th.out[k];
        CHECK(th.source[h] == v);
        CHECK(th.out_target[k] == th.target[h]);
        CHECK(th.out_apex[k] == (th.has_face(h) ? th.opposite_vertex(h) : SMR::internal::invalid_index));
      }
    check_twins_only(th, im.triangles);
  }
  // a face array where 0 -> 1 is in two faces (not a halfedge mesh): the pairing falls back to
  // first come first served and stays a pairing
  const std::vector<Index> tri = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  SMR::internal::Triangle_halfedges th;
  th.build(5, tri);
  for(Index h = 0; h < th.source.size(); ++h)
  {
    REQUIRE(th.twin[h] != SMR::internal::invalid_index);
    CHECK(th.twin[th.twin[h]] == h);
    CHECK(th.source[th.twin[h]] == th.target[h]);
  }
  CHECK(th.twin[0] == 3);                                    // 0 -> 1 of the first face pairs with 1 -> 0
  CHECK(!th.has_face(th.twin[6]));                           // the repeated 0 -> 1 gets a border twin
  CHECK(th.repeated_directed_edge);
  check_twins_only(th, tri);
  // the same in a long ring (searched sorted): vertex 0 with 40 faces, 0 -> 1 in two of them
  std::vector<Index> fan;
  for(Index i = 1; i <= 40; ++i) fan.insert(fan.end(), {0, i, i + 1});
  fan.insert(fan.end(), {0, 1, 50});                         // face 40: 0 -> 1 again
  fan.insert(fan.end(), {1, 0, 45});                         // face 41: the one 1 -> 0
  SMR::internal::Triangle_halfedges long_ring;
  long_ring.build(51, fan);
  CHECK(long_ring.repeated_directed_edge);
  for(Index h = 0; h < long_ring.source.size(); ++h)
  {
    REQUIRE(long_ring.twin[h] != SMR::internal::invalid_index);
    CHECK(long_ring.twin[long_ring.twin[h]] == h);
    CHECK(long_ring.source[long_ring.twin[h]] == long_ring.target[h]);
  }
  CHECK(long_ring.twin[0] == 3 * 41);                        // the first 0 -> 1 pairs with 1 -> 0 (first come, first served)
  CHECK(!long_ring.has_face(long_ring.twin[3 * 40]));        // the second gets a border twin
  check_twins_only(long_ring, fan);
}

// Whether a face array repeats a directed edge (or has a face with a repeated vertex), the
// fallback condition of Triangle_halfedges::build(), is found by the ring matching (with the
// apexes: two corners claiming one twin, or two corners without a face across sharing a
// target; without: every pair of targets): against a count of the directed edges, on random
// face arrays over few vertices (many repeats, with and without a face across) and on the
// long-ring path.
TEST_CASE("Triangle_halfedges finds every repeated directed edge, with and without apexes", "[pyramid][link]")
{
  typedef SMR::internal::Index Index;
  CGAL::Random rng(15);
  auto repeats = [](const std::vector<Index>& tri) {
    std::set<std::pair<Index, Index> > seen;
    for(std::size_t f = 0; f < tri.size(); f += 3)
      for(int c = 0; c < 3; ++c)
      {
        const Index a = tri[f + c], b = tri[f + (c + 1) % 3];
        if(a == b || !seen.insert(std::make_pair(a, b)).second)
          return true;
      }
    return false;
  };
  std::size_t with_repeat = 0, without = 0;
  for(int trial = 0; trial < 400; ++trial)
  {
    const Index n = Index(4 + trial % 9);
    const int faces = 1 + rng.get_int(0, 2 * int(n));
    std::vector<Index> tri;
    for(int f = 0; f < faces; ++f)
    {
      Index a = Index(rng.get_int(0, int(n))), b = Index(rng.get_int(0, int(n))), c = Index(rng.get_int(0, int(n)));
      if(trial % 2 == 0)                                       // half the trials: no repeated vertex in a face
        while(b == a) b = Index(rng.get_int(0, int(n)));
      if(trial % 2 == 0)
        while(c == a || c == b) c = Index(rng.get_int(0, int(n)));
      tri.insert(tri.end(), {a, b, c});
    }
    const bool expected = repeats(tri);
    (expected ? with_repeat : without) += 1;
    for(bool apexes : {true, false})
    {
      INFO("trial " << trial << ", apexes " << apexes);
      SMR::internal::Triangle_halfedges th;
      th.build(n, tri, apexes);
      CHECK(th.repeated_directed_edge == expected);
      for(Index h = 0; h < th.twin.size(); ++h)              // a pairing in every case
      {
        REQUIRE(th.twin[h] != SMR::internal::invalid_index);
        CHECK(th.twin[th.twin[h]] == h);
      }
    }
  }
  CHECK(with_repeat > 50);
  CHECK(without > 50);
  // a ring of 3 corners where 0 -> 1 repeats with no face holding 1 -> 0 (neither corner has a
  // face across), and one where it repeats beside the face across
  for(const std::vector<Index>& tri : {std::vector<Index>{0, 1, 2, 0, 1, 3, 0, 4, 5},
                                       std::vector<Index>{0, 1, 2, 0, 1, 3, 1, 0, 4}})
    for(bool apexes : {true, false})
    {
      SMR::internal::Triangle_halfedges th;
      th.build(6, tri, apexes);
      CHECK(th.repeated_directed_edge);
    }
}

// every array of two halfedge structures
void check_same_halfedges(const SMR::internal::Triangle_halfedges& a, const SMR::internal::Triangle_halfedges& b)
{
  CHECK(a.n == b.n);
  CHECK(a.nf == b.nf);
  CHECK(a.repeated_directed_edge == b.repeated_directed_edge);
  CHECK(a.source == b.source);
  CHECK(a.target == b.target);
  CHECK(a.twin == b.twin);
  CHECK(a.out_offsets == b.out_offsets);
  CHECK(a.out == b.out);
  CHECK(a.out_target == b.out_target);
  CHECK(a.out_apex == b.out_apex);
}

// build_after_collapses() that falls back to build(): false returned, build()'s arrays
void check_built_again(const std::vector<SMR::internal::Index>& tri, std::size_t n, const SMR::internal::Index_array& face_after,
                       const std::vector<SMR::internal::Index>& after, std::size_t n_after, bool repeated_before)
{
  SMR::internal::Triangle_halfedges before, derived, built;
  before.build(n, tri, true);
  REQUIRE(before.repeated_directed_edge == repeated_before);
  SMR::internal::Collapsed_faces change;
  change.face_after = face_after;
  CHECK(!derived.build_after_collapses(std::move(before), std::move(change), n_after, after, true));
  built.build(n_after, after, true);
  check_same_halfedges(derived, built);
}

TEST_CASE("the halfedges of a level derived from the level before and its collapses are those built from its faces", "[pyramid][halfedges]")
{
  typedef SMR::internal::Index Index;
  const Index none = SMR::internal::invalid_index;
  std::vector<Mesh> meshes;
  meshes.push_back(smr_test::icosphere<Mesh>(3));
  meshes.push_back(smr_test::planar_grid<Mesh>(12, 0.2));   // a border
  {
    Mesh two = smr_test::icosphere<Mesh>(2);                 // two components, one with a border
    Mesh grid = smr_test::planar_grid<Mesh>(6, 0.1);
    CGAL::copy_face_graph(grid, two);
    meshes.push_back(two);
  }
  meshes.push_back(pinched_grids());
  for(const char* name : {"meshes/mushroom.off", "meshes/elephant-with-holes.off"})
  {
    Mesh m;
    if(smr_test::read_cgal_mesh(name, m))
      meshes.push_back(m);
  }
  for(const Mesh& m : meshes)
  {
    SMR::internal::Indexed_mesh<Mesh> im;
    SMR::internal::build_indexed_mesh(m, get(CGAL::vertex_index, m), im);
    std::vector<Index> tri = im.triangles;
    std::size_t n = im.number_of_vertices();
    std::vector<double> xyz;
    SMR::internal::read_coordinates(im.vertices, get(CGAL::vertex_point, m), smr_test::Kernel(), xyz);
    SMR::internal::Triangle_halfedges th;
    th.build(n, tri, true);
    std::size_t levels = 0, removed_faces = 0;
    while(n > 8 && levels < 40)
    {
      // the level's collapses, selected as decompose() selects them
      SMR::internal::Plane_quadrics quadrics;
      quadrics.initialize(th, xyz);
      std::vector<unsigned char> on_border, locked;
      SMR::internal::Index_array source_of_target;
      std::vector<SMR::internal::Collapse> accepted;
      SMR::internal::select_collapses(th, xyz.data(), [&](Index o, Index e) { return quadrics.cost(o, e); }, std::size_t(-1),
                                      on_border, locked, source_of_target, accepted);
      if(accepted.empty())
        break;
      // the collapses made on the face array: a face holding o and its target is removed (its
      // collapsed halfedge starts at o's corner for o -> e, at e's for e -> o), the others
      // renamed; the kept faces and the even rows numbered in order
      std::vector<Index> target_of(n, none);
      for(const SMR::internal::Collapse& c : accepted)
        target_of[c.o] = c.e;
      const std::size_t nf = tri.size() / 3;
      SMR::internal::Collapsed_faces change;
      change.face_after.assign(nf, none);
      std::vector<Index> new_row(n, none), next_tri;
      Index rows = 0;
      for(std::size_t v = 0; v < n; ++v)
        if(target_of[v] == none)
          new_row[v] = rows++;
      for(std::size_t f = 0; f < nf; ++f)
      {
        int odd = -1;
        for(int i = 0; i < 3; ++i)
          if(target_of[tri[3 * f + i]] != none)
          {
            REQUIRE(odd == -1);                                // no face holds two odd vertices
            odd = i;
          }
        const Index e = odd < 0 ? none : target_of[tri[3 * f + odd]];
        if(odd >= 0 && (tri[3 * f + (odd + 1) % 3] == e || tri[3 * f + (odd + 2) % 3] == e))
        {
          change.face_after[f] = SMR::internal::Collapsed_faces::removed_face + (tri[3 * f + (odd + 1) % 3] == e ? odd : (odd + 2) % 3);
          ++removed_faces;
          continue;
        }
        change.face_after[f] = static_cast<Index>(next_tri.size() / 3);
        for(int i = 0; i < 3; ++i)
          next_tri.push_back(new_row[i == odd ? e : tri[3 * f + i]]);
      }
      std::vector<double> next_xyz;
      for(std::size_t v = 0; v < n; ++v)
        if(target_of[v] == none)
          next_xyz.insert(next_xyz.end(), xyz.begin() + 3 * v, xyz.begin() + 3 * v + 3);
      th.keep_twins_only();                                    // what decompose() keeps of the level before
      SMR::internal::Triangle_halfedges derived, built;
      CHECK(derived.build_after_collapses(std::move(th), std::move(change), rows, next_tri, true));
      CHECK(th.twin.empty());                                  // freed once read
      CHECK(change.face_after.empty());
      built.build(rows, next_tri, true);
      check_same_halfedges(derived, built);
      th = std::move(built);
      tri.swap(next_tri);
      xyz.swap(next_xyz);
      n = rows;
      ++levels;
    }
    CHECK(levels >= 5);
    CHECK(removed_faces > 0);
  }
  // a level before with a repeated directed edge (0 -> 1 in two faces): no derivation, the
  // halfedges are built from the faces (first come, first served)
  const Index removed = SMR::internal::Collapsed_faces::removed_face;
  check_built_again({0, 1, 2, 1, 0, 3, 0, 1, 4}, 5, {0, 1, 2}, {0, 1, 2, 1, 0, 3, 0, 1, 4}, 5, true);
  // collapses against the rule, built from the faces: a removed face entered through its
  // collapsed edge (face 0, its collapsed halfedge 0 -> 1 at corner 0)
  check_built_again({0, 1, 2, 1, 0, 3}, 4, {removed + 0, 0}, {0, 1, 2}, 3, false);
  // two crossed collapses 0 -> 1 and 3 -> 2 (2 next to 0, 1 next to 3), which the selection
  // refuses: the removed faces (0, 1, 2) and (2, 1, 3) share their third edges (collapsed
  // halfedges at corners 0 and 2)
  check_built_again({0, 1, 2, 2, 1, 3, 0, 2, 4, 3, 1, 5}, 6, {removed + 0, removed + 2, 0, 1}, {0, 1, 2, 1, 0, 3}, 4, false);
}

TEST_CASE("the corners listed by source in parallel ranges are those of the sequential counting sort", "[pyramid][halfedges]")
{
  typedef SMR::internal::Index Index;
  // random faces over 20,000 vertices (several per vertex, any order): 300,000 corners
  CGAL::Random rng(3);
  const std::size_t n = 20000;
  std::vector<Index> tri;
  for(int f = 0; f < 100000; ++f)
    for(int c = 0; c < 3; ++c)
      tri.push_back(static_cast<Index>(rng.get_int(0, int(n))));
  std::vector<Index> offsets;
  SMR::internal::Index_array out, target, apex;
  SMR::internal::list_face_halfedges_by_source(n, tri, true, offsets, out, target, apex);
  // the reference: corners in increasing halfedge number within each source
  REQUIRE(offsets.size() == n + 1);
  REQUIRE(out.size() == tri.size());
  std::vector<Index> next(n, 0);
  for(Index h = 0; h < tri.size(); ++h)
  {
    const Index v = tri[h], k = offsets[v] + next[v]++;
    REQUIRE(k < offsets[v + 1]);
    CHECK(out[k] == h);
    CHECK(target[k] == tri[SMR::internal::Triangle_halfedges::next_in_face(h)]);
    CHECK(apex[k] == tri[SMR::internal::Triangle_halfedges::next_in_face(SMR::internal::Triangle_halfedges::next_in_face(h))]);
  }
  for(std::size_t v = 0; v < n; ++v)
    CHECK(offsets[v] + next[v] == offsets[v + 1]);
  // without apexes: the same corners and targets, no apex written
  {
    std::vector<Index> o2;
    SMR::internal::Index_array out2, t2, a2;
    SMR::internal::list_face_halfedges_by_source(n, tri, false, o2, out2, t2, a2);
    CHECK(o2 == offsets);
    CHECK(out2 == out);
    CHECK(t2 == target);
    CHECK(a2.empty());
  }
  // counted first on their own (as build_after_collapses() counts them beside its twins): each
  // vertex's number of corners, then the same lists from those counts
  {
    std::vector<Index> counts;
    SMR::internal::count_face_halfedges_by_source(n, tri, counts);
    REQUIRE(counts.size() == n + 1);
    CHECK(counts[0] == 0);
    std::vector<Index> corners_of(n, 0);                     // the reference: one count per corner
    for(Index v : tri)
      ++corners_of[v];
    CHECK(std::equal(corners_of.begin(), corners_of.end(), counts.begin() + 1));
    SMR::internal::Index_array out2, t2, a2;
    SMR::internal::list_face_halfedges_by_source(n, tri, true, counts, out2, t2, a2, nullptr, true);
    CHECK(counts == offsets);
    CHECK(out2 == out);
    CHECK(t2 == target);
    CHECK(a2 == apex);
  }
#ifdef CGAL_LINKED_WITH_TBB
  for(int threads : {1, 3, 8})   // other numbers of ranges (one: the single-range case): the same lists
    for(bool apexes : {true, false})
    {
      tbb::task_arena arena(threads);
      std::vector<Index> o2;
      SMR::internal::Index_array out2, t2, a2;
      arena.execute([&] { SMR::internal::list_face_halfedges_by_source(n, tri, apexes, o2, out2, t2, a2); });
      CHECK(o2 == offsets);
      CHECK(out2 == out);
      CHECK(t2 == target);
      CHECK((apexes ? a2 == apex : a2.empty()));
    }
#endif
}

// The expansion of the face arrays (vertex splits on arrays), level by level from the coarsest
// mesh, in parallel blocks, against a plain sequential statement of it: face p of M_k is the
// removed face r if p is the r-th removed position, else the next kept face of M_{k+1} with
// its rows renamed to those of M_k; then the odd vertices back at their corners. Every level of
// the faces of a mesh large enough for several blocks, on 1, 2 and 3 threads.
TEST_CASE("the face arrays expanded in parallel blocks are those of the sequential vertex splits", "[pyramid][faces]")
{
  typedef SMR::internal::Index Index;
  Mesh m = smr_test::planar_grid<Mesh>(90, 0.3);           // 8,281 vertices, 16,200 faces
  const SMR::Pyramid<Mesh> pyr = SMR::decompose(m);
  REQUIRE(pyr.number_of_levels() > 3);
  REQUIRE(pyr.number_of_faces(0) > 2 * 4096);
  auto expanded_sequentially = [&](const SMR::internal::Pyramid_level& lev, const std::vector<Index>& F) {
    std::vector<Index> G;
    std::size_t kept = 0, r = 0;
    const std::size_t nf = F.size() / 3 + lev.removed_face_positions.size();
    for(std::size_t p = 0; p < nf; ++p)
      if(r < lev.removed_face_positions.size() && lev.removed_face_positions[r] == p)
      {
        G.insert(G.end(), lev.removed_faces.begin() + 3 * r, lev.removed_faces.begin() + 3 * r + 3);
        ++r;
      }
      else
      {
        for(int c = 0; c < 3; ++c)
          G.push_back(lev.even_rows[F[3 * kept + c]]);
        ++kept;
      }
    for(std::size_t q = 0; q < lev.renamed_corners.size(); ++q)
      G[lev.renamed_corners[q]] = lev.renamed_vertices[q];
    return G;
  };
  std::vector<std::vector<Index> > reference(pyr.number_of_levels() + 1);
  reference[pyr.number_of_levels()] = pyr.coarse_faces();
  for(std::size_t k = pyr.number_of_levels(); k-- > 0; )
    reference[k] = expanded_sequentially(pyr.levels()[k], reference[k + 1]);
  REQUIRE(reference[0].size() == 3 * pyr.number_of_faces(0));
  // level 0 is the input's faces (rows are the input's vertex numbers), each in some rotation
  std::multiset<std::array<Index, 3> > input_faces, level0_faces;
  auto rotated = [](Index a, Index b, Index c) {
    return a < b && a < c ? std::array<Index, 3>{a, b, c} : (b < c ? std::array<Index, 3>{b, c, a} : std::array<Index, 3>{c, a, b});
  };
  for(auto f : faces(m))
  {
    std::vector<Index> v;
    for(auto x : CGAL::vertices_around_face(halfedge(f, m), m))
      v.push_back(Index(x.idx()));
    input_faces.insert(rotated(v[0], v[1], v[2]));
  }
  for(std::size_t p = 0; p < reference[0].size(); p += 3)
    level0_faces.insert(rotated(reference[0][p], reference[0][p + 1], reference[0][p + 2]));
  CHECK(level0_faces == input_faces);
  auto expand_all = [&] {
    std::vector<Index> F = pyr.coarse_faces(), scratch;
    bool same = true;
    for(std::size_t k = pyr.number_of_levels(); k-- > 0; )
    {
      SMR::internal::expand_faces(pyr.levels()[k], F, scratch);
      same = same && F == reference[k];
    }
    return same;
  };
  CHECK(expand_all());
#ifdef CGAL_LINKED_WITH_TBB
  for(int threads : {1, 2, 3})
  {
    tbb::task_arena arena(threads);
    bool same = false;
    arena.execute([&] { same = expand_all(); });
    CHECK(same);
  }
#endif
}

// The in-place moves that shrink a level's arrays, in parallel waves (move_down_in_waves()),
// against the copy into a new array: kept items at random with several rates (none removed,
// a long kept prefix, a few removed, half, all but a few), as blocks of any size see them (the
// faces' move: blocks of positions, their kept items numbered by a prefix sum) and as a level's
// rows see them (keep_values_of_next_level(), dimensions 1 and 3, against values_of_next_level()),
// on 1, 2, 3 and 8 threads.
TEST_CASE("moves towards the start in parallel waves give the sequential move's arrays", "[pyramid][faces]")
{
  typedef SMR::internal::Index Index;
  std::mt19937 rng(15);
  auto kept_positions = [&](std::size_t n, double removed_rate, std::size_t kept_prefix) {
    std::bernoulli_distribution removed(removed_rate);
    std::vector<Index> kept;
    for(std::size_t p = 0; p < n; ++p)
      if(p < kept_prefix || !removed(rng))
        kept.push_back(Index(p));
    return kept;
  };
  // blocks of `block` positions of an array of n items, the kept ones moved down in order
  auto moved_in_blocks = [](const std::vector<Index>& kept, std::size_t n, std::size_t block) {
    std::vector<Index> a(n);
    std::iota(a.begin(), a.end(), Index(1000));
    std::vector<unsigned char> is_kept(n, 0);
    for(Index p : kept)
      is_kept[p] = 1;
    const std::size_t blocks = (n + block - 1) / block;
    std::vector<std::size_t> kept_before(blocks + 1, 0);
    for(std::size_t b = 0; b < blocks; ++b)
    {
      kept_before[b + 1] = kept_before[b];
      for(std::size_t p = b * block; p < (std::min)(n, (b + 1) * block); ++p)
        kept_before[b + 1] += is_kept[p];
    }
    SMR::internal::move_down_in_waves(blocks, [&](std::size_t b) { return b * block; },
                                      [&](std::size_t b) { return kept_before[b + 1]; },
                                      [&](std::size_t b) {
                                        std::size_t to = kept_before[b];
                                        for(std::size_t p = b * block; p < (std::min)(n, (b + 1) * block); ++p)
                                          if(is_kept[p])
                                            a[to++] = a[p];
                                      });
    a.resize(kept_before[blocks]);
    return a;
  };
  struct Case { std::size_t n; double rate; std::size_t prefix; };
  const std::vector<Case> cases = {{1, 0., 0}, {50000, 0., 0}, {50000, 0.2, 20000}, {50000, 0.01, 0},
                                   {200000, 0.18, 0}, {60000, 0.5, 0}, {60000, 0.99, 0}, {5000, 0.2, 0}};
  for(const Case& cs : cases)
  {
    const std::vector<Index> kept = kept_positions(cs.n, cs.rate, cs.prefix);
    std::vector<Index> expected;
    for(Index p : kept)
      expected.push_back(Index(1000) + p);
    SMR::internal::Pyramid_level lev;
    lev.even_rows = kept;
    std::vector<std::vector<double> > values(2), expected_values(2);
    for(std::size_t d : {std::size_t(1), std::size_t(3)})
    {
      std::vector<double>& v = values[d / 3];
      v.resize(cs.n * d);
      for(std::size_t i = 0; i < v.size(); ++i)
        v[i] = double(i) + 0.5;
      SMR::internal::values_of_next_level(lev, d, v, expected_values[d / 3]);
    }
    auto all_moves = [&] {
      bool same = true;
      for(std::size_t block : {std::size_t(1), std::size_t(7), std::size_t(4096)})
        same = same && moved_in_blocks(kept, cs.n, block) == expected;
      for(std::size_t d : {std::size_t(1), std::size_t(3)})
      {
        std::vector<double> v = values[d / 3];
        SMR::internal::keep_values_of_next_level(lev, d, v);
        same = same && v == expected_values[d / 3];
      }
      return same;
    };
    INFO("items " << cs.n << ", removed " << cs.rate << ", kept prefix " << cs.prefix);
    CHECK(all_moves());
#ifdef CGAL_LINKED_WITH_TBB
    for(int threads : {1, 2, 3, 8})
    {
      tbb::task_arena arena(threads);
      bool same = false;
      arena.execute([&] { same = all_moves(); });
      CHECK(same);
    }
#endif
  }
}

namespace {
// a sphere of 2,562 vertices and a grid of 1,681 with a border, their vertices moved by a
// seeded noise (non-trivial costs, no exact ties)
std::vector<Mesh> noisy_sphere_and_grid(unsigned seed)
{
  std::vector<Mesh> meshes;
  meshes.push_back(smr_test::icosphere<Mesh>(4));
  meshes.push_back(smr_test::planar_grid<Mesh>(40, 0.3));
  CGAL::Random rng(seed);
  for(Mesh& m : meshes)
    for(auto v : vertices(m))
      m.point(v) = m.point(v) + Vector_3(rng.get_double(-.01, .01), rng.get_double(-.01, .01), rng.get_double(-.01, .01));
  return meshes;
}
} // namespace

TEST_CASE("the look-ahead greedy selection and its parallel rounds take the collapses of the plain greedy loop", "[pyramid][cost]")
{
  typedef SMR::internal::Index Index;
  for(const Mesh& m : noisy_sphere_and_grid(5))
  {
    const Input_quadrics in(m);
    const SMR::internal::Triangle_halfedges& th = in.th;
    const std::vector<double>& xyz = in.xyz;
    auto cost = [&](Index o, Index e) { return in.quadrics.cost(o, e); };
    // the loop with look-ahead, and the parallel rounds with windows of 1, 7, 64 and all candidates
    for(const std::size_t window : {SMR::internal::sequential_selection, std::size_t(1), std::size_t(7), std::size_t(64),
                                    std::size_t(1) << 30})
    for(const std::size_t budget : {std::size_t(-1), std::size_t(25)})
    {
      std::vector<unsigned char> on_border, locked;
      SMR::internal::Index_array source_of_target;
      std::vector<SMR::internal::Collapse> accepted;
      SMR::internal::select_collapses(th, xyz.data(), cost, budget, on_border, locked, source_of_target, accepted, window);
      {
        // halfedges without their ends listed (decompose()'s), the ends read from the faces:
        // the same collapses
        SMR::internal::Triangle_halfedges bare;
        bare.build(in.im.number_of_vertices(), in.im.triangles, true, false);
        REQUIRE(!bare.has_ends());
        REQUIRE(bare.number_of_halfedges() == th.source.size());
        REQUIRE((bare.twin == th.twin && bare.out == th.out && bare.out_target == th.out_target && bare.out_apex == th.out_apex));
        std::vector<unsigned char> on_border2, locked2;
        SMR::internal::Index_array source_of_target2;
        std::vector<SMR::internal::Collapse> accepted2;
        SMR::internal::select_collapses(bare, xyz.data(), cost, budget, on_border2, locked2, source_of_target2, accepted2, window,
                                        SMR::internal::Run_in_place(), &in.im.triangles);
        CHECK(on_border2 == on_border);
        REQUIRE(accepted2.size() == accepted.size());
        for(std::size_t i = 0; i < accepted.size(); ++i)
          CHECK((accepted2[i].o == accepted[i].o && accepted2[i].e == accepted[i].e));
      }
      // the reference: the th.n cheapest admissible halfedges in (cost, halfedge) order (half as
      // many again each time fewer than th.n / 16 + 1 are taken), taken when the source is in no
      // taken source's closed 1-ring, the target is no taken target, no taken o' -> e' has e
      // next to o' and e' next to o, and the tests pass (each rule checked against every taken
      // collapse)
      std::vector<std::pair<double, Index> > order;
      for(Index h = 0; h < th.source.size(); ++h)
        if(!on_border[th.source[h]] || th.is_border_edge(h))
          order.emplace_back(*cost(th.source[h], th.target[h]), h);
      std::sort(order.begin(), order.end());
      auto adjacent = [&](Index a, Index b) {
        for(Index k = th.out_offsets[a]; k < th.out_offsets[a + 1]; ++k)
          if(th.out_target[k] == b) return true;
        return false;
      };
      auto admitted = [&](const std::vector<SMR::internal::Collapse>& taken, Index o, Index e) {
        for(const SMR::internal::Collapse& t : taken)
          if(t.o == o || adjacent(t.o, o) || t.e == e || (adjacent(t.o, e) && adjacent(o, t.e)))
            return false;
        return true;
      };
      std::vector<SMR::internal::Collapse> expected;
      std::size_t target_next_to_another_source = 0;
      std::size_t considered = (std::min)(order.size(), std::size_t(th.n));
      for(std::size_t i = 0; i < order.size(); ++i)
      {
        if(i == considered)
        {
          if(expected.size() >= th.n / 16 + 1) break;
          considered = (std::min)(order.size(), considered + (considered + 1) / 2);
        }
        const auto& c = order[i];
        const Index h = c.second, o = th.source[h], e = th.target[h];
        if(expected.size() >= budget || !admitted(expected, o, e)
           || !SMR::internal::satisfies_link_condition(th, h, o, e, on_border) || SMR::internal::does_collapse_flip_a_face(th, o, e, xyz.data()))
          continue;
        for(const SMR::internal::Collapse& t : expected)
          target_next_to_another_source += adjacent(t.o, e) ? 1 : 0;
        expected.push_back(SMR::internal::Collapse{o, e});
      }
      REQUIRE(accepted.size() == expected.size());
      if(budget != 25)
        CHECK(target_next_to_another_source > 0);   // the rule is used: targets in another source's 1-ring
      if(budget == 25)
        CHECK(accepted.size() == 25);
      else
        CHECK(accepted.size() > th.n / 16);
      for(std::size_t i = 0; i < accepted.size(); ++i)
      {
        CHECK(accepted[i].o == expected[i].o);
        CHECK(accepted[i].e == expected[i].e);
      }
    }
  }
}

TEST_CASE("the greedy loop takes the same collapses from the candidates' ends as from their halfedges", "[pyramid][cost]")
{
  typedef SMR::internal::Index Index;
  for(const Mesh& m : noisy_sphere_and_grid(9))                 // the grid's border halfedges among the candidates
  {
    const Input_quadrics in(m);
    const SMR::internal::Triangle_halfedges& th = in.th;
    REQUIRE(!th.repeated_directed_edge);
    auto cost = [&](Index o, Index e) { return in.quadrics.cost(o, e); };
    // as decompose() selects (n considered, at least n / 16 + 1 taken), then a front of n / 8
    // keys sorted and considered and n collapses asked for: the loop looks further and sorts
    // the rest of the candidates (which the ends version converts too)
    for(const std::size_t wanted : {std::size_t(th.n), std::size_t(th.n / 8)})
    {
      // 0: keys; 1: ends; 2: ends, the halfedges built without their ends (as decompose()
      // builds them): every end, the rest's included, read from the face array
      SMR::internal::Triangle_halfedges bare;
      bare.build(in.im.number_of_vertices(), in.im.triangles, true, false);
      REQUIRE(!bare.has_ends());
      REQUIRE(bare.number_of_halfedges() == th.source.size());
      std::vector<SMR::internal::Collapse> taken[3];
      for(const int variant : {0, 1, 2})
      {
        const bool as_ends = variant > 0;
        const SMR::internal::Triangle_halfedges& t = variant == 2 ? bare : th;
        const std::vector<Index>* faces = variant == 2 ? &in.im.triangles : nullptr;
        std::vector<unsigned char> on_border;
        SMR::internal::Candidate_key key(0);
        std::size_t all = 0, rests = 0;
        std::uint64_t limit = 0;
        SMR::internal::Key_array candidates = SMR::internal::sorted_candidates(t, cost, on_border, key, wanted, all, limit, faces);
        const std::size_t sorted = candidates.size();
        if(as_ends)
        {
          const SMR::internal::Key_array keys = candidates;
          SMR::internal::candidate_ends(t, key, candidates, 0, faces);
          for(std::size_t i = 0; i < sorted; ++i)        // the ends of every candidate's halfedge
          {
            const Index o = SMR::internal::source_of_ends(candidates[i]), e = SMR::internal::target_of_ends(candidates[i]);
            REQUIRE(o == th.source[key.halfedge(keys[i])]);
            REQUIRE(e == th.target[key.halfedge(keys[i])]);
          }
        }
        auto sort_rest = [&] {
          const std::size_t first = candidates.size();
          SMR::internal::sort_candidate_rest(t, cost, on_border, key, limit, candidates);
          if(as_ends)
          {
            const SMR::internal::Key_array keys(candidates.begin() + std::ptrdiff_t(first), candidates.end());
            SMR::internal::candidate_ends(t, key, candidates, first, faces);
            for(std::size_t i = first; i < candidates.size(); ++i)
            {
              REQUIRE(SMR::internal::source_of_ends(candidates[i]) == th.source[key.halfedge(keys[i - first])]);
              REQUIRE(SMR::internal::target_of_ends(candidates[i]) == th.target[key.halfedge(keys[i - first])]);
            }
          }
          ++rests;
        };
        std::vector<unsigned char> locked(th.n, 0);
        SMR::internal::Index_array source_of_target(th.n);
        SMR::internal::take_greedily(t, in.xyz.data(), candidates, sorted, all, sort_rest, key, std::size_t(-1), on_border,
                                     locked, source_of_target, taken[variant], wanted,
                                     wanted == th.n ? th.n / 16 + 1 : th.n, as_ends);
        CHECK(rests == (wanted < th.n ? 1u : 0u));
      }
      REQUIRE(taken[0].size() > th.n / 16);
      for(const int variant : {1, 2})
      {
        REQUIRE(taken[0].size() == taken[variant].size());
        for(std::size_t i = 0; i < taken[0].size(); ++i)
        {
          CHECK(taken[0][i].o == taken[variant][i].o);
          CHECK(taken[0][i].e == taken[variant][i].e);
        }
      }
    }
  }
}
