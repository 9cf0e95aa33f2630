// Closest-point projection: a coarse grid over the knot spans gives starting points, then Newton
// on the squared distance with the second derivatives, clamped to the domain. A parameter pinned
// at the domain boundary (the gradient pushing outwards) is held there and Newton continues in
// one dimension along that edge. Degenerate edges (Su = 0 along a collapsed edge) make the
// Hessian singular there; the step then falls back to damped Gauss-Newton.
#include <algorithm>
#include <cmath>

#include "core/bbox.h"
#include "nurbs/basis.h"
#include "nurbs/nurbs_surface.h"

namespace hm {
namespace {

constexpr int kMaxNewtonIterations = 60;
constexpr int kMaxHalvings = 40;
constexpr int kGridSamplesPerSpan = 3;
constexpr int kMaxGridSamples = 48;  // per direction
constexpr int kStarts = 4;           // best local minima of the grid tried
// A Newton step shorter than this share of the control net's size is converged.
constexpr double kStepFloor = 1e-13;

struct Point2 {
  double u, v;
};

struct Solver {
  const NurbsSurface& s;
  kernel::SurfaceArrays a;
  Vec3d q;
  double scale;  // size of the control net (m): for absolute tolerances

  void eval(double u, double v, Vec3d* d) const { kernel::surface_derivs(a, u, v, 2, d); }

  // Stationarity of the distance in the free directions (cosine between residual and tangent).
  bool stationary(double u, double v, const Vec3d* d) const {
    const Vec3d r = d[0] - q;
    const double rn = norm(r);
    if (rn <= 1e-12 * scale) return true;
    const double gu = dot(r, d[1]);
    const double gv = dot(r, d[2]);
    const bool pinned_u = (u <= s.u0 && gu > 0) || (u >= s.u1 && gu < 0);
    const bool pinned_v = (v <= s.v0 && gv > 0) || (v >= s.v1 && gv < 0);
    const double tol = 1e-7;
    const bool ok_u = pinned_u || std::abs(gu) <= tol * rn * norm(d[1]) + 1e-14 * scale * scale;
    const bool ok_v = pinned_v || std::abs(gv) <= tol * rn * norm(d[2]) + 1e-14 * scale * scale;
    return ok_u && ok_v;
  }

  // Newton step (du, dv) for the free directions.
  void step(double u, double v, const Vec3d* d, double& du, double& dv, bool& corner) const {
    const Vec3d r = d[0] - q;
    const double gu = dot(r, d[1]);
    const double gv = dot(r, d[2]);
    const double juu = dot(d[1], d[1]);
    const double juv = dot(d[1], d[2]);
    const double jvv = dot(d[2], d[2]);
    double huu = juu + dot(r, d[3]);
    double huv = juv + dot(r, d[4]);
    double hvv = jvv + dot(r, d[5]);
    const bool fix_u = (u <= s.u0 && gu > 0) || (u >= s.u1 && gu < 0);
    const bool fix_v = (v <= s.v0 && gv > 0) || (v >= s.v1 && gv < 0);
    const double damping = 1e-12 * (juu + jvv) + 1e-300;
    du = dv = 0;
    corner = fix_u && fix_v;
    if (corner) return;
    if (fix_u || fix_v) {
      // One-dimensional Newton along the edge that holds the pinned parameter.
      const double h = fix_u ? hvv : huu;
      const double j = fix_u ? jvv : juu;
      const double g = fix_u ? gv : gu;
      const double denom = h > 0 ? h : j + damping;
      (fix_u ? dv : du) = -g / denom;
      return;
    }
    double det = huu * hvv - huv * huv;
    if (!(huu > 0 && det > 0)) {
      // Not a local minimum model: Gauss-Newton (always positive semi-definite), damped.
      huu = juu + damping;
      huv = juv;
      hvv = jvv + damping;
      det = huu * hvv - huv * huv;
    }
    du = (-gu * hvv + gv * huv) / det;
    dv = (-gv * huu + gu * huv) / det;
  }

