// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The relaxation operators of Roy et al., Section 2 (Eq. 1-3): properties of the maths.

#include <catch2/catch.hpp>

#include <smr_test_utils.h>

#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <set>
#include <vector>

namespace SMR = CGAL::Surface_mesh_multiresolution;
using smr_test::Mesh;
using smr_test::Polyhedron;
using smr_test::Point_3;
using smr_test::Vector_3;

namespace {

const SMR::Relaxation_scheme all_schemes[] = {SMR::Relaxation_scheme::CURVATURE,
                                              SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE,
                                              SMR::Relaxation_scheme::UNIFORM};

const char* name(SMR::Relaxation_scheme s)
{
  return s == SMR::Relaxation_scheme::CURVATURE ? "curvature"
       : s == SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE ? "SOD" : "uniform";
}

template <typename TM>
std::vector<double> coordinates(const TM& tm)
{
  std::vector<double> xyz;
  for(auto v : vertices(tm))
  {
    const Point_3 p = get(CGAL::vertex_point, tm, v);
    xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  }
  return xyz;
}

template <typename TM>
void check_rows_are_affine_combinations(const SMR::Relaxation_operator<TM>& R)
{
  const auto& off = R.row_offsets();
  REQUIRE(off.size() == R.number_of_vertices() + 1);
  for(std::size_t i = 0; i < R.number_of_vertices(); ++i)
  {
    double sum = 0.;
    for(auto k = off[i]; k < off[i + 1]; ++k)
    {
      REQUIRE(std::isfinite(R.weights()[k]));
      REQUIRE(R.column_indices()[k] < R.number_of_vertices());
      sum += R.weights()[k];
    }
    // partition of unity up to the rounding of a sum of at most a few dozen terms
    REQUIRE(sum == Approx(1.).margin(1e-12));
  }
}

// awkward rings for the pairing of a vertex's corners: a jittered grid (border rows), a fan of
// 40 triangles (a ring longer than 32 corners: the sorted search) and an isolated vertex
Mesh awkward_rings()
{
  Mesh m = smr_test::planar_grid<Mesh>(8, 0.2);
  const double pi = 3.14159265358979323846;
  const auto centre = m.add_vertex(Point_3(20, 0, 0.3));
  std::vector<Mesh::Vertex_index> rim;
  for(int k = 0; k < 40; ++k)
    rim.push_back(m.add_vertex(Point_3(20 + std::cos(2 * pi * k / 40), std::sin(2 * pi * k / 40), 0.1 * (k % 3))));
  for(int k = 0; k < 40; ++k)
    m.add_face(centre, rim[k], rim[(k + 1) % 40]);
  m.add_vertex(Point_3(5, 5, 5));
  return m;
}

} // namespace

TEST_CASE("every scheme is a partition of unity with finite weights", "[relaxation][unity]")
{
  std::vector<Mesh> meshes = {smr_test::icosphere<Mesh>(3), smr_test::planar_grid<Mesh>(12, 0.3)};
  Mesh real;
  if(smr_test::read_cgal_mesh("meshes/elephant-with-holes.off", real))
    meshes.push_back(real);
  for(const Mesh& m : meshes)
    for(auto s : all_schemes)
    {
      INFO(name(s) << " on a mesh of " << num_vertices(m) << " vertices");
      const auto R = SMR::relaxation_operator(m, SMR::parameters::relaxation_scheme(s));
      REQUIRE(R.number_of_vertices() == num_vertices(m));
      check_rows_are_affine_combinations(R);
    }
}

TEST_CASE("curvature and SOD have linear precision on planar triangulations", "[relaxation][linear]")
{
  // jittered interior vertices make an irregular triangulation of a tilted plane
  const Mesh m = smr_test::planar_grid<Mesh>(10, 0.3);
  const std::vector<double> xyz = coordinates(m);
  std::vector<double> rxyz;
  std::size_t checked = 0;
  for(auto s : all_schemes)
  {
    const auto R = SMR::relaxation_operator(m, SMR::parameters::relaxation_scheme(s));
    CHECK(R.number_of_rows_with_rule(SMR::Relaxation_row_rule::SCHEME) + R.number_of_rows_with_rule(SMR::Relaxation_row_rule::BORDER)
          == num_vertices(m));
    R.apply(xyz, rxyz, 3);
    double max_interior = 0.;
    for(std::size_t i = 0; i < R.number_of_vertices(); ++i)
    {
      if(smr_test::is_border_vertex(R.vertex(i), m))
        continue;   // the border rule is tested on its own below
      const double d = std::sqrt(CGAL::square(rxyz[3 * i] - xyz[3 * i]) + CGAL::square(rxyz[3 * i + 1] - xyz[3 * i + 1])
                                 + CGAL::square(rxyz[3 * i + 2] - xyz[3 * i + 2]));
      max_interior = (std::max)(max_interior, d);
      ++checked;
    }
    INFO(name(s) << ": largest interior move " << max_interior);
    // grid step 0.1: a fixed point up to rounding of coordinates of size ~1
    if(s != SMR::Relaxation_scheme::UNIFORM)
      CHECK(max_interior < 1e-13);
    else
      CHECK(max_interior > 1e-3);   // the uniform Laplacian has no linear precision on irregular grids
  }
  CHECK(checked == 3 * 81);   // 9 x 9 interior vertices per scheme
}

