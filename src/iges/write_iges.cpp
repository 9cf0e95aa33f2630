#include "iges/write_iges.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace hm {
namespace {

constexpr int kParamColumns = 64;   // P records: data in columns 1-64
constexpr int kGlobalColumns = 72;  // S and G records: data in columns 1-72

// One entity: directory fields and its parameter tokens (the type number first), without
// delimiters. Pointers are DE numbers, known when the entity is made because every entity
// points only at entities written before it.
struct Entity {
  int type = 0;
  int form = 0;
  const char* status = "00000000";
  std::vector<std::string> params;
};

std::string integer(long long v) { return std::to_string(v); }

// 17 significant digits read back as the same double; a decimal point marks it as real.
std::string real(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17G", v);
  std::string s = buf;
  if (s.find('.') == std::string::npos) {
    const std::size_t e = s.find('E');
    if (e == std::string::npos) {
      s += '.';
    } else {
      s.insert(e, ".");
    }
  }
  return s;
}

std::string hollerith(const std::string& text) { return integer(text.size()) + "H" + text; }

// Metres per unit for the IGES unit flags (G14) and their G15 names.
struct UnitInfo {
  int flag;
  double metres;
  const char* name;
};
constexpr UnitInfo kUnits[] = {{1, 0.0254, "INCH"}, {2, 0.001, "MM"}, {4, 0.3048, "FT"},
                               {5, 1609.344, "MI"}, {6, 1.0, "M"},    {7, 1000.0, "KM"},
                               {8, 2.54e-5, "MIL"}, {9, 1e-6, "UM"},  {10, 0.01, "CM"},
                               {11, 2.54e-8, "UIN"}};

const UnitInfo& unit_info(int flag) {
  for (const UnitInfo& u : kUnits) {
    if (u.flag == flag) return u;
  }
  throw UsageError("IGES writer: unsupported unit flag " + std::to_string(flag));
}

void check_surface(const NurbsSurface& s, std::size_t index) {
  const std::size_t n = static_cast<std::size_t>(std::max(s.count_u, 0)) *
                        static_cast<std::size_t>(std::max(s.count_v, 0));
  if (s.degree_u < 1 || s.degree_v < 1 || s.count_u <= s.degree_u || s.count_v <= s.degree_v ||
      s.knots_u.size() != static_cast<std::size_t>(s.count_u + s.degree_u + 1) ||
      s.knots_v.size() != static_cast<std::size_t>(s.count_v + s.degree_v + 1) ||
      s.points.size() != n || s.weights.size() != n) {
    throw GeometryError("IGES writer: patch " + std::to_string(index) +
                        " has inconsistent degrees, counts, knots or weights");
  }
}

bool all_equal(const std::vector<double>& w) {
  return std::all_of(w.begin(), w.end(), [&](double x) { return x == w.front(); });
}

// 128 rational B-spline surface. `scale` divides coordinates (metres -> file units).
Entity surface_entity(const NurbsSurface& s, double scale, int name_de) {
  Entity e{128, 0, "00000000", {}};
  auto& p = e.params;
  p = {integer(128),
       integer(s.count_u - 1),
       integer(s.count_v - 1),
       integer(s.degree_u),
       integer(s.degree_v),
       integer(0),
       integer(0),
       integer(all_equal(s.weights) ? 1 : 0),
       integer(s.periodic_u),
       integer(s.periodic_v)};
  for (double k : s.knots_u) p.push_back(real(k));
  for (double k : s.knots_v) p.push_back(real(k));
  for (double w : s.weights) p.push_back(real(w));
  for (const Vec3d& q : s.points) {
    for (int c = 0; c < 3; ++c) p.push_back(real(scale == 1.0 ? q[c] : q[c] / scale));
  }
  for (double d : {s.u0, s.u1, s.v0, s.v1}) p.push_back(real(d));
  if (name_de > 0) {
    // No associativities, one property: the 406 name.
    p.insert(p.end(), {integer(0), integer(1), integer(name_de)});
  }
  return e;
}

// 126 curve in the parameter space of a surface (z = 0, normal +z).
Entity parameter_curve_entity(const NurbsCurve& c) {
  Entity e{126, 0, "00010500", {}};
  auto& p = e.params;
  const bool closed = !c.points.empty() && c.points.front() == c.points.back();
  p = {integer(126),    integer(c.count() - 1),        integer(c.degree),  integer(1),
       integer(closed), integer(all_equal(c.weights)), integer(c.periodic)};
  for (double k : c.knots) p.push_back(real(k));
  for (double w : c.weights) p.push_back(real(w));
  for (const Vec3d& q : c.points) {
    for (int k = 0; k < 3; ++k) p.push_back(real(q[k]));
  }
  for (double d : {c.t0, c.t1, 0.0, 0.0, 1.0}) p.push_back(real(d));
  return e;
}

class EntityList {
 public:
  // Appends an entity and returns its DE number (its first D record).
  int add(Entity e) {
    entities_.push_back(std::move(e));
    return 2 * static_cast<int>(entities_.size()) - 1;
  }
  const std::vector<Entity>& entities() const { return entities_; }

