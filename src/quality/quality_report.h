// The quality report of a panel mesh: the rules panel codes apply, topology, wave resolution and
// the worst panels. Angles in degrees, lengths in metres, in the mesh frame (z up).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/surface_mesh.h"

namespace hm {

// Limits of the rules and the share of panels that must meet each (the paper's rules for panel
// codes, with the bounds of issue 6).
struct QualityRules {
  double max_side_ratio = 4;              // quads: longest / shortest side, strictly below
  double max_area_ratio = 2;              // neighbouring panels: larger / smaller area, below
  double max_normal_angle_deg = 15;       // between neighbouring normals, away from knuckles
  double min_triangle_angle_deg = 30;     // triangles: smallest angle, at least
  double min_side_ratio_share = 0.98;     // of quads
  double min_area_ratio_share = 0.98;     // of panels with a neighbour
  double min_normal_angle_share = 0.95;   // of panels with a non-knuckle neighbour
  double min_triangle_angle_share = 0.0;  // of triangles (reported; gate off by default)
  double max_warp = 0.1;                  // quads: corner distance from mean plane / mean diagonal
  bool require_convex = true;
  bool require_no_zero_area = true;
  bool require_no_close_centres = true;
  bool require_consistent_orientation = true;
  bool require_normals_into_fluid = true;
  bool require_no_free_edges_below_waterline = true;
  bool require_manifold = true;
  bool require_no_crossing = true;  // no panel passes through another (when it was measured)
};

struct WaveOptions {
  std::optional<double> speed;   // U, m/s
  std::optional<double> froude;  // Fn; U = Fn sqrt(g L)
  std::optional<double> length;  // L for the Froude number, m (default: waterline length)
  double gravity = 9.80665;      // m/s^2
};

struct QualityOptions {
  QualityRules rules;
  // The waterplane z in the mesh frame; default: the highest point of the mesh (a mesh of the
  // wetted part ends on its waterline).
  std::optional<double> waterline_z;
  // The mesh is not cut at a waterplane: it ends at the hull's own upper edge (deck edge or sheer
  // line), which may fall well below the top of the mesh towards the ends. A run of boundary
  // edges off the centre plane that reaches the top of the mesh is that upper edge and counts as
  // above water; a run that does not (a hole, a gap beside the keel) stays a free edge.
  bool uncut = false;
  // The mesh is one side of the centre plane y = 0 (boundary edges on it are expected). Unset:
  // a half hull when every vertex lies on one side of y = 0 (within plane_tol).
  std::optional<bool> half_hull;
  // Knuckle edges (vertex pairs, either order) and/or a dihedral threshold: an edge whose
  // neighbouring normals differ by more than this is a knuckle. Knuckles are left out of the
  // normal-angle rule.
  std::vector<std::array<Index, 2>> knuckle_edges;
  double knuckle_angle_deg = 40;
  // A face is zero-area when area <= zero_area_rel * (longest side)^2.
  double zero_area_rel = 1e-10;
  // Two panel centres are "very close" when nearer than this fraction of the smaller panel's
  // size (sqrt of its area).
  double close_centre_fraction = kCloseCentreFraction;
  // Boundary classification tolerance, relative to the bounding-box diagonal.
  double plane_tol = 1e-6;
  WaveOptions waves;
  std::size_t worst_count = 10;
  // Pairs of panels that pass through each other and the first one's place (model frame, m), as
  // the caller measured them (query/find_self_intersections.h: this stage has no BVH). Unset:
  // not measured, and the rule is not applied.
  std::optional<std::size_t> crossing_pairs;
  Vec3d crossing_where;
};

enum class QualityRule : std::uint8_t {
  kFlipped,  // orientation opposite to its neighbours
  kZeroArea,
  kNonManifold,  // touches an edge used by more than two faces
  kFreeEdgeBelowWaterline,
  kNonConvex,
  kCloseCentre,
  kSideRatio,
  kAreaRatio,
  kNormalAngle,
  kWarp,
  kTriangleAngle,
};
const char* to_string(QualityRule r);

// How the panels' smallest corner angles spread (every panel, triangles and quads alike): shares
// at or above 20, 30 and 40 degrees and three percentiles (degrees).
struct AngleDistribution {
  double share_20 = 1, share_30 = 1, share_40 = 1;
  double p05 = 0, p50 = 0, p95 = 0;
};

struct WorstPanel {
  Index face = kInvalid;
  Vec3d centroid;
  QualityRule rule = QualityRule::kSideRatio;
  double value = 0;  // the measure the rule tests (for flags: 1)
};

struct TopologyFacts {
  std::size_t edges = 0;
  std::size_t boundary_edges = 0;
  std::size_t boundary_loops = 0;
  std::size_t centre_plane_edges = 0;  // boundary edges on y = 0
  std::size_t waterline_edges = 0;     // boundary edges on z = waterline_z
  std::size_t above_water_edges = 0;   // boundary edges above the waterline (deck, sheer);
                                       // with QualityOptions::uncut, the hull's upper edge
  std::size_t free_edges_below = 0;    // any other boundary edge: a hole in the wetted hull
  // Panels with corners on both sides of the waterplane: a mesh that goes on above the
  // waterline should still end its panels on it.
  std::size_t panels_across_waterline = 0;
  // Panels wholly at or above the waterplane with an edge on it (a mesh that goes on above).
  std::size_t panels_above_on_waterline = 0;
  std::size_t nonmanifold_edges = 0;
  std::size_t inconsistent_edges = 0;  // interior edges used twice in the same direction
  std::size_t flipped_faces = 0;       // minority orientation of their connected component
  std::size_t components = 0;
  bool watertight = false;              // no boundary and no non-manifold edge
  bool orientation_consistent = false;  // every interior edge used once in each direction
  // Volume enclosed by the panels below the waterline, closed by the centre plane and the
  // waterplane (divergence theorem, see quality/hydrostatics.h): positive when the normals point
  // out of the body into the fluid.
  double enclosed_volume = 0;
  bool normals_into_fluid = false;
  double waterline_z = 0;
  bool uncut = false;  // QualityOptions::uncut: no waterline, above_water_edges the upper edge
};

struct WaveFigures {
  bool requested = false;
  double speed = 0;           // U, m/s
  double froude = 0;          // Fn (from U and L)
  double length = 0;          // L used, m
  double wavelength = 0;      // lambda = 2 pi U^2 / g, m
  double panel_length_x = 0;  // median x-extent of the panels touching the waterline, m
  double panels_per_wavelength = 0;
  bool warn = false;  // fewer than 10 panels per wavelength
};

// Per-face arrays (one value per face), written as VTU cell data by face_fields().
struct FaceQuality {
  std::vector<double> area, min_angle_deg, max_angle_deg, equilateral, side_ratio, warp,
      warp_angle_deg, aspect_ratio;
  std::vector<double> neighbour_area_ratio;    // max over neighbours (1 when none)
  std::vector<double> neighbour_normal_angle;  // max over non-knuckle neighbours, degrees
  std::vector<double> convex, zero_area, is_quad, flipped, close_centre;  // 0 / 1
  std::vector<Vec3d> centroid, normal;
};

struct QualityReport {
  std::size_t faces = 0, vertices = 0, quads = 0, triangles = 0;
  // Shares of the panels meeting each rule (1 when no panel is concerned).
  double side_ratio_share = 1, area_ratio_share = 1, normal_angle_share = 1,
         triangle_angle_share = 1;
  // Of neighbour pairs (edges between two panels), the share whose area ratio is under the
  // limit: the per-pair measure some rules state, laxer than area_ratio_share's per-panel one
  // (a panel passes only when every neighbour does).
  double area_ratio_pair_share = 1;
  double max_side_ratio = 0, max_area_ratio = 0, max_normal_angle_deg = 0;
  double min_triangle_angle_deg = 0;
  AngleDistribution min_angle;
  double min_equilateral = 0, mean_equilateral = 0;  // over triangles
  double max_warp = 0, max_warp_angle_deg = 0, max_aspect_ratio = 0;
  std::size_t non_convex = 0, zero_area = 0, close_centre_pairs = 0, knuckle_edges = 0;
  std::optional<std::size_t> crossing_pairs;  // from QualityOptions
  Vec3d crossing_where;
  TopologyFacts topology;
  WaveFigures waves;
  std::vector<WorstPanel> worst;
  FaceQuality per_face;
  bool half_hull = false;

  // Whether the mesh meets every rule (shares recomputed from per_face under these limits).
  bool passes(const QualityRules& rules) const;
  // One line per failed rule, empty when the mesh passes.
  std::vector<std::string> failures(const QualityRules& rules) const;
};

// adjacency -> per-face metrics -> neighbours -> topology -> waves -> worst panels.
// Throws GeometryError when a face names a missing vertex.
QualityReport assess_quality(const SurfaceMesh& mesh, const QualityOptions& options);

std::string to_json(const QualityReport& report, const QualityRules& rules, int indent = 2);
// A fixed-width table, as `hullmesh quality` prints it.
std::string format_table(const QualityReport& report, const QualityRules& rules);
// The per-face arrays as VTU cell data; the spans point into report.per_face.
std::vector<FaceField> face_fields(const QualityReport& report);

}  // namespace hm
