#include "iges/convert_trims.h"

#include <algorithm>
#include <cmath>

#include "iges/convert_curves.h"
#include "iges/convert_surfaces.h"
#include "iges/curve_ops.h"
#include "iges/project_curve.h"
#include "iges/work_budget.h"

namespace hm::iges {
namespace {

using Chain = std::vector<NurbsCurve>;

void reverse_chain(Chain& c) {
  std::reverse(c.begin(), c.end());
  for (NurbsCurve& k : c) reverse_curve(k);
}

void flatten(Chain& c) {
  for (NurbsCurve& k : c) {
    for (Vec3d& q : k.points) q.z = 0;
  }
}

double model_size(const NurbsSurface& s) {
  Vec3d lo = s.points.front(), hi = lo;
  for (const Vec3d& q : s.points) {
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
  }
  return std::max(norm(hi - lo), 1e-300);
}

// Everything a loop builder needs about the patch being built.
struct LoopSite {
  const Context& ctx;
  const NurbsSurface& surface;  // wrapper transform applied
  const Affine& wrapper;        // applied to model-space curves
  Diagnostics& diags;
  int wrapper_index;
};

Chain project_chain(const LoopSite& site, Chain model, int curve_index) {
  const double size = model_size(site.surface);
  const double tol = std::max(site.ctx.options.trim_tolerance, 1e-12) * size;
  Chain uv;
  double dist = 0;
  WorkBudget& budget = job_budget();
  for (NurbsCurve& c : model) {
    apply(site.wrapper, c);
    std::uint64_t left =
        kMaxProjectionsPerEntity - std::min(budget.projections, kMaxProjectionsPerEntity);
    const std::uint64_t had = left;
    uv.push_back(project_to_uv(site.surface, c, tol, dist, left));
    budget.projections += had - left;
    if (left == 0) {
      throw EntityFault(curve_index, "projecting the trim curves needs more than " +
                                         std::to_string(kMaxProjectionsPerEntity) +
                                         " closest-point projections for one patch");
    }
  }
  if (dist > 1e-3 * size) {
    const DirEntry& e = site.ctx.entry(curve_index);
    site.diags.add(Severity::kWarning, e.de, e.param_line, e.type,
                   "model-space trim curve lies up to " + std::to_string(dist) +
                       " (model units) from its surface; projected anyway");
  }
  return uv;
}

// Parameter-space curve, or the model-space one projected, whichever the flags prefer and the
// file provides.
Chain uv_or_projected(const LoopSite& site, int uv_index, int model_index, bool prefer_model,
                      bool reverse_model) {
  if (uv_index >= 0 && !(prefer_model && model_index >= 0)) {
    try {
      Chain uv = convert_curve(site.ctx, uv_index);
      flatten(uv);
      return uv;
    } catch (const EntityFault& f) {
      if (model_index < 0) throw;
      const DirEntry& e = site.ctx.entry(f.index());
      site.diags.add(Severity::kWarning, e.de, e.param_line, e.type,
                     std::string(f.what()) + "; using the model-space curve instead");
    }
  }
  if (model_index < 0) {
    throw EntityFault(site.wrapper_index,
                      "trim curve with neither a parameter-space nor a "
                      "model-space curve");
  }
  Chain model = convert_curve(site.ctx, model_index);
  if (reverse_model) reverse_chain(model);
  return project_chain(site, std::move(model), model_index);
}

// 142 curve on a parametric surface: PREF 2 prefers the model-space curve C.
Chain loop_142(const LoopSite& site, int index) {
  site.ctx.mark(index);
  const Params p(site.ctx.model, index);
  p.require(4, "a curve on a surface");
  const int b = p.pointer(3), c = p.pointer(4);
  const std::int64_t pref = p.integer_or(5, 0);
  return uv_or_projected(site, b, c, pref == 2, false);
}

// 141 boundary: one loop of model-space curves, each with optional parameter-space curves.
Chain loop_141(const LoopSite& site, int index) {
  site.ctx.mark(index);
  const Params p(site.ctx.model, index);
  p.require(4, "a boundary");
  const bool has_uv = p.integer(1) == 1;
  const std::int64_t pref = p.integer(2);
  const std::int64_t n = p.integer(4);
  if (n < 1 || static_cast<std::uint64_t>(n) > p.size())
    p.fault("boundary with " + std::to_string(n) + " curves");
  Chain loop;
  std::size_t k = 5;
  for (std::int64_t i = 0; i < n; ++i) {
    p.require(k + 2, "the boundary curves");
    const int model = p.pointer(k);
    const bool reverse = p.integer(k + 1) == 2;
    const std::int64_t kk = p.integer(k + 2);
    if (kk < 0 || static_cast<std::uint64_t>(kk) > p.size())
      p.fault("bad parameter-space curve count");
    p.require(k + 2 + static_cast<std::uint64_t>(kk), "the parameter-space curves");
    Chain part;
    if (has_uv && kk > 0 && !(pref == 1 && model >= 0)) {
      for (std::int64_t j = 0; j < kk; ++j) {
        Chain c =
            uv_or_projected(site, p.pointer(k + 3 + static_cast<std::size_t>(j)), -1, false, false);
        part.insert(part.end(), c.begin(), c.end());
      }
      if (reverse) reverse_chain(part);
    } else {
      part = uv_or_projected(site, -1, model, true, reverse);
    }
    loop.insert(loop.end(), part.begin(), part.end());
    k += 3 + static_cast<std::size_t>(kk);
  }
  return loop;
}

// 508 loop: edges of 504 lists (or vertices of 502 lists), each with optional (u, v) curves in
// the loop's direction; without them the edge's model curve is used, reversed when OF = 0.
Chain loop_508(const LoopSite& site, int index) {
  site.ctx.mark(index);
  const Params p(site.ctx.model, index);
  const std::int64_t n = p.integer(1);
  if (n < 1 || static_cast<std::uint64_t>(n) > p.size())
    p.fault("loop with " + std::to_string(n) + " edges");
  Chain loop;
  std::size_t k = 2;
  for (std::int64_t e = 0; e < n; ++e) {
    p.require(k + 4, "the loop's edges");
    const std::int64_t type = p.integer(k);
    const int list = p.pointer_to(k + 1, {504, 502}, "edge or vertex list");
    const std::int64_t ndx = p.integer(k + 2);
    const bool same_sense = p.integer(k + 3) != 0;
    const std::int64_t kk = p.integer(k + 4);
    if (kk < 0 || static_cast<std::uint64_t>(kk) > p.size())
      p.fault("bad parameter-space curve count");
    p.require(k + 4 + 2 * static_cast<std::uint64_t>(kk), "the edge's parameter-space curves");
    if (list >= 0) site.ctx.mark(list);
    Chain part;
    for (std::int64_t j = 0; j < kk; ++j) {
      const int uv = p.pointer(k + 6 + 2 * static_cast<std::size_t>(j));
      if (uv < 0) continue;
      Chain c = convert_curve(site.ctx, uv);
      flatten(c);
      part.insert(part.end(), c.begin(), c.end());
    }
    if (type == 0 && list >= 0 && site.ctx.entry(list).type == 504) {
      // The edge's model curve and vertices belong to the face even when (u, v) curves are
      // used: they are marked used, and the curve is projected when there is no (u, v) curve.
      const Params edges(site.ctx.model, list);
      const std::int64_t count = edges.integer(1);
      if (ndx < 1 || ndx > count)
        p.fault("edge index " + std::to_string(ndx) + " outside the edge list DE " +
                std::to_string(2 * list + 1));
      const std::size_t at = 2 + 5 * static_cast<std::size_t>(ndx - 1);
      edges.require(at + 4, "the edge list");
      for (std::size_t v : {at + 1, at + 3}) {
        const int vl = edges.pointer(v);
        if (vl >= 0) site.ctx.mark(vl);
      }
      const int curve = edges.pointer(at);
      if (curve >= 0) site.ctx.mark(curve);
      if (part.empty()) {
        if (curve < 0) edges.fault("edge " + std::to_string(ndx) + " has no curve");
        part = uv_or_projected(site, -1, curve, true, !same_sense);
      }
    }
    loop.insert(loop.end(), part.begin(), part.end());
    k += 5 + 2 * static_cast<std::size_t>(kk);
  }
  return loop;
}

Vec3d start_of(const NurbsCurve& c) { return c.points.front(); }
Vec3d end_of(const NurbsCurve& c) { return c.points.back(); }

// Clamps every curve (so its ends are its end control points) and flips curves that join the
// chain only when reversed.
void orient_chain(Chain& chain, double tol) {
  for (NurbsCurve& c : chain) clamp_to_range(c);
  const std::size_t n = chain.size();
  if (n < 2) return;
  auto near = [&](const Vec3d& a, const Vec3d& b) { return norm(a - b) <= tol; };
  const NurbsCurve& c1 = chain[1];
  if (!near(end_of(chain[0]), start_of(c1)) && !near(end_of(chain[0]), end_of(c1)) &&
      (near(start_of(chain[0]), start_of(c1)) || near(start_of(chain[0]), end_of(c1)))) {
    reverse_curve(chain[0]);
  }
  for (std::size_t i = 1; i < n; ++i) {
    const Vec3d prev = end_of(chain[i - 1]);
    if (!near(start_of(chain[i]), prev) && near(end_of(chain[i]), prev)) reverse_curve(chain[i]);
  }
}

double loop_area(const TrimLoop& loop) {
  double a = 0;
  std::vector<Vec3d> pts;
  for (const NurbsCurve& c : loop.curves_uv) {
    const std::vector<Vec3d> s = sample_points(c, 4);
    pts.insert(pts.end(), s.begin(), s.end());
  }
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec3d& p = pts[i];
    const Vec3d& q = pts[(i + 1) % pts.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

TrimLoop domain_loop(const NurbsSurface& s) {
  const Vec3d a{s.u0, s.v0, 0}, b{s.u1, s.v0, 0}, c{s.u1, s.v1, 0}, d{s.u0, s.v1, 0};
  TrimLoop loop;
  for (auto [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, d}, std::pair{d, a}}) {
    NurbsCurve line;
    line.degree = 1;
    line.knots = {0, 0, 1, 1};
    line.points = {p, q};
    line.weights = {1, 1};
    loop.curves_uv.push_back(line);
  }
  loop.outer = true;
  return loop;
}

// Builds the loops with `make`, dropping (with a warning) those that fail, then puts the outer
// loop first and drops a lone outer loop that is only the natural boundary.
template <class Make>
std::vector<TrimLoop> collect_loops(const LoopSite& site, const std::vector<int>& sources,
                                    int outer_source, Make make) {
  const NurbsSurface& s = site.surface;
  const double tol_uv = 1e-6 * std::max(s.u1 - s.u0, s.v1 - s.v0);
  std::vector<TrimLoop> loops;
  bool have_outer = false;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    try {
      TrimLoop loop{make(sources[i]), sources[i] == outer_source && outer_source >= 0};
      if (loop.curves_uv.empty()) continue;
      orient_chain(loop.curves_uv, 1e3 * tol_uv);
      have_outer = have_outer || loop.outer;
      loops.push_back(std::move(loop));
    } catch (const EntityFault& f) {
      const DirEntry& e = site.ctx.entry(f.index());
      site.diags.add(Severity::kWarning, e.de, e.param_line, e.type,
                     std::string(f.what()) + "; trim loop dropped from the patch of DE " +
                         std::to_string(2 * site.wrapper_index + 1));
    }
  }
  std::stable_partition(loops.begin(), loops.end(), [](const TrimLoop& l) { return l.outer; });
  if (!have_outer && !loops.empty()) loops.insert(loops.begin(), domain_loop(s));
  if (loops.size() == 1 && is_natural_boundary(loops.front(), s)) loops.clear();
  return loops;
}

bool needs_plane_bounds(const Context& ctx, int surface) {
  const DirEntry& e = ctx.entry(surface);
  return e.type == 190 || (e.type == 108 && e.form == 0);
}

// Curves bounding an unbounded plane: the model-space curves of the outer trim loop (142 C
// curve, 141 curves, 508 edge curves), or the 142 (u, v) curve when there is no model curve.
PlaneBounds plane_bounds(const Context& ctx, int loop) {
  PlaneBounds b;
  if (loop < 0) return b;
  const Params p(ctx.model, loop);
  auto add = [&](int curve) {
    if (curve < 0) return;
    for (NurbsCurve& c : convert_curve(ctx, curve)) b.model_curves.push_back(std::move(c));
  };
  const int type = p.entry().type;
  if (type == 142) {
    const int uv = p.pointer(3), model = p.pointer(4);
    if (model >= 0) {
      add(model);
    } else if (uv >= 0) {
      b.uv_curves = convert_curve(ctx, uv);
    }
    return b;
  }
  const std::int64_t n = p.integer(type == 141 ? 4 : 1);
  if (n < 0 || static_cast<std::uint64_t>(n) > p.size()) p.fault("bad curve count");
  std::size_t k = type == 141 ? 5 : 2;
  for (std::int64_t i = 0; i < n; ++i) {
    if (type == 141) {
      add(p.pointer(k));
      const std::int64_t kk = p.integer(k + 2);
      if (kk < 0 || static_cast<std::uint64_t>(kk) > p.size()) p.fault("bad curve count");
      k += 3 + static_cast<std::size_t>(kk);
    } else {  // 508: TYPE, EDGE, NDX, OF, K, (ISOP, CURV) x K
      const int list = p.pointer(k + 1);
      const std::int64_t ndx = p.integer(k + 2), kk = p.integer(k + 4);
      if (kk < 0 || static_cast<std::uint64_t>(kk) > p.size()) p.fault("bad curve count");
      if (p.integer(k) == 0 && list >= 0 && ctx.entry(list).type == 504) {
        const Params edges(ctx.model, list);
        if (ndx < 1 || ndx > edges.integer(1)) p.fault("edge index outside the edge list");
        add(edges.pointer(2 + 5 * static_cast<std::size_t>(ndx - 1)));
      }
      k += 5 + 2 * static_cast<std::size_t>(kk);
    }
  }
  return b;
}

}  // namespace

bool is_wrapper_type(int type) { return type == 143 || type == 144 || type == 510; }

int wrapped_surface(const Context& ctx, int index) {
  try {
    const Params p(ctx.model, index);
    return p.pointer(ctx.entry(index).type == 143 ? 2 : 1);
  } catch (const EntityFault&) {
    return -1;
  }
}

bool is_natural_boundary(const TrimLoop& loop, const NurbsSurface& s) {
  const double du = s.u1 - s.u0, dv = s.v1 - s.v0;
  const double tu = 1e-5 * du, tv = 1e-5 * dv;
  for (const NurbsCurve& c : loop.curves_uv) {
    for (const Vec3d& q : sample_points(c)) {
      const bool on_u = std::fabs(q.x - s.u0) <= tu || std::fabs(q.x - s.u1) <= tu;
      const bool on_v = std::fabs(q.y - s.v0) <= tv || std::fabs(q.y - s.v1) <= tv;
      const bool inside =
          q.x >= s.u0 - tu && q.x <= s.u1 + tu && q.y >= s.v0 - tv && q.y <= s.v1 + tv;
      if (!inside || !(on_u || on_v)) return false;
    }
  }
  return std::fabs(loop_area(loop)) >= (1 - 1e-4) * du * dv;
}

std::optional<Patch> convert_wrapped(const Context& ctx, int index, bool reversed,
                                     Diagnostics& diags) {
  ctx.mark(index);
  const Params p(ctx.model, index);
  const int type = p.entry().type;
  const Affine wrapper = ctx.transforms.of(index);
  Patch patch;
  patch.reversed = reversed;
  patch.wrapper_de = p.entry().de;
  int surface = -1;
  std::vector<int> sources;
  int outer = -1;
  if (type == 144) {
    p.require(4, "a trimmed surface");
    surface = p.pointer(1);
    const std::int64_t n2 = p.integer(3);
    if (n2 < 0 || static_cast<std::uint64_t>(n2) > p.size())
      p.fault("trimmed surface with " + std::to_string(n2) + " inner loops");
    p.require(4 + static_cast<std::uint64_t>(n2), "the inner boundaries");
    outer = p.integer(2) != 0 ? p.pointer_to(4, {142}, "outer boundary") : -1;
    if (outer >= 0) sources.push_back(outer);
    for (std::int64_t i = 0; i < n2; ++i)
      sources.push_back(p.pointer_to(5 + static_cast<std::size_t>(i), {142}, "inner boundary"));
    patch.wrapping = Wrapping::kTrimmed;
  } else if (type == 143) {
    p.require(3, "a bounded surface");
    surface = p.pointer(2);
    const std::int64_t n = p.integer(3);
    if (n < 0 || static_cast<std::uint64_t>(n) > p.size())
      p.fault("bounded surface with " + std::to_string(n) + " boundaries");
    p.require(3 + static_cast<std::uint64_t>(n), "the boundaries");
    for (std::int64_t i = 0; i < n; ++i)
      sources.push_back(p.pointer_to(4 + static_cast<std::size_t>(i), {141}, "boundary"));
    if (!sources.empty()) outer = sources.front();  // re-chosen by area below
    patch.wrapping = Wrapping::kBounded;
  } else {
    p.require(3, "a face");
    surface = p.pointer(1);
    const std::int64_t n = p.integer(2);
    if (n < 0 || static_cast<std::uint64_t>(n) > p.size())
      p.fault("face with " + std::to_string(n) + " loops");
    p.require(3 + static_cast<std::uint64_t>(n), "the face's loops");
    for (std::int64_t i = 0; i < n; ++i)
      sources.push_back(p.pointer_to(4 + static_cast<std::size_t>(i), {508}, "loop"));
    if (p.integer(3) != 0 && !sources.empty()) outer = sources.front();
    patch.wrapping = Wrapping::kFace;
  }
  sources.erase(std::remove(sources.begin(), sources.end(), -1), sources.end());
  if (surface < 0) p.fault("null surface pointer");
  if (!is_surface_type(ctx.entry(surface).type)) {
    p.fault("the wrapped entity DE " + std::to_string(2 * surface + 1) + " of type " +
            std::to_string(ctx.entry(surface).type) + " is not a supported surface");
  }
  // Planes without their own extent take it from the trim curves.
  PlaneBounds bounds;
  const bool plane = needs_plane_bounds(ctx, surface);
  if (plane)
    bounds = plane_bounds(ctx, sources.empty() ? -1 : (outer >= 0 ? outer : sources.front()));
  std::optional<ConvertedSurface> cs =
      convert_surface(ctx, surface, plane ? &bounds : nullptr, diags);
  if (!cs) return std::nullopt;
  patch.surface = std::move(cs->surface);
  apply(wrapper, patch.surface);
  patch.source_type = ctx.entry(surface).type;
  patch.de = ctx.entry(surface).de;
  const LoopSite site{ctx, patch.surface, wrapper, diags, index};
  auto make = [&](int src) {
    const int t = ctx.entry(src).type;
    return t == 142 ? loop_142(site, src) : (t == 141 ? loop_141(site, src) : loop_508(site, src));
  };
  patch.loops = collect_loops(site, sources, outer, make);
  if (type == 143 && patch.loops.size() > 1) {
    // 143 does not say which boundary is outer: the one enclosing the most area is.
    auto biggest = std::max_element(patch.loops.begin(), patch.loops.end(),
                                    [](const TrimLoop& a, const TrimLoop& b) {
                                      return std::fabs(loop_area(a)) < std::fabs(loop_area(b));
                                    });
    for (TrimLoop& l : patch.loops) l.outer = false;
    biggest->outer = true;
    std::rotate(patch.loops.begin(), biggest, biggest + 1);
  }
  return patch;
}

}  // namespace hm::iges