 private:
  std::vector<Entity> entities_;
};

// One trim loop as a 142 curve on the surface: a 126 per curve, joined by a 102 when several.
int add_loop(EntityList& list, const TrimLoop& loop, int surface_de, std::size_t index) {
  if (loop.curves_uv.empty()) {
    throw GeometryError("IGES writer: patch " + std::to_string(index) + " has an empty trim loop");
  }
  std::vector<int> curves;
  for (const NurbsCurve& c : loop.curves_uv) {
    if (c.degree < 1 || c.knots.size() != c.points.size() + c.degree + 1 ||
        c.weights.size() != c.points.size()) {
      throw GeometryError("IGES writer: patch " + std::to_string(index) +
                          " has a malformed trim curve");
    }
    curves.push_back(list.add(parameter_curve_entity(c)));
  }
  int curve_de = curves.front();
  if (curves.size() > 1) {
    Entity composite{102, 0, "00010500", {integer(102), integer(curves.size())}};
    for (int de : curves) composite.params.push_back(integer(de));
    curve_de = list.add(std::move(composite));
  }
  // Creation 0 (unspecified), no model-space curve, parameter-space curve preferred.
  return list.add(Entity{
      142,
      0,
      "00010000",
      {integer(142), integer(0), integer(surface_de), integer(curve_de), integer(0), integer(1)}});
}

void add_patch(EntityList& list, const Patch& patch, double scale, std::size_t index) {
  check_surface(patch.surface, index);
  int name_de = 0;
  if (!patch.name.empty()) {
    name_de =
        list.add(Entity{406, 15, "00000000", {integer(406), integer(1), hollerith(patch.name)}});
  }
  Entity surface = surface_entity(patch.surface, scale, name_de);
  if (patch.loops.empty()) {
    list.add(std::move(surface));
    return;
  }
  surface.status = "00010000";  // physically dependent on the 144
  const int surface_de = list.add(std::move(surface));
  int outer = 0;
  std::vector<int> inner;
  for (const TrimLoop& loop : patch.loops) {
    const int de = add_loop(list, loop, surface_de, index);
    if (loop.outer && outer == 0) {
      outer = de;
    } else {
      inner.push_back(de);
    }
  }
  Entity trimmed{144,
                 0,
                 "00000000",
                 {integer(144), integer(surface_de), integer(outer != 0 ? 1 : 0),
                  integer(inner.size()), integer(outer)}};
  for (int de : inner) trimmed.params.push_back(integer(de));
  list.add(std::move(trimmed));
}

// Appends fixed-width records: `width` data columns, the section letter in column 73 and the
// sequence number in 74-80. Tokens never straddle records except Hollerith strings longer than
// a record. `suffix` (8 columns, the DE pointer of P records) fills columns 65-72.
class RecordWriter {
 public:
  RecordWriter(std::string& out, char section, int width)
      : out_(out), section_(section), width_(width) {}

  void tokens(const std::vector<std::string>& params, char delim, char end,
              const std::string& suffix = "") {
    std::string line;
    for (std::size_t k = 0; k < params.size(); ++k) {
      std::string token = params[k] + (k + 1 == params.size() ? end : delim);
      if (!line.empty() && line.size() + token.size() > static_cast<std::size_t>(width_)) {
        record(line, suffix);
        line.clear();
      }
      while (token.size() > static_cast<std::size_t>(width_) - line.size()) {
        const std::size_t take = width_ - line.size();
        record(line + token.substr(0, take), suffix);
        line.clear();
        token.erase(0, take);
      }
      line += token;
    }
    if (!line.empty()) record(line, suffix);
  }

