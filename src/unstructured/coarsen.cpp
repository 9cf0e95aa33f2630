// Coarsening driver: rounds of collect -> score -> select -> apply -> rescore, then improve.
//
// The index of a candidate collapse v -> t is the paper's q = sum_i (w_i q_i) / 4 over the panels
// the collapse makes (v's faces with v replaced by t):
//   q1 shape       min over those panels of 4 sqrt(3) A / (l0^2 + l1^2 + l2^2)
//   q2 area ratio  smallest over largest area among those panels and t's other faces
//   q3 curvature   size_quality(r_c), r_c = max over the panels of l_eq / (h0 c(x))
//   q4 sources     size_quality(r_s), r_s = max over the panels of l_eq / (h0 s(x))
// with l_eq the edge of the equilateral triangle of the panel's area, size_quality(r) =
// max(0, 1 - r / 2), and c, s the curvature and source factors (coarsen_state.h). Collapses run
// best q first, but only those whose panels stay within a size gate r <= level, where r is the
// largest over the panels of max(l_eq, longest edge) / h(x),
// h = h0 c s: the level starts small and rises when few candidates pass it, so panels grow evenly
// against the field and a source's size is met where it is placed.
#include "unstructured/coarsen.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <numbers>
#include <queue>
#include <string>

#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"
#include "kernels/independent_set.h"
#include "unstructured/coarsen_state.h"

namespace hm {
namespace {

using namespace coarsen_detail;

constexpr std::size_t kDefaultPanels = 4000;
// The per-round loops (regions, applying, rescoring) run hundreds of times on items of a few
// microseconds: below this many items one thread does them faster than two.
constexpr std::size_t kRoundSerialBelow = 512;
constexpr double kFirstLevel = 0.05;
constexpr double kLevelStep = 1.15;
// Witnesses sample the surface at the fine vertices only; the panel can stray a little more
// between them (at its centre over a curved hull), so they are held to this share of the bound
// left after the fine mesh's chord error.
constexpr double kWitnessShare = 0.85;
// The size gate's edge grows by at most this much per metre along the hull.
constexpr double kGrading = 0.15;
// The tightest bend radius the size field follows, in panel edges h, and the passes that settle
// h against it.
constexpr double kTightestRadius = 0.5;
constexpr int kCapPasses = 4;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void check_options(const CoarsenOptions& o) {
  auto finite_nonneg = [](double x) { return std::isfinite(x) && x >= 0; };
  const CoarsenWeights& w = o.weights;
  if (!finite_nonneg(w.shape) || !finite_nonneg(w.area_ratio) || !finite_nonneg(w.curvature) ||
      !finite_nonneg(w.sources) || w.shape + w.area_ratio + w.curvature + w.sources <= 0) {
    throw UsageError("coarsen: weights must be finite, >= 0, and not all zero");
  }
  if (!std::isfinite(o.panel_size) || !std::isfinite(o.max_deviation) ||
      !std::isfinite(o.curvature_length) || !(o.mean_quality >= 0 && o.mean_quality <= 1) ||
      !(o.min_quality >= 0 && o.min_quality <= 1)) {
    throw UsageError("coarsen: sizes must be finite and quality levels in [0, 1]");
  }
  if (!(o.max_normal_change_deg > 0 && o.max_normal_change_deg < 180)) {
    throw UsageError("coarsen: the normal change limit must lie in (0, 180) degrees");
  }
  for (std::size_t i = 0; i < o.sources.size(); ++i) {
    const SizeSource& src = o.sources[i];
    if (!(src.radius > 0 && std::isfinite(src.radius)) ||
        !(src.size > 0 && std::isfinite(src.size)) || !is_finite(src.a) || !is_finite(src.b)) {
      throw UsageError("coarsen: source " + std::to_string(i + 1) +
                       " needs a finite position, a radius > 0 and a size > 0");
    }
  }
}

struct Run {
  State& s;
  const CoarsenOptions& o;
  std::size_t target = 0;  // 0: no panel target
  bool stop_at_size = false;
  std::vector<Candidate> cand;
  double level = kFirstLevel;
  CoarsenReport& report;