TEST_CASE("straight borders are kept by the border rule", "[relaxation][border]")
{
  const Mesh m = smr_test::planar_grid<Mesh>(8, 0.25);
  const std::vector<double> xyz = coordinates(m);
  // corners of the unit square, mapped into 3D
  const Point_3 o(0.3, -0.2, 0.5);
  const Vector_3 u(0.8, 0.36, 0.48), w(-0.6, 0.48, 0.64);
  const std::vector<Point_3> corners = {o, o + u, o + w, o + u + w};
  for(auto s : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE})
  {
    const auto R = SMR::relaxation_operator(m, SMR::parameters::relaxation_scheme(s));
    std::vector<double> rxyz;
    R.apply(xyz, rxyz, 3);
    std::size_t border = 0;
    for(std::size_t i = 0; i < R.number_of_vertices(); ++i)
    {
      const Point_3 p = get(CGAL::vertex_point, m, R.vertex(i));
      if(!smr_test::is_border_vertex(R.vertex(i), m))
        continue;
      CHECK(R.row_rule(i) == SMR::Relaxation_row_rule::BORDER);
      const bool corner = std::any_of(corners.begin(), corners.end(),
                                      [&](const Point_3& c) { return CGAL::squared_distance(c, p) < 1e-20; });
      const double d = std::sqrt(CGAL::square(rxyz[3 * i] - p.x()) + CGAL::square(rxyz[3 * i + 1] - p.y())
                                 + CGAL::square(rxyz[3 * i + 2] - p.z()));
      if(corner)
        CHECK(d > 1e-3);     // a corner is cut: it moves along the border curve towards its neighbours
      else
        CHECK(d < 1e-13);
      ++border;
    }
    CHECK(border == 32);
  }
}

TEST_CASE("second-order difference coefficients (Guskov et al.)", "[relaxation][sod]")
{
  CGAL::Random rng(11);
  auto random_point = [&] { return std::array<double, 3>{{rng.get_double(-1, 1), rng.get_double(-1, 1), rng.get_double(-1, 1)}}; };
  for(int trial = 0; trial < 200; ++trial)
  {
    // a random planar hinge: p1, p2 on the edge, p3 and p4 on either side, in a random plane
    const auto o = random_point(), a = random_point(), b0 = random_point();
    const Vector_3 ea(a[0], a[1], a[2]);
    Vector_3 eb(b0[0], b0[1], b0[2]);
    eb = eb - (eb * ea) / (ea * ea) * ea;                      // orthogonal to ea
    auto in_plane = [&](double s, double t) {
      return std::array<double, 3>{{o[0] + s * ea.x() + t * eb.x(), o[1] + s * ea.y() + t * eb.y(), o[2] + s * ea.z() + t * eb.z()}};
    };
    const double s3 = rng.get_double(-0.5, 1.5), t3 = rng.get_double(0.2, 1.0);
    const double s4 = rng.get_double(-0.5, 1.5), t4 = -rng.get_double(0.2, 1.0);
    const auto p1 = in_plane(0, 0), p2 = in_plane(1, 0), p3 = in_plane(s3, t3), p4 = in_plane(s4, t4);
    double c[4];
    REQUIRE(SMR::internal::second_order_difference_coefficients(p1.data(), p2.data(), p3.data(), p4.data(), 1e-3, c));
    const double scale = std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]) + std::abs(c[3]);
    // constants and linear functions are annihilated
    CHECK(std::abs(c[0] + c[1] + c[2] + c[3]) <= 1e-13 * scale);
    for(int k = 0; k < 3; ++k)
    {
      const double lin[4] = {p1[k], p2[k], p3[k], p4[k]};
      CHECK(std::abs(c[0] * lin[0] + c[1] * lin[1] + c[2] * lin[2] + c[3] * lin[3]) <= 1e-12 * scale);
    }
    // known answer: f = 0 on the p4 side and f = g * (distance to the edge line) on the p3 side
    // has a normal-derivative jump g, so D_e = g * L with L = |p2 - p1|
    const double g = rng.get_double(0.5, 2.);
    const double L = std::sqrt(ea * ea), h3 = t3 * std::sqrt(eb * eb);
    CHECK(c[2] * g * h3 == Approx(g * L).epsilon(1e-12));
    // invariant under a rigid motion and a uniform scaling of the hinge
    const double ang = rng.get_double(0, 6.28), sc = rng.get_double(0.1, 10.);
    auto move = [&](const std::array<double, 3>& p) {
      return std::array<double, 3>{{sc * (std::cos(ang) * p[0] - std::sin(ang) * p[1]) + 5.,
                                    sc * (std::sin(ang) * p[0] + std::cos(ang) * p[1]) - 2., sc * p[2] + 1.}};
    };
    double cm[4];
    REQUIRE(SMR::internal::second_order_difference_coefficients(move(p1).data(), move(p2).data(), move(p3).data(),
                                                                move(p4).data(), 1e-3, cm));
    for(int k = 0; k < 4; ++k)
      CHECK(cm[k] == Approx(c[k]).epsilon(1e-9).margin(1e-9 * scale));
  }
  // a degenerate hinge is left out
  const double q1[3] = {0, 0, 0}, q2[3] = {1, 0, 0}, q3[3] = {0.5, 1e-6, 0}, q4[3] = {0.5, -1, 0};
  double c[4];
  CHECK_FALSE(SMR::internal::second_order_difference_coefficients(q1, q2, q3, q4, 1e-3, c));
}

TEST_CASE("weights are invariant under rigid motions and scaling", "[relaxation][invariance]")
{
  Mesh m = smr_test::icosphere<Mesh>(2);
  CGAL::Random rng(3);
  for(auto v : vertices(m))   // make it irregular
  {
    const Point_3 p = m.point(v);
    m.point(v) = Point_3(p.x() * 1.3 + rng.get_double(-0.05, 0.05), p.y() + rng.get_double(-0.05, 0.05), p.z() * 0.8);
  }
  Mesh moved = m;
  const double c = std::cos(0.7), s = std::sin(0.7);
  for(auto v : vertices(moved))
  {
    const Point_3 p = moved.point(v);
    moved.point(v) = Point_3(3 * (c * p.x() - s * p.z()) + 10., 3 * p.y() - 4., 3 * (s * p.x() + c * p.z()) + 0.5);
  }
  for(auto sch : all_schemes)
  {
    const auto R = SMR::relaxation_operator(m, SMR::parameters::relaxation_scheme(sch));
    const auto Rm = SMR::relaxation_operator(moved, SMR::parameters::relaxation_scheme(sch));
    REQUIRE(R.column_indices() == Rm.column_indices());
    for(std::size_t k = 0; k < R.weights().size(); ++k)
      CHECK(Rm.weights()[k] == Approx(R.weights()[k]).epsilon(1e-9).margin(1e-12));
  }
}

