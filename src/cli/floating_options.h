// The floating position options shared by the meshers: --draft, --waterline-z, --baseline-z,
// --trim, --heel, --pivot-x. They place the hull before it is meshed, so that the waterplane cuts
// it as a border (panels end on the waterline) instead of clipping a finished mesh.
//
// Output frame when any is given: the floating frame with the free surface at z = 0 (the frame
// WAMIT, NEMOH, HAMS and Hydrostar expect): the file's x and y, rotated by heel and trim about the
// pivot, and shifted in z.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <span>
#include <string>

#include "core/bbox.h"
#include "nurbs/patch.h"
#include "quality/hydrostatics.h"

namespace hm::cli {

struct FloatingArgs {
  std::optional<double> draft;        // m above the baseline
  std::optional<double> waterline_z;  // m, the waterplane in the file's frame
  std::optional<double> baseline_z;   // m; default: the lowest point of the hull
  std::optional<double> pivot_x;      // m; default: the middle of the hull's length
  double trim_deg = 0;                // bow down positive
  double heel_deg = 0;                // starboard down positive
  // "TA,TF": the drafts at the aft and forward perpendiculars, m above the baseline (instead of
  // --draft, --trim and --pivot-x); "XA,XF": where the perpendiculars are (default: the hull's
  // aft and forward ends).
  std::string drafts, perpendiculars;
  // m: also mesh the hull above the waterplane, up to this height above it (0: the wetted part
  // only). The waterline stays a line of panel edges.
  double above_waterline = 0;
  bool given() const {
    return draft || waterline_z || trim_deg != 0 || heel_deg != 0 || !drafts.empty();
  }
};

void add_floating_options(CLI::App* cmd, FloatingArgs& args);

// UsageError naming `option` when it is asked for (wanted) without a waterplane: checked before
// any meshing.
void require_waterplane(const std::string& option, bool wanted, const FloatingArgs& args);

struct Floating {
  FloatingTransform transform;  // file frame -> floating frame (free surface z = 0)
  double draft = 0, baseline_z = 0, pivot_x = 0, trim_deg = 0, heel_deg = 0;
  // The surface above the waterplane is kept up to z = above_waterline (floating frame, m); 0:
  // the wetted part only.
  double above_waterline = 0;
  // The hull is cut at z = above_waterline and split at the waterplane. It is cut even when the
  // height looks above the top (the placement's sample is coarse; a cut with nothing above it
  // keeps every face).
  bool meshes_above() const { return above_waterline > 0; }
};

// The placement for `args` of a hull whose surfaces span `box` (file frame, metres). Throws
// UsageError when the waterplane would miss the placed hull: a draft at or above its highest point
// (nothing left dry, no waterline) or a position that lifts it wholly out of the water, and for
// a negative --above-waterline.
Floating resolve_floating(const FloatingArgs& args, std::span<const Patch> patches,
                          const BBox3d& box);

}  // namespace hm::cli
