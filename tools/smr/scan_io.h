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
#include <CGAL/property_map.h>
#include <CGAL/Surface_mesh_multiresolution/internal/spatial_order.h>
#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/parallel_sort.h>
#endif

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstring>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>
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
using CGAL::IO::internal::PLY_read_typed_list_with_typed_size;

// The PLY number types, as CGAL's header parser makes them.
enum class Number_type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

// A list: its count, then as many integer entries; number(is_count, x) reads one number (false:
// unreadable or past the data). Why entry by entry: CGAL's list get() resizes its buffer to the
// count it reads, so a crafted count (2^31 in a 100-byte file) would allocate gigabytes before
// the read fails; here a list grows entry by entry and stops at the end of the data.
template <typename ReadNumber>
void read_list(const ReadNumber& number, std::vector<long long>& v)
{
  double count = 0;
  const bool counted = number(true, count);
  v.clear();
  if(!counted || !(count >= 0))
    throw std::runtime_error("a list with an unreadable or negative count");
  for(double i = 0; i < count; ++i)
  {
    double x = 0;
    if(!number(false, x))
      throw std::runtime_error("a list of " + std::to_string(static_cast<long long>(count)) + " entries, more than the file holds");
    if(!(x == std::floor(x) && std::abs(x) < 4.5e15)) throw std::runtime_error("a list with a non-integer entry");
    v.push_back(static_cast<long long>(x));
  }
}

// How one property of an element is read, resolved once per element: its types, and for binary
// files the reading by CGAL's typed property objects (their read<T>() decodes little- and
// big-endian numbers). Why not their get(): see read_list(); dynamic casts per item also cost.
struct Property_reader
{
  bool is_list = false;
  std::string type;                                               // the PLY type of a scalar
  Number_type scalar = Number_type::float32, count = Number_type::uint8, item = Number_type::int32;
  std::function<double(std::istream&)> number;
  std::function<void(std::istream&, std::vector<long long>&)> list;   // throws past the data
};

template <typename T> constexpr Number_type number_type_of();
template <> constexpr Number_type number_type_of<std::int8_t>() { return Number_type::int8; }
template <> constexpr Number_type number_type_of<std::uint8_t>() { return Number_type::uint8; }
template <> constexpr Number_type number_type_of<std::int16_t>() { return Number_type::int16; }
template <> constexpr Number_type number_type_of<std::uint16_t>() { return Number_type::uint16; }
template <> constexpr Number_type number_type_of<std::int32_t>() { return Number_type::int32; }
template <> constexpr Number_type number_type_of<std::uint32_t>() { return Number_type::uint32; }
template <> constexpr Number_type number_type_of<float>() { return Number_type::float32; }
template <> constexpr Number_type number_type_of<double>() { return Number_type::float64; }

template <typename T>
bool scalar_as(const PLY_read_number* p, const char* name, Property_reader& r)
{
  auto q = dynamic_cast<const PLY_read_typed_number<T>*>(p);
  if(!q) return false;
  r.type = name;
  r.scalar = number_type_of<T>();
  r.number = [q](std::istream& is) { return double(q->template read<T>(is)); };
  return true;
}

template <typename S, typename I>
bool list_as(const PLY_read_number* p, Property_reader& r)
{
  auto q = dynamic_cast<const PLY_read_typed_list_with_typed_size<S, I>*>(p);
  if(!q) return false;
  r.is_list = true;
  r.count = number_type_of<S>();
  r.item = number_type_of<I>();
  r.list = [q](std::istream& is, std::vector<long long>& v) {
    read_list([&](bool is_count, double& x) {
      x = is_count ? double(q->template read<S>(is)) : double(q->template read<I>(is));
      return bool(is);
    }, v);
  };
  return true;
}

template <typename S>
bool list_with_size(const PLY_read_number* p, Property_reader& r)
{
  return list_as<S, std::int8_t>(p, r) || list_as<S, std::uint8_t>(p, r) || list_as<S, std::int16_t>(p, r)
         || list_as<S, std::uint16_t>(p, r) || list_as<S, std::int32_t>(p, r) || list_as<S, std::uint32_t>(p, r)
         || list_as<S, float>(p, r) || list_as<S, double>(p, r);
}

