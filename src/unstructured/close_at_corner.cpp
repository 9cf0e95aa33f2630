// Close a gap at the corner of its two sides: where two patches meet at a knuckle and a gap
// parts them, the point that closes it lies where their surfaces' planes meet (with the plane of
// a border that turns off there), not on the chamfer between the two receded borders. Used by
// the snap (snap_borders.cpp) for welds of two vertices and for splits.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

// A gap is closed at the corner its two surfaces make when their normals there differ by at
// least this (degrees): the tangent planes then meet in a line near the gap.
constexpr double kCornerMinDeg = 5;
// A border vertex whose two border faces' planes differ by this much (degrees) is on a knuckle of
// its own patch: well above the turn of a curved surface between two faces (a bilge of 2 m
// radius, faces of 0.23 m: 7 degrees), below the knuckle threshold.
constexpr double kBentDeg = 20;
// Weight of the pull towards the members' mean, against the unit normals' planes: it only fixes
// the point along the line the planes meet in (the border's direction).
constexpr double kCornerPull = 1e-4;
// The corner is taken when it lies no farther from the members' mean than this share of their
// spread; otherwise the planes meet too far off (a step, nearly parallel sides) and the mean stays.
constexpr double kCornerReach = 0.6;
// ... and where the gap is at least this share of the border edges there: a narrower one is two
// samplings of one curve a chord error apart (a clean seam at a knuckle), whose vertices lie on
// the curve already.
constexpr double kCornerMinGap = 0.1;
// ... and when it lies at least this share of the border edges from the mean, which tilts the
// faces there by about 0.3 degrees: a smaller move restores no knuckle, and the mean keeps the
// mesh as it was (kcs's bulb, where two patches meet at a 15 degree crease: moves of 1-35 um
// there made one edge of its fine mesh a knuckle, and the structured mesher a block more).
constexpr double kCornerMinMove = 0.005;
// ... and when no member would go back into its own patch by more than this cosine to reach it.
constexpr double kCornerBack = 0.25;

// A side's border runs along the knuckle line when within this cosine of it (about 30 degrees).
constexpr double kAlongKnuckleCos = 0.866;

}  // namespace

// The plane of each border vertex's surface where it ends: the mean of the normals of the faces
// along its border edges. Zero where those faces' planes differ by kBentDeg or more (a patch
// corner on a knuckle of its own, such as a transom's foot at the keel: no one plane holds the
// vertex there). With the ways its border edges run from it.
std::vector<CornerSide> corner_sides(const SurfaceMesh& m, const Border& b,
                                     std::span<const Index> local, std::span<const Vec3d> inward) {
  const double min_cos = std::cos(kBentDeg * std::numbers::pi / 180);
  const std::size_t nb = b.vertices.size();
  std::vector<CornerSide> out(nb);
  std::vector<Vec3d> first(nb, Vec3d{});
  std::vector<std::uint8_t> bent(nb, 0), runs(nb, 0);
  for (const BorderEdge& e : b.edges) {
    const Vec3d f = face_normal(m.positions, m.faces[e.face]);
    for (const Index v : {e.v0, e.v1}) {
      const Index i = local[v];
      // Faces of one patch may arrive turned against each other before orient_faces.
      if (squared_norm(first[i]) == 0) first[i] = f;
      if (std::abs(dot(f, first[i])) < min_cos) bent[i] = 1;
      out[i].n += dot(f, first[i]) < 0 ? -1.0 * f : f;
      if (runs[i] < 2) {
        out[i].along[runs[i]++] = normalized(m.positions[v == e.v0 ? e.v1 : e.v0] - m.positions[v]);
      }
    }
  }
  for (std::size_t i = 0; i < nb; ++i) {
    out[i].p = m.positions[b.vertices[i]];
    out[i].n = bent[i] ? Vec3d{} : normalized(out[i].n);
    out[i].in = inward[i];
  }
  return out;
}

// Where the gap between two sides closes: the point nearest their mean c on the line their
// surfaces' planes meet in, so that two patches meeting at a knuckle across a gap meet at the
// knuckle again, not on a chamfer across it (which halves the knuckle's angle into two creases).
// A side whose border turns off the knuckle there (a patch corner: the side's border runs on
// along the deck, or the centre plane) keeps to that border's line too: the plane through p
// along it and the surface normal (the deck's plane, the centre plane), else the point nearest
// the mean slides off it. The mean where the normals agree (a smooth seam), the gap is a chord
// error wide, the planes meet far off, or a side would go back over its own patch.
Vec3d close_at_corner(const CornerSide (&side)[2], const Vec3d& c, double edge) {
  const CornerSide &a = side[0], &b = side[1];
  if (squared_norm(a.n) == 0 || squared_norm(b.n) == 0) return c;
  const double spread = norm(a.p - b.p);
  const double min_cos = std::cos(kCornerMinDeg * std::numbers::pi / 180);
  if (!(std::abs(dot(a.n, b.n)) < min_cos) || !(spread > 0) || spread < kCornerMinGap * edge) {
    return c;
  }
  // Least squares over the planes, relative to c: (sum n n^T + pull I) d = sum n (n . (q - c)),
  // symmetric positive definite by the pull.
  Eigen::Matrix3d m = kCornerPull * Eigen::Matrix3d::Identity();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  const auto add_plane = [&](const Vec3d& n, const Vec3d& q) {
    const Eigen::Vector3d e(n.x, n.y, n.z);
    m += e * e.transpose();
    r += dot(n, q - c) * e;
  };
  add_plane(a.n, a.p);
  add_plane(b.n, b.p);
  const Vec3d knuckle = normalized(cross(a.n, b.n));
  for (const CornerSide* s : {&a, &b}) {
    // Its border runs along the knuckle line (within about 30 degrees) one way at least; the
    // other way, when it turns off it, gives the border's plane.
    const double c0 = std::abs(dot(s->along[0], knuckle));
    const double c1 = squared_norm(s->along[1]) == 0 ? c0 : std::abs(dot(s->along[1], knuckle));
    if (std::max(c0, c1) < kAlongKnuckleCos) return c;
    if (std::min(c0, c1) >= kAlongKnuckleCos) continue;
    add_plane(normalized(cross(c0 < c1 ? s->along[0] : s->along[1], s->n)), s->p);
  }
  const Eigen::LLT<Eigen::Matrix3d> llt(m);
  if (llt.info() != Eigen::Success) return c;
  const Eigen::Vector3d x = llt.solve(r);
  const Vec3d d{x(0), x(1), x(2)};
  if (!is_finite(d) || !(norm(d) <= kCornerReach * spread) || norm(d) < kCornerMinMove * edge) {
    return c;
  }
  // Each side reaches the corner by going on past its border, not back over its own patch
  // (which would fold its faces).
  for (const CornerSide* s : {&a, &b}) {
    const Vec3d go = c + d - s->p;
    if (dot(go, s->in) > kCornerBack * norm(go)) return c;
  }
  return c + d;
}

}  // namespace hm::merge
