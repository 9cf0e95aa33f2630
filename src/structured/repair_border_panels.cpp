// The paper's three repairs of distorted border panels, chosen by the quality each yields. A
// border panel is a quad with a side on a block border (the face across that side belongs to
// another block: a cut station, a lateral plane or knuckle, the caps at the hull's ends); it is
// distorted when it breaks a panel rule (quad side ratio 4, neighbour area ratio 2). Its inner
// side is the opposite one, shared with its inner neighbour N. Distorted border panels side by
// side along one border (sharing a side from the border inwards) form a run and are repaired
// together: a lone panel's repair would only move its distortion to the panels beside it. The
// repairs of a run:
//   1. remove the panels and extend their N: the inner sides' free nodes merge into their
//      partners on the border (a row's end on the hull's boundary too, where the side between
//      them is a boundary edge and the boundary runs straight through it);
//   2. extend the panels and shrink their N: the inner sides' free nodes move towards N's far
//      side (by 15% or 30% of the way), onto the NURBS;
//   3. split each panel into two triangles (along the diagonal that scores better).
// A candidate is scored by the panels failing a rule among those it changes and the ones beside
// them, then by the worst rule value, over its yardstick, of the panels it changes (as the
// relocation scores a move); the best is kept when it beats the run as it stands, a split only
// when fewer panels fail (it costs quads), and none that leaves more pairs of panels through each
// other, among those it changes and one ring beyond, than there were. Free nodes are row nodes
// off the border rows, breakpoints, caps, knuckles and the boundary.
//
// collect (a distorted border quad, in face order, and its run) -> score (every candidate against
// the mesh as the earlier repairs left it) -> apply the best -> drop the removed faces. Serial
// and in face order, so deterministic.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "mesh/adjacency.h"
#include "query/find_self_intersections.h"
#include "query/hull_query.h"
#include "structured/editable_faces.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// How far along N the inner side moves (repair 2).
constexpr double kExtendSteps[] = {0.15, 0.3};
// A panel on a bridge (bridge_starts) is a border panel when its sides off the bridge are under
// this share of its side on it.
constexpr double kBridgeThin = 0.5;

// The centroid of f's corners other than a and b.
Vec3d off_side(const EditableFaces& m, const Face& f, Index a, Index b) {
  Vec3d sum{0, 0, 0};
  int n = 0;
  for (int k = 0; k < corner_count(f); ++k) {
    if (f[k] == a || f[k] == b) continue;
    sum += m.position(f[k]);
    ++n;
  }
  return n > 0 ? sum / static_cast<double>(n) : sum;
}

// Some side of a face in core has its two faces on one side of it, seen along their mean normal:
// the surface folds over there.
bool folds(const EditableFaces& m, const std::set<Index>& core) {
  for (Index g : core) {
    if (m.removed(g)) continue;
    const Face& f = m.face(g);
    const int c = corner_count(f);
    for (int k = 0; k < c; ++k) {
      const Index a = f[k], b = f[(k + 1) % c];
      const Index h = m.across(g, a, b);
      if (h == kInvalid) continue;
      const Vec3d ng = face_normal(m.positions(), f), nh = face_normal(m.positions(), m.face(h));
      if (ng == Vec3d{} || nh == Vec3d{}) continue;  // no area: no side to fold over
      const Vec3d n = ng + nh;
      const Vec3d pa = m.position(a), ab = m.position(b) - pa;
      const double s1 = dot(cross(ab, off_side(m, f, a, b) - pa), n);
      const double s2 = dot(cross(ab, off_side(m, m.face(h), a, b) - pa), n);
      if (s1 * s2 >= 0) return true;
    }
  }
  return false;
}

// Whether side c of quad p lies on a bridge between two rows' starts (bridge_starts) with the
// quad thin on it: its sides off the bridge under kBridgeThin of the side on it. The strip
// between the bridge and the row before is as thin as the stations are close there; a wider one
// is left, as its inner nodes would move far (ship_449_patches at 15 m, --trim 3 and 1,500
// panels: 2.8 m, and a panel crossed another).
bool on_thin_bridge(const EditableFaces& m, std::span<const NodeSlot> slots, const Face& p, int c) {
  const Index b0 = p[c], b1 = p[(c + 1) % 4], i0 = p[(c + 3) % 4], i1 = p[(c + 2) % 4];
  if (!slots[b0].bridge || !slots[b1].bridge) return false;
  const double thin = kBridgeThin * norm(m.position(b1) - m.position(b0));
  return norm(m.position(i0) - m.position(b0)) < thin &&
         norm(m.position(i1) - m.position(b1)) < thin;
}

}  // namespace