inline Property_reader reader_of(const PLY_read_number* p)
{
  Property_reader r;
  if(scalar_as<std::int8_t>(p, "char", r) || scalar_as<std::uint8_t>(p, "uchar", r) || scalar_as<std::int16_t>(p, "short", r)
     || scalar_as<std::uint16_t>(p, "ushort", r) || scalar_as<std::int32_t>(p, "int", r) || scalar_as<std::uint32_t>(p, "uint", r)
     || scalar_as<float>(p, "float", r) || scalar_as<double>(p, "double", r))
    return r;
  if(list_with_size<std::uint8_t>(p, r) || list_with_size<std::int8_t>(p, r) || list_with_size<std::uint16_t>(p, r)
     || list_with_size<std::int16_t>(p, r) || list_with_size<std::uint32_t>(p, r) || list_with_size<std::int32_t>(p, r))
    return r;
  throw std::runtime_error("property '" + p->name() + "' has a type the reader does not know");
}

// The numbers of an ASCII PLY file's data, read as CGAL 5.5's PLY reader reads them through
// std::istream (PLY_read_typed_number<T>::read(), that is libstdc++'s operator>> in the C
// locale): the same text accepted, the same values, the same characters consumed. Integers:
// blanks skipped, an optional sign, decimal digits; char, short and int through a long,
// range-checked, then narrowed; unsigned types modulo 2^bits after a '-'; uchar through an
// unsigned short. Reals: see real(). Why by hand: the stream reads each number through a
// sentry, a std::string and strtof (a third of the 1.5-1.9 s the tool took to read the
// Stanford dragon's 33 MB ASCII PLY; 1.0-1.35 s now); here std::from_chars (the same
// correctly rounded values) parses the text in place. The file is read in blocks of 1 MiB,
// allocated at the first read (a longer number grows the block, as the stream's std::string
// would grow).
class Ascii_numbers
{
public:
  explicit Ascii_numbers(std::istream& is) : m_is(is) {}

  // one number of type t into x; false if there is none (the end of the file, text that is no
  // number of that type, a value out of its range)
  bool read(Number_type t, double& x)
  {
    switch(t)
    {
      case Number_type::int8: return narrowed<long, short, signed char>(x);
      case Number_type::uint8: return narrowed<unsigned short, unsigned short, unsigned char>(x);
      case Number_type::int16: return narrowed<long, short, short>(x);
      case Number_type::uint16: return narrowed<unsigned short, unsigned short, unsigned short>(x);
      case Number_type::int32: return narrowed<long, int, int>(x);
      case Number_type::uint32: return narrowed<unsigned int, unsigned int, unsigned int>(x);
      case Number_type::float32: return real<float>(x);
      default: return real<double>(x);
    }
  }

private:
  // the character at m_pos + i (reading more of the file when needed), or -1 past its end
  int peek(std::size_t i)
  {
    while(m_pos + i >= m_end)
      if(!more())
        return -1;
    return static_cast<unsigned char>(m_data[m_pos + i]);
  }

  // moves what is left to the front and reads more; false when the file has nothing more
  bool more()
  {
    if(m_at_end)
      return false;
    if(m_pos > 0)
    {
      std::memmove(m_data.data(), m_data.data() + m_pos, m_end - m_pos);
      m_end -= m_pos;
      m_pos = 0;
    }
    if(m_end == m_data.size())              // the first read, or one number as long as the block
      m_data.resize((std::max)(2 * m_data.size(), std::size_t(1) << 20));
    m_is.read(m_data.data() + m_end, static_cast<std::streamsize>(m_data.size() - m_end));
    const std::size_t got = static_cast<std::size_t>(m_is.gcount());
    m_end += got;
    m_at_end = got == 0;
    return got > 0;
  }

