// Copyright (c) 2026  The Surface_mesh_multiresolution authors. All rights reserved.
//
// This file is part of Surface_mesh_multiresolution, an add-on package for CGAL.
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : The Surface_mesh_multiresolution authors
#ifndef CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SURFACE_MESH_RELAXATION_ROWS_H
#define CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SURFACE_MESH_RELAXATION_ROWS_H

#include <CGAL/Surface_mesh_multiresolution/internal/config.h>
#include <CGAL/Surface_mesh_multiresolution/internal/indexed_mesh.h>
#include <CGAL/Surface_mesh_multiresolution/internal/parallel.h>
#include <CGAL/Surface_mesh_multiresolution/internal/relaxation_weights.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_row_rule.h>
#include <CGAL/Surface_mesh_multiresolution/Relaxation_scheme.h>

#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>

#include <algorithm>
#include <atomic>
#include <bitset>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace CGAL {
namespace Surface_mesh_multiresolution {
namespace internal {

// The rows of the 1-ring schemes (curvature, uniform) read from a Surface_mesh's own
// halfedges, for the relaxations whose weights are used once (relax()). The index path
// (Indexed_mesh, then Relaxation_weight_builder) copies the faces into an array, lists every
// vertex's corners by a counting sort and pairs them by searching the ring: on the dragon that
// was 60 % of a relax() step. A Surface_mesh already pairs its halfedges (the opposite of h is
// h ^ 1), so a walk around each vertex gives its corners; sorted by face they are the index
// path's corners in its order, and the rows it computes are the index path's bit for bit:
// same cotangents (each face's, with the rotation build_indexed_mesh() gives it), same
// pairing, same order of the sums. Where the two pairings could differ (two edges between the
// same vertices: the index path pairs such corners first come, first served), apply_rows()
// says so and the caller takes the index path.
//
// Rows are the vertex indices: usable() only on a mesh without removed elements, where
// vertices(tm) and faces(tm) list the indices in order.
template <typename Point>
class Surface_mesh_relaxation_rows
{
  typedef CGAL::Surface_mesh<Point>               Mesh;
  typedef typename Mesh::Vertex_index             Vertex_index;
  typedef typename Mesh::Halfedge_index           Halfedge_index;
  typedef typename Mesh::Face_index               Face_index;
  typedef Relaxation_weight_builder               Builder;

  // one step of the walk around a vertex: the outgoing halfedge, its target, its face
  // (invalid_index on the border), whether its opposite is a border halfedge
  struct Step
  {
    Index halfedge, target, face;
    bool opposite_on_border;
  };

  static constexpr std::size_t group = 8;   // vertices walked together

public:
  explicit Surface_mesh_relaxation_rows(const Mesh& m) : m_mesh(m) {}

  static bool usable(const Mesh& m) { return !m.has_garbage() && m.number_of_halfedges() < std::size_t(invalid_index); }

  // Throws std::invalid_argument, with build_indexed_mesh()'s words, for the first face of
  // faces(tm) that is not a triangle or repeats a vertex.
  void check_faces() const
  {
    const Mesh& m = m_mesh;
    report_first_defect(first_position_where(m.number_of_faces(), [&](std::size_t f) {
      Halfedge_index h[3];
      return !triangle(f, h);
    }));
  }

  // the cotangents of every face's angles on xyz (3 per vertex index), as the index path
  // computes them (the face's vertices from the source of halfedge(f) on); checks the faces
  // as check_faces() does
  void compute_cotangents(const double* xyz)
  {
    const Mesh& m = m_mesh;
    m_cotangent.resize(m.number_of_halfedges());
    report_first_defect(first_position_where(m.number_of_faces(), [&](std::size_t f) {
      Halfedge_index h[3];
      if(!triangle(f, h))
        return true;
      const Index t[3] = {Index(m.target(h[2])), Index(m.target(h[0])), Index(m.target(h[1]))};
      double cot[3];
      Builder::face_cotangents(t, xyz, cot);
      for(int k = 0; k < 3; ++k)
        m_cotangent[h[k]] = cot[k];
      return false;
    }));
  }

  // frees the cotangents
  void release() { Uninitialized_vector<double>().swap(m_cotangent); }

