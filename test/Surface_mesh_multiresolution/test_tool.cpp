// SPDX-License-Identifier: GPL-3.0-or-later
// The command-line tool smr, run as a user runs it, on generated files: channels kept with
// their names and exact values, triangle strips, polygon soups, pinched surfaces, unreferenced
// vertices, and bad files refused with a message and a non-zero exit status, no output left.
#include <catch2/catch.hpp>
#include "smr_test_utils.h"
#include "scan_io.h"

#include <CGAL/Polygon_mesh_processing/border.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>

using smr_tool::Mesh;
using smr_tool::Point;

namespace {

// Each test case works in a directory of its own under the build tree's tool_work/ (whatever
// the working directory: run by hand from the source tree, the files went there): CTest runs
// the cases as parallel processes, which wrote and read the same file names (sphere.ply,
// smr_stderr.txt) at the same time and sometimes read each other's files.
struct Own_directory
{
  std::filesystem::path previous;
  explicit Own_directory(const std::string& name) : previous(std::filesystem::current_path())
  {
    const std::filesystem::path dir = std::filesystem::path(SMR_TOOL_WORK_DIR) / name;
    std::filesystem::create_directories(dir);
    std::filesystem::current_path(dir);
  }
  ~Own_directory() { std::filesystem::current_path(previous); }
};

struct Run { int status; std::string err; };

// runs `smr ARGS` in the working directory, stderr captured
Run smr(const std::string& args)
{
  const std::string cmd = std::string(SMR_TOOL) + " " + args + " 2> smr_stderr.txt > smr_stdout.txt";
  const int raw = std::system(cmd.c_str());
  std::ifstream is("smr_stderr.txt");
  std::stringstream ss;
  ss << is.rdbuf();
  return Run{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, ss.str()};
}

bool exists(const std::string& file) { return std::ifstream(file).good(); }

void write_text(const std::string& file, const std::string& text)
{
  std::ofstream os(file, std::ios::binary);
  os << text;
}

// a coloured sphere written as binary PLY (colours uchar, a float 'quality' scalar)
void write_coloured_sphere(const std::string& file, int subdivisions)
{
  smr_tool::Scan s;
  s.mesh = smr_test::icosphere<Mesh>(subdivisions);
  s.channels = {smr_tool::Channel{"color", {"red", "green", "blue"}, {"uchar", "uchar", "uchar"}},
                smr_tool::Channel{"scalar", {"quality"}, {"float"}}};
  s.maps = smr_tool::add_channel_maps(s.mesh, 2);
  for(auto v : vertices(s.mesh))
  {
    const Point& p = s.mesh.point(v);
    s.maps[0][v] = {{std::round(127.5 + 127.5 * p.x()), std::round(127.5 + 127.5 * p.y()), double((v.idx() * 37) % 256), 0.}};
    s.maps[1][v] = {{double(float(p.z() * 0.25)), 0., 0., 0.}};
  }
  std::string dropped;
  smr_tool::write_scan(file, s.mesh, s.channels, s.maps, true, dropped);
}

} // namespace

TEST_CASE("decompose then reconstruct gives the PLY back byte for byte, channels included", "[tool]")
{
  const Own_directory here("round_trip");
  write_coloured_sphere("sphere.ply", 3);
  REQUIRE(smr("decompose sphere.ply -o sphere.smrp").status == 0);
  REQUIRE(smr("reconstruct sphere.smrp -o sphere0.ply").status == 0);
  std::ifstream a("sphere.ply", std::ios::binary), b("sphere0.ply", std::ios::binary);
  const std::string sa((std::istreambuf_iterator<char>(a)), {}), sb((std::istreambuf_iterator<char>(b)), {});
  CHECK(sa == sb);
  const Run quiet = smr("reconstruct sphere.smrp -o sphere1.ply --level 1 --quiet");   // --quiet after the subcommand too
  REQUIRE(quiet.status == 0);
  CHECK(quiet.err.empty());
  REQUIRE(smr("info sphere.smrp").status == 0);
  std::ifstream info("smr_stdout.txt");
  const std::string text((std::istreambuf_iterator<char>(info)), {});
  CHECK(text.find("color (red green blue)") != std::string::npos);
  CHECK(text.find("scalar (quality)") != std::string::npos);
}

