// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tests that attack: the invariants of every pyramid, crafted and randomly edited pyramid
// files, extreme finite coordinates, and a seeded property-based fuzz test of every public
// function on random meshes (holes, components, fans around a vertex of high valence,
// isolated vertices, degenerate triangles, huge and tiny coordinates, several channel types).
// CI also runs them under AddressSanitizer and UndefinedBehaviorSanitizer.

#include <catch2/catch.hpp>

#include <smr_test_utils.h>

#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Surface_mesh_multiresolution/internal/Pyramid_checks.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <set>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace SMR = CGAL::Surface_mesh_multiresolution;
using smr_test::Mesh;
using smr_test::Point_3;
using smr_test::Vector_3;
typedef SMR::internal::Index Index;
typedef SMR::internal::Pyramid_access Access;
typedef CGAL::Simple_cartesian<double>::Vector_2 Vector_2;

namespace {

std::string bytes_of(const SMR::Pyramid<Mesh>& pyr)
{
  std::stringstream ss(std::ios::in | std::ios::out | std::ios::binary);
  REQUIRE(SMR::IO::write_pyramid(ss, pyr));
  return ss.str();
}

// reads a file's bytes; the reason of a refusal in `error`
bool read_bytes(const std::string& bytes, SMR::Pyramid<Mesh>& pyr, std::string& error)
{
  std::istringstream in(bytes, std::ios::binary);
  return SMR::IO::read_pyramid(in, pyr, error);
}

// the file with its checksum recomputed after an edit of the payload (24 bytes of header
// before it, 8 bytes of checksum after it)
std::string with_checksum(std::string bytes)
{
  const std::string payload = bytes.substr(24, bytes.size() - 32);
  const std::uint64_t hash = SMR::internal::fnv1a(payload);
  std::memcpy(&bytes[bytes.size() - 8], &hash, 8);
  return bytes;
}

// the doubles of every point, bit for bit (-0.0 differs from 0.0)
std::vector<std::uint64_t> coordinate_bits(const Mesh& m)
{
  std::vector<std::uint64_t> out;
  for(auto v : vertices(m))
    for(int c = 0; c < 3; ++c)
    {
      const double x = m.point(v)[c];
      std::uint64_t b;
      std::memcpy(&b, &x, 8);
      out.push_back(b);
    }
  return out;
}

bool all_finite(const Mesh& m)
{
  for(auto v : vertices(m))
    for(int c = 0; c < 3; ++c)
      if(!std::isfinite(m.point(v)[c])) return false;
  return true;
}

// everything a user does with a pyramid, none of which may fail on a valid one: every level
// rebuilt as a valid mesh, adaptive reconstructions at 0, infinity and a budget, filters,
// noise estimate, denoising, and a second save and read
void use_fully(const SMR::Pyramid<Mesh>& pyr)
{
  const std::size_t K = pyr.number_of_levels();
  for(std::size_t k = 0; k <= K; ++k)
  {
    INFO("level " << k << " of " << K);
    Mesh out;
    SMR::reconstruct(pyr, out, SMR::parameters::level(k));
    REQUIRE(out.is_valid(false));   // Surface_mesh's own check: isolated vertices are valid
    REQUIRE(num_vertices(out) == pyr.number_of_vertices(k));
    REQUIRE(num_faces(out) == pyr.number_of_faces(k));
  }
  Mesh a;
  INFO("adaptive reconstructions");
  SMR::reconstruct_adaptively(pyr, a, std::numeric_limits<double>::infinity());
  REQUIRE(num_vertices(a) == pyr.number_of_vertices(K));
  SMR::reconstruct_adaptively(pyr, a, 0.);
  REQUIRE(num_vertices(a) == pyr.number_of_vertices(0));
  const std::size_t budget = pyr.number_of_vertices(0) / 2;
  for(const SMR::Adaptive_criterion criterion : {SMR::Adaptive_criterion::DETAIL_LENGTH, SMR::Adaptive_criterion::APPROXIMATION_ERROR})
  {
    // vertices without faces are not counted in a budget, and left out on request
    SMR::reconstruct_adaptively(pyr, a, 0., SMR::parameters::target_number_of_vertices(budget).adaptive_criterion(criterion)
                                              .remove_isolated_vertices(true));
    REQUIRE(a.is_valid(false));
    std::size_t isolated = 0;
    for(auto v : vertices(a)) isolated += a.is_isolated(v) ? 1 : 0;
    REQUIRE(isolated == 0);
    REQUIRE((num_vertices(a) <= budget || num_vertices(a) <= pyr.number_of_vertices(K)));
    SMR::reconstruct_adaptively(pyr, a, 1e-3, SMR::parameters::adaptive_criterion(criterion));
    REQUIRE(a.is_valid(false));
  }
  const double sigma = SMR::estimate_noise(pyr);
  REQUIRE((std::isfinite(sigma) && sigma >= 0.));
  if(K > 0)
  {
    SMR::Pyramid<Mesh> p = pyr;
    SMR::denoise(p, SMR::parameters::number_of_iterations(2u));
    SMR::low_pass(p, 1);
    REQUIRE(SMR::internal::check_pyramid(p).empty());
    SMR::reconstruct(p, a);
  }
  SMR::Pyramid<Mesh> back;
  std::string error;
  REQUIRE(read_bytes(bytes_of(pyr), back, error));
  REQUIRE(bytes_of(back) == bytes_of(pyr));
  // (the file holds values where the details are their analysis: the reader's analysis, on
  // the halfedges its checks built, gives the decomposition's details bit for bit)
  for(std::size_t j = 1; j <= K; ++j)
    for(std::size_t c = 0; c < pyr.number_of_channels(); ++c)
    {
      const std::vector<double>& a = static_cast<const SMR::Pyramid<Mesh>&>(back).details(j, c);
      const std::vector<double>& b = pyr.details(j, c);
      REQUIRE(a.size() == b.size());
      CHECK(std::memcmp(a.data(), b.data(), 8 * a.size()) == 0);
      CHECK(back.levels()[j - 1].corrections[c] == pyr.levels()[j - 1].corrections[c]);
    }
}

} // namespace