  // Calls apply_row(i, columns, values, length) for every row i, in parallel: the rows of
  // Relaxation_weight_builder::build_and_apply() on the index view of the mesh (xyz: the
  // coordinates the weights are computed on; fixed: nullptr or a flag per row). The
  // cotangents must have been computed for the curvature scheme. Returns false, after calls
  // for some rows, when some vertex has two edges to one neighbour: the caller then computes
  // every row on the index path.
  template <typename ApplyRow>
  bool apply_rows(Relaxation_scheme scheme, const double* xyz, const unsigned char* fixed, const ApplyRow& apply_row) const
  {
    CGAL_precondition(scheme != Relaxation_scheme::SECOND_ORDER_DIFFERENCE);
    const Mesh& m = m_mesh;
    std::atomic<bool> ambiguous(false);
    std::atomic<std::size_t> corner_count(0);
    parallel_for_blocks(m.number_of_vertices(), [&](std::size_t first, std::size_t last) {
      std::vector<Step> walks[group];
      std::size_t count[group];
      std::vector<Index> corner, scratch, col;   // corner: the walk's positions of the corners, by face
      std::vector<double> val;
      std::size_t listed = 0;
      for(std::size_t i0 = first; i0 < last && !ambiguous.load(std::memory_order_relaxed); i0 += group)
      {
        const std::size_t g = (std::min)(group, last - i0);
        if(!walk_around(i0, g, walks, count))
        {
          ambiguous = true;
          return;
        }
        for(std::size_t j = 0; j < g; ++j)
        {
          if(!distinct_targets(walks[j].data(), count[j], scratch))
          {
            ambiguous = true;
            return;
          }
          const std::size_t length = row(scheme, i0 + j, walks[j].data(), count[j], xyz, fixed, corner, col, val);
          listed += corner.size();
          apply_row(i0 + j, col.data(), val.data(), length);
        }
      }
      corner_count += listed;
    });
    // every face halfedge is some vertex's corner on a valid mesh: the walks saw them all
    return !ambiguous.load() && corner_count.load() == 3 * m.number_of_faces();
  }

private:
  // the halfedges of face f from halfedge(f) on; false if it is not a triangle of three vertices
  bool triangle(std::size_t f, Halfedge_index* h) const
  {
    const Mesh& m = m_mesh;
    h[0] = m.halfedge(Face_index(static_cast<typename Mesh::size_type>(f)));
    h[1] = m.next(h[0]);
    h[2] = m.next(h[1]);
    return m.next(h[2]) == h[0] && m.target(h[0]) != m.target(h[1]) && m.target(h[1]) != m.target(h[2])
           && m.target(h[2]) != m.target(h[0]);
  }

  void report_first_defect(std::size_t f) const
  {
    if(f < m_mesh.number_of_faces())
      throw std::invalid_argument(triangle_defect(m_mesh, Face_index(static_cast<typename Mesh::size_type>(f)), f));
  }

  // Row i from the walk around vertex i (n steps) into col, val (resized as needed), the
  // index path's row; returns its length. corner: the walk's positions of the corners.
  std::size_t row(Relaxation_scheme scheme, std::size_t i, const Step* walk, std::size_t n, const double* xyz,
                  const unsigned char* fixed, std::vector<Index>& corner, std::vector<Index>& col, std::vector<double>& val) const
  {
    // The corners are the walk's face halfedges. The apex of corner r is the target of the
    // walk's next halfedge (the opposite of the corner's predecessor in its face), whose face
    // says whether the corner is some corner's twin.
    corner.clear();
    bool border = false;
    for(std::size_t r = 0; r < n; ++r)
      if(walk[r].face != invalid_index)
      {
        corner.push_back(static_cast<Index>(r));
        border = border || walk[r].opposite_on_border || walk[r + 1 < n ? r + 1 : 0].face == invalid_index;
      }
    sort_by_face(walk, corner);
    const std::size_t d = corner.size();
    if(col.size() < 2 * d + 1)
    {
      col.resize(2 * d + 1);
      val.resize(2 * d + 1);
    }
    if(d == 0 || (fixed != nullptr && fixed[i]))
    {
      col[0] = static_cast<Index>(i);
      val[0] = 1.;
      return 1;
    }
    if(border)
    {
      // the border neighbours in the index path's order: targets of corners whose edge has no
      // second face, then apexes of corners that are no corner's twin
      std::size_t length = 0;
      for(Index r : corner)
        if(walk[r].opposite_on_border)
          col[length++] = walk[r].target;
      for(Index r : corner)
      {
        const Step& after = walk[r + 1 < n ? r + 1 : 0];
        if(after.face == invalid_index)
          col[length++] = after.target;
      }
      Builder::border_weights(scheme, i, xyz, length, col.data(), val.data());
      return length;
    }
    for(std::size_t k = 0; k < d; ++k)
    {
      const Step& c = walk[corner[k]];
      col[k] = c.target;
      val[k] = scheme == Relaxation_scheme::UNIFORM ? 1. / double(d) : m_cotangent[c.halfedge] + m_cotangent[c.halfedge ^ 1];
    }
    if(scheme != Relaxation_scheme::UNIFORM)
      Builder::normalised_curvature_row(d, val.data());
    return d;
  }

