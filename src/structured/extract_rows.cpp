// Rows: the hull's sections at the planned stations, refined onto the NURBS, split where knuckle
// lines and lateral block planes cross them, and measured in panels.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
#include <vector>

#include "core/bbox.h"
#include "core/parallel.h"
#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// A breakpoint closer than this (in panels) to one already on the curve is the same node.
constexpr double kBreakMerge = 0.3;
// The largest turn of a row across one panel, radians (10 degrees).
constexpr double kMaxTurnPerPanel = 10 * M_PI / 180;
// Chord length (panels) over which a row's turning is measured: section points sit wherever the
// fine mesh's edges cross the plane, and angles between their uneven little segments are noise.
constexpr double kTurnChord = 0.25;
constexpr double kMinTurnSpacing = 0.35;
constexpr double kTinyStep = 1e-9;  // m
// Knuckle chains that meet end to end turning by less than this are one line (degrees).
constexpr double kContinueDeg = 45;
// A row's curve shorter than both of these is a fragment (panels; share of the longest curve).
constexpr double kFragmentPanels = 3;
constexpr double kFragmentShare = 0.15;
// ... but one at least this long (panels) that runs on at the next station or the one before is
// a piece of hull (see drop_fragments).
constexpr double kRunPanels = 0.5;
// A curve beside a fragment at the next station or the one before, under this many times
// kFragmentPanels long, is the same piece of hull running on, though it may be just long enough
// not to be a fragment itself (see drop_fragments).
constexpr double kRunLength = 2;

RowCurve make_curve(const SectionPolyline& pl, const Metric& metric) {
  RowCurve c;
  const std::size_t n = pl.points.size() + (pl.closed ? 1 : 0);
  c.points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const SectionPoint& sp = pl.points[i % pl.points.size()];
    c.points.push_back(sp.point);
    c.patch.push_back(sp.patch);
    c.uv.push_back(sp.uv);
  }
  c.z_min = c.z_max = c.points.front().z;
  for (const Vec3d& p : c.points) {
    c.z_min = std::min(c.z_min, p.z);
    c.z_max = std::max(c.z_max, p.z);
  }
  // Metric length for now; grade_by_turning rewrites it once the breakpoints are known.
  c.s.assign(n, 0);
  for (std::size_t i = 1; i < n; ++i)
    c.s[i] = c.s[i - 1] + metric.length(c.points[i - 1], c.points[i]);
  return c;
}

// Rewrites the measure of points first..last (their metric lengths in metric_s, from `base`) so
// that each stretch counts at least one panel per kMaxTurnPerPanel of turning; returns the measure
// at `last`.
double grade_stretch(RowCurve& c, std::span<const double> metric_s, std::size_t first,
                     std::size_t last, double base) {
  const double g0 = metric_s[first], total = metric_s[last] - g0;
  if (!(total > 0)) {
    for (std::size_t i = first; i <= last; ++i) c.s[i] = base;
    return base;
  }
  const std::size_t kc =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(total / kTurnChord)));
  const double step = total / static_cast<double>(kc);
  std::vector<Vec3d> q(kc + 1);
  for (std::size_t k = 0, i = first; k <= kc; ++k) {
    const double t = std::min(g0 + step * static_cast<double>(k), metric_s[last]);
    while (i + 1 < last && metric_s[i + 1] < t) ++i;
    const double len = metric_s[i + 1] - metric_s[i];
    const double f = len > 0 ? std::clamp((t - metric_s[i]) / len, 0.0, 1.0) : 0.0;
    q[k] = c.points[i] * (1 - f) + c.points[i + 1] * f;
  }
  std::vector<double> turn(kc + 1, 0);
  for (std::size_t k = 1; k < kc; ++k) {
    const Vec3d a = q[k] - q[k - 1], b = q[k + 1] - q[k];
    const double na = norm(a), nb = norm(b);
    if (na > kTinyStep && nb > kTinyStep) {
      turn[k] = std::acos(std::clamp(dot(a, b) / (na * nb), -1.0, 1.0));
    }
  }
  // Panels per chord: one chord's worth of length, or its turning if that asks for more (never
  // closer than kMinTurnSpacing panels: a skeg's edge turns half a circle in millimetres).
  std::vector<double> per_chord(kc);
  for (std::size_t k = 0; k < kc; ++k) {
    const double by_turn =
        std::min(0.5 * (turn[k] + turn[k + 1]) / kMaxTurnPerPanel, step / kMinTurnSpacing);
    per_chord[k] = std::max(step, by_turn);
  }
  // Spread over a panel either way (two moving averages): panel widths then change gradually
  // along the row instead of halving where the curvature starts, which broke the area-ratio rule
  // between neighbours in a row.
  const std::size_t half = static_cast<std::size_t>(std::lround(1.0 / kTurnChord));
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<double> smooth(kc);
    for (std::size_t k = 0; k < kc; ++k) {
      const std::size_t a = k >= half ? k - half : 0, b = std::min(kc - 1, k + half);
      double sum = 0;
      for (std::size_t i = a; i <= b; ++i) sum += per_chord[i];
      smooth[k] = std::max(step, sum / static_cast<double>(b - a + 1));
    }
    per_chord = std::move(smooth);
  }
  std::vector<double> measure(kc + 1, base);
  for (std::size_t k = 0; k < kc; ++k) measure[k + 1] = measure[k] + per_chord[k];
  std::vector<double> out(last - first + 1);
  for (std::size_t i = first; i <= last; ++i) {
    const double kf = (metric_s[i] - g0) / step;
    const std::size_t k = std::min(static_cast<std::size_t>(std::max(kf, 0.0)), kc - 1);
    out[i - first] = measure[k] + (kf - static_cast<double>(k)) * (measure[k + 1] - measure[k]);
  }
  for (std::size_t i = first; i <= last; ++i) c.s[i] = out[i - first];
  return measure[kc];
}

