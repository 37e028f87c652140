// Copyright (c) 2026  Hex_meshing_3 project authors.
// SPDX-License-Identifier: GPL-3.0-or-later
// Author(s)     : Hex_meshing_3 developers
#ifndef CGAL_HEX_MESHING_3_POLYHEDRAL_MESH_3_H
#define CGAL_HEX_MESHING_3_POLYHEDRAL_MESH_3_H

// The face-based (OpenFOAM polyMesh) view of a non-conformal hexahedral mesh. Each hexahedron
// becomes a polyhedral cell: a hex face whose centre is a hanging node (finer cells beyond it) is
// split into the four quarters facing them (1:4); a face with hanging midpoints on two opposite
// edges whose two halves between those midpoints are each a face of another cell or a boundary face
// (two cells side by side beyond it, as in a buffer layer over a boundary) is split into these
// halves (1:2); any other face lists all the vertices lying on its edges (hanging nodes on edges
// included), and so does each piece of a split face. Faces are numbered as OpenFOAM requires:
// internal faces first in upper-triangular order (sorted by owner, then neighbour, owner <
// neighbour, normal from owner to neighbour), then boundary faces grouped by patch.

#include <CGAL/Hex_meshing_3/Hex_mesh_3.h>
#include <CGAL/Hex_meshing_3/internal/vertex_cells.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hex_meshing_3 {

/*!
 * \ingroup PkgHexMeshing3Mesh
 * \brief polygons stored one after the other (compressed rows): `faces[i]` is a read-only range
 * of the vertex indices of polygon `i` (`begin()`, `end()`, `size()`, `operator[]`). A vector
 * per polygon would take three times the memory on large meshes.
 */
class Polygon_list
{
public:
  typedef std::uint32_t Index;
  struct Polygon
  {
    const Index* first;
    const Index* last;
    const Index* begin() const { return first; }
    const Index* end() const { return last; }
    std::size_t size() const { return std::size_t(last - first); }
    bool empty() const { return first == last; }
    Index operator[](std::size_t k) const { return first[k]; }
  };
  struct const_iterator
  {
    typedef std::forward_iterator_tag iterator_category;
    typedef Polygon value_type;
    typedef std::ptrdiff_t difference_type;
    typedef const Polygon* pointer;
    typedef Polygon reference;
    const Polygon_list* list;
    std::size_t i;
    Polygon operator*() const { return (*list)[i]; }
    const_iterator& operator++() { ++i; return *this; }
    bool operator!=(const const_iterator& o) const { return i != o.i; }
    bool operator==(const const_iterator& o) const { return i == o.i; }
  };

  std::size_t size() const { return start_.empty() ? 0 : start_.size() - 1; }   // (empty once moved from)
  bool empty() const { return size() == 0; }
  Polygon operator[](std::size_t i) const
  { return {vertices_.data() + start_[i], vertices_.data() + start_[i + 1]}; }
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size()}; }
  void clear() { vertices_.clear(); start_.assign(1, 0); }
  /// appends the polygon with the vertices in [b, e)
  template <typename Iterator>
  void push_back(Iterator b, Iterator e)
  {
    if(start_.empty()) start_.push_back(0);
    vertices_.insert(vertices_.end(), b, e);
    start_.push_back(vertices_.size());
  }
  void reserve(std::size_t polygons, std::size_t vertices) { start_.reserve(polygons + 1); vertices_.reserve(vertices); }
  void shrink_to_fit() { start_.shrink_to_fit(); vertices_.shrink_to_fit(); }
  void swap(Polygon_list& o) { vertices_.swap(o.vertices_); start_.swap(o.start_); }
  bool operator==(const Polygon_list& o) const { return start_ == o.start_ && vertices_ == o.vertices_; }
  bool operator!=(const Polygon_list& o) const { return !(*this == o); }

private:
  std::vector<Index> vertices_;
  std::vector<std::size_t> start_{0};
};

/*!
 * \ingroup PkgHexMeshing3Mesh
 * \brief the polyhedral (face-based) form of a `Hex_mesh_3`, as OpenFOAM stores meshes.
 */
struct Polyhedral_mesh_3
{
  typedef std::uint32_t Index;
  struct Patch { std::string name; std::size_t start = 0, size = 0; };

  Polygon_list faces;                      ///< internal faces, then boundary faces by patch
  std::vector<Index> owner;                ///< one per face
  std::vector<Index> neighbour;            ///< one per internal face
  std::vector<Patch> patches;              ///< as in the `Hex_mesh_3`, with their face ranges
  std::size_t number_of_cells = 0;

