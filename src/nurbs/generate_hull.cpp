#include "nurbs/generate_hull.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "core/parallel.h"
#include "nurbs/gauss_legendre.h"
#include "nurbs/hull_shapes.h"
#include "nurbs/knot_ops.h"

namespace hm {
namespace {

constexpr int kMaxPatches = 1000;
constexpr int kKnuckleSamples = 101;
constexpr int kAreaCells = 32;

// A part surface to be cut into a grid of sub-patches, with what lies beyond each side.
struct Piece {
  std::string name;
  NurbsSurface surface;
  std::array<SideKind, 4> sides{};  // u0, u1, v0, v1
};

void validate_spec(const HullSpec& spec) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!positive(spec.length) || !positive(spec.beam) || !positive(spec.depth) ||
      !positive(spec.draft)) {
    throw UsageError("hull length, beam, depth and draft must be positive");
  }
  if (spec.kind != HullKind::kWigley && !(spec.draft < spec.depth)) {
    throw UsageError("the draft must be below the depth for this hull kind");
  }
  if (spec.patches < 1 || spec.patches > kMaxPatches) {
    throw UsageError("patches must be between 1 and 1000 (got " + std::to_string(spec.patches) +
                     ")");
  }
  if (spec.full_hull && spec.patches < 2) {
    throw UsageError("a full hull needs at least 2 patches (one per side)");
  }
  const HullDefects& d = spec.defects;
  if (!std::isfinite(d.gap) || d.gap < 0) throw UsageError("gap must be >= 0 m");
  if (!std::isfinite(d.overlap) || d.overlap < 0 || d.overlap > 0.5) {
    throw UsageError("overlap must be a fraction between 0 and 0.5");
  }
  if (d.flip_every < 0) throw UsageError("flip_every must be >= 0");
}

// Rough size of a surface from its control net: mean polygon length along u and along v.
void net_lengths(const NurbsSurface& s, double& along_u, double& along_v) {
  along_u = along_v = 0;
  for (int j = 0; j < s.count_v; ++j) {
    for (int i = 0; i + 1 < s.count_u; ++i) along_u += norm(s.point(i + 1, j) - s.point(i, j));
  }
  for (int i = 0; i < s.count_u; ++i) {
    for (int j = 0; j + 1 < s.count_v; ++j) along_v += norm(s.point(i, j + 1) - s.point(i, j));
  }
  along_u /= s.count_v;
  along_v /= s.count_u;
}

// Splits `total` (>= pieces.size()) over the pieces in proportion to their rough areas, at least
// one each, by largest remainders (ties to the earlier piece).
std::vector<int> distribute(int total, const std::vector<Piece>& pieces) {
  const int n = static_cast<int>(pieces.size());
  std::vector<double> area(n);
  for (int k = 0; k < n; ++k) {
    double lu, lv;
    net_lengths(pieces[k].surface, lu, lv);
    area[k] = std::max(lu * lv, 1e-12);
  }
  const double sum = std::accumulate(area.begin(), area.end(), 0.0);
  std::vector<int> count(n, 1);
  std::vector<double> frac(n);
  int given = n;
  for (int k = 0; k < n; ++k) {
    const double share = (total - n) * area[k] / sum;
    count[k] += static_cast<int>(std::floor(share));
    frac[k] = share - std::floor(share);
    given += static_cast<int>(std::floor(share));
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return frac[a] > frac[b]; });
  for (int k = 0; given < total; k = (k + 1) % n, ++given) ++count[order[k]];
  return count;
}

std::vector<double> uniform_breaks(double a, double b, int n) {
  std::vector<double> t(n + 1);
  for (int k = 0; k <= n; ++k) t[k] = k == n ? b : a + (b - a) * k / n;
  return t;
}

// How a side of a sub-patch opens when a gap is asked for.
enum class GapSide {
  kNone,         // free edge: stays
  kSurface,      // a neighbour on the same side of the hull: recede gap / 2 along the surface
  kCentreplane,  // the mirrored patch of a full hull: recede until y = gap / 2
};

