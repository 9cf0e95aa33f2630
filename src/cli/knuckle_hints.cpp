#include "cli/knuckle_hints.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cli/load_hull.h"
#include "core/error.h"

namespace hm::cli {
namespace {

// A polyline hint longer than this is refused before anything is allocated for it.
constexpr std::size_t kMaxHintPoints = 100000;

// "what@D": the distance after the last '@' (absent: 0, the library's 1e-3 L).
double split_distance(std::string& body, const std::string& option, const std::string& text) {
  const std::size_t at = body.rfind('@');
  if (at == std::string::npos) return 0;
  const double d = parse_numbers_in(body.substr(at + 1), 1, option + " " + text)[0];
  if (!(d > 0)) throw UsageError(option + " " + text + ": the distance after '@' must be > 0");
  body.resize(at);
  return d;
}

int parse_index(const std::string& item, const std::string& option, const std::string& text) {
  std::size_t used = 0;
  long long v = -1;
  try {
    v = std::stoll(item, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != item.size() || item.empty() || v < 0 || v > 2'000'000'000) {
    throw UsageError(option + " " + text + ": '" + item + "' is not a patch index or DE number");
  }
  return static_cast<int>(v);
}

KnuckleHintSpec parse_one(const std::string& text, const std::string& option) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) {
    throw UsageError(option + " " + text +
                     ": expected plane:X,Y,Z,NX,NY,NZ[@D], points:X,Y,Z;X,Y,Z;...[@D], "
                     "patches:A,B or de:A,B");
  }
  const std::string kind = text.substr(0, colon);
  std::string body = text.substr(colon + 1);
  KnuckleHintSpec spec;
  KnuckleHint& h = spec.hint;
  if (kind == "plane") {
    h.kind = KnuckleHint::Kind::kPlane;
    h.distance = split_distance(body, option, text);
    const std::vector<double> v = parse_numbers_in(body, 6, option + " " + text);
    h.plane_point = {v[0], v[1], v[2]};
    h.plane_normal = {v[3], v[4], v[5]};
    if (!(norm(h.plane_normal) > 0)) {
      throw UsageError(option + " " + text + ": the plane's normal is zero");
    }
  } else if (kind == "points") {
    h.kind = KnuckleHint::Kind::kPoints;
    h.distance = split_distance(body, option, text);
    const std::size_t n = 1 + static_cast<std::size_t>(std::count(body.begin(), body.end(), ';'));
    if (n < 2 || n > kMaxHintPoints) {
      throw UsageError(option + " " + text + ": a polyline needs 2 to " +
                       std::to_string(kMaxHintPoints) + " points, separated by ';'");
    }
    h.points.reserve(n);
    std::size_t from = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t to = std::min(body.find(';', from), body.size());
      const std::vector<double> v =
          parse_numbers_in(body.substr(from, to - from), 3, option + " " + text);
      h.points.push_back({v[0], v[1], v[2]});
      from = to + 1;
    }
  } else if (kind == "patches" || kind == "de") {
    h.kind = KnuckleHint::Kind::kPatchPair;
    const std::size_t comma = body.find(',');
    if (comma == std::string::npos || body.find(',', comma + 1) != std::string::npos) {
      throw UsageError(option + " " + text + ": expected two numbers A,B");
    }
    const int a = parse_index(body.substr(0, comma), option, text);
    const int b = parse_index(body.substr(comma + 1), option, text);
    if (a == b) throw UsageError(option + " " + text + ": the two patches must differ");
    if (kind == "de" && (a == 0 || b == 0)) {
      throw UsageError(option + " " + text + ": DE numbers start at 1");
    }
    if (kind == "de") {
      spec.de_a = a;
      spec.de_b = b;
    } else {
      h.patch_a = static_cast<PatchId>(a);
      h.patch_b = static_cast<PatchId>(b);
    }
  } else {
    throw UsageError(option + " " + text + ": unknown kind '" + kind +
                     "' (plane, points, patches or de)");
  }
  return spec;
}

