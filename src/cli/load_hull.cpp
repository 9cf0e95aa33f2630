#include "cli/load_hull.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "core/error.h"

namespace hm::cli {

ImportResult load_hull(const std::string& path, const std::string& units, bool quiet) {
  ImportOptions options;
  options.force_units = units;
  ImportResult r = read_iges_file(path, options);
  if (!quiet) {
    for (const Diagnostic& d : r.diagnostics.items())
      if (d.severity != Severity::kNote)
        std::fprintf(stderr, "%s: %s\n", path.c_str(), format(d).c_str());
  }
  return r;
}

void check_merged_manifold(const std::string& file, const SurfaceMesh& mesh,
                           const EdgeAdjacency& adjacency, const std::string& hint) {
  if (adjacency.nonmanifold_edges.empty()) return;
  const MeshEdge& e = adjacency.edges[adjacency.nonmanifold_edges.front()];
  const Vec3d p = 0.5 * (mesh.positions[e.v0] + mesh.positions[e.v1]);
  throw GeometryError(file + ": merging left " +
                      std::to_string(adjacency.nonmanifold_edges.size()) +
                      " edges with more than two faces (the first near x " + std::to_string(p.x) +
                      ", y " + std::to_string(p.y) + ", z " + std::to_string(p.z) + " m); " + hint);
}

namespace {

std::string describe_patch(std::span<const Patch> patches, PatchId p) {
  if (p >= patches.size()) return "patch " + std::to_string(p);
  const Patch& patch = patches[p];
  std::string s = "patch " + std::to_string(p);
  if (!patch.name.empty()) s += " '" + patch.name + "'";
  if (patch.de > 0) s += " (DE " + std::to_string(patch.de) + ")";
  return s;
}

}  // namespace

SelfIntersections measure_crossings(const SurfaceMesh& mesh) {
  return find_self_intersections(mesh, crossing_tolerance(mesh.positions), 1);
}

std::string describe_crossings(const std::string& file, std::span<const Patch> patches,
                               const SurfaceMesh& mesh, const SelfIntersections& s,
                               const std::string& what) {
  if (s.count == 0 || s.first.empty()) return {};
  const FaceCrossing& c = s.first.front();
  const PatchId pa = c.face_a < mesh.face_patch.size() ? mesh.face_patch[c.face_a] : kInvalid;
  const PatchId pb = c.face_b < mesh.face_patch.size() ? mesh.face_patch[c.face_b] : kInvalid;
  const std::string who = pa == pb
                              ? "faces of " + describe_patch(patches, pa)
                              : describe_patch(patches, pa) + " and " + describe_patch(patches, pb);
  char where[96];
  std::snprintf(where, sizeof where, "x %.4g, y %.4g, z %.4g m", c.where.x, c.where.y, c.where.z);
  return file + ": " + what + " passes through itself: " + std::to_string(s.count) +
         (s.count == 1 ? " pair of faces crosses" : " pairs of faces cross") + ", the first of " +
         who + " near " + where;
}

std::vector<double> parse_numbers_in(const std::string& text, std::size_t count,
                                     const std::string& where) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw UsageError(where + ": '" + item + "' is not a number");
    }
    if (!std::isfinite(out.back())) throw UsageError(where + ": values must be finite");
  }
  if (out.size() != count) {
    throw UsageError(where + ": expected " + std::to_string(count) +
                     " comma-separated numbers, got " + std::to_string(out.size()));
  }
  return out;
}

std::vector<double> parse_numbers(const std::string& text, std::size_t count,
                                  const std::string& option) {
  return parse_numbers_in(text, count, option + " " + text);
}

long long now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double seconds_since(long long start_ns) { return 1e-9 * double(now_ns() - start_ns); }

}  // namespace hm::cli