// Fastest rate of recession along the side of a sub-domain at u = side (v = side), per unit of
// the parameter across it: the largest |dS/du| (|dS/dv|), or only its y part for the centreplane,
// of 17 points along the side. A side that recedes by gap / 2 over this rate recedes by at most
// gap / 2 in metres anywhere along it (by the mean rate, up to twice that where the rate is high:
// 0.22 m gaps for 0.1 m asked), so `--gap M` makes gaps of at most M.
double edge_speed(const NurbsSurface& s, bool across_u, double side, double lo, double hi,
                  GapSide kind) {
  constexpr int kSamples = 16;
  double fastest = 0;
  for (int k = 0; k <= kSamples; ++k) {
    const double t = lo + (hi - lo) * k / double(kSamples);
    const SurfaceDerivs d =
        across_u ? evaluate_derivs(s, side, t, 1) : evaluate_derivs(s, t, side, 1);
    const Vec3d& rate = across_u ? d.su : d.sv;
    fastest = std::max(fastest, kind == GapSide::kCentreplane ? std::abs(rate.y) : norm(rate));
  }
  return fastest;
}

// The sub-patch over `dom` = {ua, ub, va, vb} with gap or overlap defects applied: a gap side
// recedes (at most a quarter of the width); an `interior` side (a neighbour in the same piece)
// extends by the overlap fraction of the width.
NurbsSurface defect_piece(const NurbsSurface& s, std::array<double, 4> dom,
                          const std::array<GapSide, 4>& gaps, const std::array<bool, 4>& interior,
                          const HullDefects& defects) {
  const double wu = dom[1] - dom[0], wv = dom[3] - dom[2];
  std::array<double, 4> d = dom;
  for (int side = 0; side < 4; ++side) {
    const bool across_u = side < 2;
    const double width = across_u ? wu : wv;
    const double sign = side % 2 == 0 ? 1.0 : -1.0;  // towards the inside of the sub-patch
    if (defects.gap > 0 && gaps[side] != GapSide::kNone) {
      const double speed = edge_speed(s, across_u, dom[side], across_u ? dom[2] : dom[0],
                                      across_u ? dom[3] : dom[1], gaps[side]);
      if (speed > 0) d[side] += sign * std::min(0.5 * defects.gap / speed, 0.25 * width);
    }
    if (defects.overlap > 0 && interior[side]) d[side] -= sign * defects.overlap * width;
  }
  d[0] = std::max(d[0], s.u0);
  d[1] = std::min(d[1], s.u1);
  d[2] = std::max(d[2], s.v0);
  d[3] = std::min(d[3], s.v1);
  return extract_subsurface(s, d[0], d[1], d[2], d[3]);
}

// Cuts one piece into `count` sub-patches: nv rows along v, each row cut into about count / nv
// columns along u (rows may differ by one column, so any count is reachable exactly).
// `cells` gets, per patch, how many quadrature cells its area needs along u and v so that the
// whole piece is covered by about kAreaCells x kAreaCells cells however it is cut.
void cut_piece(const Piece& piece, int count, const HullSpec& spec, std::vector<Patch>& out,
               std::vector<std::array<int, 2>>& cells) {
  const NurbsSurface& s = piece.surface;
  double lu, lv;
  net_lengths(s, lu, lv);
  const double aspect = lv > 0 ? lu / lv : 1.0;
  const int nv = std::clamp(static_cast<int>(std::lround(std::sqrt(count / aspect))), 1, count);
  const std::vector<double> vb = uniform_breaks(s.v0, s.v1, nv);
  const bool plain = spec.defects.gap <= 0 && spec.defects.overlap <= 0;
  const std::vector<NurbsSurface> rows = plain ? split_v(s, vb) : std::vector<NurbsSurface>{};
  const auto gap_side = [&](bool interior, SideKind k) {
    if (interior || k == SideKind::kShared) return GapSide::kSurface;
    return k == SideKind::kCentre && spec.full_hull ? GapSide::kCentreplane : GapSide::kNone;
  };
  int index = 1;
  for (int j = 0; j < nv; ++j) {
    const int nu = count / nv + (j < count % nv ? 1 : 0);
    const std::vector<double> ub = uniform_breaks(s.u0, s.u1, nu);
    std::vector<NurbsSurface> columns;
    if (plain) columns = split_u(rows[j], ub);
    for (int i = 0; i < nu; ++i) {
      Patch p;
      if (plain) {
        p.surface = std::move(columns[i]);
      } else {
        const std::array<bool, 4> interior = {i > 0, i + 1 < nu, j > 0, j + 1 < nv};
        const std::array<GapSide, 4> gaps = {
            gap_side(interior[0], piece.sides[0]), gap_side(interior[1], piece.sides[1]),
            gap_side(interior[2], piece.sides[2]), gap_side(interior[3], piece.sides[3])};
        p.surface =
            defect_piece(s, {ub[i], ub[i + 1], vb[j], vb[j + 1]}, gaps, interior, spec.defects);
      }
      p.wrapping = Wrapping::kGenerated;
      p.source_type = 128;
      p.name = piece.name + "_" + std::to_string(index++);
      out.push_back(std::move(p));
      cells.push_back({(kAreaCells + nu - 1) / nu, (kAreaCells + nv - 1) / nv});
    }
  }
}

