// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The package's foundation: named parameters, attribute traits, input validation.

#include <catch2/catch.hpp>

#include <smr_test_utils.h>

#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>

#include <limits>
#include <string>
#include <type_traits>

namespace SMR = CGAL::Surface_mesh_multiresolution;
using smr_test::Kernel;
using smr_test::Mesh;
using smr_test::Point_3;
using smr_test::Vector_3;

TEST_CASE("package parameters chain with CGAL's in any order", "[parameters]")
{
  Mesh m = smr_test::icosphere<Mesh>(1);
  auto shifted = m.add_property_map<Mesh::Vertex_index, Point_3>("v:shifted").first;
  for(auto v : vertices(m)) shifted[v] = m.point(v) + Vector_3(10, 0, 0);

  const auto np1 = SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme::UNIFORM)
                     .vertex_point_map(shifted).number_of_iterations(2u).relax_geometry(true);
  const auto np2 = SMR::parameters::number_of_iterations(2u).relax_geometry(true)
                     .vertex_point_map(shifted).relaxation_scheme(SMR::Relaxation_scheme::UNIFORM);
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::choose_parameter;
  CHECK(choose_parameter(get_parameter(np1, SMR::internal_np::relaxation_scheme), SMR::Relaxation_scheme::CURVATURE)
        == SMR::Relaxation_scheme::UNIFORM);
  CHECK(choose_parameter(get_parameter(np2, CGAL::internal_np::number_of_iterations), 1u) == 2u);
  static_assert(CGAL::parameters::is_default_parameter<decltype(np1), SMR::internal_np::vertex_attribute_maps_t>::value, "");
  static_assert(!CGAL::parameters::is_default_parameter<decltype(np1), SMR::internal_np::relax_geometry_t>::value, "");

  // both orders do the same thing: relax the shifted copy, leave the points alone
  Mesh a = m, b = m;
  auto sa = a.property_map<Mesh::Vertex_index, Point_3>("v:shifted").first;
  auto sb = b.property_map<Mesh::Vertex_index, Point_3>("v:shifted").first;
  SMR::relax(a, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme::UNIFORM).vertex_point_map(sa).number_of_iterations(2u));
  SMR::relax(b, SMR::parameters::number_of_iterations(2u).vertex_point_map(sb).relaxation_scheme(SMR::Relaxation_scheme::UNIFORM));
  CHECK(smr_test::positions_in_order(a) == smr_test::positions_in_order(m));
  for(auto v : vertices(a)) CHECK(sa[v] == sb[v]);

  // a plain CGAL pack is accepted; the package's parameters take their defaults (curvature)
  Mesh c = m, d = m;
  SMR::relax(c, CGAL::parameters::number_of_iterations(1));
  SMR::relax(d, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme::CURVATURE));
  CHECK(smr_test::positions_in_order(c) == smr_test::positions_in_order(d));

  // the package's pack goes into stock CGAL functions
  auto vnm = get(CGAL::dynamic_vertex_property_t<Vector_3>(), m);
  CGAL::Polygon_mesh_processing::compute_vertex_normals(m, vnm, np1);
  for(auto v : vertices(m)) CHECK(get(vnm, v) * (shifted[v] - Point_3(10, 0, 0)) > 0.9);   // the sphere's normals
  Mesh e = m;
  const int removed = CGAL::Surface_mesh_simplification::edge_collapse(e, CGAL::Surface_mesh_simplification::Count_stop_predicate<Mesh>(30),
      SMR::parameters::relax_geometry(false).get_cost(CGAL::Surface_mesh_simplification::Edge_length_cost<Mesh>()));
  CHECK(removed > 0);
}

TEST_CASE("attribute traits map channel values to doubles and back", "[attributes]")
{
  using CT = SMR::Attribute_traits<CGAL::IO::Color>;
  static_assert(CT::dimension == 4, "r, g, b, alpha");
  const CGAL::IO::Color c(1, 2, 250, 128);
  CHECK(CT::from_array(CT::to_array(c)) == c);
  // clamped to [0,255] and rounded to the nearest integer
  CHECK(CT::from_array({{300., -5., 127.4, 254.6}}) == CGAL::IO::Color(255, 0, 127, 255));
  CHECK(CT::from_array({{std::numeric_limits<double>::quiet_NaN(), 0.49, 0.51, 255.49}}) == CGAL::IO::Color(0, 0, 1, 255));

  using PT = SMR::Attribute_traits<Kernel::Point_2>;
  static_assert(PT::dimension == 2, "");
  CHECK(PT::from_array(PT::to_array(Kernel::Point_2(0.25, -3.))) == Kernel::Point_2(0.25, -3.));
  using VT = SMR::Attribute_traits<Vector_3>;
  CHECK(VT::from_array(VT::to_array(Vector_3(1, 2, 3))) == Vector_3(1, 2, 3));
  using P3 = SMR::Attribute_traits<Point_3>;
  CHECK(P3::from_array(P3::to_array(Point_3(1, 2, 3))) == Point_3(1, 2, 3));
  using AT = SMR::Attribute_traits<std::array<double, 5> >;
  static_assert(AT::dimension == 5, "");
  const std::array<double, 5> a{{1, 2, 3, 4, 5}};
  CHECK(AT::from_array(AT::to_array(a)) == a);
  using AF = SMR::Attribute_traits<std::array<float, 2> >;
  CHECK(AF::from_array(AF::to_array({{0.5f, 2.f}})) == std::array<float, 2>{{0.5f, 2.f}});
  using D = SMR::Attribute_traits<double>;
  CHECK(D::from_array(D::to_array(0.1)) == 0.1);
  using F = SMR::Attribute_traits<float>;
  CHECK(F::from_array(F::to_array(0.1f)) == 0.1f);
}

