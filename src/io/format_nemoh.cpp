// NEMOH mesh file (.dat), as NEMOH's solver and Capytaine's load_MAR read it.
//
//   2 ISYM               2, then 1 when the xz-plane (y = 0) is a plane of symmetry, else 0
//   1 x y z              node table: node number (1, 2, ... in order) and coordinates
//   ...
//   0 0.0 0.0 0.0        closes the node table
//   n1 n2 n3 n4          panel table: four node numbers per panel
//   ...
//   0 0 0 0              closes the panel table
//
// Normals: the panel is described as seen from the fluid looking into the body, corners
// counter-clockwise, so the right-hand rule points into the fluid: hullmesh's convention, no
// reversal. Capytaine reads the file without reordering, and so agrees.
// Symmetry: only y = 0 (ISYM = 1): then one half is given (hullmesh writes the port half,
// y >= 0) and NEMOH mirrors it. Symmetry about x = 0 cannot be expressed (UsageError on write).
// Numbering: node numbers from 1, in order (the reader rejects any other order rather than guess);
// a triangle repeats its first node as the fourth, which is also what Capytaine expects.
// No patches, no title. Numbers: shortest round-trip text (bit for bit).
#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {

void write_nemoh(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  if (o.info.symmetry.about_x0)
    throw UsageError("NEMOH .dat can declare symmetry about y = 0 only, not about x = 0");
  std::string s = o.info.symmetry.about_y0 ? "2 1\n" : "2 0\n";
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    append_uint(s, i + 1);
    for (int k = 0; k < 3; ++k) {
      s += ' ';
      append_real(s, m.positions[i][k]);
    }
    s += '\n';
  }
  s += "0 0.0 0.0 0.0\n";
  for (const Face& f : m.faces) {
    for (int k = 0; k < 4; ++k) {
      append_uint(s, std::uint64_t(f[is_triangle(f) && k == 3 ? 0 : k]) + 1);
      s += k < 3 ? ' ' : '\n';
    }
  }
  s += "0 0 0 0\n";
  put(out, s);
}

MeshFile read_nemoh(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  TextCursor c(bytes, name);
  MeshFile r;
  SurfaceMesh& m = r.mesh;
  std::string_view line;
  std::vector<std::string_view> tok;
  if (!c.next_nonblank_line(line)) c.fail("empty file (expected the '2 ISYM' header)");
  if (split(line, tok) < 2 || to_int(c, tok[0], "header") != 2)
    c.fail("expected the header '2 ISYM' (first number 2)");
  const std::int64_t isym = to_int(c, tok[1], "ISYM");
  if (isym != 0 && isym != 1) c.fail("ISYM must be 0 or 1");
  r.info.symmetry.about_y0 = isym == 1;
  for (;;) {
    if (!c.next_nonblank_line(line))
      c.fail("file ends inside the node table (expected a closing '0 0. 0. 0.' line)");
    split(line, tok);
    if (to_int(c, tok[0], "node number") == 0) break;
    if (tok.size() < 4) c.fail("expected 'number x y z'");
    if (to_int(c, tok[0], "node number") != std::int64_t(m.positions.size()) + 1)
      c.fail("node number " + std::string(tok[0]) + " out of order (expected " +
             std::to_string(m.positions.size() + 1) + ")");
    if (m.positions.size() >= vertex_limit(limits))
      c.fail_limit("more than " + std::to_string(vertex_limit(limits)) + " nodes");
    m.positions.push_back(to_point(c, tok[1], tok[2], tok[3]));
  }
  for (;;) {
    if (!c.next_nonblank_line(line))
      c.fail("file ends inside the panel table (expected a closing '0 0 0 0' line)");
    split(line, tok);
    if (to_int(c, tok[0], "node number") == 0) break;
    if (tok.size() < 3) c.fail("expected four node numbers");
    Index corner[4];
    for (int k = 0; k < 4; ++k)
      corner[k] = to_index(c, tok[k < int(tok.size()) ? k : 2], 1, m.positions.size(), "node");
    Face f;
    if (!collapse_repeated(corner, f)) c.fail("panel has fewer than three distinct nodes");
    if (m.faces.size() >= face_limit(limits))
      c.fail_limit("more than " + std::to_string(face_limit(limits)) + " panels");
    m.faces.push_back(f);
  }
  m.face_patch.assign(m.faces.size(), 0);
  return r;
}

}  // namespace hm::io
