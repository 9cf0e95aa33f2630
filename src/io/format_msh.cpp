// Gmsh MSH 4.1, ASCII.
//
//   $MeshFormat 4.1 0 8 $EndMeshFormat
//   $PhysicalNames: one 2-D physical group per patch, tag patch + 1, named "patch_<patch>"
//   $Entities: one surface entity per patch (tag patch + 1, its bounding box, physical tag
//              patch + 1)
//   $Nodes: one block holding every node (tags 1..N, in vertex order), classified on the first
//           surface
//   $Elements: one block per run of consecutive faces with the same patch and type, so that
//              the face order survives; element type 2 (3-node triangle) and 3 (4-node quad);
//              element tags are face index + 1
//
// Normals: Gmsh orders a surface element's nodes counter-clockwise about its normal (right-hand
// rule) and gives that normal no fixed side; hullmesh writes its own order (normal into the
// fluid) unchanged, and reads a foreign file's order as it is.
// Patches: on read, the first physical tag of an element's surface entity, minus one; an entity
// with no physical tag gives its own tag minus one. Nodes may be numbered in any order and
// sparsely. Elements of dimension 0, 1 and 3 are skipped; 2-D elements other than linear
// triangles and quads are rejected. No symmetry, no title. Numbers: shortest round-trip text.
#include <algorithm>
#include <limits>
#include <map>
#include <unordered_map>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {

void write_msh(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  // Per patch: bounding box of its faces.
  std::map<PatchId, std::pair<Vec3d, Vec3d>> boxes;
  for (std::size_t i = 0; i < m.faces.size(); ++i) {
    const PatchId p = patch_of(m, i);
    if (p >= PatchId(std::numeric_limits<int>::max()))
      throw UsageError("Gmsh .msh: patch id " + std::to_string(p) + " is too large for a tag");
    const Face& f = m.faces[i];
    auto [it, fresh] = boxes.try_emplace(p, m.positions[f[0]], m.positions[f[0]]);
    for (int k = 0; k < corner_count(f); ++k)
      for (int a = 0; a < 3; ++a) {
        it->second.first[a] = std::min(it->second.first[a], m.positions[f[k]][a]);
        it->second.second[a] = std::max(it->second.second[a], m.positions[f[k]][a]);
      }
  }
  std::string s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n";
  append_uint(s, boxes.size());
  s += '\n';
  for (const auto& [p, box] : boxes) {
    s += "2 ";
    append_uint(s, std::uint64_t(p) + 1);
    s += " \"patch_" + std::to_string(p) + "\"\n";
  }
  s += "$EndPhysicalNames\n$Entities\n0 0 ";
  append_uint(s, boxes.size());
  s += " 0\n";
  for (const auto& [p, box] : boxes) {
    append_uint(s, std::uint64_t(p) + 1);
    for (const Vec3d* v : {&box.first, &box.second})
      for (int a = 0; a < 3; ++a) {
        s += ' ';
        append_real(s, (*v)[a]);
      }
    s += " 1 ";
    append_uint(s, std::uint64_t(p) + 1);
    s += " 0\n";
  }
  s += "$EndEntities\n$Nodes\n";
  const std::size_t nv = m.positions.size();
  const std::uint64_t node_entity = boxes.empty() ? 1 : std::uint64_t(boxes.begin()->first) + 1;
  s += nv ? "1 " : "0 ";
  append_uint(s, nv);
  s += nv ? " 1 " : " 0 ";
  append_uint(s, nv);
  s += '\n';
  if (nv) {
    s += "2 ";
    append_uint(s, node_entity);
    s += " 0 ";
    append_uint(s, nv);
    s += '\n';
    for (std::size_t i = 0; i < nv; ++i) {
      append_uint(s, i + 1);
      s += '\n';
    }
    for (const Vec3d& p : m.positions) {
      append_point(s, p);
      s += '\n';
    }
  }
  s += "$EndNodes\n";
  put(out, s);
  s.clear();
  // Runs of faces with one patch and one type.
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  for (std::size_t i = 0; i < m.faces.size(); ++i) {
    if (i == 0 || patch_of(m, i) != patch_of(m, i - 1) ||
        is_triangle(m.faces[i]) != is_triangle(m.faces[i - 1]))
      runs.push_back({i, i});
    runs.back().second = i + 1;
  }
  s += "$Elements\n";
  append_uint(s, runs.size());
  s += ' ';
  append_uint(s, m.faces.size());
  s += m.faces.empty() ? " 0 0\n" : " 1 ";
  if (!m.faces.empty()) {
    append_uint(s, m.faces.size());
    s += '\n';
  }
  for (const auto& [begin, end] : runs) {
    s += "2 ";
    append_uint(s, std::uint64_t(patch_of(m, begin)) + 1);
    s += is_triangle(m.faces[begin]) ? " 2 " : " 3 ";
    append_uint(s, end - begin);
    s += '\n';
    for (std::size_t i = begin; i < end; ++i) {
      append_uint(s, i + 1);
      for (int k = 0; k < corner_count(m.faces[i]); ++k) {
        s += ' ';
        append_uint(s, std::uint64_t(m.faces[i][k]) + 1);
      }
      s += '\n';
    }
    if (s.size() > (1u << 20)) {
      put(out, s);
      s.clear();
    }
  }
  s += "$EndElements\n";
  put(out, s);
}

