// VTK XML unstructured grid (.vtu), ASCII data arrays.
//
//   <!-- title -->
//   <VTKFile type="UnstructuredGrid" ...><UnstructuredGrid>
//   <FieldData> symmetry: Int32, 2 components, about_y0 about_x0 (0 or 1) </FieldData>
//   <Piece NumberOfPoints="N" NumberOfCells="F">
//   <Points> Float64 x y z </Points>
//   <Cells> connectivity (0-based), offsets, types (5 triangle, 9 quad) </Cells>
//   <CellData> patch, block (Int64, -1 = none), then one Float64 array per face field
//
// The reader takes what hullmesh writes and similar files from other tools: one Piece, ASCII
// arrays (binary and appended data are rejected), cell types 5, 9 and 7 (polygon of 3 or 4
// points); vertex, line and 3-D cells are skipped. Normals: VTK's right-hand rule over the point
// order; hullmesh's order (into the fluid) is written unchanged. Numbers: shortest round-trip
// text (bit for bit).
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/text_reader.h"

namespace hm::io {

void write_vtu(std::ostream& out, const SurfaceMesh& m, const MeshWriteOptions& o) {
  std::string title = one_line(o.info.title, 200);
  for (std::size_t at; (at = title.find("--")) != std::string::npos;) title[at + 1] = ' ';
  std::string s;
  s.reserve(64 * (m.positions.size() + m.faces.size()) + 1024);
  s += "<?xml version=\"1.0\"?>\n<!-- " + title + " -->\n";
  s += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n";
  s += "<UnstructuredGrid>\n<FieldData>\n<DataArray type=\"Int32\" Name=\"symmetry\" "
       "NumberOfComponents=\"2\" NumberOfTuples=\"1\" format=\"ascii\">\n";
  s += o.info.symmetry.about_y0 ? "1 " : "0 ";
  s += o.info.symmetry.about_x0 ? "1\n" : "0\n";
  s += "</DataArray>\n</FieldData>\n";
  s += "<Piece NumberOfPoints=\"" + std::to_string(m.positions.size()) + "\" NumberOfCells=\"" +
       std::to_string(m.faces.size()) + "\">\n";
  s += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec3d& p : m.positions) {
    append_point(s, p);
    s += '\n';
  }
  s += "</DataArray>\n</Points>\n<Cells>\n";
  s += "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const Face& f : m.faces) {
    for (int k = 0; k < corner_count(f); ++k) {
      append_uint(s, f[k]);
      s += k + 1 < corner_count(f) ? ' ' : '\n';
    }
  }
  s += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  std::size_t offset = 0;
  for (const Face& f : m.faces) {
    offset += corner_count(f);
    append_uint(s, offset);
    s += '\n';
  }
  s += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (const Face& f : m.faces) s += is_triangle(f) ? "5\n" : "9\n";  // VTK_TRIANGLE, VTK_QUAD
  s += "</DataArray>\n</Cells>\n<CellData>\n";
  auto int_array = [&](const char* name, const std::vector<Index>& v) {
    s += std::string("<DataArray type=\"Int64\" Name=\"") + name + "\" format=\"ascii\">\n";
    for (Index x : v) {
      if (x == kInvalid)
        s += "-1";
      else
        append_uint(s, x);
      s += '\n';
    }
    s += "</DataArray>\n";
  };
  if (!m.face_patch.empty()) int_array("patch", m.face_patch);
  if (!m.face_block.empty()) int_array("block", m.face_block);
  for (const FaceField& field : o.face_fields) {
    s += std::string("<DataArray type=\"Float64\" Name=\"") + field.name + "\" format=\"ascii\">\n";
    for (double v : field.values) {
      append_real(s, v);
      s += '\n';
    }
    s += "</DataArray>\n";
  }
  s += "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  put(out, s);
}

namespace {

class VtuReader {
 public:
  VtuReader(std::string_view bytes, const std::string& name, const ResourceLimits& limits)
      : text_(bytes), name_(name), limits_(limits) {}

