// Station planning: where the rows go. A node that walks one panel size along the hull, normal to
// its row, must reach the next station, so stations crowd where the hull turns away from x (the
// stem, a bulb, a sonar dome, the forefoot) and keep the panel length x elsewhere. Sampled
// sections estimate that walk; stations are then placed by equidistribution between the border
// stations (the ends and the cut stations), which are fixed first.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"
#include "structured/nearest_on_lines.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// At most this many points of a sampled section take part in the walk estimate.
constexpr std::size_t kWalkPoints = 48;
// A station step never falls below this share of the panel length in x: beyond it, the ends
// are left to the caps.
constexpr double kMinStepShare = 0.2;
// Automatic cuts make blocks at least this many panel lengths long.
constexpr double kMinBlockPanels = 3;
// How fast the station spacing may grow along x (m per m).
constexpr double kGrading = 0.3;
// A cut station taken from a vertex's x sits this far (relative to L) beside it.
constexpr double kOffVertex = 1e-5;

struct Sample {
  double x = 0;
  std::vector<Vec3d> points;              // subsampled section points, every polyline
  std::vector<std::vector<Vec3d>> lines;  // the section polylines, whole
  NearestOnLines grid;                    // of lines
  bool empty() const { return points.empty(); }
};

std::vector<Sample> sample_sections(const HullQuery& query, double x0, double x1,
                                    std::size_t count) {
  std::vector<Plane> planes(count);
  std::vector<Sample> samples(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double x = x0 + (x1 - x0) * (static_cast<double>(k) + 0.5) / static_cast<double>(count);
    samples[k].x = x;
    planes[k] = Plane{{x, 0, 0}, {1, 0, 0}};
  }
  SectionOptions so;
  so.refine = false;  // a planning estimate: the triangulation is within its chord error
  const std::vector<Section> secs = query.sections(planes, so);
  parallel_for_each_item(count, [&](std::size_t k) {
    std::size_t total = 0;
    for (const SectionPolyline& pl : secs[k].polylines) total += pl.points.size();
    const std::size_t stride = std::max<std::size_t>(1, total / kWalkPoints);
    std::size_t i = 0;
    for (const SectionPolyline& pl : secs[k].polylines) {
      std::vector<Vec3d>& line = samples[k].lines.emplace_back();
      for (const SectionPoint& sp : pl.points) {
        line.push_back(sp.point);
        if (i++ % stride == 0) samples[k].points.push_back(sp.point);
      }
      if (pl.closed && !pl.points.empty()) line.push_back(pl.points.front().point);
    }
    samples[k].grid.build(samples[k].lines);
  });
  return samples;
}

// How far in x a node of sample a gets when it walks one panel size towards sample b: the
// smallest ratio of x advance to walked (metric) length over a's points.
double walk_step(const Sample& a, const Sample& b, const Metric& metric) {
  double step = std::numeric_limits<double>::infinity();
  const double dx = std::abs(b.x - a.x);
  for (const Vec3d& p : a.points) {
    const double best = metric.length(p, b.grid.nearest(p));
    if (best > 0 && std::isfinite(best)) step = std::min(step, dx / best);
  }
  return step;
}

// The largest lateral move of a's points to b's, per metre of x: near zero in the parallel
// middle body.
double section_change(const Sample& a, const Sample& b) {
  double worst = 0;
  for (const Vec3d& p : a.points) {
    const Vec3d q = b.grid.nearest(p);
    worst = std::max(worst, std::hypot(q.y - p.y, q.z - p.z));
  }
  return worst / std::max(std::abs(b.x - a.x), 1e-300);
}

// How transverse a fine triangle must be to count as part of an end face: its unit normal's x.
constexpr double kTransverse = 0.95;
// An end face reaching farther from its end than this share of the length is no transom: the
// stations are left to cut it rather than lose the hull's ends to the caps.
constexpr double kMaxEndReach = 0.1;