// The measure along the row: metric length, but at least one panel per kMaxTurnPerPanel of
// turning (a tight bilge gets panels enough that neighbouring normals stay close), taken
// stretch by stretch between breakpoints so that a knuckle's corner counts for nothing.
void grade_by_turning(RowCurve& c) {
  // Each stretch reads the metric lengths: the one before it has already rewritten their shared
  // point, and reading that graded value shrank (or emptied) every stretch after the first.
  const std::vector<double> metric_s = c.s;
  double base = 0;
  for (std::size_t b = 0; b + 1 < c.breaks.size(); ++b) {
    base = grade_stretch(c, metric_s, c.breaks[b].point, c.breaks[b + 1].point, base);
  }
  for (Breakpoint& b : c.breaks) b.s = c.s[b.point];
}

// Inserts a point at arc length t (linear between its neighbours) and returns its index.
Index insert_point(RowCurve& c, double t) {
  std::size_t k;
  double f;
  c.locate(t, k, f);
  if (f < 1e-9) return static_cast<Index>(k);
  if (f > 1 - 1e-9) return static_cast<Index>(k + 1);
  const Vec3d p = c.points[k] * (1 - f) + c.points[k + 1] * f;
  // (u, v) interpolates only within one patch; across a border the nearer corner's is kept.
  const bool same = c.patch[k] == c.patch[k + 1];
  const Vec2d uv = same ? c.uv[k] * (1 - f) + c.uv[k + 1] * f : (f < 0.5 ? c.uv[k] : c.uv[k + 1]);
  const PatchId patch = f < 0.5 || same ? c.patch[k] : c.patch[k + 1];
  c.points.insert(c.points.begin() + static_cast<std::ptrdiff_t>(k + 1), p);
  c.uv.insert(c.uv.begin() + static_cast<std::ptrdiff_t>(k + 1), uv);
  c.patch.insert(c.patch.begin() + static_cast<std::ptrdiff_t>(k + 1), patch);
  c.s.insert(c.s.begin() + static_cast<std::ptrdiff_t>(k + 1), t);
  for (Breakpoint& b : c.breaks)
    if (b.point > k) ++b.point;
  return static_cast<Index>(k + 1);
}

bool near_break(const RowCurve& c, double t) {
  for (const Breakpoint& b : c.breaks)
    if (std::abs(b.s - t) < kBreakMerge) return true;
  return false;
}