TEST_CASE("a level of detail keeps input vertices with their exact colours and scalars", "[tool]")
{
  const Own_directory here("lod");
  write_coloured_sphere("sphere.ply", 4);
  const smr_tool::Scan in = smr_tool::read_scan("sphere.ply");
  for(const char* guide : {"", "--guide color"})
  {
    REQUIRE(smr(std::string("lod sphere.ply -o lod.ply --ratio 0.1 ") + guide).status == 0);
    const smr_tool::Scan out = smr_tool::read_scan("lod.ply");
    REQUIRE(out.channels.size() == 2);
    CHECK(out.channels[0].names == std::vector<std::string>{"red", "green", "blue"});
    CHECK(out.channels[0].types == std::vector<std::string>{"uchar", "uchar", "uchar"});
    CHECK(num_vertices(out.mesh) == std::size_t(std::lround(0.1 * double(num_vertices(in.mesh)))));
    std::map<Point, Mesh::Vertex_index> by_position;
    for(auto v : vertices(in.mesh)) by_position[in.mesh.point(v)] = v;
    std::size_t matched = 0;
    for(auto v : vertices(out.mesh))
    {
      const auto it = by_position.find(out.mesh.point(v));
      REQUIRE(it != by_position.end());                  // an input vertex, at its exact position
      CHECK(out.maps[0][v] == in.maps[0][it->second]);   // its colour
      CHECK(out.maps[1][v] == in.maps[1][it->second]);   // its scalar
      ++matched;
    }
    CHECK(matched == num_vertices(out.mesh));
    CHECK(CGAL::is_closed(out.mesh));
  }
}

TEST_CASE("triangle strips are expanded with a consistent orientation", "[tool]")
{
  const Own_directory here("strips");
  // a 4 x 3 grid of vertices as two strips (rows), the second restarted with -1 in one list
  std::string ply = "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\n"
                    "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
  for(int j = 0; j < 3; ++j)
    for(int i = 0; i < 4; ++i) ply += std::to_string(i) + " " + std::to_string(j) + " 0\n";
  ply += "17 4 0 5 1 6 2 7 3 -1 8 4 9 5 10 6 11 7\n";
  write_text("strips.ply", ply);
  const Run r = smr("relax strips.ply -o strips_out.ply --iterations 0");
  REQUIRE(r.status == 0);
  CHECK(r.err.find("triangle strips expanded: 12 triangles") != std::string::npos);
  const smr_tool::Scan out = smr_tool::read_scan("strips_out.ply");
  CHECK(num_faces(out.mesh) == 12);
  CHECK(num_vertices(out.mesh) == 12);
  std::vector<Mesh::Halfedge_index> borders;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(out.mesh, std::back_inserter(borders));
  CHECK(borders.size() == 1);                            // one sheet, no flipped face cut it apart
  for(auto f : faces(out.mesh))                          // every face keeps the strip's orientation (+z)
  {
    const auto h = halfedge(f, out.mesh);
    const Point &a = out.mesh.point(source(h, out.mesh)), &b = out.mesh.point(target(h, out.mesh)),
                &c = out.mesh.point(target(next(h, out.mesh), out.mesh));
    CHECK(CGAL::cross_product(b - a, c - a).z() > 0);
  }
}

