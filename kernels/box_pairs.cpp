#include "kernels/box_pairs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>

#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"

namespace hm {
namespace {

constexpr std::int64_t kAxisCells = std::int64_t{1} << 21;  // 21 bits per axis in a key
constexpr int kMaxWidenings = 8;

struct Grid {
  Vec3d origin;
  double cell = 1;
  std::int64_t nx = 1, ny = 1;  // cells along x and y (those along z only bound the keys)

  std::int64_t index(double x, double o) const {
    const double c = std::floor((x - o) / cell);
    return static_cast<std::int64_t>(std::clamp(c, 0.0, double(kAxisCells - 1)));
  }
  std::array<std::int64_t, 3> of(const Vec3d& p) const {
    return {index(p.x, origin.x), index(p.y, origin.y), index(p.z, origin.z)};
  }
  // The cell's place in x-fastest order: under 2^63 with at most 2^21 cells per axis.
  std::uint64_t key(const std::array<std::int64_t, 3>& c) const {
    return std::uint64_t(c[0] + nx * (c[1] + ny * c[2]));
  }
  // (box, cell) entries of box [l, h]: the cells its range covers.
  std::uint64_t entries(const Vec3d& l, const Vec3d& h) const {
    const auto a = of(l), b = of(h);
    return std::uint64_t(b[0] - a[0] + 1) * std::uint64_t(b[1] - a[1] + 1) *
           std::uint64_t(b[2] - a[2] + 1);
  }
};

struct Entry {
  std::uint64_t key;
  Index box;
  // Bit k: the box starts in this cell along axis k. A pair's intersection has its low corner in
  // the cell of the later start on each axis, so it is this cell when, on every axis, one of
  // the two boxes starts here.
  std::uint8_t starts;
};
constexpr std::uint8_t kStartsHere = 7;

bool sound(const Vec3d& l, const Vec3d& h) {
  return l.x <= h.x && l.y <= h.y && l.z <= h.z && is_finite(l) && is_finite(h);
}

}  // namespace

std::vector<std::array<Index, 2>> overlapping_box_pairs(
    std::span<const Vec3d> lo, std::span<const Vec3d> hi,
    const std::function<bool(Index, Index)>& keep, std::size_t max_entries) {
  if (lo.size() != hi.size())
    throw InternalError("overlapping_box_pairs: lo and hi differ in size");
  const std::size_t n = lo.size();
  if (n >= std::size_t{kInvalid}) {
    throw LimitError("overlapping_box_pairs: " + std::to_string(n) +
                     " boxes exceed 32-bit indices");
  }
  if (n < 2) return {};
  const std::size_t budget = max_entries > 0 ? max_entries : 64 * n + (std::size_t{1} << 20);

  // The grid: its origin at the low corner of all sound boxes, its cell edge the median box
  // extent (a few long boxes do not coarsen it for the rest), never finer than 2^21 cells across.
  BBox3d all;
  std::vector<double> extent;
  extent.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!sound(lo[i], hi[i])) continue;
    all.add(lo[i]);
    all.add(hi[i]);
    const Vec3d e = hi[i] - lo[i];
    extent.push_back(std::max({e.x, e.y, e.z}));
  }
  if (extent.size() < 2) return {};
  const Vec3d span = all.extent();
  const double widest = std::max({span.x, span.y, span.z});
  std::nth_element(extent.begin(), extent.begin() + extent.size() / 2, extent.end());
  Grid grid;
  grid.origin = all.lo;
  grid.cell = extent[extent.size() / 2];
  if (!(grid.cell > 0)) grid.cell = widest / std::cbrt(double(extent.size()));
  grid.cell = std::max(grid.cell, widest / double(kAxisCells - 2));
  if (!(grid.cell > 0)) grid.cell = 1;  // every box is the same point

  // Count -> (widen) -> scan -> scatter -> sort: the entries of each cell side by side, boxes
  // ascending within a cell.
  std::vector<std::uint64_t> count(n + 1, 0);
  for (int widen = 0;; ++widen) {
    parallel_for(
        0, n,
        [&](std::size_t i) { count[i + 1] = sound(lo[i], hi[i]) ? grid.entries(lo[i], hi[i]) : 0; },
        1024);
    std::uint64_t total = 0;
    for (std::size_t i = 1; i <= n; ++i) total += count[i];
    if (total <= budget) break;
    if (widen == kMaxWidenings) {
      throw LimitError("overlapping_box_pairs: " + std::to_string(total) + " grid entries for " +
                       std::to_string(n) + " boxes exceed the limit of " + std::to_string(budget));
    }
    grid.cell *= 2;
  }
  for (std::size_t i = 0; i < n; ++i) count[i + 1] += count[i];
  const auto top = grid.of(all.hi);
  grid.nx = top[0] + 1;
  grid.ny = top[1] + 1;
  const std::uint64_t cells = std::uint64_t(grid.nx * grid.ny * (top[2] + 1));
  std::vector<Entry> entries(count[n]);
  const auto each_entry = [&](std::size_t i, auto&& take) {
    const auto a = grid.of(lo[i]), b = grid.of(hi[i]);
    for (std::int64_t z = a[2]; z <= b[2]; ++z)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t x = a[0]; x <= b[0]; ++x)
          take(grid.key({x, y, z}),
               std::uint8_t((x == a[0]) | (y == a[1]) << 1 | (z == a[2]) << 2));
  };
  if (cells <= 4 * entries.size() + (std::uint64_t{1} << 20) &&
      entries.size() < std::numeric_limits<std::uint32_t>::max()) {
    // Few enough cells for an array of them: a counting sort, boxes ascending within a cell as
    // they are visited (a hull surface fills a tenth to a thirtieth of its box's cells). The
    // array costs 4 bytes a cell, at most 16 an entry (an entry is 16) and 4 MB. With at most 2
    // cells an entry, DTMB 5415's merged surface at 40,000 fine triangles (825,282 cells for
    // 270,513 entries) took the comparison sort below: 16-18 ms on 1 or 2 threads, against 4-8.
    std::vector<std::uint32_t> first(cells + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      if (count[i + 1] > count[i])
        each_entry(i, [&](std::uint64_t k, std::uint8_t) { ++first[k + 1]; });
    }
    for (std::uint64_t c = 0; c < cells; ++c) first[c + 1] += first[c];
    for (std::size_t i = 0; i < n; ++i) {
      if (count[i + 1] == count[i]) continue;
      each_entry(i, [&](std::uint64_t k, std::uint8_t m) {
        entries[first[k]++] = {k, static_cast<Index>(i), m};
      });
    }
  } else {
    parallel_for(
        0, n,
        [&](std::size_t i) {
          std::uint64_t k = count[i];
          if (count[i + 1] > count[i])
            each_entry(i, [&](std::uint64_t key, std::uint8_t m) {
              entries[k++] = {key, static_cast<Index>(i), m};
            });
        },
        1024);
    parallel_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
      return a.key != b.key ? a.key < b.key : a.box < b.box;
    });
  }
  std::vector<std::size_t> run;  // starts of the cells' runs, and the end
  for (std::size_t k = 0; k < entries.size(); ++k) {
    if (k == 0 || entries[k].key != entries[k - 1].key) run.push_back(k);
  }
  run.push_back(entries.size());

  // Pairs per cell, in parallel; the result is sorted at the end, so the order the threads find
  // them in does not matter.
  std::vector<std::array<Index, 2>> out;
  std::mutex out_lock;
  parallel_for(
      0, run.size() - 1,
      [&](std::size_t r) {
        std::vector<std::array<Index, 2>> found;
        for (std::size_t i = run[r]; i < run[r + 1]; ++i) {
          const Index a = entries[i].box;
          const std::uint8_t sa = entries[i].starts;
          for (std::size_t j = i + 1; j < run[r + 1]; ++j) {
            // Otherwise tested in the cell of the pair's low corner.
            if ((sa | entries[j].starts) != kStartsHere) continue;
            const Index b = entries[j].box;
            if (!boxes_meet(lo[a], hi[a], lo[b], hi[b])) continue;
            if (keep(a, b)) found.push_back({a, b});
          }
        }
        if (found.empty()) return;
        const std::lock_guard<std::mutex> guard(out_lock);
        out.insert(out.end(), found.begin(), found.end());
      },
      16);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace hm
