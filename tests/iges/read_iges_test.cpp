// IGES reader: the lexical layer, directory fields, structure, units, names, groups and the
// table of bad inputs. Geometry of each surface type is in read_iges_geometry_test.cpp.
#include "iges/read_iges.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/error.h"
#include "iges/iges_records.h"
#include "iges_test_entities.h"
#include "iges_text_builder.h"
#include "support/test_support.h"

namespace hm {
namespace {

using test::DirFields;
using test::holl;
using test::IgesTextBuilder;
using test::num;

std::size_t count(const ImportResult& r, Severity s) { return r.diagnostics.count(s); }

bool has_message(const ImportResult& r, Severity s, const std::string& part) {
  for (const Diagnostic& d : r.diagnostics.items()) {
    if (d.severity == s && d.message.find(part) != std::string::npos) return true;
  }
  return false;
}

// Expects `f` to throw E with a message containing every part.
template <class E, class F>
void expect_error(F f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const E& e) {
    for (const std::string& p : parts) {
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
          << "message '" << e.what() << "' lacks '" << p << "'";
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
}

TEST(IgesRecords, NumbersAcceptDExponentsPlusSignsAndIntegralReals) {
  EXPECT_DOUBLE_EQ(*iges::parse_real("1.5D3"), 1500.0);
  EXPECT_DOUBLE_EQ(*iges::parse_real("+2.5d-1"), 0.25);
  EXPECT_DOUBLE_EQ(*iges::parse_real(" 7. "), 7.0);
  EXPECT_DOUBLE_EQ(*iges::parse_real(".5E1"), 5.0);
  EXPECT_FALSE(iges::parse_real("1e400"));
  EXPECT_FALSE(iges::parse_real("NaN"));
  EXPECT_FALSE(iges::parse_real("inf"));
  EXPECT_FALSE(iges::parse_real("1.0x"));
  EXPECT_EQ(*iges::parse_real("1e-400"), 0.0);
  EXPECT_EQ(*iges::parse_int("12"), 12);
  EXPECT_EQ(*iges::parse_int("3."), 3);
  EXPECT_FALSE(iges::parse_int("3.5"));
}

TEST(IgesRecords, TokenizerReadsHollerithWithDelimitersInside) {
  std::vector<iges::Token> t;
  const std::string text = "406,1,7Ha,b;c d,2.5;trailing comment";
  EXPECT_EQ(iges::tokenize(text, {}, 100, t), "");
  ASSERT_EQ(t.size(), 4u);
  EXPECT_TRUE(t[2].hollerith);
  EXPECT_EQ(t[2].view(), "a,b;c d");
  EXPECT_EQ(t[3].view(), "2.5");
  t.clear();
  EXPECT_NE(iges::tokenize("1,20Habc;", {}, 100, t), "");  // count runs past the text
}

TEST(IgesReader, ReadsHeaderFieldsAndCrLfAndShortLines) {
  IgesTextBuilder b;
  b.crlf = true;
  b.short_lines = true;
  b.add(128, test::square(0, 0, 2).params());
  const ImportResult r = read_iges(b.build(), "crlf.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.header.sending_system, "hullmesh tests");
  EXPECT_EQ(r.header.file_name, "test.igs");
  EXPECT_EQ(r.header.author, "a tester");
  EXPECT_EQ(r.header.organisation, "hullmesh org");
  EXPECT_EQ(r.header.unit_flag, 6);
  EXPECT_EQ(r.header.unit_name, "M");
  EXPECT_EQ(r.header.date, "20240101.120000");
  EXPECT_DOUBLE_EQ(r.header.min_resolution, 1e-7);
  EXPECT_EQ(count(r, Severity::kWarning), 0u);
  EXPECT_DOUBLE_EQ(r.bbox.hi.x, 2.0);
}

TEST(IgesReader, CustomDelimitersAndDExponents) {
  IgesTextBuilder b;
  b.param_delim = '/';
  b.record_delim = '#';
  test::Surface128 s = test::square(0, 0, 1);
  std::vector<std::string> p = s.params();
  p[p.size() - 4 - 12 + 3] = "3.0D0";  // x of the second control point, D exponent
  p[p.size() - 4 - 12 + 3 + 1] = "0.0d+00";
  b.add(128, p, DirFields{0, 0, "00000000", "HULL", 7});
  const ImportResult r = read_iges(b.build(), "delims.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_DOUBLE_EQ(r.patches[0].surface.points[1].x, 3.0);
  EXPECT_EQ(r.patches[0].name, "HULL(7)");
  EXPECT_EQ(r.patches[0].wrapping, Wrapping::kPlain);
  EXPECT_EQ(r.patches[0].de, 1);
}

TEST(IgesReader, NameFrom406Form15WithDelimitersInTheHollerith) {
  IgesTextBuilder b;
  const int name = 3;  // the 406 follows the surface
  std::vector<std::string> p = test::square(0, 0, 1).params();
  p.insert(p.end(), {"0", "1", num(name)});  // no associativities, one property
  b.add(128, p);
  b.add(406, {"1", holl("Bow, port; #1")}, DirFields{15});
  const ImportResult r = read_iges(b.build(), "name.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.patches[0].name, "Bow, port; #1");
  EXPECT_EQ(r.skipped_by_type.count(406), 0u);
}

TEST(IgesReader, SurfaceWrappedByATrimIsReportedOnceAsTheTrim) {
  IgesTextBuilder b;
  const int surf = b.add(128, test::square(0, 0, 1).params(), DirFields{0, 0, "00010000"});
  const int uv =
      b.add(126, test::polyline_126({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}}),
            DirFields{0, 0, "00010500"});
  const int cos = b.add(142, {"1", num(surf), num(uv), "0", "1"}, DirFields{0, 0, "00010000"});
  b.add(144, {num(surf), "1", "0", num(cos)});
  const ImportResult r = read_iges(b.build(), "once.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.patches[0].wrapping, Wrapping::kTrimmed);
  EXPECT_EQ(r.patches[0].de, surf);
  EXPECT_EQ(r.patches[0].wrapper_de, 7);
  EXPECT_TRUE(r.patches[0].loops.empty()) << "a loop on the domain boundary is dropped";
  EXPECT_TRUE(r.skipped_by_type.empty());
  EXPECT_EQ(r.entities_by_type.at(128), 1);
  EXPECT_EQ(r.entities_by_type.at(144), 1);
}

TEST(IgesReader, FreeEntitiesAreCountedAsSkipped) {
  IgesTextBuilder b;
  b.add(128, test::square(0, 0, 1).params());
  b.add(116, {"1.", "2.", "3.", "0"});
  b.add(110, test::line_110({0, 0, 0}, {1, 0, 0}));
  b.add(110, test::line_110({0, 0, 0}, {0, 1, 0}));
  const ImportResult r = read_iges(b.build(), "skip.igs");
  EXPECT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.skipped_by_type.at(116), 1);
  EXPECT_EQ(r.skipped_by_type.at(110), 2);
  EXPECT_TRUE(has_message(r, Severity::kNote, "110 x 2"));
}

TEST(IgesReader, BRepFaceOrientationFromShellAndGroupNames) {
  IgesTextBuilder b;
  const int s1 = b.add(128, test::square(0, 0, 1).params());
  const int s2 = b.add(128, test::square(1, 0, 1).params());
  const int f1 = b.add(510, {num(s1), "0", "1"});
  const int f2 = b.add(510, {num(s2), "0", "1"});
  const int shell = b.add(514, {"2", num(f1), "1", num(f2), "0"}, DirFields{1});
  b.add(186, {num(shell), "1", "0"});
  const int gname = b.next_de() + 2;
  b.add(402, {"2", num(f1), num(f2), "0", "1", num(gname)}, DirFields{7});
  b.add(406, {"1", holl("hull")}, DirFields{15});
  const ImportResult r = read_iges(b.build(), "brep.igs");
  ASSERT_EQ(r.patches.size(), 2u);
  EXPECT_EQ(r.patches[0].wrapping, Wrapping::kFace);
  EXPECT_FALSE(r.patches[0].reversed);
  EXPECT_TRUE(r.patches[1].reversed);
  EXPECT_EQ(r.patches[1].wrapper_de, f2);
  ASSERT_EQ(r.groups.size(), 1u);
  EXPECT_EQ(r.groups[0].name, "hull");
  EXPECT_EQ(r.groups[0].member_des, (std::vector<int>{f1, f2}));
  EXPECT_TRUE(r.skipped_by_type.empty());
}

TEST(IgesReader, ShellReversedBySolidFlipsItsFaces) {
  IgesTextBuilder b;
  const int s1 = b.add(128, test::square(0, 0, 1).params());
  const int f1 = b.add(510, {num(s1), "0", "1"});
  const int shell = b.add(514, {"1", num(f1), "1"}, DirFields{1});
  b.add(186, {num(shell), "0", "0"});
  const ImportResult r = read_iges(b.build(), "solid.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_TRUE(r.patches[0].reversed);
}

// A 20 x 4 x 2 box of control points written in the given unit.
std::string hull_in_units(int flag, const std::string& name, double length) {
  IgesTextBuilder b;
  b.unit_flag = flag;
  b.unit_name = name;
  test::Surface128 s;
  s.points = {{0, 0, 0},
              {length, 0, 0},
              {0, 0.2 * length, 0.1 * length},
              {length, 0.2 * length, 0.1 * length}};
  b.add(128, s.params());
  return b.build();
}

TEST(IgesUnits, MillimetreFlagConvertsToMetres) {
  const ImportResult r = read_iges(hull_in_units(2, "MM", 120000), "mm.igs");
  EXPECT_DOUBLE_EQ(r.units.declared_to_metres, 0.001);
  EXPECT_DOUBLE_EQ(r.units.applied_to_metres, 0.001);
  EXPECT_FALSE(r.units.implausible);
  EXPECT_NEAR(r.bbox.hi.x, 120.0, 1e-9);
  EXPECT_NEAR(r.patches[0].surface.points[3].y, 24.0, 1e-9);
  EXPECT_EQ(count(r, Severity::kWarning), 0u);
}

TEST(IgesUnits, LyingUnitFlagWarnsWithASuggestionAndForceOverrides) {
  // Declared millimetres but written in metres: a 5 mm ship.
  const std::string text = hull_in_units(2, "MM", 5.0);
  const ImportResult r = read_iges(text, "lying.igs");
  EXPECT_TRUE(r.units.implausible);
  EXPECT_EQ(r.units.suggestion, "m");
  EXPECT_DOUBLE_EQ(r.units.applied_to_metres, 0.001);
  EXPECT_TRUE(has_message(r, Severity::kWarning, "--units m"));
  ImportOptions o;
  o.force_units = "m";
  const ImportResult f = read_iges(text, "lying.igs", o);
  EXPECT_TRUE(f.units.forced);
  EXPECT_DOUBLE_EQ(f.units.applied_to_metres, 1.0);
  EXPECT_NEAR(f.bbox.hi.x, 5.0, 1e-12);
  o.force_units = "furlong";
  EXPECT_THROW(read_iges(text, "lying.igs", o), UsageError);
}

TEST(IgesUnits, FactorsOfFlagsAndNames) {
  EXPECT_DOUBLE_EQ(iges_unit_to_metres(1), 0.0254);
  EXPECT_DOUBLE_EQ(iges_unit_to_metres(4), 0.3048);
  EXPECT_DOUBLE_EQ(iges_unit_to_metres(10), 0.01);
  EXPECT_EQ(iges_unit_to_metres(3), 0.0);
  EXPECT_EQ(iges_unit_to_metres(99), 0.0);
  EXPECT_DOUBLE_EQ(unit_name_to_metres("MM"), 0.001);
  EXPECT_DOUBLE_EQ(unit_name_to_metres("in"), 0.0254);
  EXPECT_DOUBLE_EQ(unit_name_to_metres("um"), 1e-6);
  EXPECT_EQ(unit_name_to_metres("cubit"), 0.0);
  // Flag 3: the name decides.
  const ImportResult r = read_iges(hull_in_units(3, "FT", 300), "ft.igs");
  EXPECT_DOUBLE_EQ(r.units.declared_to_metres, 0.3048);
}

// ---- the bad-input table ----------------------------------------------------------------

std::string one_surface(const test::Surface128& s) {
  IgesTextBuilder b;
  b.add(128, s.params());
  return b.build();
}

TEST(IgesBadInput, EmptyFile) {
  expect_error<IgesError>([] { read_iges("", "empty.igs"); }, {"empty.igs", "empty"});
  expect_error<IgesError>([] { read_iges("\n\n  \r\n", "blank.igs"); }, {"empty"});
}

TEST(IgesBadInput, NonIgesText) {
  expect_error<IgesError>([] { read_iges("Hello, this is a text file.\nSecond line\n", "t.txt"); },
                          {"t.txt", "line 1", "not an IGES record"});
}

TEST(IgesBadInput, TruncatedSections) {
  IgesTextBuilder b;
  b.add(128, test::square(0, 0, 1).params());
  const std::string full = b.build();
  // Cut inside a P record, and after a whole P record: no T record either way.
  const std::size_t p2 = full.find("P0000002");
  expect_error<IgesError>([&] { read_iges(full.substr(0, p2), "cut.igs"); },
                          {"cut.igs", "truncated", "inside a record of the P section"});
  expect_error<IgesError>([&] { read_iges(full.substr(0, p2 + 9), "cut2.igs"); },
                          {"cut2.igs", "truncated", "no T (terminate) record", "P section"});
  // Cut after the first D line: an odd D section.
  const std::size_t d1 = full.find("D0000001");
  expect_error<IgesError>([&] { read_iges(full.substr(0, d1 + 9), "cutd.igs"); },
                          {"truncated D section"});
  // Only S and G.
  expect_error<IgesError>([&] { read_iges(full.substr(0, full.find("D0000001") - 72), "sg.igs"); },
                          {"no D"});
}

TEST(IgesBadInput, WrongSectionCountsInTWarnOnly) {
  IgesTextBuilder b;
  b.add(128, test::square(0, 0, 1).params());
  b.t_record = "S      1G      4D      9P      3";
  const ImportResult r = read_iges(b.build(), "t.igs");
  EXPECT_EQ(r.patches.size(), 1u);
  EXPECT_TRUE(has_message(r, Severity::kWarning, "declares 9 D lines but the file has 2"));
}

TEST(IgesBadInput, PPointerOutsideThePSection) {
  IgesTextBuilder b;
  b.add(128, test::square(0, 0, 1).params());
  std::string text = b.build();
  const std::size_t d = text.find("D0000001");
  text.replace(d - 72 + 8, 8, "     999");
  expect_error<IgesError>([&] { read_iges(text, "p.igs"); },
                          {"p.igs", "DE 1", "parameter pointer 999", "outside the P section"});
}

TEST(IgesBadInput, DanglingPointer) {
  IgesTextBuilder b;
  b.add(144, {"99", "0", "0", "0"});
  expect_error<IgesError>([&] { read_iges(b.build(), "dangle.igs"); },
                          {"dangle.igs", "no readable surface", "dangling pointer", "DE 99"});
  // With a good surface beside it, the file loads and the bad entity is a diagnostic.
  IgesTextBuilder c;
  c.add(128, test::square(0, 0, 1).params());
  c.add(144, {"99", "0", "0", "0"});
  const ImportResult r = read_iges(c.build(), "dangle2.igs");
  EXPECT_EQ(r.patches.size(), 1u);
  ASSERT_EQ(count(r, Severity::kError), 1u);
  const Diagnostic& d = r.diagnostics.items().back().severity == Severity::kError
                            ? r.diagnostics.items().back()
                            : r.diagnostics.items()[r.diagnostics.items().size() - 2];
  EXPECT_EQ(d.de, 3);
  EXPECT_EQ(d.entity_type, 144);
  EXPECT_GT(d.line, 0);
}

TEST(IgesBadInput, CyclicTransformChain) {
  IgesTextBuilder b;
  b.add(128, test::square(0, 0, 1).params(), DirFields{0, 3});
  b.add(124, {"1", "0", "0", "0", "0", "1", "0", "0", "0", "0", "1", "0"}, DirFields{0, 3});
  expect_error<IgesError>([&] { read_iges(b.build(), "cycle.igs"); },
                          {"cycle.igs", "DE 3", "cyclic transformation chain"});
}

TEST(IgesBadInput, NaNAndHugeNumbers) {
  for (const char* bad : {"NaN", "1e400", "-1.0D999"}) {
    IgesTextBuilder b;
    std::vector<std::string> p = test::square(0, 0, 1).params();
    p[p.size() - 5] = bad;  // z of the last control point
    b.add(128, p);
    expect_error<IgesError>([&] { read_iges(b.build(), "num.igs"); },
                            {"DE 1", "not a finite number", bad});
  }
}

TEST(IgesBadInput, ZeroWeight) {
  test::Surface128 s = test::square(0, 0, 1);
  s.polynomial = false;
  s.weights = {1, 1, 0, 1};
  expect_error<IgesError>([&] { read_iges(one_surface(s), "w.igs"); },
                          {"DE 1", "weight 2 is zero"});
}

TEST(IgesBadInput, DecreasingKnots) {
  test::Surface128 s = test::square(0, 0, 1);
  s.knots_v = {0, 0.5, 0.25, 1};
  expect_error<IgesError>([&] { read_iges(one_surface(s), "k.igs"); },
                          {"DE 1", "decreasing knots", "v knot 2"});
}

TEST(IgesBadInput, DegreeLargerThanControlNet) {
  test::Surface128 s = test::square(0, 0, 1);
  s.m1 = 3;
  s.knots_u = {0, 0, 0, 1, 1, 1};  // K1 + M1 + 2 knots
  expect_error<IgesError>([&] { read_iges(one_surface(s), "d.igs"); },
                          {"DE 1", "degree larger than the control net"});
}

// A patch whose control points coincide, and one whose control points lie on one line: neither
// has area. Each is left out with an error naming its entity; the good patch imports.
TEST(IgesBadInput, PatchesCollapsedToAPointOrALineAreLeftOutByEntity) {
  test::Surface128 point = test::square(0, 0, 1);
  point.points.assign(4, Vec3d{3, 2, 1});
  test::Surface128 line = test::square(0, 0, 1);
  line.points = {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {2, 0, 0}};
  IgesTextBuilder b;
  b.add(128, test::square(0, 0, 1).params());
  const int p_de = b.add(128, point.params());
  const int l_de = b.add(128, line.params());
  const ImportResult r = read_iges(b.build(), "collapsed.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_EQ(r.patches[0].de, 1);
  EXPECT_EQ(r.skipped_by_type.at(128), 2);
  EXPECT_DOUBLE_EQ(r.bbox.extent().x, 1.0) << "the box is the good patch's";
  int found = 0;
  for (const Diagnostic& d : r.diagnostics.items()) {
    if (d.severity != Severity::kError) continue;
    if (d.de == p_de) {
      EXPECT_NE(d.message.find("collapses to a point"), std::string::npos) << d.message;
      ++found;
    }
    if (d.de == l_de) {
      EXPECT_NE(d.message.find("collapses to a line"), std::string::npos) << d.message;
      ++found;
    }
    EXPECT_GT(d.line, 0) << "the parameter line is named";
  }
  EXPECT_EQ(found, 2);
}

TEST(IgesBadInput, AFileOfOnlyCollapsedPatchesHasNoReadableSurface) {
  test::Surface128 point = test::square(0, 0, 1);
  point.points.assign(4, Vec3d{0, 0, 0});
  expect_error<IgesError>([&] { read_iges(one_surface(point), "pt.igs"); },
                          {"pt.igs", "no readable surface", "DE 1", "collapses to a point"});
  test::Surface128 line = test::square(0, 0, 1);
  line.points = {{0, 0, 0}, {0, 0, 5}, {0, 0, 1}, {0, 0, 7}};
  expect_error<IgesError>([&] { read_iges(one_surface(line), "ln.igs"); },
                          {"ln.igs", "DE 1", "collapses to a line"});
}

TEST(IgesBadInput, DeclaredTrillionControlPointsIsALimitErrorBeforeAllocation) {
  IgesTextBuilder b;
  b.add(128, {"999999", "999999", "3", "3", "0", "0", "1", "0", "0", "0.", "0.", "1."});
  expect_error<LimitError>(
      [&] { read_iges(b.build(), "huge.igs"); },
      {"huge.igs", "DE 1", "1000000000000 control points", "max_control_points"});
}

TEST(IgesBadInput, CompositeCurvesSharingMembersCannotExplode) {
  // C(k) = 102 [C(k-1), C(k-1)]: 2^40 lines if expanded naively.
  IgesTextBuilder b;
  const int surf = b.add(128, test::square(0, 0, 1).params());
  int c = b.add(110, test::line_110({0, 0, 0}, {1, 0, 0}));
  for (int k = 0; k < 40; ++k) c = b.add(102, {"2", num(c), num(c)});
  const int cos = b.add(142, {"1", num(surf), num(c), "0", "1"});
  b.add(144, {num(surf), "1", "0", num(cos)});
  ImportOptions o;
  o.limits.max_control_points = 1000;
  const ImportResult r = read_iges(b.build(), "dag.igs", o);
  ASSERT_EQ(r.patches.size(), 1u) << "the patch stays, its bad loop is dropped";
  EXPECT_TRUE(r.patches[0].loops.empty());
  EXPECT_TRUE(has_message(r, Severity::kWarning, "expands past"));
}

TEST(IgesBadInput, EntityCountOverTheLimit) {
  IgesTextBuilder b;
  for (int i = 0; i < 5; ++i) b.add(128, test::square(i, 0, 1).params());
  ImportOptions o;
  o.limits.max_entities = 3;
  expect_error<LimitError>([&] { read_iges(b.build(), "many.igs", o); },
                           {"5 directory entries", "max_entities"});
}

TEST(IgesBadInput, UnreadableFileIsAnIoError) {
  expect_error<IoError>([] { read_iges_file("/nonexistent/dir/x.igs"); },
                        {"/nonexistent/dir/x.igs"});
  const std::string path = (test::scratch_dir("iges_limit") / "small.igs").string();
  {
    std::ofstream out(path);
    out << "0123456789";
  }
  ImportOptions o;
  o.limits.max_file_bytes = 5;
  expect_error<LimitError>([&] { read_iges_file(path, o); }, {"max_file_bytes"});
}

}  // namespace
}  // namespace hm
