// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CHANNELS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CHANNELS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/Attribute_traits.h>
#include <CGAL/Surface_mesh_multiresolution/parameters.h>

#include <boost/property_map/property_map.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// vertex_attribute_maps(m) accepts a std::tuple of property maps or a single map
template <typename T>
struct Is_tuple : std::false_type {};
template <typename... T>
struct Is_tuple<std::tuple<T...> > : std::true_type {};

template <typename T>
auto as_tuple(const T& t) -> typename std::enable_if<Is_tuple<T>::value, const T&>::type { return t; }
template <typename T>
auto as_tuple(const T& t) -> typename std::enable_if<!Is_tuple<T>::value, std::tuple<T> >::type { return std::tuple<T>(t); }

template <typename Map>
struct Channel_traits
{
  typedef typename boost::property_traits<Map>::value_type Value;
  typedef Attribute_traits<Value> Traits;
  static constexpr std::size_t dimension = Traits::dimension;
};

template <typename Tuple>
struct Channel_tuple;

template <typename... Maps>
struct Channel_tuple<std::tuple<Maps...> >
{
  static constexpr std::size_t size = sizeof...(Maps);
  static constexpr std::size_t total_dimension() { return (std::size_t(0) + ... + Channel_traits<Maps>::dimension); }
};

template <typename Tuple, typename F, std::size_t... I>
void for_each_channel_impl(const Tuple& t, F&& f, std::index_sequence<I...>)
{
  (f(std::get<I>(t), std::integral_constant<std::size_t, I>()), ...);
}

// calls f(map, integral_constant<c>) for every channel map c of the tuple
template <typename... Maps, typename F>
void for_each_channel(const std::tuple<Maps...>& t, F&& f)
{
  for_each_channel_impl(t, std::forward<F>(f), std::index_sequence_for<Maps...>());
}

// Reads one channel for the vertices (in row order) into buf: row r's value goes to
// buf[r * stride + offset ...]. \throws std::invalid_argument on a non-finite value.
template <typename Map, typename VertexRange>
void read_channel(const Map& map, const VertexRange& vertices, std::size_t channel_number,
                  double* buf, std::size_t stride, std::size_t offset)
{
  typedef Channel_traits<Map> CT;
  std::size_t r = 0;
  for(const auto& v : vertices)
  {
    const std::array<double, CT::dimension> a = CT::Traits::to_array(get(map, v));
    double* out = buf + r * stride + offset;
    for(std::size_t c = 0; c < CT::dimension; ++c)
    {
      if(!std::isfinite(a[c]))
        throw std::invalid_argument("attribute channel " + std::to_string(channel_number) + " has a non-finite value at vertex "
                                    + std::to_string(r) + " (in the order of vertices(tm))");
      out[c] = a[c];
    }
    ++r;
  }
}

template <typename Map, typename VertexRange>
void write_channel(const Map& map, const VertexRange& vertices, const double* buf, std::size_t stride, std::size_t offset)
{
  typedef Channel_traits<Map> CT;
  std::size_t r = 0;
  for(const auto& v : vertices)
  {
    std::array<double, CT::dimension> a;
    const double* in = buf + r * stride + offset;
    for(std::size_t c = 0; c < CT::dimension; ++c)
      a[c] = in[c];
    put(map, v, CT::Traits::from_array(a));
    ++r;
  }
}

// All channels of a tuple interleaved, total_dimension() doubles per row.
template <typename... Maps, typename VertexRange>
void read_channels(const std::tuple<Maps...>& maps, const VertexRange& vertices, std::vector<double>& buf)
{
  const std::size_t stride = Channel_tuple<std::tuple<Maps...> >::total_dimension();
  buf.resize(stride * vertices.size());
  std::size_t offset = 0;
  for_each_channel(maps, [&](const auto& map, auto c) {
    read_channel(map, vertices, decltype(c)::value + 1, buf.data(), stride, offset);
    offset += Channel_traits<std::decay_t<decltype(map)> >::dimension;
  });
}

template <typename... Maps, typename VertexRange>
void write_channels(const std::tuple<Maps...>& maps, const VertexRange& vertices, const std::vector<double>& buf)
{
  const std::size_t stride = Channel_tuple<std::tuple<Maps...> >::total_dimension();
  std::size_t offset = 0;
  for_each_channel(maps, [&](const auto& map, auto) {
    write_channel(map, vertices, buf.data(), stride, offset);
    offset += Channel_traits<std::decay_t<decltype(map)> >::dimension;
  });
}

// The parameters that say which channels a relaxation touches, as relax() and
// Relaxation_operator::apply() read them.
template <typename NamedParameters>
struct Relaxed_channels
{
  bool geometry;
  unsigned int iterations;
  typedef std::decay_t<decltype(as_tuple(parameters::choose_parameter(
      parameters::get_parameter(std::declval<NamedParameters>(), internal_np::vertex_attribute_maps), std::tuple<>())))> Maps;
  Maps maps;
  static constexpr std::size_t attribute_dimension = Channel_tuple<Maps>::total_dimension();

  explicit Relaxed_channels(const NamedParameters& np)
    : geometry(parameters::choose_parameter(parameters::get_parameter(np, internal_np::relax_geometry), true)),
      iterations(parameters::choose_parameter(parameters::get_parameter(np, CGAL::internal_np::number_of_iterations), 1u)),
      maps(as_tuple(parameters::choose_parameter(parameters::get_parameter(np, internal_np::vertex_attribute_maps), std::tuple<>())))
  {}
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_CHANNELS_H