// One id per knuckle line: chains that the feature finder split at a corner but that run on
// straight through it (a chine that a patch corner interrupts) share the smallest chain index.
std::vector<Index> knuckle_groups(const SurfaceMesh& surface, const FeatureSet& features) {
  const std::size_t n = features.knuckles.size();
  std::vector<Index> parent(n);
  std::iota(parent.begin(), parent.end(), Index{0});
  auto find = [&](Index a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  // The direction a chain leaves its end e (0: first vertex, 1: last), pointing out of it.
  auto out_dir = [&](const FeatureLine& l, int e) {
    const std::size_t m = l.vertices.size();
    const Vec3d& end = surface.positions[e == 0 ? l.vertices[0] : l.vertices[m - 1]];
    const Vec3d& in = surface.positions[e == 0 ? l.vertices[std::min<std::size_t>(1, m - 1)]
                                               : l.vertices[m >= 2 ? m - 2 : 0]];
    return normalized(end - in);
  };
  const double cos_limit = std::cos(kContinueDeg * M_PI / 180);
  for (std::size_t a = 0; a < n; ++a) {
    const FeatureLine& la = features.knuckles[a];
    if (la.closed || la.vertices.size() < 2) continue;
    for (std::size_t b = a + 1; b < n; ++b) {
      const FeatureLine& lb = features.knuckles[b];
      if (lb.closed || lb.vertices.size() < 2) continue;
      for (int ea = 0; ea < 2; ++ea) {
        for (int eb = 0; eb < 2; ++eb) {
          const Index va = ea == 0 ? la.vertices.front() : la.vertices.back();
          const Index vb = eb == 0 ? lb.vertices.front() : lb.vertices.back();
          if (va != vb) continue;
          // Straight on: a leaves the corner the way b enters it.
          if (-dot(out_dir(la, ea), out_dir(lb, eb)) >= cos_limit) {
            parent[find(static_cast<Index>(b))] = find(static_cast<Index>(a));
          }
        }
      }
    }
  }
  std::vector<Index> group(n);
  for (std::size_t k = 0; k < n; ++k) group[k] = find(static_cast<Index>(k));
  return group;
}

void add_knuckle_breaks(RowCurve& c, double x, const SurfaceMesh& surface,
                        const FeatureSet& features, std::span<const Index> group, double tol) {
  for (std::size_t k = 0; k < features.knuckles.size(); ++k) {
    const FeatureLine& line = features.knuckles[k];
    const std::size_t n = line.vertices.size();
    const std::size_t segs = line.closed ? n : n - 1;
    for (std::size_t i = 0; i < segs; ++i) {
      const Vec3d& a = surface.positions[line.vertices[i]];
      const Vec3d& b = surface.positions[line.vertices[(i + 1) % n]];
      if ((a.x - x) * (b.x - x) > 0 || a.x == b.x) continue;
      const double f = (x - a.x) / (b.x - a.x);
      const Vec3d p = a * (1 - f) + b * f;
      // The section crosses the knuckle's mesh edge at one of its own points, refined onto the
      // NURBS: that point, not the chord's, is the breakpoint.
      std::size_t best = 0;
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < c.points.size(); ++j) {
        const double d = squared_norm(c.points[j] - p);
        if (d < best_d) {
          best_d = d;
          best = j;
        }
      }
      if (std::sqrt(best_d) > tol || near_break(c, c.s[best])) continue;
      c.breaks.push_back({c.s[best], static_cast<Index>(best), {BreakKind::kKnuckle, group[k]}});
    }
  }
}

void add_plane_breaks(RowCurve& c, std::span<const BlockPlane> planes) {
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const Vec3d n = normalized(planes[p].normal);
    if (std::abs(std::abs(n.x) - 1) <= 1e-6) continue;  // a cut station
    for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
      const double da = dot(n, c.points[k] - planes[p].point);
      const double db = dot(n, c.points[k + 1] - planes[p].point);
      if (!((da < 0 && db >= 0) || (da >= 0 && db < 0))) continue;
      const double t = c.s[k] + da / (da - db) * (c.s[k + 1] - c.s[k]);
      if (near_break(c, t)) continue;
      const Index at = insert_point(c, t);
      // On the plane exactly (the interpolated point is off it by rounding): a waterline node
      // then has z = 0 to the bit, as the hydrostatics and the panel codes take it.
      c.points[at] = c.points[at] - dot(n, c.points[at] - planes[p].point) * n;
      c.breaks.push_back({t, at, {BreakKind::kPlane, static_cast<Index>(p)}});
      ++k;  // past the inserted point
    }
  }
}

bool is_fragment(const RowCurve& c, double longest) {
  return c.length() < kFragmentPanels && c.length() < kFragmentShare * longest;
}

double longest_curve(const Row& row) {
  double longest = 0;
  for (const RowCurve& c : row.curves) longest = std::max(longest, c.length());
  return longest;
}