TEST_CASE("several channels of mixed types relax as if relaxed one by one", "[attributes][channels]")
{
  Mesh m = smr_test::icosphere<Mesh>(2);
  auto uv = m.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  auto t = m.add_property_map<Mesh::Vertex_index, float>("v:temperature").first;
  auto n = m.add_property_map<Mesh::Vertex_index, Vector_3>("v:normal").first;
  for(auto v : vertices(m))
  {
    const Point_3 p = m.point(v);
    uv[v] = Kernel::Point_2(std::atan2(p.y(), p.x()), p.z());
    t[v] = float(20. + 5. * p.x() * p.y());
    n[v] = p - CGAL::ORIGIN;
  }
  Mesh all = m, one = m;
  auto uv_a = all.property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  auto t_a = all.property_map<Mesh::Vertex_index, float>("v:temperature").first;
  auto n_a = all.property_map<Mesh::Vertex_index, Vector_3>("v:normal").first;
  SMR::relax(all, SMR::parameters::number_of_iterations(3).vertex_attribute_maps(std::make_tuple(uv_a, t_a, n_a)));
  auto uv_o = one.property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  auto t_o = one.property_map<Mesh::Vertex_index, float>("v:temperature").first;
  auto n_o = one.property_map<Mesh::Vertex_index, Vector_3>("v:normal").first;
  Mesh g1 = one, g2 = one, g3 = one;   // the geometry moves along in each run, as it did above
  SMR::relax(g1, SMR::parameters::number_of_iterations(3).vertex_attribute_maps(g1.property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first));
  SMR::relax(g2, SMR::parameters::number_of_iterations(3).vertex_attribute_maps(std::make_tuple(g2.property_map<Mesh::Vertex_index, float>("v:temperature").first)));
  SMR::relax(g3, SMR::parameters::number_of_iterations(3).vertex_attribute_maps(std::make_tuple(g3.property_map<Mesh::Vertex_index, Vector_3>("v:normal").first)));
  CHECK(smr_test::positions_in_order(g1) == smr_test::positions_in_order(all));
  auto uv1 = g1.property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  auto t2 = g2.property_map<Mesh::Vertex_index, float>("v:temperature").first;
  auto n3 = g3.property_map<Mesh::Vertex_index, Vector_3>("v:normal").first;
  for(auto v : vertices(all))
  {
    CHECK(uv_a[v] == uv1[v]);
    CHECK(t_a[v] == t2[v]);
    CHECK(n_a[v] == n3[v]);
    CHECK(uv_o[v] == uv[v]);   // `one` itself was untouched
  }
  (void)t_o; (void)n_o;
}