NurbsSurface mirror_y(const NurbsSurface& s) {
  NurbsSurface m = s;
  for (Vec3d& p : m.points) p.y = -p.y;
  return reverse_u(m);  // a mirror flips su x sv; reversing u makes it point outward again
}

// The pieces of one side of the hull for `count` patches.
std::vector<Piece> side_pieces(const HullShape& shape, int count, bool starboard) {
  std::vector<Piece> pieces;
  if (count < static_cast<int>(shape.parts.size())) {
    pieces.push_back({shape.merged.name, shape.merged.surface, shape.merged.sides});
  } else {
    for (const HullPart& p : shape.parts) pieces.push_back({p.name, p.surface, p.sides});
  }
  if (starboard) {
    for (Piece& p : pieces) {
      p.name += "_stbd";
      p.surface = mirror_y(p.surface);
      std::swap(p.sides[0], p.sides[1]);
    }
  }
  return pieces;
}

// Defects that keep each patch's geometry and change its representation. Every defect is a fixed
// pattern (gaps and overlaps on every shared side, a repeated knot mid-patch, every n-th patch
// flipped), so the output does not depend on defects.seed.
void apply_point_defects(const HullDefects& defects, std::vector<Patch>& patches) {
  parallel_for(0, patches.size(), [&](std::size_t k) {
    Patch& p = patches[k];
    if (defects.duplicate_points) {
      // Full multiplicity (degree + 1) mid-patch: two coinciding columns of control points.
      NurbsSurface& s = p.surface;
      const double mid = 0.5 * (s.u0 + s.u1);
      const int times = s.degree_u + 1 - knot_multiplicity(s.knots_u, mid);
      if (times > 0) s = insert_knot_u(s, mid, times);
    }
    if (defects.flip_every > 0 && (k + 1) % static_cast<std::size_t>(defects.flip_every) == 0) {
      p.surface = reverse_u(p.surface);
      p.reversed = true;  // same face: the outward normal is now -su x sv
    }
  });
}

// The knot-span breaks, each span cut into equal parts so that there are at least n cells.
std::vector<double> cell_breaks(const std::vector<double>& spans, int n) {
  const int per_span =
      (n + static_cast<int>(spans.size()) - 2) / static_cast<int>(spans.size() - 1);
  std::vector<double> t{spans.front()};
  for (std::size_t k = 0; k + 1 < spans.size(); ++k) {
    for (int m = 1; m < per_span; ++m) {
      t.push_back(spans[k] + (spans[k + 1] - spans[k]) * m / per_span);
    }
    t.push_back(spans[k + 1]);
  }
  return t;
}

