// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
//
// The `smr` tool's path from a file to a triangle mesh with attribute channels, and back:
// PLY files with every per-vertex property (colours, normals, texture coordinates, scalars),
// faces and triangle strips; OFF, OBJ and STL through CGAL's polygon soup readers (geometry
// only). The soup is repaired with the vertex attributes following every change, and each
// change is reported in `Scan::notes`. Errors are thrown as std::runtime_error with a message
// for the user.
#ifndef SMR_TOOL_SCAN_IO_H
#define SMR_TOOL_SCAN_IO_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/IO/PLY/PLY_reader.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace smr_tool {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3                                          Point;
typedef CGAL::Surface_mesh<Point>                           Mesh;
typedef std::array<double, 4>                               Value4;   // one channel's value, unused components 0
typedef Mesh::Property_map<Mesh::Vertex_index, Value4>      Channel_map;

// The tool's channels have at most 4 components (the package's channels are typed at compile
// time; four-component arrays let one build serve every file) and there are at most 4 of them.
constexpr std::size_t max_channels = 4;

// One attribute channel: its kind ("color", "normal", "texture", "scalar") and the PLY name and
// type of each component (the output writes them back with their names and types).
struct Channel
{
  std::string kind;
  std::vector<std::string> names, types;
};

struct Scan
{
  Mesh mesh;                                  // a triangle mesh; vertex i has the values i of every channel
  std::vector<Channel> channels;
  std::vector<Channel_map> maps;              // "v:smr0", "v:smr1"... on `mesh`
  bool double_positions = false;              // whether the file stored x, y, z as doubles
  std::vector<std::string> notes;             // what the reading changed, for the user
};

inline std::string plural(std::size_t n, const std::string& what)
{
  if(n == 1) return "1 " + what;
  if(what.size() >= 6 && what.compare(what.size() - 6, 6, "vertex") == 0)
    return std::to_string(n) + " " + what.substr(0, what.size() - 2) + "ices";
  return std::to_string(n) + " " + what + "s";
}

