// EditableFaces: adjacency kept by hand, and the rules a candidate edit is scored by.
#include "structured/editable_faces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "mesh/adjacency.h"
#include "query/find_self_intersections.h"

namespace hm::structured {
namespace {

// A boundary node may merge along the boundary only where it turns by less than this (degrees):
// elsewhere it is a corner of the hull's outline.
constexpr double kStraightDeg = 20;

}  // namespace

EditableFaces::EditableFaces(std::vector<Face>& faces, std::vector<Vec3d>& positions)
    : faces_(faces), positions_(positions), around_(positions.size()) {
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < corner_count(faces[f]); ++c)
      around_[faces[f][c]].insert(static_cast<Index>(f));
}

Index EditableFaces::across(Index f, Index a, Index b) const {
  for (Index g : around_[a]) {
    if (g == f || removed(g)) continue;
    const Face& h = faces_[g];
    const int n = corner_count(h);
    for (int c = 0; c < n; ++c) {
      const Index x = h[c], y = h[(c + 1) % n];
      if ((x == a && y == b) || (x == b && y == a)) return g;
    }
  }
  return kInvalid;
}

double EditableFaces::worst(const std::set<Index>& core) const {
  double w = 0;
  for (Index f : core) {
    if (removed(f)) continue;
    if (!(face_area(positions_, faces_[f]) > 0)) return std::numeric_limits<double>::infinity();
    double side = 0, area = 0;
    rules(f, side, area);
    w = std::max({w, side / kSideTarget, area / kAreaTarget});
  }
  return w;
}

EditableFaces::Score EditableFaces::score(const std::set<Index>& core,
                                          const std::set<Index>& judged) const {
  Score sc;
  sc.worst = worst(core);
  for (Index f : judged) {
    if (removed(f)) continue;
    double side = 0, area = 0;
    rules(f, side, area);
    sc.fails += side > kSideLimit || area > kAreaLimit;
  }
  return sc;
}

EditableFaces::Score EditableFaces::score(const std::set<Index>& core) const {
  std::set<Index> near = core;
  for (Index f : core) {
    if (removed(f)) continue;
    const Face& h = faces_[f];
    const int n = corner_count(h);
    for (int c = 0; c < n; ++c) {
      const Index g = across(f, h[c], h[(c + 1) % n]);
      if (g != kInvalid) near.insert(g);
    }
  }
  return score(core, near);
}

void EditableFaces::rules(Index f, double& side, double& area) const {
  const Face& h = faces_[f];
  side = is_triangle(h) ? 1 : side_ratio(positions_, h);
  area = 1;
  const double a = face_area(positions_, h);
  const int n = corner_count(h);
  for (int c = 0; c < n; ++c) {
    const Index g = across(f, h[c], h[(c + 1) % n]);
    if (g == kInvalid) continue;
    const double b = face_area(positions_, faces_[g]);
    area = std::max(area, std::min(a, b) > 0 ? std::max(a, b) / std::min(a, b)
                                             : std::numeric_limits<double>::infinity());
  }
}

bool EditableFaces::flat(const std::set<Index>& core) const {
  for (Index f : core)
    if (!removed(f) && flat_face(positions_, faces_[f])) return true;
  return false;
}

bool EditableFaces::manifold(const std::set<Index>& core) const {
  for (Index f : core) {
    if (removed(f)) continue;
    const Face& h = faces_[f];
    const int n = corner_count(h);
    // A merge that brings two opposite corners of a quad together folds it.
    for (int c = 0; c < n; ++c)
      for (int d = c + 1; d < n; ++d)
        if (h[c] == h[d]) return false;
    for (int c = 0; c < n; ++c) {
      const Index a = h[c], b = h[(c + 1) % n];
      int users = 0;
      for (Index g : around_[a]) {
        if (removed(g)) continue;
        const Face& k = faces_[g];
        const int m = corner_count(k);
        bool same_corners = g != f && m == n;
        for (int i = 0; i < m; ++i) {
          const Index x = k[i], y = k[(i + 1) % m];
          users += (x == a && y == b) || (x == b && y == a);
          same_corners = same_corners && std::find(h.begin(), h.begin() + n, x) != h.begin() + n;
        }
        if (same_corners) return false;
      }
      if (users > 2) return false;
    }
  }
  return true;
}