TEST_CASE("every pyramid decompose() makes holds the invariants, also after filtering and denoising", "[attack][invariants]")
{
  for(int scheme = 0; scheme < 3; ++scheme)
  {
    Mesh m = smr_test::planar_grid<Mesh>(14, 0.3);
    auto uv = m.add_property_map<Mesh::Vertex_index, Vector_2>("v:uv").first;
    for(auto v : vertices(m)) uv[v] = Vector_2(m.point(v).x(), m.point(v).z());
    SMR::Pyramid<Mesh> pyr = SMR::decompose(m, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme(scheme))
                                                  .vertex_attribute_maps(std::make_tuple(uv)));
    REQUIRE(pyr.number_of_levels() > 3);
    CHECK(SMR::internal::check_pyramid(pyr) == "");
    SMR::enhance(pyr, 1, 2, 1.5);
    SMR::denoise(pyr, SMR::parameters::number_of_iterations(3u));
    CHECK(SMR::internal::check_pyramid(pyr) == "");
  }
  Mesh elephant;
  if(smr_test::read_cgal_mesh("meshes/elephant.off", elephant))
    CHECK(SMR::internal::check_pyramid(SMR::decompose(elephant)) == "");
}

// The pyramid with its weights stored in the levels and no weight positions, as read from
// a file of format 1 or 2: written in format 2, which serialises the records as they are
SMR::Pyramid<Mesh> with_stored_weights(const SMR::Pyramid<Mesh>& pyr)
{
  SMR::Pyramid<Mesh> stored = pyr;
  SMR::internal::Level_weights weights(pyr);
  std::vector<Index> F = pyr.coarse_faces();
  for(std::size_t k = pyr.number_of_levels(); k-- > 0; )
  {
    SMR::internal::expand_faces(pyr.levels()[k], F);
    Access::levels(stored)[k].weights = weights.of(pyr.levels()[k], F);
  }
  Access::weight_positions(stored).clear();
  return stored;
}

// The parts of a file of format 3, written as they are (see pyramid_io.h)
struct Format3_parts
{
  std::uint32_t scheme = 0;
  std::uint64_t n0 = 0, levels = 0;
  std::vector<std::uint64_t> dims{3};
  std::vector<double> positions;
  std::vector<Index> faces;                              // of M_0
  std::vector<std::vector<Index> > odd, targets;        // per level
  std::uint8_t kind = 0;                                 // of channel 0
  std::vector<std::vector<double> > details;            // kind 2: per level
  std::vector<SMR::internal::Corrections> corrections;  // kind 2: per level
  std::vector<double> coarse;                            // kind 2
  std::uint32_t version = 3;                             // 4: the pyramid's own order follows
  std::vector<Index> vertex_order, face_order;           // version 4 (empty: the input's)
  std::string trailing;

  explicit Format3_parts(const SMR::Pyramid<Mesh>& p)
    : n0(p.number_of_input_vertices()), levels(p.number_of_levels()), positions(p.weight_positions())
  {
    SMR::internal::reconstruct_faces(p, 0, faces);
    for(const auto& l : p.levels())
    {
      odd.push_back(l.odd_rows);
      targets.push_back(l.collapse_targets);
      details.push_back(l.details[0]);
      corrections.push_back(l.corrections[0]);
    }
    coarse = p.coarse_values()[0];
  }

  std::string bytes() const
  {
    SMR::internal::Byte_writer w;
    w.scalar(scheme);
    w.scalar(n0);
    w.array(dims);
    w.scalar(levels);
    w.array(positions);
    w.array(faces);
    for(std::size_t k = 0; k < odd.size(); ++k) { w.array(odd[k]); w.array(targets[k]); }
    w.scalar(kind);
    if(kind == 2)
    {
      for(std::size_t k = 0; k < details.size(); ++k) { w.array(details[k]); w.corrections(corrections[k]); }
      w.array(coarse);
    }
    if(version >= 4)
    {
      w.array(vertex_order);
      w.array(face_order);
    }
    const std::string payload = w.bytes() + trailing;
    std::string out(SMR::internal::pyramid_magic, 8);
    const std::uint32_t order = 0x01020304u;
    const std::uint64_t size = payload.size(), hash = SMR::internal::fnv1a(payload);
    out.append(reinterpret_cast<const char*>(&version), 4);
    out.append(reinterpret_cast<const char*>(&order), 4);
    out.append(reinterpret_cast<const char*>(&size), 8);
    out += payload;
    out.append(reinterpret_cast<const char*>(&hash), 8);
    return out;
  }
};

