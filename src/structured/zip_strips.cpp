// Strips: consecutive rows zipped segment by segment between the breakpoints both carry, in
// parallel (each strip writes its own faces), then committed in row order with their blocks.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "core/parallel.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// The labels two curves share, in the order along the first (a label out of order on the second
// is dropped: the strip cannot follow it).
std::vector<BreakLabel> common_labels(const RowCurve& a, const RowCurve& b) {
  std::vector<BreakLabel> out;
  std::size_t from = 0;
  for (const Breakpoint& x : a.breaks) {
    for (std::size_t k = from; k < b.breaks.size(); ++k) {
      if (b.breaks[k].label == x.label) {
        out.push_back(x.label);
        from = k + 1;
        break;
      }
    }
  }
  return out;
}

double break_s(const RowCurve& c, const BreakLabel& l) {
  for (const Breakpoint& b : c.breaks)
    if (b.label == l) return b.s;
  return -1;
}

// Vertex ids and arc lengths of a row curve's nodes within [s0, s1].
void chain(const std::vector<double>& s, Index first_vertex, double s0, double s1,
           std::vector<Index>& ids, std::vector<double>& frac) {
  ids.clear();
  frac.clear();
  const double len = std::max(s1 - s0, 1e-300);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] < s0 - 1e-9 || s[i] > s1 + 1e-9) continue;
    ids.push_back(first_vertex + static_cast<Index>(i));
    frac.push_back((s[i] - s0) / len);
  }
}

// The bridge's nodes ahead of a chain of the given metric length, fractions over both.
void lead(const StartBridge& br, double length, std::vector<Index>& ids,
          std::vector<double>& frac) {
  const double total = std::max(br.length + length, 1e-300);
  for (double& f : frac) f = (br.length + f * length) / total;
  std::vector<double> at;
  for (double t : br.at) at.push_back(t / total);
  ids.insert(ids.begin(), br.nodes.begin(), br.nodes.end());
  frac.insert(frac.begin(), at.begin(), at.end());
}

const StartBridge* bridge_of(const std::vector<StartBridge>& bridges, std::size_t curve) {
  for (const StartBridge& br : bridges)
    if (br.curve == curve) return &br;
  return nullptr;
}

}  // namespace

std::vector<StripFaces> zip_strips(std::span<const Row> rows, std::span<const RowNodes> nodes,
                                   std::span<const std::vector<Index>> first_vertex,
                                   std::span<const std::vector<StartBridge>> bridges,
                                   std::span<const Vec3d> positions, const ZipOptions& zo,
                                   std::span<const double> row_seconds) {
  // Columns: the strips between consecutive border rows; a block is a column's share between
  // two labels every row of it carries.
  std::vector<std::size_t> column_of(rows.size(), 0);
  std::vector<std::size_t> column_start;
  for (std::size_t j = 0, p = 0; j + 1 < rows.size(); ++j) {
    if (rows[j].border && j > 0) ++p;
    if (rows[j].border) column_start.push_back(j);
    column_of[j] = p;
  }

  std::vector<StripFaces> strips(rows.size() > 0 ? rows.size() - 1 : 0);
  parallel_for_each_item(strips.size(), [&](std::size_t j) {
    const auto t0 = std::chrono::steady_clock::now();
    StripFaces& sf = strips[j];
    struct Stamp {
      StripFaces& sf;
      double grown;
      std::chrono::steady_clock::time_point t0;
      ~Stamp() {
        sf.seconds =
            grown + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      }
    } stamp{sf, row_seconds[j + 1], t0};
    const Row& a = rows[j];
    const Row& b = rows[j + 1];
    if (a.curves.size() != b.curves.size() || a.curves.empty()) {
      sf.unmatched = true;
      return;
    }
    // The labels every row of this column carries, per curve.
    const std::size_t p = column_of[j];
    const std::size_t j0 = column_start[p];
    std::vector<Index> ids_a, ids_b;
    std::vector<double> fa, fb;
    for (std::size_t c = 0; c < a.curves.size(); ++c) {
      std::vector<BreakLabel> column = rows[j0].curves.size() > c
                                           ? common_labels(rows[j0].curves[c], a.curves[c])
                                           : std::vector<BreakLabel>{};
      const std::vector<BreakLabel> labels = common_labels(a.curves[c], b.curves[c]);
      for (std::size_t q = 0; q + 1 < labels.size(); ++q) {
        const double a0 = break_s(a.curves[c], labels[q]), a1 = break_s(a.curves[c], labels[q + 1]);
        const double b0 = break_s(b.curves[c], labels[q]), b1 = break_s(b.curves[c], labels[q + 1]);
        chain(nodes[j].s[c], first_vertex[j][c], a0, a1, ids_a, fa);
        chain(nodes[j + 1].s[c], first_vertex[j + 1][c], b0, b1, ids_b, fb);
        if (ids_a.size() < 1 || ids_b.size() < 1) continue;
        if (labels[q].kind == BreakKind::kLow) {
          if (const StartBridge* br = bridge_of(bridges[j], c)) {
            if (br->forward) {
              lead(*br, b1 - b0, ids_b, fb);
            } else {
              lead(*br, a1 - a0, ids_a, fa);
            }
          }
        }
        const std::size_t before = sf.faces.size();
        const ZipCounts n = zip_chains(ids_a, fa, ids_b, fb, positions, zo, sf.faces);
        sf.counts.quads += n.quads;
        sf.counts.triangles += n.triangles;
        sf.counts.split += n.split;
        // The block: how many of the column's labels lie at or below this segment's start.
        std::size_t seg = 0;
        for (const BreakLabel& l : column) {
          if (break_s(a.curves[c], l) <= a0 + 1e-12) ++seg;
        }
        const std::uint32_t key =
            static_cast<std::uint32_t>((p << 16) | (c << 8) | std::min<std::size_t>(seg, 255));
        sf.block_key.insert(sf.block_key.end(), sf.faces.size() - before, key);
        if (seg >= 1 && seg < column.size()) {
          sf.block_names[key] = {to_string(column[seg - 1]), to_string(column[seg])};
        }
        if (labels[q].kind == BreakKind::kKnuckle) {
          sf.knuckle_edges.push_back({ids_a.front(), ids_b.front()});
        }
      }
    }
  });
  return strips;
}

