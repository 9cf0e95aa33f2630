// VTK legacy (.vtk), ASCII.
//
//   # vtk DataFile Version 3.0
//   title (one line, at most 255 characters)
//   ASCII
//   DATASET POLYDATA
//   POINTS N double          x y z per vertex
//   POLYGONS F SIZE          "3 a b c" or "4 a b c d" per face, 0-based
//   FIELD FieldData 1        symmetry 2 1 int: about_y0 about_x0 (0 or 1)
//   CELL_DATA F              SCALARS patch int, SCALARS block int (-1 = none), then one
//                            SCALARS <name> double per extra face field
//
// The reader also takes DATASET UNSTRUCTURED_GRID (CELLS / CELL_TYPES: 5 triangle, 9 quad,
// 7 polygon of 3 or 4 points; vertex and line cells and 3-D cells are skipped, other 2-D cells
// rejected), POLYDATA with VERTICES and LINES (skipped), and the VTK 5.1 layout with
// OFFSETS / CONNECTIVITY. Keywords are case-insensitive, as in VTK. Binary files are rejected.
// Normals: VTK's right-hand rule over the point order; hullmesh writes its own order (into the
// fluid) unchanged. Numbering from 0. Numbers: shortest round-trip text (bit for bit).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <span>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {
namespace {

std::string vtk_name(const char* name) {
  std::string s(name);
  for (char& ch : s)
    if (std::isspace(static_cast<unsigned char>(ch))) ch = '_';
  return s.empty() ? "field" : s;
}

void int_scalars(std::string& s, const char* name, const std::vector<Index>& v) {
  s += std::string("SCALARS ") + name + " int 1\nLOOKUP_TABLE default\n";
  for (Index x : v) {
    if (x == kInvalid || x > 0x7fffffffu)
      s += "-1";
    else
      append_uint(s, x);
    s += '\n';
  }
}

}  // namespace

void write_vtk(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  std::string s = "# vtk DataFile Version 3.0\n" + one_line(o.info.title, 255) +
                  "\nASCII\nDATASET POLYDATA\nPOINTS ";
  append_uint(s, m.positions.size());
  s += " double\n";
  for (const Vec3d& p : m.positions) {
    append_point(s, p);
    s += '\n';
  }
  std::size_t size = 0;
  for (const Face& f : m.faces) size += 1 + corner_count(f);
  s += "POLYGONS ";
  append_uint(s, m.faces.size());
  s += ' ';
  append_uint(s, size);
  s += '\n';
  for (const Face& f : m.faces) {
    s += is_triangle(f) ? '3' : '4';
    for (int k = 0; k < corner_count(f); ++k) {
      s += ' ';
      append_uint(s, f[k]);
    }
    s += '\n';
  }
  s += "FIELD FieldData 1\nsymmetry 2 1 int\n";
  s += o.info.symmetry.about_y0 ? "1 " : "0 ";
  s += o.info.symmetry.about_x0 ? "1\n" : "0\n";
  if (!m.faces.empty()) {
    s += "CELL_DATA ";
    append_uint(s, m.faces.size());
    s += '\n';
    std::vector<Index> patch(m.faces.size());
    for (std::size_t i = 0; i < patch.size(); ++i) patch[i] = patch_of(m, i);
    int_scalars(s, "patch", patch);
    if (!m.face_block.empty()) int_scalars(s, "block", m.face_block);
    for (const FaceField& field : o.face_fields) {
      s += "SCALARS " + vtk_name(field.name) + " double 1\nLOOKUP_TABLE default\n";
      for (double v : field.values) {
        append_real(s, v);
        s += '\n';
      }
    }
  }
  put(out, s);
}

namespace {

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

class VtkReader {
 public:
  VtkReader(std::string_view bytes, const std::string& name, const ResourceLimits& limits)
      : c_(bytes, name), limits_(limits) {}