TEST_CASE("relaxing constant or linear fields on a plane changes nothing", "[relaxation][attributes]")
{
  Mesh m = smr_test::planar_grid<Mesh>(10, 0.3);
  m.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color", CGAL::IO::Color(12, 200, 77, 255));
  auto scalar = m.add_property_map<Mesh::Vertex_index, double>("v:scalar", 0.).first;
  auto rgb = m.add_property_map<Mesh::Vertex_index, std::array<double, 3> >("v:rgb").first;
  for(auto v : vertices(m))
  {
    const Point_3 p = m.point(v);
    scalar[v] = 2. * p.x() - 3. * p.y() + 0.5 * p.z() + 1.;                       // linear in space
    rgb[v] = {{100. + 50. * p.x(), 20. - 10. * p.y(), 30. * p.z() + 5. * p.x()}};   // a linear colour field
  }
  std::vector<double> s0, r0;
  for(auto v : vertices(m)) { s0.push_back(scalar[v]); r0.insert(r0.end(), rgb[v].begin(), rgb[v].end()); }

  // with the four corners of the square constrained, every vertex is a fixed point: interior
  // vertices by linear precision, border vertices because the border rule interpolates
  // linearly along the straight sides
  const Point_3 o(0.3, -0.2, 0.5);
  const Vector_3 u(0.8, 0.36, 0.48), w(-0.6, 0.48, 0.64);
  const std::vector<Point_3> corners = {o, o + u, o + w, o + u + w};
  auto corner = m.add_property_map<Mesh::Vertex_index, bool>("v:corner", false).first;
  std::size_t number_of_corners = 0;
  for(auto v : vertices(m))
    for(const Point_3& c : corners)
      if(CGAL::squared_distance(c, m.point(v)) < 1e-20) { corner[v] = true; ++number_of_corners; }
  REQUIRE(number_of_corners == 4);

  for(auto sch : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE})
  {
    Mesh mm = m;
    auto c = mm.property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
    auto sc = mm.property_map<Mesh::Vertex_index, double>("v:scalar").first;
    auto rg = mm.property_map<Mesh::Vertex_index, std::array<double, 3> >("v:rgb").first;
    SMR::relax(mm, SMR::parameters::relaxation_scheme(sch).relax_geometry(false).number_of_iterations(5)
                                   .vertex_is_constrained_map(mm.property_map<Mesh::Vertex_index, bool>("v:corner").first)
                                   .vertex_attribute_maps(std::make_tuple(c, sc, rg)));
    std::size_t i = 0;
    for(auto v : vertices(mm))
    {
      CHECK(c[v] == CGAL::IO::Color(12, 200, 77, 255));   // constant: exactly unchanged
      // values of size ~100 after five affine combinations: rounding only
      CHECK(sc[v] == Approx(s0[i]).margin(1e-12));
      for(int k = 0; k < 3; ++k)
        CHECK(rg[v][k] == Approx(r0[3 * i + k]).margin(1e-11));
      ++i;
    }
    // the geometry was not touched
    CHECK(smr_test::positions_in_order(mm) == smr_test::positions_in_order(m));
  }
}

TEST_CASE("Fig. 3 analogue: swirl colours on a sphere smooth out, the mean is kept", "[relaxation][fig3]")
{
  Mesh m = smr_test::icosphere<Mesh>(4);
  auto color = m.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  auto channel = m.add_property_map<Mesh::Vertex_index, std::array<double, 3> >("v:swirl").first;
  for(auto v : vertices(m))
  {
    const Point_3 p = m.point(v);
    const double a = std::atan2(p.y(), p.x()) + 6. * p.z();          // a swirl around the z axis
    channel[v] = {{127.5 + 127.5 * std::sin(3 * a), 127.5 + 127.5 * std::cos(3 * a), 127.5}};
    color[v] = CGAL::IO::Color(static_cast<unsigned char>(channel[v][0]), static_cast<unsigned char>(channel[v][1]), 128);
  }
  auto stats = [&](std::array<double, 3>& mean) {
    mean = {{0., 0., 0.}};
    for(auto v : vertices(m)) for(int k = 0; k < 3; ++k) mean[k] += channel[v][k];
    for(int k = 0; k < 3; ++k) mean[k] /= double(num_vertices(m));
    double var = 0.;
    for(auto v : vertices(m)) for(int k = 0; k < 3; ++k) var += CGAL::square(channel[v][k] - mean[k]);
    return var / double(num_vertices(m));
  };
  std::array<double, 3> mean0, mean;
  const double var0 = stats(mean0);
  double previous = var0;
  const auto R = SMR::relaxation_operator(m);
  for(int it = 1; it <= 20; ++it)
  {
    R.apply(m, SMR::parameters::relax_geometry(false).vertex_attribute_maps(std::make_tuple(channel, color)));
    const double var = stats(mean);
    INFO("iteration " << it);
    CHECK(var < previous);
    previous = var;
    // curvature weights on a near-regular sphere are near-symmetric: the mean moves by far less
    // than the spread of the colours
    for(int k = 0; k < 3; ++k)
      CHECK(std::abs(mean[k] - mean0[k]) < 1e-3 * std::sqrt(var0));
  }
  CHECK(previous < 0.5 * var0);
  // the byte colours followed the same relaxation (rounded)
  for(auto v : vertices(m))
    CHECK(std::abs(int(color[v].red()) - channel[v][0]) <= 20.);
}

