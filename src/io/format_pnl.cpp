// HAMS panel mesh (HullMesh.pnl; WaterplaneMesh.pnl for the interior waterplane lid has the same
// layout with "Waterplane" in its first and last lines). HAMS reads it with list-directed READs
// that skip a fixed number of lines, so the writer reproduces the layout of HAMS's own examples
// line for line:
//
//       --------------Hull Mesh File---------------
//   (blank)
//       # Number of Panels, Nodes, X-Symmetry and Y-Symmetry
//       NPANEL NNODE ISX ISY
//   (blank)
//       #Start Definition of Node Coordinates     ! node_number   x   y   z
//       1 x y z                        (nodes numbered 1, 2, ... in order)
//      #End Definition of Node Coordinates
//   (blank)
//      #Start Definition of Node Relations   ! panel_number  number_of_vertices  ids...
//       1 4 n1 n2 n3 n4                (or "k 3 n1 n2 n3" for a triangle)
//      #End Definition of Node Relations
//   (blank)
//       --------------End Hull Mesh File---------------
//
// Normals: HAMS computes its panel normal as (P4 - P2) x (P3 - P1) (quads) or
// (P1 - P2) x (P3 - P2) (triangles), the reverse of the right-hand rule, and wants it into the
// body; so the right-hand rule over the written order points into the fluid (HAMS's cylinder
// example confirms it: its bottom panels turn clockwise seen from below). Hull panels: no
// reversal. Waterplane lid panels: HAMS's examples turn counter-clockwise seen from above
// (normal +z), written as given.
// Symmetry: ISX = 1 for x = 0, ISY = 1 for y = 0, one at a time (both is a UsageError); the
// stored half is x >= 0 or y >= 0.
// Waterplane: HAMS stops unless every lid node has |z| <= 1e-10, so the writer checks it.
// Numbering: nodes from 1 in order (the reader rejects another order); triangles are 3-vertex
// panels. No patches, no title. Numbers: shortest round-trip text (bit for bit).
#include <cmath>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {

void write_pnl(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  const MeshSymmetry& sym = o.info.symmetry;
  if (sym.about_x0 && sym.about_y0)
    throw UsageError("HAMS .pnl allows one plane of symmetry at a time (x = 0 or y = 0)");
  const bool lid = o.pnl_waterplane || o.info.waterplane_lid;
  if (lid)
    for (std::size_t i = 0; i < m.positions.size(); ++i)
      if (std::abs(m.positions[i].z) > 1e-10)
        throw GeometryError("HAMS WaterplaneMesh.pnl: node " + std::to_string(i + 1) +
                            " is not on z = 0 (HAMS requires |z| <= 1e-10)");
  const char* kind = lid ? "Waterplane" : "Hull";
  std::string s = std::string("    --------------") + kind + " Mesh File---------------\n \n";
  s += "    # Number of Panels, Nodes, X-Symmetry and Y-Symmetry\n    ";
  append_uint(s, m.faces.size());
  s += "    ";
  append_uint(s, m.positions.size());
  s += sym.about_x0 ? "    1" : "    0";
  s += sym.about_y0 ? "    1\n \n" : "    0\n \n";
  s += "    #Start Definition of Node Coordinates     ! node_number   x   y   z\n";
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    s += "    ";
    append_uint(s, i + 1);
    for (int k = 0; k < 3; ++k) {
      s += "    ";
      append_real(s, m.positions[i][k]);
    }
    s += '\n';
  }
  s += "   #End Definition of Node Coordinates\n \n";
  s += "   #Start Definition of Node Relations   ! panel_number  number_of_vertices   "
       "Vertex1_ID   Vertex2_ID   Vertex3_ID   (Vertex4_ID)\n";
  for (std::size_t i = 0; i < m.faces.size(); ++i) {
    const Face& f = m.faces[i];
    s += "    ";
    append_uint(s, i + 1);
    s += is_triangle(f) ? "    3" : "    4";
    for (int k = 0; k < corner_count(f); ++k) {
      s += "    ";
      append_uint(s, std::uint64_t(f[k]) + 1);
    }
    s += '\n';
  }
  s += "   #End Definition of Node Relations\n \n";
  s += std::string("    --------------End ") + kind + " Mesh File---------------\n";
  put(out, s);
}

