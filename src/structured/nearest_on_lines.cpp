#include "structured/nearest_on_lines.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/bbox.h"

namespace hm::structured {

void NearestOnLines::build(const std::vector<std::vector<Vec3d>>& lines) {
  segs_.clear();
  first_.clear();
  items_.clear();
  BBox3d box;
  for (const std::vector<Vec3d>& l : lines) {
    for (std::size_t i = 0; i < l.size(); ++i) {
      segs_.push_back({l[i], i + 1 < l.size() ? l[i + 1] - l[i] : Vec3d{0, 0, 0}});
      box.add(l[i]);
    }
  }
  if (segs_.empty()) return;
  // About one segment per cell along the curve, at most 256 cells across the larger extent, and
  // at most about 4 cells per segment in all: a curve fills a thin share of its box, and a grid
  // of one segment per cell over the whole box grows as the square of the segments (a 300-point
  // section's 22,000 cells, zeroed for each of kcs's 500 sampled sections, were 9% of a run).
  const double ey = box.hi.y - box.lo.y, ez = box.hi.z - box.lo.z;
  const double span = std::max({ey, ez, 1e-300});
  const double n = static_cast<double>(segs_.size());
  cell_ = std::max({span / 256, (ey + ez) / n, std::sqrt(ey * ez / (4 * n))});
  if (!(cell_ > 0)) cell_ = 1;
  y0_ = box.lo.y;
  z0_ = box.lo.z;
  x_lo_ = box.lo.x;
  x_hi_ = box.hi.x;
  ny_ = static_cast<int>(ey / cell_) + 1;
  nz_ = static_cast<int>(ez / cell_) + 1;
  // Count -> scan -> fill: each segment goes into every cell its (y, z) box overlaps.
  std::vector<Index> count(static_cast<std::size_t>(ny_) * nz_ + 1, 0);
  auto for_cells = [&](const Seg& sg, auto&& f) {
    const Vec3d b = sg.a + sg.d;
    const int i0 = cell_y(std::min(sg.a.y, b.y)), i1 = cell_y(std::max(sg.a.y, b.y));
    const int j0 = cell_z(std::min(sg.a.z, b.z)), j1 = cell_z(std::max(sg.a.z, b.z));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) f(static_cast<std::size_t>(i) + ny_ * j);
  };
  for (const Seg& sg : segs_) for_cells(sg, [&](std::size_t c) { ++count[c + 1]; });
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  first_ = count;
  items_.resize(count.back());
  for (std::size_t k = 0; k < segs_.size(); ++k) {
    for_cells(segs_[k], [&](std::size_t c) { items_[count[c]++] = static_cast<Index>(k); });
  }
}

int NearestOnLines::cell_y(double y) const {
  return std::clamp(static_cast<int>((y - y0_) / cell_), 0, ny_ - 1);
}

int NearestOnLines::cell_z(double z) const {
  return std::clamp(static_cast<int>((z - z0_) / cell_), 0, nz_ - 1);
}

Vec3d NearestOnLines::nearest(const Vec3d& q) const {
  Vec3d best = q;
  if (segs_.empty()) return best;
  double best_d = std::numeric_limits<double>::infinity();
  Index best_k = kInvalid;
  const int ci = cell_y(q.y), cj = cell_z(q.z);
  // q may lie outside the grid: distances then count from the grid's edge.
  const double out_y = std::max({y0_ - q.y, q.y - (y0_ + ny_ * cell_), 0.0});
  const double out_z = std::max({z0_ - q.z, q.z - (z0_ + nz_ * cell_), 0.0});
  // Every segment lies at least this far from q in x. The grid is in (y, z); a query from the
  // next station lies a station's step off the lines' plane, and without this part of the bound
  // the rings grew until they were that step wide in (y, z) too.
  const double out_x = std::max({x_lo_ - q.x, q.x - x_hi_, 0.0});
  // Rings of cells around q's cell (Chebyshev distance r), until no cell beyond can be nearer.
  for (int r = 0;; ++r) {
    for (int j = cj - r; j <= cj + r; ++j) {
      if (j < 0 || j >= nz_) continue;
      const bool edge_row = j == cj - r || j == cj + r;
      const int step = edge_row || r == 0 ? 1 : 2 * r;
      for (int i = ci - r; i <= ci + r; i += step) {
        if (i < 0 || i >= ny_) continue;
        const std::size_t c = static_cast<std::size_t>(i) + ny_ * j;
        for (Index t = first_[c]; t < first_[c + 1]; ++t) {
          const Index k = items_[t];
          const Seg& sg = segs_[k];
          const double dd = squared_norm(sg.d);
          const double f = dd > 0 ? std::clamp(dot(q - sg.a, sg.d) / dd, 0.0, 1.0) : 0.0;
          const Vec3d p = sg.a + sg.d * f;
          const double dist = squared_norm(p - q);
          if (dist < best_d || (dist == best_d && k < best_k)) {
            best_d = dist;
            best_k = k;
            best = p;
          }
        }
      }
    }
    // A cell beyond ring r lies at least r cells farther from q in y or in z.
    const double far_y = out_y + r * cell_, far_z = out_z + r * cell_;
    const double reach2 =
        out_x * out_x + std::min(far_y * far_y + out_z * out_z, out_y * out_y + far_z * far_z);
    if (best_d <= reach2 || (r >= ny_ && r >= nz_)) return best;
  }
}

}  // namespace hm::structured