TEST_CASE("Fig. 2 analogue: the uniform scheme drifts tangentially, curvature and SOD barely", "[relaxation][fig2]")
{
  Mesh m;
  if(!smr_test::read_cgal_mesh("meshes/mannequin-devil.off", m))
  {
    WARN("CGAL's data set (libcgal-demo) is not installed: skipped");
    return;
  }
  auto normals = get(CGAL::dynamic_vertex_property_t<Vector_3>(), m);
  CGAL::Polygon_mesh_processing::compute_vertex_normals(m, normals);
  double mean_edge = 0.;
  for(auto e : edges(m)) mean_edge += std::sqrt(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))));
  mean_edge /= double(num_edges(m));

  std::map<SMR::Relaxation_scheme, double> tangential, normal;
  for(auto s : all_schemes)
  {
    Mesh r = m;
    SMR::relax(r, SMR::parameters::relaxation_scheme(s));
    double t = 0., n = 0.;
    for(auto v : vertices(m))
    {
      if(smr_test::is_border_vertex(v, m)) continue;
      const Vector_3 d = r.point(v) - m.point(v);
      const double dn = d * get(normals, v);
      t += std::sqrt((std::max)(0., d.squared_length() - dn * dn));
      n += std::abs(dn);
    }
    tangential[s] = t / num_vertices(m) / mean_edge;
    normal[s] = n / num_vertices(m) / mean_edge;
  }
  INFO("mean tangential drift / mean edge: uniform " << tangential[SMR::Relaxation_scheme::UNIFORM]
       << ", curvature " << tangential[SMR::Relaxation_scheme::CURVATURE]
       << ", SOD " << tangential[SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE]);
  CHECK(tangential[SMR::Relaxation_scheme::UNIFORM] > 3. * tangential[SMR::Relaxation_scheme::CURVATURE]);
  CHECK(tangential[SMR::Relaxation_scheme::UNIFORM] > 3. * tangential[SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE]);
  // all three smooth: they move vertices along the normal by comparable amounts
  for(auto s : all_schemes)
    CHECK(normal[s] > 0.);
}

TEST_CASE("several relaxation steps: relax() and the stored operator agree", "[relaxation][iterations]")
{
  Mesh m = smr_test::icosphere<Mesh>(2);
  auto f = m.add_property_map<Mesh::Vertex_index, double>("v:f", 0.).first;
  for(auto v : vertices(m)) f[v] = m.point(v).x() * m.point(v).y() + m.point(v).z();
  Mesh a = m, b = m;
  auto fa = a.property_map<Mesh::Vertex_index, double>("v:f").first;
  auto fb = b.property_map<Mesh::Vertex_index, double>("v:f").first;
  SMR::relax(a, SMR::parameters::relax_geometry(false).number_of_iterations(4).vertex_attribute_maps(fa));
  const auto R = SMR::relaxation_operator(b);
  std::vector<double> x;
  for(auto v : vertices(b)) x.push_back(fb[v]);
  for(int it = 0; it < 4; ++it) R.apply(x, x, 1);
  std::size_t i = 0;
  for(auto v : vertices(a)) CHECK(fa[v] == x[i++]);   // same arithmetic, same order: identical

  // with the geometry, weights follow the moving mesh: two relax() calls of one step equal one call of two steps
  Mesh c = m, d = m;
  SMR::relax(c, SMR::parameters::number_of_iterations(2));
  SMR::relax(d);
  SMR::relax(d);
  CHECK(smr_test::positions_in_order(c) == smr_test::positions_in_order(d));
}

TEST_CASE("several relaxation steps in one call read the first step's ring pairing: the same bits as one step per call",
          "[relaxation][iterations]")
{
  // awkward rings for the pairing, and constrained rows, which a later step of the same call
  // pairs from the first one
  Mesh m = awkward_rings();
  auto constrained = m.add_property_map<Mesh::Vertex_index, bool>("v:fixed", false).first;
  std::size_t k = 0;
  for(auto v : vertices(m)) constrained[v] = (k++ % 7 == 3);
  for(auto s : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM})
  {
    Mesh a = m, b = m;
    auto ca = a.property_map<Mesh::Vertex_index, bool>("v:fixed").first;
    auto cb = b.property_map<Mesh::Vertex_index, bool>("v:fixed").first;
    SMR::relax(a, SMR::parameters::relaxation_scheme(s).vertex_is_constrained_map(ca).number_of_iterations(3));
    for(int it = 0; it < 3; ++it)
      SMR::relax(b, SMR::parameters::relaxation_scheme(s).vertex_is_constrained_map(cb));
    CHECK(smr_test::positions_in_order(a) == smr_test::positions_in_order(b));
    CHECK(smr_test::positions_in_order(a) != smr_test::positions_in_order(m));
  }
}