TEST_CASE("crafted pyramid files are refused with a reason", "[attack][io]")
{
  Mesh m = smr_test::planar_grid<Mesh>(10, 0.3);
  const SMR::Pyramid<Mesh> decomposed = SMR::decompose(m);
  REQUIRE(decomposed.number_of_levels() > 2);
  const std::size_t n1 = decomposed.number_of_vertices(1);
  // format 2 (the records as they are): each edit breaks one invariant; the writer writes
  // what it is given, the reader refuses it
  const SMR::Pyramid<Mesh> good = with_stored_weights(decomposed);
  {
    SMR::Pyramid<Mesh> p;
    std::string error;
    REQUIRE(read_bytes(bytes_of(good), p, error));
    CHECK(bytes_of(p).substr(8, 4) == std::string("\x02\0\0\0", 4));
  }
  const std::vector<std::pair<std::string, std::function<void(SMR::Pyramid<Mesh>&)> > > edits = {
    {"a face corner that is not a vertex of its level", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[1].removed_faces[0] = Index(p.number_of_vertices(1) + 3); }},
    {"a coarsest face corner outside the coarsest mesh", [](SMR::Pyramid<Mesh>& p) { Access::coarse_faces(p)[0] = Index(p.number_of_vertices(p.number_of_levels())); }},
    {"a renamed vertex that is not odd", [](SMR::Pyramid<Mesh>& p) { auto& l = Access::levels(p)[0]; l.renamed_vertices[0] = l.collapse_targets[0]; }},
    {"a renamed vertex that is another odd vertex", [](SMR::Pyramid<Mesh>& p) { auto& l = Access::levels(p)[0]; l.renamed_vertices[0] = l.renamed_vertices[0] == l.odd_rows[0] ? l.odd_rows[1] : l.odd_rows[0]; }},
    {"a collapse target outside its level", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[0].collapse_targets[0] = Index(p.number_of_vertices(0)); }},
    {"a collapse target that is odd", [](SMR::Pyramid<Mesh>& p) { auto& l = Access::levels(p)[0]; l.collapse_targets[0] = l.odd_rows[1]; }},
    {"two vertices collapsed into one", [](SMR::Pyramid<Mesh>& p) { auto& l = Access::levels(p)[0]; l.collapse_targets[1] = l.collapse_targets[0]; }},
    {"odd rows not increasing", [](SMR::Pyramid<Mesh>& p) { auto& l = Access::levels(p)[0]; std::swap(l.odd_rows[0], l.odd_rows[1]); }},
    {"an odd row outside its level", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[0].odd_rows.back() = Index(p.number_of_vertices(0)); }},
    {"a weight column outside its level", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[0].weights.columns[5] = Index(p.number_of_vertices(0)); }},
    {"a weight that is not finite", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[0].weights.values[5] = std::nan(""); }},
    {"weight offsets that decrease", [](SMR::Pyramid<Mesh>& p) { auto& w = Access::levels(p)[0].weights; std::swap(w.offsets[3], w.offsets[4]); }},
    {"details of the wrong size", [](SMR::Pyramid<Mesh>& p) { auto& d = Access::levels(p)[1].details[0]; d.resize(d.size() - 3); }},
    {"a detail that is infinite", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[1].details[0][4] = std::numeric_limits<double>::infinity(); }},
    {"a correction outside its level", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[0].corrections[0].emplace_back(Index(3 * p.number_of_vertices(0)), 1.); }},
    {"coarsest values of the wrong size", [](SMR::Pyramid<Mesh>& p) { Access::coarse_values(p)[0].push_back(1.); }},
    {"a removed face position outside its level", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[0].removed_face_positions.back() = Index(p.number_of_faces(0)); }},
    {"a removed face without its odd vertex", [](SMR::Pyramid<Mesh>& p) { auto& l = Access::levels(p)[0]; for(int i = 0; i < 3; ++i) l.removed_faces[i] = l.collapse_targets[i]; }},
    {"a renamed corner outside its level", [](SMR::Pyramid<Mesh>& p) { Access::levels(p)[0].renamed_corners[0] = Index(3 * p.number_of_faces(0)); }},
    {"a renamed corner in a removed face", [](SMR::Pyramid<Mesh>& p) { auto& l = Access::levels(p)[0]; l.renamed_corners[0] = 3 * l.removed_face_positions[0]; }},
    {"a coarsest face repeated (no halfedge mesh)", [](SMR::Pyramid<Mesh>& p) { auto& F = Access::coarse_faces(p); F.insert(F.end(), F.begin(), F.begin() + 3); }},
    {"a removed face's third corner moved (each level still a halfedge mesh, the collapse no longer valid)", [](SMR::Pyramid<Mesh>& p) {
       auto& l = Access::levels(p)[0];
       for(int i = 0; i < 3; ++i)
         if(std::find(l.odd_rows.begin(), l.odd_rows.end(), l.removed_faces[i]) == l.odd_rows.end() && l.removed_faces[i] != l.collapse_targets[0])
         { l.removed_faces[i] = l.even_rows[(l.removed_faces[i] + 17) % l.even_rows.size()]; break; } }},
    {"a removed face dropped (counts disagree)", [](SMR::Pyramid<Mesh>& p) { auto& l = Access::levels(p)[0]; l.removed_face_positions.pop_back(); }},
  };
  for(const auto& edit : edits)
  {
    INFO(edit.first);
    SMR::Pyramid<Mesh> bad = good;
    edit.second(bad);
    SMR::Pyramid<Mesh> p = good;
    std::string error;
    CHECK_FALSE(read_bytes(bytes_of(bad), p, error));
    CHECK(error.find("inconsistent pyramid") == 0);
    CHECK(p.number_of_vertices(1) == n1);   // left unchanged
  }
  // format 3 (positions, faces of M_0, collapses; the rest derived): the unedited parts are
  // read back as the decomposition made them, each edit is refused
  const Format3_parts parts(decomposed);
  {
    Format3_parts v4 = parts;   // format 4 with the input's order: the same pyramid
    v4.version = 4;
    SMR::Pyramid<Mesh> p;
    std::string error;
    REQUIRE(read_bytes(v4.bytes(), p, error));
    CHECK(bytes_of(p) == bytes_of(decomposed));
  }
  {
    SMR::Pyramid<Mesh> p;
    std::string error;
    REQUIRE(read_bytes(parts.bytes(), p, error));
    CHECK(bytes_of(p) == bytes_of(decomposed));
    Format3_parts explicit_details = parts;
    explicit_details.kind = 2;
    REQUIRE(read_bytes(explicit_details.bytes(), p, error));
    CHECK(bytes_of(p) == bytes_of(decomposed));
  }
  const std::vector<std::pair<std::string, std::function<void(Format3_parts&)> > > edits3 = {
    {"more levels than vertices", [](Format3_parts& f) { f.levels = f.n0 + 1; }},
    {"a missing weight position", [](Format3_parts& f) { f.positions.pop_back(); }},
    {"a weight position that is not finite", [](Format3_parts& f) { f.positions[7] = std::nan(""); }},
    {"a face corner outside M_0", [](Format3_parts& f) { f.faces[4] = Index(f.n0); }},
    {"a face of M_0 repeated (no halfedge mesh)", [](Format3_parts& f) { f.faces.insert(f.faces.end(), f.faces.begin(), f.faces.begin() + 3); }},
    {"a face of M_0 with a vertex twice", [](Format3_parts& f) { f.faces[1] = f.faces[0]; }},
    {"odd rows not increasing", [](Format3_parts& f) { std::swap(f.odd[0][0], f.odd[0][1]); }},
    {"an odd row outside its level", [](Format3_parts& f) { f.odd[1].back() = Index(f.n0); }},
    {"a collapse target missing", [](Format3_parts& f) { f.targets[0].pop_back(); }},
    {"a collapse target outside its level", [](Format3_parts& f) { f.targets[0][0] = Index(f.n0); }},
    {"a collapse target that is odd", [](Format3_parts& f) { f.targets[0][0] = f.odd[0][1]; }},
    {"two vertices collapsed into one", [](Format3_parts& f) { f.targets[0][1] = f.targets[0][0]; }},
    {"a collapse target that is no neighbour", [](Format3_parts& f) {
       for(Index v = 0; v < f.n0; ++v)
         if(!std::binary_search(f.odd[0].begin(), f.odd[0].end(), v)
            && std::find(f.targets[0].begin(), f.targets[0].end(), v) == f.targets[0].end())
         {
           bool neighbour = false;
           for(std::size_t i = 0; i < f.faces.size(); i += 3)
             if(std::find(f.faces.begin() + i, f.faces.begin() + i + 3, f.odd[0][0]) != f.faces.begin() + i + 3
                && std::find(f.faces.begin() + i, f.faces.begin() + i + 3, v) != f.faces.begin() + i + 3)
               neighbour = true;
           if(!neighbour) { f.targets[0][0] = v; return; }
         } }},
    {"two odd vertices in one face", [](Format3_parts& f) {
       // the first face's first two corners become the only odd vertices, into its third
       const Index a = (std::min)(f.faces[0], f.faces[1]), b = (std::max)(f.faces[0], f.faces[1]);
       f.odd[0] = {a, b};
       f.targets[0] = {f.faces[2], f.faces[2]}; }},
    {"a channel kind that does not exist", [](Format3_parts& f) { f.kind = 3; }},
    {"explicit details of the wrong size", [](Format3_parts& f) { f.kind = 2; f.details[1].resize(f.details[1].size() - 3); }},
    {"an explicit detail that is infinite", [](Format3_parts& f) { f.kind = 2; f.details[0][4] = std::numeric_limits<double>::infinity(); }},
    {"a correction outside its level", [](Format3_parts& f) { f.kind = 2; f.corrections[0].emplace_back(Index(3 * f.n0), 1.); }},
    {"coarsest values of the wrong size", [](Format3_parts& f) { f.kind = 2; f.coarse.push_back(1.); }},
    {"bytes after the payload", [](Format3_parts& f) { f.trailing = "x"; }},
    {"a vertex order that is not a permutation (format 4)", [](Format3_parts& f) {
       f.version = 4; f.vertex_order.resize(f.n0); std::iota(f.vertex_order.begin(), f.vertex_order.end(), Index(0)); f.vertex_order[1] = 0; }},
    {"a vertex order of the wrong size (format 4)", [](Format3_parts& f) {
       f.version = 4; f.vertex_order.resize(f.n0 - 1); std::iota(f.vertex_order.begin(), f.vertex_order.end(), Index(0)); }},
    {"a face order with a position outside M_0 (format 4)", [](Format3_parts& f) {
       f.version = 4; f.face_order.resize(f.faces.size() / 3); std::iota(f.face_order.begin(), f.face_order.end(), Index(0));
       f.face_order.back() = Index(f.face_order.size()); }},
  };
  for(const auto& edit : edits3)
  {
    INFO(edit.first);
    Format3_parts bad = parts;
    edit.second(bad);
    SMR::Pyramid<Mesh> p = decomposed;
    std::string error;
    CHECK_FALSE(read_bytes(bad.bytes(), p, error));
    CHECK(error.find("inconsistent pyramid") == 0);
    CHECK(p.number_of_vertices(1) == n1);   // left unchanged
  }
  // the two edits of payload words that once crashed reconstruct() and reconstruct_adaptively()
  std::string error;
  SMR::Pyramid<Mesh> p;
  REQUIRE(read_bytes(bytes_of(good), p, error));
  CHECK(error.empty());
  std::string v9 = bytes_of(good);
  std::uint32_t version = 9;
  std::memcpy(&v9[8], &version, 4);
  CHECK_FALSE(read_bytes(v9, p, error));
  CHECK(error == "pyramid format version 9 is not supported (versions 1 to 4 are)");
}