  MeshFile read() {
    std::string_view line;
    if (!c_.next_line(line)) c_.fail("empty file");
    if (line.substr(0, 14) != "# vtk DataFile") c_.fail("not a legacy VTK file (first line)");
    if (!c_.next_line(line)) c_.fail("file ends before the title line");
    r_.info.title = std::string(trim(line));
    if (!c_.next_line(line)) c_.fail("file ends before ASCII");
    if (iequals(trim(line), "BINARY")) c_.fail("binary legacy VTK is not supported");
    if (!iequals(trim(line), "ASCII")) c_.fail("expected ASCII");
    const std::string_view kw = word("DATASET");
    if (!iequals(kw, "DATASET")) c_.fail("expected DATASET");
    const std::string_view type = word("the dataset type");
    if (iequals(type, "POLYDATA"))
      grid_ = false;
    else if (iequals(type, "UNSTRUCTURED_GRID"))
      grid_ = true;
    else
      c_.fail("dataset " + std::string(type.substr(0, 30)) +
              " is not supported (POLYDATA or UNSTRUCTURED_GRID)");
    std::string_view t;
    while (c_.next_token(t)) {
      if (iequals(t, "POINTS")) {
        read_points();
      } else if (iequals(t, "POLYGONS")) {
        read_cells(/*polygons=*/true, /*keep=*/true);
      } else if (iequals(t, "VERTICES") || iequals(t, "LINES")) {
        read_cells(true, false);
      } else if (iequals(t, "TRIANGLE_STRIPS")) {
        c_.fail("triangle strips are not supported");
      } else if (iequals(t, "CELLS")) {
        read_cells(false, true);
      } else if (iequals(t, "CELL_TYPES")) {
        read_cell_types();
      } else if (iequals(t, "FIELD")) {
        read_field(/*cells=*/0, /*keep=*/false);
      } else if (iequals(t, "CELL_DATA")) {
        finish_cells();
        const std::size_t n = count("CELL_DATA", face_limit(limits_) * 2, 2);
        if (n != cell_count_)
          c_.fail("CELL_DATA " + std::to_string(n) + " does not match the " +
                  std::to_string(cell_count_) + " cells");
        read_attributes(n, true);
      } else if (iequals(t, "POINT_DATA")) {
        const std::size_t n = count("POINT_DATA", vertex_limit(limits_), 2);
        read_attributes(n, false);
      } else if (iequals(t, "METADATA")) {
        skip_metadata();
      } else {
        c_.fail("unexpected keyword " + std::string(t.substr(0, 30)));
      }
    }
    finish_cells();
    SurfaceMesh& m = r_.mesh;
    m.face_patch.resize(m.faces.size(), 0);
    if (!m.face_block.empty()) m.face_block.resize(m.faces.size(), kInvalid);
    for (const Face& f : m.faces)
      for (int k = 0; k < corner_count(f); ++k)
        if (f[k] >= m.positions.size())
          c_.fail("a cell refers to point " + std::to_string(f[k]) + " of " +
                  std::to_string(m.positions.size()));
    return std::move(r_);
  }

 private:
  std::string_view word(const char* what) { return require_token(c_, what); }
  std::int64_t integer(const char* what) { return to_int(c_, word(what), what); }
  std::size_t count(const char* what, std::uint64_t limit, std::uint64_t min_bytes) {
    return to_count(c_, word(what), what, limit, min_bytes);
  }

  void read_points() {
    if (!r_.mesh.positions.empty()) c_.fail("a second POINTS section");
    const std::size_t n = count("POINTS", vertex_limit(limits_), 6);
    word("the point data type");
    r_.mesh.positions.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::string_view x = word("x"), y = word("y"), z = word("z");
      r_.mesh.positions.push_back(to_point(c_, x, y, z));
    }
  }

