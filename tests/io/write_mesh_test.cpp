#include "io/write_mesh.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/write_polylines.h"
#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;

// One unit square as a quad (patch 0) and a triangle beside it (patch 1).
SurfaceMesh square_and_triangle() {
  SurfaceMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  m.faces = {Face{0, 1, 2, 3}, Face{1, 4, 2, kInvalid}};
  m.face_patch = {0, 1};
  return m;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(WriteMesh, ObjKeepsQuadsAndGroupsByPatch) {
  const fs::path dir = test::scratch_dir("obj");
  write_mesh((dir / "m.obj").string(), square_and_triangle());
  const std::string s = slurp(dir / "m.obj");
  EXPECT_NE(s.find("f 1 2 3 4\n"), std::string::npos) << s;
  EXPECT_NE(s.find("f 2 5 3\n"), std::string::npos) << s;
  EXPECT_NE(s.find("g patch_1\n"), std::string::npos);
}

TEST(WriteMesh, StlSplitsQuadsWithOutwardNormals) {
  const fs::path dir = test::scratch_dir("stl");
  write_mesh((dir / "m.stl").string(), square_and_triangle());
  const std::string s = slurp(dir / "m.stl");
  std::uint32_t n = 0;
  std::memcpy(&n, s.data() + 80, 4);
  EXPECT_EQ(n, 3u);
  EXPECT_EQ(s.size(), 84u + 50u * 3u);
  for (std::uint32_t t = 0; t < n; ++t) {
    float normal[3];
    std::memcpy(normal, s.data() + 84 + 50 * t, 12);
    EXPECT_FLOAT_EQ(normal[2], 1.0f);  // counter-clockwise in the xy plane
  }
}

TEST(WriteMesh, VtuHasCellTypesPatchAndFields) {
  const fs::path dir = test::scratch_dir("vtu");
  const std::vector<double> err = {0.25, 0.5};
  MeshWriteOptions o;
  o.face_fields.push_back({"chord_error", err});
  write_mesh((dir / "m.vtu").string(), square_and_triangle(), o);
  const std::string s = slurp(dir / "m.vtu");
  EXPECT_NE(s.find("NumberOfPoints=\"5\" NumberOfCells=\"2\""), std::string::npos);
  EXPECT_NE(s.find("Name=\"types\" format=\"ascii\">\n9\n5\n"), std::string::npos);
  EXPECT_NE(s.find("Name=\"patch\" format=\"ascii\">\n0\n1\n"), std::string::npos);
  EXPECT_NE(s.find("Name=\"chord_error\" format=\"ascii\">\n0.25\n0.5\n"), std::string::npos);
}

TEST(WriteMesh, UnknownExtensionNamesKnownFormats) {
  try {
    write_mesh("out.xyz", square_and_triangle());
    FAIL() << "expected UsageError";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown mesh format '.xyz'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find(".vtu"), std::string::npos);
  }
}

TEST(WriteMesh, MissingFolderIsIoError) {
  EXPECT_THROW(write_mesh("/nonexistent-folder/m.obj", square_and_triangle()), IoError);
}

TEST(AtomicFile, FailedWriteKeepsOldFileAndLeavesNoTemporary) {
  const fs::path dir = test::scratch_dir("atomic");
  const std::string path = (dir / "keep.txt").string();
  write_file_atomically(path, [](std::ostream& o) { o << "old"; });
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& o) {
                                       o << "half";
                                       throw IoError("simulated failure");
                                     }),
               IoError);
  EXPECT_EQ(slurp(path), "old");
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace hm

namespace hm {
namespace {

TEST(WritePolylines, CsvAndVtkCarryEveryPoint) {
  const auto dir = test::scratch_dir("polylines");
  PolylineRecord a{"x=1", {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}}, {0, 0, 1}, {}, false};
  PolylineRecord b{"z=2", {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}}, {}, {}, true};
  const std::vector<PolylineRecord> lines = {a, b};
  write_polylines((dir / "s.csv").string(), lines);
  write_polylines((dir / "s.vtk").string(), lines);
  const std::string c = slurp(dir / "s.csv");
  EXPECT_NE(c.find("0,x=1,0,2,1,1,1,1,,\n"), std::string::npos) << c;
  EXPECT_NE(c.find("1,z=2,1,0,0,0,2,,,\n"), std::string::npos) << c;
  const std::string v = slurp(dir / "s.vtk");
  EXPECT_NE(v.find("POINTS 6 double"), std::string::npos);
  EXPECT_NE(v.find("LINES 2 9\n3 0 1 2\n4 3 4 5 3\n"), std::string::npos) << v;
  EXPECT_THROW(write_polylines((dir / "s.txt").string(), lines), UsageError);
}

}  // namespace
}  // namespace hm