TEST_CASE("pyramid files of format version 1 are read and describe their mesh exactly", "[attack][io]")
{
  // grid8_v1.smrpyr: write_pyramid() of format version 1 for planar_grid(8, 0.3) with a
  // colour channel (the colour of vertex i: (i % 256, 7, 99))
  Mesh m = smr_test::planar_grid<Mesh>(8, 0.3);
  auto color = m.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  for(auto v : vertices(m)) color[v] = CGAL::IO::Color(static_cast<unsigned char>(v.idx() % 256), 7, 99);
  std::ifstream in(SMR_TEST_DATA_DIR "/grid8_v1.smrpyr", std::ios::binary);
  REQUIRE(in);
  SMR::Pyramid<Mesh> old;
  std::string error;
  REQUIRE(SMR::IO::read_pyramid(in, old, error));
  CHECK(SMR::internal::check_pyramid(old).empty());
  // (the selection has changed since: the file's levels are not those of a new decomposition,
  // but they reconstruct the mesh and its colours exactly, and survive a version 2 round trip)
  Mesh back;
  auto back_color = back.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  SMR::reconstruct(old, back, SMR::parameters::vertex_attribute_maps(std::make_tuple(back_color)));
  REQUIRE(num_vertices(back) == num_vertices(m));
  for(auto v : vertices(m))
  {
    CHECK(back.point(v) == m.point(v));
    CHECK(back_color[v] == color[v]);
  }
  SMR::Pyramid<Mesh> again_read;
  REQUIRE(read_bytes(bytes_of(old), again_read, error));
  CHECK(bytes_of(again_read) == bytes_of(old));
  // and a version 1 file whose records are edited is refused too
  std::ifstream again(SMR_TEST_DATA_DIR "/grid8_v1.smrpyr", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
  std::size_t refused = 0;
  for(std::size_t at = 24; at + 4 <= bytes.size() - 8; at += 4 * 37)   // about 300 words, of every array
  {
    std::string edited = bytes;
    std::uint32_t w;
    std::memcpy(&w, &edited[at], 4);
    w += 1;
    std::memcpy(&edited[at], &w, 4);
    SMR::Pyramid<Mesh> p;
    if(!read_bytes(with_checksum(edited), p, error))
      ++refused;
    else
      use_fully(p);
  }
  CHECK(refused > 0);
}

TEST_CASE("any finite coordinates: weights stay finite and the round trip is exact, -0.0 included", "[attack][extreme]")
{
  const double big = std::numeric_limits<double>::max();
  for(double scale : {1e300, -1e300, 1e-300, 4.9e-324 * 1024, big / 2})
  {
    INFO("scale " << scale);
    Mesh m = smr_test::icosphere<Mesh>(2);
    for(auto v : vertices(m))
    {
      const Point_3 p = m.point(v);
      m.point(v) = Point_3(p.x() * scale, p.y() * scale, v.idx() % 7 == 0 ? -0.0 : p.z() * scale);
    }
    // the operator's weights are finite and sum to 1
    const auto R = SMR::relaxation_operator(m);
    for(double w : R.weights()) REQUIRE(std::isfinite(w));
    for(int scheme = 0; scheme < 3; ++scheme)
    {
      const SMR::Pyramid<Mesh> pyr = SMR::decompose(m, SMR::parameters::relaxation_scheme(SMR::Relaxation_scheme(scheme)));
      CHECK(pyr.number_of_levels() > 3);
      REQUIRE(SMR::internal::check_pyramid(pyr) == "");   // finite weights, details and values
      for(std::size_t j = 1; j <= pyr.number_of_levels(); ++j)
        for(double l : pyr.detail_lengths(j, 0)) REQUIRE(std::isfinite(l));
      Mesh out;
      SMR::reconstruct(pyr, out);
      CHECK(coordinate_bits(out) == coordinate_bits(m));
      SMR::Pyramid<Mesh> back;
      std::string error;
      REQUIRE(read_bytes(bytes_of(pyr), back, error));
      Mesh coarse;
      SMR::reconstruct_adaptively(back, coarse, std::numeric_limits<double>::infinity());
      CHECK(num_vertices(coarse) == pyr.number_of_vertices(pyr.number_of_levels()));
    }
  }
}

TEST_CASE("seeded fuzzing: random meshes through every public function", "[attack][fuzz]")
{
  // SMR_FUZZ_SEED and SMR_FUZZ_TRIALS (environment) run other or longer campaigns
  const char* seed = std::getenv("SMR_FUZZ_SEED");
  const char* trials = std::getenv("SMR_FUZZ_TRIALS");
  CGAL::Random rng(seed != nullptr ? unsigned(std::stoul(seed)) : 20261201u);
  const int number_of_trials = trials != nullptr ? std::stoi(trials) : 40;
  for(int trial = 0; trial < number_of_trials; ++trial)
  {
    INFO("trial " << trial);
    // a sphere or a jittered grid, with holes, a second component, isolated vertices,
    // degenerate triangles, and coordinates at a random scale (with some -0.0)
    Mesh m = rng.get_int(0, 2) == 0 ? smr_test::icosphere<Mesh>(rng.get_int(0, 3))
                                    : smr_test::planar_grid<Mesh>(rng.get_int(2, 12), rng.get_double(0, 0.45), unsigned(trial));
    for(int h = rng.get_int(0, 4); h > 0 && num_faces(m) > 2; --h)
    {
      CGAL::Euler::remove_face(halfedge(Mesh::Face_index(rng.get_int(0, int(num_faces(m)))), m), m);
      m.collect_garbage();                                    // face indices stay 0..n-1
    }
    if(rng.get_int(0, 3) == 0)
    {
      Mesh other = smr_test::icosphere<Mesh>(1);
      for(auto v : vertices(other)) other.point(v) = other.point(v) + Vector_3(3, 0, 0);
      CGAL::copy_face_graph(other, m);
    }
    if(rng.get_int(0, 4) == 0)                                // a fan: a vertex of valence 40 to 200
    {
      const int d = rng.get_int(40, 201);
      std::vector<Mesh::Vertex_index> rim;
      for(int i = 0; i < d; ++i)
        rim.push_back(m.add_vertex(Point_3(5 + std::cos(6.283 * i / d), std::sin(6.283 * i / d), rng.get_double(0, 0.1))));
      const auto centre = m.add_vertex(Point_3(5, 0, 0.5));
      for(int i = 0; i + 1 < d; ++i)
        m.add_face(centre, rim[i], rim[i + 1]);
    }
    for(int i = rng.get_int(0, 3); i > 0; --i)
      m.add_vertex(Point_3(rng.get_double(), rng.get_double(), rng.get_double()));
    for(int i = rng.get_int(0, 4); i > 0 && num_vertices(m) > 1; --i)   // coincident points: zero-area triangles
      m.point(Mesh::Vertex_index(rng.get_int(0, int(num_vertices(m))))) = m.point(Mesh::Vertex_index(rng.get_int(0, int(num_vertices(m)))));
    const double scale = std::pow(10., 100 * rng.get_int(-3, 4));
    for(auto v : vertices(m))
    {
      const Point_3 p = m.point(v);
      m.point(v) = Point_3(p.x() * scale, rng.get_int(0, 10) == 0 ? -0.0 : p.y() * scale, p.z() * scale);
    }
    auto field = m.add_property_map<Mesh::Vertex_index, double>("v:f").first;
    auto uv = m.add_property_map<Mesh::Vertex_index, Vector_2>("v:uv").first;
    auto color = m.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:c").first;
    for(auto v : vertices(m))
    {
      field[v] = rng.get_int(0, 8) == 0 ? -0.0 : rng.get_double(-1, 1) * std::pow(10., rng.get_int(-300, 300));
      uv[v] = Vector_2(rng.get_double(), rng.get_double());
      color[v] = CGAL::IO::Color(static_cast<unsigned char>(rng.get_int(0, 256)), 0, 255);
    }
    const auto maps = std::make_tuple(field, uv, color);
    const SMR::Relaxation_scheme scheme = SMR::Relaxation_scheme(rng.get_int(0, 3));
    SMR::Pyramid<Mesh> pyr = SMR::decompose(m, SMR::parameters::relaxation_scheme(scheme).vertex_attribute_maps(maps));
    REQUIRE(SMR::internal::check_pyramid(pyr) == "");
    // exact round trip, bit for bit, every channel
    Mesh out;
    auto of = out.add_property_map<Mesh::Vertex_index, double>("v:f").first;
    auto ouv = out.add_property_map<Mesh::Vertex_index, Vector_2>("v:uv").first;
    auto oc = out.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:c").first;
    SMR::reconstruct(pyr, out, SMR::parameters::vertex_attribute_maps(std::make_tuple(of, ouv, oc)));
    REQUIRE(coordinate_bits(out) == coordinate_bits(m));
    for(auto v : vertices(m))
    {
      REQUIRE(std::memcmp(&of[v], &field[v], sizeof(double)) == 0);
      REQUIRE(ouv[v] == uv[v]);
      REQUIRE(oc[v] == color[v]);
    }
    use_fully(pyr);
    // relaxation of the geometry and the channels stays finite
    SMR::relax(m, SMR::parameters::relaxation_scheme(scheme).vertex_attribute_maps(maps));
    REQUIRE(all_finite(m));
    // random edits of the saved payload, checksum recomputed: refused, or accepted and usable
    const std::string bytes = bytes_of(pyr);
    for(int e = 0; e < 25; ++e)
    {
      INFO("payload edit " << e);
      std::string edited = bytes;
      const std::size_t words = (bytes.size() - 32) / 4;
      const std::size_t at = 24 + 4 * std::size_t(rng.get_int(0, int(words)));
      std::uint32_t w;
      std::memcpy(&w, &edited[at], 4);
      const std::uint32_t choices[] = {0u, 1u, w + 1, w - 1, 0xFFFFFFFFu, std::uint32_t(rng.get_int(0, 1 << 20))};
      const std::uint32_t was = w;
      w = choices[rng.get_int(0, 6)];
      std::memcpy(&edited[at], &w, 4);
      INFO("word at " << at << ": " << was << " -> " << w);
      SMR::Pyramid<Mesh> p;
      std::string error;
      if(read_bytes(with_checksum(edited), p, error))
        use_fully(p);
      else
        CHECK(!error.empty());
    }
  }
}

TEST_CASE("details are edited through fixed-size views, detail lengths are their norms without overflow", "[attack][details]")
{
  Mesh m = smr_test::icosphere<Mesh>(2);
  auto field = m.add_property_map<Mesh::Vertex_index, double>("v:f").first;
  for(auto v : vertices(m)) field[v] = double(v.idx());
  SMR::Pyramid<Mesh> pyr = SMR::decompose(m, SMR::parameters::vertex_attribute_maps(std::make_tuple(field)));
  REQUIRE(pyr.number_of_levels() > 1);
  SMR::Detail_view d = pyr.details(1, 0);
  REQUIRE(d.size() == 3 * pyr.number_of_vertices(0));
  d[0] = 3e300; d[1] = -4e300; d[2] = 0.;             // |(3, -4, 0)| = 5, at a scale where squares overflow
  d[3] = 3e-300; d[4] = 4e-300; d[5] = -0.;           // and where they underflow
  SMR::Detail_view s = pyr.details(1, 1);
  s[0] = -2.5;
  const std::vector<double> l = pyr.detail_lengths(1, 0);
  REQUIRE(l.size() == pyr.number_of_vertices(0));
  CHECK(l[0] == Approx(5e300).epsilon(1e-15));
  CHECK(l[1] / 1e-300 == Approx(5.).epsilon(1e-15));
  CHECK(pyr.detail_lengths(1, 1)[0] == 2.5);          // a scalar channel: the absolute value
  for(std::size_t r = 2; r < l.size(); ++r)
  {
    const double* x = std::as_const(pyr).details(1, 0).data() + 3 * r;
    CHECK(l[r] == std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));   // ordinary values: the plain formula
  }
  for(double& x : pyr.details(2, 0)) x = 0.;          // a range of doubles
  CHECK(std::as_const(pyr).details(2, 0) == std::vector<double>(3 * pyr.number_of_vertices(1), 0.));
  REQUIRE_THROWS_AS(pyr.detail_lengths(0, 0), std::invalid_argument);
  REQUIRE_THROWS_AS(pyr.detail_lengths(1, 2), std::invalid_argument);
}

