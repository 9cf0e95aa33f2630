// The quality report's driver: adjacency -> per-face -> neighbours -> topology -> waves -> worst.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/bbox.h"
#include "quality/quality_steps.h"

namespace hm {
namespace {

ResolvedSettings resolve(const SurfaceMesh& mesh, const QualityOptions& o) {
  BBox3d box;
  for (const Vec3d& p : mesh.positions) box.add(p);
  ResolvedSettings s;
  s.tol = o.plane_tol * box.diagonal();
  s.waterline_z = o.waterline_z.value_or(box.empty() ? 0.0 : box.hi.z);
  s.uncut = o.uncut;
  s.half_hull = o.half_hull.value_or(!box.empty() && (box.lo.y >= -s.tol || box.hi.y <= s.tol) &&
                                     box.hi.y - box.lo.y > s.tol);
  return s;
}

struct Candidate {
  WorstPanel panel;
  double severity;  // how far past its limit (>= 1), for ordering within a rule
};

// The face's first failing rule in QualityRule order (most serious first), if any.
bool worst_rule(const QualityReport& r, const QualityRules& rules, std::size_t f,
                const std::vector<std::uint8_t>& free_face,
                const std::vector<std::uint8_t>& nonmanifold_face, Candidate& out) {
  const FaceQuality& q = r.per_face;
  auto set = [&](QualityRule rule, double value, double severity) {
    out.panel = {static_cast<Index>(f), q.centroid[f], rule, value};
    out.severity = severity;
    return true;
  };
  const bool quad = q.is_quad[f] != 0;
  if (q.flipped[f] != 0 && r.topology.inconsistent_edges > 0)
    return set(QualityRule::kFlipped, 1, 1);
  if (q.zero_area[f] != 0) return set(QualityRule::kZeroArea, q.area[f], 1);
  if (nonmanifold_face[f]) return set(QualityRule::kNonManifold, 1, 1);
  if (free_face[f]) return set(QualityRule::kFreeEdgeBelowWaterline, 1, 1);
  if (quad && q.convex[f] == 0) return set(QualityRule::kNonConvex, 1, 1);
  if (q.close_centre[f] != 0) return set(QualityRule::kCloseCentre, 1, 1);
  if (quad && q.side_ratio[f] >= rules.max_side_ratio)
    return set(QualityRule::kSideRatio, q.side_ratio[f], q.side_ratio[f] / rules.max_side_ratio);
  if (q.neighbour_area_ratio[f] >= rules.max_area_ratio)
    return set(QualityRule::kAreaRatio, q.neighbour_area_ratio[f],
               q.neighbour_area_ratio[f] / rules.max_area_ratio);
  if (q.neighbour_normal_angle[f] >= rules.max_normal_angle_deg)
    return set(QualityRule::kNormalAngle, q.neighbour_normal_angle[f],
               q.neighbour_normal_angle[f] / rules.max_normal_angle_deg);
  if (quad && q.warp[f] > rules.max_warp)
    return set(QualityRule::kWarp, q.warp[f], q.warp[f] / rules.max_warp);
  if (!quad && q.min_angle_deg[f] < rules.min_triangle_angle_deg)
    return set(QualityRule::kTriangleAngle, q.min_angle_deg[f],
               rules.min_triangle_angle_deg / std::max(q.min_angle_deg[f], 1e-12));
  return false;
}

std::vector<WorstPanel> worst_panels(const QualityReport& r, const QualityOptions& o,
                                     const std::vector<std::uint8_t>& free_face,
                                     const std::vector<std::uint8_t>& nonmanifold_face) {
  std::vector<Candidate> all;
  Candidate c;
  for (std::size_t f = 0; f < r.faces; ++f)
    if (worst_rule(r, o.rules, f, free_face, nonmanifold_face, c)) all.push_back(c);
  auto order = [](const Candidate& a, const Candidate& b) {
    if (a.panel.rule != b.panel.rule) return a.panel.rule < b.panel.rule;
    if (a.severity != b.severity) return a.severity > b.severity;
    return a.panel.face < b.panel.face;
  };
  const std::size_t n = std::min(o.worst_count, all.size());
  std::partial_sort(all.begin(), all.begin() + n, all.end(), order);
  std::vector<WorstPanel> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back(all[i].panel);
  return out;
}

template <class... Args>
std::string fmt(const char* format, Args... args) {
  char buf[160];
  std::snprintf(buf, sizeof buf, format, args...);
  return buf;
}

}  // namespace

const char* to_string(QualityRule r) {
  switch (r) {
    case QualityRule::kFlipped:
      return "flipped";
    case QualityRule::kZeroArea:
      return "zero area";
    case QualityRule::kNonManifold:
      return "non-manifold";
    case QualityRule::kFreeEdgeBelowWaterline:
      return "free edge below waterline";
    case QualityRule::kNonConvex:
      return "non-convex";
    case QualityRule::kCloseCentre:
      return "close centre";
    case QualityRule::kSideRatio:
      return "side ratio";
    case QualityRule::kAreaRatio:
      return "area ratio";
    case QualityRule::kNormalAngle:
      return "normal angle";
    case QualityRule::kWarp:
      return "warp";
    case QualityRule::kTriangleAngle:
      return "triangle angle";
  }
  return "?";
}

QualityReport assess_quality(const SurfaceMesh& mesh, const QualityOptions& o) {
  QualityReport r;
  const ResolvedSettings s = resolve(mesh, o);
  r.half_hull = s.half_hull;
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  measure_faces(mesh, o, r);
  measure_neighbours(mesh, adj, knuckle_mask(adj, r.per_face, o), r);
  std::vector<std::uint8_t> free_face, nonmanifold_face;
  check_topology(mesh, adj, s, r, free_face, nonmanifold_face);
  find_close_centres(o, r);
  r.waves = wave_resolution(mesh, o.waves, s);
  const RuleShares shares = rule_shares(r.per_face, o.rules);
  r.side_ratio_share = shares.side_ratio;
  r.area_ratio_share = shares.area_ratio;
  r.area_ratio_pair_share = area_ratio_pair_share(adj, r.per_face, o.rules.max_area_ratio);
  r.min_angle = angle_distribution(r.per_face.min_angle_deg);
  r.normal_angle_share = shares.normal_angle;
  r.triangle_angle_share = shares.triangle_angle;
  r.worst = worst_panels(r, o, free_face, nonmanifold_face);
  r.crossing_pairs = o.crossing_pairs;
  r.crossing_where = o.crossing_where;
  return r;
}

std::vector<std::string> QualityReport::failures(const QualityRules& rules) const {
  std::vector<std::string> out;
  const RuleShares s = rule_shares(per_face, rules);
  auto share = [&](double got, double need, const char* what) {
    if (got < need) out.push_back(fmt(what, 100 * got, 100 * need));
  };
  share(s.side_ratio, rules.min_side_ratio_share, "quad side ratio: %.2f%% pass, need %.2f%%");
  share(s.area_ratio, rules.min_area_ratio_share, "neighbour area ratio: %.2f%% pass, need %.2f%%");
  share(s.normal_angle, rules.min_normal_angle_share,
        "neighbour normal angle: %.2f%% pass, need %.2f%%");
  share(s.triangle_angle, rules.min_triangle_angle_share,
        "triangle min angle: %.2f%% pass, need %.2f%%");
  if (s.max_warp > rules.max_warp)
    out.push_back(fmt("max warp %.4g > %.4g", s.max_warp, rules.max_warp));
  auto count = [&](bool required, std::size_t n, const char* what) {
    if (required && n > 0) out.push_back(std::to_string(n) + " " + what);
  };
  count(rules.require_convex, non_convex, "non-convex quads");
  count(rules.require_no_zero_area, zero_area, "zero-area panels");
  count(rules.require_no_close_centres, close_centre_pairs, "pairs of very close panel centres");
  count(rules.require_manifold, topology.nonmanifold_edges, "non-manifold edges");
  if (rules.require_no_crossing && crossing_pairs.value_or(0) > 0) {
    out.push_back(fmt("%zu pairs of panels pass through each other (the first near x %.4g, y %.4g",
                      *crossing_pairs, crossing_where.x, crossing_where.y) +
                  fmt(", z %.4g m)", crossing_where.z));
  }
  count(rules.require_consistent_orientation, topology.inconsistent_edges,
        "edges with inconsistent orientation");
  count(rules.require_no_free_edges_below_waterline, topology.free_edges_below,
        topology.uncut ? "free edges off the deck edge and the centre plane (holes)"
                       : "free edges below the waterline");
  if (rules.require_normals_into_fluid && faces > 0 && !topology.normals_into_fluid)
    out.push_back(
        fmt("normals point into the body (enclosed volume %.6g m^3)", topology.enclosed_volume));
  return out;
}

bool QualityReport::passes(const QualityRules& rules) const { return failures(rules).empty(); }

}  // namespace hm
