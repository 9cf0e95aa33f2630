// Reads the JSON block file. Every key is checked: unknown keys, wrong types and impossible
// values are errors that name the key, never silently ignored.
#include "structured/read_block_file.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/error.h"

namespace hm {
namespace {

using nlohmann::json;

// A block file is a few planes and boxes; a larger one is not a block file.
constexpr std::uintmax_t kMaxBytes = 1 << 20;
constexpr std::size_t kMaxEntries = 10'000;

struct Reader {
  std::string path;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(path + ": " + key + ": " + what);
  }

  void only_keys(const json& j, const std::string& where, const std::set<std::string>& allowed) {
    if (!j.is_object()) fail(where, "must be an object");
    for (const auto& [k, v] : j.items()) {
      if (!allowed.count(k)) {
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(where + "." + k, "unknown key (allowed: " + list + ")");
      }
    }
  }

  double number(const json& j, const std::string& key) {
    if (!j.is_number()) fail(key, "must be a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(key, "must be finite");
    return v;
  }

  Vec3d vec3(const json& j, const std::string& key) {
    if (!j.is_array() || j.size() != 3) fail(key, "must be an array of three numbers");
    return {number(j[0], key + "[0]"), number(j[1], key + "[1]"), number(j[2], key + "[2]")};
  }

  // The entry's "name", or its key when it has none.
  std::string name(const json& j, const std::string& key) {
    if (!j.contains("name")) return key;
    if (!j["name"].is_string()) fail(key + ".name", "must be a string");
    const std::string n = j["name"].get<std::string>();
    return n.empty() ? key : n;
  }

  Vec3d size3(const json& j, const std::string& key) {
    const Vec3d s = vec3(j, key);
    if (!(s.x > 0 && s.y > 0 && s.z > 0)) fail(key, "every size must be > 0 m");
    return s;
  }
};

}  // namespace

void read_block_file(const std::string& path, StructuredOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open the block file");
  in.seekg(0, std::ios::end);
  const std::streamoff bytes = in.tellg();
  if (bytes < 0 || static_cast<std::uintmax_t>(bytes) > kMaxBytes) {
    throw LimitError(path + ": a block file is at most 1 MiB");
  }
  in.seekg(0);
  std::stringstream text;
  text << in.rdbuf();
  json root;
  try {
    root = json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw InputError(path + ": not valid JSON (byte " + std::to_string(e.byte) + ")");
  }
  Reader r{path};
  r.only_keys(root, "(top level)", {"size", "planes", "blocks"});
  if (root.contains("size")) options.size = r.size3(root["size"], "size");
  if (root.contains("planes")) {
    const json& planes = root["planes"];
    if (!planes.is_array()) r.fail("planes", "must be an array");
    if (planes.size() > kMaxEntries) r.fail("planes", "at most 10000 planes");
    for (std::size_t i = 0; i < planes.size(); ++i) {
      const std::string key = "planes[" + std::to_string(i) + "]";
      const json& p = planes[i];
      r.only_keys(p, key, {"name", "x", "y", "z", "point", "normal"});
      BlockPlane bp;
      bp.name = r.name(p, key);
      int given = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const char* a = axis == 0 ? "x" : axis == 1 ? "y" : "z";
        if (!p.contains(a)) continue;
        ++given;
        const double v = r.number(p[a], key + "." + a);
        bp.point = {axis == 0 ? v : 0, axis == 1 ? v : 0, axis == 2 ? v : 0};
        bp.normal = {axis == 0 ? 1.0 : 0, axis == 1 ? 1.0 : 0, axis == 2 ? 1.0 : 0};
      }
      if (p.contains("point") || p.contains("normal")) {
        if (!p.contains("point") || !p.contains("normal")) {
          r.fail(key, "a general plane needs both \"point\" and \"normal\"");
        }
        ++given;
        bp.point = r.vec3(p["point"], key + ".point");
        bp.normal = r.vec3(p["normal"], key + ".normal");
        if (norm(bp.normal) < 1e-12) r.fail(key + ".normal", "must not be zero");
      }
      if (given != 1) {
        r.fail(key, "give exactly one of \"x\", \"y\", \"z\" or \"point\" with \"normal\"");
      }
      options.planes.push_back(bp);
    }
  }
  if (root.contains("blocks")) {
    const json& blocks = root["blocks"];
    if (!blocks.is_array()) r.fail("blocks", "must be an array");
    if (blocks.size() > kMaxEntries) r.fail("blocks", "at most 10000 blocks");
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const std::string key = "blocks[" + std::to_string(i) + "]";
      const json& b = blocks[i];
      r.only_keys(b, key, {"name", "min", "max", "size"});
      SizeBox box;
      box.name = r.name(b, key);
      if (!b.contains("size")) r.fail(key + ".size", "is required");
      box.size = r.size3(b["size"], key + ".size");
      const double inf = std::numeric_limits<double>::infinity();
      box.lo = b.contains("min") ? r.vec3(b["min"], key + ".min") : Vec3d{-inf, -inf, -inf};
      box.hi = b.contains("max") ? r.vec3(b["max"], key + ".max") : Vec3d{inf, inf, inf};
      if (box.lo.x > box.hi.x || box.lo.y > box.hi.y || box.lo.z > box.hi.z) {
        r.fail(key, "\"min\" must not exceed \"max\" on any axis");
      }
      options.size_boxes.push_back(box);
    }
  }
}

}  // namespace hm