void EditableFaces::set_face(Index f, const Face& h) {
  const Face old = faces_[f];
  if (old[0] != kInvalid)
    for (int c = 0; c < corner_count(old); ++c) around_[old[c]].erase(f);
  faces_[f] = h;
  if (h[0] != kInvalid)
    for (int c = 0; c < corner_count(h); ++c) around_[h[c]].insert(f);
}

// Face h with vertex `from` renamed `to`, and a repeated corner dropped (a quad that loses a side
// becomes a triangle; one that loses two, or a triangle that loses one, is removed).
Face renamed(const Face& h, Index from, Index to) {
  Index c[4];
  int n = 0;
  for (int k = 0; k < corner_count(h); ++k) {
    const Index v = h[k] == from ? to : h[k];
    if (n > 0 && c[n - 1] == v) continue;
    c[n++] = v;
  }
  if (n > 1 && c[n - 1] == c[0]) --n;
  if (n == 4) return {c[0], c[1], c[2], c[3]};
  if (n == 3) return {c[0], c[1], c[2], kInvalid};
  return {kInvalid, kInvalid, kInvalid, kInvalid};
}

std::set<Index> EditableFaces::ring(const std::set<Index>& core) const {
  std::set<Index> out = core;
  for (Index g : core) {
    if (removed(g)) continue;
    const Face& h = face(g);
    for (int c = 0; c < corner_count(h); ++c) out.insert(around(h[c]).begin(), around(h[c]).end());
  }
  return out;
}

std::size_t EditableFaces::crossings(const std::set<Index>& core, const std::set<Index>& near,
                                     double tol) const {
  std::size_t n = 0;
  for (Index f : core) {
    if (removed(f)) continue;
    for (Index g : near) {
      // A pair within core once.
      if (g == f || removed(g) || (core.count(g) && g < f)) continue;
      if (faces_cross(positions_, faces_[f], faces_[g], tol)) ++n;
    }
  }
  return n;
}

void EditableFaces::merge_node(Index from, Index to) {
  // A copy: set_face changes around(from).
  const std::set<Index> faces_of(around(from).begin(), around(from).end());
  for (Index g : faces_of) set_face(g, renamed(face(g), from, to));
}

bool NodeFreedom::may_merge(Index i, Index b, std::span<const NodeSlot> slots) const {
  if (on_knuckle[i]) return false;
  if (movable[i]) return true;
  return i < slots.size() && slots[i].row != kInvalid && straight[i] &&
         boundary_edges.count({std::min(i, b), std::max(i, b)}) > 0;
}

NodeFreedom node_freedom(std::span<const NodeSlot> slots,
                         std::span<const std::array<Index, 2>> knuckle_edges,
                         const SurfaceMesh& mesh) {
  const std::size_t nv = mesh.vertex_count();
  NodeFreedom out;
  out.movable.assign(nv, 0);
  out.on_knuckle.assign(nv, 0);
  out.straight.assign(nv, 0);
  for (std::size_t v = 0; v < nv && v < slots.size(); ++v)
    out.movable[v] = !slots[v].fixed && slots[v].row != kInvalid;
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, nv);
  const double straight_cos = std::cos(kStraightDeg * std::numbers::pi / 180);
  for (const BoundaryLoop& l : adj.boundary_loops) {
    const std::size_t n = l.vertices.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Index a = l.vertices[(k + n - 1) % n], v = l.vertices[k], b = l.vertices[(k + 1) % n];
      out.movable[v] = 0;
      out.boundary_edges.insert({std::min(v, b), std::max(v, b)});
      const Vec3d da = mesh.positions[a] - mesh.positions[v];
      const Vec3d db = mesh.positions[b] - mesh.positions[v];
      const double c = dot(da, db) / std::max(norm(da) * norm(db), 1e-300);
      out.straight[v] = c < -straight_cos;
    }
  }
  for (const auto& e : knuckle_edges) {
    out.movable[e[0]] = out.movable[e[1]] = 0;
    out.on_knuckle[e[0]] = out.on_knuckle[e[1]] = 1;
  }
  return out;
}

void drop_removed_faces(SurfaceMesh& mesh) {
  std::size_t kept = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (mesh.faces[f][0] == kInvalid) continue;
    mesh.faces[kept] = mesh.faces[f];
    mesh.face_block[kept] = mesh.face_block[f];
    ++kept;
  }
  mesh.faces.resize(kept);
  mesh.face_block.resize(kept);
}

}  // namespace hm::structured
