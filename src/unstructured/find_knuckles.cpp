// Knuckle edges: dihedral score, one-sided NURBS confirmation, user hints, and lines followed on
// where their jump fades below the threshold.
//
// Why one-sided: a knuckle inside a patch sits on a knot of full multiplicity, where the surface
// is only C0. Its normal there depends on the side it is approached from, so each face's normal
// is taken on the smooth piece of its patch (between C0 knot lines) that holds the face's
// centroid, next to the edge. Refined vertices of a tessellation need not sit exactly on the knot
// line (they are projected onto the NURBS), so pushing a little into the face is not enough: the
// parameter is clamped into that piece.
#include "unstructured/find_knuckles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "core/bbox.h"
#include "core/parallel.h"
#include "nurbs/knot_ops.h"

namespace hm::detail {
namespace {

// Fraction of the way from the edge midpoint to the face centroid where the NURBS normal is
// taken: next to the edge, so that a smooth surface shows no jump at all (the smooth piece, not
// the push, puts the point on the face's side of a C0 knot).
constexpr double kPush = 1e-3;
// Vertex (u, v) are trusted for a face when the surface at the uv midpoint of the edge and at the
// uv centroid lies within this fraction of the face's size (the larger of the edge length and
// |centroid - midpoint|) of the 3D points. A seam or a collapsed row gives a welded vertex a
// (u, v) from elsewhere in the domain, which misses by far more; a coarse mesh's chord error
// (the 3D points are off the surface) stays below it.
constexpr double kUvConsistency = 0.5;
// A corner's (u, v) is its own when the surface there lies within this fraction of the face's
// size of the corner: the tessellation puts its vertices on the surface, and the merge moves
// some across gaps (a welded vertex at the mean of its cluster) without new (u, v).
constexpr double kCornerOnSurface = 1e-4;
// A parameter whose derivative is below this fraction of the other's is collapsed there.
constexpr double kCollapsed = 1e-9;
// Distance from a C0 knot line, as a fraction of the domain, at which a one-sided normal is taken.
constexpr double kKnotOffset = 1e-9;
// A face whose centroid's (u, v) lies within this fraction of the domain of a C0 knot line is on
// it, not on one side, and which smooth piece holds it is a matter of rounding. Newton started
// from a corner on a crease stops on the crease: a bottom face at a full hull's transom whose
// keel corner is the other half's vertex is projected from its corners on the transom's edge,
// and took the transom's normal (the generated 2-patch chine hull's port transom edge stopped
// 0.43 m short of the keel). Its side is then the piece whose normal its own agrees with.
constexpr double kOnBreak = 1e-7;
// A candidate is confirmed when the NURBS normals jump by at least this fraction of the
// threshold: the mesh dihedral adds the discretisation angle of both faces to the true jump.
constexpr double kConfirmFraction = 0.5;
// A knuckle line is followed on from its end along the edge that continues it best (turn below
// kExtendTurnDeg) while the NURBS jump stays above this fraction of the threshold, whatever the
// mesh dihedral: a chine fades out towards the stem, and is still a chine there.
constexpr double kExtendFraction = 0.25;
constexpr double kExtendTurnDeg = 30;

double angle_deg(const Vec3d& a, const Vec3d& b) {
  // atan2 of |a x b| and a . b is accurate near 0 and 180 degrees, unlike acos.
  return std::atan2(norm(cross(a, b)), dot(a, b)) * 180.0 / std::numbers::pi;
}

// Parameters where a patch is only C0 or worse (knots of multiplicity >= degree), with the
// domain ends: the patch is smooth between consecutive entries.
std::vector<double> c0_breaks(const std::vector<double>& knots, int degree,
                              const std::vector<double>& spans) {
  std::vector<double> breaks;
  for (std::size_t i = 0; i < spans.size(); ++i) {
    if (i == 0 || i + 1 == spans.size() || knot_multiplicity(knots, spans[i]) >= degree) {
      breaks.push_back(spans[i]);
    }
  }
  return breaks;
}

// t moved into the smooth piece of `breaks` holding `inside`, kKnotOffset of the range in.
double clamp_to_piece(double t, double inside, const std::vector<double>& breaks) {
  if (breaks.size() < 2) return t;
  const auto hi = std::clamp(std::upper_bound(breaks.begin(), breaks.end(), inside),
                             breaks.begin() + 1, breaks.end() - 1);
  const double a = *(hi - 1), b = *hi;
  const double eps = kKnotOffset * (breaks.back() - breaks.front());
  if (b - a <= 2 * eps) return std::clamp(t, a, b);
  return std::clamp(t, a + eps, b - eps);
}

// The interior break that `inside` lies on (within kOnBreak of the range), or NaN.
double break_at(double inside, const std::vector<double>& breaks) {
  if (breaks.size() < 3) return std::numeric_limits<double>::quiet_NaN();
  const double tol = kOnBreak * (breaks.back() - breaks.front());
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i) {
    if (std::abs(inside - breaks[i]) <= tol) return breaks[i];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

bool face_uv_usable(const SurfaceMesh& mesh, const Face& face, PatchId patch) {
  if (mesh.vertex_uv.size() != mesh.vertex_count() ||
      mesh.vertex_patch.size() != mesh.vertex_count()) {
    return false;
  }
  for (int c = 0; c < corner_count(face); ++c) {
    if (mesh.vertex_patch[face[c]] != patch) return false;
  }
  return true;
}

// The face's corner (u, v), with a coordinate that does not move the point (a corner on a
// collapsed row or column: su or sv vanishes there, so its welded vertex may carry any value)
// replaced by the mean of the other corners' values; nullopt when a corner's (u, v) maps further
// than `tol` from the corner (a vertex the merge moved across a gap keeps the (u, v) it had).
std::optional<std::array<Vec2d, 4>> corner_parameters(const SurfaceMesh& mesh,
                                                      const NurbsSurface& s, const Face& face,
                                                      double tol) {
  const int n = corner_count(face);
  std::array<Vec2d, 4> uv{};
  std::array<bool, 4> free_u{}, free_v{};
  Vec2d sum;
  int count_u = 0, count_v = 0;
  for (int c = 0; c < n; ++c) {
    uv[c] = mesh.vertex_uv[face[c]];
    const SurfaceDerivs d = evaluate_derivs(s, uv[c].x, uv[c].y, 1);
    if (!(norm(d.p - mesh.positions[face[c]]) <= tol)) return std::nullopt;
    const double su = norm(d.su), sv = norm(d.sv);
    free_u[c] = su <= kCollapsed * sv;
    free_v[c] = sv <= kCollapsed * su;
    if (!free_u[c]) sum.x += uv[c].x, ++count_u;
    if (!free_v[c]) sum.y += uv[c].y, ++count_v;
  }
  for (int c = 0; c < n; ++c) {
    if (free_u[c] && count_u > 0) uv[c].x = sum.x / count_u;
    if (free_v[c] && count_v > 0) uv[c].y = sum.y / count_v;
  }
  return uv;
}

// (u, v) of a point of `s` next to `q`: Newton from a corner of the face on that patch, else a
// full search.
Vec2d project(const SurfaceMesh& mesh, const NurbsSurface& s, const Face& face, PatchId patch,
              const Vec3d& q) {
  if (mesh.vertex_patch.size() == mesh.vertex_count() &&
      mesh.vertex_uv.size() == mesh.vertex_count()) {
    for (int c = 0; c < corner_count(face); ++c) {
      if (mesh.vertex_patch[face[c]] != patch) continue;
      const Vec2d seed = mesh.vertex_uv[face[c]];
      const SurfaceProjection p = closest_point(s, q, seed.x, seed.y);
      return {p.u, p.v};
    }
  }
  const SurfaceProjection p = closest_point(s, q);
  return {p.u, p.v};
}

// (u, v) on face f's patch of a point inside f next to the midpoint of its edge a-b, on the
// smooth piece of the patch that holds the face's centroid; and the C0 knot lines (u, v; NaN
// for none) that the centroid lies on, where that piece is not settled.
struct SidePoint {
  Vec2d uv;
  Vec2d on_break;
};
SidePoint side_parameter(const SurfaceMesh& mesh, const SmoothPieces& pieces, const NurbsSurface& s,
                         Index f, Index a, Index b) {
  const Face& face = mesh.faces[f];
  const PatchId patch = mesh.face_patch[f];
  const Vec3d mid = 0.5 * (mesh.positions[a] + mesh.positions[b]);
  const Vec3d centroid = face_centroid(mesh.positions, face);
  Vec2d uv, uv_centroid;
  bool have = false;
  const double size = std::max(norm(centroid - mid), norm(mesh.positions[b] - mesh.positions[a]));
  const std::optional<std::array<Vec2d, 4>> corners =
      face_uv_usable(mesh, face, patch) ? corner_parameters(mesh, s, face, kCornerOnSurface * size)
                                        : std::nullopt;
  if (corners) {
    const std::array<Vec2d, 4>& corner = *corners;
    const int n = corner_count(face);
    Vec2d uv_mid;
    for (int c = 0; c < n; ++c) {
      uv_centroid += corner[c];
      if (face[c] == a || face[c] == b) uv_mid += 0.5 * corner[c];
    }
    uv_centroid *= 1.0 / n;
    const double tol = kUvConsistency * size;
    if (norm(evaluate(s, uv_mid.x, uv_mid.y) - mid) <= tol &&
        norm(evaluate(s, uv_centroid.x, uv_centroid.y) - centroid) <= tol) {
      uv = uv_mid + kPush * (uv_centroid - uv_mid);
      have = true;
    }
  }
  if (!have) {
    uv = project(mesh, s, face, patch, mid + kPush * (centroid - mid));
    uv_centroid = project(mesh, s, face, patch, centroid);
  }
  return {{clamp_to_piece(uv.x, uv_centroid.x, pieces.u),
           clamp_to_piece(uv.y, uv_centroid.y, pieces.v)},
          {break_at(uv_centroid.x, pieces.u), break_at(uv_centroid.y, pieces.v)}};
}

// Unit NURBS normal on face f's side of edge a-b, signed by how its patch faces the mesh (with
// `facing`, where that is known), else like face_n; nullopt when the surface has no usable
// normal there. Not by the face alone: a sliver standing on its edge along a seam the snap
// closed has a normal square to the surface, whose sign says nothing, and a face folded over
// has it backwards.
std::optional<Vec3d> side_normal(const SurfaceMesh& mesh, std::span<const Patch> patches,
                                 std::span<const SmoothPieces> pieces, const PatchFacing* facing,
                                 Index f, Index a, Index b, const Vec3d& face_n) {
  const PatchId patch = mesh.face_patch[f];
  const NurbsSurface& s = patches[patch].surface;
  const SidePoint side = side_parameter(mesh, pieces[patch], s, f, a, b);
  // Where the centroid lies on a knot line, the point on either side of it: the face's side is
  // the one whose normal agrees with the face's best (either way round).
  struct Params {
    double t[2];
    int count;
  };
  const auto either_side = [](double t, double on_break, const std::vector<double>& breaks) {
    if (!std::isfinite(on_break)) return Params{{t, t}, 1};
    const double d = kKnotOffset * (breaks.back() - breaks.front());
    return Params{{on_break - d, on_break + d}, 2};
  };
  const Params us = either_side(side.uv.x, side.on_break.x, pieces[patch].u);
  const Params vs = either_side(side.uv.y, side.on_break.y, pieces[patch].v);
  Vec3d n;
  double best = -1;
  for (int i = 0; i < us.count; ++i) {
    for (int j = 0; j < vs.count; ++j) {
      const Vec3d c = normal(s, us.t[i], vs.t[j]);
      if (!is_finite(c) || squared_norm(c) == 0) continue;
      if (const double fit = std::abs(dot(c, face_n)); fit > best) best = fit, n = c;
    }
  }
  if (best < 0) return std::nullopt;
  double sign = facing ? facing->of(patch) : 0;
  if (sign == 0) sign = dot(n, face_n) < 0 ? -1 : 1;
  return sign * n;
}

// A hint with its distance resolved and its polyline's box, so that most edges are turned down
// without visiting the points.
struct PreparedHint {
  const KnuckleHint* hint = nullptr;
  double distance = 0;
  Vec3d unit_normal;  // kPlane
  BBox3d box;         // kPoints: the polyline's box grown by distance
};

PreparedHint prepare(const KnuckleHint& hint, double length) {
  PreparedHint p{&hint, hint.distance > 0 ? hint.distance : 1e-3 * length, {}, {}};
  p.unit_normal = normalized(hint.plane_normal);
  for (const Vec3d& q : hint.points) p.box.add(q);
  if (!p.box.empty()) {
    const Vec3d grow{p.distance, p.distance, p.distance};
    p.box.lo -= grow;
    p.box.hi += grow;
  }
  return p;
}

double distance_to_segment(const Vec3d& q, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double len2 = squared_norm(ab);
  const double t = len2 > 0 ? std::clamp(dot(q - a, ab) / len2, 0.0, 1.0) : 0.0;
  return norm(q - (a + t * ab));
}

bool near_polyline(const PreparedHint& h, const Vec3d& q) {
  const Vec3d& lo = h.box.lo;
  const Vec3d& hi = h.box.hi;
  if (h.box.empty() || q.x < lo.x || q.y < lo.y || q.z < lo.z || q.x > hi.x || q.y > hi.y ||
      q.z > hi.z) {
    return false;
  }
  const std::vector<Vec3d>& pts = h.hint->points;
  if (pts.size() == 1) return norm(q - pts[0]) <= h.distance;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    if (distance_to_segment(q, pts[i], pts[i + 1]) <= h.distance) return true;
  }
  return false;
}

bool matches(const PreparedHint& h, const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
             Index e) {
  const MeshEdge& me = adjacency.edges[e];
  const Vec3d& p0 = mesh.positions[me.v0];
  const Vec3d& p1 = mesh.positions[me.v1];
  switch (h.hint->kind) {
    case KnuckleHint::Kind::kPlane:
      return std::abs(dot(0.5 * (p0 + p1) - h.hint->plane_point, h.unit_normal)) <= h.distance;
    case KnuckleHint::Kind::kPatchPair: {
      if (mesh.face_patch.size() != mesh.face_count()) return false;
      const EdgeFaces ef = edge_faces(adjacency, e);
      const PatchId a = mesh.face_patch[ef.f0], b = mesh.face_patch[ef.f1];
      return (a == h.hint->patch_a && b == h.hint->patch_b) ||
             (a == h.hint->patch_b && b == h.hint->patch_a);
    }
    case KnuckleHint::Kind::kPoints:
      return near_polyline(h, p0) && near_polyline(h, p1);
  }
  return false;
}

bool any_matches(std::span<const PreparedHint> hints, const SurfaceMesh& mesh,
                 const EdgeAdjacency& adjacency, Index e) {
  return std::any_of(hints.begin(), hints.end(),
                     [&](const PreparedHint& h) { return matches(h, mesh, adjacency, e); });
}

// Per-edge flags written by the parallel pass.
enum : std::uint8_t { kCandidate = 1, kRejected = 2, kKnuckle = 4 };

Index other_end(const MeshEdge& e, Index v) { return e.v0 == v ? e.v1 : e.v0; }

// Interior edges around each vertex, ascending ids.
struct VertexEdges {
  std::vector<Index> offset, edge;
  std::span<const Index> around(Index v) const {
    return {edge.data() + offset[v], edge.data() + offset[v + 1]};
  }
};

VertexEdges interior_edges_by_vertex(std::size_t vertex_count, const EdgeAdjacency& adjacency) {
  VertexEdges g;
  g.offset.assign(vertex_count + 1, 0);
  for (const MeshEdge& e : adjacency.edges) {
    if (e.uses != 2) continue;
    ++g.offset[e.v0 + 1];
    ++g.offset[e.v1 + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) g.offset[v + 1] += g.offset[v];
  g.edge.resize(g.offset.back());
  std::vector<Index> fill(g.offset.begin(), g.offset.end() - 1);
  for (std::size_t i = 0; i < adjacency.edges.size(); ++i) {
    const MeshEdge& e = adjacency.edges[i];
    if (e.uses != 2) continue;
    g.edge[fill[e.v0]++] = static_cast<Index>(i);
    g.edge[fill[e.v1]++] = static_cast<Index>(i);
  }
  return g;
}

struct ExtendContext {
  const SurfaceMesh& mesh;
  const EdgeAdjacency& adjacency;
  std::span<const Patch> patches;
  std::span<const SmoothPieces> pieces;
  const PatchFacing& facing;
  std::span<const PreparedHint> suppress;
  double min_jump;  // degrees
};

// The edge at `v` that continues the line arriving along `from` (turn < kExtendTurnDeg, least
// turn first) and whose NURBS normals still jump by min_jump; kInvalid when none.
Index continuation(const ExtendContext& c, const VertexEdges& around, Index v, Index from,
                   std::span<const std::uint8_t> flags) {
  const std::vector<Vec3d>& p = c.mesh.positions;
  const Vec3d in = p[v] - p[other_end(c.adjacency.edges[from], v)];
  std::vector<std::pair<double, Index>> options;
  for (Index e : around.around(v)) {
    if (flags[e] & kKnuckle) continue;
    const double turn = angle_deg(in, p[other_end(c.adjacency.edges[e], v)] - p[v]);
    if (turn < kExtendTurnDeg) options.emplace_back(turn, e);
  }
  std::sort(options.begin(), options.end());
  for (const auto& [turn, e] : options) {
    if (any_matches(c.suppress, c.mesh, c.adjacency, e)) continue;
    if (nurbs_normal_jump_deg(c.mesh, c.adjacency, c.patches, c.pieces, c.facing, e) >=
        c.min_jump) {
      return e;
    }
  }
  return kInvalid;
}

// Follows every knuckle line on from its ends (serial, in vertex order: the few ends make it
// cheap, and the order makes it deterministic).
void extend_lines(const ExtendContext& c, std::vector<std::uint8_t>& flags) {
  const VertexEdges around = interior_edges_by_vertex(c.mesh.vertex_count(), c.adjacency);
  std::vector<Index> degree(c.mesh.vertex_count(), 0);  // knuckle edges per vertex
  for (std::size_t e = 0; e < flags.size(); ++e) {
    if (!(flags[e] & kKnuckle)) continue;
    ++degree[c.adjacency.edges[e].v0];
    ++degree[c.adjacency.edges[e].v1];
  }
  for (std::size_t i = 0; i < degree.size(); ++i) {
    if (degree[i] != 1) continue;
    Index v = static_cast<Index>(i);
    Index from = kInvalid;
    for (Index e : around.around(v)) {
      if (flags[e] & kKnuckle) from = e;
    }
    if (from == kInvalid) continue;  // the knuckle edge is not interior
    for (;;) {
      const Index next_edge = continuation(c, around, v, from, flags);
      if (next_edge == kInvalid) break;
      flags[next_edge] |= kKnuckle;
      const Index next = other_end(c.adjacency.edges[next_edge], v);
      ++degree[v];
      if (++degree[next] > 1) break;  // joined another line
      v = next;
      from = next_edge;
    }
  }
}

// A sliver whose three sides are all knuckle edges holds one line twice: two paths between the
// same two vertices, its longest side and the two sides through its third corner
// (ship_449_patches.iges: four patch seams at x = const near the bilge, slivers 0.34-0.73 m
// long and 3-12 mm wide). The longest side stops being a knuckle, and the line runs through
// the third corner. The coarsening keeps one edge there in any case; counted twice, the lines
// made the merged surface's knuckles 2 m longer than the panels' could be. A triangle is such a
// sliver when its third corner lies within kDoubledWidth of its longest side's length of that
// side. Serial in face order.
constexpr double kDoubledWidth = 0.05;

void drop_doubled_sides(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                        std::vector<std::uint8_t>& flags) {
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    if (!is_triangle(face)) continue;
    Index side[3];
    bool all = true;
    for (int c = 0; c < 3; ++c) {
      side[c] = adjacency.slot_edge[4 * f + c];
      all = all && side[c] != kInvalid && (flags[side[c]] & kKnuckle);
    }
    if (!all) continue;
    // Side c runs from corner c to corner c + 1; the longest, and the corner off it.
    int longest = 0;
    double best = -1;
    for (int c = 0; c < 3; ++c) {
      const double l = squared_norm(mesh.positions[face[(c + 1) % 3]] - mesh.positions[face[c]]);
      if (l > best) {
        best = l;
        longest = c;
      }
    }
    if (!(best > 0)) continue;
    const Vec3d& a = mesh.positions[face[longest]];
    const Vec3d& b = mesh.positions[face[(longest + 1) % 3]];
    const Vec3d& m = mesh.positions[face[(longest + 2) % 3]];
    // Twice the area over the side: the third corner's distance from the side's line.
    const double side_length = std::sqrt(best);
    if (norm(cross(b - a, m - a)) / side_length > kDoubledWidth * side_length) continue;
    flags[side[longest]] &= static_cast<std::uint8_t>(~kKnuckle);
  }
}

}  // namespace

EdgeFaces edge_faces(const EdgeAdjacency& adjacency, Index e) {
  const MeshEdge& me = adjacency.edges[e];
  const Index slot = me.first_slot;
  return {slot / 4, adjacency.opposite_face[slot], me.same_direction};
}

double dihedral_angle_deg(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency, Index e) {
  const EdgeFaces ef = edge_faces(adjacency, e);
  const Vec3d n0 = face_normal(mesh.positions, mesh.faces[ef.f0]);
  Vec3d n1 = face_normal(mesh.positions, mesh.faces[ef.f1]);
  if (ef.flipped) n1 = -n1;
  return angle_deg(n0, n1);
}

std::vector<SmoothPieces> smooth_pieces(std::span<const Patch> patches) {
  std::vector<SmoothPieces> out(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const NurbsSurface& s = patches[i].surface;
    out[i].u = c0_breaks(s.knots_u, s.degree_u, span_breaks_u(s));
    out[i].v = c0_breaks(s.knots_v, s.degree_v, span_breaks_v(s));
  }
  return out;
}

PatchFacing::PatchFacing(const SurfaceMesh& mesh, std::span<const Patch> patches)
    : mesh_(mesh),
      patches_(patches),
      face_start_(patches.size() + 1, 0),
      once_(std::make_unique<std::once_flag[]>(patches.size())),
      facing_(patches.size(), 0) {
  // Each patch's faces, ascending (count -> scan -> fill).
  for (const PatchId p : mesh.face_patch) {
    if (p < patches.size()) ++face_start_[p + 1];
  }
  for (std::size_t p = 0; p < patches.size(); ++p) face_start_[p + 1] += face_start_[p];
  faces_.resize(face_start_.back());
  std::vector<Index> fill(face_start_.begin(), face_start_.end() - 1);
  for (std::size_t f = 0; f < mesh.face_patch.size(); ++f) {
    const PatchId p = mesh.face_patch[f];
    if (p < patches.size()) faces_[fill[p]++] = Index(f);
  }
}

double PatchFacing::of(PatchId p) const {
  std::call_once(once_[p], [&] {
    const NurbsSurface& s = patches_[p].surface;
    const bool have_uv = mesh_.vertex_uv.size() == mesh_.vertex_count() &&
                         mesh_.vertex_patch.size() == mesh_.vertex_count();
    // Faces spread over the patch (kProbes of them at most), each voting once, by its first
    // corner that is the patch's own vertex and lies where its (u, v) puts it: whether the
    // surface's normal there points the face's way. kVotes votes decide.
    const Index first = face_start_[p], count = face_start_[p + 1] - first;
    const Index stride = std::max<Index>(1, count / kProbes);
    int votes = 0, cast = 0;
    for (Index k = 0; have_uv && k < count && cast < kVotes; k += stride) {
      const Face& face = mesh_.faces[faces_[first + k]];
      const int n = corner_count(face);
      double longest = 0;
      for (int c = 0; c < n; ++c) {
        longest =
            std::max(longest, norm(mesh_.positions[face[(c + 1) % n]] - mesh_.positions[face[c]]));
      }
      for (int c = 0; c < n; ++c) {
        const Index v = face[c];
        if (mesh_.vertex_patch[v] != p) continue;
        const Vec2d uv = mesh_.vertex_uv[v];
        if (!(norm(evaluate(s, uv.x, uv.y) - mesh_.positions[v]) <= kCornerOnSurface * longest)) {
          continue;
        }
        const double d = dot(normal(s, uv.x, uv.y), face_normal(mesh_.positions, face));
        votes += d > 0 ? 1 : d < 0 ? -1 : 0;
        ++cast;
        break;
      }
    }
    facing_[p] = votes > 0 ? 1 : votes < 0 ? -1 : 0;
  });
  return facing_[p];
}

double nurbs_normal_jump_deg(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                             std::span<const Patch> patches, std::span<const SmoothPieces> pieces,
                             const PatchFacing& facing, Index e) {
  const MeshEdge& me = adjacency.edges[e];
  const EdgeFaces ef = edge_faces(adjacency, e);
  const Vec3d fn0 = face_normal(mesh.positions, mesh.faces[ef.f0]);
  Vec3d fn1 = face_normal(mesh.positions, mesh.faces[ef.f1]);
  // Two faces wound against each other (a mesh not yet oriented): whether the face or its whole
  // patch is turned is not known here, so both sides take their faces' signs, the second turned.
  if (ef.flipped) fn1 = -fn1;
  const PatchFacing* by_patch = ef.flipped ? nullptr : &facing;
  const std::optional<Vec3d> n0 =
      side_normal(mesh, patches, pieces, by_patch, ef.f0, me.v0, me.v1, fn0);
  const std::optional<Vec3d> n1 =
      side_normal(mesh, patches, pieces, by_patch, ef.f1, me.v0, me.v1, fn1);
  if (!n0 || !n1) return -1;
  return angle_deg(*n0, *n1);
}

KnuckleEdges find_knuckles(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                           std::span<const Patch> patches, const FeatureOptions& options,
                           double length) {
  std::vector<PreparedHint> add, suppress;
  for (const KnuckleHint& h : options.add) add.push_back(prepare(h, length));
  for (const KnuckleHint& h : options.suppress) suppress.push_back(prepare(h, length));
  const double threshold = options.knuckle_angle_deg;
  const bool confirm = options.confirm_on_nurbs;
  const std::vector<SmoothPieces> pieces =
      confirm ? smooth_pieces(patches) : std::vector<SmoothPieces>{};
  const PatchFacing facing(mesh, confirm ? patches : std::span<const Patch>{});

  // The cut puts its vertices on the plane exactly (to rounding in a leaning frame); 1e-9 L only
  // absorbs a file whose own vertices lie there.
  const double wl = options.waterline_z, wl_tol = 1e-9 * length;
  auto on_waterline = [&](Index e) {
    if (!options.waterline_inside || std::isnan(wl)) return false;
    const MeshEdge& me = adjacency.edges[e];
    const Vec3d& up = options.waterplane_normal;
    return std::abs(dot(up, mesh.positions[me.v0]) - wl) <= wl_tol &&
           std::abs(dot(up, mesh.positions[me.v1]) - wl) <= wl_tol;
  };
  std::vector<std::uint8_t> flags(adjacency.edges.size(), 0);
  parallel_for(0, adjacency.edges.size(), [&](std::size_t i) {
    const Index e = static_cast<Index>(i);
    if (adjacency.edges[e].uses != 2) return;
    int f = 0;
    if (dihedral_angle_deg(mesh, adjacency, e) > threshold) {
      f |= kCandidate;
      // An unknown NURBS normal (negative jump) leaves the mesh's verdict standing.
      const double jump =
          confirm ? nurbs_normal_jump_deg(mesh, adjacency, patches, pieces, facing, e) : -1;
      f |= jump < 0 || jump >= kConfirmFraction * threshold ? kKnuckle : kRejected;
    }
    if (any_matches(add, mesh, adjacency, e)) f |= kKnuckle;
    if (any_matches(suppress, mesh, adjacency, e)) f &= ~kKnuckle;
    if (on_waterline(e)) f |= kKnuckle;
    flags[i] = static_cast<std::uint8_t>(f);
  });
  if (confirm) {
    extend_lines({mesh, adjacency, patches, pieces, facing, suppress, kExtendFraction * threshold},
                 flags);
  }
  drop_doubled_sides(mesh, adjacency, flags);

  KnuckleEdges out;
  out.edge_knuckle.resize(flags.size());
  for (std::size_t i = 0; i < flags.size(); ++i) {
    out.edge_knuckle[i] = (flags[i] & kKnuckle) ? 1 : 0;
    out.candidates += (flags[i] & kCandidate) ? 1 : 0;
    out.rejected_by_nurbs += (flags[i] & kRejected) ? 1 : 0;
  }
  return out;
}

}  // namespace hm::detail
