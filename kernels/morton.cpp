#include "kernels/morton.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "kernels/order_by_key.h"

namespace hm {
namespace {

constexpr int kBits = 21;
constexpr double kCells = double((1u << kBits) - 1);

// Spreads the low 21 bits of x so that bit i lands on bit 3i.
std::uint64_t spread3(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

std::uint64_t quantize(double v, double lo, double scale) {
  const double q = (v - lo) * scale;
  if (!(q > 0)) return 0;  // also NaN
  return q >= kCells ? std::uint64_t(kCells) : std::uint64_t(q);
}

}  // namespace

void morton_codes(std::span<const Vec3d> points, const BBox3d& box,
                  std::span<std::uint64_t> codes) {
  const Vec3d e = box.extent();
  // One scale for all axes keeps cells cubic, so the order follows distance, not aspect.
  const double extent = std::max({e.x, e.y, e.z});
  const double scale = extent > 0 ? kCells / extent : 0;
  parallel_for(
      0, points.size(),
      [&](std::size_t i) {
        const Vec3d& p = points[i];
        codes[i] = spread3(quantize(p.x, box.lo.x, scale)) |
                   spread3(quantize(p.y, box.lo.y, scale)) << 1 |
                   spread3(quantize(p.z, box.lo.z, scale)) << 2;
      },
      1024);
}

std::vector<Index> morton_order(std::span<const Vec3d> points) {
  BBox3d box;
  for (const Vec3d& p : points) box.add(p);
  std::vector<std::uint64_t> codes(points.size());
  morton_codes(points, box, codes);
  return order_by_key(codes);  // ties by index
}

}  // namespace hm
