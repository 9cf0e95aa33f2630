// collect triangles (local frame) -> candidate pairs from their boxes, each decided in double as
// it is found -> the crossing points of the few that cross -> sort and count the face pairs.
#include "query/find_self_intersections.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include "core/bbox.h"
#include "kernels/box_pairs.h"

namespace hm {
namespace {

struct Triangles {
  std::vector<std::array<Vec3d, 3>> corners;  // local frame, m
  std::vector<Index> face;                    // the mesh face each triangle came from
};

Triangles collect_triangles(const SurfaceMesh& mesh, const Vec3d& centre) {
  Triangles t;
  t.corners.reserve(2 * mesh.faces.size());
  t.face.reserve(2 * mesh.faces.size());
  auto add = [&](Index f, Index a, Index b, Index c) {
    t.corners.push_back(
        {mesh.positions[a] - centre, mesh.positions[b] - centre, mesh.positions[c] - centre});
    t.face.push_back(f);
  };
  for (Index f = 0; f < mesh.faces.size(); ++f) {
    const Face& q = mesh.faces[f];
    add(f, q[0], q[1], q[2]);
    if (!is_triangle(q)) add(f, q[0], q[2], q[3]);
  }
  return t;
}

// ---- the decision, triangle against triangle, in double ----------------------------------------

struct Chord {
  double t0 = 0, t1 = 0;  // along the planes' common line
  Vec3d p0, p1;           // the chord's ends
};

// The chord of triangle p on the line with direction dir, from the signed distances d of its
// corners to the other plane (which straddle it).
Chord chord(const std::array<Vec3d, 3>& p, const std::array<double, 3>& d, const Vec3d& dir) {
  Chord c;
  c.t0 = std::numeric_limits<double>::infinity();
  c.t1 = -c.t0;
  auto take = [&](const Vec3d& x) {
    const double t = dot(dir, x);
    if (t < c.t0) c.t0 = t, c.p0 = x;
    if (t > c.t1) c.t1 = t, c.p1 = x;
  };
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (d[i] == 0) take(p[i]);
    if ((d[i] < 0 && d[j] > 0) || (d[i] > 0 && d[j] < 0)) {
      take(p[i] + (d[i] / (d[i] - d[j])) * (p[j] - p[i]));
    }
  }
  return c;
}

// 2D: the signed distance of r from the line through p and q, positive on the left.
double side(const Vec2d& p, const Vec2d& q, const Vec2d& r) {
  const double len = norm(q - p);
  return len > 0 ? cross(q - p, r - p) / len : 0;
}

bool strictly_inside(const std::array<Vec2d, 3>& t, const Vec2d& r, double tol) {
  const double s = cross(t[1] - t[0], t[2] - t[0]) > 0 ? 1 : -1;
  for (int i = 0; i < 3; ++i) {
    if (s * side(t[i], t[(i + 1) % 3], r) <= tol) return false;
  }
  return true;
}

// Coplanar triangles overlap when an edge of one crosses an edge of the other (each beyond tol of
// the other's line) or a corner of one is inside the other by more than tol. Sets where.
bool coplanar_overlap(const std::array<Vec3d, 3>& a, const std::array<Vec3d, 3>& b,
                      const Vec3d& normal, double tol, Vec3d& where) {
  // Drop the normal's largest axis.
  const Vec3d m{std::abs(normal.x), std::abs(normal.y), std::abs(normal.z)};
  const int drop = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  auto flat = [drop](const Vec3d& p) {
    return drop == 0 ? Vec2d{p.y, p.z} : drop == 1 ? Vec2d{p.z, p.x} : Vec2d{p.x, p.y};
  };
  const std::array<Vec2d, 3> a2{flat(a[0]), flat(a[1]), flat(a[2])};
  const std::array<Vec2d, 3> b2{flat(b[0]), flat(b[1]), flat(b[2])};
  for (int i = 0; i < 3; ++i) {
    if (strictly_inside(b2, a2[i], tol)) return where = a[i], true;
    if (strictly_inside(a2, b2[i], tol)) return where = b[i], true;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const double s0 = side(a2[i], a2[i1], b2[j]), s1 = side(a2[i], a2[i1], b2[j1]);
      const double r0 = side(b2[j], b2[j1], a2[i]), r1 = side(b2[j], b2[j1], a2[i1]);
      const bool cross_a = (s0 > tol && s1 < -tol) || (s0 < -tol && s1 > tol);
      const bool cross_b = (r0 > tol && r1 < -tol) || (r0 < -tol && r1 > tol);
      if (cross_a && cross_b) {
        where = a[i] + (r0 / (r0 - r1)) * (a[i1] - a[i]);
        return true;
      }
    }
  }
  return false;
}