namespace {

// Nodes per element of each MSH element type (0 = unknown), and its dimension.
int nodes_of_type(std::int64_t type, int& dim) {
  static const struct {
    int type, nodes, dim;
  } kTypes[] = {{1, 2, 1},   {2, 3, 2},   {3, 4, 2},   {4, 4, 3},   {5, 8, 3},   {6, 6, 3},
                {7, 5, 3},   {8, 3, 1},   {9, 6, 2},   {10, 9, 2},  {11, 10, 3}, {12, 27, 3},
                {13, 18, 3}, {14, 14, 3}, {15, 1, 0},  {16, 8, 2},  {17, 20, 3}, {18, 15, 3},
                {19, 13, 3}, {20, 9, 2},  {21, 10, 2}, {22, 12, 2}, {23, 15, 2}, {24, 15, 2},
                {25, 21, 2}, {26, 4, 1},  {27, 5, 1},  {28, 6, 1},  {29, 20, 3}, {30, 35, 3},
                {31, 56, 3}, {92, 64, 3}, {93, 125, 3}};
  for (const auto& t : kTypes)
    if (t.type == type) {
      dim = t.dim;
      return t.nodes;
    }
  return 0;
}

class MshReader {
 public:
  MshReader(std::string_view bytes, const std::string& name, const ResourceLimits& limits)
      : c_(bytes, name), limits_(limits) {}

  MeshFile read() {
    std::string_view t;
    bool format_seen = false;
    while (c_.next_token(t)) {
      if (t.empty() || t[0] != '$')
        c_.fail("expected a section such as $Nodes, found " + std::string(t.substr(0, 20)));
      const std::string section(t.substr(1));
      if (section == "MeshFormat") {
        read_format();
        format_seen = true;
      } else if (!format_seen) {
        c_.fail("the file does not start with $MeshFormat");
      } else if (section == "Entities") {
        read_entities();
      } else if (section == "Nodes") {
        read_nodes();
      } else if (section == "Elements") {
        read_elements();
      } else {
        skip_section(section);
        continue;
      }
      expect("$End" + section);
    }
    if (!format_seen) c_.fail("empty file (expected $MeshFormat)");
    r_.mesh.face_patch.resize(r_.mesh.faces.size(), 0);
    return std::move(r_);
  }

 private:
  std::string_view token(const char* what) { return require_token(c_, what); }
  std::int64_t integer(const char* what) { return to_int(c_, token(what), what); }
  std::size_t count(const char* what, std::uint64_t limit, std::uint64_t min_bytes) {
    return to_count(c_, token(what), what, limit, min_bytes);
  }
  void expect(const std::string& word) {
    const std::string_view t = token(word.c_str());
    if (t != word) c_.fail("expected " + word + ", found " + std::string(t.substr(0, 20)));
  }
  void skip_section(const std::string& section) {
    const std::string end = "$End" + section;
    std::string_view t;
    while (c_.next_token(t))
      if (t == end) return;
    c_.fail("file ends inside $" + section + " (no " + end + ")");
  }

  void read_format() {
    const std::string_view version = token("the MSH version");
    const std::int64_t type = integer("the file type");
    integer("the data size");
    if (version != "4.1")
      c_.fail("MSH version " + std::string(version.substr(0, 10)) +
              " is not supported (hullmesh reads MSH 4.1)");
    if (type != 0) c_.fail("binary MSH is not supported (hullmesh reads ASCII MSH 4.1)");
  }

