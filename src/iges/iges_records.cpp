#include "iges/iges_records.h"

#include <charconv>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace hm::iges {
namespace {

bool is_section_letter(char c) { return c == 'S' || c == 'G' || c == 'D' || c == 'P' || c == 'T'; }

int section_rank(char c) {
  switch (c) {
    case 'S':
      return 0;
    case 'G':
      return 1;
    case 'D':
      return 2;
    case 'P':
      return 3;
    default:
      return 4;  // T
  }
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Finds the section letter of a line shorter than 73 columns: "<data><letter><blanks><digits>".
// Returns the letter's position, or npos.
std::size_t short_line_letter(std::string_view line) {
  std::size_t i = line.size();
  while (i > 0 && line[i - 1] == ' ') --i;
  const std::size_t digits_end = i;
  while (i > 0 && is_digit(line[i - 1])) --i;
  if (i == digits_end) return std::string_view::npos;
  while (i > 0 && line[i - 1] == ' ') --i;
  if (i == 0 || !is_section_letter(line[i - 1])) return std::string_view::npos;
  return i - 1;
}

[[noreturn]] void fail(const std::string& source, int line, const std::string& what) {
  if (line > 0) throw IgesError(source + ": line " + std::to_string(line) + ": " + what);
  throw IgesError(source + ": " + what);
}

// Reads "S      1G      4D     68P   1173" from the T record: declared section line counts.
void check_terminate_counts(const Sections& s, Sections& out) {
  if (s.t.empty()) return;
  const std::string_view t = s.t.front().data;
  const char letters[4] = {'S', 'G', 'D', 'P'};
  const std::size_t actual[4] = {s.s.size(), s.g.size(), s.d.size(), s.p.size()};
  for (int k = 0; k < 4; ++k) {
    const std::size_t at = static_cast<std::size_t>(8 * k);
    if (t.size() < at + 8 || t[at] != letters[k]) {
      out.warnings.push_back("T record (line " + std::to_string(s.t.front().line) +
                             ") does not hold the " + letters[k] + " section count");
      continue;
    }
    const auto n = parse_int(t.substr(at + 1, 7));
    if (!n || *n != static_cast<std::int64_t>(actual[k])) {
      out.warnings.push_back(std::string("T record declares ") +
                             std::string(trim(t.substr(at + 1, 7))) + " " + letters[k] +
                             " lines but the file has " + std::to_string(actual[k]));
    }
  }
}

}  // namespace

Sections split_sections(std::string_view text, const std::string& source) {
  if (trim(text).empty() || text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    fail(source, 0, "empty file: no IGES records");
  }
  Sections out;
  int rank = 0;
  int line_no = 0;
  std::size_t pos = 0;
  bool after_t = false;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(' ') == std::string_view::npos) continue;
    if (after_t) {
      out.warnings.push_back("text after the T record ignored (line " + std::to_string(line_no) +
                             ")");
      break;
    }
    std::size_t letter_at = 72;
    if (line.size() < 73 || !is_section_letter(line[72])) {
      letter_at = short_line_letter(line);
      if (letter_at == std::string_view::npos) {
        const bool last =
            text.find_first_not_of(" \t\r\n", std::min(pos, text.size())) == std::string_view::npos;
        if (last && rank > 0) {
          fail(source, line_no,
               "truncated: the file ends inside a record of the " + std::string(1, "SGDPT"[rank]) +
                   " section");
        }
        const char c = line.size() >= 73 ? line[72] : ' ';
        std::string what =
            "not an IGES record: expected a section letter S, G, D, P or T in "
            "column 73";
        if (c == 'B' || c == 'C') what += " (binary or compressed IGES is not supported)";
        fail(source, line_no, what);
      }
    }
    const char letter = line[letter_at];
    const int r = section_rank(letter);
    if (r < rank) {
      fail(source, line_no,
           std::string("section '") + letter +
               "' found after a later section: sections out of order");
    }
    rank = r;
    const Record rec{line.substr(0, std::min<std::size_t>(letter_at, 72)), line_no};
    switch (letter) {
      case 'S':
        out.s.push_back(rec);
        break;
      case 'G':
        out.g.push_back(rec);
        break;
      case 'D':
        out.d.push_back(rec);
        break;
      case 'P':
        out.p.push_back(rec);
        break;
      default:
        out.t.push_back(rec);
        after_t = true;
    }
  }
  auto last_section = [&] {
    if (!out.p.empty()) return std::string("P");
    if (!out.d.empty()) return std::string("D");
    if (!out.g.empty()) return std::string("G");
    return std::string("S");
  };
  if (out.g.empty()) fail(source, line_no, "truncated or not IGES: no G (global) section");
  if (out.d.empty()) fail(source, line_no, "truncated: no D (directory entry) section");
  if (out.d.size() % 2 != 0) {
    fail(source, out.d.back().line,
         "truncated D section: an odd number of directory lines (" + std::to_string(out.d.size()) +
             ")");
  }
  if (out.p.empty()) fail(source, line_no, "truncated: no P (parameter data) section");
  if (out.t.empty()) {
    fail(source, line_no,
         "truncated: no T (terminate) record; the file ends in the " + last_section() + " section");
  }
  check_terminate_counts(out, out);
  return out;
}