bool triangles_cross(const std::array<Vec3d, 3>& a, const std::array<Vec3d, 3>& b, double tol,
                     Vec3d& where) {
  const Vec3d na = cross(a[1] - a[0], a[2] - a[0]);
  const Vec3d nb = cross(b[1] - b[0], b[2] - b[0]);
  const double la = norm(na), lb = norm(nb);
  if (!(la > 0) || !(lb > 0)) return false;  // a zero-area face has no plane to cross
  const Vec3d ua = na / la, ub = nb / lb;
  std::array<double, 3> da{}, db{};  // corners of a from b's plane, and of b from a's
  for (int i = 0; i < 3; ++i) {
    da[i] = dot(ub, a[i] - b[0]);
    db[i] = dot(ua, b[i] - a[0]);
  }
  auto lo = [](const std::array<double, 3>& d) { return std::min({d[0], d[1], d[2]}); };
  auto hi = [](const std::array<double, 3>& d) { return std::max({d[0], d[1], d[2]}); };
  const bool flat_a = std::max(-lo(da), hi(da)) <= tol;
  const bool flat_b = std::max(-lo(db), hi(db)) <= tol;
  if (flat_a && flat_b) return coplanar_overlap(a, b, ub, tol, where);
  if (!(lo(da) < -tol && hi(da) > tol && lo(db) < -tol && hi(db) > tol)) return false;
  const Vec3d dir = cross(ua, ub);
  const double ld = norm(dir);
  if (!(ld > 0)) return false;
  const Vec3d u = dir / ld;
  const Chord ca = chord(a, da, u), cb = chord(b, db, u);
  const double t0 = std::max(ca.t0, cb.t0), t1 = std::min(ca.t1, cb.t1);
  if (!(t1 - t0 > tol)) return false;
  // The middle of the shared part, on a's chord.
  const double span = ca.t1 - ca.t0;
  const double s = span > 0 ? (0.5 * (t0 + t1) - ca.t0) / span : 0.5;
  where = ca.p0 + s * (ca.p1 - ca.p0);
  return true;
}

bool share_a_vertex(const Face& f, const Face& g) {
  for (int i = 0; i < corner_count(f); ++i)
    for (int j = 0; j < corner_count(g); ++j)
      if (f[i] == g[j]) return true;
  return false;
}

}  // namespace

double crossing_tolerance(std::span<const Vec3d> positions) {
  BBox3d box;
  for (const Vec3d& p : positions) box.add(p);
  const Vec3d e = box.extent();
  return 1e-7 * std::max({e.x, e.y, e.z});
}

bool faces_cross(std::span<const Vec3d> positions, const Face& a, const Face& b, double tol) {
  if (share_a_vertex(a, b)) return false;
  // A local frame at a's first corner, as the whole-mesh search centres its box.
  const Vec3d o = positions[a[0]];
  // A face's triangles in that frame, (0, 1, 2) and for a quad (0, 2, 3); returns their count.
  auto triangles = [&](const Face& f, std::array<std::array<Vec3d, 3>, 2>& t) {
    t[0] = {positions[f[0]] - o, positions[f[1]] - o, positions[f[2]] - o};
    if (is_triangle(f)) return 1;
    t[1] = {positions[f[0]] - o, positions[f[2]] - o, positions[f[3]] - o};
    return 2;
  };
  std::array<std::array<Vec3d, 3>, 2> ta, tb;
  const int na = triangles(a, ta), nb = triangles(b, tb);
  Vec3d where;
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j)
      if (triangles_cross(ta[i], tb[j], tol, where)) return true;
  return false;
}

SelfIntersections find_self_intersections(const SurfaceMesh& mesh, double tol,
                                          std::size_t max_listed) {
  SelfIntersections out;
  if (mesh.faces.size() < 2) return out;
  BBox3d box;
  for (const Vec3d& p : mesh.positions) box.add(p);
  const Triangles tris = collect_triangles(mesh, box.center());

  // Exact boxes, in double: two triangles whose boxes do not meet cannot cross.
  std::vector<Vec3d> lo(tris.corners.size()), hi(tris.corners.size());
  for (std::size_t t = 0; t < lo.size(); ++t) {
    BBox3d b;
    for (const Vec3d& p : tris.corners[t]) b.add(p);
    lo[t] = b.lo;
    hi[t] = b.hi;
  }
  const auto crossing = [&](Index a, Index b, Vec3d& where) {
    const Index fa = tris.face[a], fb = tris.face[b];
    if (fa == fb || share_a_vertex(mesh.faces[fa], mesh.faces[fb])) return false;
    return triangles_cross(tris.corners[a], tris.corners[b], tol, where);
  };
  const std::vector<std::array<Index, 2>> hits =
      overlapping_box_pairs(lo, hi, [&](Index a, Index b) {
        Vec3d where;
        return crossing(a, b, where);
      });

  // Face pairs, in a fixed order whatever order the threads found them in.
  std::vector<FaceCrossing> faces;
  faces.reserve(hits.size());
  for (const auto& [a, b] : hits) {
    Vec3d where;
    crossing(a, b, where);  // again, for the point: crossings are few
    Index fa = tris.face[a], fb = tris.face[b];
    if (fa > fb) std::swap(fa, fb);
    faces.push_back({fa, fb, where + box.center()});
  }
  auto key = [](const FaceCrossing& c) { return std::make_tuple(c.face_a, c.face_b); };
  std::sort(faces.begin(), faces.end(), [&](const FaceCrossing& x, const FaceCrossing& y) {
    if (key(x) != key(y)) return key(x) < key(y);
    return std::tie(x.where.x, x.where.y, x.where.z) < std::tie(y.where.x, y.where.y, y.where.z);
  });
  faces.erase(
      std::unique(faces.begin(), faces.end(),
                  [&](const FaceCrossing& x, const FaceCrossing& y) { return key(x) == key(y); }),
      faces.end());
  out.count = faces.size();
  faces.resize(std::min(faces.size(), max_listed));
  out.first = std::move(faces);
  return out;
}

}  // namespace hm