// Area of one surface: Gauss-Legendre, 4 x 4 points on each cell, the cells being the knot
// spans cut to at least cells_u x cells_v (knuckles and collapsed rows sit on span borders, so
// every cell's integrand is smooth). Fixed work per cell keeps 1000 patches fast.
double surface_area(const NurbsSurface& s, std::array<int, 2> cells) {
  static const GaussRule g = gauss_legendre_01(4);
  const std::vector<double> bu = cell_breaks(span_breaks_u(s), cells[0]);
  const std::vector<double> bv = cell_breaks(span_breaks_v(s), cells[1]);
  double area = 0;
  for (std::size_t i = 0; i + 1 < bu.size(); ++i) {
    for (std::size_t j = 0; j + 1 < bv.size(); ++j) {
      const double hu = bu[i + 1] - bu[i], hv = bv[j + 1] - bv[j];
      double cell = 0;
      for (std::size_t a = 0; a < g.nodes.size(); ++a) {
        for (std::size_t b = 0; b < g.nodes.size(); ++b) {
          const SurfaceDerivs d =
              evaluate_derivs(s, bu[i] + hu * g.nodes[a], bv[j] + hv * g.nodes[b], 1);
          cell += g.weights[a] * g.weights[b] * norm(cross(d.su, d.sv));
        }
      }
      area += hu * hv * cell;
    }
  }
  return area;
}

std::vector<Vec3d> sample_knuckle(const HullShape& shape, const KnuckleLine& k) {
  const NurbsSurface& s = shape.parts[k.part].surface;
  const double lo = k.fixed_u ? s.v0 : s.u0, hi = k.fixed_u ? s.v1 : s.u1;
  std::vector<Vec3d> line;
  for (int i = 0; i < kKnuckleSamples; ++i) {
    const double t = i + 1 == kKnuckleSamples ? hi : lo + (hi - lo) * i / (kKnuckleSamples - 1);
    line.push_back(k.fixed_u ? evaluate(s, k.value, t) : evaluate(s, t, k.value));
  }
  return line;
}

}  // namespace

bool parse_hull_kind(const std::string& name, HullKind& kind) {
  if (name == "wigley") {
    kind = HullKind::kWigley;
  } else if (name == "round-bilge" || name == "round_bilge" || name == "roundbilge") {
    kind = HullKind::kRoundBilge;
  } else if (name == "chine") {
    kind = HullKind::kChine;
  } else {
    return false;
  }
  return true;
}

const char* to_string(HullKind k) {
  switch (k) {
    case HullKind::kWigley:
      return "wigley";
    case HullKind::kRoundBilge:
      return "round-bilge";
    case HullKind::kChine:
      return "chine";
  }
  return "unknown";
}

// Patch counts: a half hull gets all `patches`; a full hull gives ceil(n / 2) to port and
// floor(n / 2) to starboard. Each side is cut from its separate parts (transom, side, bottom,
// ...) when it has at least one patch per part, else from the merged surface that holds all
// parts with knuckle knots inside. Parts get patches in proportion to their areas (at least one
// each); a part's patches form rows along v of near-square cells, so the total is exact.
GeneratedHull generate_hull(const HullSpec& spec) {
  validate_spec(spec);
  const HullShape shape = make_hull_shape(spec);
  const int port = spec.full_hull ? (spec.patches + 1) / 2 : spec.patches;
  const int starboard = spec.patches - port;

  GeneratedHull hull;
  std::vector<std::array<int, 2>> cells;  // per patch: area quadrature cells along u and v
  for (int side = 0; side < (spec.full_hull ? 2 : 1); ++side) {
    const std::vector<Piece> pieces = side_pieces(shape, side == 0 ? port : starboard, side == 1);
    const std::vector<int> counts = distribute(side == 0 ? port : starboard, pieces);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      cut_piece(pieces[k], counts[k], spec, hull.patches, cells);
    }
  }
  apply_point_defects(spec.defects, hull.patches);

  HullFacts& facts = hull.facts;
  facts.displacement_volume = shape.displacement_volume;
  facts.wetted_area = shape.wetted_area;
  std::vector<double> areas(hull.patches.size());
  parallel_for(0, hull.patches.size(),
               [&](std::size_t k) { areas[k] = surface_area(hull.patches[k].surface, cells[k]); });
  facts.surface_area = std::accumulate(areas.begin(), areas.end(), 0.0);
  for (const KnuckleLine& k : shape.knuckles) {
    facts.knuckles.push_back(sample_knuckle(shape, k));
    if (spec.full_hull) {
      std::vector<Vec3d> mirrored = facts.knuckles.back();
      for (Vec3d& p : mirrored) p.y = -p.y;
      facts.knuckles.push_back(std::move(mirrored));
    }
  }
  return hull;
}

}  // namespace hm