  bool target_reached() const { return target > 0 && s.live_faces <= target; }

  void rescore(std::span<const Index> vertices) {
    parallel_for(
        0, vertices.size(),
        [&](std::size_t i) { cand[vertices[i]] = score_vertex(s, vertices[i]); }, 64,
        kRoundSerialBelow);
  }

  // The vertices whose own panels a collapse v -> t changes, to be rescored after it (listed
  // before it, with repeats): t and v's other neighbours. The rest of t's ring keep their panels
  // and their checks; only q2 of their collapses into t sees t's new panels. They are rescored
  // when their own panels change, and any stale candidate is checked again before it is applied.
  void changed_by(Index v, Index t, std::vector<Index>& out) const {
    out.push_back(t);
    for (Index f : s.vertex_faces[v]) {
      for (Index w : s.faces[f]) {
        if (w != v && w != t) out.push_back(w);
      }
    }
  }

  bool any_candidate() const {
    for (const Candidate& c : cand) {
      if (c.target != kInvalid) return true;
    }
    return false;
  }

  // Mean and minimum face index over the live faces (serial sums: thread-count independent).
  std::pair<double, double> face_indices() const {
    std::vector<double> q(s.faces.size(), 0.0);
    parallel_for(0, q.size(), [&](std::size_t f) {
      if (s.face_alive[f]) q[f] = face_index(s, static_cast<Index>(f));
    });
    double sum = 0, lo = 1;
    for (std::size_t f = 0; f < q.size(); ++f) {
      if (!s.face_alive[f]) continue;
      sum += q[f];
      lo = std::min(lo, q[f]);
    }
    return {s.live_faces ? sum / static_cast<double>(s.live_faces) : 0.0, lo};
  }

  // The quality stop rules: the index has come down to the level asked for.
  bool quality_reached(double& last_mean) const {
    if (o.mean_quality <= 0 && o.min_quality <= 0) return false;
    const auto [mean, lo] = face_indices();
    const bool falling = mean < last_mean;
    last_mean = mean;
    return falling && ((o.mean_quality > 0 && mean <= o.mean_quality) ||
                       (o.min_quality > 0 && lo <= o.min_quality));
  }

  // Raise the size gate; false when the gate may rise no further (a panel-size run is done).
  bool raise_level() {
    if (stop_at_size && level >= 1) return false;
    level = stop_at_size ? std::min(1.0, level * kLevelStep) : level * kLevelStep;
    return true;
  }

  void commit(Index v, Applied a, double deviation, const std::array<Index, 2>& joined) {
    if (a == Applied::kDone) {
      ++report.collapses;
      s.live_faces -= cand[v].faces_removed;
      s.max_witness_distance = std::max(s.max_witness_distance, deviation);
      const auto at = std::lower_bound(s.corner_edges.begin(), s.corner_edges.end(), joined);
      if (joined[0] != kInvalid && (at == s.corner_edges.end() || *at != joined)) {
        s.corner_edges.insert(at, joined);
      }
    } else {
      (a == Applied::kRejectedDeviation ? report.rejected_deviation : report.rejected_shape) += 1;
    }
  }

