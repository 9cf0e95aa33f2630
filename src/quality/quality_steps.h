// Internal to src/quality: the steps assess_quality runs, one file each.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/adjacency.h"
#include "quality/quality_report.h"

namespace hm {

// Settings resolved from QualityOptions and the mesh (defaults filled in).
struct ResolvedSettings {
  double waterline_z = 0;
  bool half_hull = false;
  double tol = 0;      // absolute plane tolerance, m
  bool uncut = false;  // QualityOptions::uncut
};

// quality_metrics.cpp: per-face metrics (kernel) into report.per_face and the summary figures.
void measure_faces(const SurfaceMesh& mesh, const QualityOptions& o, QualityReport& report);

// neighbour_metrics.cpp: one flag per edge of adj: a knuckle (input edge set or dihedral angle,
// measured with the orientation of inconsistent edges corrected).
std::vector<std::uint8_t> knuckle_mask(const EdgeAdjacency& adj, const FaceQuality& fq,
                                       const QualityOptions& o);
void measure_neighbours(const SurfaceMesh& mesh, const EdgeAdjacency& adj,
                        const std::vector<std::uint8_t>& knuckle, QualityReport& report);
// Share of the edges between two panels whose larger area is under `limit` times the smaller
// (1 when there is no such edge).
double area_ratio_pair_share(const EdgeAdjacency& adj, const FaceQuality& fq, double limit);

// topology_checks.cpp
void check_topology(const SurfaceMesh& mesh, const EdgeAdjacency& adj, const ResolvedSettings& s,
                    QualityReport& report, std::vector<std::uint8_t>& free_edge_face,
                    std::vector<std::uint8_t>& nonmanifold_face);
void find_close_centres(const QualityOptions& o, QualityReport& report);

// wave_resolution.cpp
WaveFigures wave_resolution(const SurfaceMesh& mesh, const WaveOptions& w,
                            const ResolvedSettings& s);

// Shares of panels meeting the ratio and angle rules under `rules`, from the per-face arrays.
struct RuleShares {
  double side_ratio = 1, area_ratio = 1, normal_angle = 1, triangle_angle = 1;
  double max_warp = 0;
};
RuleShares rule_shares(const FaceQuality& fq, const QualityRules& rules);
AngleDistribution angle_distribution(std::vector<double> min_angle_deg);

}  // namespace hm