TEST_CASE("a polygon soup (STL) is welded, a pinched surface is split, unreferenced vertices go: all said", "[tool]")
{
  const Own_directory here("soup");
  // an octahedron as an STL soup: 8 triangles, 24 corners, 6 distinct positions
  const Point p[6] = {Point(1, 0, 0), Point(-1, 0, 0), Point(0, 1, 0), Point(0, -1, 0), Point(0, 0, 1), Point(0, 0, -1)};
  const int t[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  std::ostringstream stl;
  stl << "solid octahedron\n";
  for(const auto& f : t)
  {
    stl << "facet normal 0 0 0\nouter loop\n";
    for(int j = 0; j < 3; ++j) stl << "vertex " << p[f[j]].x() << " " << p[f[j]].y() << " " << p[f[j]].z() << "\n";
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid octahedron\n";
  write_text("soup.stl", stl.str());
  Run r = smr("relax soup.stl -o soup_out.off --iterations 0");
  REQUIRE(r.status == 0);
  Mesh m;
  REQUIRE(CGAL::IO::read_polygon_mesh("soup_out.off", m));
  CHECK(num_vertices(m) == 6);
  CHECK(num_faces(m) == 8);
  CHECK(CGAL::is_closed(m));
  // two triangles that share one vertex only (a bow tie), plus two vertices no face uses
  write_text("bowtie.ply", "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                           "0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n5 5 5\n6 6 6\n3 0 1 2\n3 0 3 4\n");
  r = smr("relax bowtie.ply -o bowtie_out.ply --iterations 0");
  REQUIRE(r.status == 0);
  CHECK(r.err.find("2 unreferenced vertices removed") != std::string::npos);
  CHECK(r.err.find("1 vertex duplicated") != std::string::npos);
  const smr_tool::Scan out = smr_tool::read_scan("bowtie_out.ply");
  CHECK(num_vertices(out.mesh) == 6);
  CHECK(num_faces(out.mesh) == 2);
  CHECK(CGAL::is_valid_polygon_mesh(out.mesh));
}

TEST_CASE("bad files and arguments: a message, a non-zero status, no output file", "[tool][input]")
{
  const Own_directory here("bad_input");
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  write_text("bad_index.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  write_text("truncated.ply", header + "0 0 0\n1 0 0\n");
  write_text("no_faces.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n");
  write_text("junk.ply", "this is not a mesh\n\x01\x02\x03");
  write_text("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  {
    // a binary PLY with an infinite coordinate
    std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 1, 0, std::numeric_limits<float>::infinity(), 0, 1, 0};
    bin.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    bin.push_back(char(3));
    const std::int32_t f[3] = {0, 1, 2};
    bin.append(reinterpret_cast<const char*>(f), sizeof f);
    write_text("infinite.ply", bin);
  }
  write_coloured_sphere("sphere.ply", 2);
  REQUIRE(smr("decompose sphere.ply -o good.smrp").status == 0);
  {
    std::ifstream is("good.smrp", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(is)), {});
    write_text("cut.smrp", bytes.substr(0, bytes.size() / 2));
  }
  const std::vector<std::pair<std::string, std::string> > cases = {
    {"lod bad_index.ply -o out.ply --ratio 0.5", "refers to vertex 7"},
    {"lod truncated.ply -o out.ply --ratio 0.5", "truncated"},
    {"decompose no_faces.ply -o out.smrp", "no faces"},
    {"denoise junk.ply -o out.ply", "not a PLY file"},
    {"relax infinite.ply -o out.ply", "non-finite"},
    {"reconstruct cut.smrp -o out.ply", "cut.smrp"},
    {"reconstruct good.smrp -o out.ply --level 99", "does not exist"},
    {"filter good.smrp -o out.ply --stop-band 1 99", "not a range"},
    {"lod good.smrp -o out.ply --guide texture --ratio 0.5", "no such channel"},
    {"relax missing.ply -o out.ply", "cannot open"},
    {"relax sphere.ply -o out.xyz", "unknown output format"},
    {"decompose sphere.ply -o out.ply", "pyramid format"},
  };
  for(const auto& c : cases)
  {
    INFO(c.first);
    std::remove("out.ply");
    std::remove("out.smrp");
    const Run r = smr(c.first);
    CHECK(r.status == 1);
    CHECK(r.err.find(c.second) != std::string::npos);
    CHECK(!exists("out.ply"));
    CHECK(!exists("out.smrp"));
    CHECK(!exists("out.ply.partial.ply"));
  }
  // the quad is triangulated (said), not refused
  const Run q = smr("relax quad.off -o quad_out.off --iterations 0");
  CHECK(q.status == 0);
  CHECK(q.err.find("1 polygon with more than 3 corners triangulated") != std::string::npos);
  // arguments CLI11 refuses: its message and status
  CHECK(smr("lod sphere.ply -o out.ply --ratio 2").status != 0);
  CHECK(smr("filter sphere.ply -o out.ply --low-pass 1 --stop-band 1 2").status != 0);
  CHECK(smr("").status != 0);
}

TEST_CASE("seeded fuzzing of the PLY reader: every mutated file is read into a valid mesh or refused with a message", "[tool][input][fuzz]")
{
  const Own_directory here("fuzz");
  // binary and ASCII, faces and strips; bytes flipped, truncated, header words changed
  write_coloured_sphere("fuzz_base.ply", 1);
  std::ifstream is("fuzz_base.ply", std::ios::binary);
  const std::string binary((std::istreambuf_iterator<char>(is)), {});
  std::string ascii = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
                      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
  for(int i = 0; i < 6; ++i) ascii += std::to_string(i % 3) + " " + std::to_string(i / 3) + " 0 " + std::to_string(40 * i) + " 7 9\n";
  ascii += "7 0 3 1 4 2 5 -1\n";
  std::mt19937 random(20261201);
  std::size_t refused = 0, read = 0;
  for(int trial = 0; trial < 600; ++trial)
  {
    std::string bytes = trial % 2 ? binary : ascii;
    const int edits = 1 + int(random() % 4);
    for(int e = 0; e < edits; ++e)
    {
      const std::size_t at = random() % bytes.size();
      switch(random() % 4)
      {
        case 0: bytes[at] = char(random() % 256); break;                       // a byte flipped
        case 1: bytes.resize(at); break;                                        // truncated
        case 2: bytes[at] = "0123456789-. \n"[random() % 14]; break;            // a plausible character
        default: bytes.insert(at, std::string(1 + random() % 8, char(0xff)));  // bytes inserted
      }
      if(bytes.empty()) bytes = "p";
    }
    write_text("fuzz.ply", bytes);
    try
    {
      const smr_tool::Scan s = smr_tool::read_scan("fuzz.ply");
      ++read;
      REQUIRE(CGAL::is_valid_polygon_mesh(s.mesh));
      REQUIRE(CGAL::is_triangle_mesh(s.mesh));
      REQUIRE(s.maps.size() == s.channels.size());
      for(auto v : vertices(s.mesh))
        for(int d = 0; d < 3; ++d) REQUIRE(std::isfinite(s.mesh.point(v)[d]));
    }
    catch(const std::runtime_error& e)
    {
      ++refused;
      REQUIRE(std::string(e.what()).size() > 10);
    }
  }
  INFO(read << " read, " << refused << " refused");
  CHECK(read > 0);
  CHECK(refused > 0);
}

TEST_CASE("the soup check answers as CGAL's is_polygon_soup_a_polygon_mesh()", "[tool][soup]")
{
  typedef std::vector<std::vector<std::size_t> > Polygons;
  auto agree = [](const Polygons& polygons, std::size_t points) {
    const bool ours = smr_tool::is_oriented_polygon_mesh(polygons, points);
    const bool cgal = CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons);
    CHECK(ours == cgal);
    return cgal;
  };
  SECTION("known answers")
  {
    // one triangle; a square as two triangles and as one quad; a closed tetrahedron
    CHECK(agree({{0, 1, 2}}, 3));
    CHECK(agree({{0, 1, 2}, {0, 2, 3}}, 4));
    CHECK(agree({{0, 1, 2, 3}}, 4));
    CHECK(agree({{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}, 4));
    // two triangles meeting at a vertex (a bow tie) and two tetrahedra sharing a vertex
    CHECK_FALSE(agree({{0, 1, 2}, {0, 3, 4}}, 5));
    CHECK_FALSE(agree({{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 5, 4}, {0, 4, 6}, {4, 5, 6}, {5, 0, 6}}, 7));
    // an edge in three triangles; a face reversed; a corner twice; too few corners
    CHECK_FALSE(agree({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}, 5));
    CHECK_FALSE(agree({{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}, 4));
    CHECK_FALSE(agree({{0, 1, 0, 2}}, 3));
    CHECK_FALSE(agree({{0, 1}}, 2));
    CHECK(agree({}, 0));
  }
  SECTION("a vertex of high degree: a closed fan, a half-disk, two half-disks")
  {
    // a double cone: apexes 0 and 1, a ring of m vertices 2 .. m+1; every apex has degree m
    const std::size_t m = 1000;
    Polygons cone;
    for(std::size_t i = 0; i < m; ++i)
    {
      const std::size_t a = 2 + i, b = 2 + (i + 1) % m;
      cone.push_back({0, a, b});
      cone.push_back({1, b, a});
    }
    CHECK(agree(cone, m + 2));                 // closed: every fan a disk
    Polygons open = cone;
    open.erase(open.begin());                  // one triangle at apex 0 out: a half-disk there
    CHECK(agree(open, m + 2));
    open.erase(open.begin() + std::ptrdiff_t(m - 1));   // {0, 502, 503}, far from the first: two half-disks at 0
    CHECK_FALSE(agree(open, m + 2));
  }
  SECTION("seeded random damage to a sphere's soup")
  {
    const Mesh sphere = smr_test::icosphere<Mesh>(2);
    Polygons base;
    for(auto f : faces(sphere))
    {
      std::vector<std::size_t> p;
      for(auto v : vertices_around_face(halfedge(f, sphere), sphere)) p.push_back(v.idx());
      base.push_back(p);
    }
    const std::size_t n = num_vertices(sphere);
    std::mt19937 rng(2026);
    std::size_t meshes = 0, not_meshes = 0;
    for(int trial = 0; trial < 400; ++trial)
    {
      Polygons soup = base;
      const int removals = int(rng() % 16);
      for(int r = 0; r < removals && soup.size() > 1; ++r) soup.erase(soup.begin() + std::ptrdiff_t(rng() % soup.size()));
      if(rng() % 4 == 0)
      {
        auto& p = soup[rng() % soup.size()];
        std::reverse(p.begin(), p.end());
      }
      if(rng() % 4 == 0)   // two vertices identified: pinches, non-manifold edges, repeated corners
      {
        const std::size_t a = rng() % n, b = rng() % n;
        for(auto& p : soup) for(auto& v : p) if(v == b) v = a;
      }
      if(rng() % 8 == 0) soup.push_back(soup[rng() % soup.size()]);
      if(rng() % 8 == 0 && soup.size() > 1)   // two triangles sharing an edge merged into a quad
      {
        const std::vector<std::size_t> t = soup.back();
        for(std::size_t i = 0; i + 1 < soup.size(); ++i)
        {
          const auto& u = soup[i];
          if(u.size() != 3 || t.size() != 3) continue;
          for(int e = 0; e < 3; ++e)
          {
            const std::size_t x = t[std::size_t(e)], y = t[std::size_t((e + 1) % 3)], z = t[std::size_t((e + 2) % 3)];
            for(int g = 0; g < 3; ++g)
              if(u[std::size_t(g)] == y && u[std::size_t((g + 1) % 3)] == x)
              {
                soup[i] = {x, u[std::size_t((g + 2) % 3)], y, z};
                soup.pop_back();
                goto merged;
              }
          }
        }
      merged:;
      }
      std::shuffle(soup.begin(), soup.end(), rng);
      (agree(soup, n) ? meshes : not_meshes) += 1;
    }
    INFO(meshes << " polygon meshes, " << not_meshes << " not");
    CHECK(meshes > 50);
    CHECK(not_meshes > 50);
  }
}

TEST_CASE("smr --spatial-order keeps every vertex with its values and every face, in a local order", "[tool][order]")
{
  const Own_directory here("spatial_order");
  // a coloured sphere whose vertices and faces are shuffled: neighbours far apart in the file
  smr_tool::Scan s;
  {
    const Mesh sphere = smr_test::icosphere<Mesh>(4);
    const std::size_t n = num_vertices(sphere);
    std::vector<std::size_t> perm(n);
    for(std::size_t i = 0; i < n; ++i) perm[i] = i;
    std::mt19937 rng(7);
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<Mesh::Vertex_index> made(n);
    std::vector<std::size_t> inverse(n);
    for(std::size_t i = 0; i < n; ++i) inverse[perm[i]] = i;
    for(std::size_t i = 0; i < n; ++i) made[i] = s.mesh.add_vertex(sphere.point(Mesh::Vertex_index(Mesh::size_type(inverse[i]))));
    std::vector<Mesh::Face_index> fs(faces(sphere).begin(), faces(sphere).end());
    std::shuffle(fs.begin(), fs.end(), rng);
    for(auto f : fs)
    {
      std::vector<Mesh::Vertex_index> t;
      for(auto v : vertices_around_face(halfedge(f, sphere), sphere)) t.push_back(made[perm[v.idx()]]);
      s.mesh.add_face(t);
    }
  }
  s.channels = {smr_tool::Channel{"scalar", {"quality"}, {"double"}}};
  s.maps = smr_tool::add_channel_maps(s.mesh, 1);
  for(auto v : vertices(s.mesh)) s.maps[0][v] = {{double(v.idx()) * 0.5, 0., 0., 0.}};
  std::string dropped;
  smr_tool::write_scan("shuffled.ply", s.mesh, s.channels, s.maps, true, dropped);
  REQUIRE(smr("relax shuffled.ply -o ordered.ply --iterations 0 --spatial-order").status == 0);
  REQUIRE(smr("relax shuffled.ply -o as_read.ply --iterations 0").status == 0);
  const smr_tool::Scan in = smr_tool::read_scan("as_read.ply"), out = smr_tool::read_scan("ordered.ply");
  REQUIRE(num_vertices(out.mesh) == num_vertices(in.mesh));
  REQUIRE(num_faces(out.mesh) == num_faces(in.mesh));
  // every vertex at its position with its value; every face with its corners in their cyclic order
  std::map<Point, std::array<double, 4> > value_at;
  for(auto v : vertices(in.mesh)) value_at[in.mesh.point(v)] = in.maps[0][v];
  for(auto v : vertices(out.mesh))
  {
    const auto it = value_at.find(out.mesh.point(v));
    REQUIRE(it != value_at.end());
    CHECK(it->second == out.maps[0][v]);
  }
  auto face_set = [](const Mesh& m) {
    std::set<std::array<Point, 3> > set;
    for(auto f : faces(m))
    {
      std::array<Point, 3> t;
      int i = 0;
      for(auto v : vertices_around_face(halfedge(f, m), m)) t[std::size_t(i++)] = m.point(v);
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      set.insert(t);
    }
    return set;
  };
  CHECK(face_set(out.mesh) == face_set(in.mesh));
  // the library's own order (Memory_order::SPATIAL): the vertices numbered in the order the
  // faces first name them, and the order is a fixed point (ordering the output again changes
  // nothing: its faces are sorted by the Morton codes of their centroids, ties in order)
  std::vector<double> xyz;
  for(auto v : vertices(out.mesh))
    for(int c = 0; c < 3; ++c) xyz.push_back(out.mesh.point(v)[c]);
  std::vector<CGAL::Surface_mesh_multiresolution::internal::Index> tri, vertex_order, face_order;
  std::size_t next_new = 0;
  bool first_use = true;
  for(auto f : faces(out.mesh))
    for(auto v : vertices_around_face(halfedge(f, out.mesh), out.mesh))
    {
      tri.push_back(v.idx());
      if(std::size_t(v.idx()) >= next_new)
      {
        first_use = first_use && std::size_t(v.idx()) == next_new;
        ++next_new;
      }
    }
  CHECK(first_use);
  CGAL::Surface_mesh_multiresolution::internal::spatial_order(xyz, tri, vertex_order, face_order);
  REQUIRE(vertex_order.size() == num_vertices(out.mesh));
  REQUIRE(face_order.size() == num_faces(out.mesh));
  bool fixed_point = true;
  for(std::size_t i = 0; i < vertex_order.size(); ++i) fixed_point = fixed_point && vertex_order[i] == i;
  for(std::size_t p = 0; p < face_order.size(); ++p) fixed_point = fixed_point && face_order[p] == p;
  CHECK(fixed_point);
  // and it is the order the library gives the mesh as read: the same points, in that order
  {
    std::vector<double> xyz_in;
    std::vector<CGAL::Surface_mesh_multiresolution::internal::Index> tri_in, vertex_order_in, face_order_in;
    for(auto v : vertices(in.mesh))
      for(int c = 0; c < 3; ++c) xyz_in.push_back(in.mesh.point(v)[c]);
    for(auto f : faces(in.mesh))
      for(auto v : vertices_around_face(halfedge(f, in.mesh), in.mesh)) tri_in.push_back(v.idx());
    CGAL::Surface_mesh_multiresolution::internal::spatial_order(xyz_in, tri_in, vertex_order_in, face_order_in);
    REQUIRE(vertex_order_in.size() == num_vertices(out.mesh));
    bool same = true;
    for(std::size_t i = 0; i < vertex_order_in.size(); ++i)
      same = same && out.mesh.point(Mesh::Vertex_index(Mesh::size_type(i))) == in.mesh.point(Mesh::Vertex_index(vertex_order_in[i]));
    CHECK(same);
  }
  // neighbours are close in memory: the mean index span of a face is far smaller than in the
  // shuffled file
  auto mean_span = [](const Mesh& m) {
    double sum = 0;
    for(auto f : faces(m))
    {
      std::size_t lo = num_vertices(m), hi = 0;
      for(auto v : vertices_around_face(halfedge(f, m), m)) { lo = (std::min)(lo, std::size_t(v.idx())); hi = (std::max)(hi, std::size_t(v.idx())); }
      sum += double(hi - lo);
    }
    return sum / double(num_faces(m));
  };
  const double span_in = mean_span(in.mesh), span_out = mean_span(out.mesh);
  INFO("mean face span: " << span_in << " as read, " << span_out << " ordered");
  CHECK(span_out * 10 < span_in);
}

namespace {

// The numbers of `text` read one type at a time, until the first that fails: by CGAL 5.5's
// ASCII PLY reading (PLY_read_typed_number<T>::read() on a stream) and by smr_tool's.
template <typename T>
void check_ascii_numbers_as_cgal(const std::string& text)
{
  std::vector<double> cgal, ours;
  {
    std::istringstream is(text);
    const CGAL::IO::internal::PLY_read_typed_number<T> reader("p", 0);
    for(;;)
    {
      const T t = reader.template read<T>(is);
      if(!is) break;
      cgal.push_back(double(t));
    }
  }
  {
    std::istringstream is(text);
    smr_tool::ply::Ascii_numbers numbers(is);
    double x = 0;
    while(numbers.read(smr_tool::ply::number_type_of<T>(), x)) ours.push_back(x);
  }
  INFO("type " << int(smr_tool::ply::number_type_of<T>()) << ", text '" << (text.size() < 200 ? text : text.substr(0, 200) + "...") << "'");
  REQUIRE(ours.size() == cgal.size());
  for(std::size_t i = 0; i < ours.size(); ++i)
  {
    INFO("number " << i);
    REQUIRE(std::memcmp(&ours[i], &cgal[i], sizeof(double)) == 0);   // the same bits (signed zeros, infinities)
  }
}

void check_ascii_numbers_as_cgal_every_type(const std::string& text)
{
  check_ascii_numbers_as_cgal<std::int8_t>(text);
  check_ascii_numbers_as_cgal<std::uint8_t>(text);
  check_ascii_numbers_as_cgal<std::int16_t>(text);
  check_ascii_numbers_as_cgal<std::uint16_t>(text);
  check_ascii_numbers_as_cgal<std::int32_t>(text);
  check_ascii_numbers_as_cgal<std::uint32_t>(text);
  check_ascii_numbers_as_cgal<float>(text);
  check_ascii_numbers_as_cgal<double>(text);
}

} // namespace

TEST_CASE("ASCII PLY numbers are read as CGAL's PLY reader reads them", "[tool][input]")
{
  SECTION("limits, signs, and texts that are no numbers")
  {
    const std::vector<std::string> texts = {
      "0 1 -1 +1 127 128 -128 -129 255 256 300 -300 32767 32768 -32768 -32769 65535 65536 70000 -70000",
      "2147483647 2147483648 -2147483648 -2147483649 4294967295 4294967296 -4294967295",
      "9223372036854775807 9223372036854775808 -9223372036854775808 -9223372036854775809 99999999999999999999999",
      "1.5 -2.25 .5 5. 1e3 1E-3 1e+3 -0 -0.0 +0 0.1 3.4028234e38 3.4028236e38 1e39 -1e39 1e-45 1e-46 1.4e-45",
      "1e308 1.7976931348623157e308 1.8e308 1e309 -1e309 2.2250738585072014e-308 4.9e-324 2e-324 1e-400",
      "+5 ++5 +-5 -+5 --5", "-", "+", ".", "-.", "e5", "1e", "1e+", "1.5.3 7", "1.0-2.0 3", "0x10 7", "007 08",
      "1,5", "12abc", "  \t\n\r\v\f 42 \n", "", "   ", "5-", "5+3", "3 e 4", "0.000000000000000000000000000001",
      "0.1000000000000000055511151231257827021181583404541015625", "123456789012345678901234567890.5",
      std::string("4\0" "2", 3), "\xff 1", "1\xff", "nan inf infinity",
    };
    for(const std::string& t : texts) check_ascii_numbers_as_cgal_every_type(t);
  }
  SECTION("seeded random texts of number characters")
  {
    std::mt19937 random(20261203);
    const char alphabet[] = "0123456789+-.eE \n\txX";
    for(int trial = 0; trial < 20000; ++trial)
    {
      std::string t;
      const std::size_t length = 1 + random() % 40;
      for(std::size_t i = 0; i < length; ++i) t += alphabet[random() % (sizeof alphabet - 1)];
      check_ascii_numbers_as_cgal_every_type(t);
    }
  }
  SECTION("numbers across the reading blocks, and one number longer than a block")
  {
    // 300,000 numbers (about 2.6 MB: across the 1 MiB blocks), then a 3 MB number
    std::mt19937 random(7);
    std::string t;
    for(int i = 0; i < 300000; ++i) t += std::to_string(int(random() % 200000) - 100000) + (i % 7 ? " " : ".5\n");
    t += std::string(3000000, '0') + "17.25 9";
    check_ascii_numbers_as_cgal<float>(t);
    check_ascii_numbers_as_cgal<std::int32_t>(t);
  }
}

TEST_CASE("an ASCII PLY and its binary encodings read to the same soup, every number type", "[tool][input]")
{
  const Own_directory here("ascii_binary");
  // vertices with properties of every PLY type (positions as doubles), faces with int8 to
  // uint32 indices behind uchar to int counts
  const std::vector<std::pair<std::string, std::string> > props = {
    {"char", "c"}, {"uchar", "u"}, {"short", "s"}, {"ushort", "us"}, {"int", "i"}, {"uint", "ui"}, {"float", "f"}};
  // the tool keeps at most 4 channels of 4 components: the scalars fill two channels
  std::string head = "ply\nformat FORMAT 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\n";
  for(const auto& p : props) head += "property " + p.first + " q_" + p.second + "\n";
  head += "element face 4\nproperty list uchar int vertex_indices\nelement extra 2\nproperty list short uint numbers\n"
          "property float w\nend_header\n";
  const double xyz[5][3] = {{0, 0, 0}, {1, 0, 0.1}, {1, 1, -0.2}, {0, 1, 1e-300}, {0.5, 0.5, 1.25}};
  const long long scalar[5][7] = {{-128, 0, -32768, 0, -2147483647, 0, 3}, {127, 255, 32767, 65535, 2147483647, 4294967295LL, -2},
                                  {-1, 1, -1, 1, -1, 1, 1}, {5, 6, 7, 8, 9, 10, 11}, {0, 200, 300, 40000, 100000, 3000000000LL, 0}};
  const int face[4][3] = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  std::ostringstream ascii;
  ascii.precision(17);
  for(int v = 0; v < 5; ++v)
  {
    ascii << xyz[v][0] << ' ' << xyz[v][1] << ' ' << xyz[v][2];
    for(int k = 0; k < 6; ++k) ascii << ' ' << scalar[v][k];
    ascii << ' ' << double(scalar[v][6]) + 0.5;
    ascii << '\n';
  }
  for(const auto& f : face) ascii << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
  ascii << "2 4000000000 7 0.25\n0 -1.5\n";
  std::string binary;
  auto put = [&](const auto value) {
    const char* b = reinterpret_cast<const char*>(&value);
    binary.append(b, sizeof value);
  };
  for(int v = 0; v < 5; ++v)
  {
    for(int d = 0; d < 3; ++d) put(xyz[v][d]);
    put(std::int8_t(scalar[v][0])); put(std::uint8_t(scalar[v][1])); put(std::int16_t(scalar[v][2]));
    put(std::uint16_t(scalar[v][3])); put(std::int32_t(scalar[v][4])); put(std::uint32_t(scalar[v][5]));
    put(float(double(scalar[v][6]) + 0.5));
  }
  for(const auto& f : face) { put(std::uint8_t(3)); for(int c : f) put(std::int32_t(c)); }
  put(std::int16_t(2)); put(std::uint32_t(4000000000u)); put(std::uint32_t(7)); put(0.25f);
  put(std::int16_t(0)); put(-1.5f);
  auto with_format = [&](const std::string& format) {
    std::string h = head;
    h.replace(h.find("FORMAT"), 6, format);
    return h;
  };
  write_text("a.ply", with_format("ascii") + ascii.str());
  write_text("b.ply", with_format("binary_little_endian") + binary);
  const smr_tool::Scan a = smr_tool::read_scan("a.ply"), b = smr_tool::read_scan("b.ply");
  REQUIRE(num_vertices(a.mesh) == 5);
  REQUIRE(num_faces(a.mesh) == 4);
  REQUIRE(num_vertices(b.mesh) == 5);
  REQUIRE(a.channels.size() == b.channels.size());
  REQUIRE(a.channels.size() == 2);
  CHECK(a.double_positions);
  for(auto v : vertices(a.mesh))
  {
    CHECK(a.mesh.point(v) == b.mesh.point(v));
    CHECK(a.mesh.point(v) == Point(xyz[v.idx()][0], xyz[v.idx()][1], xyz[v.idx()][2]));
    for(std::size_t c = 0; c < a.maps.size(); ++c) CHECK(a.maps[c][v] == b.maps[c][v]);
    // the values as written: 4 scalars in the first channel, 3 in the second
    for(int k = 0; k < 7; ++k)
      CHECK(a.maps[std::size_t(k / 4)][v][std::size_t(k % 4)] == double(scalar[v.idx()][k]) + (k == 6 ? 0.5 : 0.));
  }
  for(auto f : faces(a.mesh))
  {
    std::vector<std::size_t> ca, cb;
    for(auto v : vertices_around_face(halfedge(f, a.mesh), a.mesh)) ca.push_back(v.idx());
    for(auto v : vertices_around_face(halfedge(f, b.mesh), b.mesh)) cb.push_back(v.idx());
    CHECK(ca == cb);
    CHECK(ca == std::vector<std::size_t>{std::size_t(face[f.idx()][0]), std::size_t(face[f.idx()][1]), std::size_t(face[f.idx()][2])});
  }
  // a truncated ASCII file is refused as the binary one is
  write_text("cut.ply", with_format("ascii") + ascii.str().substr(0, 40));
  CHECK_THROWS_WITH(smr_tool::read_scan("cut.ply"), Catch::Contains("truncated or unreadable"));
}
