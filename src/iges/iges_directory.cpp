#include "iges/iges_directory.h"

#include "core/error.h"

namespace hm::iges {
namespace {

std::string_view field(std::string_view rec, int k) {
  const std::size_t at = static_cast<std::size_t>(8 * k);
  if (rec.size() <= at) return {};
  return rec.substr(at, 8);
}

// Optional numeric field: blank is 0; junk is 0 too (fields nobody here relies on).
int soft_int(std::string_view f) {
  const auto v = parse_int(f);
  if (!v || *v < -2'000'000'000 || *v > 2'000'000'000) return 0;
  return static_cast<int>(*v);
}

int two_digits(std::string_view status, int k) {
  const std::string_view s = status.size() >= static_cast<std::size_t>(2 * k + 2)
                                 ? status.substr(static_cast<std::size_t>(2 * k), 2)
                                 : std::string_view{};
  return soft_int(s);
}

}  // namespace

std::vector<DirEntry> parse_directory(const std::vector<Record>& d, std::size_t p_lines,
                                      const std::string& source) {
  std::vector<DirEntry> out(d.size() / 2);
  for (std::size_t e = 0; e < out.size(); ++e) {
    const Record& r1 = d[2 * e];
    const Record& r2 = d[2 * e + 1];
    DirEntry& de = out[e];
    de.de = static_cast<int>(2 * e + 1);
    auto required = [&](const Record& r, int k, const char* what) {
      const std::string_view f = trim(field(r.data, k));
      const auto v = parse_int(f);
      if (!v || *v < -2'000'000'000 || *v > 2'000'000'000) {
        throw IgesError(source + ": line " + std::to_string(r.line) + ": DE " +
                        std::to_string(de.de) + ": unreadable " + what + " field '" +
                        std::string(f) + "'");
      }
      return static_cast<int>(*v);
    };
    de.type = required(r1, 0, "entity type");
    de.param_line = required(r1, 1, "parameter pointer");
    de.structure = soft_int(field(r1.data, 2));
    de.line_font = soft_int(field(r1.data, 3));
    de.level = soft_int(field(r1.data, 4));
    de.view = soft_int(field(r1.data, 5));
    de.transform = trim(field(r1.data, 6)).empty() ? 0 : required(r1, 6, "transformation pointer");
    de.label_display = soft_int(field(r1.data, 7));
    const std::string_view status = trim(field(r1.data, 8));
    // Status is 8 digits, right-justified; pad on the left when writers dropped leading zeros.
    std::string padded(8 - std::min<std::size_t>(8, status.size()), '0');
    padded.append(status.substr(0, 8));
    de.blank = two_digits(padded, 0);
    de.subordinate = two_digits(padded, 1);
    de.use = two_digits(padded, 2);
    de.hierarchy = two_digits(padded, 3);
    de.line_weight = soft_int(field(r2.data, 1));
    de.color = soft_int(field(r2.data, 2));
    de.param_count = required(r2, 3, "parameter line count");
    de.form = trim(field(r2.data, 4)).empty() ? 0 : required(r2, 4, "form number");
    de.label = std::string(trim(field(r2.data, 7)));
    de.subscript = soft_int(field(r2.data, 8));
    const int second_type = soft_int(field(r2.data, 0));
    if (second_type != de.type) {
      throw IgesError(source + ": line " + std::to_string(r2.line) + ": DE " +
                      std::to_string(de.de) + ": the two directory lines disagree on the type (" +
                      std::to_string(de.type) + " and " + std::to_string(second_type) + ")");
    }
    const std::int64_t first = de.param_line;
    const std::int64_t last = first + std::max(de.param_count, 1) - 1;
    if (first < 1 || last > static_cast<std::int64_t>(p_lines) || de.param_count < 0) {
      throw IgesError(source + ": line " + std::to_string(r1.line) + ": DE " +
                      std::to_string(de.de) + " (type " + std::to_string(de.type) +
                      "): parameter pointer " + std::to_string(de.param_line) + " (" +
                      std::to_string(de.param_count) + " lines) lies outside the P section (" +
                      std::to_string(p_lines) + " lines)");
    }
  }
  return out;
}

}  // namespace hm::iges
