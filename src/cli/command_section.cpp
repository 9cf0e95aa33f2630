// hullmesh section FILE --x 10.5 --z -2.0 ... -o sections.csv: plane cuts of the hull, refined
// onto the exact NURBS. The obvious tool for a body plan and for checking a hull.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/load_hull.h"
#include "core/error.h"
#include "io/write_polylines.h"
#include "query/hull_query.h"
#include "tessellate/tessellate.h"

namespace hm::cli {
namespace {

struct SectionCommand {
  std::string file;
  std::string output;
  std::string units;
  std::vector<double> xs, ys, zs;
  std::vector<std::string> planes;  // "px,py,pz,nx,ny,nz"
  int stations = 0;
  int waterlines = 0;
  double waterline_z = NAN;  // for sectional areas of x stations
  double chord_relative = 1e-4;
};

struct LabelledPlane {
  std::string label;
  Plane plane;
  bool station = false;  // x = const
};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

Plane parse_plane(const std::string& text) {
  const std::vector<double> v = parse_numbers(text, 6, "--plane px,py,pz,nx,ny,nz");
  const Vec3d n{v[3], v[4], v[5]};
  if (!(norm(n) > 0) || !is_finite(n)) throw UsageError("--plane '" + text + "': zero normal");
  return Plane{{v[0], v[1], v[2]}, n};
}

std::vector<LabelledPlane> collect_planes(const SectionCommand& c, const BBox3d& box) {
  std::vector<LabelledPlane> out;
  for (double x : c.xs) out.push_back({"x=" + number(x), {{x, 0, 0}, {1, 0, 0}}, true});
  for (double y : c.ys) out.push_back({"y=" + number(y), {{0, y, 0}, {0, 1, 0}}, false});
  for (double z : c.zs) out.push_back({"z=" + number(z), {{0, 0, z}, {0, 0, 1}}, false});
  for (const std::string& p : c.planes) out.push_back({"plane " + p, parse_plane(p), false});
  // Evenly spaced interior stations and waterlines over the hull's extent (cell centres, so that
  // the extreme ends, where a section degenerates to a point, are not cut).
  for (int i = 0; i < c.stations; ++i) {
    const double x = box.lo.x + (i + 0.5) * box.extent().x / c.stations;
    out.push_back({"x=" + number(x), {{x, 0, 0}, {1, 0, 0}}, true});
  }
  for (int i = 0; i < c.waterlines; ++i) {
    const double z = box.lo.z + (i + 0.5) * box.extent().z / c.waterlines;
    out.push_back({"z=" + number(z), {{0, 0, z}, {0, 0, 1}}, false});
  }
  if (out.empty())
    throw UsageError(
        "section: give at least one of --x, --y, --z, --plane, --stations, --waterlines");
  return out;
}

// |integral of y dz| over the parts of the polylines below z_max: the area between a station
// curve and the centre plane (y = 0) below the waterline, for one side.
double area_below(const Section& s, double z_max) {
  double area = 0;
  for (const SectionPolyline& pl : s.polylines) {
    const std::size_t n = pl.points.size();
    const std::size_t segments = pl.closed ? n : (n > 0 ? n - 1 : 0);
    double sum = 0;
    for (std::size_t i = 0; i < segments; ++i) {
      Vec3d a = pl.points[i].point, b = pl.points[(i + 1) % n].point;
      if (a.z > z_max && b.z > z_max) continue;
      if (a.z > z_max || b.z > z_max) {  // clip the segment at the waterline
        const double t = (z_max - a.z) / (b.z - a.z);
        const Vec3d m = a + t * (b - a);
        (a.z > z_max ? a : b) = m;
      }
      sum += 0.5 * (std::abs(a.y) + std::abs(b.y)) * (b.z - a.z);
    }
    area += std::abs(sum);
  }
  return area;
}

int run_section(const SectionCommand& c, const GlobalOptions& g) {
  if (c.xs.empty() && c.ys.empty() && c.zs.empty() && c.planes.empty() && c.stations == 0 &&
      c.waterlines == 0)
    throw UsageError(
        "section: give at least one of --x, --y, --z, --plane, --stations, --waterlines");
  const long long t0 = now_ns();
  const ImportResult hull = load_hull(c.file, c.units, g.quiet);
  std::vector<LabelledPlane> planes = collect_planes(c, hull.bbox);
  TessellateOptions to;
  to.chord_tolerance = c.chord_relative * std::max(hull.bbox.extent().x, 1e-12);
  to.measure_chord = false;
  const Tessellation t = tessellate(hull.patches, to, silent_progress());
  const HullQuery query(hull.patches, t.mesh);
  std::vector<Plane> raw(planes.size());
  std::transform(planes.begin(), planes.end(), raw.begin(),
                 [](const LabelledPlane& p) { return p.plane; });
  const std::vector<Section> sections = query.sections(raw);

  std::vector<PolylineRecord> records;
  for (std::size_t i = 0; i < sections.size(); ++i) {
    for (const SectionPolyline& pl : sections[i].polylines) {
      PolylineRecord r;
      r.label = planes[i].label;
      r.closed = pl.closed;
      for (const SectionPoint& p : pl.points) {
        r.points.push_back(p.point);
        r.point_patch.push_back(p.patch);
        r.point_uv.push_back(p.uv);
      }
      records.push_back(std::move(r));
    }
  }
  write_polylines(c.output, records);
  if (g.quiet) return 0;

  const bool areas = !std::isnan(c.waterline_z);
  std::printf("%s: %zu planes, %zu polylines (%.3f s)\n", c.output.c_str(), planes.size(),
              records.size(), seconds_since(t0));
  std::printf("  %-14s %9s %7s %7s %12s%s\n", "plane", "polylines", "closed", "points", "length m",
              areas ? "  area below WL m^2 (one side)" : "");
  std::vector<std::pair<double, double>> station_areas;
  for (std::size_t i = 0; i < sections.size(); ++i) {
    std::size_t points = 0, closed = 0;
    double length = 0;
    for (const SectionPolyline& pl : sections[i].polylines) {
      points += pl.points.size();
      closed += pl.closed ? 1 : 0;
      for (std::size_t k = 1; k < pl.points.size(); ++k)
        length += norm(pl.points[k].point - pl.points[k - 1].point);
      if (pl.closed && pl.points.size() > 1)
        length += norm(pl.points.front().point - pl.points.back().point);
    }
    std::printf("  %-14s %9zu %7zu %7zu %12.6g", planes[i].label.c_str(),
                sections[i].polylines.size(), closed, points, length);
    if (areas && planes[i].station) {
      const double a = area_below(sections[i], c.waterline_z);
      station_areas.push_back({planes[i].plane.point.x, a});
      std::printf("  %12.6g", a);
    }
    std::printf("\n");
  }
  if (areas && station_areas.size() >= 2) {
    // Trapezoid over the stations, closed by zero area at the hull's ends.
    std::sort(station_areas.begin(), station_areas.end());
    std::vector<std::pair<double, double>> pts{{hull.bbox.lo.x, 0.0}};
    pts.insert(pts.end(), station_areas.begin(), station_areas.end());
    pts.push_back({hull.bbox.hi.x, 0.0});
    double volume = 0;
    for (std::size_t k = 1; k < pts.size(); ++k)
      volume += 0.5 * (pts[k].second + pts[k - 1].second) * (pts[k].first - pts[k - 1].first);
    std::printf("  volume below z = %.6g from the stations (one side, trapezoid): %.6g m^3\n",
                c.waterline_z, volume);
  }
  return 0;
}

}  // namespace

void register_section(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto c = std::make_shared<SectionCommand>();
  CLI::App* cmd = app.add_subcommand(
      "section", "Cut the hull with planes (stations, waterlines, buttocks, any plane)");
  cmd->add_option("file", c->file, "IGES file")->required();
  cmd->add_option("-o,--output", c->output, "Output polylines (.csv or .vtk)")->required();
  cmd->add_option("--x", c->xs, "Station plane x = X (repeatable)");
  cmd->add_option("--y", c->ys, "Buttock plane y = Y (repeatable)");
  cmd->add_option("--z", c->zs, "Waterline plane z = Z (repeatable)");
  cmd->add_option("--plane", c->planes, "Any plane: px,py,pz,nx,ny,nz (repeatable)");
  cmd->add_option("--stations", c->stations, "N evenly spaced stations over the hull's length")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--waterlines", c->waterlines, "N evenly spaced waterlines over its height")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--waterline-z", c->waterline_z,
                  "Report each station's area below this z, and the volume they integrate to");
  cmd->add_option("--chord-tol-rel", c->chord_relative,
                  "Tolerance of the internal triangulation, fraction of L (default 1e-4)")
      ->check(CLI::Range(1e-9, 0.1));
  cmd->add_option("--units", c->units, "Force the file's unit (m, mm, cm, in, ft, km)")
      ->check(CLI::IsMember({"m", "mm", "cm", "in", "ft", "km"}));
  cmd->callback(
      [c, &global, &action] { action = [c, &global] { return run_section(*c, global); }; });
}

}  // namespace hm::cli
