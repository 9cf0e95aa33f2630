// End-to-end tests of `hullmesh render`: the picture shows the hull (pixel coverage against the
// projected area computed here) and its colours follow the chosen data.
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::run_hullmesh;

struct Picture {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  std::array<int, 3> at(int x, int y) const {
    const std::size_t i = (std::size_t(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
  bool background(int x, int y) const { return at(x, y) == std::array<int, 3>{255, 255, 255}; }
};

Picture read_png(const fs::path& path) {
  Picture p;
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return p;
  image.format = PNG_FORMAT_RGB;
  p.rgb.resize(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, p.rgb.data(), 0, nullptr)) {
    p.width = image.width;
    p.height = image.height;
  }
  return p;
}

// The mesh as hullmesh wrote it in OBJ: vertices, faces (0-based) and each face's patch group.
struct ObjMesh {
  std::vector<std::array<double, 3>> v;
  std::vector<std::vector<int>> f;
  std::vector<int> patch;
};

ObjMesh read_obj(const fs::path& path) {
  ObjMesh m;
  std::ifstream in(path);
  std::string line;
  int group = 0;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v") {
      std::array<double, 3> p;
      s >> p[0] >> p[1] >> p[2];
      m.v.push_back(p);
    } else if (tag == "g") {
      std::string name;
      s >> name;
      group = std::stoi(name.substr(name.find('_') + 1));
    } else if (tag == "f") {
      std::vector<int> face;
      std::string corner;
      while (s >> corner) face.push_back(std::stoi(corner.substr(0, corner.find('/'))) - 1);
      m.f.push_back(face);
      m.patch.push_back(group);
    }
  }
  return m;
}

// A picture axis: coordinate a (0 = x, 1 = y, 2 = z) of the mesh.
struct Projection {
  int across, up;  // model coordinates shown to the right and upwards
};

// Area in m^2 of the union of the faces projected onto (across, up), by marking the centres of
// a fine grid's cells that some projected triangle covers.
double projected_area(const ObjMesh& m, Projection pr) {
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const auto& p : m.v) {
    lo[0] = std::min(lo[0], p[pr.across]);
    hi[0] = std::max(hi[0], p[pr.across]);
    lo[1] = std::min(lo[1], p[pr.up]);
    hi[1] = std::max(hi[1], p[pr.up]);
  }
  const int n = 2000;
  const double cell = std::max(hi[0] - lo[0], hi[1] - lo[1]) / n;
  const int nx = int((hi[0] - lo[0]) / cell) + 2, ny = int((hi[1] - lo[1]) / cell) + 2;
  std::vector<char> covered(std::size_t(nx) * ny, 0);
  auto fill = [&](const std::array<double, 3>& a, const std::array<double, 3>& b,
                  const std::array<double, 3>& c) {
    const double ax = a[pr.across], ay = a[pr.up], bx = b[pr.across], by = b[pr.up];
    const double cx = c[pr.across], cy = c[pr.up];
    const double area2 = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    if (area2 == 0) return;
    const int i0 = std::max(0, int((std::min({ax, bx, cx}) - lo[0]) / cell) - 1);
    const int i1 = std::min(nx - 1, int((std::max({ax, bx, cx}) - lo[0]) / cell) + 1);
    const int j0 = std::max(0, int((std::min({ay, by, cy}) - lo[1]) / cell) - 1);
    const int j1 = std::min(ny - 1, int((std::max({ay, by, cy}) - lo[1]) / cell) + 1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const double px = lo[0] + (i + 0.5) * cell, py = lo[1] + (j + 0.5) * cell;
        const double w0 = (bx - px) * (cy - py) - (cx - px) * (by - py);
        const double w1 = (cx - px) * (ay - py) - (ax - px) * (cy - py);
        const double w2 = (ax - px) * (by - py) - (bx - px) * (ay - py);
        const bool inside =
            area2 > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0) : (w0 <= 0 && w1 <= 0 && w2 <= 0);
        if (inside) covered[std::size_t(j) * nx + i] = 1;
      }
    }
  };
  for (const auto& f : m.f) {
    for (std::size_t k = 1; k + 1 < f.size(); ++k) fill(m.v[f[0]], m.v[f[k]], m.v[f[k + 1]]);
  }
  return std::count(covered.begin(), covered.end(), 1) * cell * cell;
}

