#include "iges/iges_model.h"

#include <cmath>

#include "core/error.h"

namespace hm::iges {
namespace {

// Joins records, each padded to `width` columns, so that Hollerith strings may span lines.
std::string join_records(const std::vector<Record>& recs, std::size_t width) {
  std::string out;
  out.reserve(recs.size() * width);
  for (const Record& r : recs) {
    const std::string_view d = r.data.substr(0, std::min(width, r.data.size()));
    out.append(d);
    out.append(width - d.size(), ' ');
  }
  return out;
}

void read_header(const Sections& s, IgesModel& m) {
  const std::string g = join_records(s.g, 72);
  std::size_t pos = 0;
  std::string error;
  m.delims = read_global_delimiters(g, pos, error);
  if (!error.empty()) {
    throw IgesError(m.source + ": line " + std::to_string(s.g.front().line) + ": " + error);
  }
  std::vector<Token> t;
  error = tokenize(std::string_view(g).substr(pos), m.delims, 1000, t);
  if (!error.empty()) {
    m.file_diagnostics.warn("G section: " + error + "; header fields may be incomplete");
  }
  // t[0] is G3.
  auto str = [&](int k) {
    const std::size_t i = static_cast<std::size_t>(k - 3);
    return i < t.size() ? std::string(t[i].view()) : std::string();
  };
  auto num = [&](int k, double fallback) {
    const std::size_t i = static_cast<std::size_t>(k - 3);
    if (i >= t.size() || t[i].empty()) return fallback;
    const auto v = parse_real(t[i].view());
    if (!v) {
      m.file_diagnostics.warn("G section: parameter G" + std::to_string(k) + " '" +
                              std::string(t[i].view()) + "' is not a number; using the default");
      return fallback;
    }
    return *v;
  };
  IgesHeader& h = m.header;
  h.file_name = str(4);
  h.sending_system = str(3).empty() ? h.file_name : str(3);
  h.native_system = str(5);
  h.preprocessor = str(6);
  h.model_scale = num(13, 1.0);
  const double flag = num(14, 1.0);
  h.unit_flag = std::fabs(flag) < 1e6 ? static_cast<int>(flag) : 0;
  h.unit_name = str(15);
  h.date = str(18);
  h.min_resolution = num(19, 0.0);
  h.author = str(21);
  h.organisation = str(22);
}

void tokenize_entities(IgesModel& m) {
  const std::size_t n = m.entries.size();
  m.first_token.assign(n + 1, 0);
  m.token_error.assign(n, std::string());
  m.tokens.reserve(m.pdata.size() / 10 + 16);
  const std::string_view all(m.pdata);
  for (std::size_t i = 0; i < n; ++i) {
    const DirEntry& e = m.entries[i];
    m.first_token[i] = static_cast<std::uint32_t>(m.tokens.size());
    const std::size_t first = static_cast<std::size_t>(e.param_line - 1) * 64;
    const std::size_t len = static_cast<std::size_t>(std::max(e.param_count, 1)) * 64;
    std::string err =
        tokenize(all.substr(first, len), m.delims, m.limits.max_params_per_entity + 1, m.tokens);
    if (err == "too many") {
      throw LimitError(m.source + ": DE " + std::to_string(e.de) + " (type " +
                       std::to_string(e.type) + "): more than " +
                       std::to_string(m.limits.max_params_per_entity) +
                       " parameters (limit max_params_per_entity)");
    }
    const std::size_t count = m.tokens.size() - m.first_token[i];
    if (err.empty()) {
      const auto type = count > 0 ? parse_int(m.tokens[m.first_token[i]].view()) : std::nullopt;
      if (!type) {
        err = "the parameter data does not start with an entity type number";
      } else if (*type != e.type) {
        err = "the parameter data is of type " + std::to_string(*type) +
              " but the directory says " + std::to_string(e.type);
      }
    }
    m.token_error[i] = std::move(err);
    if (m.tokens.size() > 0xF0000000u) {
      throw LimitError(m.source + ": too many parameters in the file");
    }
  }
  m.first_token[n] = static_cast<std::uint32_t>(m.tokens.size());
}

}  // namespace

IgesModel load_model(std::string_view text, const std::string& source,
                     const ResourceLimits& limits) {
  IgesModel m;
  m.source = source;
  m.limits = limits;
  const Sections s = split_sections(text, source);
  for (const std::string& w : s.warnings) m.file_diagnostics.warn(w);
  const std::uint64_t entity_count = s.d.size() / 2;
  if (entity_count > limits.max_entities) {
    throw LimitError(source + ": " + std::to_string(entity_count) +
                     " directory entries, over the " + "limit of " +
                     std::to_string(limits.max_entities) + " (max_entities)");
  }
  read_header(s, m);
  m.entries = parse_directory(s.d, s.p.size(), source);
  // Each P line belongs to one entity; overlapping ranges would let a small file make us
  // tokenize the same text again and again.
  std::uint64_t claimed = 0;
  for (const DirEntry& e : m.entries)
    claimed += static_cast<std::uint64_t>(std::max(e.param_count, 1));
  if (claimed > 2 * s.p.size() + 16) {
    throw IgesError(source + ": the directory claims " + std::to_string(claimed) +
                    " parameter lines but the P section has " + std::to_string(s.p.size()) +
                    ": entities overlap");
  }
  m.pdata = join_records(s.p, 64);
  tokenize_entities(m);
  return m;
}

Params::Params(const IgesModel& m, int index) : m_(&m), index_(index) {
  const std::size_t i = static_cast<std::size_t>(index);
  if (!m.token_error[i].empty()) throw EntityFault(index, m.token_error[i]);
  first_ = m.first_token[i];
  count_ = m.first_token[i + 1] - first_ - 1;
}

void Params::fault(const std::string& message) const { throw EntityFault(index_, message); }

void Params::require(std::uint64_t k, const char* what) const {
  if (k > count_) {
    fault(std::string("too few parameters for ") + what + ": needs " + std::to_string(k) +
          ", has " + std::to_string(count_));
  }
}

double Params::real(std::size_t k) const {
  if (k < 1 || k > count_) {
    fault("parameter " + std::to_string(k) + " is missing (the entity has " +
          std::to_string(count_) + ")");
  }
  const Token& t = tok(k);
  if (t.empty()) return 0.0;  // IGES default for an omitted real
  const auto v = t.hollerith ? std::nullopt : parse_real(t.view());
  if (!v) {
    fault("parameter " + std::to_string(k) + " '" + std::string(t.view().substr(0, 40)) +
          "' is not a finite number");
  }
  return *v;
}

double Params::real_or(std::size_t k, double fallback) const { return has(k) ? real(k) : fallback; }

std::int64_t Params::integer(std::size_t k) const {
  if (k < 1 || k > count_) {
    fault("parameter " + std::to_string(k) + " is missing (the entity has " +
          std::to_string(count_) + ")");
  }
  const Token& t = tok(k);
  if (t.empty()) return 0;
  const auto v = t.hollerith ? std::nullopt : parse_int(t.view());
  if (!v) {
    fault("parameter " + std::to_string(k) + " '" + std::string(t.view().substr(0, 40)) +
          "' is not an integer");
  }
  return *v;
}

std::int64_t Params::integer_or(std::size_t k, std::int64_t fallback) const {
  return has(k) ? integer(k) : fallback;
}

int Params::bounded(std::size_t k, std::int64_t lo, std::int64_t hi, const char* what) const {
  const std::int64_t v = integer(k);
  if (v < lo || v > hi) {
    fault(std::string(what) + " (parameter " + std::to_string(k) + ") is " + std::to_string(v) +
          ", outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return static_cast<int>(v);
}

std::string Params::text(std::size_t k) const {
  if (k < 1 || k > count_) return {};
  return std::string(tok(k).view());
}

int Params::pointer(std::size_t k) const {
  const std::int64_t v = integer(k);
  if (v == 0) return -1;
  const int i = m_->index_of(v);
  if (i < 0) {
    fault("dangling pointer: parameter " + std::to_string(k) + " points to DE " +
          std::to_string(v) + ", which is not a directory entry of this file");
  }
  return i;
}

int Params::pointer_to(std::size_t k, std::initializer_list<int> types, const char* what) const {
  const int i = pointer(k);
  if (i < 0) return i;
  const int type = m_->entries[static_cast<std::size_t>(i)].type;
  for (int t : types) {
    if (t == type) return i;
  }
  fault(std::string(what) + " (parameter " + std::to_string(k) + ") points to DE " +
        std::to_string(2 * i + 1) + " of type " + std::to_string(type) +
        ", which cannot serve there");
}

std::vector<double> read_knots(const Params& p, std::size_t k, std::size_t count,
                               const char* name) {
  std::vector<double> knots(count);
  for (std::size_t i = 0; i < count; ++i) {
    knots[i] = p.real(k + i);
    if (i > 0 && knots[i] < knots[i - 1]) {
      p.fault(std::string("decreasing knots: ") + name + " knot " + std::to_string(i) + " (" +
              std::to_string(knots[i]) + ") is less than knot " + std::to_string(i - 1) + " (" +
              std::to_string(knots[i - 1]) + ")");
    }
  }
  if (count > 0 && !(knots.back() > knots.front())) {
    p.fault(std::string("the ") + name + " knot vector spans no interval (all knots equal)");
  }
  return knots;
}

std::vector<double> read_weights(const Params& p, std::size_t k, std::size_t count) {
  std::vector<double> w(count);
  for (std::size_t i = 0; i < count; ++i) {
    w[i] = p.real(k + i);
    if (!(w[i] > 0)) {
      p.fault("weight " + std::to_string(i) + " is " +
              (w[i] == 0 ? std::string("zero") : std::to_string(w[i])) +
              "; weights must be positive");
    }
  }
  return w;
}

std::vector<Vec3d> read_points(const Params& p, std::size_t k, std::size_t count) {
  std::vector<Vec3d> pts(count);
  for (std::size_t i = 0; i < count; ++i) {
    pts[i] = {p.real(k + 3 * i), p.real(k + 3 * i + 1), p.real(k + 3 * i + 2)};
  }
  return pts;
}

std::string describe(const IgesModel& m, int index) {
  const DirEntry& e = m.entries[static_cast<std::size_t>(index)];
  return "DE " + std::to_string(e.de) + " (type " + std::to_string(e.type) + ")";
}

}  // namespace hm::iges