inline std::string extension_of(const std::string& file)
{
  const std::size_t dot = file.find_last_of('.'), slash = file.find_last_of('/');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "";
  std::string e = file.substr(dot + 1);
  for(char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// ---- reading a PLY file: every element, every property ------------------------------------

namespace ply {
using CGAL::IO::internal::PLY_read_number;
using CGAL::IO::internal::PLY_read_typed_number;
using CGAL::IO::internal::PLY_read_typed_list;

// the value of a scalar property as a double, and its PLY type name
inline bool number(const PLY_read_number* p, double& v, std::string& type)
{
#define SMR_TOOL_TRY_NUMBER(T, NAME)                                                       \
  if(auto q = dynamic_cast<const PLY_read_typed_number<T>*>(p)) { v = double(q->buffer()); type = NAME; return true; }
  SMR_TOOL_TRY_NUMBER(std::int8_t, "char") SMR_TOOL_TRY_NUMBER(std::uint8_t, "uchar")
  SMR_TOOL_TRY_NUMBER(std::int16_t, "short") SMR_TOOL_TRY_NUMBER(std::uint16_t, "ushort")
  SMR_TOOL_TRY_NUMBER(std::int32_t, "int") SMR_TOOL_TRY_NUMBER(std::uint32_t, "uint")
  SMR_TOOL_TRY_NUMBER(float, "float") SMR_TOOL_TRY_NUMBER(double, "double")
#undef SMR_TOOL_TRY_NUMBER
  return false;
}

// the entries of an integer list property
inline bool list(const PLY_read_number* p, std::vector<long long>& v)
{
#define SMR_TOOL_TRY_LIST(T)                                                               \
  if(auto q = dynamic_cast<const PLY_read_typed_list<T>*>(p)) { v.assign(q->buffer().begin(), q->buffer().end()); return true; }
  SMR_TOOL_TRY_LIST(std::int8_t) SMR_TOOL_TRY_LIST(std::uint8_t) SMR_TOOL_TRY_LIST(std::int16_t)
  SMR_TOOL_TRY_LIST(std::uint16_t) SMR_TOOL_TRY_LIST(std::int32_t) SMR_TOOL_TRY_LIST(std::uint32_t)
#undef SMR_TOOL_TRY_LIST
  return false;
}
} // namespace ply

// A polygon soup with per-point attribute values, as read.
struct Soup
{
  std::vector<Point> points;
  std::vector<std::vector<std::size_t> > polygons;
  std::vector<Channel> channels;
  std::vector<std::vector<Value4> > values;   // per channel, per point
  bool double_positions = false;
  std::vector<std::string> notes;
};

// The channel a vertex property belongs to, by its name.
inline std::string kind_of_property(const std::string& name)
{
  static const char* colour[] = {"red", "green", "blue", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue", "r", "g", "b", "a"};
  static const char* normal[] = {"nx", "ny", "nz", "normal_x", "normal_y", "normal_z"};
  static const char* texture[] = {"u", "v", "s", "t", "texture_u", "texture_v", "texture_s", "texture_t"};
  for(const char* c : colour) if(name == c) return "color";
  for(const char* c : normal) if(name == c) return "normal";
  for(const char* c : texture) if(name == c) return "texture";
  return "scalar";
}

inline void read_ply(const std::string& file, Soup& soup)
{
  std::ifstream is(file, std::ios::binary);
  if(!is)
    throw std::runtime_error("cannot open " + file);
  CGAL::IO::internal::PLY_reader reader(false);
  if(!reader.init(is))
    throw std::runtime_error(file + ": not a PLY file (bad header)");
  bool have_vertices = false;
  std::size_t strips = 0;
  for(std::size_t i = 0; i < reader.number_of_elements(); ++i)
  {
    CGAL::IO::internal::PLY_element& element = reader.element(i);
    const std::string& name = element.name();
    const bool is_vertex = name == "vertex" || name == "vertices";
    const bool is_face = name == "face" || name == "faces";
    const bool is_strip = name == "tristrips";
    // vertex properties: x, y, z and the channels (grouped by kind, in the file's order)
    int xyz[3] = {-1, -1, -1};
    std::vector<int> channel_of(element.number_of_properties(), -1), component_of(element.number_of_properties(), -1);
    int indices = -1;
    for(std::size_t k = 0; k < element.number_of_properties(); ++k)
    {
      const std::string& pn = element.property(k)->name();
      if(is_vertex)
      {
        double unused; std::string type;
        if(pn == "x" || pn == "y" || pn == "z")
        {
          xyz[pn[0] - 'x'] = int(k);
          continue;
        }
        if(!ply::number(element.property(k), unused, type))
        {
          soup.notes.push_back("vertex property '" + pn + "' is a list: not read");
          continue;
        }
        const std::string kind = kind_of_property(pn);
        int c = -1;
        for(std::size_t j = 0; j < soup.channels.size(); ++j)
          if(soup.channels[j].kind == kind && soup.channels[j].names.size() < 4) c = int(j);
        if(c < 0)
        {
          if(soup.channels.size() == max_channels)
          {
            soup.notes.push_back("vertex property '" + pn + "' dropped: the tool keeps at most " + std::to_string(max_channels)
                                 + " channels of 4 components");
            continue;
          }
          soup.channels.push_back(Channel{kind, {}, {}});
          soup.values.emplace_back();
          c = int(soup.channels.size() - 1);
        }
        channel_of[k] = c;
        component_of[k] = int(soup.channels[c].names.size());
        soup.channels[c].names.push_back(pn);
        soup.channels[c].types.push_back(type);
      }
      else if((is_face || is_strip) && (pn == "vertex_indices" || pn == "vertex_index"))
        indices = int(k);
    }
    if(is_vertex)
    {
      if(have_vertices)
        throw std::runtime_error(file + ": more than one vertex element");
      if(xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
        throw std::runtime_error(file + ": the vertex element has no x, y, z");
      double unused; std::string type;
      ply::number(element.property(std::size_t(xyz[0])), unused, type);
      soup.double_positions = type == "double";
      have_vertices = true;
    }
    if((is_face || is_strip) && indices < 0)
      throw std::runtime_error(file + ": element '" + name + "' has no vertex_indices list");
    std::vector<long long> list;
    for(std::size_t j = 0; j < element.number_of_items(); ++j)
    {
      for(std::size_t k = 0; k < element.number_of_properties(); ++k)
      {
        element.property(k)->get(is);
        if(is.fail())
          throw std::runtime_error(file + ": truncated or unreadable at item " + std::to_string(j) + " of element '" + name + "'");
      }
      if(is_vertex)
      {
        double p[3]; std::string type;
        for(int d = 0; d < 3; ++d)
          ply::number(element.property(std::size_t(xyz[d])), p[d], type);
        soup.points.emplace_back(p[0], p[1], p[2]);
        for(auto& v : soup.values) v.push_back(Value4{{0., 0., 0., 0.}});
        for(std::size_t k = 0; k < element.number_of_properties(); ++k)
          if(channel_of[k] >= 0)
            ply::number(element.property(k), soup.values[std::size_t(channel_of[k])].back()[std::size_t(component_of[k])], type);
      }
      else if(is_face || is_strip)
      {
        if(!ply::list(element.property(std::size_t(indices)), list))
          throw std::runtime_error(file + ": the vertex indices of element '" + name + "' are not integers");
        if(is_face)
          soup.polygons.emplace_back(list.begin(), list.end());
        else
        {
          // a triangle strip with -1 restarts: triangle i is (s[i], s[i+1], s[i+2]), every
          // second one reversed to keep the orientation
          ++strips;
          std::size_t start = 0;
          for(std::size_t e = 0; e <= list.size(); ++e)
            if(e == list.size() || list[e] < 0)
            {
              for(std::size_t t = start; t + 2 < e; ++t)
              {
                const std::size_t a = std::size_t(list[t]), b = std::size_t(list[t + 1]), c = std::size_t(list[t + 2]);
                if((t - start) % 2 == 0) soup.polygons.push_back({a, b, c});
                else soup.polygons.push_back({b, a, c});
              }
              start = e + 1;
            }
        }
        for(long long v : list)
          if(v < -1 || (v == -1 && is_face) || (v >= 0 && std::size_t(v) >= soup.points.size()))
            throw std::runtime_error(file + ": item " + std::to_string(j) + " of element '" + name + "' refers to vertex "
                                     + std::to_string(v) + (have_vertices ? " (the file has " + plural(soup.points.size(), "vertex") + ")"
                                                                          : " before the vertices are read"));
      }
    }
  }
  if(strips > 0)
    soup.notes.push_back("triangle strips expanded: " + plural(soup.polygons.size(), "triangle"));
}

// ---- repairing the soup, the attribute values following every change ------------------------

// Why by hand and not CGAL::Polygon_mesh_processing::repair_polygon_soup(): it does not say
// where the points went, and the attribute values must follow them.
inline void repair(Soup& s)
{
  const std::size_t n = s.points.size();
  for(std::size_t i = 0; i < n; ++i)
    for(int d = 0; d < 3; ++d)
      if(!std::isfinite(s.points[i][d]) || std::abs(s.points[i][d]) > 1e150)
        throw std::runtime_error("vertex " + std::to_string(i) + " has a non-finite or huge coordinate");
  for(std::size_t c = 0; c < s.values.size(); ++c)
    for(std::size_t i = 0; i < n; ++i)
      for(double v : s.values[c][i])
        if(!std::isfinite(v))
          throw std::runtime_error("vertex " + std::to_string(i) + " has a non-finite '" + s.channels[c].kind + "' value");
  // 1. points with equal coordinates and equal attributes become one (seams with different
  //    attributes stay apart)
  std::vector<std::size_t> order(n), rep(n);
  for(std::size_t i = 0; i < n; ++i) order[i] = i;
  auto key_less = [&](std::size_t a, std::size_t b) {
    if(s.points[a] != s.points[b]) return s.points[a] < s.points[b];
    for(const auto& v : s.values) if(v[a] != v[b]) return v[a] < v[b];
    return a < b;
  };
  auto same = [&](std::size_t a, std::size_t b) {
    if(s.points[a] != s.points[b]) return false;
    for(const auto& v : s.values) if(v[a] != v[b]) return false;
    return true;
  };
  std::sort(order.begin(), order.end(), key_less);
  std::size_t merged = 0;
  for(std::size_t i = 0; i < n; ++i)
  {
    rep[order[i]] = (i > 0 && same(order[i - 1], order[i])) ? rep[order[i - 1]] : order[i];
    merged += rep[order[i]] != order[i];
  }
  // 2. polygons: merged indices, consecutive repeats out; fewer than 3 corners, a corner twice
  //    or the same corners as an earlier polygon: taken out
  std::size_t degenerate = 0, duplicates = 0;
  std::map<std::vector<std::size_t>, std::size_t> seen;
  std::vector<std::vector<std::size_t> > kept;
  for(auto& p : s.polygons)
  {
    std::vector<std::size_t> q;
    for(std::size_t v : p)
      if(q.empty() || rep[v] != q.back()) q.push_back(rep[v]);
    while(q.size() > 1 && q.front() == q.back()) q.pop_back();
    std::vector<std::size_t> sorted = q;
    std::sort(sorted.begin(), sorted.end());
    if(q.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) { ++degenerate; continue; }
    if(!seen.emplace(sorted, kept.size()).second) { ++duplicates; continue; }
    kept.push_back(std::move(q));
  }
  s.polygons.swap(kept);
  // 3. unreferenced points out
  std::vector<std::size_t> new_index(n, std::size_t(-1));
  std::size_t m = 0;
  std::vector<char> used(n, 0);
  for(const auto& p : s.polygons) for(std::size_t v : p) used[v] = 1;
  for(std::size_t i = 0; i < n; ++i)
    if(used[i])
    {
      new_index[i] = m;
      s.points[m] = s.points[i];
      for(auto& v : s.values) v[m] = v[i];
      ++m;
    }
  const std::size_t unreferenced = n - m - merged;
  s.points.resize(m);
  for(auto& v : s.values) v.resize(m);
  for(auto& p : s.polygons) for(std::size_t& v : p) v = new_index[v];
  if(merged) s.notes.push_back(plural(merged, "duplicate vertex") + " merged (equal position and attributes)");
  if(degenerate) s.notes.push_back(plural(degenerate, "degenerate face") + " removed (a corner repeated or fewer than 3)");
  if(duplicates) s.notes.push_back(plural(duplicates, "duplicate face") + " removed");
  if(unreferenced) s.notes.push_back(plural(unreferenced, "unreferenced vertex") + " removed");
  // 4. orientation and manifoldness: CGAL's soup orientation, which duplicates the vertices
  //    where the surface is pinched; the copies take the attributes of their originals
  struct Follow_duplicates : CGAL::Polygon_mesh_processing::Default_orientation_visitor
  {
    Soup* s; std::size_t* counts;   // the visitor is copied: its state lives outside
    void duplicated_vertex(std::size_t from, std::size_t copy)
    {
      for(auto& v : s->values) { if(v.size() <= copy) v.resize(copy + 1); v[copy] = v[from]; }
      ++counts[0];
    }
    void non_manifold_edge(std::size_t, std::size_t, std::size_t) { ++counts[1]; }
    void polygon_orientation_reversed(std::size_t) { ++counts[2]; }
  };
  std::size_t counts[3] = {0, 0, 0};
  Follow_duplicates follow;
  follow.s = &s;
  follow.counts = counts;
  CGAL::Polygon_mesh_processing::orient_polygon_soup(s.points, s.polygons, CGAL::parameters::visitor(follow));
  if(counts[1]) s.notes.push_back(plural(counts[1], "non-manifold edge") + " cut apart");
  if(counts[0]) s.notes.push_back(plural(counts[0], "vertex") + " duplicated where the surface is pinched (non-manifold)");
  if(counts[2]) s.notes.push_back(plural(counts[2], "face") + " reversed to orient the surface consistently");
}

// Reads a mesh file into a triangle mesh with channels; throws std::runtime_error with a message.
inline Scan read_scan(const std::string& file)
{
  Soup soup;
  const std::string ext = extension_of(file);
  if(ext == "ply")
    read_ply(file, soup);
  else if(ext == "off" || ext == "obj" || ext == "stl")
  {
    std::ifstream probe(file);
    if(!probe)
      throw std::runtime_error("cannot open " + file);
    if(!CGAL::IO::read_polygon_soup(file, soup.points, soup.polygons))
      throw std::runtime_error(file + ": not a readable " + ext + " file");
    soup.double_positions = ext != "stl";     // text numbers (binary STL holds floats): written back as doubles
    for(auto& p : soup.polygons)
      for(std::size_t v : p)
        if(v >= soup.points.size())
          throw std::runtime_error(file + ": a face refers to vertex " + std::to_string(v) + " of " + std::to_string(soup.points.size()));
  }
  else
    throw std::runtime_error(file + ": unknown format '" + ext + "' (PLY, OFF, OBJ or STL)");
  if(soup.polygons.empty())
    throw std::runtime_error(file + ": no faces (" + plural(soup.points.size(), "vertex") + "): a surface mesh is needed");
  repair(soup);
  if(soup.polygons.empty())
    throw std::runtime_error(file + ": no valid face left after the repair");
  Scan scan;
  scan.double_positions = soup.double_positions;
  scan.notes = soup.notes;
  scan.channels = soup.channels;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, scan.mesh);
  // the vertices are created in the order of the points (all referenced after the repair)
  if(num_vertices(scan.mesh) != soup.points.size())
    throw std::runtime_error(file + ": the repaired faces do not form a surface mesh");
  std::size_t polygons = 0;
  for(auto f : faces(scan.mesh))
    polygons += degree(f, scan.mesh) != 3;
  if(polygons)
  {
    if(!CGAL::Polygon_mesh_processing::triangulate_faces(scan.mesh))
      throw std::runtime_error(file + ": a polygon could not be triangulated");
    scan.notes.push_back(plural(polygons, "polygon") + " with more than 3 corners triangulated");
  }
  for(std::size_t c = 0; c < scan.channels.size(); ++c)
  {
    Channel_map m = scan.mesh.add_property_map<Mesh::Vertex_index, Value4>("v:smr" + std::to_string(c)).first;
    for(auto v : vertices(scan.mesh))
      m[v] = soup.values[c][v.idx()];
    scan.maps.push_back(m);
  }
  return scan;
}

// The channel maps "v:smr0"... of an output mesh, created.
inline std::vector<Channel_map> add_channel_maps(Mesh& mesh, std::size_t count)
{
  std::vector<Channel_map> maps;
  for(std::size_t c = 0; c < count; ++c)
    maps.push_back(mesh.add_property_map<Mesh::Vertex_index, Value4>("v:smr" + std::to_string(c), Value4{{0., 0., 0., 0.}}).first);
  return maps;
}

// ---- writing -------------------------------------------------------------------------------

inline void put_binary(std::string& out, const std::string& type, double v)
{
  auto raw = [&out](const auto x) { out.append(reinterpret_cast<const char*>(&x), sizeof x); };
  auto clamp = [v](double lo, double hi) { return (std::min)(hi, (std::max)(lo, std::round(v))); };
  if(type == "char") raw(std::int8_t(clamp(-128, 127)));
  else if(type == "uchar") raw(std::uint8_t(clamp(0, 255)));
  else if(type == "short") raw(std::int16_t(clamp(-32768, 32767)));
  else if(type == "ushort") raw(std::uint16_t(clamp(0, 65535)));
  else if(type == "int") raw(std::int32_t(clamp(-2147483648., 2147483647.)));
  else if(type == "uint") raw(std::uint32_t(clamp(0, 4294967295.)));
  else if(type == "float") raw(float(v));
  else raw(v);
}

// Writes a scan to `file`, its format from the extension (PLY binary little-endian with every
// channel under its names and types; OFF, OBJ, STL: geometry only, said in `dropped`). The
// file appears complete or not at all: written next to it, then renamed.
inline void write_scan(const std::string& file, const Mesh& mesh, const std::vector<Channel>& channels,
                       const std::vector<Channel_map>& maps, bool double_positions, std::string& dropped)
{
  const std::string ext = extension_of(file);
  const std::string partial = file + ".partial." + (ext.empty() ? std::string("ply") : ext);
  dropped.clear();
  bool ok = true;
  if(ext == "ply" || ext.empty())
  {
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by smr (Surface_mesh_multiresolution)\n";
    header += "element vertex " + std::to_string(num_vertices(mesh)) + "\n";
    const char* pt = double_positions ? "double" : "float";
    header += std::string("property ") + pt + " x\nproperty " + pt + " y\nproperty " + pt + " z\n";
    for(const Channel& c : channels)
      for(std::size_t j = 0; j < c.names.size(); ++j)
        header += "property " + c.types[j] + " " + c.names[j] + "\n";
    header += "element face " + std::to_string(num_faces(mesh)) + "\nproperty list uchar int vertex_indices\nend_header\n";
    std::string body;
    std::vector<std::uint32_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), 0);
    std::uint32_t i = 0;
    for(auto v : vertices(mesh))
    {
      index[v.idx()] = i++;
      for(int d = 0; d < 3; ++d) put_binary(body, pt, mesh.point(v)[d]);
      for(std::size_t c = 0; c < channels.size(); ++c)
        for(std::size_t j = 0; j < channels[c].names.size(); ++j)
          put_binary(body, channels[c].types[j], maps[c][v][j]);
    }
    for(auto f : faces(mesh))
    {
      body.push_back(char(3));
      for(auto v : CGAL::vertices_around_face(halfedge(f, mesh), mesh))
        put_binary(body, "int", double(index[v.idx()]));
    }
    std::ofstream os(partial, std::ios::binary);
    os << header;
    os.write(body.data(), std::streamsize(body.size()));
    os.close();
    ok = bool(os);
  }
  else if(ext == "off" || ext == "obj" || ext == "stl")
  {
    ok = CGAL::IO::write_polygon_mesh(partial, mesh, CGAL::parameters::stream_precision(17));
    for(const Channel& c : channels)
      dropped += (dropped.empty() ? "" : ", ") + c.kind;
  }
  else
    throw std::runtime_error(file + ": unknown output format '" + ext + "' (PLY, OFF, OBJ or STL)");
  if(!ok || std::rename(partial.c_str(), file.c_str()) != 0)
  {
    std::remove(partial.c_str());
    throw std::runtime_error("cannot write " + file);
  }
}

} // namespace smr_tool

#endif // SMR_TOOL_SCAN_IO_H