// The curves' bounding boxes in (y, z) come within `gap` metres of each other.
bool near_in_section(const RowCurve& a, const RowCurve& b, double gap) {
  BBox3d ba, bb;
  for (const Vec3d& p : a.points) ba.add(Vec3d{0, p.y, p.z});
  for (const Vec3d& p : b.points) bb.add(Vec3d{0, p.y, p.z});
  return ba.lo.y <= bb.hi.y + gap && bb.lo.y <= ba.hi.y + gap && ba.lo.z <= bb.hi.z + gap &&
         bb.lo.z <= ba.hi.z + gap;
}

// The curves run between the same two stretches of boundary: both ends within `reach` (m, in y
// and z) of the other's. A curve from the keel to the waterline and a fragment of it are not.
bool same_piece(const RowCurve& a, const RowCurve& b, double reach) {
  const auto near = [&](const Vec3d& p, const Vec3d& q) {
    return std::hypot(p.y - q.y, p.z - q.z) <= reach;
  };
  return near(a.points.front(), b.points.front()) && near(a.points.back(), b.points.back());
}

// Whether curve i of row j runs on, station by station towards `step` (+1 forward, -1 aft),
// through curves of the same piece that are dropped, to one that is kept.
bool kept_beyond(const std::vector<Row>& rows, const std::vector<std::vector<std::uint8_t>>& drop,
                 std::size_t j, std::size_t i, int step, double reach) {
  const RowCurve* at = &rows[j].curves[i];
  for (std::ptrdiff_t k = static_cast<std::ptrdiff_t>(j) + step;
       k >= 0 && k < static_cast<std::ptrdiff_t>(rows.size()); k += step) {
    const Row& row = rows[static_cast<std::size_t>(k)];
    const RowCurve* next = nullptr;
    bool kept = false;
    for (std::size_t c = 0; c < row.curves.size() && !next; ++c) {
      if (!same_piece(*at, row.curves[c], reach)) continue;
      next = &row.curves[c];
      kept = drop[static_cast<std::size_t>(k)][c] == 0;
    }
    if (!next) return false;
    if (kept) return true;
    at = next;
  }
  return false;
}

