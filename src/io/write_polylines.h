// Writing polylines (hull sections, knuckle lines, boundaries) as CSV or legacy VTK.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm {

// One polyline in metres. point_patch and point_uv are optional (empty or one per point).
struct PolylineRecord {
  std::string label;  // for example "x=10.5"
  std::vector<Vec3d> points;
  std::vector<PatchId> point_patch;
  std::vector<Vec2d> point_uv;
  bool closed = false;  // the last point joins the first
};

// The format follows the extension: .csv (one row per point: polyline, label, closed, point,
// x, y, z, patch, u, v) or .vtk (legacy POLYDATA with LINES, label index and patch as data).
// Written atomically; throws UsageError for another extension, IoError when it cannot write.
void write_polylines(const std::string& path, std::span<const PolylineRecord> lines);

}  // namespace hm
