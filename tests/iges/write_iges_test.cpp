// The IGES writer: fixed 80-column records, consistent sections and pointers, numbers that read
// back as the same doubles, units, trimmed patches, and the file written through a rename.
// Parsing here is a small independent reader of our own output, not the project's importer.
#include "iges/write_iges.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "nurbs/generate_hull.h"
#include "support/test_support.h"

namespace hm {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<Patch> hull_patches(HullKind kind, int n, bool full = false) {
  HullSpec spec;
  spec.kind = kind;
  spec.patches = n;
  spec.full_hull = full;
  return generate_hull(spec).patches;
}

struct DirEntry {
  int type = 0, pstart = 0, pcount = 0, form = 0;
  std::string status;
};

// The D section and each entity's parameter tokens, read back from our own fixed layout.
struct Parsed {
  std::map<char, int> counts;
  std::map<int, DirEntry> entries;                 // by DE number
  std::map<int, std::vector<std::string>> params;  // by DE number, delimiters removed
  std::vector<std::string> global;
};

std::vector<std::string> split_tokens(const std::string& data) {
  std::vector<std::string> out;
  std::size_t k = 0;
  std::string cur;
  while (k < data.size()) {
    const char c = data[k];
    if (std::isdigit(static_cast<unsigned char>(c)) && cur.empty()) {
      // A Hollerith string nH...: take n characters verbatim.
      std::size_t e = k;
      while (e < data.size() && std::isdigit(static_cast<unsigned char>(data[e]))) ++e;
      if (e < data.size() && data[e] == 'H') {
        const std::size_t n = std::stoul(data.substr(k, e - k));
        out.push_back(data.substr(e + 1, n));
        k = e + 1 + n + 1;  // skip the delimiter
        continue;
      }
    }
    if (c == ',' || c == ';') {
      out.push_back(cur);
      cur.clear();
    } else if (c != ' ') {
      cur += c;
    }
    ++k;
  }
  return out;
}

Parsed parse(const std::string& text) {
  Parsed r;
  std::string global, pdata;
  std::map<int, std::string> pby_de;
  const std::vector<std::string> lines = lines_of(text);
  std::vector<std::string> dlines;
  for (const std::string& line : lines) {
    const char section = line.size() >= 73 ? line[72] : '?';
    ++r.counts[section];
    if (section == 'G') global += line.substr(0, 72);
    if (section == 'D') dlines.push_back(line);
    if (section == 'P') pby_de[std::stoi(line.substr(64, 8))] += line.substr(0, 64);
  }
  for (std::size_t k = 0; k + 1 < dlines.size(); k += 2) {
    DirEntry e;
    e.type = std::stoi(dlines[k].substr(0, 8));
    e.pstart = std::stoi(dlines[k].substr(8, 8));
    e.status = dlines[k].substr(64, 8);
    e.pcount = std::stoi(dlines[k + 1].substr(24, 8));
    e.form = std::stoi(dlines[k + 1].substr(32, 8));
    r.entries[static_cast<int>(k) + 1] = e;
  }
  for (auto& [de, data] : pby_de) r.params[de] = split_tokens(data);
  r.global = split_tokens(global);
  return r;
}

double number(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

// Parameters of the first entity of the given type.
const std::vector<std::string>& first_of(const Parsed& r, int type) {
  for (const auto& [de, e] : r.entries) {
    if (e.type == type) return r.params.at(de);
  }
  throw std::runtime_error("no entity of type " + std::to_string(type));
}

TEST(WriteIges, RecordsAreEightyColumnsInOrderWithCountsInT) {
  const std::string text = write_iges(hull_patches(HullKind::kChine, 48, true));
  const std::vector<std::string> lines = lines_of(text);
  ASSERT_FALSE(lines.empty());
  std::map<char, int> seq;
  const std::string order = "SGDPT";
  std::size_t rank = 0;
  for (const std::string& line : lines) {
    ASSERT_EQ(line.size(), 80u) << line;
    const char section = line[72];
    ASSERT_NE(order.find(section), std::string::npos) << line;
    ASSERT_GE(order.find(section), rank) << "sections out of order: " << line;
    rank = order.find(section);
    EXPECT_EQ(std::stoi(line.substr(73)), ++seq[section]) << line;
    if (section == 'P') {
      EXPECT_EQ(line[64], ' ') << "parameter data past column 64: " << line;
    }
  }
  const std::string& t = lines.back();
  EXPECT_EQ(t[72], 'T');
  EXPECT_EQ(std::stoi(t.substr(1, 7)), seq['S']);
  EXPECT_EQ(std::stoi(t.substr(9, 7)), seq['G']);
  EXPECT_EQ(std::stoi(t.substr(17, 7)), seq['D']);
  EXPECT_EQ(std::stoi(t.substr(25, 7)), seq['P']);
  EXPECT_EQ(seq['D'] % 2, 0);
  EXPECT_EQ(text.back(), '\n');
}

TEST(WriteIges, IsDeterministicByteForByte) {
  const std::vector<Patch> a = hull_patches(HullKind::kRoundBilge, 48, true);
  const std::vector<Patch> b = hull_patches(HullKind::kRoundBilge, 48, true);
  EXPECT_EQ(write_iges(a), write_iges(b));
  IgesWriteOptions o;
  o.timestamp = "20300101.120000";
  EXPECT_NE(write_iges(a), write_iges(a, o));
}

TEST(WriteIges, EntitiesPointersAndNumbersReadBackExactly) {
  const std::vector<Patch> patches = hull_patches(HullKind::kRoundBilge, 7);
  const Parsed r = parse(write_iges(patches));
  std::vector<int> surfaces;
  for (const auto& [de, e] : r.entries) {
    ASSERT_EQ(r.params.count(de), 1u) << de;
    const auto& p = r.params.at(de);
    EXPECT_EQ(std::stoi(p.at(0)), e.type);
    if (e.type == 128) surfaces.push_back(de);
  }
  ASSERT_EQ(surfaces.size(), patches.size());
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const NurbsSurface& s = patches[k].surface;
    const auto& p = r.params.at(surfaces[k]);
    EXPECT_EQ(std::stoi(p[1]), s.count_u - 1);
    EXPECT_EQ(std::stoi(p[2]), s.count_v - 1);
    EXPECT_EQ(std::stoi(p[3]), s.degree_u);
    EXPECT_EQ(std::stoi(p[4]), s.degree_v);
    EXPECT_EQ(std::stoi(p[7]), 1);  // polynomial: all weights equal
    std::size_t at = 10;
    for (double knot : s.knots_u) EXPECT_EQ(number(p[at++]), knot);
    for (double knot : s.knots_v) EXPECT_EQ(number(p[at++]), knot);
    for (double w : s.weights) EXPECT_EQ(number(p[at++]), w);
    for (const Vec3d& q : s.points) {
      for (int c = 0; c < 3; ++c) {
        const double x = number(p[at++]), want = q[c];
        EXPECT_EQ(std::memcmp(&x, &want, sizeof x), 0) << p[at - 1] << " vs " << want;
      }
    }
    for (double d : {s.u0, s.u1, s.v0, s.v1}) EXPECT_EQ(number(p[at++]), d);
    // The name: no associativities, one 406 form 15 property.
    ASSERT_EQ(p.size(), at + 3);
    EXPECT_EQ(p[at], "0");
    EXPECT_EQ(p[at + 1], "1");
    const int name_de = std::stoi(p[at + 2]);
    EXPECT_EQ(r.entries.at(name_de).type, 406);
    EXPECT_EQ(r.entries.at(name_de).form, 15);
    EXPECT_EQ(r.params.at(name_de).at(2), patches[k].name);
  }
}

TEST(WriteIges, RealsCarryADecimalPointAndSeventeenDigits) {
  Patch p;
  NurbsSurface& s = p.surface;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.points = {{0.1, -0.0, 1e-300}, {1e20, 2, 3}, {-7, 1.0 / 3.0, 5e-324}, {123456789.123, 0, 0}};
  s.weights = {1, 2, 0.5, 1};
  const Parsed r = parse(write_iges({p}));
  const auto& q = first_of(r, 128);
  EXPECT_EQ(std::stoi(q[7]), 0);  // rational
  for (std::size_t k = 10; k < q.size(); ++k) {
    EXPECT_NE(q[k].find('.'), std::string::npos) << q[k];
  }
  std::size_t at = 10 + 8 + 4;
  for (const Vec3d& v : s.points) {
    for (int c = 0; c < 3; ++c) {
      const double x = number(q[at++]), want = v[c];
      EXPECT_EQ(std::memcmp(&x, &want, sizeof x), 0) << q[at - 1];
    }
  }
}

TEST(WriteIges, UnitsScaleCoordinatesOrLie) {
  const std::vector<Patch> patches = hull_patches(HullKind::kWigley, 1);
  const double x = patches[0].surface.points[1].x;  // L / 2
  IgesWriteOptions mm;
  mm.unit_flag = 2;
  const Parsed honest = parse(write_iges(patches, mm));
  EXPECT_EQ(honest.global.at(13), "2");
  EXPECT_EQ(honest.global.at(14), "MM");
  EXPECT_EQ(honest.global.at(17), mm.timestamp);
  const auto& hp = first_of(honest, 128);
  // 128 with 3 x 3 points: points start after 10 + 6 + 6 + 9 parameters.
  EXPECT_DOUBLE_EQ(number(hp.at(31 + 3)), x * 1000.0);
  mm.lie_about_units = true;
  const Parsed lying = parse(write_iges(patches, mm));
  EXPECT_EQ(lying.global.at(13), "2");
  EXPECT_EQ(number(first_of(lying, 128).at(31 + 3)), x);
  IgesWriteOptions bad;
  bad.unit_flag = 3;
  EXPECT_THROW(write_iges(patches, bad), UsageError);
}

TEST(WriteIges, TrimmedPatchesBecome144With142And126) {
  Patch p = hull_patches(HullKind::kWigley, 1)[0];
  p.name.clear();
  TrimLoop outer;
  outer.curves_uv = {make_line({0.1, 0.1, 0}, {0.9, 0.1, 0}),
                     make_line({0.9, 0.1, 0}, {0.5, 0.9, 0}),
                     make_line({0.5, 0.9, 0}, {0.1, 0.1, 0})};
  TrimLoop hole;
  hole.outer = false;
  hole.curves_uv = {make_circular_arc({0.5, 0.4, 0}, {0.6, 0.4, 0}, {0.4, 0.4, 0}),
                    make_circular_arc({0.5, 0.4, 0}, {0.4, 0.4, 0}, {0.6, 0.4, 0})};
  p.loops = {outer, hole};
  const Parsed r = parse(write_iges({p}));
  std::map<int, int> by_type;
  int trimmed = 0;
  for (const auto& [de, e] : r.entries) {
    ++by_type[e.type];
    if (e.type == 144) trimmed = de;
  }
  EXPECT_EQ(by_type[128], 1);
  EXPECT_EQ(by_type[142], 2);
  EXPECT_EQ(by_type[126], 5);
  EXPECT_EQ(by_type[102], 2);
  EXPECT_EQ(by_type[406], 0);
  ASSERT_NE(trimmed, 0);
  const auto& t = r.params.at(trimmed);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_EQ(r.entries.at(std::stoi(t[1])).type, 128);
  EXPECT_EQ(std::stoi(t[2]), 1);  // outer loop given
  EXPECT_EQ(std::stoi(t[3]), 1);  // one hole
  for (int k : {4, 5}) {
    const auto& c = r.params.at(std::stoi(t[k]));
    EXPECT_EQ(std::stoi(c.at(0)), 142);
    EXPECT_EQ(std::stoi(c.at(2)), std::stoi(t[1]));  // on the surface
    EXPECT_EQ(r.entries.at(std::stoi(c.at(3))).type, 102);
    EXPECT_EQ(std::stoi(c.at(5)), 1);  // parameter-space curve preferred
  }
  EXPECT_EQ(r.entries.at(std::stoi(t[1])).status, "00010000");
}

TEST(WriteIges, LongNamesSpanRecords) {
  std::vector<Patch> patches = hull_patches(HullKind::kWigley, 1);
  patches[0].name = std::string(150, 'x') + ",;" + std::string(20, 'y');
  const std::string text = write_iges(patches);
  for (const std::string& line : lines_of(text)) EXPECT_EQ(line.size(), 80u);
  const Parsed r = parse(text);
  bool found = false;
  for (const auto& [de, e] : r.entries) {
    if (e.type == 406) found = r.params.at(de).at(2) == patches[0].name;
  }
  EXPECT_TRUE(found);
}

TEST(WriteIges, RejectsMalformedPatches) {
  std::vector<Patch> patches = hull_patches(HullKind::kWigley, 1);
  patches[0].surface.knots_u.pop_back();
  EXPECT_THROW(write_iges(patches), GeometryError);
}

TEST(WriteIges, FileIsWrittenThroughARename) {
  const std::filesystem::path dir = test::scratch_dir("write_iges_file");
  const std::vector<Patch> patches = hull_patches(HullKind::kChine, 7);
  const std::string path = (dir / "hull.igs").string();
  write_iges_file(path, patches);
  std::ifstream in(path, std::ios::binary);
  const std::string got((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(got, write_iges(patches));
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left behind

  const std::string missing = (dir / "no" / "such" / "dir" / "hull.igs").string();
  try {
    write_iges_file(missing, patches);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hm