  MeshFile read() {
    if (text_.find("<VTKFile") == std::string_view::npos) fail(0, "not a VTK XML file");
    cells_pos_ = text_.size();
    const std::size_t comment = text_.find("<!--");
    if (comment != std::string_view::npos && comment < text_.find("<VTKFile")) {
      const std::size_t end = text_.find("-->", comment);
      if (end != std::string_view::npos)
        r_.info.title = std::string(trim(text_.substr(comment + 4, end - comment - 4)));
    }
    std::string section;
    std::size_t pos = 0;
    bool piece = false;
    while ((pos = text_.find('<', pos)) != std::string_view::npos) {
      const std::size_t end = text_.find('>', pos);
      if (end == std::string_view::npos) fail(pos, "unterminated tag");
      const std::string_view tag = text_.substr(pos + 1, end - pos - 1);
      const std::string_view tname = tag.substr(0, tag.find_first_of(" \t\r\n/"));
      if (tname == "VTKFile" && attribute(tag, "type", pos) != "UnstructuredGrid")
        fail(pos, "VTK XML type is not UnstructuredGrid");
      if (tname == "Piece") {
        if (piece) fail(pos, "more than one Piece is not supported");
        piece = true;
        npoints_ = count(attribute(tag, "NumberOfPoints", pos), "NumberOfPoints",
                         vertex_limit(limits_), pos);
        ncells_ = count(attribute(tag, "NumberOfCells", pos), "NumberOfCells",
                        face_limit(limits_) * 2, pos);
      } else if (tname == "Points" || tname == "Cells" || tname == "CellData" ||
                 tname == "PointData" || tname == "FieldData") {
        section = std::string(tname);
      } else if (!tname.empty() && tname[0] == '/' && tname.substr(1) == section) {
        section.clear();
      } else if (tname == "DataArray") {
        pos = read_array(tag, end + 1, section, pos);
        continue;
      } else if (tname == "AppendedData") {
        fail(pos, "appended data is not supported (write ascii arrays)");
      }
      pos = end + 1;
    }
    if (!piece) fail(text_.size(), "no Piece");
    assemble();
    return std::move(r_);
  }

 private:
  std::size_t line_at(std::size_t pos) {
    pos = std::min(pos, text_.size());
    if (pos < counted_pos_) {
      counted_pos_ = 0;
      counted_line_ = 1;
    }
    for (; counted_pos_ < pos; ++counted_pos_)
      if (text_[counted_pos_] == '\n') ++counted_line_;
    return counted_line_;
  }
  [[noreturn]] void fail(std::size_t pos, const std::string& what) {
    throw InputError(name_ + ", line " + std::to_string(line_at(pos)) + ": " + what);
  }

  std::string_view attribute(std::string_view tag, const char* key, std::size_t pos) {
    const std::string k = std::string(" ") + key + "=\"";
    const std::size_t at = tag.find(k);
    if (at == std::string_view::npos) return {};
    const std::size_t end = tag.find('"', at + k.size());
    if (end == std::string_view::npos) fail(pos, std::string("unterminated attribute ") + key);
    return tag.substr(at + k.size(), end - at - k.size());
  }

  std::size_t count(std::string_view v, const char* what, std::uint64_t limit, std::size_t pos) {
    TextCursor c(v, name_, line_at(pos));
    std::string_view t;
    if (!c.next_token(t)) fail(pos, std::string("missing ") + what);
    return to_count(c, t, what, limit, 0);
  }

