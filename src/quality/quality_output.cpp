// The quality report as JSON, as a fixed-width table, and as VTU cell data.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "quality/quality_report.h"

namespace hm {
namespace {

std::string line(const char* key, const std::string& value) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "  %-30s %s\n", key, value.c_str());
  return buf;
}

template <class... Args>
std::string f(const char* format, Args... args) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, args...);
  return buf;
}

std::string rule_row(const char* rule, double share, double need, const std::string& extreme) {
  return f("  %-30s %7.2f%%  (need %6.2f%%)  %s\n", rule, 100 * share, 100 * need, extreme.c_str());
}

}  // namespace

std::string to_json(const QualityReport& r, const QualityRules& rules, int indent) {
  using nlohmann::json;
  json j;
  j["faces"] = r.faces;
  j["vertices"] = r.vertices;
  j["quads"] = r.quads;
  j["triangles"] = r.triangles;
  j["half_hull"] = r.half_hull;
  j["rules"] = {
      {"side_ratio",
       {{"limit", rules.max_side_ratio}, {"share", r.side_ratio_share}, {"max", r.max_side_ratio}}},
      {"area_ratio",
       {{"limit", rules.max_area_ratio},
        {"share", r.area_ratio_share},
        {"pair_share", r.area_ratio_pair_share},
        {"max", r.max_area_ratio}}},
      {"normal_angle_deg",
       {{"limit", rules.max_normal_angle_deg},
        {"share", r.normal_angle_share},
        {"max", r.max_normal_angle_deg},
        {"knuckle_edges", r.knuckle_edges}}},
      {"triangle_min_angle_deg",
       {{"limit", rules.min_triangle_angle_deg},
        {"share", r.triangle_angle_share},
        {"min", r.min_triangle_angle_deg}}},
  };
  j["equilateral"] = {{"min", r.min_equilateral}, {"mean", r.mean_equilateral}};
  j["warp"] = {
      {"max", r.max_warp}, {"max_angle_deg", r.max_warp_angle_deg}, {"limit", rules.max_warp}};
  j["max_aspect_ratio"] = r.max_aspect_ratio;
  j["non_convex"] = r.non_convex;
  j["zero_area"] = r.zero_area;
  j["close_centre_pairs"] = r.close_centre_pairs;
  // null when not measured
  j["crossing_pairs"] = r.crossing_pairs ? json(*r.crossing_pairs) : json(nullptr);
  const TopologyFacts& t = r.topology;
  j["topology"] = {{"edges", t.edges},
                   {"boundary_edges", t.boundary_edges},
                   {"boundary_loops", t.boundary_loops},
                   {"centre_plane_edges", t.centre_plane_edges},
                   {"waterline_edges", t.waterline_edges},
                   {"above_water_edges", t.above_water_edges},
                   {"free_edges_below_waterline", t.free_edges_below},
                   {"panels_across_waterline", t.panels_across_waterline},
                   {"panels_above_on_waterline", t.panels_above_on_waterline},
                   {"nonmanifold_edges", t.nonmanifold_edges},
                   {"inconsistent_edges", t.inconsistent_edges},
                   {"flipped_faces", t.flipped_faces},
                   {"components", t.components},
                   {"watertight", t.watertight},
                   {"orientation_consistent", t.orientation_consistent},
                   {"enclosed_volume_m3", t.enclosed_volume},
                   {"normals_into_fluid", t.normals_into_fluid},
                   {"waterline_z", t.waterline_z},
                   {"uncut", t.uncut}};
  if (r.waves.requested) {
    const WaveFigures& w = r.waves;
    j["waves"] = {{"speed_m_s", w.speed},
                  {"froude", w.froude},
                  {"length_m", w.length},
                  {"wavelength_m", w.wavelength},
                  {"panel_length_x_m", w.panel_length_x},
                  {"panels_per_wavelength", w.panels_per_wavelength},
                  {"warning", w.warn}};
  }
  json worst = json::array();
  for (const WorstPanel& p : r.worst)
    worst.push_back({{"face", p.face},
                     {"centroid", {p.centroid.x, p.centroid.y, p.centroid.z}},
                     {"rule", to_string(p.rule)},
                     {"value", p.value}});
  j["worst"] = worst;
  j["failures"] = r.failures(rules);
  j["passes"] = r.passes(rules);
  return j.dump(indent);
}

