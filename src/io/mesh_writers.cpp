#include "io/mesh_writers.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace hm::io {
namespace {

// Shortest text that reads back to the same double.
void put_double(std::string& s, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  s += buf;
}

std::size_t triangle_count(const SurfaceMesh& m) {
  std::size_t n = 0;
  for (const Face& f : m.faces) n += is_triangle(f) ? 1 : 2;
  return n;
}

}  // namespace

void write_vtu(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  std::string s;
  s.reserve(64 * (m.positions.size() + m.faces.size()) + 1024);
  s += "<?xml version=\"1.0\"?>\n<!-- " + o.title + " -->\n";
  s += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n";
  s += "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" + std::to_string(m.positions.size()) +
       "\" NumberOfCells=\"" + std::to_string(m.faces.size()) + "\">\n";
  s += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec3d& p : m.positions) {
    put_double(s, p.x);
    s += ' ';
    put_double(s, p.y);
    s += ' ';
    put_double(s, p.z);
    s += '\n';
  }
  s += "</DataArray>\n</Points>\n<Cells>\n";
  s += "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const Face& f : m.faces) {
    for (int k = 0; k < corner_count(f); ++k)
      s += std::to_string(f[k]) + (k + 1 < corner_count(f) ? " " : "\n");
  }
  s += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  std::size_t offset = 0;
  for (const Face& f : m.faces) {
    offset += corner_count(f);
    s += std::to_string(offset) + '\n';
  }
  s += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (const Face& f : m.faces) s += is_triangle(f) ? "5\n" : "9\n";  // VTK_TRIANGLE, VTK_QUAD
  s += "</DataArray>\n</Cells>\n<CellData>\n";
  auto int_array = [&](const char* name, const std::vector<Index>& v) {
    s += std::string("<DataArray type=\"Int64\" Name=\"") + name + "\" format=\"ascii\">\n";
    for (Index x : v) s += (x == kInvalid ? std::string("-1") : std::to_string(x)) + '\n';
    s += "</DataArray>\n";
  };
  if (!m.face_patch.empty()) int_array("patch", m.face_patch);
  if (!m.face_block.empty()) int_array("block", m.face_block);
  for (const FaceField& field : o.face_fields) {
    s += std::string("<DataArray type=\"Float64\" Name=\"") + field.name + "\" format=\"ascii\">\n";
    for (double v : field.values) {
      put_double(s, v);
      s += '\n';
    }
    s += "</DataArray>\n";
  }
  s += "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

void write_stl_binary(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  char header[80] = {};
  std::snprintf(header, sizeof header, "binary STL from %s", o.title.c_str());
  out.write(header, 80);
  const std::uint32_t n = static_cast<std::uint32_t>(triangle_count(m));
  out.write(reinterpret_cast<const char*>(&n), 4);
  std::vector<char> rec(50);
  auto put_tri = [&](const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const Vec3d nrm = normalized(cross(b - a, c - a));
    const float v[12] = {float(nrm.x), float(nrm.y), float(nrm.z), float(a.x),
                         float(a.y),   float(a.z),   float(b.x),   float(b.y),
                         float(b.z),   float(c.x),   float(c.y),   float(c.z)};
    std::memcpy(rec.data(), v, 48);
    rec[48] = rec[49] = 0;
    out.write(rec.data(), 50);
  };
  const auto& p = m.positions;
  for (const Face& f : m.faces) {
    put_tri(p[f[0]], p[f[1]], p[f[2]]);
    if (!is_triangle(f)) put_tri(p[f[0]], p[f[2]], p[f[3]]);
  }
}

void write_obj(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  std::string s = "# " + o.title + "\n# " + std::to_string(m.positions.size()) + " vertices, " +
                  std::to_string(m.faces.size()) + " faces\n";
  for (const Vec3d& p : m.positions) {
    s += "v ";
    put_double(s, p.x);
    s += ' ';
    put_double(s, p.y);
    s += ' ';
    put_double(s, p.z);
    s += '\n';
  }
  Index group = kInvalid;
  for (std::size_t i = 0; i < m.faces.size(); ++i) {
    const Face& f = m.faces[i];
    if (!m.face_patch.empty() && m.face_patch[i] != group) {
      group = m.face_patch[i];
      s += "g patch_" + std::to_string(group) + '\n';
    }
    s += 'f';
    for (int k = 0; k < corner_count(f); ++k) s += ' ' + std::to_string(f[k] + 1);  // 1-based
    s += '\n';
  }
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

}  // namespace hm::io
