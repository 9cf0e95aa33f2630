#include "io/write_polylines.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "io/atomic_file.h"

namespace hm {
namespace {

void put(std::string& s, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  s += buf;
}

std::string csv(std::span<const PolylineRecord> lines) {
  std::string s = "polyline,label,closed,point,x,y,z,patch,u,v\n";
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const PolylineRecord& pl = lines[l];
    for (std::size_t i = 0; i < pl.points.size(); ++i) {
      s += std::to_string(l) + ',' + pl.label + ',' + (pl.closed ? "1" : "0") + ',' +
           std::to_string(i) + ',';
      put(s, pl.points[i].x);
      s += ',';
      put(s, pl.points[i].y);
      s += ',';
      put(s, pl.points[i].z);
      s += ',';
      if (i < pl.point_patch.size()) s += std::to_string(pl.point_patch[i]);
      s += ',';
      if (i < pl.point_uv.size()) {
        put(s, pl.point_uv[i].x);
        s += ',';
        put(s, pl.point_uv[i].y);
      } else {
        s += ',';
      }
      s += '\n';
    }
  }
  return s;
}

std::string vtk(std::span<const PolylineRecord> lines) {
  std::size_t points = 0, conn = 0;
  for (const PolylineRecord& pl : lines) {
    points += pl.points.size();
    conn += 1 + pl.points.size() + (pl.closed ? 1 : 0);
  }
  std::string s = "# vtk DataFile Version 3.0\nhullmesh polylines\nASCII\nDATASET POLYDATA\n";
  s += "POINTS " + std::to_string(points) + " double\n";
  for (const PolylineRecord& pl : lines)
    for (const Vec3d& p : pl.points) {
      put(s, p.x);
      s += ' ';
      put(s, p.y);
      s += ' ';
      put(s, p.z);
      s += '\n';
    }
  s += "LINES " + std::to_string(lines.size()) + ' ' + std::to_string(conn) + '\n';
  std::size_t base = 0;
  for (const PolylineRecord& pl : lines) {
    const std::size_t n = pl.points.size();
    s += std::to_string(n + (pl.closed ? 1 : 0));
    for (std::size_t i = 0; i < n; ++i) s += ' ' + std::to_string(base + i);
    if (pl.closed) s += ' ' + std::to_string(base);
    s += '\n';
    base += n;
  }
  s += "CELL_DATA " + std::to_string(lines.size()) +
       "\nSCALARS polyline int 1\nLOOKUP_TABLE default\n";
  for (std::size_t l = 0; l < lines.size(); ++l) s += std::to_string(l) + '\n';
  s += "POINT_DATA " + std::to_string(points) + "\nSCALARS patch int 1\nLOOKUP_TABLE default\n";
  for (const PolylineRecord& pl : lines)
    for (std::size_t i = 0; i < pl.points.size(); ++i)
      s += (i < pl.point_patch.size() ? std::to_string(pl.point_patch[i]) : std::string("-1")) +
           '\n';
  return s;
}

}  // namespace

void write_polylines(const std::string& path, std::span<const PolylineRecord> lines) {
  const std::string ext = std::filesystem::path(path).extension().string();
  std::string text;
  if (ext == ".csv") {
    text = csv(lines);
  } else if (ext == ".vtk") {
    text = vtk(lines);
  } else {
    throw UsageError(path + ": unknown polyline format '" + ext + "' (known: .csv, .vtk)");
  }
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace hm
