// STL, binary (default) or ASCII (MeshWriteOptions::stl_ascii).
//
// Binary: an 80-byte header ("binary STL from <title>"), a little-endian uint32 triangle count,
// then per triangle 12 float32 (normal, three vertices) and a uint16 attribute (0).
// ASCII: solid <title> / facet normal nx ny nz / outer loop / vertex x y z (x3) / endloop /
// endfacet / endsolid <title>.
//
// Normals: STL orders each triangle's vertices counter-clockwise seen from outside the solid (the
// right-hand rule points out of the solid, which for a hull is into the fluid): hullmesh's
// convention, no reversal. The stored facet normal is that unit normal; readers ignore it and
// use the vertex order.
// Quads are split along their 0-2 diagonal into (0,1,2) and (0,2,3); a read gives triangles.
// Precision: binary stores float32 (positions come back to float precision); ASCII writes
// shortest round-trip doubles, so it reads back bit for bit.
// Numbering: none. The reader welds vertices by exact equality of coordinates (-0 = +0), in the
// order first seen, so the result is the same on every run. The reader detects the kind: a file
// whose size is 84 + 50 n for the count n it declares is binary, else one starting with "solid"
// is ASCII. No patches, no symmetry.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {
namespace {

template <typename F>
void for_each_triangle(const SurfaceMesh& m, F&& f) {
  const auto& p = m.positions;
  for (const Face& face : m.faces) {
    f(p[face[0]], p[face[1]], p[face[2]]);
    if (!is_triangle(face)) f(p[face[0]], p[face[2]], p[face[3]]);
  }
}

void write_stl_binary(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  char header[80] = {};
  std::snprintf(header, sizeof header, "binary STL from %s", one_line(o.info.title, 60).c_str());
  out.write(header, 80);
  std::uint32_t n = 0;
  for (const Face& f : m.faces) n += is_triangle(f) ? 1 : 2;
  char count[4];
  for (int b = 0; b < 4; ++b) count[b] = char((n >> (8 * b)) & 0xff);  // little endian
  out.write(count, 4);
  std::string buf;
  buf.reserve(50 * 4096);
  for_each_triangle(m, [&](const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const Vec3d nrm = normalized(cross(b - a, c - a));
    const float v[12] = {float(nrm.x), float(nrm.y), float(nrm.z), float(a.x),
                         float(a.y),   float(a.z),   float(b.x),   float(b.y),
                         float(b.z),   float(c.x),   float(c.y),   float(c.z)};
    char rec[50] = {};
    std::memcpy(rec, v, 48);
    buf.append(rec, 50);
    if (buf.size() >= 50 * 4096) {
      put(out, buf);
      buf.clear();
    }
  });
  put(out, buf);
}

void write_stl_ascii(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  const std::string title = one_line(o.info.title, 200);
  std::string s = "solid " + title + '\n';
  auto vec = [&](const Vec3d& v) {
    append_real(s, v.x);
    s += ' ';
    append_real(s, v.y);
    s += ' ';
    append_real(s, v.z);
    s += '\n';
  };
  for_each_triangle(m, [&](const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    s += "  facet normal ";
    vec(normalized(cross(b - a, c - a)));
    s += "    outer loop\n";
    for (const Vec3d* v : {&a, &b, &c}) {
      s += "      vertex ";
      vec(*v);
    }
    s += "    endloop\n  endfacet\n";
    if (s.size() > (1u << 20)) {
      put(out, s);
      s.clear();
    }
  });
  s += "endsolid " + title + '\n';
  put(out, s);
}

MeshFile read_binary(std::string_view bytes, const std::string& name, std::uint32_t n,
                     const ResourceLimits& limits) {
  MeshFile r;
  std::string title(bytes.substr(0, 80));
  title = title.substr(0, title.find('\0'));
  if (title.rfind("binary STL from ", 0) == 0) title = title.substr(16);
  r.info.title = std::string(trim(one_line(title, 80)));
  if (n > face_limit(limits))
    throw LimitError(name + ": binary STL declares " + std::to_string(n) +
                     " triangles, over the limit of " + std::to_string(face_limit(limits)));
  SurfaceMesh& m = r.mesh;
  m.faces.reserve(n);
  Welder weld(m.positions, n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const std::size_t at = 84 + 50 * std::size_t(t);
    float v[12];
    std::memcpy(v, bytes.data() + at, 48);
    Face f{kInvalid, kInvalid, kInvalid, kInvalid};
    for (int k = 0; k < 3; ++k) {
      const Vec3d p{v[3 + 3 * k], v[4 + 3 * k], v[5 + 3 * k]};
      if (!is_finite(p))
        throw InputError(name + ": triangle " + std::to_string(t + 1) + " (byte offset " +
                         std::to_string(at) + "): a vertex coordinate is not finite");
      f[k] = weld.add(p);
    }
    m.faces.push_back(f);
  }
  return r;
}

void expect(TextCursor& c, const char* word) {
  std::string_view t;
  if (!c.next_token(t)) c.fail(std::string("file ends before '") + word + "'");
  if (t != word)
    c.fail(std::string("expected '") + word + "', found '" + std::string(t.substr(0, 20)) + "'");
}

MeshFile read_ascii(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  TextCursor c(bytes, name);
  MeshFile r;
  std::string_view line;
  c.next_line(line);
  r.info.title = std::string(trim(trim(line).substr(5)));
  SurfaceMesh& m = r.mesh;
  Welder weld(m.positions, 1024);
  std::string_view t;
  bool closed = false;
  while (c.next_token(t)) {
    if (t == "endsolid") {
      closed = true;
      c.next_line(line);  // the name after endsolid
      continue;
    }
    if (t == "solid") {  // another solid in the same file
      closed = false;
      c.next_line(line);
      continue;
    }
    if (t != "facet") c.fail("expected 'facet', found '" + std::string(t.substr(0, 20)) + "'");
    expect(c, "normal");
    for (int k = 0; k < 3; ++k) {
      double ignored;
      if (!c.next_token(t) || !parse_double(t, ignored)) c.fail("expected a facet normal");
    }
    expect(c, "outer");
    expect(c, "loop");
    Face f{kInvalid, kInvalid, kInvalid, kInvalid};
    for (int k = 0; k < 3; ++k) {
      expect(c, "vertex");
      std::string_view x, y, z;
      if (!c.next_token(x) || !c.next_token(y) || !c.next_token(z))
        c.fail("file ends inside a vertex");
      if (m.positions.size() >= vertex_limit(limits))
        c.fail_limit("more than " + std::to_string(vertex_limit(limits)) + " vertices");
      f[k] = weld.add(to_point(c, x, y, z));
    }
    expect(c, "endloop");
    expect(c, "endfacet");
    if (m.faces.size() >= face_limit(limits))
      c.fail_limit("more than " + std::to_string(face_limit(limits)) + " facets");
    m.faces.push_back(f);
  }
  if (!closed) c.fail("file ends without 'endsolid'");
  return r;
}

}  // namespace

void write_stl(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  if (o.stl_ascii)
    write_stl_ascii(out, m, o);
  else
    write_stl_binary(out, m, o);
}

MeshFile read_stl(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  MeshFile r;
  std::uint32_t n = 0;
  if (bytes.size() >= 84) {
    const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + 80);
    n = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
        std::uint32_t(b[3]) << 24;
  }
  if (bytes.size() >= 84 && bytes.size() == 84 + 50 * std::uint64_t(n)) {
    r = read_binary(bytes, name, n, limits);
  } else if (trim(bytes.substr(0, 512)).substr(0, 5) == "solid") {
    r = read_ascii(bytes, name, limits);
  } else if (bytes.size() < 84) {
    throw InputError(name + ": not an STL file (" + std::to_string(bytes.size()) +
                     " bytes: too short for binary, and no 'solid' line)");
  } else {
    throw InputError(name + ": binary STL declares " + std::to_string(n) + " triangles (" +
                     std::to_string(84 + 50 * std::uint64_t(n)) + " bytes) but the file has " +
                     std::to_string(bytes.size()) + " bytes (truncated?)");
  }
  r.mesh.face_patch.assign(r.mesh.faces.size(), 0);
  return r;
}

}  // namespace hm::io