// Where the mesh lands in the picture: hull pixels' bounding columns and rows give the scale
// (the mesh's extent across over the columns it spans) and the offset.
struct PixelMap {
  double pixel = 0;          // metres per pixel
  double left = 0, top = 0;  // model coordinates at the left edge of the first hull column and
                             // the top edge of the first hull row
  int col0 = 0, row0 = 0;
  std::pair<int, int> to_pixel(double a, double u) const {
    return {col0 + int(std::floor((a - left) / pixel)), row0 + int(std::floor((top - u) / pixel))};
  }
};

PixelMap map_pixels(const Picture& pic, std::uint32_t rows, const ObjMesh& m, Projection pr) {
  int c0 = int(pic.width), c1 = -1, r0 = int(rows);
  for (int y = 0; y < int(rows); ++y) {
    for (int x = 0; x < int(pic.width); ++x) {
      if (pic.background(x, y)) continue;
      c0 = std::min(c0, x);
      c1 = std::max(c1, x);
      r0 = std::min(r0, y);
    }
  }
  double lo = 1e300, hi = -1e300, top = -1e300;
  for (const auto& p : m.v) {
    lo = std::min(lo, p[pr.across]);
    hi = std::max(hi, p[pr.across]);
    top = std::max(top, p[pr.up]);
  }
  PixelMap map;
  map.pixel = (hi - lo) / (c1 - c0 + 1);
  map.left = lo;
  map.top = top;
  map.col0 = c0;
  map.row0 = r0;
  return map;
}

