// Every format reads back what it wrote: the same positions (bit for bit for text, float
// precision for binary STL), the same faces in the same corner order, normals pointing the same
// way, and the symmetry, patches and title where the format carries them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;

// Two quads and two triangles on two patches; vertices in order of first use by the faces, so
// that formats which list corners per panel and weld on read (GDF, STL) give the same numbering.
SurfaceMesh two_patch_mesh() {
  SurfaceMesh m;
  const double third = 1.0 / 3.0;
  m.positions = {{0.1, 0.2, -third},
                 {1.7, 0.2, -third},
                 {1.7, 1.3, -0.05},
                 {0.1, 1.3, -0.05},
                 {3.3, 0.2, -third},
                 {3.3, 1.3, -1e-7},
                 {2.5, 2.9, 12345.678901234567}};
  m.faces = {Face{0, 1, 2, 3}, Face{1, 4, 2, kInvalid}, Face{4, 5, 2, kInvalid}, Face{2, 5, 6, 3}};
  m.face_patch = {0, 0, 1, 1};
  m.face_block = {7, 7, kInvalid, 2};
  return m;
}

// The faces as triangles, quads split along 0-2 (what STL stores).
std::vector<std::array<Vec3d, 3>> triangles(const SurfaceMesh& m) {
  std::vector<std::array<Vec3d, 3>> t;
  const auto& p = m.positions;
  for (const Face& f : m.faces) {
    t.push_back({p[f[0]], p[f[1]], p[f[2]]});
    if (!is_triangle(f)) t.push_back({p[f[0]], p[f[2]], p[f[3]]});
  }
  return t;
}

struct Case {
  const char* file;
  bool patches;   // carries face_patch
  bool symmetry;  // carries the y = 0 symmetry flag
  bool title;     // carries the title
  bool float_precision = false;
  bool triangles_only = false;
  bool stl_ascii = false;
};

class RoundTrip : public testing::TestWithParam<Case> {};

TEST_P(RoundTrip, SamePanelsSymmetryAndNormals) {
  const Case& c = GetParam();
  const fs::path dir = test::scratch_dir(std::string("round_trip_") + c.file);
  const std::string path = (dir / c.file).string();
  const SurfaceMesh in = two_patch_mesh();
  MeshWriteOptions o;
  o.info.title = "round trip of two patches";
  o.info.symmetry.about_y0 = true;
  o.stl_ascii = c.stl_ascii;
  const std::vector<double> err = {0.25, -1.5, 3e-9, 1.0 / 7.0};
  o.face_fields.push_back({"chord_error", err});
  write_mesh(path, in, o);
  const MeshFile out = read_mesh(path);
  const SurfaceMesh& m = out.mesh;
  ASSERT_EQ(m.face_patch.size(), m.faces.size());

  if (c.triangles_only) {
    const auto a = triangles(in), b = triangles(m);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t t = 0; t < a.size(); ++t)
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d) {
          if (c.float_precision) {
            EXPECT_EQ(float(a[t][k][d]), b[t][k][d]) << t << ' ' << k;
          } else {
            EXPECT_EQ(a[t][k][d], b[t][k][d]) << t << ' ' << k;
          }
        }
    EXPECT_EQ(m.positions.size(), in.positions.size()) << "welding on read";
  } else {
    ASSERT_EQ(m.positions.size(), in.positions.size());
    for (std::size_t i = 0; i < in.positions.size(); ++i)
      EXPECT_EQ(m.positions[i], in.positions[i]) << "vertex " << i;  // bit for bit
    ASSERT_EQ(m.faces.size(), in.faces.size());
    for (std::size_t i = 0; i < in.faces.size(); ++i) {
      EXPECT_EQ(m.faces[i], in.faces[i]) << "face " << i;
      const Vec3d n0 = face_normal(in.positions, in.faces[i]);
      const Vec3d n1 = face_normal(m.positions, m.faces[i]);
      EXPECT_GT(dot(n0, n1), 0.999999) << "face " << i << " normal flipped";
    }
  }
  if (c.patches) {
    EXPECT_EQ(m.face_patch, in.face_patch);
  } else {
    EXPECT_EQ(m.face_patch, std::vector<PatchId>(m.faces.size(), 0));
  }
  EXPECT_EQ(out.info.symmetry.about_y0, c.symmetry);
  EXPECT_FALSE(out.info.symmetry.about_x0);
  if (c.title) {
    EXPECT_EQ(out.info.title, o.info.title);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Formats, RoundTrip,
    testing::Values(Case{"m.gdf", false, true, true}, Case{"m.dat", false, true, false},
                    Case{"HullMesh.pnl", false, true, false}, Case{"m.hst", false, true, true},
                    Case{"m.msh", true, false, false}, Case{"m.vtk", true, true, true},
                    Case{"m.vtu", true, true, true}, Case{"m.obj", true, false, true},
                    Case{"binary.stl", false, false, true, true, true},
                    Case{"ascii.stl", false, false, true, false, true, true}),
    [](const testing::TestParamInfo<Case>& i) {
      std::string s = i.param.file;
      for (char& ch : s)
        if (ch == '.') ch = '_';
      return s;
    });

TEST(RoundTripVtk, BlockAndFieldsComeBack) {
  const fs::path dir = test::scratch_dir("round_trip_fields");
  const SurfaceMesh in = two_patch_mesh();
  const std::vector<double> err = {0.25, -1.5, 3e-9, 1.0 / 7.0};
  MeshWriteOptions o;
  o.face_fields.push_back({"chord_error", err});
  for (const char* name : {"f.vtk", "f.vtu"}) {
    write_mesh((dir / name).string(), in, o);
    const MeshFile out = read_mesh((dir / name).string());
    EXPECT_EQ(out.mesh.face_block, in.face_block) << name;
    ASSERT_EQ(out.fields.size(), 1u) << name;
    EXPECT_EQ(out.fields[0].name, "chord_error");
    EXPECT_EQ(out.fields[0].values, err) << name;
  }
}