// Drops the rows' fragments: curves under kFragmentPanels long and under kFragmentShare of their
// row's longest curve. A station that grazes a raked transom or a skeg cuts off such a sliver;
// the strips on either side cover its surface, and a sliver row of its own would pair with
// nothing. A fragment at least kRunPanels long, on a station that is no border, with a short
// curve beside it (within `gap` in y and z; under kRunLength * kFragmentPanels, as every fragment
// is) at the next station or the one before, is no graze but a piece of hull that is short in
// section and runs on in x, and stays: the stem above a bulb, forward of the neck's aftmost point,
// where the sections are the bulb's and the stem's (the generated 48-patch round-bilge hull at
// 16,000 panels: the stem's rows were dropped, a fan from the bulb's row end covered the stem, and
// the fan's panels lay in the centre plane, 0.11 m off the hull). Shorter ones go still: a full
// hull's stem tip of 0.06 panels, kept, was left uncapped (property seed 5395). A shelf under a
// ballast waterline narrowing towards its end (ship_449_patches at 5 m with --trim 1.5, its stern
// down: 3.1, 2.4 and 3.1 panels at three stations in a row) lost its middle station's curve while a
// fragment had to have a fragment beside it, and the caps and joins around the gap crossed (12
// pairs of panels).
// At the end stations a curve is measured against the longer of its own row's and the next row's
// longest, and goes when it is a fragment by that and no curve the next row keeps lies beside
// it: an end station a fifth of a panel from a stem above a bulb cut the bulb's nose and the
// stem's tip, 0.21 and 0.11 panels long. The stem's pieces at the two stations before were
// dropped, so the strip aft of them had capped the stem to its tip, and the end cap covered the
// tip again, back to back (a full round-bilge hull of 24 patches at 6.684 m, --trim 0.63, 1,500
// panels: 4 pairs of panels through each other).
void drop_fragments(std::vector<Row>& rows, double gap) {
  std::vector<double> longest(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) longest[j] = longest_curve(rows[j]);
  const auto runs_on = [&](const RowCurve& c, std::size_t k) {
    for (const RowCurve& d : rows[k].curves) {
      if (d.length() < kRunLength * kFragmentPanels && near_in_section(c, d, gap)) return true;
    }
    return false;
  };
  std::vector<std::vector<std::uint8_t>> drop(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (const RowCurve& c : rows[j].curves) {
      const bool fragment = is_fragment(c, longest[j]);
      const bool runs = (j > 0 && runs_on(c, j - 1)) || (j + 1 < rows.size() && runs_on(c, j + 1));
      const bool kept = !fragment || (!rows[j].border && c.length() >= kRunPanels && runs);
      drop[j].push_back(kept ? 0 : 1);
    }
  }
  // A piece of hull that is a fragment at some stations only, between stations that keep it, is
  // kept at those too. Whether a short curve is a fragment depends on its row's longest curve,
  // and where that is a bulb narrowing to its nose the stem above it was dropped at two stations
  // and kept at the two after: the strip before the gap capped the stem to its tip, over the
  // panels of the rows beyond (property seed 30378 in wide mode, a round-bilge hull trimmed by
  // the bow: 2 pairs of panels through each other at the stem's tip).
  std::vector<std::vector<std::uint8_t>> rekeep(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    rekeep[j].assign(rows[j].curves.size(), 0);
    for (std::size_t i = 0; i < rows[j].curves.size(); ++i) {
      if (drop[j][i] && kept_beyond(rows, drop, j, i, -1, 0.5 * gap) &&
          kept_beyond(rows, drop, j, i, +1, 0.5 * gap)) {
        rekeep[j][i] = 1;
      }
    }
  }
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (std::size_t i = 0; i < rows[j].curves.size(); ++i)
      if (rekeep[j][i]) drop[j][i] = 0;
  }
  // The end rows: a curve short by the row beside it (which may have dropped its own fragments
  // of the same piece) with no kept curve of that row beside it is a piece of hull whose strip
  // before has already capped it to the end.
  if (rows.size() > 2) {
    for (const std::size_t j : {std::size_t{0}, rows.size() - 1}) {
      const std::size_t next = j == 0 ? 1 : j - 1;
      for (std::size_t i = 0; i < rows[j].curves.size(); ++i) {
        const RowCurve& c = rows[j].curves[i];
        if (drop[j][i] || !is_fragment(c, std::max(longest[j], longest[next]))) continue;
        bool beside = false;
        for (std::size_t k = 0; k < rows[next].curves.size(); ++k) {
          beside = beside || (!drop[next][k] && near_in_section(c, rows[next].curves[k], gap));
        }
        if (!beside) drop[j][i] = 1;
      }
    }
  }
  for (std::size_t j = 0; j < rows.size(); ++j) {
    std::size_t i = 0;
    std::erase_if(rows[j].curves, [&](const RowCurve&) { return drop[j][i++] != 0; });
  }
}

// Puts a curve's end exactly where the station plane crosses the surface's nearest boundary edge
// (within tol): the section refines its points onto the NURBS, which a waterplane cut left a
// little way off, and a row's ends must lie on the waterline and the centre plane exactly.
void snap_end(Vec3d& end, double x, const SurfaceMesh& surface,
              std::span<const std::array<Index, 2>> boundary, double tol) {
  double best = tol;
  Vec3d at = end;
  for (const auto& [a, b] : boundary) {
    const Vec3d& pa = surface.positions[a];
    const Vec3d& pb = surface.positions[b];
    if ((pa.x - x) * (pb.x - x) > 0 || pa.x == pb.x) continue;
    const double f = (x - pa.x) / (pb.x - pa.x);
    Vec3d p = pa * (1 - f) + pb * f;
    p.x = x;
    // An edge on the waterplane or the centre plane keeps its coordinate exactly.
    if (pa.y == pb.y) p.y = pa.y;
    if (pa.z == pb.z) p.z = pa.z;
    const double d = norm(p - end);
    if (d < best) {
      best = d;
      at = p;
    }
  }
  end = at;
}

