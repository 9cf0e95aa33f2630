#include "io/render_view.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>

#include "core/error.h"
#include "io/render_legend.h"
#include "io/write_png.h"
#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;

double luminance(Rgb8 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Reads a PNG back with libpng (independent of write_png): width, height, RGB bytes.
bool read_png(const fs::path& path, RgbImage& out) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return false;
  image.format = PNG_FORMAT_RGB;
  out.width = image.width;
  out.height = image.height;
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  return png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr) != 0;
}

TEST(RenderColours, SequentialMapGetsLighterAlongItsLength) {
  double last = -1;
  for (int k = 0; k <= 64; ++k) {
    const double l = luminance(sequential_colour(k / 64.0));
    EXPECT_GT(l, last) << k;
    last = l;
  }
  EXPECT_LT(luminance(sequential_colour(0)), 40);
  EXPECT_GT(luminance(sequential_colour(1)), 200);
  EXPECT_EQ(sequential_colour(-3), sequential_colour(0));  // clamped
  EXPECT_EQ(sequential_colour(7), sequential_colour(1));
  EXPECT_EQ(sequential_colour(std::nan("")), sequential_colour(0));
}

TEST(RenderColours, ScalarFacesMapTheirRangeAndSkipValuelessFaces) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> v = {2, 4, 3, std::nan(""), 1e30, -inf};
  const ScalarRange r = value_range(v);
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.lo, 2);
  EXPECT_EQ(r.hi, 4);
  const std::vector<Rgb8> c = scalar_face_colours(v, r);
  ASSERT_EQ(c.size(), v.size());
  EXPECT_EQ(c[0], sequential_colour(0));
  EXPECT_EQ(c[1], sequential_colour(1));
  EXPECT_EQ(c[2], sequential_colour(0.5));
  EXPECT_EQ(c[3], kNoValue);
  EXPECT_EQ(c[4], kNoValue);
  EXPECT_EQ(c[5], kNoValue);
  EXPECT_FALSE(value_range(std::vector<double>{std::nan("")}).valid);
  // A constant field sits in the middle of the map.
  EXPECT_EQ(scalar_face_colours(std::vector<double>{5.0}, value_range(std::vector<double>{5.0}))[0],
            sequential_colour(0.5));
}

TEST(RenderColours, CategoriesDifferAndBlocklessFacesAreGrey) {
  std::set<std::tuple<int, int, int>> seen;
  for (Index id = 0; id < 24; ++id) {
    const Rgb8 c = category_colour(id);
    EXPECT_TRUE(seen.insert({c.r, c.g, c.b}).second) << id;
    EXPECT_FALSE(c == kBackground);
  }
  // Consecutive ids differ strongly (at least 60 in some channel).
  for (Index id = 0; id < 23; ++id) {
    const Rgb8 a = category_colour(id), b = category_colour(id + 1);
    EXPECT_GE(std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)}), 60) << id;
  }
  const std::vector<Index> ids = {3, kInvalid};
  const std::vector<Rgb8> c = category_face_colours(ids);
  EXPECT_EQ(c[0], category_colour(3));
  EXPECT_EQ(c[1], kNoValue);
}

// Two triangles sharing the edge 0-1 (on the x axis), folded by `fold_deg`.
SurfaceMesh folded_pair(double fold_deg) {
  const double a = fold_deg * 3.14159265358979323846 / 180;
  SurfaceMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -std::cos(a), std::sin(a)}};
  m.faces = {{0, 1, 2, kInvalid}, {1, 0, 3, kInvalid}};
  m.face_patch = {0, 0};
  return m;
}

