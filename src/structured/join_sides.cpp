// A heeled hull's two sides, meshed apart, joined along the centre plane: collect the seam (open
// edges in the plane, each side's) -> weld nodes that meet -> insert the rest into the other
// side's edges -> split the panels that gained nodes -> drop panels back to back -> fill small
// holes left in the plane -> drop the welded nodes.
//
// Frame: the one both sides were meshed in, the centre plane y = 0; metres.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "mesh/adjacency.h"
#include "structured/structured.h"
#include "structured/structured_steps.h"

namespace hm {
namespace {

// A node of one side welds to one of the other within this share of the shorter seam edge at
// either: beyond it, it goes into the other side's edge.
constexpr double kWeldShare = 0.25;
// A node goes into an edge of the other side it lies within this share of that edge's length
// of (the chord of a curved stem or keel lies off the nodes of a finer side by its sag).
constexpr double kInsertReach = 0.25;

struct Seam {
  std::vector<std::array<Index, 2>> edges;  // open edges in the plane, as their face runs them
  std::vector<Index> faces;                 // the face of each
  std::vector<Index> nodes;                 // their ends, ascending
  std::vector<Index> corners;               // of them, those on the waterline
  std::map<Index, double> shortest;         // node -> shortest seam edge at it, m
  std::map<Index, double> longest;          // node -> longest seam edge at it, m
  std::map<Index, Vec3d> along;             // node -> the way its seam edges run (summed units)
  std::map<Index, Index> next;              // node -> the node its seam edge runs to
};

Seam collect_seam(const SurfaceMesh& m, const EdgeAdjacency& adj, Index v_begin, Index v_end,
                  const SeamPlanes& planes) {
  Seam s;
  auto in_plane = [&](Index v) { return std::abs(m.positions[v].y) <= planes.centre_tol; };
  // Where the centre plane and the waterline meet at a small angle (a flat run aft), the last
  // waterline edges lie within the plane's tolerance too; they are no seam.
  auto on_waterline = [&](Index v) {
    return std::abs(dot(planes.up, m.positions[v]) - planes.waterline) <= planes.waterline_tol;
  };
  for (Index e : adj.boundary_edges) {
    const Index slot = adj.edges[e].first_slot;
    const Face& f = m.faces[slot / 4];
    const Index a = f[slot % 4], b = f[(slot % 4 + 1) % corner_count(f)];
    if (a < v_begin || a >= v_end || !in_plane(a) || !in_plane(b)) continue;
    if (on_waterline(a) && on_waterline(b)) continue;
    s.edges.push_back({a, b});
    s.next[a] = b;
    s.faces.push_back(slot / 4);
    const double len = norm(m.positions[b] - m.positions[a]);
    if (len > 0) {
      const Vec3d unit = (m.positions[b] - m.positions[a]) / len;
      for (Index v : {a, b}) s.along[v] = s.along[v] + unit;
    }
    for (Index v : {a, b}) {
      auto [it, fresh] = s.shortest.emplace(v, len);
      if (!fresh) it->second = std::min(it->second, len);
      auto [jt, first] = s.longest.emplace(v, len);
      if (!first) jt->second = std::max(jt->second, len);
    }
  }
  for (const auto& [v, len] : s.shortest) {
    s.nodes.push_back(v);
    if (on_waterline(v)) s.corners.push_back(v);
  }
  return s;
}

// The nearest of `nodes` to p, and its distance.
std::pair<Index, double> nearest_node(const SurfaceMesh& m, std::span<const Index> nodes,
                                      const Vec3d& p) {
  Index best = kInvalid;
  double d = std::numeric_limits<double>::infinity();
  for (Index v : nodes) {
    const double dv = norm(m.positions[v] - p);
    if (dv < d) {
      d = dv;
      best = v;
    }
  }
  return {best, d};
}

using structured::min_angle;

// A quad's smallest corner angle, radians.
double min_angle(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return std::min(min_angle(a, b, c), min_angle(c, d, a));
}

// The polygon (face corners with nodes inserted into its sides) as faces. A quad whose nodes all
// lie on one side keeps a quad: triangles fan from the far side's ends to the inserted nodes,
// with the quad between, where its smallest angle is largest. Otherwise ears are cut, each time
// the ear whose smallest angle is largest among those turning the face's way.
std::vector<Face> split_polygon(std::span<const Vec3d> pos, const std::vector<Index>& poly,
                                const Face& original, std::size_t split_sides) {
  std::vector<Face> out;
  const std::size_t n = poly.size();
  if (!is_triangle(original) && split_sides == 1) {
    // poly = a, m1..mk, b, c, d with the nodes m on side a-b (rotate it so).
    std::size_t start = 0;
    while (start < n) {
      const Index v = poly[start], next = poly[(start + 1) % n];
      const bool corner =
          std::find(original.begin(), original.begin() + 4, v) != original.begin() + 4;
      const bool next_corner =
          std::find(original.begin(), original.begin() + 4, next) != original.begin() + 4;
      if (corner && !next_corner) break;
      ++start;
    }
    std::vector<Index> r(n);
    for (std::size_t i = 0; i < n; ++i) r[i] = poly[(start + i) % n];
    const std::size_t k = n - 4;  // inserted nodes
    const Index c = r[k + 2], d = r[k + 3];
    // chain[0..k+1] = a, m1..mk, b; d fans chain[0..j], the quad is chain[j], chain[j+1], c, d,
    // and c fans chain[j+1..k+1].
    double best = -1;
    std::size_t best_j = 0;
    for (std::size_t j = 0; j <= k; ++j) {
      double q = min_angle(pos[r[j]], pos[r[j + 1]], pos[c], pos[d]);
      for (std::size_t i = 0; i < j; ++i)
        q = std::min(q, min_angle(pos[r[i]], pos[r[i + 1]], pos[d]));
      for (std::size_t i = j + 1; i <= k; ++i)
        q = std::min(q, min_angle(pos[r[i]], pos[r[i + 1]], pos[c]));
      if (q > best) {
        best = q;
        best_j = j;
      }
    }
    for (std::size_t i = 0; i < best_j; ++i) out.push_back({r[i], r[i + 1], d, kInvalid});
    out.push_back({r[best_j], r[best_j + 1], c, d});
    for (std::size_t i = best_j + 1; i <= k; ++i) out.push_back({r[i], r[i + 1], c, kInvalid});
    return out;
  }
  // Ears. The face's way round: Newell's normal of the polygon.
  Vec3d normal{0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) normal = normal + cross(pos[poly[i]], pos[poly[(i + 1) % n]]);
  std::vector<Index> left = poly;
  while (left.size() > 3) {
    const std::size_t m = left.size();
    double best = -1;
    std::size_t best_i = 0;
    for (std::size_t i = 0; i < m; ++i) {
      const Vec3d& a = pos[left[(i + m - 1) % m]];
      const Vec3d& b = pos[left[i]];
      const Vec3d& c = pos[left[(i + 1) % m]];
      if (!(dot(cross(b - a, c - b), normal) > 0)) continue;
      double q = min_angle(a, b, c);
      // With four corners left the ear decides the last triangle too: a node put into a
      // triangle's side lies on a line with that side's ends, and the ear beside it would leave
      // a triangle of no area (ship_449_patches at 8.5 m heeled 5 degrees). Such an ear comes
      // after every other (before none turning the face's way). Otherwise the ear is judged by
      // the smaller angle of both triangles: a node 6 micrometres off the side it went into
      // left a needle of 8.9e-9 m^2 beside the face it came from (kcs.iges at 0.34 m heeled 5
      // degrees: a neighbour area ratio of 95,900).
      const Face last{left[(i + m - 1) % m], left[(i + 1) % m], left[(i + 2) % m], kInvalid};
      if (m == 4) {
        q = structured::flat_face(pos, last)
                ? -0.5 + 0.1 * q
                : std::min(q, min_angle(pos[last[0]], pos[last[1]], pos[last[2]]));
      }
      if (q > best) {
        best = q;
        best_i = i;
      }
    }
    out.push_back({left[(best_i + m - 1) % m], left[best_i], left[(best_i + 1) % m], kInvalid});
    left.erase(left.begin() + static_cast<std::ptrdiff_t>(best_i));
  }
  out.push_back({left[0], left[1], left[2], kInvalid});
  return out;
}

// Panels on the same corners, one of each side (a cap panel each side left lying in the centre
// plane, as an upright half drops it): the two are no hull, and their common sides would have
// four faces. Both go, and their blocks' counts with them. Returns how many pairs.
std::size_t drop_back_to_back(StructuredMesh& out) {
  SurfaceMesh& m = out.mesh;
  std::map<std::array<Index, 4>, Index> seen;  // sorted corners -> first face
  std::vector<std::uint8_t> keep(m.faces.size(), 1);
  std::size_t pairs = 0;
  for (Index f = 0; f < m.faces.size(); ++f) {
    std::array<Index, 4> key = m.faces[f];
    std::sort(key.begin(), key.end());
    auto [it, fresh] = seen.emplace(key, f);
    if (fresh || !keep[it->second]) continue;
    for (Index g : {it->second, f}) {
      keep[g] = 0;
      BlockReport& b = out.report.blocks[m.face_block[g]];
      --(is_triangle(m.faces[g]) ? b.triangles : b.quads);
    }
    ++pairs;
  }
  keep_faces(m, keep);
  return pairs;
}

// Holes the seam left in the plane: where the profile turns a corner (a skeg's trailing edge)
// one side's seam may cut across it and the other's follow it, farther than kInsertReach. A
// boundary loop of at most kSeamHoleNodes nodes, all in the plane, is filled by ears, its faces
// wound against the panels beside it. Returns how many.
constexpr std::size_t kSeamHoleNodes = 12;

std::size_t fill_seam_holes(StructuredMesh& out, double centre_tol) {
  SurfaceMesh& m = out.mesh;
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  std::size_t filled = 0;
  for (const BoundaryLoop& loop : adj.boundary_loops) {
    const std::size_t n = loop.vertices.size();
    if (!loop.closed || n < 3 || n > kSeamHoleNodes) continue;
    if (!std::all_of(loop.vertices.begin(), loop.vertices.end(),
                     [&](Index v) { return std::abs(m.positions[v].y) <= centre_tol; }))
      continue;
    // The face along the first side runs it one way; the hole's faces run it the other.
    const Index slot = adj.edges[loop.edges[0]].first_slot;
    const Index f = slot / 4;
    std::vector<Index> poly(loop.vertices.begin(), loop.vertices.end());
    if (m.faces[f][slot % 4] == poly[0]) std::reverse(poly.begin(), poly.end());
    const Face none{kInvalid, kInvalid, kInvalid, kInvalid};
    for (const Face& piece : split_polygon(m.positions, poly, none, 0)) {
      m.faces.push_back(piece);
      m.face_patch.push_back(m.face_patch[f]);
      m.face_block.push_back(m.face_block[f]);
      ++out.report.blocks[m.face_block[f]].triangles;
    }
    ++filled;
  }
  return filled;
}

// Sums starboard's report into port's; starboard's blocks follow port's, named by side.
void join_reports(StructuredReport& port, const StructuredReport& stbd) {
  const Index first = static_cast<Index>(port.blocks.size());
  for (BlockReport& b : port.blocks) b.lower = "port: " + b.lower;
  for (BlockReport b : stbd.blocks) {
    b.id += first;
    b.lower = "starboard: " + b.lower;
    port.blocks.push_back(std::move(b));
  }
  port.stations = std::max(port.stations, stbd.stations);
  port.cut_stations = std::max(port.cut_stations, stbd.cut_stations);
  port.cap_triangles += stbd.cap_triangles;
  port.cap_quads += stbd.cap_quads;
  port.transoms += stbd.transoms;
  port.rows_joined += stbd.rows_joined;
  port.curve_caps += stbd.curve_caps;
  port.border_gaps += stbd.border_gaps;
  port.split_twisted += stbd.split_twisted;
  port.rows_unmatched += stbd.rows_unmatched;
  port.quality_moves += stbd.quality_moves;
  port.edge_snaps += stbd.edge_snaps;
  port.border_distorted += stbd.border_distorted;
  port.border_removed += stbd.border_removed;
  port.border_extended += stbd.border_extended;
  port.border_split += stbd.border_split;
  port.nodes_welded += stbd.nodes_welded;
  port.wedges_collapsed += stbd.wedges_collapsed;
  port.non_convex_split += stbd.non_convex_split;
  port.folds_flipped += stbd.folds_flipped;
  port.triangles_paired += stbd.triangles_paired;
  port.size_passes = std::max(port.size_passes, stbd.size_passes);
  port.first_pass_faces += stbd.first_pass_faces;
  port.seconds_plan += stbd.seconds_plan;
  port.seconds_rows += stbd.seconds_rows;
  port.seconds_grow += stbd.seconds_grow;
  port.seconds_relax += stbd.seconds_relax;
}

// Starboard's vertices, faces, blocks and knuckle edges appended to port's.
void append_side(StructuredMesh& out, const StructuredMesh& starboard) {
  SurfaceMesh& m = out.mesh;
  const SurfaceMesh& s = starboard.mesh;
  const Index nv = static_cast<Index>(m.vertex_count());
  const Index nb = static_cast<Index>(out.report.blocks.size());
  m.positions.insert(m.positions.end(), s.positions.begin(), s.positions.end());
  m.vertex_patch.insert(m.vertex_patch.end(), s.vertex_patch.begin(), s.vertex_patch.end());
  m.vertex_uv.insert(m.vertex_uv.end(), s.vertex_uv.begin(), s.vertex_uv.end());
  for (Face f : s.faces) {
    for (int c = 0; c < corner_count(f); ++c) f[c] += nv;
    m.faces.push_back(f);
  }
  m.face_patch.insert(m.face_patch.end(), s.face_patch.begin(), s.face_patch.end());
  for (Index b : s.face_block) m.face_block.push_back(b == kInvalid ? b : b + nb);
  for (const auto& e : starboard.knuckle_edges) out.knuckle_edges.push_back({e[0] + nv, e[1] + nv});
  join_reports(out.report, starboard.report);
}

// Starboard nodes welded to port's (vert_to), mutual nearest pairs within reach. The seams' ends
// on the waterline first, within the longer seam edge at either: where the waterline meets the
// plane at a small angle (a keel rising through it aft), each side may end its seam a little
// way along the line the two share, and nothing else joins the two ends. Then every node,
// within kWeldShare of the shorter seam edge at either. placed: 1 for both nodes of a pair.
std::size_t weld_seams(const SurfaceMesh& m, const Seam (&seam)[2], std::vector<Index>& vert_to,
                       std::vector<std::uint8_t>& placed) {
  std::size_t welded = 0;
  auto weld = [&](std::span<const Index> port_nodes, std::span<const Index> stbd_nodes, bool ends) {
    for (Index v : stbd_nodes) {
      if (placed[v]) continue;
      const auto [p, d] = nearest_node(m, port_nodes, m.positions[v]);
      if (p == kInvalid || placed[p]) continue;
      if (nearest_node(m, stbd_nodes, m.positions[p]).first != v) continue;
      const double reach =
          ends ? std::max(seam[1].longest.at(v), seam[0].longest.at(p))
               : kWeldShare * std::min(seam[1].shortest.at(v), seam[0].shortest.at(p));
      if (!(d <= reach)) continue;
      vert_to[v] = p;
      placed[v] = placed[p] = 1;
      ++welded;
    }
  };
  weld(seam[0].corners, seam[1].corners, true);
  weld(seam[0].nodes, seam[1].nodes, false);
  return welded;
}

// Seam edge (as its face runs it) -> the other side's nodes that go into it, ascending along it.
using Inserts = std::map<std::pair<Index, Index>, std::vector<std::pair<double, Index>>>;

// Every seam node not welded into the edge of the other side it lies on. Not a seam's end on
// the waterline: where the seam doubles back along the waterline (a keel rising through it at a
// small angle) the other side's edge there runs the other way, and a panel split at it would
// run its side the same way as the panel across it. What such an end leaves open in the plane,
// the hole fill closes. nv: port's vertex count.
Inserts plan_inserts(const SurfaceMesh& m, const Seam (&seam)[2],
                     std::span<const std::uint8_t> placed, Index nv) {
  Inserts inserts;
  for (int side = 0; side < 2; ++side) {
    const Seam& other = seam[1 - side];
    for (Index v : seam[side].nodes) {
      if (placed[v]) continue;
      if (std::binary_search(seam[side].corners.begin(), seam[side].corners.end(), v)) continue;
      const Vec3d& q = m.positions[v];
      double best = std::numeric_limits<double>::infinity(), best_t = 0;
      std::size_t best_e = other.edges.size();
      for (std::size_t e = 0; e < other.edges.size(); ++e) {
        const Vec3d& a = m.positions[other.edges[e][0]];
        const Vec3d d = m.positions[other.edges[e][1]] - a;
        const double dd = squared_norm(d);
        if (!(dd > 0)) continue;
        const double t = dot(q - a, d) / dd;
        if (!(t > 0 && t < 1)) continue;
        // The two sides run their common seam opposite ways: an edge running the node's own way
        // is the other leg of a seam that doubles back (a skeg's trailing edge).
        auto way = seam[side].along.find(v);
        if (way != seam[side].along.end() && !(dot(way->second, d) < 0)) continue;
        const double dist = norm(a + d * t - q);
        if (dist <= kInsertReach * std::sqrt(dd) && dist < best) {
          best = dist;
          best_t = t;
          best_e = e;
        }
      }
      if (best_e == other.edges.size()) continue;  // beyond the other's seam: a true border
      inserts[{other.edges[best_e][0], other.edges[best_e][1]}].push_back({best_t, v});
    }
  }
  // Nodes put into one edge must follow each other along their own seam, which runs the edge
  // the other way: where that seam folds on itself (a few millimetres at kcs's propeller
  // aperture) they do not, and the split panels would run their sides the same way as the
  // panels across them. Such an edge takes none; the hole fill closes what stays open.
  for (auto it = inserts.begin(); it != inserts.end();) {
    std::vector<std::pair<double, Index>>& along = it->second;
    std::sort(along.begin(), along.end());
    const Seam& own = seam[along.front().second < nv ? 0 : 1];
    bool follow = true;
    for (std::size_t i = 0; i + 1 < along.size(); ++i) {
      auto n = own.next.find(along[i + 1].second);
      follow = follow && n != own.next.end() && n->second == along[i].second;
    }
    it = follow ? std::next(it) : inserts.erase(it);
  }
  return inserts;
}

// Each face with inserted nodes on its sides becomes the faces of its polygon (split_polygon);
// the first piece takes its slot, the others go at the end with its patch and block.
void split_at_inserts(StructuredMesh& out, const Seam (&seam)[2], const Inserts& inserts) {
  SurfaceMesh& m = out.mesh;
  std::map<Index, std::size_t> split_faces;  // face -> sides with nodes
  for (int side = 0; side < 2; ++side) {
    for (std::size_t e = 0; e < seam[side].edges.size(); ++e) {
      if (inserts.count({seam[side].edges[e][0], seam[side].edges[e][1]}))
        ++split_faces[seam[side].faces[e]];
    }
  }
  for (const auto& [f, sides] : split_faces) {
    const Face original = m.faces[f];
    std::vector<Index> poly;
    const int n = corner_count(original);
    for (int k = 0; k < n; ++k) {
      const Index a = original[k], b = original[(k + 1) % n];
      poly.push_back(a);
      auto it = inserts.find({a, b});
      if (it == inserts.end()) continue;
      for (const auto& [t, v] : it->second) poly.push_back(v);
    }
    const std::vector<Face> pieces = split_polygon(m.positions, poly, original, sides);
    m.faces[f] = pieces.front();
    for (std::size_t i = 1; i < pieces.size(); ++i) {
      m.faces.push_back(pieces[i]);
      m.face_patch.push_back(m.face_patch[f]);
      m.face_block.push_back(m.face_block[f]);
    }
    // The block's counts: the pieces for the face.
    BlockReport& b = out.report.blocks[m.face_block[f]];
    --(is_triangle(original) ? b.triangles : b.quads);
    for (const Face& p : pieces) ++(is_triangle(p) ? b.triangles : b.quads);
  }
}

}  // namespace

StructuredMesh join_sides(StructuredMesh port, StructuredMesh starboard, const SeamPlanes& planes,
                          SideJoin* counts) {
  StructuredMesh out = std::move(port);
  SurfaceMesh& m = out.mesh;
  const Index nv = static_cast<Index>(m.vertex_count());
  append_side(out, starboard);
  const Index total = static_cast<Index>(m.vertex_count());

  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  const Seam seam[2] = {collect_seam(m, adj, 0, nv, planes),
                        collect_seam(m, adj, nv, total, planes)};
  SideJoin c;
  c.seam_nodes = seam[0].nodes.size() + seam[1].nodes.size();
  std::vector<Index> vert_to(total);
  for (Index v = 0; v < total; ++v) vert_to[v] = v;
  std::vector<std::uint8_t> placed(total, 0);
  c.welded = weld_seams(m, seam, vert_to, placed);
  const Inserts inserts = plan_inserts(m, seam, placed, nv);
  for (const auto& [edge, along] : inserts) c.inserted += along.size();
  split_at_inserts(out, seam, inserts);

  // The welded nodes of starboard leave; knuckle edges follow.
  for (Face& f : m.faces)
    for (int k = 0; k < corner_count(f); ++k) f[k] = vert_to[f[k]];
  for (auto& e : out.knuckle_edges) e = {vert_to[e[0]], vert_to[e[1]]};
  c.back_to_back = drop_back_to_back(out);
  c.holes_filled = fill_seam_holes(out, planes.centre_tol);
  structured::drop_unused_vertices(out);
  out.report.quads = out.report.triangles = 0;
  for (const Face& f : m.faces) ++(is_triangle(f) ? out.report.triangles : out.report.quads);
  if (counts) *counts = c;
  return out;
}

}  // namespace hm