void commit_strips(std::span<const Row> rows, std::span<const StripFaces> strips,
                   StructuredMesh& out) {
  SurfaceMesh& mesh = out.mesh;
  StructuredReport& rep = out.report;
  // Commit the strips in row order; blocks numbered by their keys in ascending order.
  std::map<std::uint32_t, Index> block_ids;
  for (const StripFaces& sf : strips)
    for (std::uint32_t k : sf.block_key) block_ids.emplace(k, 0);
  Index next_id = 0;
  for (auto& [key, id] : block_ids) id = next_id++;
  rep.blocks.resize(block_ids.size());
  for (const auto& [key, id] : block_ids) {
    BlockReport& br = rep.blocks[id];
    br.id = id;
    br.x0 = std::numeric_limits<double>::infinity();
    br.x1 = -br.x0;
  }
  for (std::size_t j = 0; j < strips.size(); ++j) {
    const StripFaces& sf = strips[j];
    for (const auto& [key, names] : sf.block_names) {
      BlockReport& br = rep.blocks[block_ids[key]];
      if (br.lower.empty()) {
        br.lower =
            (rows[j].curves.size() > 1 ? "curve " + std::to_string((key >> 8) & 255) + " " : "") +
            names[0];
        br.upper = names[1];
      }
    }
    if (sf.unmatched) ++rep.rows_unmatched;
    rep.split_twisted += sf.counts.split;
    for (std::size_t f = 0; f < sf.faces.size(); ++f) {
      const Index id = block_ids[sf.block_key[f]];
      BlockReport& br = rep.blocks[id];
      br.x0 = std::min(br.x0, rows[j].x);
      br.x1 = std::max(br.x1, rows[j + 1].x);
      br.seconds += sf.seconds / static_cast<double>(sf.faces.size());
      mesh.faces.push_back(sf.faces[f]);
      mesh.face_block.push_back(id);
    }
    out.knuckle_edges.insert(out.knuckle_edges.end(), sf.knuckle_edges.begin(),
                             sf.knuckle_edges.end());
  }
  for (BlockReport& br : rep.blocks) {
    br.rows = 0;
    for (const Row& r : rows) br.rows += r.x >= br.x0 - 1e-12 && r.x <= br.x1 + 1e-12;
  }
}

}  // namespace hm::structured