  // Writes the outgoing halfedges of vertex v0 + j, j < g, in walks[j][0..count[j]) in the
  // order of the walk (each the opposite of the previous one's predecessor); false if a walk
  // does not come back (not a valid halfedge graph). The g walks advance together: each step
  // is a scattered read that depends on the one before, so one walk at a time waits on every
  // read in turn, where g walks overlap theirs (a relax() step on the dragon: about 10 % less
  // time, in one comparison on a noisy machine).
  bool walk_around(std::size_t v0, std::size_t g, std::vector<Step>* walks, std::size_t* count) const
  {
    const Mesh& m = m_mesh;
    Halfedge_index start[group], o[group];
    bool active[group];
    std::size_t walking = 0;
    for(std::size_t j = 0; j < g; ++j)
    {
      count[j] = 0;
      const Halfedge_index in = m.halfedge(Vertex_index(static_cast<typename Mesh::size_type>(v0 + j)));
      active[j] = in != Mesh::null_halfedge();
      if(active[j])
      {
        o[j] = start[j] = m.opposite(in);
        ++walking;
      }
    }
    while(walking > 0)
      for(std::size_t j = 0; j < g; ++j)
      {
        if(!active[j])
          continue;
        std::vector<Step>& walk = walks[j];
        if(count[j] == walk.size())
        {
          if(count[j] > m.number_of_halfedges())
            return false;
          walk.resize(2 * count[j] + 16);
        }
        const Face_index f = m.face(o[j]);
        walk[count[j]++] = Step{Index(o[j]), Index(m.target(o[j])), f == Mesh::null_face() ? invalid_index : Index(f),
                                m.is_border(m.opposite(o[j]))};
        o[j] = m.opposite(m.prev(o[j]));
        if(o[j] == start[j])
        {
          active[j] = false;
          --walking;
        }
      }
    return true;
  }

  // whether the walk's targets are distinct (else two edges join v to one neighbour, and the
  // index path may pair the corners around them otherwise); rings longer than 32 are sorted
  static bool distinct_targets(const Step* walk, std::size_t n, std::vector<Index>& scratch)
  {
    if(n <= 32)
    {
      // as many bits set as targets (their residues modulo 64): distinct without comparing pairs
      std::bitset<64> bits;
      for(std::size_t k = 0; k < n; ++k)
        bits.set(walk[k].target & 63);
      if(bits.count() == n)
        return true;
      for(std::size_t k = 1; k < n; ++k)
        for(std::size_t l = 0; l < k; ++l)
          if(walk[k].target == walk[l].target)
            return false;
      return true;
    }
    scratch.clear();
    for(std::size_t r = 0; r < n; ++r)
      scratch.push_back(walk[r].target);
    std::sort(scratch.begin(), scratch.end());
    return std::adjacent_find(scratch.begin(), scratch.end()) == scratch.end();
  }

  // the positions of the corners in the order of their faces, as the index path lists them
  // (insertion sort for short rings, else std::sort: D log D for a vertex of valence D)
  static void sort_by_face(const Step* walk, std::vector<Index>& corner)
  {
    const auto by_face = [walk](Index x, Index y) { return walk[x].face < walk[y].face; };
    if(corner.size() > 32)
    {
      std::sort(corner.begin(), corner.end(), by_face);
      return;
    }
    for(std::size_t k = 1; k < corner.size(); ++k)
    {
      const Index c = corner[k];
      std::size_t l = k;
      for(; l > 0 && by_face(c, corner[l - 1]); --l)
        corner[l] = corner[l - 1];
      corner[l] = c;
    }
  }

  const Mesh& m_mesh;
  Uninitialized_vector<double> m_cotangent;   // per halfedge index: the angle opposite it in its face
};

} // namespace internal
} // namespace Surface_mesh_multiresolution
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_MULTIRESOLUTION_INTERNAL_SURFACE_MESH_RELAXATION_ROWS_H
