// Mesh hydrostatics: clip panels at the waterplane, integrate exactly on flat triangles, chain the
// waterline section and take its area moments by Green's theorem.
#include "quality/hydrostatics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/bbox.h"
#include "core/parallel.h"
#include "quality/hydrostatic_sums.h"

namespace hm {
namespace {

// A clipped-polygon vertex: an original vertex (a == b) or the crossing on the edge a-b (a < b).
struct ClipVertex {
  Index a, b;
  Vec3d p;
  bool on_plane;
  std::uint64_t key() const { return (std::uint64_t{a} << 32) | b; }
};

struct Clipper {
  std::span<const Vec3d> positions;
  double z0;
  double tol;

  int side(Index v) const {
    const double d = positions[v].z - z0;
    return d < -tol ? -1 : (d > tol ? 1 : 0);
  }
  // Crossing on the edge (a, b), computed from the lower index so that both faces sharing the
  // edge get the same bits.
  ClipVertex crossing(Index a, Index b) const {
    if (b < a) std::swap(a, b);
    const Vec3d& pa = positions[a];
    const Vec3d& pb = positions[b];
    const double t = (z0 - pa.z) / (pb.z - pa.z);
    Vec3d p = pa + t * (pb - pa);
    p.z = z0;
    return {a, b, p, true};
  }
  // Sutherland-Hodgman of the triangle against z <= z0 (vertices on the plane are kept).
  int clip(const std::array<Index, 3>& t, std::array<ClipVertex, 4>& out) const {
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const Index c = t[i], d = t[(i + 1) % 3];
      const int sc = side(c), sd = side(d);
      if (sc <= 0) out[n++] = {c, c, positions[c], sc == 0};
      if (sc * sd < 0) out[n++] = crossing(c, d);
    }
    return n >= 3 ? n : 0;
  }
};

// Exact integrals of the degree <= 2 integrands over the flat triangle (p0, p1, p2).
void add_triangle(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2, double z0,
                  SurfaceIntegrals& s) {
  const Vec3d a = 0.5 * cross(p1 - p0, p2 - p0);
  const Vec3d m[3] = {0.5 * (p0 + p1), 0.5 * (p1 + p2), 0.5 * (p2 + p0)};
  // Edge-midpoint rule: exact for quadratics on a triangle.
  auto mean = [&](auto f) { return (f(m[0]) + f(m[1]) + f(m[2])) / 3.0; };
  using I = SurfaceIntegrals;
  s.v[I::kArea] += norm(a);
  s.v[I::kVolume] += a.z * mean([&](const Vec3d& p) { return p.z - z0; });
  s.v[I::kMx] += a.z * mean([&](const Vec3d& p) { return p.x * (p.z - z0); });
  s.v[I::kMy] += a.z * mean([&](const Vec3d& p) { return p.y * (p.z - z0); });
  s.v[I::kMz] += a.z * mean([&](const Vec3d& p) { return 0.5 * (p.z * p.z - z0 * z0); });
  s.v[I::kAwp] -= a.z;
  s.v[I::kSx] -= a.z * mean([](const Vec3d& p) { return p.x; });
  s.v[I::kSy] -= a.z * mean([](const Vec3d& p) { return p.y; });
  s.v[I::kSxx] -= a.z * mean([](const Vec3d& p) { return p.x * p.x; });
  s.v[I::kSyy] -= a.z * mean([](const Vec3d& p) { return p.y * p.y; });
}

// The face as triangles 0-1-2 and 0-2-3 (as face_area splits a quad).
int face_triangles(const Face& f, std::array<std::array<Index, 3>, 2>& t) {
  t[0] = {f[0], f[1], f[2]};
  if (is_triangle(f)) return 1;
  t[1] = {f[0], f[2], f[3]};
  return 2;
}

bool is_lid(const Clipper& c, const Face& f) {
  for (int i = 0; i < corner_count(f); ++i)
    if (c.side(f[i]) != 0) return false;
  return true;
}

struct DirectedEdge {
  std::uint64_t tail, head;
  Vec3d pt, ph;
};

// The wet panels' edges lying in the waterplane, as their faces traverse them, with pairs used in
// both directions (inside a flat region in the plane) cancelled.
std::vector<DirectedEdge> waterline_edges(const SurfaceMesh& mesh, const Clipper& c) {
  std::vector<DirectedEdge> edges;
  for (const Face& f : mesh.faces) {
    bool touches = false;
    for (int i = 0; i < corner_count(f); ++i) touches |= c.side(f[i]) >= 0;
    if (!touches || is_lid(c, f)) continue;
    std::array<std::array<Index, 3>, 2> tris;
    const int nt = face_triangles(f, tris);
    for (int k = 0; k < nt; ++k) {
      std::array<ClipVertex, 4> poly;
      const int n = c.clip(tris[k], poly);
      for (int i = 0; i < n; ++i) {
        const ClipVertex& p = poly[i];
        const ClipVertex& q = poly[(i + 1) % n];
        if (p.on_plane && q.on_plane && p.key() != q.key())
          edges.push_back({p.key(), q.key(), p.p, q.p});
      }
    }
  }
  // Cancel opposite pairs: group by the undirected key, keep the net surplus direction.
  auto undirected = [](const DirectedEdge& e) {
    return std::pair{std::min(e.tail, e.head), std::max(e.tail, e.head)};
  };
  std::stable_sort(edges.begin(), edges.end(), [&](const DirectedEdge& x, const DirectedEdge& y) {
    return undirected(x) < undirected(y);
  });
  std::vector<DirectedEdge> net;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int balance = 0;
    for (; j < edges.size() && undirected(edges[j]) == undirected(edges[i]); ++j)
      balance += edges[j].tail < edges[j].head ? 1 : -1;
    for (std::size_t k = i; k < j && balance != 0; ++k) {
      const int dir = edges[k].tail < edges[k].head ? 1 : -1;
      if (dir * balance > 0) {
        net.push_back(edges[k]);
        balance -= dir;
      }
    }
    i = j;
  }
  return net;
}

