// Wavefront OBJ.
//
//   # title
//   # N vertices, F faces
//   v x y z                 one per vertex
//   g patch_<p>             before each run of faces of patch p
//   f a b c [d]             1-based vertex numbers; quads kept as quads
//
// Normals: OBJ's right-hand rule over the vertex order (counter-clockwise seen from the front);
// hullmesh's order (into the fluid) is written unchanged.
// The reader takes "f" corners as i, i/t, i//n or i/t/n, negative (relative) numbers, and
// ignores vt, vn, usemtl, s, l and other statements. Faces must have 3 or 4 corners. Groups
// (g or o) become patches: "patch_<p>" gives p, any other name the next free number in order of
// first appearance; faces before any group get patch 0. No symmetry. Numbers: shortest
// round-trip text (bit for bit).
#include <map>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {

void write_obj(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  std::string s = "# " + one_line(o.info.title, 200) + "\n# " + std::to_string(m.positions.size()) +
                  " vertices, " + std::to_string(m.faces.size()) + " faces\n";
  for (const Vec3d& p : m.positions) {
    s += "v ";
    append_point(s, p);
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
    for (int k = 0; k < corner_count(f); ++k) {
      s += ' ';
      append_uint(s, std::uint64_t(f[k]) + 1);
    }
    s += '\n';
    if (s.size() > (1u << 20)) {
      put(out, s);
      s.clear();
    }
  }
  put(out, s);
}

MeshFile read_obj(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  TextCursor c(bytes, name);
  MeshFile r;
  r.info.title.clear();
  SurfaceMesh& m = r.mesh;
  std::string_view line;
  std::vector<std::string_view> tok;
  std::map<std::string, PatchId, std::less<>> groups;
  PatchId next_free = 0, patch = 0;
  bool first = true;
  while (c.next_line(line)) {
    if (first && line.substr(0, 2) == "# ") r.info.title = std::string(trim(line.substr(2)));
    first = false;
    line = line.substr(0, line.find('#'));
    if (split(line, tok) == 0) continue;
    const std::string_view key = tok[0];
    if (key == "v") {
      if (tok.size() < 4) c.fail("expected 'v x y z'");
      if (m.positions.size() >= vertex_limit(limits))
        c.fail_limit("more than " + std::to_string(vertex_limit(limits)) + " vertices");
      m.positions.push_back(to_point(c, tok[1], tok[2], tok[3]));
    } else if (key == "f") {
      const std::size_t n = tok.size() - 1;
      if (n < 3 || n > 4)
        c.fail("a face with " + std::to_string(n) + " corners (hullmesh reads 3 or 4)");
      Face f{kInvalid, kInvalid, kInvalid, kInvalid};
      for (std::size_t k = 0; k < n; ++k) {
        const std::string_view v = tok[k + 1].substr(0, tok[k + 1].find('/'));
        const std::int64_t i = to_int(c, v, "vertex number");
        const std::int64_t nv = std::int64_t(m.positions.size());
        const std::int64_t at = i < 0 ? nv + i : i - 1;
        if (i == 0 || at < 0 || at >= nv)
          c.fail("vertex number " + std::to_string(i) + " out of range (" + std::to_string(nv) +
                 " vertices so far)");
        f[k] = Index(at);
      }
      if (m.faces.size() >= face_limit(limits))
        c.fail_limit("more than " + std::to_string(face_limit(limits)) + " faces");
      m.faces.push_back(f);
      m.face_patch.push_back(patch);
    } else if (key == "g" || key == "o") {
      const std::string gname = tok.size() > 1 ? std::string(tok[1]) : std::string();
      const auto it = groups.find(gname);
      if (it != groups.end()) {
        patch = it->second;
      } else {
        std::int64_t p = -1;
        if (gname.rfind("patch_", 0) == 0 && parse_int(std::string_view(gname).substr(6), p) &&
            p >= 0 && p < std::int64_t(kInvalid)) {
          patch = PatchId(p);
        } else {
          patch = next_free;
        }
        groups.emplace(gname, patch);
        if (patch >= next_free) next_free = patch + 1;
      }
    }
  }
  return r;
}

}  // namespace hm::io