  // Cells as (point count, ids); VTK 5.1 files give OFFSETS and CONNECTIVITY instead.
  void read_cells(bool polygons, bool keep) {
    const std::size_t n = count("the cell count", face_limit(limits_) * 2, 2);
    const std::size_t size = count("the cell list size", 8 * face_limit(limits_), 2);
    const TextCursor::Mark mark = c_.mark();
    std::string_view t;
    if (c_.next_token(t) && iequals(t, "OFFSETS")) {
      word("the offsets type");
      if (n == 0) c_.fail("OFFSETS needs at least one entry");
      std::vector<std::int64_t> offsets(n);
      for (auto& o : offsets) o = integer("an offset");
      if (!iequals(word("CONNECTIVITY"), "CONNECTIVITY")) c_.fail("expected CONNECTIVITY");
      word("the connectivity type");
      if (offsets[0] != 0 || offsets.back() != std::int64_t(size))
        c_.fail("offsets must run from 0 to the connectivity size");
      std::vector<std::int64_t> ids;
      ids.reserve(size);
      for (std::size_t i = 0; i < size; ++i) ids.push_back(integer("a point id"));
      for (std::size_t cell = 0; cell + 1 < n; ++cell) {
        const std::int64_t a = offsets[cell], b = offsets[cell + 1];
        if (b < a || b > std::int64_t(size)) c_.fail("offsets decrease or overrun");
        add_cell(polygons, keep, std::span(ids).subspan(a, b - a));
      }
      return;
    }
    c_.reset(mark);
    std::size_t used = 0;
    std::vector<std::int64_t> ids;
    for (std::size_t cell = 0; cell < n; ++cell) {
      const std::size_t k = count("a cell's point count", 64, 2);
      used += 1 + k;
      if (used > size) c_.fail("the cells hold more entries than the declared size");
      ids.resize(k);
      for (auto& id : ids) id = integer("a point id");
      add_cell(polygons, keep, ids);
    }
    if (used != size) c_.fail("the cells hold fewer entries than the declared size");
  }

  void add_cell(bool polygons, bool keep, std::span<const std::int64_t> ids) {
    ++cell_count_;
    if (!polygons) {  // an unstructured-grid cell: kind decided by CELL_TYPES
      pending_.push_back({ids.begin(), ids.end()});
      return;
    }
    if (!keep) {
      kept_.push_back(false);
      return;
    }
    push_face(ids);
  }