TEST_CASE("a relax() step applies its weights as it computes them: the stored operator's bits", "[relaxation][iterations]")
{
  // awkward rings and constrained rows; positions and two attribute channels of 1 + 6 values
  // (a combined dimension of 7: the general row sum) relaxed by one step of relax() and by
  // the operator computed on the same mesh and applied to it
  Mesh m = awkward_rings();
  auto constrained = m.add_property_map<Mesh::Vertex_index, bool>("v:fixed", false).first;
  auto f = m.add_property_map<Mesh::Vertex_index, double>("v:f", 0.).first;
  auto g = m.add_property_map<Mesh::Vertex_index, std::array<double, 6> >("v:g").first;
  std::size_t k = 0;
  for(auto v : vertices(m))
  {
    constrained[v] = (k % 7 == 3);
    f[v] = std::sin(double(k));
    for(int c = 0; c < 6; ++c) g[v][c] = std::cos(double(k * (c + 1)));
    ++k;
  }
  for(auto s : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM, SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE})
  {
    Mesh a = m, b = m;
    auto np_of = [s](Mesh& t) {
      return SMR::parameters::relaxation_scheme(s)
          .vertex_is_constrained_map(t.property_map<Mesh::Vertex_index, bool>("v:fixed").first)
          .vertex_attribute_maps(std::make_tuple(t.property_map<Mesh::Vertex_index, double>("v:f").first,
                                                 t.property_map<Mesh::Vertex_index, std::array<double, 6> >("v:g").first));
    };
    SMR::relax(a, np_of(a));
    const auto R = SMR::relaxation_operator(b, np_of(b));
    R.apply(b, np_of(b));
    CHECK(smr_test::positions_in_order(a) == smr_test::positions_in_order(b));
    CHECK(smr_test::positions_in_order(a) != smr_test::positions_in_order(m));
    auto fa = a.property_map<Mesh::Vertex_index, double>("v:f").first, fb = b.property_map<Mesh::Vertex_index, double>("v:f").first;
    auto ga = a.property_map<Mesh::Vertex_index, std::array<double, 6> >("v:g").first;
    auto gb = b.property_map<Mesh::Vertex_index, std::array<double, 6> >("v:g").first;
    std::size_t moved = 0;
    for(auto v : vertices(a))
    {
      CHECK(fa[v] == fb[v]);
      CHECK(ga[v] == gb[v]);
      moved += (fa[v] != f[v]) ? 1 : 0;
    }
    CHECK(moved > 0);
    // the attributes alone, one step: the same again, the positions untouched
    Mesh c = m, d = m;
    SMR::relax(c, np_of(c).relax_geometry(false));
    SMR::relaxation_operator(d, np_of(d)).apply(d, np_of(d).relax_geometry(false));
    CHECK(smr_test::positions_in_order(c) == smr_test::positions_in_order(m));
    CHECK(smr_test::positions_in_order(d) == smr_test::positions_in_order(m));
    auto fc = c.property_map<Mesh::Vertex_index, double>("v:f").first, fd = d.property_map<Mesh::Vertex_index, double>("v:f").first;
    auto gc = c.property_map<Mesh::Vertex_index, std::array<double, 6> >("v:g").first;
    auto gd = d.property_map<Mesh::Vertex_index, std::array<double, 6> >("v:g").first;
    for(auto v : vertices(c))
    {
      CHECK(fc[v] == fd[v]);
      CHECK(gc[v] == gd[v]);
    }
  }
}

namespace {

// the points' coordinates as bits (== takes -0.0 for 0.0)
std::vector<std::uint64_t> coordinate_bits(const Mesh& m)
{
  std::vector<std::uint64_t> bits;
  for(const Point_3& p : smr_test::positions_in_order(m))
    for(int c = 0; c < 3; ++c)
    {
      const double x = p[c];
      std::uint64_t b;
      std::memcpy(&b, &x, sizeof b);
      bits.push_back(b);
    }
  return bits;
}

// A closed surface of 4 triangles with two distinct edges between its vertices N and S (a
// sphere cut into two lunes along them, a vertex inside each lune), built halfedge by
// halfedge (Surface_mesh::add_face() joins such edges into one), then an icosphere beside it.
Mesh with_double_edge()
{
  Mesh m;
  typedef Mesh::Halfedge_index H;
  const auto N = m.add_vertex(Point_3(0, 0, 1)), S = m.add_vertex(Point_3(0.1, 0, -1));
  const auto a = m.add_vertex(Point_3(1, 0.2, 0)), b = m.add_vertex(Point_3(-1, -0.1, 0.1));
  auto edge = [&](Mesh::Vertex_index from, Mesh::Vertex_index to) {
    const H h = m.add_edge();
    m.set_target(h, to);
    m.set_target(m.opposite(h), from);
    return h;
  };
  const H e1 = edge(N, S), e2 = edge(N, S), Na = edge(N, a), aS = edge(a, S), Nb = edge(N, b), bS = edge(b, S);
  auto face = [&](H x, H y, H z) {
    const auto f = m.add_face();
    for(H h : {x, y, z}) m.set_face(h, f);
    m.set_next(x, y);
    m.set_next(y, z);
    m.set_next(z, x);
    m.set_halfedge(f, x);
  };
  face(Na, aS, m.opposite(e1));                 // N a S
  face(m.opposite(aS), m.opposite(Na), e2);     // S a N
  face(e1, m.opposite(bS), m.opposite(Nb));     // N S b
  face(m.opposite(e2), Nb, bS);                 // S N b
  m.set_halfedge(N, m.opposite(Na));
  m.set_halfedge(S, e1);
  m.set_halfedge(a, Na);
  m.set_halfedge(b, Nb);
  CGAL::copy_face_graph(smr_test::icosphere<Mesh>(1), m);
  return m;
}

} // namespace