namespace {

void find_line(TextCursor& c, std::string_view needle, const char* what) {
  std::string_view line;
  while (c.next_line(line))
    if (line.find(needle) != std::string_view::npos) return;
  c.fail(std::string("file ends before ") + what);
}

}  // namespace

MeshFile read_pnl(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  TextCursor c(bytes, name);
  MeshFile r;
  r.info.title.clear();
  SurfaceMesh& m = r.mesh;
  std::string_view line;
  std::vector<std::string_view> tok;
  if (!c.next_nonblank_line(line)) c.fail("empty file (expected the HAMS mesh header)");
  if (line.find("Mesh File") == std::string_view::npos)
    c.fail("not a HAMS .pnl file (no 'Mesh File' in the first line)");
  r.info.waterplane_lid = line.find("Waterplane") != std::string_view::npos;
  find_line(c, "Number of Panels", "the '# Number of Panels' line");
  if (!c.next_nonblank_line(line) || split(line, tok) < 4)
    c.fail("expected 'panels nodes x-symmetry y-symmetry'");
  const std::size_t npanel = to_count(c, tok[0], "number of panels", face_limit(limits), 8);
  const std::size_t nnode = to_count(c, tok[1], "number of nodes", vertex_limit(limits), 8);
  const std::int64_t isx = to_int(c, tok[2], "X-Symmetry"), isy = to_int(c, tok[3], "Y-Symmetry");
  if ((isx != 0 && isx != 1) || (isy != 0 && isy != 1)) c.fail("symmetry flags must be 0 or 1");
  r.info.symmetry = {isy == 1, isx == 1};
  find_line(c, "Start Definition of Node Coordinates", "the node coordinates");
  m.positions.reserve(nnode);
  for (;;) {
    if (!c.next_nonblank_line(line)) c.fail("file ends inside the node coordinates");
    if (line.find("End Definition") != std::string_view::npos) break;
    if (split(line, tok) < 4) c.fail("expected 'node_number x y z'");
    if (to_int(c, tok[0], "node number") != std::int64_t(m.positions.size()) + 1)
      c.fail("node number " + std::string(tok[0]) + " out of order (expected " +
             std::to_string(m.positions.size() + 1) + ")");
    if (m.positions.size() >= nnode)
      c.fail("more nodes than the " + std::to_string(nnode) + " declared");
    m.positions.push_back(to_point(c, tok[1], tok[2], tok[3]));
  }
  if (m.positions.size() != nnode)
    c.fail(std::to_string(m.positions.size()) + " nodes, but the header declares " +
           std::to_string(nnode));
  find_line(c, "Start Definition of Node Relations", "the node relations (panels)");
  m.faces.reserve(npanel);
  for (;;) {
    if (!c.next_nonblank_line(line)) c.fail("file ends inside the node relations");
    if (line.find("End Definition") != std::string_view::npos) break;
    if (split(line, tok) < 2) c.fail("expected 'panel_number number_of_vertices ids...'");
    const std::int64_t n = to_int(c, tok[1], "number of vertices");
    if (n != 3 && n != 4) c.fail("a panel has 3 or 4 vertices, not " + std::to_string(n));
    if (tok.size() < std::size_t(2 + n)) c.fail("expected " + std::to_string(n) + " vertex ids");
    if (m.faces.size() >= npanel)
      c.fail("more panels than the " + std::to_string(npanel) + " declared");
    Face f{kInvalid, kInvalid, kInvalid, kInvalid};
    for (int k = 0; k < n; ++k) f[k] = to_index(c, tok[2 + k], 1, nnode, "vertex id");
    m.faces.push_back(f);
  }
  if (m.faces.size() != npanel)
    c.fail(std::to_string(m.faces.size()) + " panels, but the header declares " +
           std::to_string(npanel));
  m.face_patch.assign(m.faces.size(), 0);
  return r;
}

}  // namespace hm::io