TEST_CASE("adaptive faces: keeping exactly the vertices of M_k gives the faces of M_k", "[attack][adaptive]")
{
  Mesh m = smr_test::planar_grid<Mesh>(16, 0.3);
  CGAL::Euler::remove_face(halfedge(Mesh::Face_index(100), m), m);   // a hole
  m.collect_garbage();
  const SMR::Pyramid<Mesh> pyr = SMR::decompose(m);
  REQUIRE(pyr.number_of_levels() > 3);
  SMR::internal::Adaptive_hierarchy h;
  SMR::internal::build_adaptive_hierarchy(pyr, h);
  auto canonical = [](Index a, Index b, Index c) {
    std::array<Index, 3> t{{a, b, c}};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  for(std::size_t k = 0; k <= pyr.number_of_levels(); ++k)
  {
    INFO("level " << k);
    std::vector<unsigned char> keep(pyr.number_of_vertices(0), 0);
    for(Index g : pyr.vertices(k)) keep[g] = 1;
    std::vector<Index> kept;
    const std::vector<Index> F = SMR::internal::adaptive_faces(pyr, h, keep, kept);
    CHECK(kept == pyr.vertices(k));
    std::vector<Index> Fk;
    SMR::internal::reconstruct_faces(pyr, k, Fk);              // rows of M_k = rows of `kept`
    std::multiset<std::array<Index, 3> > a, b;
    for(std::size_t i = 0; i < F.size(); i += 3) a.insert(canonical(F[i], F[i + 1], F[i + 2]));
    for(std::size_t i = 0; i < Fk.size(); i += 3) b.insert(canonical(Fk[i], Fk[i + 1], Fk[i + 2]));
    CHECK(a == b);
  }
}

// the halfedges of a planar grid of size x size squares (smr_test::planar_grid) and its
// border flags
struct Grid_halfedges
{
  Grid_halfedges(int size, double jitter)
  {
    const Mesh m = smr_test::planar_grid<Mesh>(size, jitter);
    SMR::internal::Indexed_mesh<Mesh> im;
    SMR::internal::build_indexed_mesh(m, get(CGAL::vertex_index, m), im);
    n = im.number_of_vertices();
    th.build(n, im.triangles, true);
    on_border.assign(n, 0);
    for(std::size_t h = 3 * th.nf; h < th.source.size(); ++h)
      on_border[th.source[h]] = on_border[th.target[h]] = 1;
  }
  std::size_t n = 0;
  SMR::internal::Triangle_halfedges th;
  std::vector<unsigned char> on_border;
};

TEST_CASE("a level's collapses are checked in parallel and the first refused one is reported", "[attack][io]")
{
  using SMR::internal::Index;
  // a level of more than two parallel blocks of collapses (the blocks are 8192 long): a greedy
  // independent set of interior vertices of a 300 x 300 grid, each collapsed into its first
  // free neighbour along an edge that satisfies the link condition
  const Grid_halfedges grid(300, 0.2);
  const SMR::internal::Triangle_halfedges& th = grid.th;
  const std::vector<unsigned char>& on_border = grid.on_border;
  const std::size_t n = grid.n;
  std::vector<unsigned char> taken(n, 0);
  SMR::internal::Pyramid_level lev;
  for(Index v = 0; v < n; ++v)
    lev.vertices.push_back(v);
  for(Index o = 0; o < n; ++o)
  {
    if(taken[o] || on_border[o])
      continue;
    for(Index k = th.out_offsets[o]; k < th.out_offsets[o + 1]; ++k)
    {
      const Index e = th.out_target[k];
      if(taken[e] == 1 || !SMR::internal::satisfies_link_condition(th, th.out[k], o, e, on_border))
        continue;
      lev.odd_rows.push_back(o);
      lev.collapse_targets.push_back(e);
      taken[o] = 1;                                   // odd
      for(Index q = th.out_offsets[o]; q < th.out_offsets[o + 1]; ++q)
        taken[th.out_target[q]] = (std::max)(taken[th.out_target[q]], static_cast<unsigned char>(2));   // a neighbour: not odd
      taken[e] = 1;                                   // a target: neither odd nor a target again
      break;
    }
  }
  const std::size_t odd = lev.odd_rows.size();
  REQUIRE(odd > 2 * 8192);
  CHECK(SMR::internal::check_level_halfedges(lev, th).empty());
  // two refusals far apart (different blocks): the one of the earlier odd row is reported,
  // whichever comes first
  const std::string neighbours = "two odd vertices are neighbours", far = "a collapse target is not a neighbour of its odd vertex";
  auto with_refusals = [&](std::size_t odd_pair_at, std::size_t far_target_at) {
    SMR::internal::Pyramid_level bad = lev;
    // a vertex two rows away from odd row `far_target_at` (not among its neighbours) as its target
    const Index o = bad.odd_rows[far_target_at];
    bad.collapse_targets[far_target_at] = o + 2 * 301 < n ? o + 2 * 301 : o - 2 * 301;
    for(Index k = th.out_offsets[o]; k < th.out_offsets[o + 1]; ++k)
      REQUIRE(th.out_target[k] != bad.collapse_targets[far_target_at]);
    // a neighbour of the odd row `odd_pair_at` made odd too, with a target of its own
    const Index a = bad.odd_rows[odd_pair_at];
    for(Index k = th.out_offsets[a]; k < th.out_offsets[a + 1]; ++k)
    {
      const Index b = th.out_target[k];
      if(std::find(bad.collapse_targets.begin(), bad.collapse_targets.end(), b) != bad.collapse_targets.end())
        continue;
      const auto at = std::lower_bound(bad.odd_rows.begin(), bad.odd_rows.end(), b);
      bad.collapse_targets.insert(bad.collapse_targets.begin() + (at - bad.odd_rows.begin()), a);
      bad.odd_rows.insert(at, b);
      break;
    }
    REQUIRE(bad.odd_rows.size() == odd + 1);
    return SMR::internal::check_level_halfedges(bad, th);
  };
  CHECK(with_refusals(odd / 5, 4 * odd / 5) == neighbours);
  CHECK(with_refusals(4 * odd / 5, odd / 5) == far);
}

TEST_CASE("crossed collapses are refused by the selection rule and by the reader's checks", "[attack][io]")
{
  using SMR::internal::Index;
  // Two interior vertices o1, o2 of a grid that are not neighbours and share two neighbours a
  // and b: o1 -> a with o2 -> b crosses (b next to o1, a next to o2), each collapse alone is valid
  const Grid_halfedges grid(8, 0.1);
  const SMR::internal::Triangle_halfedges& th = grid.th;
  const std::vector<unsigned char>& on_border = grid.on_border;
  const std::size_t n = grid.n;
  auto neighbour = [&](Index v, Index k) { return th.out_target[th.out_offsets[v] + k]; };
  auto valence = [&](Index v) { return th.out_offsets[v + 1] - th.out_offsets[v]; };
  auto adjacent = [&](Index u, Index v) {
    for(Index k = 0; k < valence(u); ++k)
      if(neighbour(u, k) == v) return true;
    return false;
  };
  auto halfedge_between = [&](Index u, Index v) {
    for(Index k = th.out_offsets[u]; k < th.out_offsets[u + 1]; ++k)
      if(th.out_target[k] == v) return th.out[k];
    return SMR::internal::invalid_index;
  };
  Index o1 = 0, o2 = 0, a = 0, b = 0;
  bool found = false;
  for(Index u = 0; u < n && !found; ++u)
    for(Index v = u + 1; v < n && !found; ++v)
    {
      if(on_border[u] || on_border[v] || adjacent(u, v)) continue;
      Index common[2], shared = 0;
      for(Index k = 0; k < valence(u); ++k)
        if(adjacent(v, neighbour(u, k)) && shared++ < 2) common[shared - 1] = neighbour(u, k);
      if(shared != 2) continue;
      o1 = u; o2 = v; a = common[0]; b = common[1]; found = true;
    }
  REQUIRE(found);
  REQUIRE(SMR::internal::satisfies_link_condition(th, halfedge_between(o1, a), o1, a, on_border));
  REQUIRE(SMR::internal::satisfies_link_condition(th, halfedge_between(o2, b), o2, b, on_border));
  std::vector<Index> source_of(n, SMR::internal::invalid_index);   // o1 -> a taken
  source_of[a] = o1;
  CHECK(SMR::internal::crosses_a_taken_collapse(th, o2, b, [&](Index y) { return source_of[y] != SMR::internal::invalid_index; },
                                                [&](Index y) { return source_of[y]; }));
  SMR::internal::Pyramid_level lev;
  for(Index v = 0; v < n; ++v)
    lev.vertices.push_back(v);
  auto level_with = [&](Index t1, Index t2) {
    SMR::internal::Pyramid_level l = lev;
    l.odd_rows = {o1, o2};                             // o1 < o2
    l.collapse_targets = {t1, t2};
    return SMR::internal::check_level_halfedges(l, th);
  };
  CHECK(level_with(a, b) == "two collapses cross (each target next to the other's odd vertex)");
  // o2 into a neighbour that is not next to o1: no crossing, a valid level
  Index c = SMR::internal::invalid_index;
  for(Index k = 0; k < valence(o2); ++k)
  {
    const Index w = neighbour(o2, k);
    if(w != a && w != b && !adjacent(o1, w) && SMR::internal::satisfies_link_condition(th, halfedge_between(o2, w), o2, w, on_border))
      c = w;
  }
  REQUIRE(c != SMR::internal::invalid_index);
  CHECK(level_with(a, c).empty());
}