TEST_CASE("relax() on a Surface_mesh reads its own halfedges: the index path's rows, bit for bit", "[relaxation][halfedges]")
{
  // One step of relax() on a Surface_mesh computes its rows from the mesh's halfedges; the
  // operator (and a mesh with removed elements) computes them on the index view. Both must be
  // the same, bit for bit: borders, a ring longer than 32 corners, an isolated vertex, open
  // fans pinched at a vertex, constrained rows, meshes of CGAL's data set. Where two edges
  // join the same vertices the halfedge rows give up and relax() takes the index path.
  typedef SMR::internal::Surface_mesh_relaxation_rows<Point_3> Rows;
  std::vector<std::pair<Mesh, bool> > meshes;   // (mesh, whether its halfedges give the rows)
  meshes.emplace_back(smr_test::icosphere<Mesh>(3), true);
  meshes.emplace_back(awkward_rings(), true);
  {
    // two open fans of 5 triangles around vertex 0, joined there only (a pinched vertex)
    Mesh pinched;
    const auto c = pinched.add_vertex(Point_3(0, 0, 0));
    std::vector<Mesh::Vertex_index> rim;
    for(int k = 0; k < 12; ++k)
      rim.push_back(pinched.add_vertex(Point_3(std::cos(0.5 * k), std::sin(0.5 * k), 0.2 * (k % 3) - 0.1 * (k % 2))));
    for(int k = 0; k < 5; ++k) REQUIRE(pinched.add_face(c, rim[k], rim[k + 1]) != Mesh::null_face());
    for(int k = 6; k < 11; ++k) REQUIRE(pinched.add_face(c, rim[k], rim[k + 1]) != Mesh::null_face());
    meshes.emplace_back(pinched, true);
  }
  Mesh data;
  if(smr_test::read_cgal_mesh("meshes/elephant-with-holes.off", data)) meshes.emplace_back(data, true);
  if(smr_test::read_cgal_mesh("meshes/mannequin-devil.off", data)) meshes.emplace_back(data, true);
  meshes.emplace_back(with_double_edge(), false);
  REQUIRE(meshes.back().first.is_valid(false));
  for(const auto& entry : meshes)
  {
    const Mesh& m = entry.first;
    for(auto s : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM})
      for(bool with_constraints : {false, true})
      {
        INFO(name(s) << " on a mesh of " << num_vertices(m) << " vertices, constraints " << with_constraints);
        // the halfedge rows can (or cannot) be read
        {
          const std::vector<double> xyz = coordinates(m);
          Rows rows(m);
          if(s == SMR::Relaxation_scheme::CURVATURE) rows.compute_cotangents(xyz.data());
          std::size_t calls = 0;
          CHECK(rows.apply_rows(s, xyz.data(), nullptr, [&](std::size_t, const SMR::internal::Index*, const double*, std::size_t) {
            ++calls;
          }) == entry.second);
          if(entry.second) CHECK(calls == num_vertices(m));
        }
        Mesh a = m, b = m, c = m;
        auto fa = a.add_property_map<Mesh::Vertex_index, bool>("v:fixed", false).first;
        auto fb = b.add_property_map<Mesh::Vertex_index, bool>("v:fixed", false).first;
        auto fc = c.add_property_map<Mesh::Vertex_index, bool>("v:fixed", false).first;
        if(with_constraints)
          for(auto v : vertices(m)) fa[v] = fb[v] = fc[v] = (v.idx() % 5 == 2);
        // c: a removed vertex at the end (has_garbage(): the index path), the same rows
        c.remove_vertex(c.add_vertex(Point_3(9, 9, 9)));
        REQUIRE(c.has_garbage());
        SMR::relax(a, SMR::parameters::relaxation_scheme(s).vertex_is_constrained_map(fa));
        SMR::relaxation_operator(b, SMR::parameters::relaxation_scheme(s).vertex_is_constrained_map(fb))
            .apply(b, SMR::parameters::vertex_is_constrained_map(fb));
        SMR::relax(c, SMR::parameters::relaxation_scheme(s).vertex_is_constrained_map(fc));
        CHECK(coordinate_bits(a) == coordinate_bits(b));
        CHECK(coordinate_bits(a) == coordinate_bits(c));
        CHECK(coordinate_bits(a) != coordinate_bits(m));
      }
  }
}

TEST_CASE("relax() on a Surface_mesh refuses what the index view refuses, with its words", "[relaxation][halfedges]")
{
  // a quadrangle among triangles: the first such face is named, for both 1-ring schemes
  Mesh m = smr_test::icosphere<Mesh>(1);
  std::vector<Mesh::Vertex_index> q;
  for(int k = 0; k < 4; ++k) q.push_back(m.add_vertex(Point_3(5 + (k == 1 || k == 2), (k >= 2), 0)));
  m.add_face(q);
  m.add_face(q[0], q[2], m.add_vertex(Point_3(5, -1, 0)));
  const std::size_t quad = m.number_of_faces() - 2;
  for(auto s : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM})
  {
    Mesh r = m;
    REQUIRE_THROWS_WITH(SMR::relax(r, SMR::parameters::relaxation_scheme(s)),
                        Catch::Contains("face " + std::to_string(quad) + " ") && Catch::Contains("not a triangle: it has 4 vertices"));
    CHECK(smr_test::positions_in_order(r) == smr_test::positions_in_order(m));   // nothing written
  }
  // non-finite coordinates in two of the blocks the points are read in: the first is named
  Mesh n = smr_test::icosphere<Mesh>(6);
  REQUIRE(num_vertices(n) > 40000);
  n.point(Mesh::Vertex_index(35000)) = Point_3(std::numeric_limits<double>::infinity(), 0, 0);
  n.point(Mesh::Vertex_index(20000)) = Point_3(0, std::numeric_limits<double>::quiet_NaN(), 0);
  const Mesh n0 = n;
  REQUIRE_THROWS_WITH(SMR::relax(n), Catch::Contains("vertex 20000 ") && Catch::Contains("non-finite coordinate"));
  CHECK(coordinate_bits(n) == coordinate_bits(n0));
}

TEST_CASE("constrained vertices do not move", "[relaxation][constraints]")
{
  Mesh m = smr_test::icosphere<Mesh>(2);
  auto constrained = m.add_property_map<Mesh::Vertex_index, bool>("v:constrained", false).first;
  std::size_t k = 0;
  for(auto v : vertices(m)) constrained[v] = (k++ % 3 == 0);
  const auto before = smr_test::positions_in_order(m);
  SMR::relax(m, SMR::parameters::vertex_is_constrained_map(constrained).number_of_iterations(3));
  k = 0;
  for(auto v : vertices(m))
  {
    if(constrained[v]) CHECK(m.point(v) == before[k]);
    else CHECK(m.point(v) != before[k]);
    ++k;
  }
}

