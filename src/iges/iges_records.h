// The lexical layer of IGES 5.3: 80-column records split into the S, G, D, P and T sections,
// free-format parameter tokens (Hollerith strings, custom delimiters, D exponents) and numbers.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/limits.h"

namespace hm::iges {

// One record: columns 1..72 (may be shorter when the line was short) and its file line number.
struct Record {
  std::string_view data;
  int line = 0;  // 1-based line in the file
};

// The five sections in file order. D and P keep one Record per 80-column line.
struct Sections {
  std::vector<Record> s, g, d, p, t;
  std::vector<std::string> warnings;  // section-count mismatches against T, odd layouts
};

// Splits the text into sections. Accepts LF and CR-LF, short lines (letter and sequence number
// at the end) and a missing final newline. Throws IgesError for empty or non-IGES text, sections
// out of order and missing G/D/P/T sections.
Sections split_sections(std::string_view text, const std::string& source);

// A parameter token: a field between delimiters, blanks trimmed, or a Hollerith string's content.
struct Token {
  const char* ptr = nullptr;
  std::uint32_t len = 0;
  bool hollerith = false;
  std::string_view view() const { return {ptr, len}; }
  bool empty() const { return len == 0 && !hollerith; }
};

struct Delimiters {
  char param = ',';
  char record = ';';
};

// Tokenizes free-format text up to the first record delimiter. Appends to `out`. Returns an
// error message (empty on success), e.g. for a Hollerith count running past the text. Stops with
// LimitError-worthy status when more than max_tokens tokens are found (returns "too many").
std::string tokenize(std::string_view text, const Delimiters& delims, std::uint64_t max_tokens,
                     std::vector<Token>& out);

// Reads the G1/G2 delimiters at the start of the global section text; advances `pos` past them.
Delimiters read_global_delimiters(std::string_view text, std::size_t& pos, std::string& error);

// Number parsing for fields: accepts free-format reals with E or D exponents and a leading '+'.
// Returns nullopt on malformed, non-finite or overflowing values (1e400); underflow gives 0.
std::optional<double> parse_real(std::string_view s);
// Integers; accepts "3", "+3" and integral reals such as "3." written by some exporters.
std::optional<std::int64_t> parse_int(std::string_view s);

// Trims blanks at both ends.
inline std::string_view trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return s.substr(b, e - b);
}

}  // namespace hm::iges
