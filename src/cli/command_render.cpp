// hullmesh render MESH -o view.png: a ray-traced picture of a panel mesh (profile, plan, body
// plan or isometric), coloured plain, by provenance, by features or by a per-face measure.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/error.h"
#include "io/read_mesh.h"
#include "io/render_legend.h"
#include "io/render_view.h"
#include "io/write_png.h"
#include "quality/quality_report.h"
#include "query/trace_view.h"

namespace hm::cli {
namespace {

struct RenderCliOptions {
  std::string file;
  std::string output;
  std::string view = "profile";
  std::string colour = "plain";
  int width = 1600;
  double knuckle_angle = 40;
  std::vector<double> range;  // empty, or {lo, hi}
};

// Categorical legends list at most this many ids, then "...".
constexpr std::size_t kMaxSwatches = 20;

ViewKind view_kind(const std::string& name) {
  if (name == "plan") return ViewKind::kPlan;
  if (name == "bodyplan") return ViewKind::kBodyPlan;
  if (name == "iso") return ViewKind::kIso;
  return ViewKind::kProfile;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The formats whose files say which patch each face came from (cell data, physical groups or
// named groups); the others give every face patch 0.
bool carries_patches(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".vtu" || ext == ".vtk" || ext == ".msh" || ext == ".obj";
}

std::vector<LegendEntry> id_entries(std::span<const Index> ids, bool& more) {
  std::vector<Index> present(ids.begin(), ids.end());
  std::sort(present.begin(), present.end());
  present.erase(std::unique(present.begin(), present.end()), present.end());
  if (!present.empty() && present.back() == kInvalid) present.pop_back();
  more = present.size() > kMaxSwatches;
  if (more) present.resize(kMaxSwatches);
  std::vector<LegendEntry> entries;
  for (Index id : present) entries.push_back({std::to_string(id), category_colour(id)});
  return entries;
}

// What the picture is coloured by: per-face colours, edge kinds (features) and the legend.
struct Colouring {
  std::vector<Rgb8> face_colour;
  std::vector<std::array<EdgeKind, 4>> edge_kind;  // empty: every edge plain
  std::string summary;                             // for the printed line
  // Exactly one legend, or none (plain).
  bool scalar = false;
  ScalarRange range;
  std::vector<LegendEntry> swatches;
  bool more = false;
};

Colouring colour_faces(const MeshFile& file, const RenderCliOptions& o) {
  const SurfaceMesh& mesh = file.mesh;
  Colouring c;
  const std::string& mode = o.colour;
  if (mode == "plain" || mode == "features") {
    c.face_colour.assign(mesh.faces.size(), kPlainPanel);
    if (mode == "features") {
      c.edge_kind = classify_face_edges(mesh, o.knuckle_angle);
      c.swatches = {{"knuckle", kKnuckleLine}, {"boundary", kBoundaryLine}};
      std::size_t knuckles = 0, boundaries = 0;
      for (const auto& k : c.edge_kind) {
        knuckles += std::count(k.begin(), k.end(), EdgeKind::kKnuckle);
        boundaries += std::count(k.begin(), k.end(), EdgeKind::kBoundary);
      }
      c.summary = "features: " + std::to_string(boundaries) + " boundary edges, about " +
                  std::to_string(knuckles / 2) + " knuckle edges over " +
                  legend_number(o.knuckle_angle) + " deg";
    }
    return c;
  }
  if (mode == "patch") {
    if (!carries_patches(o.file)) {
      throw UsageError("--color patch: " + o.file +
                       " carries no patch ids (its format has none); " +
                       "write the mesh as .vtu, .vtk, .msh or .obj to keep them");
    }
    c.face_colour = category_face_colours(mesh.face_patch);
    c.swatches = id_entries(mesh.face_patch, c.more);
    c.summary = "patch";
    return c;
  }
  if (mode == "block") {
    if (mesh.face_block.size() != mesh.faces.size()) {
      throw UsageError("--color block: " + o.file +
                       " carries no block ids (structured meshes written as .vtu or .vtk do)");
    }
    c.face_colour = category_face_colours(mesh.face_block);
    c.swatches = id_entries(mesh.face_block, c.more);
    c.summary = "block";
    return c;
  }

  // A per-face measure: the quality report's, else a cell-data array of the file.
  std::vector<double> values;
  QualityOptions q;
  q.knuckle_angle_deg = o.knuckle_angle;
  const QualityReport report = assess_quality(mesh, q);
  std::string names;
  for (const FaceField& f : face_fields(report)) {
    names += std::string(names.empty() ? "" : ", ") + f.name;
    if (mode == f.name) values.assign(f.values.begin(), f.values.end());
  }
  std::string file_names;
  for (const NamedFaceField& f : file.fields) {
    file_names += (file_names.empty() ? "" : ", ") + f.name;
    if (values.empty() && mode == f.name && f.values.size() == mesh.faces.size()) values = f.values;
  }
  if (values.empty()) {
    throw UsageError("--color " + mode +
                     ": not a colour mode; use plain, patch, block, features, a per-face "
                     "measure (" +
                     names + ")" +
                     (file_names.empty()
                          ? ""
                          : ", or a cell-data array of " + o.file + " (" + file_names + ")"));
  }
  c.scalar = true;
  c.range = value_range(values);
  if (o.range.size() == 2) c.range = {o.range[0], o.range[1], true};
  c.face_colour = scalar_face_colours(values, c.range);
  c.summary = mode + " from " + legend_number(c.range.lo) + " to " + legend_number(c.range.hi);
  return c;
}

int run_render(const RenderCliOptions& o, const GlobalOptions& g) {
  if (o.range.size() == 2 && !(o.range[0] < o.range[1])) {
    throw UsageError("--range " + legend_number(o.range[0]) + "," + legend_number(o.range[1]) +
                     ": the low end must be below the high end");
  }
  const MeshFile file = read_mesh(o.file);
  if (file.mesh.faces.empty()) throw GeometryError(o.file + ": the mesh has no faces to render");
  const Colouring c = colour_faces(file, o);

  const ViewKind kind = view_kind(o.view);
  const ViewCamera camera = fit_view_camera(file.mesh, kind, static_cast<std::uint32_t>(o.width));
  const ViewHits hits = trace_view(file.mesh, camera);
  PixelHits px;
  px.width = hits.width;
  px.height = hits.height;
  px.face = hits.face;
  px.point = hits.point;
  px.column_dir = hits.column_dir;
  px.pixel_size = camera.pixel_size;
  px.centre_line_x = camera.centre_line_x;
  RgbImage img = shade_view(file.mesh, px, c.face_colour, c.edge_kind);
  const std::uint32_t picture_height = img.height;
  if (c.scalar) {
    append_scalar_legend(img, o.colour, c.range);
  } else if (!c.swatches.empty()) {
    append_swatch_legend(img, o.colour, c.swatches, c.more);
  }
  write_png(o.output, img.width, img.height, img.rgb);

  if (!g.quiet) {
    std::size_t covered = 0;
    for (Index f : hits.face) covered += f != kInvalid;
    std::printf("%s: %s view of %zu faces, %u x %u pixels (%u for the picture), %.4g m per pixel\n",
                o.output.c_str(), o.view.c_str(), file.mesh.faces.size(), img.width, img.height,
                picture_height, camera.pixel_size);
    std::printf("  colour %s; %zu pixels show the hull\n",
                c.summary.empty() ? o.colour.c_str() : c.summary.c_str(), covered);
  }
  return static_cast<int>(ExitCode::kOk);
}

}  // namespace

void register_render(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto opts = std::make_shared<RenderCliOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Ray-trace a picture of a panel mesh into a PNG");
  cmd->add_option("mesh", opts->file, "Mesh file (any format hullmesh reads)")->required();
  cmd->add_option("-o,--output", opts->output, "PNG file to write")->required();
  cmd->add_option("--view", opts->view, "profile, plan (from below), bodyplan or iso")
      ->check(CLI::IsMember({"profile", "plan", "bodyplan", "iso"}))
      ->capture_default_str();
  cmd->add_option("--width", opts->width, "Picture width in pixels; the height follows the view")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  cmd->add_option("--color,--colour", opts->colour,
                  "plain, patch, block, features, or a per-face measure of `hullmesh quality` "
                  "(side_ratio, min_angle_deg, neighbour_area_ratio, warp, area, ...) or of the "
                  "file's cell data")
      ->capture_default_str();
  cmd->add_option("--knuckle-angle", opts->knuckle_angle,
                  "Dihedral angle above which an edge is a knuckle, degrees (features)")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
  cmd->add_option("--range", opts->range, "LO,HI: the measure's colour range (default: its own)")
      ->expected(2)
      ->delimiter(',');
  cmd->callback(
      [opts, &global, &action] { action = [opts, &global] { return run_render(*opts, global); }; });
}

}  // namespace hm::cli
