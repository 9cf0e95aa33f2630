// WAMIT low-order Geometric Data File (.gdf).
//
//   header line (at most 72 characters)
//   ULEN GRAV            characteristic length; gravity in the same length unit per s^2
//   ISX ISY              1 = x = 0 (resp. y = 0) is a plane of symmetry, else 0
//   NPAN                 number of panels in the file
//   X1 Y1 Z1 ... X4 Y4 Z4 of each panel (free format; hullmesh writes one vertex per line,
//                        which WAMIT, OrcaWave and Capytaine's loader all read)
//
// Normals: WAMIT numbers the vertices counter-clockwise when the panel is seen from the fluid, so
// the right-hand rule over the vertex order points into the fluid: the same as hullmesh's, no
// reversal. (WAMIT's own unit normal n points out of the fluid, into the body; that is computed
// by WAMIT, not written.) Lid panels on the interior free surface (irregular-frequency removal)
// are counter-clockwise seen from above, normal up.
// Symmetry: with ISY = 1 only y >= 0 is panelled (the port half, y to port); with ISX = 1 only
// x >= 0. Both may be set.
// Numbering: none; each panel lists its four vertices. A triangle repeats its first vertex as
// the fourth (two adjacent vertices coincide, as WAMIT requires). The reader welds vertices by
// exact equality of coordinates, in the order first seen, and recognises a triangle by any two
// adjacent coincident vertices.
// Units: lengths in the unit of ULEN; hullmesh writes metres and GRAV = 9.80665 by default.
// Numbers: shortest round-trip text, so positions read back bit for bit.
#include <array>
#include <sstream>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {

void write_gdf(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  if (!(o.info.ulen > 0) || !(o.info.grav > 0))
    throw UsageError("WAMIT .gdf needs ULEN > 0 and GRAV > 0");
  std::string s = one_line(o.info.title, 72) + '\n';
  append_real(s, o.info.ulen);
  s += ' ';
  append_real(s, o.info.grav);
  s += "   ULEN GRAV\n";
  s += o.info.symmetry.about_x0 ? "1 " : "0 ";
  s += o.info.symmetry.about_y0 ? "1   ISX ISY\n" : "0   ISX ISY\n";
  append_uint(s, m.faces.size());
  s += "   NPAN\n";
  put(out, s);
  for (const Face& f : m.faces) {
    s.clear();
    for (int k = 0; k < 4; ++k) {
      const Vec3d& p = m.positions[f[is_triangle(f) && k == 3 ? 0 : k]];
      append_point(s, p);
      s += '\n';
    }
    put(out, s);
  }
}

MeshFile read_gdf(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  TextCursor c(bytes, name);
  MeshFile r;
  std::string_view line;
  if (!c.next_line(line)) c.fail("empty file (expected the WAMIT header line)");
  r.info.title = std::string(trim(line));
  std::vector<std::string_view> tok;
  if (!c.next_line(line) || split(line, tok) < 2) c.fail("expected 'ULEN GRAV'");
  r.info.ulen = to_real(c, tok[0], "ULEN");
  r.info.grav = to_real(c, tok[1], "GRAV");
  if (!(r.info.ulen > 0) || !(r.info.grav > 0)) c.fail("ULEN and GRAV must be positive");
  if (!c.next_line(line) || split(line, tok) < 2) c.fail("expected 'ISX ISY'");
  const std::int64_t isx = to_int(c, tok[0], "ISX"), isy = to_int(c, tok[1], "ISY");
  if ((isx != 0 && isx != 1) || (isy != 0 && isy != 1)) c.fail("ISX and ISY must be 0 or 1");
  r.info.symmetry = {isy == 1, isx == 1};
  if (!c.next_line(line) || split(line, tok) < 1) c.fail("expected NPAN");
  // 12 numbers per panel, at least two bytes each.
  const std::size_t npan = to_count(c, tok[0], "NPAN", face_limit(limits), 24);
  SurfaceMesh& m = r.mesh;
  m.faces.reserve(npan);
  Welder weld(m.positions, npan);
  std::string_view t[3];
  for (std::size_t i = 0; i < npan; ++i) {
    Index corner[4];
    for (int k = 0; k < 4; ++k) {
      for (auto& x : t)
        if (!c.next_token(x))
          c.fail("file ends inside panel " + std::to_string(i + 1) + " of " + std::to_string(npan));
      corner[k] = weld.add(to_point(c, t[0], t[1], t[2]));
    }
    Face f;
    if (!collapse_repeated(corner, f))
      c.fail("panel " + std::to_string(i + 1) + " has fewer than three distinct vertices");
    m.faces.push_back(f);
  }
  m.face_patch.assign(m.faces.size(), 0);
  return r;
}

}  // namespace hm::io
