// Hydrostar mesh file (.hst), single body, as Hydrostar, Capytaine and BEMRosetta read it:
//
//   PROJECT: title
//   NBBODY 1
//   NUMPANEL 1 1 N        body 1, one part, N panels
//   SYMMETRY ISYM         0 none, 1 about the xz-plane (y = 0), 2 about the xz- and yz-planes
//   COORDINATES TYPE 0
//   1 x y z               nodes numbered 1, 2, ... in order
//   ENDCOORDINATES
//   PANEL TYPE 0
//   n1 n2 n3 n4           or n1 n2 n3 for a triangle (PANEL TYPE 1 puts a panel number first)
//   ENDPANEL
//   ENDFILE
//
// Normals: the right-hand rule over the node order points into the fluid, as Capytaine and
// BEMRosetta read these files without reordering: hullmesh's convention, no reversal.
// Symmetry: ISYM 1 keeps y >= 0, ISYM 2 also x >= 0. Symmetry about x = 0 alone cannot be
// expressed (UsageError on write). The reader also takes "SYMMETRY_BODY ibody ISYM".
// Numbering: nodes from 1 in order (the reader rejects another order); a four-node record with a
// repeated node is read as a triangle. Single body only (NBBODY > 1 is rejected). No patches.
// Numbers: shortest round-trip text (bit for bit), always with a decimal point.
#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {

void write_hst(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  const MeshSymmetry& sym = o.info.symmetry;
  if (sym.about_x0 && !sym.about_y0)
    throw UsageError("Hydrostar .hst cannot declare symmetry about x = 0 alone");
  std::string s = "PROJECT: " + one_line(o.info.title, 200) + "\nNBBODY 1\nNUMPANEL 1 1 ";
  append_uint(s, m.faces.size());
  s += sym.about_x0 ? "\nSYMMETRY 2\n" : (sym.about_y0 ? "\nSYMMETRY 1\n" : "\nSYMMETRY 0\n");
  s += "COORDINATES TYPE 0\n";
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    append_uint(s, i + 1);
    for (int k = 0; k < 3; ++k) {
      s += ' ';
      append_real(s, m.positions[i][k]);
    }
    s += '\n';
  }
  s += "ENDCOORDINATES\nPANEL TYPE 0\n";
  for (const Face& f : m.faces) {
    for (int k = 0; k < corner_count(f); ++k) {
      append_uint(s, std::uint64_t(f[k]) + 1);
      s += k + 1 < corner_count(f) ? ' ' : '\n';
    }
  }
  s += "ENDPANEL\nENDFILE\n";
  put(out, s);
}

namespace {

void read_panels(TextCursor& c, int type, SurfaceMesh& m, const ResourceLimits& limits) {
  std::string_view line;
  std::vector<std::string_view> tok;
  for (;;) {
    if (!c.next_nonblank_line(line)) c.fail("file ends inside a PANEL block (no ENDPANEL)");
    if (starts_with_word(line, "ENDPANEL")) return;
    const std::size_t n = split(line, tok);
    const std::size_t first = type == 1 ? 1 : 0;
    if (n < first + 3 || n > first + 4) c.fail("expected 3 or 4 node numbers");
    if (type == 1 && to_int(c, tok[0], "panel number") != std::int64_t(m.faces.size()) + 1)
      c.fail("panel number " + std::string(tok[0]) + " out of order");
    Index corner[4];
    for (std::size_t k = 0; k < 4; ++k)
      corner[k] =
          to_index(c, tok[first + std::min(k, n - first - 1)], 1, m.positions.size(), "node");
    Face f;
    if (!collapse_repeated(corner, f)) c.fail("panel has fewer than three distinct nodes");
    if (m.faces.size() >= face_limit(limits))
      c.fail_limit("more than " + std::to_string(face_limit(limits)) + " panels");
    m.faces.push_back(f);
  }
}

void read_nodes(TextCursor& c, SurfaceMesh& m, const ResourceLimits& limits) {
  std::string_view line;
  std::vector<std::string_view> tok;
  if (!m.positions.empty()) c.fail("a second COORDINATES block (one body only)");
  for (;;) {
    if (!c.next_nonblank_line(line)) c.fail("file ends inside COORDINATES (no ENDCOORDINATES)");
    if (starts_with_word(line, "ENDCOORDINATES")) return;
    const std::size_t n = split(line, tok);
    if (n != 3 && n != 4) c.fail("expected 'number x y z'");
    if (n == 4 && to_int(c, tok[0], "node number") != std::int64_t(m.positions.size()) + 1)
      c.fail("node number " + std::string(tok[0]) + " out of order (expected " +
             std::to_string(m.positions.size() + 1) + ")");
    if (m.positions.size() >= vertex_limit(limits))
      c.fail_limit("more than " + std::to_string(vertex_limit(limits)) + " nodes");
    m.positions.push_back(to_point(c, tok[n - 3], tok[n - 2], tok[n - 1]));
  }
}

}  // namespace

MeshFile read_hst(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  TextCursor c(bytes, name);
  MeshFile r;
  r.info.title.clear();
  SurfaceMesh& m = r.mesh;
  std::string_view line;
  std::vector<std::string_view> tok;
  bool any = false, saw_panels = false;
  while (c.next_nonblank_line(line)) {
    const std::string_view t = trim(line);
    if (t[0] == '#') continue;
    split(t, tok);
    const std::string_view key = tok[0];
    if (key == "ENDFILE") {
      any = true;
      break;
    } else if (key == "COORDINATES") {
      read_nodes(c, m, limits);
    } else if (key == "PANEL") {
      const std::int64_t type = tok.size() >= 3 ? to_int(c, tok[2], "PANEL TYPE") : -1;
      if (tok.size() < 3 || tok[1] != "TYPE" || (type != 0 && type != 1))
        c.fail("expected 'PANEL TYPE 0' or 'PANEL TYPE 1'");
      read_panels(c, int(type), m, limits);
      saw_panels = true;
    } else if (key == "SYMMETRY" || key == "SYMMETRY_BODY") {
      const std::size_t at = key == "SYMMETRY" ? 1 : 2;
      if (tok.size() <= at) c.fail("expected a symmetry index");
      const std::int64_t isym = to_int(c, tok[at], "symmetry");
      if (isym < 0 || isym > 2) c.fail("symmetry must be 0, 1 or 2");
      r.info.symmetry = {isym >= 1, isym == 2};
    } else if (key == "NUMPANEL") {
      if (tok.size() < 2) c.fail("expected 'NUMPANEL body part count'");
      to_count(c, tok.back(), "NUMPANEL", face_limit(limits), 0);
    } else if (key == "NBBODY") {
      if (tok.size() < 2 || to_int(c, tok[1], "NBBODY") != 1)
        c.fail("only single-body files are read (NBBODY 1)");
    } else if (key.substr(0, 7) == "PROJECT") {
      r.info.title = std::string(trim(t.substr(7)));
      if (!r.info.title.empty() && r.info.title[0] == ':')
        r.info.title = std::string(trim(std::string_view(r.info.title).substr(1)));
    }
    any = true;  // other keywords (RHO, GRAVITY, USER, ...) carry nothing for the mesh
  }
  if (!any) c.fail("empty file");
  if (!saw_panels) c.fail("no PANEL block");
  m.face_patch.assign(m.faces.size(), 0);
  return r;
}

}  // namespace hm::io
