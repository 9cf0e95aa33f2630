// Internal to io/: a cursor over a text file's bytes for the mesh readers, with line numbers in
// every error, and checked conversions of tokens to numbers, counts and indices.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/limits.h"
#include "core/types.h"
#include "core/vec.h"

namespace hm::io {

// Caps on a mesh read from a file: faces by max_triangles, vertices by four per face (a GDF or
// STL lists every corner before welding).
inline std::uint64_t face_limit(const ResourceLimits& l) { return l.max_triangles; }
inline std::uint64_t vertex_limit(const ResourceLimits& l) { return 4 * l.max_triangles; }

class TextCursor {
 public:
  TextCursor(std::string_view text, std::string name, std::size_t first_line = 1)
      : text_(text), name_(std::move(name)), pos_line_(first_line) {}

  // The next line without its terminator (LF or CR-LF); false at the end of the text.
  bool next_line(std::string_view& line);
  // The next whitespace-separated token, across lines; false at the end of the text.
  bool next_token(std::string_view& token);
  // The next line that is not blank (after trimming); false at the end.
  bool next_nonblank_line(std::string_view& line);
  // 1-based line number of the last line or token returned (0 before any).
  std::size_t line() const { return line_; }
  std::size_t remaining_bytes() const { return text_.size() - pos_; }
  bool at_end() const { return pos_ >= text_.size(); }
  const std::string& name() const { return name_; }

  // Save and restore the position, to look ahead one token.
  struct Mark {
    std::size_t pos, line, pos_line;
  };
  Mark mark() const { return {pos_, line_, pos_line_}; }
  void reset(const Mark& m) {
    pos_ = m.pos;
    line_ = m.line;
    pos_line_ = m.pos_line;
  }

  // Throws InputError "NAME, line L: what".
  [[noreturn]] void fail(const std::string& what) const;
  // Throws LimitError "NAME, line L: what".
  [[noreturn]] void fail_limit(const std::string& what) const;

 private:
  std::string_view text_;
  std::string name_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;      // line of the last item returned
  std::size_t pos_line_ = 1;  // line at pos_
};

std::string_view trim(std::string_view s);
// Splits on blanks and tabs; returns the number of tokens (out is cleared first).
std::size_t split(std::string_view line, std::vector<std::string_view>& out);
bool starts_with_word(std::string_view line, std::string_view word);  // case-sensitive, trimmed

// Parses a whole token as a double (accepting Fortran D exponents); false if it is not one.
bool parse_double(std::string_view token, double& value);
bool parse_int(std::string_view token, std::int64_t& value);

// Checked conversions: fail on the cursor's line naming `what`.
double to_real(const TextCursor& c, std::string_view token, const char* what);
std::int64_t to_int(const TextCursor& c, std::string_view token, const char* what);
// A declared count: negative or unparsable -> InputError; over `limit` -> LimitError; more than
// the rest of the file could hold at min_bytes_each per item -> InputError. Checked before any
// allocation sized by it.
std::size_t to_count(const TextCursor& c, std::string_view token, const char* what,
                     std::uint64_t limit, std::uint64_t min_bytes_each);
// A vertex reference numbered from `base`, checked against count; returns the 0-based index.
Index to_index(const TextCursor& c, std::string_view token, std::int64_t base, std::size_t count,
               const char* what);
// The next token, or fail "file ends before <what>".
std::string_view require_token(TextCursor& c, const char* what);
Vec3d to_point(const TextCursor& c, std::string_view x, std::string_view y, std::string_view z);

// Formatting for the writers: shortest text that reads back to the same double, always with a
// decimal point or exponent dot so that readers expecting a real (Capytaine's regexes) see one.
void append_real(std::string& s, double v);
void append_uint(std::string& s, std::uint64_t v);
// "x y z" (append_real each, separated by blanks), no line end.
void append_point(std::string& s, const Vec3d& p);
// A title on one line: control characters replaced by blanks, cut to max_chars.
std::string one_line(const std::string& title, std::size_t max_chars);

// Deterministic welding of corner positions by exact equality (-0 equals +0): indices in the
// order positions are first seen.
class Welder {
 public:
  explicit Welder(std::vector<Vec3d>& positions, std::size_t expected);
  Index add(const Vec3d& p);

 private:
  struct Key {
    std::uint64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    std::size_t operator()(const Key& k) const;
  };
  std::vector<Vec3d>& positions_;
  std::unordered_map<Key, Index, Hash> index_;
};

// Triangle from a four-corner record with a repeated corner: drops each corner equal to the one
// after it (cyclically), so (a,b,c,a), (a,b,c,c), (a,a,b,c) all give (a,b,c). Returns false when
// fewer than three corners remain.
bool collapse_repeated(const Index (&corners)[4], std::array<Index, 4>& face);

}  // namespace hm::io
