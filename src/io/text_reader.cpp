#include "io/text_reader.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace hm::io {

bool TextCursor::next_line(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const std::size_t end = text_.find('\n', pos_);
  const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
  line = text_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  line_ = pos_line_;
  pos_ = end == std::string_view::npos ? text_.size() : end + 1;
  ++pos_line_;
  return true;
}

bool TextCursor::next_token(std::string_view& token) {
  while (pos_ < text_.size()) {
    const char ch = text_[pos_];
    if (ch == '\n') {
      ++pos_line_;
    } else if (ch != ' ' && ch != '\t' && ch != '\r' && ch != '\f' && ch != '\v') {
      break;
    }
    ++pos_;
  }
  if (pos_ >= text_.size()) return false;
  const std::size_t start = pos_;
  while (pos_ < text_.size()) {
    const char ch = text_[pos_];
    if (ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n' || ch == '\f' || ch == '\v') break;
    ++pos_;
  }
  token = text_.substr(start, pos_ - start);
  line_ = pos_line_;
  return true;
}

bool TextCursor::next_nonblank_line(std::string_view& line) {
  while (next_line(line))
    if (!trim(line).empty()) return true;
  return false;
}

void TextCursor::fail(const std::string& what) const {
  throw InputError(name_ + ", line " + std::to_string(line_) + ": " + what);
}

void TextCursor::fail_limit(const std::string& what) const {
  throw LimitError(name_ + ", line " + std::to_string(line_) + ": " + what);
}

std::string_view trim(std::string_view s) {
  const char* ws = " \t\r\f\v";
  const std::size_t a = s.find_first_not_of(ws);
  if (a == std::string_view::npos) return {};
  const std::size_t b = s.find_last_not_of(ws);
  return s.substr(a, b - a + 1);
}

std::size_t split(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out.size();
}

bool starts_with_word(std::string_view line, std::string_view word) {
  const std::string_view t = trim(line);
  if (t.substr(0, word.size()) != word) return false;
  return t.size() == word.size() || t[word.size()] == ' ' || t[word.size()] == '\t';
}

bool parse_double(std::string_view token, double& value) {
  if (token.empty() || token.size() > 64) return false;
  // Fortran writes 1.0D+00; from_chars does not take a leading '+'.
  std::array<char, 65> buf{};
  std::size_t n = 0;
  for (char ch : token) buf[n++] = (ch == 'D' || ch == 'd') ? 'e' : ch;
  const char* first = buf.data();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, buf.data() + n, value);
  return ec == std::errc() && ptr == buf.data() + n;
}

bool parse_int(std::string_view token, std::int64_t& value) {
  if (token.empty()) return false;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last;
}

namespace {
std::string quoted(std::string_view t) {
  std::string s(t.substr(0, 40));
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 32 || static_cast<unsigned char>(ch) > 126) ch = '?';
  return "'" + s + (t.size() > 40 ? "...'" : "'");
}
}  // namespace

double to_real(const TextCursor& c, std::string_view token, const char* what) {
  double v = 0;
  if (!parse_double(token, v))
    c.fail(std::string(what) + ": " + quoted(token) + " is not a number");
  if (!std::isfinite(v)) c.fail(std::string(what) + ": " + quoted(token) + " is not finite");
  return v;
}

std::int64_t to_int(const TextCursor& c, std::string_view token, const char* what) {
  std::int64_t v = 0;
  if (!parse_int(token, v)) c.fail(std::string(what) + ": " + quoted(token) + " is not an integer");
  return v;
}

std::size_t to_count(const TextCursor& c, std::string_view token, const char* what,
                     std::uint64_t limit, std::uint64_t min_bytes_each) {
  const std::int64_t v = to_int(c, token, what);
  if (v < 0) c.fail(std::string(what) + " is negative (" + std::to_string(v) + ")");
  const auto n = static_cast<std::uint64_t>(v);
  if (n > limit)
    c.fail_limit(std::string(what) + " " + std::to_string(n) + " exceeds the limit of " +
                 std::to_string(limit));
  if (min_bytes_each > 0 && n > c.remaining_bytes() / min_bytes_each)
    c.fail(std::string(what) + " " + std::to_string(n) + " is more than the rest of the file (" +
           std::to_string(c.remaining_bytes()) + " bytes) can hold");
  return static_cast<std::size_t>(n);
}

Index to_index(const TextCursor& c, std::string_view token, std::int64_t base, std::size_t count,
               const char* what) {
  const std::int64_t v = to_int(c, token, what);
  if (v < base || static_cast<std::uint64_t>(v - base) >= count)
    c.fail(std::string(what) + " " + std::to_string(v) + " is out of range (" +
           std::to_string(base) + " to " + std::to_string(base + std::int64_t(count) - 1) + ")");
  return static_cast<Index>(v - base);
}

Vec3d to_point(const TextCursor& c, std::string_view x, std::string_view y, std::string_view z) {
  return {to_real(c, x, "x"), to_real(c, y, "y"), to_real(c, z, "z")};
}

void append_real(std::string& s, double v) {
  char buf[40];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf - 3, v);
  std::size_t n = static_cast<std::size_t>(ptr - buf);
  if (std::isfinite(v) && std::memchr(buf, '.', n) == nullptr) {
    const char* e = static_cast<const char*>(std::memchr(buf, 'e', n));
    const std::size_t at = e ? static_cast<std::size_t>(e - buf) : n;
    std::memmove(buf + at + 2, buf + at, n - at);
    buf[at] = '.';
    buf[at + 1] = '0';
    n += 2;
  }
  s.append(buf, n);
}

void append_uint(std::string& s, std::uint64_t v) {
  char buf[24];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, ptr);
}

std::string one_line(const std::string& title, std::size_t max_chars) {
  std::string s = title.substr(0, max_chars);
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 32) ch = ' ';
  return s;
}

Welder::Welder(std::vector<Vec3d>& positions, std::size_t expected) : positions_(positions) {
  index_.reserve(expected);
}

std::size_t Welder::Hash::operator()(const Key& k) const {
  std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
  h ^= (k.y + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2));
  h ^= (k.z + 0x94D049BB133111EBull + (h << 6) + (h >> 2));
  return static_cast<std::size_t>(h);
}

Index Welder::add(const Vec3d& p) {
  auto bits = [](double v) {
    if (v == 0) v = 0;  // -0 and +0 are one position
    std::uint64_t b;
    std::memcpy(&b, &v, 8);
    return b;
  };
  const Key key{bits(p.x), bits(p.y), bits(p.z)};
  const auto [it, inserted] = index_.try_emplace(key, static_cast<Index>(positions_.size()));
  if (inserted) positions_.push_back(p);
  return it->second;
}

bool collapse_repeated(const Index (&corners)[4], std::array<Index, 4>& face) {
  face = {kInvalid, kInvalid, kInvalid, kInvalid};
  int n = 0;
  for (int i = 0; i < 4; ++i)
    if (corners[i] != corners[(i + 1) % 4]) face[n++] = corners[i];
  if (n < 3) return false;
  if (n == 3 && (face[0] == face[1] || face[1] == face[2] || face[0] == face[2])) return false;
  return true;
}

void append_point(std::string& s, const Vec3d& p) {
  append_real(s, p.x);
  s += ' ';
  append_real(s, p.y);
  s += ' ';
  append_real(s, p.z);
}

std::string_view require_token(TextCursor& c, const char* what) {
  std::string_view t;
  if (!c.next_token(t)) c.fail(std::string("file ends before ") + what);
  return t;
}

}  // namespace hm::io