TEST_CASE("bad input gives clear errors", "[input]")
{
  SECTION("a quad face")
  {
    Mesh quad;
    CGAL::make_quad(Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(1, 1, 0), Point_3(0, 1, 0), quad);
    REQUIRE_THROWS_AS(SMR::relaxation_operator(quad), std::invalid_argument);
    REQUIRE_THROWS_WITH(SMR::relax(quad), Catch::Contains("face 0") && Catch::Contains("not a triangle"));
  }
  SECTION("a non-finite coordinate")
  {
    Mesh m = smr_test::icosphere<Mesh>(1);
    const auto before = smr_test::positions_in_order(m);
    m.point(Mesh::Vertex_index(5)) = Point_3(0, std::numeric_limits<double>::quiet_NaN(), 0);
    REQUIRE_THROWS_WITH(SMR::relax(m), Catch::Contains("vertex 5") && Catch::Contains("non-finite coordinate"));
    m.point(Mesh::Vertex_index(5)) = Point_3(std::numeric_limits<double>::infinity(), 0, 0);
    REQUIRE_THROWS_AS(SMR::relaxation_operator(m), std::invalid_argument);
  }
  SECTION("a non-finite attribute leaves the mesh untouched")
  {
    Mesh m = smr_test::icosphere<Mesh>(1);
    auto f = m.add_property_map<Mesh::Vertex_index, double>("v:f", 1.).first;
    f[Mesh::Vertex_index(7)] = std::numeric_limits<double>::quiet_NaN();
    const auto before = smr_test::positions_in_order(m);
    REQUIRE_THROWS_WITH(SMR::relax(m, SMR::parameters::vertex_attribute_maps(std::make_tuple(f))),
                        Catch::Contains("channel 1") && Catch::Contains("vertex 7"));
    CHECK(smr_test::positions_in_order(m) == before);
  }
  SECTION("an operator applied to arrays of the wrong size")
  {
    const Mesh m = smr_test::icosphere<Mesh>(1);
    const auto R = SMR::relaxation_operator(m);
    std::vector<double> in(3 * num_vertices(m) - 1), out;
    REQUIRE_THROWS_AS(R.apply(in, out, 3), std::invalid_argument);
    Mesh other = smr_test::icosphere<Mesh>(2);
    REQUIRE_THROWS_AS(R.apply(other), std::invalid_argument);
  }
}

TEST_CASE("a Surface_mesh with removed, not garbage-collected elements", "[input][garbage]")
{
  Mesh m = smr_test::icosphere<Mesh>(2);
  Mesh clean = m;
  // remove one vertex's star and fill the hole again: the mesh keeps dead elements
  const Mesh::Vertex_index v0(0);
  const Mesh::Halfedge_index h = CGAL::Euler::remove_center_vertex(halfedge(v0, m), m);
  CGAL::Euler::add_center_vertex(h, m);
  REQUIRE(m.has_garbage());
  REQUIRE(m.number_of_vertices() == clean.number_of_vertices());
  const auto R = SMR::relaxation_operator(m);
  CHECK(R.number_of_vertices() == m.number_of_vertices());
  for(auto v : R.vertices()) CHECK(!m.is_removed(v));
  SMR::relax(m);
  for(auto v : vertices(m)) CHECK(std::isfinite(m.point(v).x()));
}

TEST_CASE("the index view of a Surface_mesh read in parallel is the face loop's", "[input][index-view]")
{
  // A Surface_mesh with its own vertex indices and no removed element is read in parallel
  // (rows = indices, face f at 3 f); any other vertex index map takes the loop over faces(tm).
  // Both give the same arrays, and on defects the same first face, across parallel blocks.
  typedef SMR::internal::Indexed_mesh<Mesh> View;
  Mesh m = smr_test::icosphere<Mesh>(5);   // 20480 faces: several blocks
  REQUIRE(m.number_of_faces() > 2 * 8192);   // blocks of 8192 faces: the defects below lie in two
  auto ids = m.add_property_map<Mesh::Vertex_index, std::size_t>("v:test_id").first;
  for(auto v : vertices(m)) ids[v] = v.idx();
  static_assert(SMR::internal::Is_surface_mesh_with_own_indices<Mesh, decltype(get(CGAL::vertex_index, m))>::value, "");
  static_assert(!SMR::internal::Is_surface_mesh_with_own_indices<Mesh, decltype(ids)>::value, "");
  View fast, loop;
  SMR::internal::build_indexed_mesh(m, get(CGAL::vertex_index, m), fast);
  SMR::internal::build_indexed_mesh(m, ids, loop);
  CHECK(fast.triangles == loop.triangles);
  CHECK(fast.vertices == loop.vertices);
  CHECK(fast.row_of == loop.row_of);
  CHECK(fast.triangles.size() == 3 * m.number_of_faces());

  // faces that repeat a vertex, in two blocks: both paths name the first, with the same words
  Mesh bad = m;
  auto bad_ids = bad.property_map<Mesh::Vertex_index, std::size_t>("v:test_id").first;
  for(std::size_t f : {std::size_t(17000), std::size_t(9000)})
  {
    const Mesh::Halfedge_index h = bad.halfedge(Mesh::Face_index(static_cast<Mesh::size_type>(f)));
    bad.set_target(h, bad.target(bad.next(h)));   // face f: its first two targets equal
  }
  std::string fast_error, loop_error;
  try { View v; SMR::internal::build_indexed_mesh(bad, get(CGAL::vertex_index, bad), v); } catch(const std::invalid_argument& e) { fast_error = e.what(); }
  try { View v; SMR::internal::build_indexed_mesh(bad, bad_ids, v); } catch(const std::invalid_argument& e) { loop_error = e.what(); }
  CHECK(fast_error == loop_error);
  CHECK(fast_error.find("face 9000 ") != std::string::npos);
  CHECK(fast_error.find("repeats a vertex") != std::string::npos);
}