TEST(RenderEdges, KnucklesFollowTheDihedralAngleAndBoundariesHaveOneFace) {
  for (double fold : {0.0, 30.0, 60.0, 90.0}) {
    const auto k = classify_face_edges(folded_pair(fold), 40);
    ASSERT_EQ(k.size(), 2u);
    const EdgeKind shared = fold > 40 ? EdgeKind::kKnuckle : EdgeKind::kPlain;
    EXPECT_EQ(k[0][0], shared) << fold;  // corner 0 of face 0 owns 0 -> 1
    EXPECT_EQ(k[1][0], shared) << fold;  // corner 0 of face 1 owns 1 -> 0
    for (int c : {1, 2}) {
      EXPECT_EQ(k[0][c], EdgeKind::kBoundary);
      EXPECT_EQ(k[1][c], EdgeKind::kBoundary);
    }
    EXPECT_EQ(k[0][3], EdgeKind::kPlain);
  }
}

// A unit square (one quad, z = 0) seen from below by a hand-made 20 x 20 pixel camera whose
// pixels are 0.05 m, square exactly filling the picture.
struct SquareScene {
  SurfaceMesh mesh;
  std::vector<Index> face;
  std::vector<Vec3d> point;
  std::vector<Vec3d> dir;
  PixelHits hits;
  SquareScene(bool hole) {
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    mesh.faces = {{0, 1, 2, 3}};
    mesh.face_patch = {0};
    for (int j = 0; j < 20; ++j) {
      for (int i = 0; i < 20; ++i) {
        const bool miss = hole && i == 10 && j == 10;
        face.push_back(miss ? kInvalid : 0);
        point.push_back(miss ? Vec3d{} : Vec3d{(i + 0.5) * 0.05, 1 - (j + 0.5) * 0.05, 0});
      }
    }
    dir.assign(20, Vec3d{0, 0, 1});
    hits = {20, 20, face, point, dir, 0.05, -1};
  }
};

TEST(RenderShade, FacesAreLitEdgesDarkAndMissesBackground) {
  const SquareScene s(true);
  const std::vector<Rgb8> colour = {Rgb8{200, 100, 50}};
  const RgbImage img = shade_view(s.mesh, s.hits, colour, {});
  ASSERT_EQ(img.width, 20u);
  ASSERT_EQ(img.height, 20u);
  EXPECT_EQ(img.at(10, 10), kBackground);
  // Inside: the colour times the light, never brighter than the colour, same hue.
  const Rgb8 in = img.at(5, 5);
  EXPECT_LE(in.r, 200);
  EXPECT_GT(in.r, 100);
  EXPECT_NEAR(double(in.g) / in.r, 0.5, 0.02);
  // Pixel centres 0.5 pixel from the square's border (under the 0.7 pixel limit) are edges.
  const Rgb8 edge = img.at(0, 5);
  EXPECT_LT(luminance(edge), 0.5 * luminance(in));
  EXPECT_EQ(img.at(5, 19), edge);
  // One pixel further in they are not.
  EXPECT_EQ(img.at(1, 5), in);
}

TEST(RenderShade, FeatureEdgesTakeTheirColours) {
  const SquareScene s(false);
  const std::vector<Rgb8> colour = {kPlainPanel};
  const std::vector<std::array<EdgeKind, 4>> kinds = {
      {EdgeKind::kBoundary, EdgeKind::kPlain, EdgeKind::kKnuckle, EdgeKind::kPlain}};
  const RgbImage img = shade_view(s.mesh, s.hits, colour, kinds);
  // Edge 0 -> 1 is y = 0 (the bottom row), edge 2 -> 3 is y = 1 (the top row).
  EXPECT_EQ(img.at(10, 19), kBoundaryLine);
  EXPECT_EQ(img.at(10, 0), kKnuckleLine);
  EXPECT_EQ(img.at(10, 1), kKnuckleLine);  // 1.5 pixels away: under the 1.6 pixel feature width
  EXPECT_NE(img.at(10, 2), kKnuckleLine);
  EXPECT_NE(img.at(0, 10), kKnuckleLine);  // a plain edge stays dark grey
  EXPECT_THROW(shade_view(s.mesh, s.hits, std::vector<Rgb8>{}, {}), InternalError);
}