TEST_CASE("robustness: weights stay finite and sum to one on awkward input", "[relaxation][robustness]")
{
  using Tri = std::array<std::size_t, 3>;
  SECTION("obtuse triangles: negative cotangents keep linear precision")
  {
    // a fan around an interior vertex whose triangles have angles up to about 150 degrees
    std::vector<Point_3> p = {Point_3(0, 0, 0)};
    const int n = 8;
    for(int k = 0; k < n; ++k)
    {
      const double a = 2 * CGAL_PI * k / n, r = (k % 2 == 0) ? 1.0 : 0.3;
      p.push_back(Point_3(r * std::cos(a), r * std::sin(a), 0));
    }
    std::vector<Tri> t;
    for(int k = 0; k < n; ++k) t.push_back({0, std::size_t(1 + k), std::size_t(1 + (k + 1) % n)});
    const Mesh m = smr_test::mesh_from_soup<Mesh>(p, t);
    const auto R = SMR::relaxation_operator(m);
    check_rows_are_affine_combinations(R);
    const auto& w = R.weights();
    CHECK(*std::min_element(w.begin(), w.end()) < 0.);   // negative weights occur...
    std::vector<double> xyz = coordinates(m), r;
    R.apply(xyz, r, 3);
    for(std::size_t i = 0; i < R.number_of_vertices(); ++i)
      if(!smr_test::is_border_vertex(R.vertex(i), m))
      {
        CHECK(R.row_rule(i) == SMR::Relaxation_row_rule::SCHEME);
        for(int c = 0; c < 3; ++c) CHECK(r[3 * i + c] == Approx(xyz[3 * i + c]).margin(1e-14));   // ...and still reproduce the plane
      }
  }
  SECTION("degenerate, zero-area and duplicated-point triangles, isolated vertex, several components")
  {
    std::vector<Point_3> p = {Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(0.5, 0, 0),        // collinear: zero area
                              Point_3(0.5, 1, 0), Point_3(0.5, -1, 0), Point_3(1, 1, 1), Point_3(1, 1, 1),   // duplicated point
                              Point_3(5, 5, 5), Point_3(6, 5, 5), Point_3(5, 6, 5), Point_3(5, 5, 6)};       // a tetrahedron apart
    std::vector<Tri> t = {{0, 2, 3}, {2, 1, 3}, {0, 4, 2}, {2, 4, 1}, {0, 1, 2}, {3, 1, 5}, {1, 6, 5},
                          {7, 9, 8}, {7, 8, 10}, {8, 9, 10}, {7, 10, 9}};
    Mesh m;
    for(const Point_3& q : p) m.add_vertex(q);
    for(const Tri& tr : t)
      CGAL::Euler::add_face(std::vector<Mesh::Vertex_index>{Mesh::Vertex_index(tr[0]), Mesh::Vertex_index(tr[1]), Mesh::Vertex_index(tr[2])}, m);
    m.add_vertex(Point_3(9, 9, 9));   // isolated
    REQUIRE(num_vertices(m) == 12);
    for(auto s : all_schemes)
    {
      INFO(name(s));
      const auto R = SMR::relaxation_operator(m, SMR::parameters::relaxation_scheme(s));
      check_rows_are_affine_combinations(R);
      CHECK(R.row_rule(11) == SMR::Relaxation_row_rule::FIXED);
      Mesh r = m;
      SMR::relax(r, SMR::parameters::relaxation_scheme(s).number_of_iterations(10));
      for(auto v : vertices(r))
        CHECK((std::isfinite(r.point(v).x()) && std::isfinite(r.point(v).y()) && std::isfinite(r.point(v).z())));
      CHECK(r.point(Mesh::Vertex_index(11)) == Point_3(9, 9, 9));
    }
  }
  SECTION("tiny meshes: a tetrahedron, a single triangle, an empty mesh")
  {
    Mesh tet, tri, empty;
    CGAL::make_tetrahedron(Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(0, 1, 0), Point_3(0, 0, 1), tet);
    CGAL::make_triangle(Point_3(0, 0, 0), Point_3(1, 0, 0), Point_3(0, 1, 0), tri);
    for(auto s : all_schemes)
    {
      check_rows_are_affine_combinations(SMR::relaxation_operator(tet, SMR::parameters::relaxation_scheme(s)));
      const auto Rt = SMR::relaxation_operator(tri, SMR::parameters::relaxation_scheme(s));
      check_rows_are_affine_combinations(Rt);
      for(std::size_t i = 0; i < 3; ++i) CHECK(Rt.row_rule(i) == SMR::Relaxation_row_rule::BORDER);
      const auto Re = SMR::relaxation_operator(empty, SMR::parameters::relaxation_scheme(s));
      CHECK(Re.number_of_vertices() == 0);
      SMR::relax(empty, SMR::parameters::relaxation_scheme(s));
      CHECK(num_vertices(empty) == 0);
    }
  }
  SECTION("a real scan with holes: every vertex relaxed, nothing non-finite")
  {
    Mesh m;
    if(!smr_test::read_cgal_mesh("meshes/mech-holes-shark.off", m)) { WARN("CGAL data set missing: skipped"); return; }
    for(auto s : all_schemes)
    {
      Mesh r = m;
      SMR::relax(r, SMR::parameters::relaxation_scheme(s).number_of_iterations(3));
      for(auto v : vertices(r))
        REQUIRE((std::isfinite(r.point(v).x()) && std::isfinite(r.point(v).y()) && std::isfinite(r.point(v).z())));
    }
  }
}

TEMPLATE_TEST_CASE("generic over FaceGraph models: Surface_mesh and Polyhedron_3 give the same operator",
                   "[relaxation][generic]", Polyhedron, Mesh)
{
  const TestType tm = smr_test::icosphere<TestType>(2);
  const Mesh sm = smr_test::icosphere<Mesh>(2);
  for(auto s : all_schemes)
  {
    const auto R = SMR::relaxation_operator(tm, SMR::parameters::relaxation_scheme(s));
    const auto Rs = SMR::relaxation_operator(sm, SMR::parameters::relaxation_scheme(s));
    check_rows_are_affine_combinations(R);
    // both meshes list the same points in the same vertex order
    REQUIRE(smr_test::positions_in_order(tm) == smr_test::positions_in_order(sm));
    std::vector<double> a, b;
    R.apply(coordinates(tm), a, 3);
    Rs.apply(coordinates(sm), b, 3);
    for(std::size_t k = 0; k < a.size(); ++k) CHECK(a[k] == Approx(b[k]).margin(1e-14));
  }
  TestType r = tm;
  SMR::relax(r, SMR::parameters::number_of_iterations(2));
  CHECK(smr_test::positions_in_order(r) != smr_test::positions_in_order(tm));
}

