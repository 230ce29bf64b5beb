// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Run under Valgrind's memcheck by scripts/test_memcheck.sh: the pipeline on small generated
// meshes (a sphere with a colour channel, a jittered plane with borders and a hole), every
// relaxation scheme. The internal arrays that parallel loops write whole are left
// uninitialised until written (Uninitialized_vector); memcheck reports any value read before
// it was written. The program itself checks what the pipeline promises: exact round trips
// through reconstruct() and through a pyramid file, one relax() step equal to the operator.
// (Built with CGAL_DISABLE_ROUNDING_MATH_CHECK: Valgrind does not emulate rounding modes.)

#include <smr_test_utils.h>

#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <cstdio>
#include <cstring>
#include <sstream>
#include <vector>

namespace SMR = CGAL::Surface_mesh_multiresolution;
using smr_test::Mesh;
using smr_test::Point_3;

namespace {

int failures = 0;

void check(bool ok, const char* what, const char* mesh, int scheme)
{
  if(!ok)
  {
    std::fprintf(stderr, "FAILED: %s (%s, scheme %d)\n", what, mesh, scheme);
    ++failures;
  }
}

bool same_bits(const std::vector<Point_3>& a, const std::vector<Point_3>& b)
{
  if(a.size() != b.size())
    return false;
  for(std::size_t i = 0; i < a.size(); ++i)
    for(int c = 0; c < 3; ++c)
    {
      const double x = a[i][c], y = b[i][c];
      if(std::memcmp(&x, &y, sizeof x) != 0)
        return false;
    }
  return true;
}

void run(Mesh& m, const char* name)
{
  auto value = m.add_property_map<Mesh::Vertex_index, double>("v:value").first;
  for(auto v : vertices(m))
    value[v] = 1e-3 * m.point(v).x() * m.point(v).y() - 273.15 + 1e5 * m.point(v).z();
  const std::vector<Point_3> input = smr_test::positions_in_order(m);
  const SMR::Relaxation_scheme schemes[] = {SMR::Relaxation_scheme::CURVATURE, SMR::Relaxation_scheme::UNIFORM,
                                            SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE};
  for(int s = 0; s < 3; ++s)
  {
    const auto maps = std::make_tuple(value);
    const auto pyr = SMR::decompose(m, SMR::parameters::relaxation_scheme(schemes[s]).vertex_attribute_maps(maps));
    check(pyr.number_of_levels() > 2, "several levels", name, s);
    Mesh out;
    auto out_value = out.add_property_map<Mesh::Vertex_index, double>("v:value").first;
    SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(out_value)));
    check(same_bits(smr_test::positions_in_order(out), input), "exact reconstruction", name, s);
    bool values_equal = num_vertices(out) == num_vertices(m);
    for(auto v : vertices(m))
      values_equal = values_equal && out_value[v] == value[v];
    check(values_equal, "exact attribute channel", name, s);
    // through a file
    std::stringstream file;
    check(SMR::IO::write_pyramid(file, pyr), "write", name, s);
    SMR::Pyramid<Mesh> back;
    std::string error;
    check(SMR::IO::read_pyramid(file, back, error), "read", name, s);
    Mesh out2;
    SMR::reconstruct(back, out2);
    check(same_bits(smr_test::positions_in_order(out2), input), "exact reconstruction of the read pyramid", name, s);
    // a coarser level, filtered
    Mesh coarse;
    SMR::reconstruct(pyr, coarse, SMR::parameters::level(2));
    check(num_vertices(coarse) == pyr.number_of_vertices(2), "level 2", name, s);
    // one relax() step (weights applied as computed) equals the operator applied
    Mesh relaxed = m;
    SMR::relax(relaxed, SMR::parameters::relaxation_scheme(schemes[s]));
    const auto op = SMR::relaxation_operator(m, SMR::parameters::relaxation_scheme(schemes[s]));
    std::vector<double> x, y;
    for(auto v : vertices(m))
      for(int c = 0; c < 3; ++c)
        x.push_back(m.point(v)[c]);
    y.resize(x.size());
    op.apply(x.data(), y.data(), 3);
    std::vector<Point_3> expected;
    for(std::size_t i = 0; i < y.size(); i += 3)
      expected.emplace_back(y[i], y[i + 1], y[i + 2]);
    check(same_bits(smr_test::positions_in_order(relaxed), expected), "relax() = operator", name, s);
  }
}

} // namespace

int main()
{
  Mesh sphere = smr_test::icosphere<Mesh>(3);
  run(sphere, "sphere");
  Mesh plane = smr_test::planar_grid<Mesh>(24, 0.3);
  // a hole: the faces around one interior vertex removed (and the vertex with them)
  std::vector<Mesh::Face_index> around;
  for(auto f : faces_around_target(halfedge(Mesh::Vertex_index(12 * 25 + 12), plane), plane))
    around.push_back(f);
  for(auto f : around)
    CGAL::Euler::remove_face(halfedge(f, plane), plane);
  plane.collect_garbage();
  run(plane, "plane with a hole");
  std::printf("%s\n", failures == 0 ? "memcheck pipeline: all checks passed" : "memcheck pipeline: FAILED");
  return failures == 0 ? 0 : 1;
}
