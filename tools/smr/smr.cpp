// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
//
// smr: the package's command-line tool. Subcommands info, decompose, reconstruct, filter,
// denoise, lod and relax on meshes (PLY, OFF, OBJ, STL) and saved pyramids; a PLY's
// per-vertex properties are attribute channels and come back in the output with their names.
// Errors: a message on stderr and exit status 1; Ctrl-C cancels (status 130), no output file
// is then written.
#include "scan_io.h"

#include <CGAL/Surface_mesh_multiresolution.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>

#include <CLI/CLI.hpp>

#include <atomic>
#include <iomanip>
#include <chrono>
#include <csignal>
#include <cstring>
#include <iostream>
#include <sstream>
#include <tuple>

namespace SMR = CGAL::Surface_mesh_multiresolution;
using namespace smr_tool;
typedef SMR::Pyramid<Mesh> Pyramid;

namespace {

std::atomic<bool> interrupted(false);
bool quiet = false;
bool spatial_order = false;   // --spatial-order: meshes read are put in spatial order (order_spatially())
extern "C" void on_interrupt(int) { interrupted = true; }

struct Cancelled : std::runtime_error { Cancelled() : std::runtime_error("cancelled") {} };

void say(const std::string& line)
{
  if(!quiet) std::cerr << line << std::endl;
}

// progress of the decomposition on stderr; Ctrl-C cancels
struct Decomposition_progress : SMR::Decomposition_visitor_base
{
  bool on_level_started(std::size_t k, std::size_t vertices)
  {
    if(interrupted) return false;
    if(!quiet && (k % 4 == 0)) std::cerr << "  level " << k << ": " << vertices << " vertices" << std::endl;
    return true;
  }
};

struct Denoising_progress : SMR::Denoising_visitor_base
{
  bool on_pass(unsigned int pass, unsigned int passes)
  {
    if(interrupted) return false;
    if(!quiet && pass % 10 == 0) std::cerr << "  denoising pass " << pass << " of " << passes << std::endl;
    return true;
  }
};

// ---- the attribute channels as a tuple of property maps, for 0 to 4 channels --------------

template <typename F>
auto with_maps(const std::vector<Channel_map>& m, F&& f)
{
  switch(m.size())
  {
    case 0: return f(std::tuple<>());
    case 1: return f(std::make_tuple(m[0]));
    case 2: return f(std::make_tuple(m[0], m[1]));
    case 3: return f(std::make_tuple(m[0], m[1], m[2]));
    default: return f(std::make_tuple(m[0], m[1], m[2], m[3]));
  }
}

// ---- the tool's pyramid file: channel names, then the package's pyramid format -----------

constexpr char tool_magic[9] = "SMRTOOL1";

struct Pyramid_file
{
  Pyramid pyr;
  std::vector<Channel> channels;
  bool double_positions = true;
};

void put_string(std::ostream& os, const std::string& s)
{
  const std::uint32_t n = std::uint32_t(s.size());
  os.write(reinterpret_cast<const char*>(&n), 4);
  os.write(s.data(), std::streamsize(n));
}

bool get_string(std::istream& is, std::string& s)
{
  std::uint32_t n = 0;
  if(!is.read(reinterpret_cast<char*>(&n), 4) || n > 4096) return false;
  s.resize(n);
  return bool(is.read(&s[0], std::streamsize(n)));
}

void write_pyramid_file(const std::string& file, const Pyramid_file& p)
{
  const std::string partial = file + ".partial";
  {
    std::ofstream os(partial, std::ios::binary);
    os.write(tool_magic, 8);
    const std::uint32_t nc = std::uint32_t(p.channels.size());
    os.write(reinterpret_cast<const char*>(&nc), 4);
    for(const Channel& c : p.channels)
    {
      put_string(os, c.kind);
      const std::uint32_t n = std::uint32_t(c.names.size());
      os.write(reinterpret_cast<const char*>(&n), 4);
      for(std::size_t j = 0; j < n; ++j) { put_string(os, c.names[j]); put_string(os, c.types[j]); }
    }
    os.put(p.double_positions ? 1 : 0);
    if(!SMR::IO::write_pyramid(os, p.pyr) || !os.flush())
    {
      os.close();
      std::remove(partial.c_str());
      throw std::runtime_error("cannot write " + file);
    }
  }
  if(std::rename(partial.c_str(), file.c_str()) != 0)
  {
    std::remove(partial.c_str());
    throw std::runtime_error("cannot write " + file);
  }
}

// whether the file starts as a pyramid (the tool's or the package's format)
bool is_pyramid_file(const std::string& file)
{
  std::ifstream is(file, std::ios::binary);
  char magic[8] = {0};
  is.read(magic, 8);
  return is && (std::memcmp(magic, tool_magic, 8) == 0 || std::memcmp(magic, "SMRPYR01", 8) == 0);
}

Pyramid_file read_pyramid_file(const std::string& file)
{
  std::ifstream is(file, std::ios::binary);
  if(!is) throw std::runtime_error("cannot open " + file);
  Pyramid_file p;
  char magic[8] = {0};
  is.read(magic, 8);
  const bool tool = std::memcmp(magic, tool_magic, 8) == 0;
  if(tool)
  {
    std::uint32_t nc = 0;
    if(!is.read(reinterpret_cast<char*>(&nc), 4) || nc > max_channels)
      throw std::runtime_error(file + ": corrupt pyramid file (channel list)");
    for(std::uint32_t c = 0; c < nc; ++c)
    {
      Channel ch;
      std::uint32_t n = 0;
      if(!get_string(is, ch.kind) || !is.read(reinterpret_cast<char*>(&n), 4) || n == 0 || n > 4)
        throw std::runtime_error(file + ": corrupt pyramid file (channel list)");
      ch.names.resize(n); ch.types.resize(n);
      for(std::uint32_t j = 0; j < n; ++j)
        if(!get_string(is, ch.names[j]) || !get_string(is, ch.types[j]))
          throw std::runtime_error(file + ": corrupt pyramid file (channel list)");
      p.channels.push_back(ch);
    }
    p.double_positions = is.get() == 1;
  }
  else
    is.seekg(0);
  std::string error;
  if(!SMR::IO::read_pyramid(is, p.pyr, error))
    throw std::runtime_error(file + ": " + error);
  const std::size_t attribute_channels = p.pyr.number_of_channels() - 1;
  if(tool && attribute_channels != p.channels.size())
    throw std::runtime_error(file + ": corrupt pyramid file (" + std::to_string(p.channels.size()) + " channel names, "
                             + std::to_string(attribute_channels) + " channels)");
  if(!tool)
  {
    bool all_four = true;
    for(std::size_t c = 1; c < p.pyr.number_of_channels(); ++c) all_four = all_four && p.pyr.dimensions()[c] == 4;
    if(attribute_channels > max_channels || !all_four)
      say("note: the pyramid's attribute channels are not of the tool's kind (at most 4, of 4 components): geometry only");
    else
      for(std::size_t c = 0; c < attribute_channels; ++c)
        p.channels.push_back(Channel{"scalar", {"channel" + std::to_string(c + 1) + "_0", "channel" + std::to_string(c + 1) + "_1",
                                                "channel" + std::to_string(c + 1) + "_2", "channel" + std::to_string(c + 1) + "_3"},
                                     {"float", "float", "float", "float"}});
  }
  return p;
}

// ---- inputs -------------------------------------------------------------------------------

// "color (red green blue), normal (nx ny nz)", with each component's PLY type if asked
std::string describe(const std::vector<Channel>& channels, bool with_types)
{
  std::string text;
  for(const Channel& c : channels)
  {
    text += (text.empty() ? "" : ", ") + c.kind + " (";
    for(std::size_t j = 0; j < c.names.size(); ++j)
      text += (j ? " " : "") + c.names[j] + (with_types ? ":" + c.types[j] : std::string());
    text += ")";
  }
  return text;
}

Scan read_mesh(const std::string& file)
{
  Scan scan = read_scan(file, spatial_order);
  const std::string channels = describe(scan.channels, false);
  say(file + ": " + plural(num_vertices(scan.mesh), "vertex") + ", " + plural(num_faces(scan.mesh), "face")
      + (channels.empty() ? "" : "; channels: " + channels));
  for(const std::string& n : scan.notes) say("  repaired: " + n);
  if(spatial_order) say("  faces and vertices put in the pyramid's spatial order: the outputs list them so");
  return scan;
}

SMR::Relaxation_scheme scheme_of(const std::string& s)
{
  if(s == "curvature") return SMR::Relaxation_scheme::CURVATURE;
  if(s == "sod") return SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE;
  return SMR::Relaxation_scheme::UNIFORM;
}

Pyramid_file decompose_scan(Scan& scan, const std::string& scheme, std::size_t min_vertices)
{
  Pyramid_file p;
  p.channels = scan.channels;
  p.double_positions = scan.double_positions;
  const auto t0 = std::chrono::steady_clock::now();
  p.pyr = with_maps(scan.maps, [&](const auto& maps) {
    return SMR::decompose(scan.mesh, SMR::parameters::vertex_attribute_maps(maps).relaxation_scheme(scheme_of(scheme))
                                       .minimum_number_of_vertices(min_vertices).visitor(Decomposition_progress()));
  });
  if(interrupted) throw Cancelled();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ostringstream msg;
  msg << "decomposed into " << p.pyr.number_of_levels() << " levels (" << p.pyr.number_of_vertices(p.pyr.number_of_levels())
      << " vertices in the coarsest mesh) in " << s << " s";
  say(msg.str());
  return p;
}

// the pyramid of IN: read if it is one, decomposed otherwise
Pyramid_file pyramid_of(const std::string& in, const std::string& scheme, std::size_t min_vertices)
{
  if(is_pyramid_file(in))
    return read_pyramid_file(in);
  Scan scan = read_mesh(in);
  return decompose_scan(scan, scheme, min_vertices);
}

void write_mesh(const std::string& out, const Mesh& mesh, const std::vector<Channel>& channels,
                const std::vector<Channel_map>& maps, bool double_positions)
{
  if(interrupted) throw Cancelled();
  std::string dropped;
  write_scan(out, mesh, channels, maps, double_positions, dropped);
  if(!dropped.empty())
    say("note: " + extension_of(out) + " files have no place for the channels (" + dropped + "): " + out
        + " has the geometry only (write a .ply to keep them)");
  say("wrote " + out + ": " + plural(num_vertices(mesh), "vertex") + ", " + plural(num_faces(mesh), "face"));
}

// reconstructs level k with the channels and writes it
void write_level(const Pyramid_file& p, const std::string& out, std::size_t level)
{
  Mesh mesh;
  const std::vector<Channel_map> maps = add_channel_maps(mesh, p.channels.size());
  with_maps(maps, [&](const auto& m) {
    SMR::reconstruct(p.pyr, mesh, SMR::parameters::level(level).vertex_attribute_maps(m));
    return 0;
  });
  write_mesh(out, mesh, p.channels, maps, p.double_positions);
}

// ---- subcommands --------------------------------------------------------------------------

int info(const std::string& in)
{
  if(is_pyramid_file(in))
  {
    const Pyramid_file p = read_pyramid_file(in);
    const std::size_t K = p.pyr.number_of_levels();
    std::cout << in << ": pyramid of " << K << " levels, " << p.pyr.number_of_input_vertices() << " input vertices\n";
    std::cout << "  relaxation scheme: "
              << (p.pyr.relaxation_scheme() == SMR::Relaxation_scheme::CURVATURE ? "curvature"
                  : p.pyr.relaxation_scheme() == SMR::Relaxation_scheme::SECOND_ORDER_DIFFERENCE ? "sod" : "uniform") << "\n";
    std::cout << "  channels: geometry (x y z)" << (p.channels.empty() ? "" : ", ") << describe(p.channels, false);
    std::cout << "\n  level  vertices  faces\n";
    for(std::size_t k = 0; k <= K; ++k)
      std::cout << "  " << std::setw(5) << k << "  " << std::setw(8) << p.pyr.number_of_vertices(k) << "  " << std::setw(5)
                << p.pyr.number_of_faces(k) << "\n";
    return 0;
  }
  const bool was_quiet = quiet;
  quiet = true;                                  // the repairs are listed below
  Scan scan = read_scan(in);
  quiet = was_quiet;
  const Mesh& m = scan.mesh;
  std::vector<Mesh::Halfedge_index> borders;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(m, std::back_inserter(borders));
  std::vector<std::size_t> component(num_faces(m));
  const std::size_t components = CGAL::Polygon_mesh_processing::connected_components(m, CGAL::make_property_map(component));
  std::cout << in << ": triangle mesh, " << plural(num_vertices(m), "vertex") << ", " << plural(num_faces(m), "face") << ", "
            << plural(num_edges(m), "edge") << "\n";
  std::cout << "  border loops: " << borders.size() << ", connected components: " << components << "\n";
  std::cout << "  positions: " << (scan.double_positions ? "double" : "float") << "\n  channels: geometry (x y z)"
            << (scan.channels.empty() ? "" : ", ") << describe(scan.channels, true) << "\n";
  for(const std::string& n : scan.notes) std::cout << "  repaired on reading: " << n << "\n";
  return 0;
}

int decompose_command(const std::string& in, const std::string& out, const std::string& scheme, std::size_t min_vertices)
{
  if(extension_of(out) == "ply" || extension_of(out) == "off" || extension_of(out) == "obj" || extension_of(out) == "stl")
    throw std::runtime_error(out + ": a pyramid is written in the pyramid format (use the extension .smrp)");
  Scan scan = read_mesh(in);
  const Pyramid_file p = decompose_scan(scan, scheme, min_vertices);
  write_pyramid_file(out, p);
  say("wrote " + out);
  return 0;
}

int reconstruct_command(const std::string& in, const std::string& out, std::size_t level)
{
  const Pyramid_file p = read_pyramid_file(in);
  if(level > p.pyr.number_of_levels())
    throw std::runtime_error("level " + std::to_string(level) + " does not exist (the pyramid has levels 0 to "
                             + std::to_string(p.pyr.number_of_levels()) + ")");
  write_level(p, out, level);
  return 0;
}

int filter_command(const std::string& in, const std::string& out, const std::string& scheme, const std::vector<std::size_t>& low,
                   const std::vector<std::size_t>& stop, const std::vector<double>& enhance)
{
  Pyramid_file p = pyramid_of(in, scheme, 4);
  const std::size_t K = p.pyr.number_of_levels();
  auto check = [K](std::size_t a, std::size_t b) {
    if(a > b || b >= K)
      throw std::runtime_error("levels " + std::to_string(a) + " to " + std::to_string(b) + " are not a range of detail levels 0 to "
                               + std::to_string(K == 0 ? 0 : K - 1));
  };
  if(!low.empty())
  {
    if(low[0] > K) throw std::runtime_error("--low-pass " + std::to_string(low[0]) + ": the pyramid has " + plural(K, "level"));
    SMR::low_pass(p.pyr, low[0]);
  }
  else if(!stop.empty())
  {
    check(stop[0], stop[1]);
    SMR::stop_band(p.pyr, stop[0], stop[1]);
  }
  else
  {
    const double a = enhance[0], b = enhance[1];
    if(a < 0 || b < 0 || a != std::floor(a) || b != std::floor(b)) throw std::runtime_error("--enhance: A and B are level numbers");
    if(!std::isfinite(enhance[2])) throw std::runtime_error("--enhance: the gain must be finite");
    check(std::size_t(a), std::size_t(b));
    SMR::enhance(p.pyr, std::size_t(a), std::size_t(b), enhance[2]);
  }
  write_level(p, out, 0);
  return 0;
}

int denoise_command(const std::string& in, const std::string& out)
{
  Pyramid_file p = pyramid_of(in, "curvature", 4);
  const auto t0 = std::chrono::steady_clock::now();
  SMR::denoise(p.pyr, SMR::parameters::visitor(Denoising_progress()));
  if(interrupted) throw Cancelled();
  std::ostringstream msg;
  msg << "denoised in " << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s";
  say(msg.str());
  write_level(p, out, 0);
  return 0;
}

int lod_command(const std::string& in, const std::string& out, const std::string& scheme, long long vertices, double ratio,
                double error, const std::string& guide)
{
  Pyramid_file p = pyramid_of(in, scheme, 4);
  std::size_t channel = 0;
  if(!guide.empty() && guide != "geometry")
  {
    for(std::size_t c = 0; c < p.channels.size(); ++c)
      if(p.channels[c].kind == guide) channel = c + 1;
    if(channel == 0)
      throw std::runtime_error("--guide " + guide + ": the input has no such channel");
  }
  const std::size_t n = p.pyr.number_of_input_vertices();
  std::size_t target = 0;
  if(vertices >= 0) target = std::size_t(vertices);
  else if(ratio >= 0)
  {
    if(!(ratio <= 1)) throw std::runtime_error("--ratio must be in [0, 1]");
    target = std::size_t(std::llround(ratio * double(n)));
  }
  Mesh mesh;
  const std::vector<Channel_map> maps = add_channel_maps(mesh, p.channels.size());
  double used = 0;
  with_maps(maps, [&](const auto& m) {
    const auto common = SMR::parameters::vertex_attribute_maps(m).channel(channel).remove_isolated_vertices(true)
                          .adaptive_criterion(channel == 0 ? SMR::Adaptive_criterion::APPROXIMATION_ERROR
                                                           : SMR::Adaptive_criterion::DETAIL_LENGTH);
    if(error >= 0)
      used = SMR::reconstruct_adaptively(p.pyr, mesh, error, common);
    else
      used = SMR::reconstruct_adaptively(p.pyr, mesh, 0., common.target_number_of_vertices(target));
    return 0;
  });
  std::ostringstream msg;
  msg << "level of detail: " << num_vertices(mesh) << " of " << n << " vertices";
  if(error < 0 && std::isfinite(used)) msg << " (threshold reached: " << used << ")";
  if(error < 0 && num_vertices(mesh) > target)
    msg << "; the coarsest mesh of the pyramid has " << p.pyr.number_of_vertices(p.pyr.number_of_levels()) << " vertices";
  say(msg.str());
  write_mesh(out, mesh, p.channels, maps, p.double_positions);
  return 0;
}

int relax_command(const std::string& in, const std::string& out, const std::string& scheme, unsigned int iterations)
{
  if(is_pyramid_file(in))
    throw std::runtime_error(in + ": relax works on a mesh (reconstruct the pyramid first)");
  Scan scan = read_mesh(in);
  with_maps(scan.maps, [&](const auto& m) {
    SMR::relax(scan.mesh, SMR::parameters::vertex_attribute_maps(m).relaxation_scheme(scheme_of(scheme)).number_of_iterations(iterations));
    return 0;
  });
  write_mesh(out, scan.mesh, scan.channels, scan.maps, scan.double_positions);
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  CLI::App app{"smr: multiresolution analysis of irregular triangle meshes (Roy, Foufou, Koschan, Truchetet, Abidi).\n"
               "Meshes: PLY (every per-vertex property kept as a channel), OFF, OBJ, STL (geometry). Pyramids: .smrp files."};
  app.require_subcommand(1);
  app.add_flag("-q,--quiet", quiet, "no progress or notes on stderr");
  app.add_flag("--spatial-order", spatial_order,
               "put the faces (Morton order of their centroids) and vertices (in the order those faces first name them) of every "
               "mesh read in the spatial order a decomposition keeps of its own, before working on it: faster on large meshes "
               "stored in no spatial order (decompose orders such meshes itself and keeps its outputs in the file's order); "
               "the outputs list vertices and faces in that order");
  app.fallthrough();      // --quiet and --spatial-order before or after the subcommand
  const std::vector<std::string> schemes = {"curvature", "sod", "uniform"};
  std::string in, out, scheme = "curvature", guide;
  std::size_t min_vertices = 4, level = 0;
  unsigned int iterations = 1;

  CLI::App* info_cmd = app.add_subcommand("info", "counts, channels, borders and components of a mesh, or the levels of a pyramid");
  info_cmd->add_option("FILE", in, "mesh or pyramid")->required();

  CLI::App* dec = app.add_subcommand("decompose", "build the mesh pyramid of a mesh (Section 3) and save it");
  dec->add_option("IN", in, "input mesh")->required();
  dec->add_option("-o,--output", out, "output pyramid (.smrp)")->required();
  dec->add_option("--scheme", scheme, "relaxation operator")->check(CLI::IsMember(schemes))->capture_default_str();
  dec->add_option("--min-vertices", min_vertices, "no level below this number of vertices")->capture_default_str();

  CLI::App* rec = app.add_subcommand("reconstruct", "write level K of a saved pyramid (0: the input, exactly)");
  rec->add_option("PYR", in, "saved pyramid")->required();
  rec->add_option("-o,--output", out, "output mesh")->required();
  rec->add_option("--level", level, "level to reconstruct")->capture_default_str();

  std::vector<std::size_t> low, stop;
  std::vector<double> gain;
  CLI::App* fil = app.add_subcommand("filter", "multiresolution filters (Section 4.1, Fig. 5)");
  fil->add_option("IN", in, "input mesh or pyramid")->required();
  fil->add_option("-o,--output", out, "output mesh")->required();
  fil->add_option("--scheme", scheme, "relaxation operator (for a mesh input)")->check(CLI::IsMember(schemes))->capture_default_str();
  auto* o_low = fil->add_option("--low-pass", low, "J: drop the details of levels 0 to J-1")->expected(1);
  auto* o_stop = fil->add_option("--stop-band", stop, "A B: drop the details of levels A to B")->expected(2);
  auto* o_enh = fil->add_option("--enhance", gain, "A B G: scale the details of levels A to B by G")->expected(3);
  o_low->excludes(o_stop)->excludes(o_enh);
  o_stop->excludes(o_enh);

  CLI::App* den = app.add_subcommand("denoise", "feature-preserving denoising of the geometry (Section 4.2)");
  den->add_option("IN", in, "input mesh or pyramid")->required();
  den->add_option("-o,--output", out, "output mesh")->required();

  long long vertices = -1;
  double ratio = -1, error = -1;
  CLI::App* lod = app.add_subcommand("lod", "adaptive level of detail that keeps input vertices (Section 4.3)");
  lod->add_option("IN", in, "input mesh or pyramid")->required();
  lod->add_option("-o,--output", out, "output mesh")->required();
  lod->add_option("--scheme", scheme, "relaxation operator (for a mesh input)")->check(CLI::IsMember(schemes))->capture_default_str();
  auto* o_v = lod->add_option("--vertices", vertices, "vertex budget")->check(CLI::NonNegativeNumber);
  auto* o_r = lod->add_option("--ratio", ratio, "vertex budget as a fraction of the input's vertices")->check(CLI::Range(0., 1.));
  auto* o_e = lod->add_option("--error", error,
                              "threshold: a distance in model units (approximation error), or with --guide a detail length of that channel")
                ->check(CLI::NonNegativeNumber);
  o_v->excludes(o_r)->excludes(o_e);
  o_r->excludes(o_e);
  lod->add_option("--guide", guide, "the channel that chooses the vertices: geometry (default: approximation error) or a channel kind "
                                    "(color, normal, texture, scalar: its detail lengths)");

  CLI::App* rel = app.add_subcommand("relax", "apply the relaxation operator (Section 2) to the geometry and every channel");
  rel->add_option("IN", in, "input mesh")->required();
  rel->add_option("-o,--output", out, "output mesh")->required();
  rel->add_option("--scheme", scheme, "relaxation operator")->check(CLI::IsMember(schemes))->capture_default_str();
  rel->add_option("--iterations", iterations, "number of steps")->capture_default_str();

  CLI11_PARSE(app, argc, argv);
  std::signal(SIGINT, on_interrupt);
  try
  {
    if(*info_cmd) return info(in);
    if(*dec) return decompose_command(in, out, scheme, min_vertices);
    if(*rec) return reconstruct_command(in, out, level);
    if(*fil)
    {
      if(low.empty() && stop.empty() && gain.empty())
        throw std::runtime_error("filter: one of --low-pass, --stop-band, --enhance is needed");
      return filter_command(in, out, scheme, low, stop, gain);
    }
    if(*den) return denoise_command(in, out);
    if(*lod)
    {
      if(vertices < 0 && ratio < 0 && error < 0)
        throw std::runtime_error("lod: one of --vertices, --ratio, --error is needed");
      return lod_command(in, out, scheme, vertices, ratio, error, guide);
    }
    if(*rel) return relax_command(in, out, scheme, iterations);
  }
  catch(const Cancelled&)
  {
    std::cerr << "smr: cancelled, nothing written" << std::endl;
    return 130;
  }
  catch(const std::exception& e)
  {
    std::cerr << "smr: " << e.what() << std::endl;
    return 1;
  }
  return 1;
}