  // the blanks of the C locale (std::isspace)
  static bool blank(int c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

  bool skip_blanks()
  {
    for(int c = peek(0); c >= 0; c = peek(0))
    {
      if(!blank(c))
        return true;
      ++m_pos;
    }
    return false;
  }

  // operator>>(E&) of libstdc++'s streams for E = long, unsigned short, unsigned int
  template <typename E>
  bool integer(E& v)
  {
    typedef typename std::make_unsigned<E>::type U;
    if(!skip_blanks())
      return false;
    const int sign = peek(0);
    const bool negative = sign == '-';
    if(negative || sign == '+')
      ++m_pos;
    const U max = (negative && std::is_signed<E>::value) ? U(U(0) - U((std::numeric_limits<E>::min)()))
                                                         : U((std::numeric_limits<E>::max)());
    U result = 0;
    bool digits = false, overflow = false;
    for(int c = peek(0); c >= '0' && c <= '9'; c = peek(0))
    {
      ++m_pos;
      digits = true;
      const U d = U(c - '0');
      if(result > max / 10)
        overflow = true;
      else
      {
        result = U(result * 10);
        overflow = overflow || result > max - d;
        result = U(result + d);
      }
    }
    if(!digits || overflow)
      return false;
    v = negative ? E(U(U(0) - result)) : E(result);
    return true;
  }

  // read as E, range-checked as R (operator>>(short&) and (int&) read a long), stored as T
  template <typename E, typename R, typename T>
  bool narrowed(double& x)
  {
    E e = 0;
    if(!integer(e))
      return false;
    if constexpr(!std::is_same<E, R>::value)
    {
      if(e < E((std::numeric_limits<R>::min)()) || e > E((std::numeric_limits<R>::max)()))
        return false;
    }
    x = double(static_cast<T>(static_cast<R>(e)));
    return true;
  }

  // operator>>(T&) of libstdc++'s streams for T = float, double (num_get in the C locale):
  // an optional sign, digits with at most one '.', then an 'e' or 'E' (after some digit) with
  // an optional sign and digits, taken as far as they follow that pattern; then strtof / strtod
  // must use all of it and give a finite value (an overflow fails; an underflow gives its
  // rounded value)
  template <typename T>
  bool real(double& x)
  {
    if(!skip_blanks())
      return false;
    std::size_t n = 0;
    int c = peek(0);
    if(c == '+' || c == '-')
      c = peek(++n);
    for(bool mantissa = false, dot = false, exponent = false;; c = peek(++n))
    {
      if(c >= '0' && c <= '9')
        mantissa = true;
      else if(c == '.' && !dot && !exponent)
        dot = true;
      else if((c == 'e' || c == 'E') && mantissa && !exponent)
      {
        exponent = true;
        const int sign = peek(n + 1);
        if(sign == '+' || sign == '-')
          ++n;
      }
      else
        break;
    }
    const char* const first = m_data.data() + m_pos;
    const char* const last = first + n;
    m_pos += n;
    T t = 0;
    const std::from_chars_result r = std::from_chars(first != last && *first == '+' ? first + 1 : first, last, t);
    if(r.ec == std::errc() && r.ptr == last)
    {
      x = double(t);
      return true;
    }
    if(r.ec != std::errc::result_out_of_range)
      return false;
    // out of range for from_chars: strtof / strtod say whether it overflows (fails) or
    // underflows (to a subnormal number or zero)
    const std::string text(first, last);
    char* end = nullptr;
    if constexpr(std::is_same<T, float>::value)
      t = std::strtof(text.c_str(), &end);
    else
      t = std::strtod(text.c_str(), &end);
    if(end != text.c_str() + text.size() || std::isinf(t))
      return false;
    x = double(t);
    return true;
  }

  std::istream& m_is;
  std::vector<char> m_data;                 // m_data[m_pos, m_end): read from the file, not yet parsed
  std::size_t m_pos = 0, m_end = 0;
  bool m_at_end = false;
};
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

// Checks the header's structure before CGAL's parser sees it. Why: CGAL 5.5's
// PLY_reader::init() appends every property line to the last element read, and crashes on a
// property line before any element line (found by the fuzz test). Returns whether the data
// is ASCII: the second word of the second line is "ascii", as CGAL's parser decides.
inline bool check_ply_header(std::istream& is, const std::string& file)
{
  std::string line;
  bool element = false, ascii = false;
  std::size_t bytes = 0, number = 0;
  while(std::getline(is, line))
  {
    bytes += line.size() + 1;
    if(++number == 1 && line.compare(0, 3, "ply") != 0)
      throw std::runtime_error(file + ": not a PLY file (bad header)");
    if(bytes > (1 << 20))
      throw std::runtime_error(file + ": not a PLY file (no end of header in the first MiB)");
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if(number == 2)
    {
      std::string format;
      ascii = (words >> format) && format == "ascii";
    }
    if(keyword == "element")
    {
      std::string name;
      long long count = -1;
      if(!(words >> name >> count) || count < 0)
        throw std::runtime_error(file + ": bad header line " + std::to_string(number) + ": '" + line + "'");
      element = true;
    }
    else if(keyword == "property" && !element)
      throw std::runtime_error(file + ": bad header: line " + std::to_string(number) + " has a property before any element");
    else if(keyword == "end_header")
    {
      is.clear();
      is.seekg(0);
      return ascii;
    }
  }
  throw std::runtime_error(file + ": not a PLY file (no end of header)");
}

inline void read_ply(const std::string& file, Soup& soup)
{
  std::ifstream is(file, std::ios::binary);
  if(!is)
    throw std::runtime_error("cannot open " + file);
  const bool ascii = check_ply_header(is, file);
  CGAL::IO::internal::PLY_reader reader(false);
  if(!reader.init(is))
    throw std::runtime_error(file + ": not a PLY file (bad header)");
  ply::Ascii_numbers text(is);   // the data after the header, when it is ASCII
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
    std::vector<ply::Property_reader> readers;
    for(std::size_t k = 0; k < element.number_of_properties(); ++k)
    {
      try { readers.push_back(ply::reader_of(element.property(k))); }
      catch(const std::runtime_error& e) { throw std::runtime_error(file + ": element '" + name + "': " + e.what()); }
    }
    for(std::size_t k = 0; k < element.number_of_properties(); ++k)
    {
      const std::string& pn = element.property(k)->name();
      if(is_vertex)
      {
        const std::string type = readers[k].type;
        if(pn == "x" || pn == "y" || pn == "z")
        {
          xyz[pn[0] - 'x'] = int(k);
          continue;
        }
        if(readers[k].is_list)
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
      else if((is_face || is_strip) && (pn == "vertex_indices" || pn == "vertex_index") && readers[k].is_list)
        indices = int(k);
    }
    if(is_vertex)
    {
      if(have_vertices)
        throw std::runtime_error(file + ": more than one vertex element");
      if(xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0 || readers[std::size_t(xyz[0])].is_list || readers[std::size_t(xyz[1])].is_list
         || readers[std::size_t(xyz[2])].is_list)
        throw std::runtime_error(file + ": the vertex element has no x, y, z numbers");
      soup.double_positions = readers[std::size_t(xyz[0])].type == "double";
      have_vertices = true;
    }
    if((is_face || is_strip) && indices < 0)
      throw std::runtime_error(file + ": element '" + name + "' has no vertex_indices list");
    std::vector<long long> list, unused_list;
    std::vector<double> value(element.number_of_properties(), 0.);
    for(std::size_t j = 0; j < element.number_of_items(); ++j)
    {
      for(std::size_t k = 0; k < element.number_of_properties(); ++k)
      {
        const ply::Property_reader& r = readers[k];
        bool read = true;
        try
        {
          if(r.is_list && ascii)
            ply::read_list([&](bool is_count, double& x) { return text.read(is_count ? r.count : r.item, x); },
                           int(k) == indices ? list : unused_list);
          else if(r.is_list)
            r.list(is, int(k) == indices ? list : unused_list);
          else if(ascii)
            read = text.read(r.scalar, value[k]);
          else
            value[k] = r.number(is);
        }
        catch(const std::runtime_error& e)
        {
          throw std::runtime_error(file + ": item " + std::to_string(j) + " of element '" + name + "': " + e.what());
        }
        if(!read || (!ascii && is.fail()))   // (the ASCII blocks read to the end of the file: its state says nothing)
          throw std::runtime_error(file + ": truncated or unreadable at item " + std::to_string(j) + " of element '" + name + "'");
      }
      if(is_vertex)
      {
        soup.points.emplace_back(value[std::size_t(xyz[0])], value[std::size_t(xyz[1])], value[std::size_t(xyz[2])]);
        for(auto& v : soup.values) v.push_back(Value4{{0., 0., 0., 0.}});
        for(std::size_t k = 0; k < element.number_of_properties(); ++k)
          if(channel_of[k] >= 0)
            soup.values[std::size_t(channel_of[k])].back()[std::size_t(component_of[k])] = value[k];
      }
      else if(is_face || is_strip)
      {
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

// std::sort, on every core where TBB is linked; for orders with no ties (every comparison
// here ends on the indices), whose sorted sequence is then the same for any number of threads
template <typename Iterator, typename Less>
void sort_without_ties(Iterator first, Iterator last, const Less& less)
{
#ifdef CGAL_LINKED_WITH_TBB
  tbb::parallel_sort(first, last, less);
#else
  std::sort(first, last, less);
#endif
}

// ---- is the soup already an oriented polygon mesh? ---------------------------------------------

// The answer of CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh() (CGAL 5.5):
// every polygon has at least 3 corners, all different; no directed edge is in two polygons;
// the polygons around every vertex form one fan (a disk or a half-disk). Why by hand: CGAL's
// check keeps the directed edges in a std::set and every vertex's polygons in std::sets, 25 s
// of the 50 s it took to read a 3.1M-vertex PLY; here the directed edges are listed by source
// in flat arrays (each vertex's sorted by target), and each fan is walked inside its vertex's
// own list, which holds the twin of every edge into the vertex. (A vertex's polygons each have
// one edge out of it and one into it; the polygon before the one of an edge v->q around v is the
// one of the edge v->p, the twin of the edge p->v into v of the same polygon.)
inline bool is_oriented_polygon_mesh(const std::vector<std::vector<std::size_t> >& polygons, std::size_t number_of_points)
{
  typedef std::uint32_t Id;
  std::size_t corners = 0;
  for(const auto& p : polygons)
  {
    if(p.size() < 3) return false;
    for(std::size_t v : p)
      if(v >= number_of_points) return false;
    if(p.size() == 3)
    {
      if(p[0] == p[1] || p[1] == p[2] || p[2] == p[0]) return false;   // a corner twice
    }
    else
    {
      std::vector<std::size_t> sorted(p.begin(), p.end());
      std::sort(sorted.begin(), sorted.end());
      if(std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
    }
    corners += p.size();
  }
  if(number_of_points >= std::numeric_limits<Id>::max() || corners >= std::numeric_limits<Id>::max())
    return CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons);   // beyond 32-bit numbers
  // corner c of the flattened polygons: the edge v -> t out of its vertex v, listed by v and
  // sorted by t, and the vertex p before it in its polygon (the edge p -> v into v)
  std::vector<Id> start(number_of_points + 1, 0), from(corners);
  for(const auto& p : polygons)
    for(std::size_t v : p) ++start[v + 1];
  for(std::size_t v = 0; v < number_of_points; ++v) start[v + 1] += start[v];
  std::vector<std::pair<Id, Id> > out(corners);   // (t, c)
  {
    std::vector<Id> fill(start.begin(), start.end() - 1);
    std::size_t c = 0;
    for(const auto& p : polygons)
      for(std::size_t i = 0, size = p.size(); i < size; ++i, ++c)
      {
        out[fill[p[i]]++] = std::make_pair(Id(p[(i + 1) % size]), Id(c));
        from[c] = Id(p[(i + size - 1) % size]);
      }
  }
  for(std::size_t v = 0; v < number_of_points; ++v)
  {
    const auto first = out.begin() + start[v], last = out.begin() + start[v + 1];
    std::sort(first, last);
    if(std::adjacent_find(first, last, [](const auto& x, const auto& y) { return x.first == y.first; }) != last)
      return false;   // a directed edge in two polygons
  }
  // the corner at v of the edge v -> t, or `none`
  const Id none = std::numeric_limits<Id>::max();
  auto edge = [&](Id v, Id t) -> Id {
    const auto first = out.begin() + start[v], last = out.begin() + start[v + 1];
    const auto it = std::lower_bound(first, last, std::make_pair(t, Id(0)));
    return (it != last && it->first == t) ? it->second : none;
  };
  for(std::size_t v = 0; v < number_of_points; ++v)
  {
    const std::size_t degree = start[v + 1] - start[v];
    if(degree == 0) continue;   // an unreferenced point
    // the walk starts at the edge with no twin (where the fan is a half-disk), else anywhere
    Id begin = none;
    std::size_t open = 0;
    for(std::size_t i = start[v]; i < start[v + 1]; ++i)
      if(edge(out[i].first, Id(v)) == none)
      {
        ++open;
        begin = out[i].second;
      }
    if(open > 1) return false;   // two half-disks meet at v
    if(begin == none) begin = out[start[v]].second;
    // c -> the corner of the polygon before c's around v (of the twin v -> p of c's edge p -> v)
    // is one-to-one, directed edges being unique: the walk ends at a border or back at `begin`
    // after at most `degree` steps
    std::size_t walked = 1;
    for(Id c = edge(Id(v), from[begin]); c != none && c != begin; c = edge(Id(v), from[c])) ++walked;
    if(walked != degree) return false;   // v's polygons form more than one fan
  }
  return true;
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
  sort_without_ties(order.begin(), order.end(), key_less);
  std::size_t merged = 0;
  for(std::size_t i = 0; i < n; ++i)
  {
    rep[order[i]] = (i > 0 && same(order[i - 1], order[i])) ? rep[order[i - 1]] : order[i];
    merged += rep[order[i]] != order[i];
  }
  // 2. polygons: merged indices, consecutive repeats out; fewer than 3 corners, a corner twice
  //    or the same corners as an earlier polygon: taken out
  std::size_t degenerate = 0, duplicates = 0;
  // each polygon is rewritten in place (no copy per polygon: 6 million triangles are common)
  std::vector<std::pair<std::array<std::size_t, 3>, std::size_t> > triangles;   // sorted corners, polygon
  std::map<std::vector<std::size_t>, std::size_t> larger;                        // the rare polygons: sorted corners
  std::vector<char> out(s.polygons.size(), 0);                                   // degenerate or a duplicate
  triangles.reserve(s.polygons.size());
  for(std::size_t i = 0; i < s.polygons.size(); ++i)
  {
    std::vector<std::size_t>& p = s.polygons[i];
    std::size_t m = 0;
    for(std::size_t v : p)   // p[m] is written after p[j] for every j >= m was read
      if(m == 0 || rep[v] != p[m - 1]) p[m++] = rep[v];
    p.resize(m);
    while(p.size() > 1 && p.front() == p.back()) p.pop_back();
    if(p.size() == 3)
    {
      std::array<std::size_t, 3> sorted = {{p[0], p[1], p[2]}};
      std::sort(sorted.begin(), sorted.end());
      if(sorted[0] == sorted[1] || sorted[1] == sorted[2]) { ++degenerate; out[i] = 1; continue; }
      triangles.push_back({sorted, i});
      continue;
    }
    std::vector<std::size_t> sorted = p;
    std::sort(sorted.begin(), sorted.end());
    if(p.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) { ++degenerate; out[i] = 1; continue; }
    if(!larger.emplace(sorted, i).second)
    {
      ++duplicates;
      out[i] = 1;
    }
  }
  // equal corners together, the first one first (the polygon numbers break the ties)
  sort_without_ties(triangles.begin(), triangles.end(), std::less<std::pair<std::array<std::size_t, 3>, std::size_t> >());
  for(std::size_t i = 1; i < triangles.size(); ++i)
    if(triangles[i].first == triangles[i - 1].first)
    {
      ++duplicates;
      out[triangles[i].second] = 1;
    }
  std::vector<std::pair<std::array<std::size_t, 3>, std::size_t> >().swap(triangles);
  std::size_t kept = 0;
  for(std::size_t i = 0; i < s.polygons.size(); ++i)
    if(!out[i])
    {
      if(kept != i) s.polygons[kept] = std::move(s.polygons[i]);
      ++kept;
    }
  s.polygons.resize(kept);
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
  // a soup that already is an oriented manifold needs no orientation pass (the costly part)
  if(!is_oriented_polygon_mesh(s.polygons, s.points.size()))
    CGAL::Polygon_mesh_processing::orient_polygon_soup(s.points, s.polygons, CGAL::parameters::visitor(follow));
  if(counts[1]) s.notes.push_back(plural(counts[1], "non-manifold edge") + " cut apart");
  if(counts[0]) s.notes.push_back(plural(counts[0], "vertex") + " duplicated where the surface is pinched (non-manifold)");
  if(counts[2]) s.notes.push_back(plural(counts[2], "face") + " reversed to orient the surface consistently");
}

// ---- memory order ----------------------------------------------------------------------------

// Puts the polygons and the points, with their attribute values, in the order a decomposition
// keeps of its own (Memory_order::SPATIAL, internal::spatial_order()): polygons in the Morton
// order of their centroids, points numbered in the order those polygons first name them, each
// polygon's corners kept in their cyclic order. Neighbours then lie close in memory, and a
// decomposition (Memory_order::AUTOMATIC) finds the numbering in order and keeps it: the order
// the library would give the file as read. A large mesh whose file lists its
// vertices and faces in no spatial order (Loop subdivision appends each step's new vertices
// after the old ones) decomposes faster (benchmark README). Points whose extent is not finite
// and positive keep the file's order.
// (The tool's own Hilbert order, CGAL::hilbert_sort() with faces by their first point, made the
// decomposition of the subdivided 3.1M-vertex horse slower than the library's order: 6.9
// against 6.3 s.)
inline void order_spatially(Soup& s)
{
  namespace smri = CGAL::Surface_mesh_multiresolution::internal;
  const std::size_t n = s.points.size();
  if(n >= std::size_t(smri::invalid_index) || s.polygons.size() >= std::size_t(smri::invalid_index))
    return;                                         // (numbered in 32 bits: a decomposition refuses such a mesh)
  std::vector<smri::Index> vertex_order, face_order;
  smri::spatial_order(
      n, s.polygons.size(), [&](std::size_t v, int c) { return s.points[v][c]; },
      [&](std::size_t f) { return s.polygons[f].size(); }, [&](std::size_t f, std::size_t j) { return s.polygons[f][j]; },
      vertex_order, face_order);
  if(vertex_order.size() != n)
    return;
  std::vector<std::size_t> place(n);
  std::vector<Point> points(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    place[vertex_order[i]] = i;
    points[i] = s.points[vertex_order[i]];
  }
  s.points.swap(points);
  for(std::vector<Value4>& values : s.values)
  {
    std::vector<Value4> moved(n);
    for(std::size_t i = 0; i < n; ++i) moved[i] = values[vertex_order[i]];
    values.swap(moved);
  }
  std::vector<std::vector<std::size_t> > polygons(s.polygons.size());
  for(std::size_t p = 0; p < polygons.size(); ++p)
  {
    polygons[p].swap(s.polygons[face_order[p]]);
    for(std::size_t& v : polygons[p])
      v = place[v];
  }
  s.polygons.swap(polygons);
}

// ---- reading a file into a mesh ----------------------------------------------------------------

// Reads a mesh file into a triangle mesh with channels; throws std::runtime_error with a message.
// `spatial_order`: the repaired soup is put in spatial order (order_spatially()) first.
inline Scan read_scan(const std::string& file, bool spatial_order = false)
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
  if(spatial_order)
    order_spatially(soup);
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