TEST_CASE("border rows hold exactly the border neighbours of every border vertex", "[relaxation][border]")
{
  std::vector<Mesh> meshes;
  Mesh grid = smr_test::planar_grid<Mesh>(6, 0.2);
  grid.add_vertex(Point_3(3, 3, 3));   // an isolated vertex last: the mesh's last row has no halfedge
  meshes.push_back(grid);
  Mesh holes;
  if(smr_test::read_cgal_mesh("meshes/elephant-with-holes.off", holes)) meshes.push_back(holes);
  if(smr_test::read_cgal_mesh("meshes/mannequin-devil.off", holes)) meshes.push_back(holes);
  for(const Mesh& m : meshes)
    for(auto s : all_schemes)
    {
      const auto R = SMR::relaxation_operator(m, SMR::parameters::relaxation_scheme(s));
      std::size_t border_vertices = 0;
      for(std::size_t i = 0; i < R.number_of_vertices(); ++i)
      {
        const auto v = R.vertex(i);
        std::set<std::size_t> expected, got;
        if(halfedge(v, m) == boost::graph_traits<Mesh>::null_halfedge()) { CHECK(R.row_rule(i) == SMR::Relaxation_row_rule::FIXED); continue; }
        for(auto h : CGAL::halfedges_around_source(v, m))
          if(CGAL::is_border_edge(h, m)) expected.insert(target(h, m).idx());
        if(expected.empty()) { CHECK(R.row_rule(i) != SMR::Relaxation_row_rule::BORDER); continue; }
        ++border_vertices;
        REQUIRE(R.row_rule(i) == SMR::Relaxation_row_rule::BORDER);
        for(auto k = R.row_offsets()[i]; k < R.row_offsets()[i + 1]; ++k) got.insert(R.column_indices()[k]);
        CHECK(got == expected);
      }
      CHECK(border_vertices > 0);
    }
}

TEST_CASE("the three pairings of a ring's corners give the same weights, pinched vertices included", "[relaxation][corners]")
{
  // The 1-ring weights pair each corner with the corner across its edge in one of three ways:
  // inside the ring from listed targets and apexes (relax(), reconstructions), inside the ring
  // from the face array when the halfedges exist, and through the halfedges' twins (the
  // decomposition). The rows (columns, order, bits) and their rules must be the same.
  typedef SMR::internal::Index Index;
  CGAL::Random rng(11);
  std::vector<std::pair<std::size_t, std::vector<Index> > > cases;
  {
    // two closed umbrellas of 6 faces around vertex 0 (a pinched vertex), an open one of 40
    // faces around vertex 13 (a long ring) glued to the first at vertex 1, and an open fan of
    // 3 faces around 0 as well
    std::vector<Index> F;
    for(Index i = 0; i < 6; ++i) F.insert(F.end(), {0, 1 + i, 1 + (i + 1) % 6});
    for(Index i = 0; i < 6; ++i) F.insert(F.end(), {0, 7 + i, 7 + (i + 1) % 6});
    for(Index i = 0; i < 39; ++i) F.insert(F.end(), {13, 14 + i, 15 + i});
    F.insert(F.end(), {13, 53, 1});
    for(Index i = 0; i < 3; ++i) F.insert(F.end(), {0, 54 + i, 55 + i});
    cases.emplace_back(58, F);
  }
  {
    // a perturbed grid with a hole, its centre pinched to a corner of the hole
    const Index s = 9;
    std::vector<Index> F;
    for(Index y = 0; y + 1 < s; ++y)
      for(Index x = 0; x + 1 < s; ++x)
      {
        if(x >= 3 && x <= 4 && y >= 3 && y <= 4) continue;   // the hole
        const Index a = y * s + x, b = a + 1, c = a + s, d = c + 1;
        F.insert(F.end(), {a, b, d});
        F.insert(F.end(), {a, d, c});
      }
    cases.emplace_back(std::size_t(s * s), F);
  }
  for(const auto& c : cases)
  {
    const std::size_t n = c.first;
    const std::vector<Index>& F = c.second;
    std::vector<double> xyz(3 * n);
    for(std::size_t i = 0; i < n; ++i)
    {
      const double t = 6.283185307179586 * double(i) / double(n);
      xyz[3 * i] = std::cos(t) * (1. + 0.1 * double(i % 7)) + rng.get_double(-0.05, 0.05);
      xyz[3 * i + 1] = std::sin(t) * (1. + 0.1 * double(i % 5)) + rng.get_double(-0.05, 0.05);
      xyz[3 * i + 2] = rng.get_double(-0.3, 0.3);
    }
    for(SMR::Relaxation_scheme scheme : {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM})
    {
      SMR::internal::Sparse_weights w[3];
      std::vector<SMR::Relaxation_row_rule> rules[3];
      SMR::internal::Relaxation_weight_builder listed, from_faces, paired;
      listed.set_connectivity(n, F);
      listed.build(scheme, xyz.data(), nullptr, w[0], rules[0]);
      from_faces.set_connectivity(n, F);
      CHECK(!from_faces.connectivity().repeated_directed_edge);   // the halfedges now exist
      from_faces.build(scheme, xyz.data(), nullptr, w[1], rules[1]);
      paired.set_connectivity(n, F, true);
      paired.pair_corners_from_halfedges();
      paired.keep_outgoing_lists_only();
      paired.build(scheme, xyz.data(), nullptr, w[2], rules[2]);
      for(int k = 1; k < 3; ++k)
      {
        CHECK(w[k].offsets == w[0].offsets);
        CHECK(w[k].columns == w[0].columns);
        CHECK(w[k].values == w[0].values);
        CHECK(rules[k] == rules[0]);
      }
      // the pinched vertex 0 of the first case: its row spans both umbrellas and the fan
      if(n == 58)
      {
        std::set<Index> row(w[0].columns.begin() + w[0].offsets[0], w[0].columns.begin() + w[0].offsets[1]);
        CHECK(rules[0][0] == SMR::Relaxation_row_rule::BORDER);   // the open fan puts it on a border
        CHECK(row.count(54) == 1);
        CHECK(row.count(57) == 1);
      }
    }
  }
}