std::vector<KnuckleHint> resolve(std::span<const KnuckleHintSpec> specs,
                                 std::span<const Patch> patches, const FloatingTransform* placed,
                                 const std::string& file) {
  std::vector<KnuckleHint> out;
  for (const KnuckleHintSpec& spec : specs) {
    KnuckleHint h = spec.hint;
    if (placed) {
      h.plane_point = (*placed)(h.plane_point);
      h.plane_normal = placed->rotate(h.plane_normal);
      for (Vec3d& p : h.points) p = (*placed)(p);
    }
    if (h.kind != KnuckleHint::Kind::kPatchPair) {
      out.push_back(std::move(h));
      continue;
    }
    if (spec.de_a == 0) {
      for (const PatchId p : {h.patch_a, h.patch_b}) {
        if (p >= patches.size()) {
          throw UsageError(file + ": knuckle hint patches:" + std::to_string(h.patch_a) + "," +
                           std::to_string(h.patch_b) + " names patch " + std::to_string(p) +
                           ", but the hull has patches 0 to " + std::to_string(patches.size() - 1));
        }
      }
      out.push_back(std::move(h));
      continue;
    }
    // Every patch of each DE number: a mirrored image keeps its original's.
    std::vector<PatchId> of_a, of_b;
    for (std::size_t p = 0; p < patches.size(); ++p) {
      if (patches[p].de == spec.de_a) of_a.push_back(static_cast<PatchId>(p));
      if (patches[p].de == spec.de_b) of_b.push_back(static_cast<PatchId>(p));
    }
    for (const auto& [de, found] : {std::pair{spec.de_a, &of_a}, {spec.de_b, &of_b}}) {
      if (found->empty()) {
        throw UsageError(file + ": knuckle hint de:" + std::to_string(spec.de_a) + "," +
                         std::to_string(spec.de_b) + ": no surface patch has DE " +
                         std::to_string(de) + " (hullmesh info -v lists them)");
      }
    }
    for (PatchId a : of_a) {
      for (PatchId b : of_b) {
        h.patch_a = a;
        h.patch_b = b;
        out.push_back(h);
      }
    }
  }
  return out;
}

}  // namespace

void add_knuckle_hint_options(CLI::App* cmd, KnuckleHintArgs& args) {
  // One spec per occurrence: the input file after the option is not one more spec.
  cmd->add_option("--add-knuckle", args.add,
                  "Make these edges knuckles: plane:X,Y,Z,NX,NY,NZ[@D], points:X,Y,Z;X,Y,Z;...[@D] "
                  "(m, file frame; D default 1e-3 L), patches:A,B (indices) or de:A,B (IGES DE "
                  "numbers); may repeat")
      ->allow_extra_args(false);
  cmd->add_option("--suppress-knuckle", args.suppress,
                  "Never make these edges knuckles (same forms as --add-knuckle; wins over it); "
                  "may repeat")
      ->allow_extra_args(false);
}

KnuckleHintSpecs parse_knuckle_hints(const KnuckleHintArgs& args) {
  KnuckleHintSpecs out;
  for (const std::string& s : args.add) out.add.push_back(parse_one(s, "--add-knuckle"));
  for (const std::string& s : args.suppress) {
    out.suppress.push_back(parse_one(s, "--suppress-knuckle"));
  }
  return out;
}

void apply_knuckle_hints(const KnuckleHintSpecs& specs, std::span<const Patch> patches,
                         const FloatingTransform* placed, const std::string& file,
                         FeatureOptions& features) {
  for (KnuckleHint& h : resolve(specs.add, patches, placed, file)) {
    features.add.push_back(std::move(h));
  }
  for (KnuckleHint& h : resolve(specs.suppress, patches, placed, file)) {
    features.suppress.push_back(std::move(h));
  }
}

}  // namespace hm::cli