// Colour without brightness: shading and edge lines scale a colour, this keeps its hue.
std::array<double, 3> chroma(const std::array<int, 3>& c) {
  const double s = std::max(1, c[0] + c[1] + c[2]);
  return {c[0] / s, c[1] / s, c[2] / s};
}
double chroma_distance(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  const auto p = chroma(a), q = chroma(b);
  return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

std::array<double, 3> centroid(const ObjMesh& m, std::size_t f) {
  std::array<double, 3> c{0, 0, 0};
  for (int v : m.f[f])
    for (int k = 0; k < 3; ++k) c[k] += m.v[v][k] / m.f[f].size();
  return c;
}

// A Wigley hull of two patches, meshed by the structured mesher into OBJ (patch groups kept).
class RenderCli : public ::testing::Test {
 protected:
  // A failed assertion in SetUpTestSuite reports the suite's tests as skipped, which ctest does
  // not count as failures; so the suite set-up only records what went wrong and SetUp() fails.
  static void SetUpTestSuite() {
    // ctest runs each test in its own process, two at a time: one folder per process.
    dir_ = new fs::path(test::scratch_dir("cli_render_" + std::to_string(::getpid())));
    setup_error_ = new std::string;
    const auto g = run_hullmesh(
        "-q generate wigley --patches 2 --length 100 --beam 10 --draft 6.25 "
        "--depth 8 -o '" +
        (*dir_ / "w.igs").string() + "'");
    const auto s = g.exit_code != 0
                       ? g
                       : run_hullmesh("-q structured '" + (*dir_ / "w.igs").string() + "' -o '" +
                                      obj().string() + "' --panels 300 --draft 6.25");
    if (s.exit_code != 0) *setup_error_ = "making the test mesh failed:\n" + s.out;
  }
  static void TearDownTestSuite() {
    delete dir_;
    delete setup_error_;
  }
  void SetUp() override { ASSERT_TRUE(setup_error_->empty()) << *setup_error_; }
  static fs::path obj() { return *dir_ / "w.obj"; }

  // Renders the OBJ and reads the picture back; rows of the picture proper are above the legend.
  static Picture render(const std::string& name, const std::string& args) {
    const fs::path png = *dir_ / name;
    const auto r =
        run_hullmesh("-q render '" + obj().string() + "' -o '" + png.string() + "' " + args);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    return read_png(png);
  }
  static fs::path* dir_;
  static std::string* setup_error_;
};
fs::path* RenderCli::dir_ = nullptr;
std::string* RenderCli::setup_error_ = nullptr;

void expect_coverage(const Picture& pic, const ObjMesh& m, Projection pr) {
  ASSERT_GT(pic.width, 0u);
  const PixelMap map = map_pixels(pic, pic.height, m, pr);
  std::size_t hull = 0;
  for (int y = 0; y < int(pic.height); ++y)
    for (int x = 0; x < int(pic.width); ++x) hull += !pic.background(x, y);
  const double area = projected_area(m, pr);
  EXPECT_NEAR(hull * map.pixel * map.pixel, area, 0.03 * area)
      << hull << " pixels of " << map.pixel << " m";
}

TEST_F(RenderCli, ProfileAndPlanCoverTheProjectedArea) {
  const ObjMesh m = read_obj(obj());
  ASSERT_GT(m.f.size(), 200u);
  const Picture profile = render("profile.png", "--view profile --width 800");
  EXPECT_EQ(profile.width, 800u);
  expect_coverage(profile, m, {0, 2});
  const Picture plan = render("plan.png", "--view plan --width 800");
  expect_coverage(plan, m, {0, 1});
  // The other views draw something, too.
  for (const char* v : {"bodyplan", "iso"}) {
    const Picture p = render(std::string(v) + ".png", std::string("--width 300 --view ") + v);
    ASSERT_EQ(p.width, 300u) << v;
    std::size_t hull = 0;
    for (int y = 0; y < int(p.height); ++y)
      for (int x = 0; x < int(p.width); ++x) hull += !p.background(x, y);
    EXPECT_GT(hull, p.width * p.height / 50) << v;
  }
}

TEST_F(RenderCli, PatchColoursSeparateThePatches) {
  const ObjMesh m = read_obj(obj());
  const Picture plain = render("plain.png", "--width 800");
  const Picture pic = render("patch.png", "--width 800 --color patch");
  ASSERT_GT(pic.height, plain.height);  // the legend
  const PixelMap map = map_pixels(pic, plain.height, m, {0, 2});
  std::map<int, std::vector<std::array<int, 3>>> samples;
  for (std::size_t f = 0; f < m.f.size(); ++f) {
    const auto c = centroid(m, f);
    const auto [x, y] = map.to_pixel(c[0], c[2]);
    if (x < 0 || y < 0 || x >= int(pic.width) || y >= int(plain.height)) continue;
    const auto rgb = pic.at(x, y);
    if (rgb[0] + rgb[1] + rgb[2] < 150 || pic.background(x, y)) continue;  // an edge line
    samples[m.patch[f]].push_back(rgb);
  }
  ASSERT_EQ(samples.size(), 2u);
  // Each patch's faces share one hue; the two hues differ.
  std::array<int, 3> typical[2];
  int k = 0;
  for (auto& [patch, list] : samples) {
    ASSERT_GT(list.size(), 20u) << patch;
    typical[k] = list[list.size() / 2];
    std::size_t near = 0;
    for (const auto& c : list) near += chroma_distance(c, typical[k]) < 0.03;
    EXPECT_GT(near, 0.9 * list.size()) << patch;
    ++k;
  }
  EXPECT_GT(chroma_distance(typical[0], typical[1]), 0.1);
}

TEST_F(RenderCli, SideRatioColoursFollowTheField) {
  const ObjMesh m = read_obj(obj());
  // The measure, computed here: longest over shortest side of each panel.
  std::vector<double> ratio(m.f.size());
  for (std::size_t f = 0; f < m.f.size(); ++f) {
    double lo = 1e300, hi = 0;
    for (std::size_t k = 0; k < m.f[f].size(); ++k) {
      const auto& a = m.v[m.f[f][k]];
      const auto& b = m.v[m.f[f][(k + 1) % m.f[f].size()]];
      const double l = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
    ratio[f] = hi / lo;
  }
  const double rmin = *std::min_element(ratio.begin(), ratio.end());
  const double rmax = *std::max_element(ratio.begin(), ratio.end());
  ASSERT_GT(rmax - rmin, 0.5);

  const Picture plain = render("plain_sr.png", "--width 800");
  const Picture pic = render("side_ratio.png", "--width 800 --color side_ratio");
  // The legend's colour bar: the longest run of one legend row with no white, grey or text.
  int bar_row = -1, bar_x0 = 0, bar_x1 = -1;
  for (int y = int(plain.height); y < int(pic.height); ++y) {
    int run = 0;
    for (int x = 0; x < int(pic.width); ++x) {
      const auto c = pic.at(x, y);
      const bool coloured = !pic.background(x, y) && !(c[0] == c[1] && c[1] == c[2]);
      run = coloured ? run + 1 : 0;
      if (run > bar_x1 - bar_x0 + 1) {
        bar_row = y;
        bar_x1 = x;
        bar_x0 = x - run + 1;
      }
    }
  }
  ASSERT_GE(bar_row, 0);
  const int bar_w = bar_x1 - bar_x0 + 1;
  ASSERT_GT(bar_w, 200);
  // For each panel seen at its centroid, the bar position of the nearest hue should be where
  // its value sits in [rmin, rmax].
  const PixelMap map = map_pixels(pic, plain.height, m, {0, 2});
  std::size_t checked = 0, agree = 0;
  for (std::size_t f = 0; f < m.f.size(); ++f) {
    const auto c = centroid(m, f);
    const auto [x, y] = map.to_pixel(c[0], c[2]);
    if (x < 0 || y < 0 || x >= int(pic.width) || y >= int(plain.height)) continue;
    const auto rgb = pic.at(x, y);
    if (rgb[0] + rgb[1] + rgb[2] < 150 || pic.background(x, y)) continue;
    int best = 0;
    double best_d = 1e300;
    for (int k = 0; k < bar_w; ++k) {
      const double d = chroma_distance(rgb, pic.at(bar_x0 + k, bar_row));
      if (d < best_d) {
        best_d = d;
        best = k;
      }
    }
    const double t_seen = (best + 0.5) / bar_w;
    const double t_value = (ratio[f] - rmin) / (rmax - rmin);
    ++checked;
    agree += std::abs(t_seen - t_value) < 0.12;
  }
  ASSERT_GT(checked, 100u);
  EXPECT_GT(agree, 0.85 * checked) << agree << " of " << checked;
}

TEST_F(RenderCli, SameBytesWithOneAndTwoThreads) {
  const fs::path a = *dir_ / "t1.png", b = *dir_ / "t2.png";
  for (const auto& [threads, path] : {std::pair{1, a}, std::pair{2, b}}) {
    const auto r =
        run_hullmesh("-q --threads " + std::to_string(threads) + " render '" + obj().string() +
                     "' -o '" + path.string() + "' --view iso --width 500 --color features");
    ASSERT_EQ(r.exit_code, 0) << r.out;
  }
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_FALSE(bytes(a).empty());
  EXPECT_EQ(bytes(a), bytes(b));
}

TEST_F(RenderCli, BadNamesAndMissingDataAreUsageErrors) {
  const std::string out = " -o '" + (*dir_ / "bad.png").string() + "'";
  const std::string in = " '" + obj().string() + "'";
  auto r = run_hullmesh("render" + in + out + " --view side");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("bodyplan"), std::string::npos) << r.out;
  r = run_hullmesh("render" + in + out + " --color rainbow");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("side_ratio"), std::string::npos) << r.out;
  r = run_hullmesh("render" + in + out + " --color block");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("w.obj"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("block"), std::string::npos) << r.out;
  // A GDF file has no patch groups.
  const fs::path gdf = *dir_ / "w.gdf";
  ASSERT_EQ(run_hullmesh("-q convert" + in + " '" + gdf.string() + "'").exit_code, 0);
  r = run_hullmesh("render '" + gdf.string() + "'" + out + " --color patch");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("w.gdf"), std::string::npos) << r.out;
  // A missing file is an I/O error; nothing is written.
  r = run_hullmesh("render '" + (*dir_ / "none.obj").string() + "'" + out);
  EXPECT_EQ(r.exit_code, 6) << r.out;
  EXPECT_FALSE(fs::exists(*dir_ / "bad.png"));
}

}  // namespace
}  // namespace hm