  void push_face(std::span<const std::int64_t> ids) {
    if (ids.size() < 3 || ids.size() > 4)
      c_.fail("a polygon with " + std::to_string(ids.size()) + " points (hullmesh reads 3 or 4)");
    Face f{kInvalid, kInvalid, kInvalid, kInvalid};
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (ids[k] < 0 || ids[k] >= std::int64_t(kInvalid))
        c_.fail("point id " + std::to_string(ids[k]) + " out of range");
      f[k] = Index(ids[k]);
    }
    r_.mesh.faces.push_back(f);
    kept_.push_back(true);
  }

  void read_cell_types() {
    const std::size_t n = count("CELL_TYPES", face_limit(limits_) * 2, 2);
    if (n != pending_.size()) c_.fail("CELL_TYPES count differs from CELLS");
    for (std::size_t i = 0; i < n; ++i) {
      const std::int64_t type = integer("a cell type");
      const auto& ids = pending_[i];
      if (type == 5 || type == 9 || type == 7) {
        if ((type == 5 && ids.size() != 3) || (type == 9 && ids.size() != 4))
          c_.fail("cell type " + std::to_string(type) + " with " + std::to_string(ids.size()) +
                  " points");
        push_face(ids);
      } else if ((type >= 1 && type <= 4) || (type >= 10 && type <= 16) || type == 25 ||
                 type == 24 || type == 42) {
        kept_.push_back(false);  // vertices, lines and 3-D cells carry no panel
      } else {
        c_.fail("cell type " + std::to_string(type) +
                " is not supported (hullmesh reads triangles and quads)");
      }
    }
    pending_.clear();
  }

  void finish_cells() {
    if (!pending_.empty()) c_.fail("CELLS without CELL_TYPES");
  }

  // SCALARS / FIELD / VECTORS ... for `n` tuples; cell data is kept for the kept cells.
  void read_attributes(std::size_t n, bool cells) {
    for (;;) {
      const TextCursor::Mark mark = c_.mark();
      std::string_view t;
      if (!c_.next_token(t)) return;
      if (iequals(t, "SCALARS")) {
        const std::string name(word("a name"));
        word("a data type");
        const TextCursor::Mark m2 = c_.mark();
        std::int64_t ncomp = 1;
        std::string_view u;
        if (c_.next_token(u) && !iequals(u, "LOOKUP_TABLE") && parse_int(u, ncomp)) {
        } else {
          ncomp = 1;
          c_.reset(m2);
        }
        if (ncomp < 1 || ncomp > 4)
          c_.fail("SCALARS with " + std::to_string(ncomp) + " components");
        const TextCursor::Mark m3 = c_.mark();
        if (c_.next_token(u) && iequals(u, "LOOKUP_TABLE"))
          word("a lookup table name");
        else
          c_.reset(m3);
        read_values(name, n, std::size_t(ncomp), cells);
      } else if (iequals(t, "FIELD")) {
        read_field(n, cells);
      } else if (iequals(t, "VECTORS") || iequals(t, "NORMALS")) {
        word("a name");
        word("a data type");
        read_values("", n, 3, false);
      } else if (iequals(t, "TENSORS")) {
        word("a name");
        word("a data type");
        read_values("", n, 9, false);
      } else if (iequals(t, "METADATA")) {
        skip_metadata();
      } else {
        c_.reset(mark);
        return;
      }
    }
  }

  void read_field(std::size_t tuples, bool cells) {
    word("a field name");
    const std::size_t arrays = count("the array count", 1024, 2);
    for (std::size_t a = 0; a < arrays; ++a) {
      const std::string name(word("an array name"));
      const std::size_t ncomp = count("the component count", 64, 1);
      if (ncomp == 0) c_.fail("field array " + name + " has no components");
      const std::size_t n = count("the tuple count", vertex_limit(limits_), 0);
      word("a data type");
      if (name == "symmetry" && ncomp == 2 && n == 1) {
        const std::int64_t y0 = integer("symmetry"), x0 = integer("symmetry");
        r_.info.symmetry = {y0 != 0, x0 != 0};
        continue;
      }
      if (tuples != 0 && n != tuples)
        c_.fail("field array " + name + " has " + std::to_string(n) + " tuples, expected " +
                std::to_string(tuples));
      read_values(name, n, ncomp, cells && tuples != 0);
    }
  }

  void read_values(const std::string& name, std::size_t n, std::size_t ncomp, bool keep) {
    if (n > c_.remaining_bytes() / (2 * ncomp)) c_.fail("more values than the file holds");
    keep = keep && ncomp == 1 && n == kept_.size();
    std::vector<double> v;
    if (keep) v.reserve(r_.mesh.faces.size());
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < ncomp; ++k) {
        const double x = to_real(c_, word("a value"), "a data value");
        if (keep && kept_[i]) v.push_back(x);
      }
    if (!keep) return;
    if (name == "patch" || name == "block") {
      std::vector<Index>& dst = name == "patch" ? r_.mesh.face_patch : r_.mesh.face_block;
      dst.clear();
      for (double x : v) {
        if (x != std::floor(x) || x < -1 || x >= double(kInvalid))
          c_.fail(name + " value " + std::to_string(x) + " is not an id");
        dst.push_back(x < 0 ? kInvalid : Index(x));
      }
    } else {
      r_.fields.push_back({name, std::move(v)});
    }
  }

  void skip_metadata() {
    // VTK 5.1: METADATA / INFORMATION 0 (nothing else is written by the writers we meet).
    if (!iequals(word("INFORMATION"), "INFORMATION") || integer("the information count") != 0)
      c_.fail("METADATA other than 'INFORMATION 0' is not supported");
  }

  TextCursor c_;
  const ResourceLimits& limits_;
  MeshFile r_;
  bool grid_ = false;
  std::size_t cell_count_ = 0;
  std::vector<bool> kept_;                          // per cell: did it become a face
  std::vector<std::vector<std::int64_t>> pending_;  // unstructured-grid cells before CELL_TYPES
};

}  // namespace

MeshFile read_vtk(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  return VtkReader(bytes, name, limits).read();
}

}  // namespace hm::io