  void batched() {
    std::vector<std::uint8_t> held(s.position.size(), 0), listed(s.position.size(), 0);
    std::vector<Index> pool, offsets, region, dirty, changed, changed_first;
    std::vector<std::uint64_t> keys;
    double last_mean = 2;
    while (!target_reached()) {
      // Collect: live candidates inside the size gate.
      pool.clear();
      for (std::size_t v = 0; v < cand.size(); ++v) {
        if (cand[v].target != kInvalid && cand[v].r <= level) pool.push_back(static_cast<Index>(v));
      }
      std::size_t live_vertices = 0;
      for (std::uint8_t a : s.alive) live_vertices += a;
      const std::size_t batch = std::max<std::size_t>(32, live_vertices / 5);
      if (pool.empty()) {
        if (!any_candidate() || !raise_level()) break;
        continue;
      }
      // Select: the best `batch` by key, then greedily, best first, those whose regions are
      // disjoint (a maximal independent set: local maxima alone keep ~1% of a dense batch). The
      // keys carry the vertex, so they are ranked as plain integers, best first.
      keys.resize(pool.size());
      for (std::size_t i = 0; i < pool.size(); ++i) {
        keys[i] = kernel::priority_key(cand[pool[i]].q, pool[i]);
      }
      if (keys.size() > batch) {
        std::nth_element(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(batch),
                         keys.end(), std::greater<>());
        keys.resize(batch);
      }
      std::sort(keys.begin(), keys.end(), std::greater<>());
      pool.resize(keys.size());
      for (std::size_t i = 0; i < keys.size(); ++i) pool[i] = kernel::key_index(keys[i]);
      // Regions by count -> exclusive scan -> scatter: each candidate writes its own slice.
      offsets.assign(pool.size() + 1, 0);
      for (std::size_t i = 0; i < pool.size(); ++i) {
        const Index v = pool[i];
        offsets[i + 1] = offsets[i] + region_size(s, v, cand[v].target);
      }
      region.resize(offsets.back());
      parallel_for(
          0, pool.size(),
          [&](std::size_t i) {
            collapse_region(
                s, pool[i], cand[pool[i]].target,
                std::span<Index>(region).subspan(offsets[i], offsets[i + 1] - offsets[i]));
          },
          64, kRoundSerialBelow);
      // Best first (as select_greedy returns them), and no further than the panel target.
      std::vector<Index> chosen = kernel::select_greedy(keys, offsets, region, held);
      for (Index& c : chosen) c = pool[c];
      if (target > 0) {
        std::size_t faces = s.live_faces, keep = 0;
        while (keep < chosen.size() && faces > target) faces -= cand[chosen[keep++]].faces_removed;
        chosen.resize(keep);
      }
      changed_first.assign(1, 0);
      changed.clear();
      for (Index v : chosen) {
        changed_by(v, cand[v].target, changed);
        changed_first.push_back(static_cast<Index>(changed.size()));
      }
      // Apply in parallel: the regions are disjoint.
      std::vector<Applied> result(chosen.size());
      std::vector<double> deviation(chosen.size(), 0.0);
      std::vector<std::array<Index, 2>> joined(chosen.size());
      parallel_for(
          0, chosen.size(),
          [&](std::size_t i) {
            result[i] =
                apply_collapse(s, chosen[i], cand[chosen[i]].target, deviation[i], joined[i]);
          },
          8, kRoundSerialBelow / 4);
      // Commit in a fixed order, then rescore what changed.
      dirty.clear();
      for (std::size_t i = 0; i < chosen.size(); ++i) {
        const Index v = chosen[i];
        commit(v, result[i], deviation[i], joined[i]);
        if (result[i] == Applied::kDone) {
          dirty.insert(dirty.end(), changed.begin() + changed_first[i],
                       changed.begin() + changed_first[i + 1]);
          cand[v] = Candidate{};
        } else {
          cand[v] = Candidate{};  // blocked until something around it changes
        }
      }
      // Each vertex once (rescoring writes only its own slot, so the order does not matter).
      std::size_t kept = 0;
      for (Index w : dirty) {
        if (!listed[w]) {
          listed[w] = 1;
          dirty[kept++] = w;
        }
      }
      dirty.resize(kept);
      for (Index w : dirty) listed[w] = 0;
      rescore(dirty);
      ++report.rounds;
      if (quality_reached(last_mean)) break;
      if (pool.size() < batch) raise_level();
    }
  }

