// Parametric test hulls, written as exact B-spline patches, with known properties and optional
// injected defects. Ship frame: x forward (aft perpendicular at x = 0), y to port, z up with the
// keel (baseline) at z = 0; metres.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nurbs/patch.h"

namespace hm {

enum class HullKind {
  kWigley,      // y = B/2 (1 - (2x/L)^2)(1 - (z/T)^2): exact biquadratic, closed-form hydrostatics
  kRoundBilge,  // round bilge, bulbous bow, sonar dome and flat transom (a DTMB 5415-like
                // combatant)
  kChine,       // hard-chine planing hull: knuckles at chine and transom
};
bool parse_hull_kind(const std::string& name, HullKind& kind);
const char* to_string(HullKind k);

struct HullDefects {
  double gap = 0;                 // opening between neighbouring patches, metres (0 = none)
  double overlap = 0;             // fraction of a patch width by which patches overlap (0 = none)
  bool duplicate_points = false;  // repeated control rows (full-multiplicity knots)
  int flip_every = 0;             // reverse every n-th patch's orientation (0 = none)
  std::uint64_t seed = 1;         // for defects chosen at random
};

struct HullSpec {
  HullKind kind = HullKind::kWigley;
  double length = 100.0;   // L, m
  double beam = 10.0;      // B, m
  double depth = 8.0;      // D, m: keel to deck
  double draft = 6.25;     // T, m: design draft (Wigley: the depth of its formula)
  int patches = 1;         // 1 to 1000: total patches of the half (or full) hull
  bool full_hull = false;  // false: the port half (y >= 0) only
  HullDefects defects;
};

// Known properties of a generated hull at its design draft, computed from closed forms (Wigley)
// or by fine quadrature of the defining shape.
struct HullFacts {
  double displacement_volume = 0;  // m^3, whole hull (both sides) below z = draft
  double wetted_area = 0;          // m^2, whole hull below z = draft
  double surface_area = 0;         // m^2, of the patches as generated (half or full)
  // Knuckle polylines (chine, transom edge) in metres, on the exact surface.
  std::vector<std::vector<Vec3d>> knuckles;
};

struct GeneratedHull {
  std::vector<Patch> patches;
  HullFacts facts;
};

// Throws UsageError for out-of-range settings (patches outside 1..1000, non-positive sizes).
GeneratedHull generate_hull(const HullSpec& spec);

}  // namespace hm
