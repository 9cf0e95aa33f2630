#include "mesh/snap_centre_plane.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace hm {

std::size_t snap_to_centre_plane(SurfaceMesh& mesh, double tol) {
  std::vector<std::uint64_t> keys;
  for (const Face& f : mesh.faces) {
    const int n = f[3] == kInvalid ? 3 : 4;
    for (int k = 0; k < n; ++k) {
      const Index a = f[k], b = f[(k + 1) % n];
      keys.push_back((std::uint64_t{std::min(a, b)} << 32) | std::max(a, b));
    }
  }
  std::sort(keys.begin(), keys.end());
  std::size_t moved = 0;
  auto snap = [&](Index v) {
    double& y = mesh.positions[v].y;
    if (y != 0 && std::abs(y) <= tol) {
      y = 0;
      ++moved;
    }
  };
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    if (j - i == 1) {
      snap(static_cast<Index>(keys[i] >> 32));
      snap(static_cast<Index>(keys[i] & 0xffffffffu));
    }
    i = j;
  }
  return moved;
}

}  // namespace hm