TEST(RoundTripGdf, UlenGravAndBothSymmetries) {
  const fs::path dir = test::scratch_dir("round_trip_gdf");
  MeshWriteOptions o;
  o.info.ulen = 142.0;
  o.info.grav = 32.174;
  o.info.symmetry = {true, true};
  write_mesh((dir / "q.gdf").string(), two_patch_mesh(), o);
  const MeshFile out = read_mesh((dir / "q.gdf").string());
  EXPECT_EQ(out.info.ulen, 142.0);
  EXPECT_EQ(out.info.grav, 32.174);
  EXPECT_TRUE(out.info.symmetry.about_x0);
  EXPECT_TRUE(out.info.symmetry.about_y0);
  // Hydrostar says "both planes" with 2; HAMS can hold one plane at a time, NEMOH only y = 0.
  write_mesh((dir / "q.hst").string(), two_patch_mesh(), o);
  EXPECT_EQ(read_mesh((dir / "q.hst").string()).info.symmetry, o.info.symmetry);
  EXPECT_THROW(write_mesh((dir / "q.pnl").string(), two_patch_mesh(), o), UsageError);
  EXPECT_THROW(write_mesh((dir / "q.dat").string(), two_patch_mesh(), o), UsageError);
  o.info.symmetry = {false, true};
  EXPECT_THROW(write_mesh((dir / "x.hst").string(), two_patch_mesh(), o), UsageError);
  write_mesh((dir / "x.pnl").string(), two_patch_mesh(), o);
  EXPECT_EQ(read_mesh((dir / "x.pnl").string()).info.symmetry, o.info.symmetry);
  EXPECT_FALSE(fs::exists(dir / "q.pnl"));  // a refused write leaves nothing behind
}

TEST(RoundTripPnl, WaterplaneMeshByNameAndItsZCheck) {
  const fs::path dir = test::scratch_dir("round_trip_lid");
  SurfaceMesh lid;
  lid.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  lid.faces = {Face{0, 1, 2, 3}, Face{1, 4, 2, kInvalid}};
  const std::string path = (dir / "WaterplaneMesh.pnl").string();
  write_mesh(path, lid);
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  EXPECT_NE(first.find("Waterplane Mesh File"), std::string::npos) << first;
  const MeshFile out = read_mesh(path);
  EXPECT_TRUE(out.info.waterplane_lid);
  EXPECT_EQ(out.mesh.faces, lid.faces);
  lid.positions[2].z = 1e-3;
  EXPECT_THROW(write_mesh(path, lid), GeometryError);
}

TEST(RoundTripText, HstIsReadableByRegexReadersThatNeedADecimalPoint) {
  // Capytaine's older HST and RAD loaders only match numbers with a '.'.
  std::ostringstream s;
  SurfaceMesh m;
  m.positions = {{0, 1, 2}, {1e20, 5, 0}, {3, 1e-5, 7}};
  m.faces = {Face{0, 1, 2, kInvalid}};
  write_mesh_to(s, ".hst", m);
  EXPECT_NE(s.str().find("1 0.0 1.0 2.0\n"), std::string::npos) << s.str();
  EXPECT_NE(s.str().find("2 1.0e+20 5.0 0.0\n"), std::string::npos) << s.str();
  const MeshFile back = read_mesh_from_memory(s.str(), ".hst", "mem.hst");
  EXPECT_EQ(back.mesh.positions, m.positions);
}

TEST(ReadMesh, StlWeldsDeterministicallyAndDetectsAscii) {
  const fs::path dir = test::scratch_dir("stl_weld");
  SurfaceMesh m = two_patch_mesh();
  MeshWriteOptions o;
  write_mesh((dir / "b.stl").string(), m, o);
  o.stl_ascii = true;
  write_mesh((dir / "a.stl").string(), m, o);
  const MeshFile b1 = read_mesh((dir / "b.stl").string());
  const MeshFile b2 = read_mesh((dir / "b.stl").string());
  EXPECT_EQ(b1.mesh.faces, b2.mesh.faces);
  EXPECT_EQ(b1.mesh.faces.size(), 6u);
  const MeshFile a = read_mesh((dir / "a.stl").string());
  EXPECT_EQ(a.mesh.faces, b1.mesh.faces);  // same welding for both kinds
}

TEST(ReadMesh, UnknownFormatAndMissingFile) {
  EXPECT_THROW(read_mesh("mesh.xyz"), UsageError);
  EXPECT_THROW(read_mesh("/nonexistent-folder/m.gdf"), IoError);
  ReadOptions o;
  o.format = ".obj";
  EXPECT_THROW(read_mesh("/nonexistent-folder/m.txt", o), IoError);
}

TEST(ReadMesh, FileSizeLimit) {
  ReadOptions o;
  o.limits.max_file_bytes = 10;
  EXPECT_THROW(read_mesh_from_memory("v 0 0 0\nv 1 0 0\n", ".obj", "m.obj", o), LimitError);
}

TEST(WriteMesh, NonFinitePositionIsGeometryError) {
  SurfaceMesh m = two_patch_mesh();
  m.positions[3].y = std::nan("");
  const fs::path dir = test::scratch_dir("nan_write");
  EXPECT_THROW(write_mesh((dir / "m.gdf").string(), m), GeometryError);
  EXPECT_FALSE(fs::exists(dir / "m.gdf"));
}

}  // namespace
}  // namespace hm