Delimiters read_global_delimiters(std::string_view text, std::size_t& pos, std::string& error) {
  Delimiters d;
  pos = 0;
  auto skip_blanks = [&] {
    while (pos < text.size() && text[pos] == ' ') ++pos;
  };
  auto read_one = [&](char& out, char fallback, const char* what) -> bool {
    skip_blanks();
    if (pos + 2 < text.size() && text[pos] == '1' &&
        (text[pos + 1] == 'H' || text[pos + 1] == 'h')) {
      out = text[pos + 2];
      pos += 3;
      return true;
    }
    if (pos < text.size() && (text[pos] == d.param || text[pos] == fallback)) {
      out = fallback;
      return true;
    }
    error = std::string("G section: cannot read the ") + what + " delimiter";
    return false;
  };
  if (!read_one(d.param, ',', "parameter")) return d;
  skip_blanks();
  if (pos >= text.size() || text[pos] != d.param) {
    error = "G section: expected the parameter delimiter after G1";
    return d;
  }
  ++pos;
  skip_blanks();
  if (pos < text.size() && text[pos] == d.param) {
    d.record = ';';
  } else if (!read_one(d.record, ';', "record")) {
    return d;
  }
  skip_blanks();
  if (pos < text.size() && text[pos] == d.param) {
    ++pos;
  } else if (pos < text.size() && text[pos] == d.record) {
    pos = text.size();  // G ends after the delimiters: every other field takes its default
  } else {
    error = "G section: expected the parameter delimiter after G2";
  }
  if (d.param == d.record || d.param == ' ' || d.record == ' ') {
    error = "G section: unusable delimiters";
  }
  return d;
}

std::string tokenize(std::string_view text, const Delimiters& delims, std::uint64_t max_tokens,
                     std::vector<Token>& out) {
  const std::size_t n = text.size();
  std::size_t i = 0;
  std::uint64_t count = 0;
  const char pd = delims.param, rd = delims.record;
  while (true) {
    while (i < n && text[i] == ' ') ++i;
    if (i >= n) return {};  // a missing record delimiter ends the entity at its last line
    if (++count > max_tokens) return "too many";
    std::size_t j = i;
    std::uint64_t holl = 0;
    while (j < n && is_digit(text[j]) && holl < (1ull << 40)) holl = holl * 10 + (text[j++] - '0');
    if (j > i && j < n && (text[j] == 'H' || text[j] == 'h')) {
      const std::size_t start = j + 1;
      if (holl > n - start) return "a Hollerith string runs past the end of the entity";
      out.push_back({text.data() + start, static_cast<std::uint32_t>(holl), true});
      i = start + holl;
      while (i < n && text[i] == ' ') ++i;
      if (i >= n || text[i] == rd) return {};
      if (text[i] != pd) return "unexpected text after a Hollerith string";
      ++i;
      continue;
    }
    j = i;
    while (j < n && text[j] != pd && text[j] != rd) ++j;
    const std::string_view field = trim(text.substr(i, j - i));
    out.push_back({field.data(), static_cast<std::uint32_t>(field.size()), false});
    if (j >= n || text[j] == rd) return {};
    i = j + 1;
  }
}

std::optional<double> parse_real(std::string_view s) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty() || s.size() >= 96) return std::nullopt;
  const char c0 = s.front();
  if (!(is_digit(c0) || c0 == '.' || c0 == '-')) return std::nullopt;
  char buf[96];
  bool negative_exponent = false;
  for (std::size_t k = 0; k < s.size(); ++k) {
    char c = s[k];
    if (c == 'D' || c == 'd' || c == 'E') c = 'e';
    if (c == 'e' && k + 1 < s.size() && s[k + 1] == '-') negative_exponent = true;
    buf[k] = c;
  }
  double value = 0;
  const auto [ptr, ec] = std::from_chars(buf, buf + s.size(), value);
  if (ptr != buf + s.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    if (negative_exponent) return 0.0;
    return std::nullopt;
  }
  if (ec != std::errc() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<std::int64_t> parse_int(std::string_view s) {
  // Fast path: short plain digit strings, the common case for counts and pointers.
  if (!s.empty() && s.size() <= 9) {
    std::int64_t v = 0;
    std::size_t i = 0;
    while (i < s.size() && is_digit(s[i])) v = v * 10 + (s[i++] - '0');
    if (i == s.size()) return v;
  }
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return std::nullopt;
  std::int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec == std::errc() && ptr == s.data() + s.size()) return v;
  const auto r = parse_real(s);
  if (!r || std::fabs(*r) > 9.0e15 || *r != std::floor(*r)) return std::nullopt;
  return static_cast<std::int64_t>(*r);
}

}  // namespace hm::iges
