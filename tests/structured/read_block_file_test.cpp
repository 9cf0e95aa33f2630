// The JSON block file: planes and boxes are read, and every fault names its key.
#include "structured/read_block_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace hm {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::string& text) {
  StructuredOptions o;
  try {
    read_block_file(write_temp("hm_blocks_bad.json", text), o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadBlockFile, ReadsPlanesBoxesAndSize) {
  StructuredOptions o;
  read_block_file(write_temp("hm_blocks_ok.json", R"({
    "size": [1.0, 0.5, 0.5],
    "planes": [{"name": "st 50", "x": 50}, {"z": 3}, {"point": [0, 0, 1], "normal": [0, 1, 1]}],
    "blocks": [{"name": "bow", "min": [80, -10, -10], "max": [100, 10, 10], "size": [0.5, 0.5, 0.5]}]
  })"),
                  o);
  EXPECT_EQ(o.size.x, 1.0);
  EXPECT_EQ(o.size.y, 0.5);
  ASSERT_EQ(o.planes.size(), 3u);
  EXPECT_EQ(o.planes[0].name, "st 50");
  EXPECT_EQ(o.planes[0].point.x, 50);
  EXPECT_EQ(o.planes[0].normal.x, 1);
  EXPECT_EQ(o.planes[1].point.z, 3);
  EXPECT_EQ(o.planes[1].normal.z, 1);
  EXPECT_EQ(o.planes[2].normal.y, 1);
  ASSERT_EQ(o.size_boxes.size(), 1u);
  EXPECT_EQ(o.size_boxes[0].name, "bow");
  EXPECT_EQ(o.size_boxes[0].lo.x, 80);
  EXPECT_EQ(o.size_boxes[0].size.x, 0.5);
}

TEST(ReadBlockFile, FaultsNameTheKey) {
  EXPECT_NE(error_of(R"({"plane": []})").find("plane: unknown key"), std::string::npos);
  EXPECT_NE(error_of(R"({"size": [1, -1, 1]})").find("size: every size must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"planes": [{"x": 1, "z": 2}]})").find("planes[0]: give exactly one"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"planes": [{"x": "a"}]})").find("planes[0].x: must be a number"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"planes": [{"point": [0,0,0], "normal": [0,0,0]}]})")
                .find("planes[0].normal: must not be zero"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"blocks": [{"min": [0,0,0]}]})").find("blocks[0].size: is required"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"blocks": [{"min": [1,0,0], "max": [0,1,1], "size": [1,1,1]}]})")
                .find("must not exceed"),
            std::string::npos);
  EXPECT_NE(error_of("{not json").find("not valid JSON"), std::string::npos);
}

}  // namespace
}  // namespace hm