  // The reference: one collapse at a time, best first, from a priority queue.
  void serial() {
    struct Entry {
      std::uint64_t key;
      Index v;
      std::uint32_t stamp;
      bool operator<(const Entry& o) const { return key < o.key; }
    };
    std::vector<std::uint32_t> stamp(cand.size(), 0);
    std::vector<Index> dirty;
    double last_mean = 2;
    while (!target_reached()) {
      std::priority_queue<Entry> heap;
      for (std::size_t v = 0; v < cand.size(); ++v) {
        if (cand[v].target != kInvalid && cand[v].r <= level) {
          heap.push({kernel::priority_key(cand[v].q, static_cast<Index>(v)), static_cast<Index>(v),
                     stamp[v]});
        }
      }
      if (heap.empty() && !any_candidate()) break;
      while (!heap.empty() && !target_reached()) {
        const Entry e = heap.top();
        heap.pop();
        if (e.stamp != stamp[e.v] || cand[e.v].target == kInvalid || cand[e.v].r > level) continue;
        const Index t = cand[e.v].target;
        double deviation = 0;
        std::array<Index, 2> joined;
        dirty.clear();
        changed_by(e.v, t, dirty);
        const Applied a = apply_collapse(s, e.v, t, deviation, joined);
        commit(e.v, a, deviation, joined);
        cand[e.v] = Candidate{};
        ++stamp[e.v];
        if (a != Applied::kDone) continue;
        std::sort(dirty.begin(), dirty.end());
        dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
        rescore(dirty);
        for (Index w : dirty) {
          ++stamp[w];
          if (cand[w].target != kInvalid && cand[w].r <= level) {
            heap.push({kernel::priority_key(cand[w].q, w), w, stamp[w]});
          }
        }
      }
      ++report.rounds;
      if (target_reached() || quality_reached(last_mean) || !raise_level()) break;
    }
  }
};

CoarsenedMesh compact(const State& s) {
  CoarsenedMesh out;
  const std::size_t nv = s.position.size();
  std::vector<Index> old2new(nv, kInvalid);
  for (std::size_t v = 0; v < nv; ++v) {
    if (!s.alive[v]) continue;
    old2new[v] = static_cast<Index>(out.vert_new2old.size());
    out.vert_new2old.push_back(static_cast<Index>(v));
    out.mesh.positions.push_back(s.position[v]);
    out.mesh.vertex_patch.push_back(s.vpatch[v]);
    out.mesh.vertex_uv.push_back(s.uv[v]);
    out.vertex_feature.push_back(static_cast<VertexFeature>(s.kind[v]));
  }
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (!s.face_alive[f]) continue;
    const auto& t = s.faces[f];
    out.mesh.faces.push_back({old2new[t[0]], old2new[t[1]], old2new[t[2]], kInvalid});
    out.mesh.face_patch.push_back(s.face_patch[f]);
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (!s.alive[v] || s.kind[v] != Kind::kOnLine) continue;
    for (Index w : s.line_nbr[v]) {
      // Each line edge once: from its smaller end, or from the on-line end when the other is a
      // corner.
      if (s.kind[w] == Kind::kOnLine && w < v) continue;
      out.feature_edges.push_back({old2new[v], old2new[w]});
    }
  }
  for (const auto& e : s.corner_edges) out.feature_edges.push_back({old2new[e[0]], old2new[e[1]]});
  return out;
}

}  // namespace