  // at_answer, when given, gets the derivatives at the returned (u, v).
  SurfaceProjection newton(double u, double v, SurfaceDerivs* at_answer = nullptr) const {
    u = std::clamp(u, s.u0, s.u1);
    v = std::clamp(v, s.v0, s.v1);
    Vec3d d[6];
    eval(u, v, d);
    double f = squared_norm(d[0] - q);
    bool converged = false;
    for (int it = 0; it < kMaxNewtonIterations && !converged; ++it) {
      double du, dv;
      bool corner;
      step(u, v, d, du, dv, corner);
      if (corner || !std::isfinite(du) || !std::isfinite(dv)) {
        converged = corner;
        break;
      }
      Vec3d dn[6];
      double un = u, vn = v, fn = f;
      bool decreased = false;
      const double su = norm(d[1]), sv = norm(d[2]);
      for (int h = 0; h < kMaxHalvings; ++h) {
        un = std::clamp(u + du, s.u0, s.u1);
        vn = std::clamp(v + dv, s.v0, s.v1);
        // At the minimum, rounding makes the distance rise along any step; halving a step that
        // is already below the convergence size only repeats that (up to kMaxHalvings
        // evaluations, most of a projection's cost before this check).
        if (h > 0 && std::abs(un - u) * su + std::abs(vn - v) * sv <= kStepFloor * scale) break;
        eval(un, vn, dn);
        fn = squared_norm(dn[0] - q);
        if (fn <= f) {
          decreased = true;
          break;
        }
        du *= 0.5;
        dv *= 0.5;
      }
      if (!decreased) {
        converged = stationary(u, v, d);
        break;
      }
      const double moved = std::abs(un - u) * su + std::abs(vn - v) * sv;
      const bool same = un == u && vn == v;
      u = un;
      v = vn;
      f = fn;
      std::copy(dn, dn + 6, d);
      if (moved <= kStepFloor * scale || same) converged = stationary(u, v, d);
    }
    if (!converged) converged = stationary(u, v, d);
    if (at_answer) *at_answer = SurfaceDerivs{d[0], d[1], d[2], d[3], d[4], d[5]};
    SurfaceProjection out;
    out.u = u;
    out.v = v;
    out.point = d[0];
    out.distance = std::sqrt(f);
    out.converged = converged;
    return out;
  }
};

std::vector<double> grid_params(const std::vector<double>& breaks) {
  const std::size_t spans = breaks.size() - 1;
  std::vector<double> ts;
  if (spans * kGridSamplesPerSpan + 1 <= static_cast<std::size_t>(kMaxGridSamples)) {
    for (std::size_t i = 0; i < spans; ++i) {
      for (int k = 0; k < kGridSamplesPerSpan; ++k) {
        ts.push_back(breaks[i] + (breaks[i + 1] - breaks[i]) * k / kGridSamplesPerSpan);
      }
    }
    ts.push_back(breaks.back());
    return ts;
  }
  for (int k = 0; k < kMaxGridSamples; ++k) {
    ts.push_back(breaks.front() + (breaks.back() - breaks.front()) * k / (kMaxGridSamples - 1));
  }
  ts.back() = breaks.back();
  return ts;
}

// A coarse grid of surface points over the knot spans: the starting points of a global search.
struct StartGrid {
  std::vector<double> us, vs;
  std::vector<Vec3d> pos;  // us.size() x vs.size(), u fastest

  StartGrid(const NurbsSurface& s, const kernel::SurfaceArrays& a)
      : us(grid_params(span_breaks_u(s))), vs(grid_params(span_breaks_v(s))) {
    kernel::BasisTable bu, bv;
    kernel::basis_table(s.degree_u, s.count_u, s.knots_u, us, 0, bu);
    kernel::basis_table(s.degree_v, s.count_v, s.knots_v, vs, 0, bv);
    pos.resize(us.size() * vs.size());
    kernel::surface_grid_rows(a, us, vs, bu, bv, 0, vs.size(), pos, {});
  }