// How far the flat transverse faces at the hull's ends (a transom, raked, or leaning with trim)
// reach along x: [0] the largest x of those at the aft end (low x), [1] the smallest of those at
// the fore end; -inf and +inf where there is none. An end face is a set of fine triangles within
// kTransverse of x, joined at their corners, one of which lies within `reach` of the end and one
// on a knuckle (a transom's edge: the blunt nose of a bulb or a sonar dome, smooth, is no end
// face). A station inside that reach cuts the face in a row lying across it, which the next
// station's row cannot be zipped to (a chine hull's transom at 1 degree of trim and 6,000 panels).
std::array<double, 2> end_faces(const SurfaceMesh& surface, const FeatureSet& features,
                                const BBox3d& box, double reach) {
  const std::size_t nv = surface.vertex_count();
  std::vector<Index> parent(nv);
  for (std::size_t v = 0; v < nv; ++v) parent[v] = static_cast<Index>(v);
  auto root = [&](Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<std::uint8_t> on_face(nv, 0);
  for (const Face& f : surface.faces) {
    if (std::abs(face_normal(surface.positions, f).x) < kTransverse) continue;
    const int n = corner_count(f);
    for (int c = 0; c < n; ++c) {
      on_face[f[c]] = 1;
      const Index a = root(f[c]), b = root(f[(c + 1) % n]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  // The components with a corner near each end (bit 0: aft, bit 1: fore) and on a knuckle (bit 2).
  std::vector<std::uint8_t> kind(nv, 0);
  for (const FeatureLine& l : features.knuckles) {
    for (Index v : l.vertices)
      if (on_face[v]) kind[root(v)] |= 4;
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (!on_face[v]) continue;
    const double x = surface.positions[v].x;
    if (x < box.lo.x + reach) kind[root(static_cast<Index>(v))] |= 1;
    if (x > box.hi.x - reach) kind[root(static_cast<Index>(v))] |= 2;
  }
  std::array<double, 2> out{-std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity()};
  for (std::size_t v = 0; v < nv; ++v) {
    if (!on_face[v]) continue;
    const std::uint8_t k = kind[root(static_cast<Index>(v))];
    const std::uint8_t e = k & 4 ? k : 0;
    const double x = surface.positions[v].x;
    if (e & 1) out[0] = std::max(out[0], x);
    if (e & 2) out[1] = std::min(out[1], x);
  }
  const double far = kMaxEndReach * (box.hi.x - box.lo.x);
  if (out[0] > box.lo.x + far) out[0] = -std::numeric_limits<double>::infinity();
  if (out[1] < box.hi.x - far) out[1] = std::numeric_limits<double>::infinity();
  return out;
}

// Adds x to cuts unless a cut lies within `gap` already.
void add_cut(std::vector<double>& cuts, double x, double gap) {
  for (double c : cuts)
    if (std::abs(c - x) < gap) return;
  cuts.push_back(x);
}

// The caller's stations on this surface: those more than kMinStepShare of a panel inside its x
// ends; the first and last kept become border stations (the caps take what lies beyond).
StationPlan given_stations(const BBox3d& box, double hx, const StructuredOptions& options) {
  StationPlan plan;
  const double lo = box.lo.x + kMinStepShare * hx, hi = box.hi.x - kMinStepShare * hx;
  for (std::size_t k = 0; k < options.station_x.size(); ++k) {
    const double x = options.station_x[k];
    if (!(x > lo && x < hi)) continue;
    plan.x.push_back(x);
    plan.border.push_back(k < options.station_border.size() ? options.station_border[k] : 0);
  }
  if (plan.x.size() < 2) throw GeometryError("structured: no given station cuts the hull");
  plan.border.front() = plan.border.back() = 1;
  for (std::size_t k = 1; k + 1 < plan.x.size(); ++k) plan.cuts += plan.border[k];
  return plan;
}

// A turn counts when both its branches run at least this share of the panel length away from it
// in x: a step's edge standing at one x (ship_449's forecastle break, classed
// a transom edge) has its least x anywhere along it.
constexpr double kTurnReach = 0.2;
// A station nearer a transom turn than this share of its spacing moves to that distance from it,
// on the side it was on. Of 0.25, 0.33, 0.4 and 0.5, 0.4 and 0.5 did best on DTMB 5415 at 11
// sizes from 1,600 to 8,000 panels; a turn moved a few millimetres off the true one did worse
// than none (see README, Stations).
constexpr double kTurnClear = 0.4;
// The same for a turn of the centre-plane profile (a stem's notch above a bulb or a sonar dome, a
// stern's above a skeg): there the sliver is only where the station passes the notch within a few
// millimetres (DTMB 5415 at 0.29-0.33 m: a station 1.6 mm aft of the stem's notch, and panels of
// the strip and of the fan over the notch through each other; ship_449_patches at 7.629 m and
// 6,000 panels: 221 pairs at its stern's shelf). Moving stations 0.4 of their spacing took up to
// 0.7 points off the area-rule share on kcs and DTMB 5415; 0.1 mends the same cases and moves
// next to nothing else.
constexpr double kProfileClear = 0.1;

}  // namespace

std::vector<BoundaryTurn> profile_turns(std::span<const Vec3d> p, bool closed, double need) {
  std::vector<BoundaryTurn> out;
  const std::size_t n = p.size();
  auto at = [&](std::ptrdiff_t i) {
    const std::ptrdiff_t m = static_cast<std::ptrdiff_t>(n);
    return p[static_cast<std::size_t>(((i % m) + m) % m)].x;
  };
  double x_lo = p[0].x, x_hi = p[0].x;
  for (const Vec3d& q : p) {
    x_lo = std::min(x_lo, q.x);
    x_hi = std::max(x_hi, q.x);
  }
  for (std::size_t t = closed ? 0 : 1; t + (closed ? 0 : 1) < n; ++t) {
    const double xt = p[t].x;
    // The profile's own ends are the hull's: no station lies beyond them.
    if (xt <= x_lo || xt >= x_hi) continue;
    for (int side : {+1, -1}) {
      // x leaves xt towards `side` along both branches, each at least `need` before it comes
      // back past xt.
      auto branch = [&](std::ptrdiff_t dir) {
        double reach = 0;
        for (std::size_t k = 1; k < n; ++k) {
          const std::ptrdiff_t i =
              static_cast<std::ptrdiff_t>(t) + dir * static_cast<std::ptrdiff_t>(k);
          if (!closed && (i < 0 || i >= static_cast<std::ptrdiff_t>(n))) break;
          const double d = side * (at(i) - xt);
          if (d < 0) break;
          reach = std::max(reach, d);
          if (reach >= need) break;
        }
        return reach;
      };
      const std::ptrdiff_t ti = static_cast<std::ptrdiff_t>(t);
      if (side * (at(ti - 1) - xt) < 0 || side * (at(ti + 1) - xt) < 0) continue;
      if (std::min(branch(-1), branch(+1)) >= need) out.push_back({xt, side, kProfileClear});
    }
  }
  // A notch standing at one x has every vertex of it a turn.
  std::sort(out.begin(), out.end(), [](const BoundaryTurn& a, const BoundaryTurn& b) {
    return a.x != b.x ? a.x < b.x : a.side < b.side;
  });
  out.erase(std::unique(out.begin(), out.end(),
                        [](const BoundaryTurn& a, const BoundaryTurn& b) {
                          return a.x == b.x && a.side == b.side;
                        }),
            out.end());
  return out;
}

std::vector<BoundaryTurn> transom_turns(const SurfaceMesh& surface, const FeatureSet& features,
                                        double hx) {
  std::vector<BoundaryTurn> out;
  for (const BoundaryRun& run : features.boundaries) {
    if (run.kind != BoundaryKind::kTransomEdge || run.closed || run.vertices.size() < 3) continue;
    auto x_at = [&](std::size_t i) { return surface.positions[run.vertices[i]].x; };
    const std::size_t last = run.vertices.size() - 1;
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 1; i <= last; ++i) {
      if (x_at(i) < x_at(lo)) lo = i;
      if (x_at(i) > x_at(hi)) hi = i;
    }
    // How far the nearer-reaching branch runs from vertex t, in x towards `side`.
    auto reach = [&](std::size_t t, int side) {
      double a = 0, b = 0;
      for (std::size_t i = 0; i < t; ++i) a = std::max(a, side * (x_at(i) - x_at(t)));
      for (std::size_t i = t + 1; i <= last; ++i) b = std::max(b, side * (x_at(i) - x_at(t)));
      return std::min(a, b);
    };
    const double need = kTurnReach * hx;
    if (lo != 0 && lo != last && reach(lo, +1) >= need) out.push_back({x_at(lo), +1, kTurnClear});
    if (hi != 0 && hi != last && reach(hi, -1) >= need) out.push_back({x_at(hi), -1, kTurnClear});
  }
  return out;
}

std::vector<BoundaryTurn> centre_plane_turns(const SurfaceMesh& surface, const FeatureSet& features,
                                             double hx) {
  std::vector<BoundaryTurn> out;
  std::vector<Vec3d> points;
  for (const BoundaryRun& run : features.boundaries) {
    if (run.kind != BoundaryKind::kCentrePlane || run.vertices.size() < 3) continue;
    points.clear();
    for (Index v : run.vertices) points.push_back(surface.positions[v]);
    for (const BoundaryTurn& turn : profile_turns(points, run.closed, kTurnReach * hx))
      out.push_back(turn);
  }
  return out;
}

void keep_clear_of_turns(std::span<const BoundaryTurn> turns, StationPlan& plan) {
  for (const BoundaryTurn& t : turns) {
    for (std::size_t k = 1; k + 1 < plan.x.size(); ++k) {
      if (plan.border[k]) continue;
      const double w = t.clear * std::min(plan.x[k] - plan.x[k - 1], plan.x[k + 1] - plan.x[k]);
      const double d = (plan.x[k] - t.x) * t.side;  // > 0: where the hull is in two
      if (d > 0 && d < w) {
        plan.x[k] = t.x + t.side * w;
      } else if (d <= 0 && d > -w) {
        plan.x[k] = t.x - t.side * w;
      }
    }
  }
}

StationPlan plan_stations(const HullQuery& query, const FeatureSet& features,
                          const SurfaceMesh& surface, const Metric& metric,
                          const StructuredOptions& options) {
  const BBox3d box = query.bbox();
  const double length = box.hi.x - box.lo.x;
  if (!(length > 0)) throw GeometryError("structured: the hull has no length along x");
  const double hx = metric.size.x;
  if (!options.station_x.empty()) return given_stations(box, hx, options);
  const std::size_t count =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(4 * length / hx)), 64, 4000);
  const std::vector<Sample> samples = sample_sections(query, box.lo.x, box.hi.x, count);
  const double dxs = (box.hi.x - box.lo.x) / static_cast<double>(count);  // sample spacing

  // The ends: the first and last samples that cut the hull.
  std::size_t first = 0, last = count;
  while (first < count && samples[first].empty()) ++first;
  while (last > first && samples[last - 1].empty()) --last;
  if (last - first < 2) throw GeometryError("structured: no station plane cuts the hull");

  // Step limit at each sample (m of x per panel), from the walk to the next sample.
  std::vector<double> step(count, hx);
  parallel_for(
      first, last - 1,
      [&](std::size_t k) {
        const double size_x = metric.size_at(samples[k].points.front()).x;
        const double w = std::min(walk_step(samples[k], samples[k + 1], metric),
                                  walk_step(samples[k + 1], samples[k], metric));
        step[k] = std::clamp(std::isfinite(w) ? w : size_x, kMinStepShare * size_x, size_x);
      },
      4, 16);
  step[last - 1] = step[last - 2];
  // Graded: the spacing grows by at most kGrading per metre of x either way, so neighbouring
  // strips differ in width by under a third and the area-ratio rule holds across rows.
  for (std::size_t k = first + 1; k < last; ++k)
    step[k] = std::min(step[k], step[k - 1] + kGrading * dxs);
  for (std::size_t k = last - 1; k-- > first;)
    step[k] = std::min(step[k], step[k + 1] + kGrading * dxs);

  // The end stations: about one panel in from the ends (the caps take that panel), and never
  // beyond the last sample that cuts the hull.
  // They also stay a fifth of a panel clear of an end face's reach.
  const std::array<double, 2> faces = end_faces(surface, features, box, kMinStepShare * hx);
  const double x_first =
      std::max({samples[first].x, box.lo.x + step[first], faces[0] + kMinStepShare * hx});
  const double x_last =
      std::min({samples[last - 1].x, box.hi.x - step[last - 1], faces[1] - kMinStepShare * hx});
  if (!(x_last > x_first)) throw GeometryError("structured: the hull is shorter than one panel");
  // Cut stations: the user's x planes, then the automatic ones.
  // Cuts closer than this merge: a block is at least a few panels long.
  const double gap = kMinBlockPanels * hx;
  std::vector<double> cuts;
  for (const BlockPlane& p : options.planes) {
    const Vec3d n = normalized(p.normal);
    if (std::abs(std::abs(n.x) - 1) > 1e-6) continue;  // a lateral plane, handled by the rows
    if (p.point.x > x_first + 0.5 * hx && p.point.x < x_last - 0.5 * hx) {
      add_cut(cuts, p.point.x, 1e-9 * length);
    }
  }
  if (options.auto_blocks) {
    // Where a knuckle starts or ends: a row changes its breakpoints there.
    for (const FeatureLine& k : features.knuckles) {
      if (k.closed || k.vertices.empty()) continue;
      for (Index v : {k.vertices.front(), k.vertices.back()}) {
        // Just off the vertex: a station through a mesh vertex crosses its edges at their ends,
        // where the section's refinement onto the NURBS has no bracket to hold it.
        const double x = surface.positions[v].x + kOffVertex * length;
        if (x > x_first + gap && x < x_last - gap) add_cut(cuts, x, gap);
      }
    }
    // The parallel middle body (sections that change by under 2% of a metre per metre) and the
    // regions where stations must crowd (a step under 60% of the panel length): their ends.
    std::vector<std::uint8_t> parallel(count, 0), crowded(count, 0);
    parallel_for(
        first, last - 1,
        [&](std::size_t k) {
          parallel[k] = section_change(samples[k], samples[k + 1]) < 0.02;
          crowded[k] = step[k] < 0.6 * hx;
        },
        4, 16);
    for (const auto* flags : {&parallel, &crowded}) {
      const bool need_long = flags == &parallel;
      std::size_t k = first;
      while (k < last) {
        if (!(*flags)[k]) {
          ++k;
          continue;
        }
        std::size_t e = k;
        while (e < last && (*flags)[e]) ++e;
        const double x0 = samples[k].x, x1 = samples[e - 1].x;
        if (x1 - x0 > (need_long ? 0.1 * length : kMinBlockPanels * hx)) {
          for (double x : {x0, x1}) {
            if (x > x_first + gap && x < x_last - gap) add_cut(cuts, x, gap);
          }
        }
        k = e;
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());

  // Border stations, then stations between them by equidistributing the integral of 1 / step.
  std::vector<double> borders{x_first};
  borders.insert(borders.end(), cuts.begin(), cuts.end());
  borders.push_back(x_last);
  auto density = [&](double x) {
    const double f = (x - box.lo.x) / dxs - 0.5;
    const std::size_t k = std::clamp<std::size_t>(
        static_cast<std::size_t>(std::max(0.0, std::round(f))), first, last - 1);
    return 1 / step[k];
  };
  StationPlan plan;
  plan.cuts = cuts.size();
  for (std::size_t b = 0; b + 1 < borders.size(); ++b) {
    const double x0 = borders[b], x1 = borders[b + 1];
    // Integrate the density on a fine grid, then invert it.
    constexpr int kSub = 256;
    std::vector<double> cum(kSub + 1, 0);
    for (int i = 0; i < kSub; ++i) {
      const double xm = x0 + (x1 - x0) * (i + 0.5) / kSub;
      cum[i + 1] = cum[i] + density(xm) * (x1 - x0) / kSub;
    }
    const int n = std::max(1, static_cast<int>(std::lround(cum.back())));
    plan.x.push_back(x0);
    plan.border.push_back(1);
    for (int j = 1; j < n; ++j) {
      const double target = cum.back() * j / n;
      const auto it = std::lower_bound(cum.begin(), cum.end(), target);
      const int i = std::clamp(static_cast<int>(it - cum.begin()), 1, kSub);
      const double f = (target - cum[i - 1]) / std::max(cum[i] - cum[i - 1], 1e-300);
      plan.x.push_back(x0 + (x1 - x0) * (i - 1 + f) / kSub);
      plan.border.push_back(0);
    }
  }
  plan.x.push_back(x_last);
  plan.border.push_back(1);
  std::vector<BoundaryTurn> turns = transom_turns(surface, features, hx);
  for (const BoundaryTurn& turn : centre_plane_turns(surface, features, hx)) turns.push_back(turn);
  keep_clear_of_turns(turns, plan);
  return plan;
}

}  // namespace hm::structured
