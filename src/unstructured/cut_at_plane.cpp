// Cut: collect the side of every vertex -> snap vertices near the plane onto it (along their
// patch, or along their line) -> collect the crossing edges and refine each crossing onto its
// patch -> split the crossed faces, keeping the kept side (or both) -> compact the vertices.
#include "unstructured/cut_at_plane.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"
#include "mesh/adjacency.h"
#include "nurbs/nurbs_surface.h"
#include "query/surface_refine.h"

namespace hm {
namespace {

constexpr int kSnapNewton = 8;

// A crossing refined from one corner (the nearest point of the section to the linear crossing)
// farther than this fraction of its edge from the linear crossing has run off its patch.
constexpr double kFarCrossing = 0.1;
// A line lies in the cut plane where its vertices are within this share of their shortest edge
// of it (see cut_at_plane).
constexpr double kInPlane = 0.01;

// The corners of the triangles of face f: one triangle, or the quad's 0-1-2 and 0-2-3.
int face_triangles(const Face& f, std::array<std::array<Index, 3>, 2>& out) {
  out[0] = {f[0], f[1], f[2]};
  if (f[3] == kInvalid) return 1;
  out[1] = {f[0], f[2], f[3]};
  return 2;
}

// Dihedral angle above which an edge counts as a knuckle here (below the feature finder's 25
// degrees, so that no knuckle it will find is bent by a snap).
constexpr double kSharpCos = 0.9396926207859084;  // cos 20 degrees

// What the snap needs to know of the mesh's edges.
struct SnapFacts {
  std::vector<double> shortest;       // per vertex, its shortest edge (metres)
  std::vector<std::uint8_t> movable;  // per vertex: no line edge at it, all faces on its patch
  std::vector<std::array<Index, 2>> line_edges;  // ascending; see below
};

// Line edges are those a vertex may only slide along: on the mesh boundary (deck edge, centre
// plane), between two patches, or sharp. A vertex with none lies inside one smooth patch and may
// move along it freely.
SnapFacts snap_facts(const SurfaceMesh& mesh) {
  SnapFacts facts;
  facts.movable.assign(mesh.vertex_count(), 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (Index v : mesh.faces[f]) {
      if (v != kInvalid && mesh.vertex_patch[v] != mesh.face_patch[f]) facts.movable[v] = 0;
    }
  }
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  facts.shortest.assign(mesh.vertex_count(), std::numeric_limits<double>::infinity());
  for (const MeshEdge& e : adj.edges) {
    const double len = norm(mesh.positions[e.v0] - mesh.positions[e.v1]);
    facts.shortest[e.v0] = std::min(facts.shortest[e.v0], len);
    facts.shortest[e.v1] = std::min(facts.shortest[e.v1], len);
    bool line = e.uses != 2;
    if (!line) {
      const Index f0 = e.first_slot / 4, f1 = adj.opposite_face[e.first_slot];
      line = mesh.face_patch[f0] != mesh.face_patch[f1] ||
             dot(face_normal(mesh.positions, mesh.faces[f0]),
                 face_normal(mesh.positions, mesh.faces[f1])) < kSharpCos;
    }
    if (line) {
      facts.line_edges.push_back({e.v0, e.v1});
      facts.movable[e.v0] = facts.movable[e.v1] = 0;
    }
  }
  std::sort(facts.line_edges.begin(), facts.line_edges.end());
  return facts;
}

// The cut plane x[axis] = value; side() is positive on the side that is dropped.
struct AxisPlane {
  int axis = 2;
  double value = 0;
  double sign = 1;  // +1: keep below the value, -1: keep above it
  double side(const Vec3d& p) const { return sign * (p[axis] - value); }
  Vec3d on_plane(Vec3d p) const {
    p[axis] = value;
    return p;
  }
};

// Newton on g(u, v) = S(u, v)[axis] - value along the gradient of g in (u, v): the nearest
// parameter step that puts the point on the plane. Returns false when it does not converge or
// would leave the domain or move the point farther than max_move.
bool snap_onto_plane(const NurbsSurface& s, const query::ParamDomain& d, const AxisPlane& plane,
                     double tol, double max_move, Vec2d& uv, Vec3d& p) {
  Vec2d x = uv;
  for (int it = 0; it < kSnapNewton; ++it) {
    const SurfaceDerivs dv = evaluate_derivs(s, x.x, x.y, 1);
    const double g = dv.p[plane.axis] - plane.value;
    if (std::abs(g) <= tol) {
      if (norm(dv.p - p) > max_move) return false;
      uv = x;
      p = dv.p;
      return true;
    }
    const Vec2d grad{dv.su[plane.axis], dv.sv[plane.axis]};
    const double g2 = dot(grad, grad);
    if (!(g2 > 0)) return false;
    const Vec2d next = x - (g / g2) * grad;
    if (d.map(next) != next) return false;  // would leave the patch: leave the vertex alone
    x = next;
  }
  return false;
}

// The crossing of edge (a, b) with the plane, on patch p's NURBS (a patch of a face at
// the edge): along the edge's parameter segment when both corners name p; otherwise the point of
// the section curve nearest the linear crossing, from the corner that names p (or from p's
// closest point to the linear crossing when neither does).
query::RefinedPlanePoint refine_crossing(std::span<const Patch> patches,
                                         std::span<const query::ParamDomain> domains,
                                         const SurfaceMesh& m, Index a, Index b, PatchId p,
                                         const AxisPlane& plane, double tol, PatchId& used) {
  const Vec3d pa = m.positions[a], pb = m.positions[b];
  const double f = plane.side(pa) / (plane.side(pa) - plane.side(pb));
  const Vec3d linear = pa + f * (pb - pa);
  Vec3d normal;
  normal[plane.axis] = 1;
  // On patch q, from corners c0 -> c1 (equal: the point of the section nearest the linear one).
  auto refine_on = [&](PatchId q, Vec2d c0, Vec2d c1) {
    Vec2d corners[2] = {c0, c1};
    query::unwrap_corners(domains[q], corners, 2);
    return query::refine_plane_edge(patches[q].surface, domains[q], normal, plane.on_plane(pa),
                                    corners[0], corners[1], f, linear, tol);
  };
  const auto far = [&](const query::RefinedPlanePoint& x) {
    return !x.converged || norm(x.point - linear) > kFarCrossing * norm(pb - pa);
  };
  const PatchId qa = m.vertex_patch[a], qb = m.vertex_patch[b];
  used = p;
  if (qa == p && qb == p) {
    const query::RefinedPlanePoint r = refine_on(p, m.vertex_uv[a], m.vertex_uv[b]);
    // Far only where a corner's (u, v) is not where it lies: a border vertex the snap moved
    // across a gap keeps its patch's border (u, v), and the border's crossing can lie far along
    // a plane the border runs nearly in (three crossings of a chine hull's waterline at one
    // point, 0.1-0.3 m from their edges).
    if (!far(r)) return r;
  }
  // Otherwise the nearest point of a section, which lies within the chord error of the linear
  // crossing unless the section ends before it. The start on p is the corner that names it, or
  // p's closest point to the linear crossing when neither does (both corners on borders, named
  // by their other patches: on the generated 300-patch round-bilge hull at its waterline, a's
  // patch put two crossings of one face at one point, and the face had no area).
  Vec2d start;
  if (qa == p || qb == p) {
    start = qa == p ? m.vertex_uv[a] : m.vertex_uv[b];
  } else {
    const SurfaceProjection on_p = closest_point(patches[p].surface, linear);
    start = {on_p.u, on_p.v};
  }
  query::RefinedPlanePoint best = refine_on(p, start, start);
  if (!far(best)) return best;
  // p ends before the crossing (where an overlap was cut away or a gap closed): the corners' own
  // patches are tried, and the nearer point wins. When every section ends before it, the
  // crossing lies in a gap the merge bridged; it stays on the bridging face, at the linear
  // crossing, and counts as not refined (the nearest patch's (u, v) goes with it as a start).
  const auto rank = [&](const query::RefinedPlanePoint& x) {
    return std::pair{!x.converged, norm(x.point - linear)};
  };
  for (const auto& [q, c] : {std::pair{qa, m.vertex_uv[a]}, std::pair{qb, m.vertex_uv[b]}}) {
    if (q == p) continue;
    const query::RefinedPlanePoint r = refine_on(q, c, c);
    if (rank(r) < rank(best)) {
      best = r;
      used = q;
    }
  }
  if (far(best)) {
    best.point = linear;
    best.converged = false;
  }
  return best;
}

// A crossing refined along its edge's parameter line may run along the plane past the crossing
// of the triangle's other cut edge (property seed 4295: 6 cm forward on a 0.57 m edge of a chine
// hull's side near the bow, past its neighbour's crossing), and the cut line then runs back on
// itself, with the split pieces over each other. In each triangle the cut runs from crossing to
// crossing (or from its corner in the plane to its crossing) the way the linear crossings'
// segment does; where it does not, its crossings go back to their linear places on the chord,
// flagged in `missed` (not refined). cut_edges: sorted edge keys, whose crossings are the
// vertices first_new + slot of m. In face order.
void keep_crossings_in_order(const SurfaceMesh& mesh, const AxisPlane& plane,
                             std::span<const std::pair<std::uint64_t, PatchId>> cut_edges,
                             Index first_new, SurfaceMesh& m, std::vector<std::uint8_t>& missed) {
  const auto side = [&](Index v) {
    const double d = plane.side(m.positions[v]);
    return d > 0 ? 1 : (d < 0 ? -1 : 0);
  };
  const auto slot_of = [&](Index a, Index b) {
    const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
    return static_cast<std::size_t>(
        std::lower_bound(cut_edges.begin(), cut_edges.end(), key,
                         [](const auto& entry, std::uint64_t k) { return entry.first < k; }) -
        cut_edges.begin());
  };
  const auto linear = [&](Index a, Index b) {
    const Vec3d pa = m.positions[a], pb = m.positions[b];
    const double t = plane.side(pa) / (plane.side(pa) - plane.side(pb));
    return plane.on_plane(pa + t * (pb - pa));
  };
  std::array<std::array<Index, 3>, 2> tris;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const int n = face_triangles(mesh.faces[f], tris);
    for (int t = 0; t < n; ++t) {
      // The triangle's cut, as two ends: a crossing (its edge's slot) or a corner in the plane
      // (slot cut_edges.size()).
      std::size_t slots[2];
      Vec3d ends[2], lin[2];
      int count = 0;
      for (int k = 0; k < 3; ++k) {
        const Index a = tris[t][k], b = tris[t][(k + 1) % 3];
        const bool corner = side(a) == 0, crossing = side(a) * side(b) < 0;
        if (!corner && !crossing) continue;
        if (count < 2) {
          slots[count] = corner ? cut_edges.size() : slot_of(a, b);
          ends[count] = corner ? m.positions[a] : m.positions[first_new + slots[count]];
          lin[count] = corner ? m.positions[a] : linear(a, b);
        }
        ++count;
      }
      if (count != 2 || dot(ends[1] - ends[0], lin[1] - lin[0]) > 0) continue;
      for (int k = 0; k < 2; ++k) {
        if (slots[k] == cut_edges.size()) continue;
        const Index a = static_cast<Index>(cut_edges[slots[k]].first >> 32);
        const Index b = static_cast<Index>(cut_edges[slots[k]].first & 0xffffffffu);
        m.positions[first_new + slots[k]] = linear(a, b);
        missed[slots[k]] = 1;
      }
    }
  }
}

// For each new vertex first_new + i, the vertex it is: the lowest-numbered vertex within `tol`
// of it among the new ones and those in the plane (side 0). Sorted along an axis of the plane
// (`along`) and swept, so the work is the number of points times the few within tol along it.
template <class Side>
std::vector<Index> coincident_crossings(std::span<const Vec3d> positions, Index first_new,
                                        double tol, int along, const Side& side) {
  std::vector<Index> points;
  for (Index v = 0; v < Index(positions.size()); ++v) {
    if (v >= first_new || side(v) == 0) points.push_back(v);
  }
  std::sort(points.begin(), points.end(), [&](Index a, Index b) {
    const double pa = positions[a][along], pb = positions[b][along];
    return pa != pb ? pa < pb : a < b;
  });
  std::vector<Index> to(positions.size() - first_new);
  for (std::size_t i = 0; i < to.size(); ++i) to[i] = first_new + Index(i);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1;
         j < points.size() && positions[points[j]][along] - positions[points[i]][along] <= tol;
         ++j) {
      const Index a = std::min(points[i], points[j]), b = std::max(points[i], points[j]);
      if (b < first_new || !(norm(positions[a] - positions[b]) <= tol)) continue;
      // b is new; it becomes what a is (a's own target when a is new too and already taken).
      const Index target = a >= first_new ? to[a - first_new] : a;
      to[b - first_new] = std::min(to[b - first_new], target);
    }
  }
  return to;
}

}  // namespace