BorderRepairCounts repair_border_panels(const HullQuery& query, std::span<const NodeSlot> slots,
                                        std::span<const std::array<Index, 2>> knuckle_edges,
                                        SurfaceMesh& mesh) {
  BorderRepairCounts counts;
  const std::size_t nv = mesh.vertex_count();
  const NodeFreedom freedom = node_freedom(slots, knuckle_edges, mesh);
  const std::vector<std::uint8_t>& movable = freedom.movable;
  EditableFaces m(mesh.faces, mesh.positions);
  const double cross_tol = crossing_tolerance(mesh.positions);
  const Index nf = static_cast<Index>(mesh.faces.size());
  std::vector<std::uint8_t> merged(nv, 0), done(nf, 0);

  // collect: a distorted border quad, with its border side b0-b1, inner side i1-i0 (i0 beside
  // b0) and inner neighbour n.
  struct Panel {
    Index f, b0, b1, i0, i1, n;
  };
  auto border_panel = [&](Index f, Panel& out) {
    if (f >= nf || done[f] || m.removed(f) || is_triangle(m.face(f))) return false;
    const Face p = m.face(f);
    for (int c = 0; c < 4; ++c) {
      const Index g = m.across(f, p[c], p[(c + 1) % 4]);
      const bool border =
          g == kInvalid ? on_thin_bridge(m, slots, p, c) : mesh.face_block[g] != mesh.face_block[f];
      if (!border) continue;
      double side = 0, area = 0;
      m.rules(f, side, area);
      if (side <= kSideLimit && area <= kAreaLimit) return false;
      out = {f, p[c], p[(c + 1) % 4], p[(c + 3) % 4], p[(c + 2) % 4], kInvalid};
      out.n = m.across(f, out.i1, out.i0);
      return true;
    }
    return false;
  };

  for (Index f0 = 0; f0 < nf; ++f0) {
    Panel first;
    if (!border_panel(f0, first)) continue;
    // A run: the distorted border panels beside one another along the border (sharing a side
    // b-i), repaired together, as a lone panel's repair would only move its distortion to the
    // panels beside it.
    std::vector<Panel> run{first};
    done[f0] = 1;
    for (std::size_t k = 0; k < run.size(); ++k) {
      for (auto [b, i] : {std::pair{run[k].b0, run[k].i0}, std::pair{run[k].b1, run[k].i1}}) {
        const Index g = m.across(run[k].f, b, i);
        Panel next;
        if (g != kInvalid && border_panel(g, next)) {
          done[g] = 1;
          run.push_back(next);
        }
      }
    }
    counts.distorted += run.size();

    // The inner nodes, each with its border partner and the far node it moves towards.
    std::map<Index, std::pair<Index, Vec3d>> inner;  // i -> (b, sum of far positions)
    std::map<Index, int> far_count;
    // Inner nodes that may not move (on the hull's boundary at the run's ends, say) stay.
    bool partners_agree = true, inner_free = true, any_free = false;
    for (const Panel& p : run) {
      for (auto [i, b, other] : {std::tuple{p.i0, p.b0, p.i1}, std::tuple{p.i1, p.b1, p.i0}}) {
        auto [it, fresh] = inner.emplace(i, std::pair{b, Vec3d{0, 0, 0}});
        partners_agree = partners_agree && it->second.first == b;
        any_free = any_free || (movable[i] && !merged[i]);
        if (p.n == kInvalid || mesh.face_block[p.n] != mesh.face_block[p.f]) {
          inner_free = false;
          continue;
        }
        // n's corner beside i that is not on the shared side.
        const Face nf4 = m.face(p.n);
        const int cn = corner_count(nf4);
        const int k = static_cast<int>(std::find(nf4.begin(), nf4.begin() + cn, i) - nf4.begin());
        if (k >= cn) {
          inner_free = false;
          continue;
        }
        const Index a = nf4[(k + 1) % cn], c = nf4[(k + cn - 1) % cn];
        it->second.second += m.position(a == other ? c : a);
        ++far_count[i];
      }
    }
    std::set<Index> scored;
    for (const Panel& p : run)
      for (Index v : {p.b0, p.b1, p.i0, p.i1})
        for (Index g : m.around(v)) scored.insert(g);
    EditableFaces::Score best = m.score(scored);
    const bool folded_before = folds(m, scored);
    // No repair may make panels pass through others one ring beyond the ones it changes: at a
    // stem a few millimetres off the centre plane, a row's panels and a cap's fan over the same
    // strip lie that close (DTMB 5415's sonar dome).
    const std::set<Index> near = m.ring(scored);
    const std::size_t crossed = m.crossings(scored, near, cross_tol);
    int best_kind = 0;  // 0: leave it; 1, 2, 3: the repair of that number
    double best_step = 0;
    std::vector<Face> best_split;

    // score 3: every panel of the run split along the diagonal that scores better.
    std::vector<Face> quads;
    for (const Panel& p : run) quads.push_back(m.face(p.f));
    {
      std::vector<Face> chosen;
      std::vector<Index> added;
      std::set<Index> sc = scored;
      for (const Panel& p : run) {
        const Face q = m.face(p.f);
        Face pick0{}, pick1{};
        EditableFaces::Score pick{std::numeric_limits<std::size_t>::max(), 0};
        for (int d = 0; d < 2; ++d) {
          const Face t0 =
              d == 0 ? Face{q[0], q[1], q[2], kInvalid} : Face{q[0], q[1], q[3], kInvalid};
          const Face t1 =
              d == 0 ? Face{q[0], q[2], q[3], kInvalid} : Face{q[1], q[2], q[3], kInvalid};
          m.set_face(p.f, t0);
          const Index t = m.add_face(t1);
          std::set<Index> local = sc;
          local.insert(t);
          const EditableFaces::Score s3 = m.score(local);
          m.pop_face();
          if (s3.better_than(pick)) {
            pick = s3;
            pick0 = t0;
            pick1 = t1;
          }
        }
        // Keep this panel split while the next ones are chosen.
        m.set_face(p.f, pick0);
        added.push_back(m.add_face(pick1));
        sc.insert(added.back());
        chosen.push_back(pick0);
        chosen.push_back(pick1);
      }
      const EditableFaces::Score s3 = m.score(sc);
      const bool s3_crosses = m.crossings(sc, near, cross_tol) > crossed;
      for (std::size_t k = added.size(); k-- > 0;) m.pop_face();
      for (std::size_t k = 0; k < run.size(); ++k) m.set_face(run[k].f, quads[k]);
      // A split costs quads: it must leave fewer panels failing, not only a milder worst one.
      if (s3.fails < best.fails && !s3_crosses) {
        best = s3;
        best_kind = 3;
        best_split = chosen;
      }
    }
    auto free_node = [&](Index i) { return movable[i] && !merged[i]; };
    // A removal may also merge a row's end node on the hull's boundary into its partner when the
    // side between them is a boundary edge: the boundary loses a node a fraction of a panel from
    // the next, and keeps its line (the keel, the waterline).
    auto mergeable = [&](Index i, Index b) { return !merged[i] && freedom.may_merge(i, b, slots); };
    if (inner_free && any_free && partners_agree) {
      // score 2: the inner nodes towards the far side, onto the NURBS.
      std::map<Index, Vec3d> start;
      for (const auto& [i, bf] : inner)
        if (free_node(i)) start[i] = m.position(i);
      for (double step : kExtendSteps) {
        for (const auto& [i, p0] : start) {
          const Vec3d far = inner[i].second / static_cast<double>(far_count[i]);
          m.set_position(i, query.closest_point(p0 + (far - p0) * step).point);
        }
        const EditableFaces::Score s2 = m.score(scored);
        if (s2.better_than(best) && m.crossings(scored, near, cross_tol) <= crossed) {
          best = s2;
          best_kind = 2;
          best_step = step;
        }
      }
      for (const auto& [i, p0] : start) m.set_position(i, p0);

      // score 1: the inner nodes merge into their border partners.
      std::map<Index, Face> was;
      for (Index g : scored) was[g] = m.face(g);
      for (const auto& [i, bf] : inner) {
        if (mergeable(i, bf.first)) m.merge_node(i, bf.first);
      }
      EditableFaces::Score s1{std::numeric_limits<std::size_t>::max(), 0};
      // A removal that folds the surface over (a merged node's panels lying across the next
      // row's, at a flared stem: property seed 1203) would make panels pass through each other.
      if (m.manifold(scored) && (folded_before || !folds(m, scored)) &&
          m.crossings(scored, near, cross_tol) <= crossed) {
        s1 = m.score(scored);
      }
      for (const auto& [g, h] : was) m.set_face(g, h);
      if (s1.better_than(best)) {
        best = s1;
        best_kind = 1;
      }
    }

    // apply the best.
    if (best_kind == 3) {
      for (std::size_t k = 0; k < run.size(); ++k) {
        m.set_face(run[k].f, best_split[2 * k]);
        m.add_face(best_split[2 * k + 1]);
        mesh.face_block.push_back(mesh.face_block[run[k].f]);
      }
      counts.split += run.size();
    } else if (best_kind == 2) {
      for (const auto& [i, bf] : inner) {
        if (!free_node(i)) continue;
        const Vec3d far = bf.second / static_cast<double>(far_count[i]);
        const ClosestPoint cp =
            query.closest_point(m.position(i) + (far - m.position(i)) * best_step);
        m.set_position(i, cp.point);
        mesh.vertex_patch[i] = cp.patch;
        mesh.vertex_uv[i] = cp.uv;
      }
      counts.extended += run.size();
    } else if (best_kind == 1) {
      std::vector<Index> to_merge;
      for (const auto& [i, bf] : inner)
        if (mergeable(i, bf.first)) to_merge.push_back(i);
      for (Index i : to_merge) {
        m.merge_node(i, inner[i].first);
        merged[i] = 1;
      }
      counts.removed += run.size();
    }
  }

  // Removed faces go now; the merged nodes stay in the arrays, used by no face, until
  // drop_unused_vertices (the steps between still index the vertices as the rows placed them).
  drop_removed_faces(mesh);
  return counts;
}

}  // namespace hm::structured