  // Grid points that are local minima of the distance to q (8-neighbourhood), best first.
  std::vector<Point2> starts(const Vec3d& q) const {
    const int nu = static_cast<int>(us.size());
    const int nv = static_cast<int>(vs.size());
    std::vector<double> dist(pos.size());
    for (std::size_t k = 0; k < pos.size(); ++k) dist[k] = squared_norm(pos[k] - q);
    std::vector<std::pair<double, int>> minima;
    for (int j = 0; j < nv; ++j) {
      for (int i = 0; i < nu; ++i) {
        const double dk = dist[i + nu * j];
        bool is_min = true;
        for (int dj = -1; dj <= 1 && is_min; ++dj) {
          for (int di = -1; di <= 1; ++di) {
            const int ii = i + di;
            const int jj = j + dj;
            if ((di || dj) && ii >= 0 && ii < nu && jj >= 0 && jj < nv && dist[ii + nu * jj] < dk) {
              is_min = false;
              break;
            }
          }
        }
        if (is_min) minima.push_back({dk, i + nu * j});
      }
    }
    std::sort(minima.begin(), minima.end());
    std::vector<Point2> out;
    for (std::size_t k = 0; k < minima.size() && k < kStarts; ++k) {
      const int idx = minima[k].second;
      out.push_back({us[idx % nu], vs[idx / nu]});
    }
    return out;
  }
};

bool better(const SurfaceProjection& a, const SurfaceProjection& b) {
  if (a.distance != b.distance) return a.distance < b.distance;
  return a.converged && !b.converged;
}

}  // namespace

struct SurfaceProjector::State {
  const NurbsSurface& s;
  kernel::SurfaceArrays a;
  double scale;
  std::unique_ptr<StartGrid> grid;  // built at the first global search
};

SurfaceProjector::SurfaceProjector(const NurbsSurface& s)
    : state_(new State{s, surface_arrays(s), net_size(s), nullptr}) {}

SurfaceProjector::~SurfaceProjector() = default;

SurfaceProjection SurfaceProjector::project(const Vec3d& q) {
  State& st = *state_;
  if (!st.grid) st.grid = std::make_unique<StartGrid>(st.s, st.a);
  const Solver solver{st.s, st.a, q, st.scale};
  SurfaceProjection best;
  bool have = false;
  for (const Point2& p : st.grid->starts(q)) {
    const SurfaceProjection r = solver.newton(p.u, p.v);
    if (!have || better(r, best)) best = r;
    have = true;
  }
  if (!have) best = solver.newton(0.5 * (st.s.u0 + st.s.u1), 0.5 * (st.s.v0 + st.s.v1));
  return best;
}

SurfaceProjection SurfaceProjector::project(const Vec3d& q, double u_start, double v_start) {
  const Solver solver{state_->s, state_->a, q, state_->scale};
  return solver.newton(u_start, v_start);
}

SurfaceProjection closest_point(const NurbsSurface& s, const Vec3d& q) {
  return SurfaceProjector(s).project(q);
}

SurfaceProjection closest_point(const NurbsSurface& s, const Vec3d& q, double u_start,
                                double v_start) {
  return closest_point(s, q, u_start, v_start, net_size(s));
}

SurfaceProjection closest_point(const NurbsSurface& s, const Vec3d& q, double u_start,
                                double v_start, double net) {
  // Called per vertex in the hot loops (queries, panel improvement): no projector, no allocation.
  const Solver solver{s, surface_arrays(s), q, net};
  return solver.newton(u_start, v_start);
}

SurfaceProjection closest_point(const NurbsSurface& s, const Vec3d& q, double u_start,
                                double v_start, double net, SurfaceDerivs& at_answer) {
  const Solver solver{s, surface_arrays(s), q, net};
  return solver.newton(u_start, v_start, &at_answer);
}

double net_size(const NurbsSurface& s) {
  BBox3d box;
  for (const Vec3d& p : s.points) box.add(p);
  const double d = box.diagonal();
  return d > 0 ? d : 1.0;
}

}  // namespace hm