  // Parses one DataArray's ascii content; returns the position after </DataArray>.
  std::size_t read_array(std::string_view tag, std::size_t begin, const std::string& section,
                         std::size_t pos) {
    const std::size_t end = text_.find("</DataArray>", begin);
    if (end == std::string_view::npos) fail(pos, "DataArray without </DataArray>");
    if (tag.empty() || tag.back() == '/') return begin;
    if (attribute(tag, "format", pos) != "ascii")
      fail(pos, "only format=\"ascii\" DataArrays are supported");
    const std::string name(attribute(tag, "Name", pos));
    std::size_t ncomp = 1;
    if (!attribute(tag, "NumberOfComponents", pos).empty())
      ncomp = count(attribute(tag, "NumberOfComponents", pos), "NumberOfComponents", 64, pos);
    TextCursor c(text_.substr(begin, end - begin), name_, line_at(begin));
    std::vector<double> values;
    std::string_view t;
    // Every value takes at least two bytes, so the content bounds the allocation.
    values.reserve((end - begin) / 2);
    while (c.next_token(t))
      values.push_back(to_real(c, t, name.empty() ? "a value" : name.c_str()));
    const std::size_t after = end + 12;
    auto need = [&](std::size_t n, const char* what) {
      if (values.size() != n)
        fail(begin, std::string(what) + " has " + std::to_string(values.size()) +
                        " values, expected " + std::to_string(n));
    };
    if (section == "Points") {
      need(3 * npoints_, "Points");
      points_ = std::move(values);
    } else if (section == "Cells") {
      if (name == "connectivity") {
        connectivity_ = std::move(values);
        cells_pos_ = begin;
      } else if (name == "offsets") {
        need(ncells_, "offsets");
        offsets_ = std::move(values);
      } else if (name == "types") {
        need(ncells_, "types");
        types_ = std::move(values);
      }
    } else if (section == "CellData") {
      if (ncomp == 1) {
        need(ncells_, name.c_str());
        cell_data_.push_back({name, std::move(values)});
      }
    } else if (section == "FieldData" && name == "symmetry" && values.size() == 2) {
      r_.info.symmetry = {values[0] != 0, values[1] != 0};
    }
    return after;
  }

  Index as_index(double v, std::size_t limit, const char* what) {
    if (!(v >= 0) || v != std::floor(v) || v >= double(limit))
      fail(cells_pos_, std::string(what) + " " + std::to_string(v) + " out of range");
    return Index(v);
  }

  void assemble() {
    SurfaceMesh& m = r_.mesh;
    if (points_.size() != 3 * npoints_) fail(text_.size(), "no Points array");
    m.positions.resize(npoints_);
    for (std::size_t i = 0; i < npoints_; ++i)
      m.positions[i] = {points_[3 * i], points_[3 * i + 1], points_[3 * i + 2]};
    if (ncells_ && (offsets_.size() != ncells_ || types_.size() != ncells_))
      fail(text_.size(), "Cells need offsets and types arrays");
    std::vector<bool> kept(ncells_, false);
    std::size_t start = 0;
    for (std::size_t i = 0; i < ncells_; ++i) {
      const std::size_t stop = as_index(offsets_[i], connectivity_.size() + 1, "offset");
      if (stop < start) fail(cells_pos_, "offsets decrease");
      const double type = types_[i];
      const std::size_t n = stop - start;
      if (type == 5 || type == 9 || type == 7) {
        if (n < 3 || n > 4 || (type == 5 && n != 3) || (type == 9 && n != 4))
          fail(cells_pos_, "cell " + std::to_string(i) + " has " + std::to_string(n) + " points");
        Face f{kInvalid, kInvalid, kInvalid, kInvalid};
        for (std::size_t k = 0; k < n; ++k)
          f[k] = as_index(connectivity_[start + k], npoints_, "point id");
        m.faces.push_back(f);
        kept[i] = true;
      } else if (!((type >= 1 && type <= 4) || (type >= 10 && type <= 16))) {
        fail(cells_pos_, "cell type " + std::to_string(type) + " is not supported");
      }
      start = stop;
    }
    for (auto& [name, values] : cell_data_) {
      std::vector<double> v;
      for (std::size_t i = 0; i < ncells_; ++i)
        if (kept[i]) v.push_back(values[i]);
      if (name == "patch" || name == "block") {
        std::vector<Index>& dst = name == "patch" ? m.face_patch : m.face_block;
        dst.clear();
        for (double x : v) dst.push_back(x == -1 ? kInvalid : as_index(x, kInvalid, name.c_str()));
      } else {
        r_.fields.push_back({name, std::move(v)});
      }
    }
    m.face_patch.resize(m.faces.size(), 0);
  }

  std::string_view text_;
  std::string name_;
  const ResourceLimits& limits_;
  MeshFile r_;
  std::size_t npoints_ = 0, ncells_ = 0, cells_pos_ = 0;
  std::size_t counted_pos_ = 0, counted_line_ = 1;
  std::vector<double> points_, connectivity_, offsets_, types_;
  std::vector<std::pair<std::string, std::vector<double>>> cell_data_;
};

}  // namespace

MeshFile read_vtu(std::string_view bytes, const std::string& name, const ResourceLimits& limits) {
  return VtuReader(bytes, name, limits).read();
}

}  // namespace hm::io