std::string format_table(const QualityReport& r, const QualityRules& rules) {
  std::string s;
  s += f("%zu panels (%zu quads, %zu triangles), %zu vertices%s\n", r.faces, r.quads, r.triangles,
         r.vertices, r.half_hull ? ", half hull (y = 0 symmetry)" : "");
  s += f("\n  %-30s %8s  %15s  %s\n", "rule", "pass", "", "extreme");
  s += rule_row("quad side ratio < limit", r.side_ratio_share, rules.min_side_ratio_share,
                f("max %.3g (limit %g)", r.max_side_ratio, rules.max_side_ratio));
  s += rule_row("neighbour area ratio < limit", r.area_ratio_share, rules.min_area_ratio_share,
                f("max %.3g (limit %g); %.1f%% of neighbour pairs", r.max_area_ratio,
                  rules.max_area_ratio, 100 * r.area_ratio_pair_share));
  s += rule_row("neighbour normal angle", r.normal_angle_share, rules.min_normal_angle_share,
                f("max %.3g deg (limit %g; %zu knuckle edges)", r.max_normal_angle_deg,
                  rules.max_normal_angle_deg, r.knuckle_edges));
  s += rule_row("triangle min angle", r.triangle_angle_share, rules.min_triangle_angle_share,
                r.triangles == 0 ? std::string("(no triangles)")
                                 : f("min %.3g deg (limit %g)", r.min_triangle_angle_deg,
                                     rules.min_triangle_angle_deg));
  s += "\n";
  if (r.triangles > 0)
    s += line("equilateral measure (tri)",
              f("min %.4f, mean %.4f", r.min_equilateral, r.mean_equilateral));
  s += line("quad warp", f("max %.4g of diagonal (limit %g), max angle %.3g deg", r.max_warp,
                           rules.max_warp, r.max_warp_angle_deg));
  s += line("max aspect ratio", f("%.4g", r.max_aspect_ratio));
  s += line("non-convex quads", f("%zu", r.non_convex));
  s += line("zero-area panels", f("%zu", r.zero_area));
  s += line("very close panel centres", f("%zu pairs", r.close_centre_pairs));
  s += line("panels through each other",
            !r.crossing_pairs ? std::string("not checked")
            : *r.crossing_pairs == 0
                ? std::string("0 pairs")
                : f("%zu pairs, the first near (%.4g, %.4g, %.4g) m", *r.crossing_pairs,
                    r.crossing_where.x, r.crossing_where.y, r.crossing_where.z));
  const TopologyFacts& t = r.topology;
  s += "\n";
  s += line("watertight", t.watertight ? "yes" : "no");
  s += line(
      "boundary edges",
      t.uncut ? f("%zu in %zu loops: %zu centre plane, %zu deck edge or sheer (no waterline)",
                  t.boundary_edges, t.boundary_loops, t.centre_plane_edges, t.above_water_edges)
              : f("%zu in %zu loops: %zu centre plane, %zu waterline, %zu above", t.boundary_edges,
                  t.boundary_loops, t.centre_plane_edges, t.waterline_edges, t.above_water_edges));
  s += line(t.uncut ? "free edges (holes)" : "free edges below waterline",
            f("%zu", t.free_edges_below));
  s += line("panels across waterline", f("%zu", t.panels_across_waterline));
  s += line("non-manifold edges", f("%zu", t.nonmanifold_edges));
  s += line("orientation consistent",
            t.orientation_consistent
                ? std::string("yes")
                : f("no: %zu edges, %zu flipped panels", t.inconsistent_edges, t.flipped_faces));
  s += line("normals into the fluid",
            f("%s (enclosed volume %.6g m^3 below z = %.6g)", t.normals_into_fluid ? "yes" : "NO",
              t.enclosed_volume, t.waterline_z));
  if (r.waves.requested) {
    const WaveFigures& w = r.waves;
    s += "\n";
    s += line("speed", f("%.4g m/s (Fn %.4g on L = %.4g m)", w.speed, w.froude, w.length));
    s += line("Kelvin transverse wavelength", f("%.4g m", w.wavelength));
    s += line("panels per wavelength",
              f("%.3g (panel length along x %.4g m)%s", w.panels_per_wavelength, w.panel_length_x,
                w.warn ? "  WARNING: under 10" : ""));
  }
  if (!r.worst.empty()) {
    s += f("\n  %-8s %-26s %10s  %s\n", "panel", "rule", "value", "centroid (m)");
    for (const WorstPanel& p : r.worst)
      s += f("  %-8u %-26s %10.4g  (%.4f, %.4f, %.4f)\n", p.face, to_string(p.rule), p.value,
             p.centroid.x, p.centroid.y, p.centroid.z);
  }
  const std::vector<std::string> fails = r.failures(rules);
  s += fails.empty() ? "\nPASS\n" : "\nFAIL\n";
  for (const std::string& m : fails) s += "  - " + m + "\n";
  return s;
}

std::vector<FaceField> face_fields(const QualityReport& r) {
  const FaceQuality& q = r.per_face;
  return {{"area", q.area},
          {"min_angle_deg", q.min_angle_deg},
          {"max_angle_deg", q.max_angle_deg},
          {"equilateral_q", q.equilateral},
          {"side_ratio", q.side_ratio},
          {"warp", q.warp},
          {"warp_angle_deg", q.warp_angle_deg},
          {"aspect_ratio", q.aspect_ratio},
          {"neighbour_area_ratio", q.neighbour_area_ratio},
          {"neighbour_normal_angle_deg", q.neighbour_normal_angle},
          {"convex", q.convex},
          {"zero_area", q.zero_area},
          {"is_quad", q.is_quad},
          {"flipped", q.flipped},
          {"close_centre", q.close_centre}};
}

}  // namespace hm
