// Hydrostatics of a hull at a floating position, as a check of a panel mesh against its NURBS.
//
// Frame: the mesh (or patch) frame after the caller's rigid placement: x forward, y to port, z up,
// metres. The waterplane is z = waterline_z; the body is what lies below it. Sign convention:
// face and patch normals point OUT of the body, into the fluid; every signed quantity below
// (volume, waterplane area) is positive for that orientation and negative for inward normals.
//
// Exactness. All quantities are surface integrals over the wetted surface S_w only, chosen by the
// divergence theorem so that their integrands vanish on the two planes that close a half hull:
// the centre plane y = 0 (where n = (0, -1, 0) and the integrand has no y component) and the
// waterplane z = waterline_z (where the integrand carries a factor z - waterline_z, or is
// divergence-free with the waterplane term being the wanted quantity). So for a closed body
// (S_w + centre plane + waterplane) they are exact, and a half hull needs no closing panels.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/vec.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"

namespace hm {

// p' = rotation * p + translation (rotation row-major).
struct FloatingTransform {
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3d translation;

  Vec3d rotate(const Vec3d& p) const;
  Vec3d operator()(const Vec3d& p) const { return rotate(p) + translation; }
};

struct FloatingPosition {
  double waterline_z = 0;  // the waterplane in the (placed) frame, m
  // The geometry is one side of the centre plane y = 0: volumes, areas and waterplane moments are
  // doubled and the transverse centres (TCB, TCF) are zero.
  bool half_hull = false;
};

// The placement of a hull drawn in its own frame (baseline at z = baseline_z) floating at `draft`
// with trim and heel: rotate about the pivot (pivot_x, 0, baseline_z + draft), heel first (about
// x, positive lifts the port side: starboard down), then trim (about y, positive puts the bow,
// +x, down). The placed waterplane is z = baseline_z + draft, so the draft at the pivot is
// `draft`, and at x it is draft + (x - pivot_x) tan(trim) (for zero heel).
struct Placement {
  FloatingTransform transform;
  double waterline_z = 0;
};
Placement floating_placement(double draft, double trim_deg, double heel_deg, double baseline_z = 0,
                             double pivot_x = 0);
SurfaceMesh transformed(const SurfaceMesh& mesh, const FloatingTransform& t);
// Control points move, weights stay: a rational surface maps exactly under a rigid motion.
std::vector<Patch> transformed(std::span<const Patch> patches, const FloatingTransform& t);

struct Hydrostatics {
  double volume = 0;           // displaced volume, m^3
  double wetted_area = 0;      // m^2
  double waterplane_area = 0;  // m^2
  Vec3d buoyancy_centre;       // (LCB, TCB, VCB), m
  Vec2d flotation_centre;      // (LCF, TCF), m
  double i_transverse = 0;     // I_T: waterplane second moment about the x-parallel axis by CF, m^4
  double i_longitudinal = 0;   // I_L: about the y-parallel axis through CF, m^4
  double bm_transverse = 0;    // I_T / V, m
  double bm_longitudinal = 0;  // I_L / V, m
  // Mesh only: the waterline section, chained, each polyline closed (its first point repeated at
  // the end; for a half hull an open chain's closing segment lies on the centre plane).
  std::vector<std::vector<Vec3d>> waterline;
  std::size_t open_waterline_chains = 0;  // chains whose ends did not meet (before closing)
  // Mesh only: the waterplane figures came from the panels' fluxes, as a waterline chain broke
  // off away from the centre plane (an open transom), instead of from the waterline polygon.
  bool waterplane_from_fluxes = false;
  std::size_t lid_faces = 0;  // faces lying in the waterplane, left out
};

struct MeshHydrostaticsOptions {
  // A vertex within this distance of the waterplane (relative to the bounding-box diagonal) is
  // taken to lie on it, so panels that end on the waterline are not clipped into slivers.
  double on_plane_tol = 1e-9;
};

// Panels crossing the waterplane are clipped for the measurement (triangles 0-1-2 and 0-2-3 of a
// quad, as face_area splits it). Each integrand is a polynomial of degree <= 2 on a flat triangle
// and is integrated exactly (edge-midpoint rule), so the result is exact for the polyhedron the
// panels describe: for a smooth hull the error is the geometric one, O(h^2) in the panel size.
// Waterplane area and moments come from the waterline polygon(s): the wet panels' edges lying in
// the waterplane, chained, with Green's theorem; where a chain breaks off away from the centre
// plane (an open transom), from the panels' fluxes -int (1, x, y, x^2, y^2) n_z dS instead.
Hydrostatics hydrostatics_mesh(const SurfaceMesh& mesh, const FloatingPosition& position,
                               const MeshHydrostaticsOptions& options = {});

struct NurbsHydrostaticsOptions {
  // Adaptive acceptance: a cell is accepted when its estimate and the sum of its four children
  // agree to rel_tol of the patch's scale (area x size^k, k the integrand's length power) times the
  // cell's share of the domain.
  double rel_tol = 1e-12;
  int max_depth = 10;
  // Trim loops are sampled to this fraction of the parameter domain.
  double trim_tol = 1e-8;
};

// Adaptive Gauss-Legendre quadrature over each patch's knot-span cells. In a cell the integrand is
// cut at the waterplane along Gauss lines: on each line the roots of z(u, v) = waterline_z (and the
// trim-loop crossings) split it into wet intervals, each integrated by Gauss; cells whose estimate
// disagrees with their children's are split. Accuracy: for untrimmed polynomial patches whose
// waterline is a parameter line (the generated Wigley hull) the result is exact to rounding; for
// smooth untrimmed patches about rel_tol relative; for trimmed patches it is limited by the sampled
// trim polygon, about trim_tol relative. The waterplane quantities come from the exact section
// z = waterline_z implicitly: by the divergence theorem with a divergence-free field whose flux
// through the waterplane is the wanted moment (A_wp = -int_Sw n_z dS, int x dA = -int_Sw x n_z dS,
// ...), so they share that accuracy. Normals must point out of the body (Patch::reversed honoured).
Hydrostatics hydrostatics_nurbs(std::span<const Patch> patches, const FloatingPosition& position,
                                const NurbsHydrostaticsOptions& options = {});

}  // namespace hm