  std::size_t number_of_internal_faces() const { return neighbour.size(); }

  /*!
   * builds the faces of `mesh`.
   * \throws std::logic_error if a face (or a quarter or half of a split face) is found neither
   *         twice (internal) nor among the mesh's boundary faces: the mesh is inconsistent.
   */
  template <typename HexMesh>
  void build(const HexMesh& mesh)
  {
    faces.clear(); owner.clear(); neighbour.clear(); patches.clear();
    number_of_cells = mesh.hexahedra.size();
    typedef std::array<Index, 4> Key;
    auto sorted = [](std::array<Index, 4> k) { std::sort(k.begin(), k.end()); return k; };
    auto pair_key = [](Index a, Index b) {
      return a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
    };
    std::unordered_map<std::uint64_t, Index> edge_mid;
    std::unordered_map<std::uint64_t, std::vector<std::pair<Key, Index>>> face_centre;  // by 2 smallest
    // whether a vertex is a master of an edge (bit 1) or face (bit 2) hanging node: most are
    // neither, and their faces need no lookup
    std::vector<std::uint8_t> master(mesh.points.size(), 0);
    for(const auto& h : mesh.hanging_nodes) {
      if(h.number_of_masters == 2) {
        edge_mid[pair_key(h.masters[0], h.masters[1])] = h.vertex;
        master[h.masters[0]] |= 1; master[h.masters[1]] |= 1;
      } else {
        const Key k = sorted(h.masters);
        face_centre[pair_key(k[0], k[1])].push_back({k, h.vertex});
        for(Index v : k) master[v] |= 2;
      }
    }
    auto centre_of = [&](const Key& k, Index& c) {
      if(!(master[k[0]] & master[k[1]] & master[k[2]] & master[k[3]] & 2)) return false;
      auto it = face_centre.find(pair_key(k[0], k[1]));
      if(it == face_centre.end()) return false;
      for(const auto& e : it->second) if(e.first == k) { c = e.second; return true; }
      return false;
    };
    auto mid_of = [&](Index a, Index b, Index& m) {
      if(!(master[a] & master[b] & 1)) return false;
      auto it = edge_mid.find(pair_key(a, b));
      if(it == edge_mid.end()) return false;
      m = it->second; return true;
    };

    const auto& lf = hex_local_faces();
    // boundary faces of the hex mesh, by key
    std::vector<std::pair<Key, int>> bkeys;
    bkeys.reserve(mesh.boundary_faces.size());
    for(const auto& bf : mesh.boundary_faces) bkeys.push_back({sorted(bf.vertices), bf.patch});
    std::sort(bkeys.begin(), bkeys.end());
    // a half of a coarse face is a 1:2 split only if some other cell (or the boundary) has it as
    // a whole face. Midpoints on two opposite edges alone do not tell: octrees often have them on
    // a coarse face whose neighbour is just as coarse. The other cell has the half's corners: it
    // is among the cells at its first corner (without edge midpoints there is no such split, and
    // no need for this index)
    std::vector<Index> vstart, vcells;
    if(!edge_mid.empty()) internal::vertex_cells(mesh, mesh.points.size(), vstart, vcells);
    auto is_face_beyond = [&](const Key& k, Index c) {
      for(Index i = vstart[k[0]]; i < vstart[k[0] + 1]; ++i) {
        const Index c2 = vcells[i];
        if(c2 == c) continue;
        const auto& h = mesh.hexahedra[c2];
        for(const auto& f : lf) if(sorted({{h[f[0]], h[f[1]], h[f[2]], h[f[3]]}}) == k) return true;
      }
      auto b = std::lower_bound(bkeys.begin(), bkeys.end(), std::make_pair(k, -1));
      return b != bkeys.end() && b->first == k;
    };

    // Each polygon is an item: its sorted corners (the key), its cell and how to make its vertex
    // list again (`code`: the cell's local face x 16 + the part: 0 the whole face, 1-4 a quarter
    // of a face split in four, 5-8 a half of a 1:2 split), not the list itself (the lists of
    // every cell's faces, 52 MB on motorBike, were a part of the capture's memory peak)
    struct Item { Key key; Index cell; std::uint8_t code; };
    std::vector<Item> items;
    // 3 more per face split in four (its centre a hanging node), 1 more per 1:2 split, which
    // takes two edge midpoints, each on the faces of at most 3 coarse cells (reserved so: a
    // reallocation would double them; exceeding the bound only costs that)
    std::size_t n4 = 0;
    for(const auto& h : mesh.hanging_nodes) if(h.number_of_masters != 2) ++n4;
    const std::size_t npoly = 6 * mesh.hexahedra.size() + 3 * n4 + 3 * (mesh.hanging_nodes.size() - n4);
    items.reserve(npoly);
    // the four quarters of a face split in four at its centre `ctr`, `m` its edge midpoints
    auto quarters = [](const Index* q, const Index* m, Index ctr) {
      return std::array<std::array<Index, 4>, 4>{{{{q[0], m[0], ctr, m[3]}}, {{m[0], q[1], m[1], ctr}},
                                                   {{ctr, m[1], q[2], m[2]}}, {{m[3], ctr, m[2], q[3]}}}};
    };
    // the halves of a 1:2 split across the midpoints a, b of edges (p0,p1) and (p2,p3), p the face
    // rotated by r; both keep the face's orientation
    auto halves = [](const Index* p, Index a, Index b) {
      return std::array<std::array<Index, 4>, 2>{{{{p[0], a, b, p[3]}}, {{a, p[1], p[2], b}}}};
    };
    // the vertex list of an item's polygon: a quad with, after each corner, the hanging midpoint
    // of the edge it starts (if any); a quarter as it is
    auto polygon_of = [&](Index c, std::uint8_t code, std::vector<Index>& out) {
      out.clear();
      const auto& h = mesh.hexahedra[c];
      const auto& f = lf[code >> 4];
      const int part = code & 15;
      const Index q[4] = {h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
      auto with_midpoints = [&](const std::array<Index, 4>& x) {
        for(int i = 0; i < 4; ++i) {
          out.push_back(x[std::size_t(i)]);
          Index m;
          if(mid_of(x[std::size_t(i)], x[std::size_t((i + 1) % 4)], m)) out.push_back(m);
        }
      };
      if(part == 0) { with_midpoints({{q[0], q[1], q[2], q[3]}}); return; }
      if(part <= 4) {
        Index ctr = 0, m[4] = {0, 0, 0, 0};
        centre_of(sorted({{q[0], q[1], q[2], q[3]}}), ctr);
        for(int i = 0; i < 4; ++i) mid_of(q[i], q[(i + 1) % 4], m[i]);
        const auto s4 = quarters(q, m, ctr)[std::size_t(part - 1)];
        out.insert(out.end(), s4.begin(), s4.end());
        return;
      }
      const int r = (part - 5) / 2;
      const Index p[4] = {q[r], q[r + 1], q[r + 2], q[(r + 3) % 4]};
      Index a = 0, b = 0;
      mid_of(p[0], p[1], a);
      mid_of(p[2], p[3], b);
      with_midpoints(halves(p, a, b)[std::size_t((part - 5) % 2)]);
    };
    for(Index c = 0; c < mesh.hexahedra.size(); ++c) {
      const auto& h = mesh.hexahedra[c];
      for(std::size_t fi = 0; fi < lf.size(); ++fi) {
        const auto& f = lf[fi];
        const std::uint8_t face_code = std::uint8_t(fi << 4);
        const Index q[4] = {h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
        Index ctr;
        if(centre_of(sorted({{q[0], q[1], q[2], q[3]}}), ctr)) {
          Index m[4];
          for(int i = 0; i < 4; ++i)
            if(!mid_of(q[i], q[(i + 1) % 4], m[i]))
              throw std::logic_error("Polyhedral_mesh_3: a split face lacks an edge midpoint");
          const auto sub = quarters(q, m, ctr);
          for(int i = 0; i < 4; ++i) items.push_back({sorted(sub[std::size_t(i)]), c, std::uint8_t(face_code | (1 + i))});
          continue;
        }
        // 1:2 split across the midpoints of edges (p0,p1) and (p2,p3), p the face rotated by r
        bool split = false;
        for(int r = 0; r < 2 && !split; ++r) {
          const Index p[4] = {q[r], q[r + 1], q[r + 2], q[(r + 3) % 4]};
          Index a, b;
          if(!mid_of(p[0], p[1], a) || !mid_of(p[2], p[3], b)) continue;
          const auto hv = halves(p, a, b);
          if(is_face_beyond(sorted(hv[0]), c) && is_face_beyond(sorted(hv[1]), c)) {
            items.push_back({sorted(hv[0]), c, std::uint8_t(face_code | (5 + 2 * r))});
            items.push_back({sorted(hv[1]), c, std::uint8_t(face_code | (6 + 2 * r))});
            split = true;
          }
        }
        if(!split) items.push_back({sorted({{q[0], q[1], q[2], q[3]}}), c, face_code});
      }
    }
    std::vector<Index>().swap(vstart);
    std::vector<Index>().swap(vcells);
    std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
      return a.key != b.key ? a.key < b.key : a.cell < b.cell; });

    // a face: its owner, its neighbour (internal faces), whose polygon it takes (`src`, `code`),
    // reversed (all but its first vertex) or not, and its number of vertices
    struct Internal { Index own, nei, src; std::uint8_t code, reversed, size; };
    struct Boundary { int patch; Index own; std::uint8_t code, size; };
    std::vector<Internal> internal;
    std::vector<Boundary> boundary;
    std::vector<Index> pa, pb;
    for(std::size_t i = 0; i < items.size();) {
      std::size_t j = i + 1;
      while(j < items.size() && items[j].key == items[i].key) ++j;
      if(j - i == 2) {
        const Item& a = items[i];
        const Item& b = items[i + 1];
        // the owner's polygon, unless the neighbour's lists more vertices (then reversed)
        polygon_of(a.cell, a.code, pa);
        polygon_of(b.cell, b.code, pb);
        if(pb.size() > pa.size()) internal.push_back({a.cell, b.cell, b.cell, b.code, 1, std::uint8_t(pb.size())});
        else internal.push_back({a.cell, b.cell, a.cell, a.code, 0, std::uint8_t(pa.size())});
      } else if(j - i == 1) {
        auto it = std::lower_bound(bkeys.begin(), bkeys.end(), std::make_pair(items[i].key, -1));
        if(it == bkeys.end() || it->first != items[i].key)
          throw std::logic_error("Polyhedral_mesh_3: a face bounds one cell but is not a boundary face (cell " +
                                 std::to_string(items[i].cell) + ", vertices " + std::to_string(items[i].key[0]) + " " +
                                 std::to_string(items[i].key[1]) + " " + std::to_string(items[i].key[2]) + " " +
                                 std::to_string(items[i].key[3]) + ")");
        polygon_of(items[i].cell, items[i].code, pa);
        boundary.push_back({it->second, items[i].cell, items[i].code, std::uint8_t(pa.size())});
      } else
        throw std::logic_error("Polyhedral_mesh_3: a face is shared by more than two cells");
      i = j;
    }
    std::sort(internal.begin(), internal.end(), [](const Internal& a, const Internal& b) {
      return a.own != b.own ? a.own < b.own : a.nei < b.nei; });
    std::stable_sort(boundary.begin(), boundary.end(), [](const Boundary& a, const Boundary& b) {
      return a.patch != b.patch ? a.patch < b.patch : a.own < b.own; });

    std::vector<Item>().swap(items);
    auto add_face = [&](Index src, std::uint8_t code, bool reversed) {
      polygon_of(src, code, pa);
      if(reversed) std::reverse(pa.begin() + 1, pa.end());
      faces.push_back(pa.begin(), pa.end());
    };
    std::size_t nv = 0;
    for(const Internal& f : internal) nv += f.size;
    for(const Boundary& f : boundary) nv += f.size;
    faces.reserve(internal.size() + boundary.size(), nv);
    owner.reserve(internal.size() + boundary.size());
    neighbour.reserve(internal.size());
    for(const Internal& f : internal) {
      add_face(f.src, f.code, f.reversed != 0); owner.push_back(f.own); neighbour.push_back(f.nei);
    }
    patches.resize(mesh.patch_names.size());
    for(std::size_t p = 0; p < patches.size(); ++p) patches[p].name = mesh.patch_names[p];
    std::size_t k = 0;
    for(std::size_t p = 0; p < patches.size(); ++p) {
      patches[p].start = faces.size();
      while(k < boundary.size() && boundary[k].patch == int(p)) {
        add_face(boundary[k].own, boundary[k].code, false); owner.push_back(boundary[k].own); ++k;
      }
      patches[p].size = faces.size() - patches[p].start;
    }
    if(k != boundary.size()) throw std::logic_error("Polyhedral_mesh_3: a boundary face has an unknown patch");
  }
};

} // namespace Hex_meshing_3
} // namespace CGAL

#endif