CoarsenedMesh coarsen(std::span<const Patch> patches, const SurfaceMesh& fine,
                      const EdgeAdjacency& adjacency, const FeatureSet& features,
                      const CoarsenOptions& options, Progress& progress) {
  check_options(options);
  const auto t0 = std::chrono::steady_clock::now();
  progress.stage("coarsen");
  CoarsenReport report;
  report.input_faces = fine.face_count();

  State s;
  build_state(patches, fine, adjacency, features, s);
  BBox3d box;
  for (const Vec3d& p : fine.positions) box.add(p);
  const Vec3d ext = box.hi - box.lo;
  const double length = std::max({ext.x, ext.y, ext.z});
  if (!(length > 0)) throw GeometryError("coarsen: the merged surface has no extent");

  const bool has_quality_stop = options.mean_quality > 0 || options.min_quality > 0;
  std::size_t target = options.target_panels;
  if (target == 0 && !has_quality_stop && options.panel_size <= 0) target = kDefaultPanels;
  report.max_deviation = options.max_deviation > 0 ? options.max_deviation : 1e-3 * length;
  const double chord = options.fine_chord_error > 0 ? options.fine_chord_error : 1e-4 * length;
  if (report.max_deviation < 2 * chord) {
    throw UsageError("coarsen: the deviation bound " + std::to_string(report.max_deviation) +
                     " m is below twice the fine mesh's chord error (" + std::to_string(chord) +
                     " m); tessellate finer or allow more deviation");
  }
  s.bound = kWitnessShare * (report.max_deviation - chord);
  s.sample_bound = report.max_deviation - chord;
  s.cos_normal_change = std::cos(options.max_normal_change_deg * std::numbers::pi / 180);
  s.weights = {options.weights.shape, options.weights.area_ratio, options.weights.curvature,
               options.weights.sources};
  s.field.curvature_length =
      options.curvature_length > 0 ? options.curvature_length : 0.05 * length;
  s.field.w_curvature = options.weights.curvature;
  s.field.w_sources = options.weights.sources;
  s.field.sources = options.sources;
  // The curvature the field follows is capped at a radius of kTightestRadius panels: panels
  // of edge h cannot follow a tighter bend (a rounded stem, a strip patch a few millimetres
  // wide), and shrinking them there only spreads small panels over the hull through the
  // grading. Without --panel-size, h depends on the cap through the calibration: iterate.
  const std::vector<double> kappa = vertex_curvatures(patches, fine);
  s.cfactor.resize(kappa.size());
  const auto set_factors = [&] {
    parallel_for(0, s.cfactor.size(),
                 [&](std::size_t v) { s.cfactor[v] = s.field.curvature_factor(kappa[v]); });
  };
  const auto calibrate = [&] {
    return calibrate_panel_size(fine, s.cfactor, s.field, target > 0 ? target : kDefaultPanels);
  };
  if (options.panel_size > 0) {
    s.field.h0 = options.panel_size;
    s.field.kappa_max = 1 / (kTightestRadius * s.field.h0);
    set_factors();
  } else {
    set_factors();
    s.field.h0 = calibrate();
    for (int it = 0; it < kCapPasses; ++it) {
      s.field.kappa_max = 1 / (kTightestRadius * s.field.h0);
      set_factors();
      const double h = calibrate();
      const bool settled = std::abs(h - s.field.h0) <= 1e-3 * s.field.h0;
      s.field.h0 = h;
      if (settled) break;
    }
  }
  report.panel_size = s.field.h0;
  s.gate_h.resize(s.position.size());
  parallel_for(0, s.gate_h.size(), [&](std::size_t v) {
    s.gate_h[v] = s.field.h0 * s.cfactor[v] * s.field.source_factor(s.position[v]);
  });
  grade_sizes(s, kGrading, s.gate_h);

  Run run{s, options, target, options.panel_size > 0 && target == 0, {}, kFirstLevel, report};
  run.cand.resize(s.position.size());
  std::vector<Index> all(s.position.size());
  for (std::size_t v = 0; v < all.size(); ++v) all[v] = static_cast<Index>(v);
  run.rescore(all);
  report.seconds_setup = seconds_since(t0);

  const auto t1 = std::chrono::steady_clock::now();
  if (options.serial_reference) {
    run.serial();
  } else {
    run.batched();
  }
  if (target > 0 && s.live_faces > target) report.target_reached = false;
  report.size_level = run.level;
  report.seconds_collapse = seconds_since(t1);

  const auto t2 = std::chrono::steady_clock::now();
  const ImproveCounts improved = improve_panels(s, options.improve_passes);
  report.flips = improved.flips;
  report.smoothing_moves = improved.moves;
  report.seconds_improve = seconds_since(t2);

  const auto [mean, lo] = run.face_indices();
  report.mean_quality = mean;
  report.min_quality = lo;
  report.deviation = s.max_witness_distance;
  CoarsenedMesh out = compact(s);
  report.panels = out.mesh.face_count();
  report.vertices = out.mesh.vertex_count();
  out.report = report;
  return out;
}

}  // namespace hm
