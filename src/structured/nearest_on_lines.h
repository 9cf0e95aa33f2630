// Nearest points on the polylines of one station section: the station planner asks, for points
// of one sampled section, where the next section is nearest, hundreds of times per hull.
// Positions in metres, any frame; the polylines should lie in one plane x = const (the grid is
// over (y, z), and the (y, z) distance bounds the 3D one from below, so any polylines give exact
// answers, only more slowly when they spread in x).
#pragma once

#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm::structured {

class NearestOnLines {
 public:
  // Bins the segments of `lines` (consecutive points; a line's last point is also a segment of
  // zero length) in a uniform (y, z) grid of about one segment per cell.
  void build(const std::vector<std::vector<Vec3d>>& lines);

  // The point of the polylines nearest q, exactly as a scan of every segment finds it (ties go
  // to the first segment in line order); q itself when there are no lines.
  Vec3d nearest(const Vec3d& q) const;

 private:
  struct Seg {
    Vec3d a, d;  // from a to a + d
  };
  int cell_y(double y) const;
  int cell_z(double z) const;

  std::vector<Seg> segs_;
  double y0_ = 0, z0_ = 0, cell_ = 1;
  double x_lo_ = 0, x_hi_ = 0;  // x range of every segment: a station's lines lie in its plane
  int ny_ = 0, nz_ = 0;
  std::vector<Index> first_, items_;  // cell i + ny j holds items_[first_[c] .. first_[c + 1])
};

}  // namespace hm::structured
