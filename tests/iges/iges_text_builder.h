// Builds small IGES texts for tests: formats the 80-column S, G, D, P and T records so that a
// test states only the entities and parameters it is about.
#pragma once

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace hm::test {

// A real written with 17 significant digits (round trips exactly).
inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".";
  return s;
}
inline std::string num(int v) { return std::to_string(v); }
// Hollerith string: 5Hhello.
inline std::string holl(const std::string& s) { return std::to_string(s.size()) + "H" + s; }

struct DirFields {
  DirFields() = default;
  DirFields(int form_, int transform_ = 0, std::string status_ = "00000000",  // NOLINT
            std::string label_ = "", int subscript_ = 0)
      : form(form_),
        transform(transform_),
        status(std::move(status_)),
        label(std::move(label_)),
        subscript(subscript_) {}
  int form = 0;
  int transform = 0;  // DE of a 124
  std::string status = "00000000";
  std::string label;
  int subscript = 0;
};

class IgesTextBuilder {
 public:
  char param_delim = ',';
  char record_delim = ';';
  bool crlf = false;
  bool short_lines = false;  // S, G, P and T records without padding to 72 columns
  int unit_flag = 6;         // G14
  std::string unit_name = "M";
  double model_scale = 1.0;
  std::string t_record;  // overrides the T record's data when not empty

  // Adds an entity; returns its DE number. params exclude the type number.
  int add(int type, const std::vector<std::string>& params, const DirFields& f = {}) {
    entities_.push_back({type, params, f});
    return static_cast<int>(2 * entities_.size() - 1);
  }
  // DE number the next add() will return.
  int next_de() const { return static_cast<int>(2 * entities_.size() + 1); }

  std::string build() const {
    std::vector<std::string> s_lines{"hullmesh test file"};
    std::vector<std::string> g_lines = wrap(global_params(), 72);
    std::vector<std::string> d_lines, p_lines, p_backptr;
    for (std::size_t i = 0; i < entities_.size(); ++i) {
      const Entity& e = entities_[i];
      const int de = static_cast<int>(2 * i + 1);
      std::vector<std::string> fields{std::to_string(e.type)};
      for (const std::string& p : e.params) fields.push_back(p);
      const std::vector<std::string> lines = wrap(fields, 64);
      const int first = static_cast<int>(p_lines.size()) + 1;
      for (const std::string& l : lines) {
        p_lines.push_back(l);
        p_backptr.push_back(pad_left(std::to_string(de), 8));
      }
      d_lines.push_back(f8(e.type) + f8(first) + f8(0) + f8(0) + f8(0) + f8(0) + f8(e.f.transform) +
                        f8(0) + pad_left(e.f.status, 8));
      d_lines.push_back(f8(e.type) + f8(0) + f8(0) + f8(static_cast<int>(lines.size())) +
                        f8(e.f.form) + f8(0) + f8(0) + pad_right(e.f.label, 8) + f8(e.f.subscript));
    }
    std::string out;
    emit(out, s_lines, 'S', 72, {});
    emit(out, g_lines, 'G', 72, {});
    emit(out, d_lines, 'D', 72, {});
    emit(out, p_lines, 'P', 64, p_backptr);
    char t[81];
    std::snprintf(t, sizeof t, "S%7zuG%7zuD%7zuP%7zu", s_lines.size(), g_lines.size(),
                  d_lines.size(), p_lines.size());
    emit(out, {t_record.empty() ? std::string(t) : t_record}, 'T', 72, {});
    return out;
  }

 private:
  struct Entity {
    int type;
    std::vector<std::string> params;
    DirFields f;
  };

  std::vector<std::string> global_params() const {
    return {"1H" + std::string(1, param_delim),
            "1H" + std::string(1, record_delim),
            holl("hullmesh tests"),
            holl("test.igs"),
            holl("hullmesh"),
            holl("0.1"),
            "32",
            "308",
            "15",
            "308",
            "15",
            holl("test"),
            num(model_scale),
            num(unit_flag),
            holl(unit_name),
            "1",
            "0.01",
            holl("20240101.120000"),
            "1E-07",
            "100.",
            holl("a tester"),
            holl("hullmesh org"),
            "11",
            "0"};
  }

  static std::string f8(int v) { return pad_left(std::to_string(v), 8); }
  static std::string pad_left(const std::string& s, std::size_t n) {
    return s.size() >= n ? s : std::string(n - s.size(), ' ') + s;
  }
  static std::string pad_right(const std::string& s, std::size_t n) {
    return s.size() >= n ? s.substr(0, n) : s + std::string(n - s.size(), ' ');
  }

  // Joins fields with the parameter delimiter, ends with the record delimiter, and breaks lines
  // between fields (a field longer than a line is split: only Hollerith strings may be).
  std::vector<std::string> wrap(const std::vector<std::string>& fields, std::size_t width) const {
    std::vector<std::string> lines{""};
    for (std::size_t i = 0; i < fields.size(); ++i) {
      std::string piece = fields[i] + (i + 1 < fields.size() ? param_delim : record_delim);
      if (lines.back().size() + piece.size() > width && !lines.back().empty()) lines.push_back("");
      while (lines.back().size() + piece.size() > width) {
        const std::size_t room = width - lines.back().size();
        lines.back() += piece.substr(0, room);
        piece = piece.substr(room);
        lines.push_back("");
      }
      lines.back() += piece;
    }
    return lines;
  }

  void emit(std::string& out, const std::vector<std::string>& lines, char letter, std::size_t width,
            const std::vector<std::string>& backptr) const {
    for (std::size_t i = 0; i < lines.size(); ++i) {
      char seq[32];
      std::snprintf(seq, sizeof seq, "%c%07zu", letter, i + 1);
      if (short_lines && letter != 'D') {
        out += lines[i] + seq;
      } else {
        std::string data = pad_right(lines[i], width);
        if (width == 64) data += backptr.empty() ? std::string(8, ' ') : backptr[i];
        out += data + seq;
      }
      out += crlf ? "\r\n" : "\n";
    }
  }

  std::vector<Entity> entities_;
};

}  // namespace hm::test
