#include "iges/find_collapsed.h"

#include <algorithm>
#include <cstdio>

namespace hm::iges {
namespace {

constexpr double kPointRel = 1e-9;  // of the model's box diagonal
constexpr double kPointAbs = 1e-9;  // m: a floor for a model that is all points
constexpr double kLineRel = 1e-10;  // of the patch's squared box diagonal

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace

std::vector<std::string> find_collapsed(std::span<const PatchExtent> extents) {
  BBox3d model;
  for (const PatchExtent& e : extents) model.add(e.box);
  const double point_size = std::max(kPointRel * model.diagonal(), kPointAbs);
  std::vector<std::string> why(extents.size());
  for (std::size_t i = 0; i < extents.size(); ++i) {
    const double d = extents[i].box.diagonal();
    if (d <= point_size) {
      why[i] = "the surface collapses to a point (its extent is " + number(d) + " m)";
    } else if (extents[i].grid_area <= kLineRel * d * d) {
      why[i] = "the surface collapses to a line (area " + number(extents[i].grid_area) +
               " m^2 over an extent of " + number(d) + " m)";
    }
  }
  return why;
}

}  // namespace hm::iges