  void record(const std::string& data, const std::string& suffix = "") {
    std::string line = data;
    line.resize(width_, ' ');
    line += suffix;
    line.resize(72, ' ');
    char tail[16];
    std::snprintf(tail, sizeof tail, "%c%7d\n", section_, ++count_);
    out_ += line;
    out_ += tail;
  }

  int count() const { return count_; }

 private:
  std::string& out_;
  char section_;
  int width_;
  int count_ = 0;
};

std::vector<std::string> global_params(const std::vector<Patch>& patches, const IgesWriteOptions& o,
                                       const UnitInfo& unit, double scale) {
  double max_coord = 0;
  for (const Patch& p : patches) {
    for (const Vec3d& q : p.surface.points) {
      for (int c = 0; c < 3; ++c) max_coord = std::max(max_coord, std::abs(q[c] / scale));
    }
  }
  const std::string system = std::string("hullmesh ") + HULLMESH_VERSION;
  return {hollerith(","),
          hollerith(";"),
          hollerith(system),
          hollerith(o.file_name),
          hollerith(system),
          hollerith("hullmesh IGES writer"),
          integer(32),
          integer(38),
          integer(6),
          integer(308),
          integer(15),
          hollerith(o.file_name),
          real(1.0),
          integer(unit.flag),
          hollerith(unit.name),
          integer(1),
          real(1.0),
          hollerith(o.timestamp),
          real(1e-9 / (o.lie_about_units ? 1.0 : unit.metres)),
          real(max_coord),
          hollerith(o.author),
          hollerith("hullmesh"),
          integer(11),
          integer(0),
          hollerith(o.timestamp)};
}

std::string directory_field(int v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%8d", v);
  return buf;
}

}  // namespace

std::string write_iges(const std::vector<Patch>& patches, const IgesWriteOptions& options) {
  const UnitInfo& unit = unit_info(options.unit_flag);
  // Coordinates are in metres in memory; a lying file keeps them in metres under another flag.
  const double scale = options.lie_about_units ? 1.0 : unit.metres;
  EntityList list;
  for (std::size_t k = 0; k < patches.size(); ++k) add_patch(list, patches[k], scale, k);

  std::string out;
  RecordWriter start(out, 'S', kGlobalColumns);
  start.record("hullmesh IGES 5.3 export: " + std::to_string(patches.size()) +
               " rational B-spline surfaces");
  RecordWriter global(out, 'G', kGlobalColumns);
  global.tokens(global_params(patches, options, unit, scale), ',', ';');

  // Parameter records first (into a side buffer) to learn where each entity's data starts.
  std::string pdata;
  RecordWriter param(pdata, 'P', kParamColumns);
  std::vector<int> pstart, plines;
  const auto& entities = list.entities();
  for (std::size_t k = 0; k < entities.size(); ++k) {
    const int before = param.count();
    pstart.push_back(before + 1);
    param.tokens(entities[k].params, ',', ';', directory_field(static_cast<int>(2 * k + 1)));
    plines.push_back(param.count() - before);
  }
  RecordWriter directory(out, 'D', 72);
  for (std::size_t k = 0; k < entities.size(); ++k) {
    const Entity& e = entities[k];
    std::string a = directory_field(e.type) + directory_field(pstart[k]);
    for (int f = 0; f < 6; ++f) a += directory_field(0);
    a += e.status;
    directory.record(a);
    std::string b = directory_field(e.type) + directory_field(0) + directory_field(0) +
                    directory_field(plines[k]) + directory_field(e.form) + std::string(24, ' ') +
                    directory_field(0);
    directory.record(b);
  }
  out += pdata;
  char t[80];
  std::snprintf(t, sizeof t, "S%7dG%7dD%7dP%7d", start.count(), global.count(), directory.count(),
                param.count());
  RecordWriter(out, 'T', kGlobalColumns).record(t);
  return out;
}

void write_iges_file(const std::string& path, const std::vector<Patch>& patches,
                     const IgesWriteOptions& options) {
  namespace fs = std::filesystem;
  const std::string text = write_iges(patches, options);
  const fs::path target(path);
  fs::path temp = target;
  temp += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError("cannot write " + path + ": " + std::strerror(errno));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(temp, ec);
      throw IoError("cannot write " + path + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw IoError("cannot write " + path + ": " + ec.message());
  }
}

}  // namespace hm