  void read_entities() {
    std::size_t n[4];
    for (auto& k : n) k = count("an entity count", face_limit(limits_), 4);
    for (int dim = 0; dim < 4; ++dim)
      for (std::size_t e = 0; e < n[dim]; ++e) {
        const std::int64_t tag = integer("an entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k)
          to_real(c_, token("a bounding box"), "bounding box");
        const std::size_t nphys = count("a physical tag count", face_limit(limits_), 2);
        std::int64_t first = 0;
        for (std::size_t k = 0; k < nphys; ++k) {
          const std::int64_t p = integer("a physical tag");
          if (k == 0) first = p;
        }
        if (dim == 2) surface_physical_[tag] = first;
        if (dim > 0) {
          const std::size_t nb = count("a bounding entity count", face_limit(limits_), 2);
          for (std::size_t k = 0; k < nb; ++k) integer("a bounding entity");
        }
      }
  }

  void read_nodes() {
    const std::size_t blocks = count("numEntityBlocks", vertex_limit(limits_), 8);
    const std::size_t total = count("numNodes", vertex_limit(limits_), 8);
    integer("minNodeTag");
    integer("maxNodeTag");
    if (!r_.mesh.positions.empty()) c_.fail("a second $Nodes section");
    auto& pos = r_.mesh.positions;
    pos.reserve(total);
    tags_.reserve(total);
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = integer("entityDim");
      integer("entityTag");
      const std::int64_t parametric = integer("parametric");
      const std::size_t n = count("numNodesInBlock", vertex_limit(limits_), 8);
      if (n > total - tags_.size()) c_.fail("node blocks hold more nodes than numNodes");
      if (dim < 0 || dim > 3 || (parametric != 0 && parametric != 1))
        c_.fail("bad node block header");
      for (std::size_t i = 0; i < n; ++i) tags_.push_back(integer("a node tag"));
      const int extra = parametric ? int(std::min<std::int64_t>(dim, 2)) : 0;
      for (std::size_t i = 0; i < n; ++i) {
        const std::string_view x = token("x"), y = token("y"), z = token("z");
        pos.push_back(to_point(c_, x, y, z));
        for (int k = 0; k < extra; ++k) to_real(c_, token("u, v"), "parametric coordinate");
      }
    }
    if (tags_.size() != total)
      c_.fail(std::to_string(tags_.size()) + " nodes in the blocks, but numNodes is " +
              std::to_string(total));
    // Tag -> index: direct when the tags are consecutive, else a sorted table.
    contiguous_ = true;
    for (std::size_t i = 1; i < tags_.size() && contiguous_; ++i)
      contiguous_ = tags_[i] == tags_[0] + std::int64_t(i);
    if (!contiguous_) {
      sorted_.resize(tags_.size());
      for (std::size_t i = 0; i < tags_.size(); ++i) sorted_[i] = {tags_[i], Index(i)};
      std::sort(sorted_.begin(), sorted_.end());
      for (std::size_t i = 1; i < sorted_.size(); ++i)
        if (sorted_[i].first == sorted_[i - 1].first)
          c_.fail("node tag " + std::to_string(sorted_[i].first) + " is used twice");
    }
  }

  Index node(std::int64_t tag) {
    if (contiguous_ && !tags_.empty()) {
      if (tag >= tags_[0] && tag - tags_[0] < std::int64_t(tags_.size()))
        return Index(tag - tags_[0]);
    } else {
      const auto it =
          std::lower_bound(sorted_.begin(), sorted_.end(), std::pair<std::int64_t, Index>{tag, 0});
      if (it != sorted_.end() && it->first == tag) return it->second;
    }
    c_.fail("element refers to node " + std::to_string(tag) + ", which is not defined");
  }

  void read_elements() {
    const std::size_t blocks = count("numEntityBlocks", face_limit(limits_), 8);
    const std::size_t total = count("numElements", face_limit(limits_), 4);
    integer("minElementTag");
    integer("maxElementTag");
    std::size_t seen = 0;
    auto& faces = r_.mesh.faces;
    auto& patch = r_.mesh.face_patch;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = integer("entityDim");
      const std::int64_t tag = integer("entityTag");
      const std::int64_t type = integer("elementType");
      const std::size_t n = count("numElementsInBlock", face_limit(limits_), 4);
      if (n > total - seen) c_.fail("element blocks hold more elements than numElements");
      seen += n;
      int type_dim = 0;
      const int nodes = nodes_of_type(type, type_dim);
      if (nodes == 0) c_.fail("unknown element type " + std::to_string(type));
      if (type_dim != dim)
        c_.fail("element type " + std::to_string(type) + " in a block of dimension " +
                std::to_string(dim));
      const bool keep = dim == 2;
      if (keep && type != 2 && type != 3)
        c_.fail("element type " + std::to_string(type) +
                " is not supported (hullmesh reads 3-node triangles and 4-node quads)");
      PatchId p = 0;
      if (keep) {
        const auto it = surface_physical_.find(tag);
        const std::int64_t id = it != surface_physical_.end() && it->second != 0 ? it->second : tag;
        if (id < 1 || id > std::int64_t(kInvalid))
          c_.fail("entity or physical tag " + std::to_string(id) + " cannot be a patch id");
        p = PatchId(id - 1);
      }
      for (std::size_t e = 0; e < n; ++e) {
        integer("an element tag");
        Face f{kInvalid, kInvalid, kInvalid, kInvalid};
        for (int k = 0; k < nodes; ++k) {
          const std::int64_t t = integer("a node tag");
          if (keep) f[k] = node(t);
        }
        if (keep) {
          faces.push_back(f);
          patch.push_back(p);
        }
      }
    }
    if (seen != total)
      c_.fail(std::to_string(seen) + " elements in the blocks, but numElements is " +
              std::to_string(total));
  }

  TextCursor c_;
  const ResourceLimits& limits_;
  MeshFile r_;
  std::unordered_map<std::int64_t, std::int64_t> surface_physical_;
  std::vector<std::int64_t> tags_;
  std::vector<std::pair<std::int64_t, Index>> sorted_;
  bool contiguous_ = true;
};

}  // namespace

MeshFile read_msh(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  MshReader reader(bytes, name, limits);
  MeshFile r = reader.read();
  r.info.title.clear();
  return r;
}

}  // namespace hm::io