// Girth order, the order of points up the hull from the keel: a point on the centre plane
// (within `centre`, m) before one off it, then the lower (to tol, m), then the nearer the centre
// plane. A row's open curve runs from its end first in this order, and the row lists its curves
// by their first points in it; the strips' joins and the end caps read them so. The section had
// ordered ends and curves by height alone, and before the ends were snapped onto the waterline:
//   - a shelf under the waterline, cut into a curve whose two ends lie on it, came out inboard
//     end first at one station and outboard end first at the next (its ends' heights on the
//     NURBS differ by noise), and the strips between such rows were zipped crosswise
//     (ship_449_patches at drafts of 6.5-9 m: up to 673 pairs of panels through each other).
//     Snapped onto the waterline, both ends have its height exactly;
//   - the bottom by an immersed transom, rising to the centre plane, was cut from its outboard
//     end and listed after the row's other curve, and the end cap and the strip before it
//     crossed (ship_449_patches at 15.5 m with --trim 1.5: 82 pairs).
bool girth_before(const Vec3d& a, const Vec3d& b, double tol, double centre) {
  const bool a_on = std::abs(a.y) <= centre, b_on = std::abs(b.y) <= centre;
  if (a_on != b_on) return a_on;
  if (std::abs(a.z - b.z) > tol) return a.z < b.z;
  return std::abs(a.y) < std::abs(b.y);
}

}  // namespace

std::vector<Row> extract_rows(const HullQuery& query, const SurfaceMesh& surface,
                              const EdgeAdjacency& adj, const FeatureSet& features,
                              std::span<const BlockPlane> planes, const StationPlan& plan,
                              const Metric& metric) {
  std::vector<Plane> cut(plan.x.size());
  for (std::size_t j = 0; j < cut.size(); ++j) cut[j] = Plane{{plan.x[j], 0, 0}, {1, 0, 0}};
  const std::vector<Section> secs = query.sections(cut);
  const double tol = 1e-3 * query.length_scale();
  // Points this close in height are at one height: the section's own tie (HullQuery's default
  // join tolerance). Ends snapped onto the waterline have its height exactly.
  const double tie = 1e-6 * query.length_scale();
  const double centre = kPlaneTolerance * query.length_scale();
  // A curve's end lies on the surface's boundary, but its refinement onto the NURBS can carry it
  // off: where the waterplane cut moved a fine chine vertex up onto the waterline, the end
  // refines back down onto the chine (property seed 1338: 0.17 m, a ninth of a panel, past
  // 1e-3 L), and the strip above the chine would be left open. Ends are snapped from a quarter
  // panel away.
  const double end_tol =
      std::max(tol, 0.25 * std::min({metric.size.x, metric.size.y, metric.size.z}));
  const std::vector<Index> group = knuckle_groups(surface, features);
  std::vector<std::array<Index, 2>> boundary;
  for (Index e : adj.boundary_edges) boundary.push_back({adj.edges[e].v0, adj.edges[e].v1});
  std::vector<Row> rows(plan.x.size());
  parallel_for_each_item(rows.size(), [&](std::size_t j) {
    Row& row = rows[j];
    row.x = plan.x[j];
    row.border = plan.border[j] != 0;
    for (const SectionPolyline& pl : secs[j].polylines) {
      if (pl.points.size() < 2) continue;
      SectionPolyline ends = pl;
      if (!pl.closed) {
        snap_end(ends.points.front().point, row.x, surface, boundary, end_tol);
        snap_end(ends.points.back().point, row.x, surface, boundary, end_tol);
        if (girth_before(ends.points.back().point, ends.points.front().point, tie, centre)) {
          std::reverse(ends.points.begin(), ends.points.end());
        }
      }
      RowCurve c = make_curve(ends, metric);
      // Slivers of a section (a grazed patch corner) are not rows.
      if (c.length() < 0.05) continue;
      const Index last = static_cast<Index>(c.points.size() - 1);
      c.breaks.push_back({0, 0, {BreakKind::kLow, 0}});
      c.breaks.push_back({c.s.back(), last, {BreakKind::kHigh, 0}});
      // Planes first: a plane's break is its exact crossing, a knuckle's is the nearest curve
      // point, so a knuckle on a plane (the waterline of a hull meshed above it) takes the
      // plane's.
      add_plane_breaks(c, planes);
      add_knuckle_breaks(c, row.x, surface, features, group, tol);
      std::sort(c.breaks.begin(), c.breaks.end(),
                [](const Breakpoint& a, const Breakpoint& b) { return a.s < b.s; });
      grade_by_turning(c);
      row.curves.push_back(std::move(c));
    }
    std::stable_sort(row.curves.begin(), row.curves.end(),
                     [&](const RowCurve& a, const RowCurve& b) {
                       return girth_before(a.points.front(), b.points.front(), tie, centre);
                     });
  });
  drop_fragments(rows, 2 * std::max({metric.size.x, metric.size.y, metric.size.z}));
  return rows;
}

}  // namespace hm::structured