// Chains directed edges head to tail: open chains first (from tails no edge enters), then loops.
std::vector<std::vector<Vec3d>> chain(const std::vector<DirectedEdge>& e, std::size_t& open) {
  std::vector<std::pair<std::uint64_t, std::size_t>> out(e.size()), in(e.size());
  for (std::size_t i = 0; i < e.size(); ++i) {
    out[i] = {e[i].tail, i};
    in[i] = {e[i].head, i};
  }
  std::sort(out.begin(), out.end());
  std::sort(in.begin(), in.end());
  std::vector<bool> used(e.size(), false);
  auto find = [](const auto& v, std::uint64_t key) {
    return std::lower_bound(v.begin(), v.end(), std::pair<std::uint64_t, std::size_t>{key, 0});
  };
  auto next = [&](std::uint64_t key) -> std::size_t {
    for (auto it = find(out, key); it != out.end() && it->first == key; ++it)
      if (!used[it->second]) return it->second;
    return e.size();
  };
  std::vector<std::vector<Vec3d>> chains;
  open = 0;
  auto walk = [&](std::size_t start) {
    std::vector<Vec3d> pts;
    std::size_t cur = start;
    bool closed = false;
    while (cur < e.size()) {
      used[cur] = true;
      pts.push_back(e[cur].pt);
      if (e[cur].head == e[start].tail) {
        closed = true;
        break;
      }
      const std::size_t nx = next(e[cur].head);
      if (nx == e.size()) pts.push_back(e[cur].ph);
      cur = nx;
    }
    if (!closed) ++open;
    chains.push_back(std::move(pts));
  };
  for (std::size_t i = 0; i < e.size(); ++i) {
    auto it = find(in, e[i].tail);
    if (!used[i] && (it == in.end() || it->first != e[i].tail)) walk(i);
  }
  for (std::size_t i = 0; i < e.size(); ++i)
    if (!used[i]) walk(i);
  return chains;
}

// Area moments of a closed polygon (the last point joins the first) by Green's theorem, for the
// counter-clockwise orientation seen from +z. The closing segment of a half-hull chain lies on
// y = 0, where every term below vanishes (c = x_i y_j - x_j y_i = 0).
void add_polygon(const std::vector<Vec3d>& pts, double sign, WaterplaneMoments& w) {
  for (std::size_t i = 0, n = pts.size(); i < n; ++i) {
    const Vec3d& p = pts[i];
    const Vec3d& q = pts[(i + 1) % n];
    const double c = sign * (p.x * q.y - q.x * p.y);
    w.area += c / 2;
    w.sx += c * (p.x + q.x) / 6;
    w.sy += c * (p.y + q.y) / 6;
    w.sxx += c * (p.x * p.x + p.x * q.x + q.x * q.x) / 12;
    w.syy += c * (p.y * p.y + p.y * q.y + q.y * q.y) / 12;
  }
}

}  // namespace

Vec3d FloatingTransform::rotate(const Vec3d& p) const {
  const auto& r = rotation;
  return {r[0] * p.x + r[1] * p.y + r[2] * p.z, r[3] * p.x + r[4] * p.y + r[5] * p.z,
          r[6] * p.x + r[7] * p.y + r[8] * p.z};
}

Placement floating_placement(double draft, double trim_deg, double heel_deg, double baseline_z,
                             double pivot_x) {
  const double th = trim_deg * std::numbers::pi / 180, ph = heel_deg * std::numbers::pi / 180;
  const double ct = std::cos(th), st = std::sin(th), cp = std::cos(ph), sp = std::sin(ph);
  // R = R_trim * R_heel; R_heel = [[1,0,0],[0,cp,-sp],[0,sp,cp]], R_trim = [[ct,0,st],[0,1,0],
  // [-st,0,ct]] (a point ahead of the pivot goes down for positive trim).
  Placement out;
  out.transform.rotation = {ct, st * sp, st * cp, 0, cp, -sp, -st, ct * sp, ct * cp};
  const Vec3d pivot{pivot_x, 0, baseline_z + draft};
  out.transform.translation = pivot - out.transform.rotate(pivot);
  out.waterline_z = baseline_z + draft;
  return out;
}