PlaneCut cut_at_plane(std::span<const Patch> patches, const SurfaceMesh& mesh,
                      const PlaneCutOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t nv = mesh.vertex_count();
  if (mesh.vertex_uv.size() != nv || mesh.vertex_patch.size() != nv) {
    throw GeometryError("plane cut: the mesh has no (u, v) per vertex");
  }
  BBox3d box;
  for (const Vec3d& p : mesh.positions) box.add(p);
  const double length = std::max(norm(box.extent()), 1e-300);
  const double tol = 1e-9 * length;
  if (options.axis < 0 || options.axis > 2) {
    throw GeometryError("plane cut: the axis must be 0 (x), 1 (y) or 2 (z)");
  }
  const AxisPlane plane{options.axis, options.value, options.keep_below ? 1.0 : -1.0};

  std::vector<query::ParamDomain> domains(patches.size());
  parallel_for_each_item(patches.size(), [&](std::size_t p) {
    domains[p] = query::make_domain(patches[p].surface, tol);
  });

  // Collect and snap: each vertex writes its own slot.
  PlaneCut out;
  SurfaceMesh& m = out.mesh;
  m.positions = mesh.positions;
  m.vertex_uv = mesh.vertex_uv;
  m.vertex_patch = mesh.vertex_patch;
  std::vector<std::uint8_t> snapped(nv, 0);
  if (options.snap_fraction > 0) {
    const SnapFacts facts = snap_facts(mesh);
    auto near = [&](Index v) {
      const double d = plane.side(mesh.positions[v]);
      return d != 0 && std::abs(d) < options.snap_fraction * facts.shortest[v];
    };
    // A vertex on a line slides along one of its line edges that crosses the plane, to the
    // crossing, so the line stays where it is. Decided on the input positions; of two neighbours
    // that could slide to the same crossing, only the nearer to the plane does.
    std::vector<std::pair<Index, Index>> slides;  // (vertex, along the edge to)
    for (const auto& [a, b] : facts.line_edges) {
      const double da = plane.side(mesh.positions[a]), db = plane.side(mesh.positions[b]);
      if (da * db >= 0) continue;
      const bool a_first = std::abs(da) < std::abs(db) || (std::abs(da) == std::abs(db) && a < b);
      const Index v = a_first ? a : b, w = a_first ? b : a;
      if (near(v)) slides.emplace_back(v, w);
    }
    std::sort(slides.begin(), slides.end());
    std::vector<query::RefinedPlanePoint> to(slides.size());
    parallel_for(0, slides.size(), [&](std::size_t i) {
      const Index v = slides[i].first;
      PatchId used = 0;
      to[i] = refine_crossing(patches, domains, mesh, v, slides[i].second, mesh.vertex_patch[v],
                              plane, tol, used);
    });
    for (std::size_t i = 0; i < slides.size(); ++i) {
      const Index v = slides[i].first;
      // A vertex with two crossing line edges takes the first (lowest neighbour) that converged
      // within half its shortest edge.
      if (snapped[v] || !to[i].converged ||
          norm(to[i].point - mesh.positions[v]) > 0.5 * facts.shortest[v]) {
        continue;
      }
      m.positions[v] = plane.on_plane(to[i].point);
      m.vertex_uv[v] = to[i].uv;
      snapped[v] = 1;
    }
    // A vertex of a line that runs in the plane, a hair off it, goes onto it: a full hull's keel
    // under the centre-plane cut, where the weld averaged the two halves' keel vertices 0.2 mm
    // to either side. Its crossing edges would otherwise all cross within a thousandth of their
    // length of it, and two crossings of one face, refined onto the patch's border in the
    // plane, met at one point (a face with no area). The line runs in the plane through the
    // vertex when it and the other ends of two of its line edges lie within kInPlane of its
    // shortest edge of the plane (a seam leaving the keel there moves as little).
    {
      std::vector<std::uint8_t> in_plane(nv, 0);  // line edges at v whose other end is close
      const auto close = [&](Index v, double scale) {
        return std::abs(plane.side(mesh.positions[v])) <= kInPlane * scale;
      };
      for (const auto& [a, b] : facts.line_edges) {
        if (in_plane[a] < 2 && close(b, facts.shortest[a])) ++in_plane[a];
        if (in_plane[b] < 2 && close(a, facts.shortest[b])) ++in_plane[b];
      }
      parallel_for(0, nv, [&](std::size_t v) {
        if (snapped[v] || in_plane[v] < 2 || !near(Index(v)) ||
            !close(Index(v), facts.shortest[v])) {
          return;
        }
        m.positions[v] = plane.on_plane(m.positions[v]);
        snapped[v] = 1;
      });
    }
    // A vertex inside one smooth patch moves along it: each writes its own slot.
    parallel_for(0, nv, [&](std::size_t v) {
      if (!facts.movable[v] || !near(static_cast<Index>(v))) return;
      const PatchId p = m.vertex_patch[v];
      Vec2d uv = m.vertex_uv[v];
      Vec3d pos = m.positions[v];
      if (snap_onto_plane(patches[p].surface, domains[p], plane, tol, 0.5 * facts.shortest[v], uv,
                          pos)) {
        m.positions[v] = plane.on_plane(pos);
        m.vertex_uv[v] = uv;
        snapped[v] = 1;
      }
    });
  }
  // A vertex within the refinement tolerance of the plane is on it. One left a hair off (a full
  // hull's keel vertices at y = 1e-19 under the centre-plane cut, on lines none of whose edges
  // cross) gave each crossing edge a new vertex where it already was: 661 faces with no area on
  // a full hull with gaps.
  parallel_for(0, nv, [&](std::size_t v) {
    const double d = plane.side(m.positions[v]);
    if (d == 0 || std::abs(d) > tol) return;
    m.positions[v] = plane.on_plane(m.positions[v]);
    snapped[v] = 1;
  });
  auto side = [&](Index v) {
    const double d = plane.side(m.positions[v]);
    return d > 0 ? 1 : (d < 0 ? -1 : 0);
  };

  // Crossing edges (one corner strictly on each side), sorted and unique so that both faces of an
  // edge share its new vertex, each with the lowest patch among its faces (where it is refined).
  std::vector<std::pair<std::uint64_t, PatchId>> cut_edges;
  std::array<std::array<Index, 3>, 2> tris;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const int n = face_triangles(mesh.faces[f], tris);
    for (int t = 0; t < n; ++t) {
      for (int k = 0; k < 3; ++k) {
        const Index a = tris[t][k], b = tris[t][(k + 1) % 3];
        if (side(a) * side(b) < 0) {
          cut_edges.push_back(
              {(std::uint64_t{std::min(a, b)} << 32) | std::max(a, b), mesh.face_patch[f]});
        }
      }
    }
  }
  std::sort(cut_edges.begin(), cut_edges.end());
  cut_edges.erase(std::unique(cut_edges.begin(), cut_edges.end(),
                              [](const auto& x, const auto& y) { return x.first == y.first; }),
                  cut_edges.end());

  // Refine each crossing onto the NURBS, in parallel, own slots.
  const Index first_new = static_cast<Index>(nv);
  m.positions.resize(nv + cut_edges.size());
  m.vertex_uv.resize(nv + cut_edges.size());
  m.vertex_patch.resize(nv + cut_edges.size());
  std::vector<std::uint8_t> missed(cut_edges.size(), 0);
  parallel_for(0, cut_edges.size(), [&](std::size_t e) {
    const Index a = static_cast<Index>(cut_edges[e].first >> 32);
    const Index b = static_cast<Index>(cut_edges[e].first & 0xffffffffu);
    PatchId used = 0;
    const query::RefinedPlanePoint r =
        refine_crossing(patches, domains, m, a, b, cut_edges[e].second, plane, tol, used);
    missed[e] = !r.converged;
    m.positions[first_new + e] = plane.on_plane(r.point);
    m.vertex_uv[first_new + e] = r.uv;
    m.vertex_patch[first_new + e] = used;
  });
  keep_crossings_in_order(mesh, plane, cut_edges, first_new, m, missed);
  // Crossings refined to one point are one vertex: two edges of a face that leave their patch
  // at its corner in the plane, or a crossing that lands on a vertex already there, would
  // otherwise give a face with no area between them (a full round-bilge hull's keel under the
  // centre-plane cut, the property test's seed 1107). Each new vertex takes the lowest index at
  // its point; the vertices already in the mesh keep theirs.
  const std::vector<Index> same_point =
      coincident_crossings(m.positions, first_new, tol, (options.axis + 1) % 3, side);
  auto cut_vertex = [&](Index a, Index b) {
    const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
    const auto it =
        std::lower_bound(cut_edges.begin(), cut_edges.end(), key,
                         [](const auto& entry, std::uint64_t k) { return entry.first < k; });
    return same_point[it - cut_edges.begin()];
  };

  // Split: in face order, each input face gives its kept triangles in a fixed order.
  const bool blocks = mesh.face_block.size() == mesh.faces.size();
  auto emit = [&](std::size_t f, Index a, Index b, Index c) {
    m.faces.push_back({a, b, c, kInvalid});
    m.face_patch.push_back(mesh.face_patch[f]);
    if (blocks) m.face_block.push_back(mesh.face_block[f]);
    out.face_new2old.push_back(static_cast<Index>(f));
  };
  PlaneCutReport& r = out.report;
  r.faces_in = mesh.faces.size();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const int n = face_triangles(mesh.faces[f], tris);
    bool any_above = false, any_below = false;
    for (int t = 0; t < n; ++t) {
      for (Index v : tris[t]) {
        any_above |= side(v) > 0;
        any_below |= side(v) < 0;
      }
    }
    if (!any_below && !options.keep_both) continue;  // above or in the plane: dry
    if (!any_above || !any_below) {
      // Wholly on the kept side: kept as it is (a quad stays a quad).
      m.faces.push_back(mesh.faces[f]);
      m.face_patch.push_back(mesh.face_patch[f]);
      if (blocks) m.face_block.push_back(mesh.face_block[f]);
      out.face_new2old.push_back(static_cast<Index>(f));
      continue;
    }
    ++r.faces_split;
    for (int t = 0; t < n; ++t) {
      const auto& c = tris[t];
      const int s[3] = {side(c[0]), side(c[1]), side(c[2])};
      // The kept side first (below), then with keep_both the other side: -1 keeps side <= 0.
      for (const int keep : {-1, 1}) {
        if (keep == 1 && !options.keep_both) break;
        if (s[0] * keep <= 0 && s[1] * keep <= 0 && s[2] * keep <= 0) continue;  // none kept
        if (s[0] * keep >= 0 && s[1] * keep >= 0 && s[2] * keep >= 0) {
          emit(f, c[0], c[1], c[2]);
          continue;
        }
        // Walk the triangle's boundary in order and keep the polygon on this side of the plane:
        // the corners with side * keep >= 0 and the crossing of every edge that changes sign.
        // It has 3 or 4 corners, in the triangle's winding.
        Index poly[4];
        int count = 0;
        const auto add = [&](Index v) {
          if (count == 0 || poly[count - 1] != v) poly[count++] = v;
        };
        for (int k = 0; k < 3; ++k) {
          const int k1 = (k + 1) % 3;
          if (s[k] * keep >= 0) add(c[k]);
          if (s[k] * s[k1] < 0) add(cut_vertex(c[k], c[k1]));
        }
        if (count > 1 && poly[count - 1] == poly[0]) --count;
        if (count < 3) continue;  // its crossings met at one point: no area
        if (count == 3) {
          emit(f, poly[0], poly[1], poly[2]);
        } else {
          // Split the quad along its shorter diagonal.
          const auto& x = m.positions;
          const bool d02 =
              squared_norm(x[poly[2]] - x[poly[0]]) <= squared_norm(x[poly[3]] - x[poly[1]]);
          if (d02) {
            emit(f, poly[0], poly[1], poly[2]);
            emit(f, poly[0], poly[2], poly[3]);
          } else {
            emit(f, poly[0], poly[1], poly[3]);
            emit(f, poly[1], poly[2], poly[3]);
          }
        }
      }
    }
  }
  r.faces_kept = m.faces.size();
  r.edges_cut = cut_edges.size();
  for (std::uint8_t s : snapped) r.vertices_snapped += s;
  for (std::uint8_t s : missed) r.unconverged += s;

  // Compact: the vertices the kept faces use, in their old order.
  std::vector<Index> vert_old2new(m.positions.size(), kInvalid);
  for (const Face& f : m.faces) {
    for (Index v : f) {
      if (v != kInvalid) vert_old2new[v] = 0;
    }
  }
  Index next = 0;
  for (Index& v : vert_old2new) {
    if (v != kInvalid) v = next++;
  }
  SurfaceMesh compact;
  compact.positions.resize(next);
  compact.vertex_uv.resize(next);
  compact.vertex_patch.resize(next);
  for (std::size_t v = 0; v < vert_old2new.size(); ++v) {
    const Index to = vert_old2new[v];
    if (to == kInvalid) continue;
    compact.positions[to] = m.positions[v];
    compact.vertex_uv[to] = m.vertex_uv[v];
    compact.vertex_patch[to] = m.vertex_patch[v];
  }
  for (Face& f : m.faces) {
    for (Index& v : f) {
      if (v != kInvalid) v = vert_old2new[v];
    }
  }
  compact.faces = std::move(m.faces);
  compact.face_patch = std::move(m.face_patch);
  compact.face_block = std::move(m.face_block);
  m = std::move(compact);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace hm