TEST_CASE("large blocks freed inside a Block_pool_scope are reused, trimmed and given back at its end", "[memory]")
{
  typedef SMR::internal::Block_pool Pool;
  typedef SMR::internal::Uninitialized_vector<double> Doubles;
  Pool& pool = Pool::instance();
  const std::size_t big = Pool::default_kept_bytes / sizeof(double);   // doubles in the smallest kept block
  REQUIRE(pool.kept_bytes() == 0);
  {
    Doubles a(big);                                // outside any scope: given back at once
  }
  CHECK(pool.kept_bytes() == 0);
  {
    const SMR::internal::Block_pool_scope scope;
    const double* first = nullptr;
    {
      Doubles a(big + 1000);
      first = a.data();
    }
    CHECK(pool.kept_bytes() == (big + 1000) * sizeof(double));
    const std::size_t reuses = pool.reuses();
    {
      Doubles b(big);                              // held by the kept block, within a quarter: taken as it is
      CHECK(b.data() == first);
      CHECK(pool.reuses() == reuses + 1);
      CHECK(Pool::size(b.data()) == (big + 1000) * sizeof(double));
      CHECK(pool.kept_bytes() == 0);
    }
    {
      Doubles c(big / 8);                          // 4 MiB: the block's tail is given back
      CHECK(Pool::size(c.data()) == big / 8 * sizeof(double));
      CHECK(pool.kept_bytes() == 0);
      SMR::internal::Uninitialized_vector<double> small(100);   // under 1 MiB: never from the pool
      CHECK(Pool::size(small.data()) == 100 * sizeof(double));
    }
    CHECK(pool.kept_bytes() == 0);                 // the 4 MiB block is not kept (glibc reuses such blocks)
    {
      Doubles x(big), y(big);
      x[0] = y[0] = 1.;
    }
    CHECK(pool.kept_bytes() == 2 * big * sizeof(double));
    {
      Doubles z(3 * big);                          // no kept block holds it: they are given back first
      CHECK(pool.kept_bytes() == 0);
      {
        const SMR::internal::Block_pool_scope nested;
        Doubles w(std::move(z));
      }
      CHECK(pool.kept_bytes() == 3 * big * sizeof(double));   // kept until the outer scope ends
    }
  }
  CHECK(pool.kept_bytes() == 0);
  Doubles outlives;
  {
    const SMR::internal::Block_pool_scope scope;
    outlives.resize(big);                          // made in a scope, freed after it: freed, not kept
  }
  outlives = Doubles();
  CHECK(pool.kept_bytes() == 0);
}

TEST_CASE("a large request that no kept block holds grows one; small arrays do not cut down blocks of 64 MiB", "[memory]")
{
  typedef SMR::internal::Block_pool Pool;
  typedef SMR::internal::Uninitialized_vector<double> Doubles;
  Pool& pool = Pool::instance();
  const std::size_t big = Pool::default_kept_bytes / sizeof(double);   // 32 MiB of doubles
  REQUIRE(pool.kept_bytes() == 0);
  {
    const SMR::internal::Block_pool_scope scope;
    {
      Doubles a(big), b(big), c(big);
      a[0] = b[0] = c[0] = 1.;
    }
    REQUIRE(pool.kept_bytes() == 3 * big * sizeof(double));
    const std::size_t reuses = pool.reuses();
    {
      Doubles d(2 * big);                          // none holds it: one block grows, one goes back
      CHECK(pool.reuses() == reuses + 1);
      CHECK(Pool::size(d.data()) == 2 * big * sizeof(double));
      CHECK(pool.kept_bytes() == big * sizeof(double));   // held in all: 3 blocks' bytes, as before
      d[2 * big - 1] = 2.;                         // the grown block is usable to its end
      CHECK(d[2 * big - 1] == 2.);
    }
    CHECK(pool.kept_bytes() == 3 * big * sizeof(double));
    {
      // a 4 MiB array takes the 32 MiB block (cut down), never the 64 MiB one
      Doubles e(big / 8), f(big / 8);
      CHECK(Pool::size(e.data()) == big / 8 * sizeof(double));
      CHECK(Pool::size(f.data()) == big / 8 * sizeof(double));
      CHECK(pool.kept_bytes() == 2 * big * sizeof(double));
      Doubles g(5 * big / 4);                      // a large one takes it, cut down to its size
      CHECK(Pool::size(g.data()) == 5 * big / 4 * sizeof(double));
      CHECK(pool.kept_bytes() == 0);
    }
  }
  CHECK(pool.kept_bytes() == 0);
}