SurfaceMesh transformed(const SurfaceMesh& mesh, const FloatingTransform& t) {
  SurfaceMesh out = mesh;
  for (Vec3d& p : out.positions) p = t(p);
  return out;
}

std::vector<Patch> transformed(std::span<const Patch> patches, const FloatingTransform& t) {
  std::vector<Patch> out(patches.begin(), patches.end());
  for (Patch& p : out)
    for (Vec3d& c : p.surface.points) c = t(c);
  return out;
}

Hydrostatics finish_hydrostatics(const SurfaceIntegrals& s, const WaterplaneMoments& w,
                                 bool half_hull) {
  using I = SurfaceIntegrals;
  const double k = half_hull ? 2.0 : 1.0;
  Hydrostatics h;
  h.volume = k * s.v[I::kVolume];
  h.wetted_area = k * s.v[I::kArea];
  h.waterplane_area = k * w.area;
  if (s.v[I::kVolume] != 0) {
    h.buoyancy_centre = {s.v[I::kMx] / s.v[I::kVolume],
                         half_hull ? 0.0 : s.v[I::kMy] / s.v[I::kVolume],
                         s.v[I::kMz] / s.v[I::kVolume]};
  }
  if (w.area != 0) {
    h.flotation_centre = {w.sx / w.area, half_hull ? 0.0 : w.sy / w.area};
    const double xf = h.flotation_centre.x, yf = h.flotation_centre.y;
    // Parallel-axis theorem; a half hull's I_T is about the centre plane, doubled.
    h.i_transverse = half_hull ? 2 * w.syy : w.syy - w.area * yf * yf;
    h.i_longitudinal = k * (w.sxx - w.area * xf * xf);
  }
  if (h.volume != 0) {
    h.bm_transverse = h.i_transverse / h.volume;
    h.bm_longitudinal = h.i_longitudinal / h.volume;
  }
  return h;
}

Hydrostatics hydrostatics_mesh(const SurfaceMesh& mesh, const FloatingPosition& position,
                               const MeshHydrostaticsOptions& options) {
  BBox3d box;
  for (const Vec3d& p : mesh.positions) box.add(p);
  const Clipper clip{mesh.positions, position.waterline_z, options.on_plane_tol * box.diagonal()};
  // Per-face slots, summed in face order: the same bits for any thread count.
  std::vector<SurfaceIntegrals> per_face(mesh.faces.size());
  std::vector<std::uint8_t> lid(mesh.faces.size(), 0);
  parallel_for(0, mesh.faces.size(), [&](std::size_t fi) {
    const Face& f = mesh.faces[fi];
    if (is_lid(clip, f)) {
      lid[fi] = 1;
      return;
    }
    std::array<std::array<Index, 3>, 2> tris;
    const int nt = face_triangles(f, tris);
    for (int k = 0; k < nt; ++k) {
      std::array<ClipVertex, 4> poly;
      const int n = clip.clip(tris[k], poly);
      for (int i = 1; i + 1 < n; ++i)
        add_triangle(poly[0].p, poly[i].p, poly[i + 1].p, position.waterline_z, per_face[fi]);
    }
  });
  SurfaceIntegrals sum;
  for (const SurfaceIntegrals& s : per_face) sum += s;

  std::size_t open = 0;
  std::vector<std::vector<Vec3d>> chains = chain(waterline_edges(mesh, clip), open);
  // The waterline polygon gives the exact section where it closes: loops, and for a half hull
  // chains from the centre plane to the centre plane. Where a chain breaks off elsewhere (a
  // file's open transom), its closing segment would cut across the waterplane; the fluxes through
  // the wetted panels (the same figures as the polygon's on a closed hull) stand in for it.
  const double on_centre = 1e-6 * box.diagonal();
  bool sound = true;
  for (std::size_t c = 0; c < open && c < chains.size(); ++c) {
    sound = sound && position.half_hull && std::abs(chains[c].front().y) <= on_centre &&
            std::abs(chains[c].back().y) <= on_centre;
  }
  WaterplaneMoments w;
  if (sound) {
    for (const std::vector<Vec3d>& c : chains) add_polygon(c, -1.0, w);  // clockwise from above
  } else {
    using I = SurfaceIntegrals;
    w = {sum.v[I::kAwp], sum.v[I::kSx], sum.v[I::kSy], sum.v[I::kSxx], sum.v[I::kSyy]};
  }
  Hydrostatics h = finish_hydrostatics(sum, w, position.half_hull);
  h.waterplane_from_fluxes = !sound;
  h.open_waterline_chains = open;
  // Repeat the first point: each polyline is explicitly closed (for a half hull an open chain's
  // closing segment lies on the centre plane).
  for (std::vector<Vec3d>& c : chains)
    if (c.size() > 1) c.push_back(c.front());
  h.waterline = std::move(chains);
  for (std::uint8_t l : lid) h.lid_faces += l;
  return h;
}

}  // namespace hm