TEST(RenderLegend, ScalarBarShowsTheMapLeftToRight) {
  RgbImage img;
  img.width = 600;
  img.height = 10;
  img.rgb.assign(600 * 10 * 3, 255);
  append_scalar_legend(img, "side_ratio", ScalarRange{1, 3, true});
  const int s = legend_scale(600);
  ASSERT_EQ(img.height, 10u + 26u * s);
  const int bar_y = 10 + 3 * s + 7 * s + s;  // a row inside the bar
  const int bar_w = std::min(600 - 8 * s, 300 * s);
  for (int k : {0, bar_w / 3, bar_w - 1}) {
    EXPECT_EQ(img.at(4 * s + k, bar_y), sequential_colour((k + 0.5) / bar_w)) << k;
  }
  // Some text was drawn (dark pixels) under the bar, where the numbers go.
  int dark = 0;
  for (std::uint32_t y = bar_y + 6 * s; y < img.height; ++y)
    for (std::uint32_t x = 0; x < img.width; ++x) dark += luminance(img.at(x, y)) < 80;
  EXPECT_GT(dark, 20);
}

TEST(RenderLegend, FontDrawsDigitsAndSkipsUnknownCharacters) {
  RgbImage img;
  img.width = 40;
  img.height = 10;
  img.rgb.assign(40 * 10 * 3, 255);
  draw_text(img, 0, 0, "1", 2, Rgb8{0, 0, 0});
  // '1' is .#. / ##. / .#. / .#. / ### in 2 x 2 pixel cells.
  EXPECT_EQ(img.at(2, 0), (Rgb8{0, 0, 0}));
  EXPECT_EQ(img.at(0, 0), kBackground);
  EXPECT_EQ(img.at(0, 2), (Rgb8{0, 0, 0}));
  EXPECT_EQ(img.at(4, 8), (Rgb8{0, 0, 0}));
  EXPECT_EQ(text_width("12", 2), 14);
  draw_text(img, 20, 0, "#", 2, Rgb8{0, 0, 0});  // no glyph: nothing drawn
  for (std::uint32_t y = 0; y < 10; ++y)
    for (std::uint32_t x = 20; x < 26; ++x) EXPECT_EQ(img.at(x, y), kBackground);
  EXPECT_EQ(legend_number(0.000123456), "0.000123");
  EXPECT_EQ(legend_number(1234567), "1.23e+06");
}

TEST(WritePng, RoundTripKeepsSizeAndPixels) {
  const fs::path dir = test::scratch_dir("write_png");
  RgbImage img;
  img.width = 7;
  img.height = 5;
  img.rgb.resize(7 * 5 * 3);
  for (std::uint32_t y = 0; y < 5; ++y)
    for (std::uint32_t x = 0; x < 7; ++x)
      img.set(x, y, Rgb8{std::uint8_t(30 * x), std::uint8_t(50 * y), std::uint8_t(x * y)});
  const fs::path file = dir / "pic.png";
  write_png(file.string(), img.width, img.height, img.rgb);
  RgbImage back;
  ASSERT_TRUE(read_png(file, back));
  EXPECT_EQ(back.width, 7u);
  EXPECT_EQ(back.height, 5u);
  EXPECT_EQ(back.rgb, img.rgb);
  // The same pixels give the same bytes.
  EXPECT_EQ(encode_png(7, 5, img.rgb), encode_png(7, 5, img.rgb));
}

TEST(WritePng, FailuresLeaveNoFile) {
  const fs::path dir = test::scratch_dir("write_png_fail");
  const std::vector<std::uint8_t> rgb(4 * 4 * 3, 9);
  EXPECT_THROW(write_png((dir / "missing" / "pic.png").string(), 4, 4, rgb), IoError);
  EXPECT_THROW(write_png((dir / "short.png").string(), 5, 4, rgb), IoError);
  EXPECT_FALSE(fs::exists(dir / "short.png"));
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace hm
