#include "cli/floating_options.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "cli/load_hull.h"
#include "core/error.h"

namespace hm::cli {

void add_floating_options(CLI::App* cmd, FloatingArgs& a) {
  auto* draft = cmd->add_option("--draft", a.draft,
                                "Draft above the baseline, m: cuts the hull at the waterplane and "
                                "meshes the wetted part (output frame: free surface at z = 0)");
  auto* wl = cmd->add_option("--waterline-z", a.waterline_z,
                             "The waterplane as z in the file's frame, m (instead of --draft)");
  draft->excludes(wl);
  cmd->add_option("--baseline-z", a.baseline_z,
                  "z of the baseline --draft is measured from, m (default: the hull's lowest "
                  "point)");
  auto* trim = cmd->add_option("--trim", a.trim_deg, "Trim angle, degrees, bow down positive")
                   ->check(CLI::Range(-45.0, 45.0));
  cmd->add_option("--heel", a.heel_deg, "Heel angle, degrees, starboard down positive")
      ->check(CLI::Range(-60.0, 60.0));
  auto* pivot = cmd->add_option(
      "--pivot-x", a.pivot_x, "x of the trim pivot, m (default: the middle of the hull's length)");
  cmd->add_option("--drafts", a.drafts,
                  "TA,TF: drafts at the aft and forward perpendiculars above the baseline, m "
                  "(instead of --draft and --trim)")
      ->excludes(draft)
      ->excludes(wl)
      ->excludes(trim)
      ->excludes(pivot);
  cmd->add_option("--above-waterline", a.above_waterline,
                  "Also mesh the hull above the waterplane, up to this height above it, m (the "
                  "waterline stays a line of panel edges; for codes that want the dry hull too)");
  cmd->add_option("--perpendiculars", a.perpendiculars,
                  "XA,XF: x of the aft and forward perpendiculars for --drafts, m (default: the "
                  "hull's aft and forward ends)");
}

void require_waterplane(const std::string& option, bool wanted, const FloatingArgs& args) {
  if (wanted && !args.given()) {
    throw UsageError(
        option + " needs a waterplane: give --draft, --waterline-z, --drafts, --trim or --heel");
  }
}

namespace {

// --drafts TA,TF as a draft at the middle of the perpendiculars and the trim between them: the
// waterplane through both draft marks, measured square to the baseline.
void drafts_at_perpendiculars(const FloatingArgs& a, const BBox3d& box, double& draft,
                              double& trim_deg, double& pivot_x) {
  const std::vector<double> t = parse_numbers(a.drafts, 2, "--drafts");
  double xa = box.lo.x, xf = box.hi.x;
  if (!a.perpendiculars.empty()) {
    const std::vector<double> x = parse_numbers(a.perpendiculars, 2, "--perpendiculars");
    xa = x[0];
    xf = x[1];
  }
  if (!(xf > xa)) {
    throw UsageError("--perpendiculars " + a.perpendiculars +
                     ": the forward perpendicular must lie ahead of the aft one (XF > XA)");
  }
  trim_deg = std::atan((t[1] - t[0]) / (xf - xa)) * 180 / std::numbers::pi;
  if (std::abs(trim_deg) > 45) {
    throw UsageError("--drafts " + a.drafts + ": a trim of more than 45 degrees");
  }
  pivot_x = 0.5 * (xa + xf);
  draft = 0.5 * (t[0] + t[1]);
}

}  // namespace

Floating resolve_floating(const FloatingArgs& a, std::span<const Patch> patches,
                          const BBox3d& box) {
  Floating f;
  f.baseline_z = a.baseline_z.value_or(box.lo.z);
  f.pivot_x = a.pivot_x.value_or(0.5 * (box.lo.x + box.hi.x));
  f.trim_deg = a.trim_deg;
  f.heel_deg = a.heel_deg;
  if (!(a.above_waterline >= 0) || !std::isfinite(a.above_waterline)) {
    throw UsageError("--above-waterline " + std::to_string(a.above_waterline) +
                     ": the height above the waterplane must be a finite number >= 0 (m)");
  }
  f.above_waterline = a.above_waterline;
  if (!a.drafts.empty()) {
    drafts_at_perpendiculars(a, box, f.draft, f.trim_deg, f.pivot_x);
  } else {
    // Without a draft or a waterline, the waterplane is the file's z = 0.
    const double waterline_z = a.waterline_z.value_or(a.draft ? f.baseline_z + *a.draft : 0.0);
    f.draft = waterline_z - f.baseline_z;
  }
  const Placement p = floating_placement(f.draft, f.trim_deg, f.heel_deg, f.baseline_z, f.pivot_x);
  f.transform = p.transform;
  f.transform.translation.z -= p.waterline_z;

  // Where the placed hull lies against the free surface z = 0, from a 17 x 17 sample of each
  // patch's untrimmed surface (enough to tell a waterplane that misses the hull).
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Patch& patch : patches) {
    const NurbsSurface& s = patch.surface;
    constexpr int kSamples = 16;
    for (int i = 0; i <= kSamples; ++i) {
      for (int j = 0; j <= kSamples; ++j) {
        const double u = s.u0 + (s.u1 - s.u0) * i / kSamples;
        const double v = s.v0 + (s.v1 - s.v0) * j / kSamples;
        const double z = f.transform(evaluate(s, u, v)).z;
        lo = std::min(lo, z);
        hi = std::max(hi, z);
      }
    }
  }
  char text[256];
  if (hi <= 0) {
    std::snprintf(text, sizeof text,
                  "the waterplane (draft %.4g m above the baseline z = %.4g m) lies at or above "
                  "the hull's highest point: nothing stays dry, so there is no waterline to mesh "
                  "to",
                  f.draft, f.baseline_z);
    throw UsageError(text);
  }
  if (lo >= 0) {
    std::snprintf(text, sizeof text,
                  "at draft %.4g m, trim %.4g deg and heel %.4g deg the hull lies wholly above the "
                  "waterplane: nothing is wetted",
                  f.draft, f.trim_deg, f.heel_deg);
    throw UsageError(text);
  }
  return f;
}

}  // namespace hm::cli
