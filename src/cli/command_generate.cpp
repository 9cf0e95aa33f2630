// hullmesh generate KIND -o out.igs: parametric test hulls as IGES 128 patches.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "iges/read_iges.h"
#include "iges/write_iges.h"
#include "nurbs/generate_hull.h"

namespace hm::cli {
namespace {

struct GenerateOptions {
  std::string kind;
  std::string output;
  HullSpec spec;
  std::string lie_units;  // declare this unit while writing metres
  bool spec_draft_set = false;
};

int run_generate(GenerateOptions o, const GlobalOptions& g) {
  if (!parse_hull_kind(o.kind, o.spec.kind))
    throw UsageError("unknown hull kind '" + o.kind + "' (expected wigley, round-bilge or chine)");
  const GeneratedHull hull = generate_hull(o.spec);
  IgesWriteOptions w;
  w.file_name = o.output;
  if (!o.lie_units.empty()) {
    static const struct {
      const char* name;
      int flag;
    } kFlags[] = {{"in", 1}, {"mm", 2}, {"ft", 4}, {"km", 5}, {"m", 6}, {"cm", 10}};
    int flag = 0;
    for (const auto& f : kFlags)
      if (o.lie_units == f.name) flag = f.flag;
    if (flag == 0) throw UsageError("--lie-units: unknown unit '" + o.lie_units + "'");
    w.unit_flag = flag;
    w.lie_about_units = true;
  }
  write_iges_file(o.output, hull.patches, w);
  if (!g.quiet) {
    std::printf("%s: %s hull, %zu patches, L %.6g m, B %.6g m, D %.6g m, T %.6g m (%s)\n",
                o.output.c_str(), to_string(o.spec.kind), hull.patches.size(), o.spec.length,
                o.spec.beam, o.spec.depth, o.spec.draft, o.spec.full_hull ? "full" : "port half");
    std::printf("  at T: displacement %.9g m^3, wetted area %.9g m^2 (both sides)\n",
                hull.facts.displacement_volume, hull.facts.wetted_area);
    std::printf("  surface area of the patches %.9g m^2, %zu knuckle lines\n",
                hull.facts.surface_area, hull.facts.knuckles.size());
  }
  return 0;
}

}  // namespace

void register_generate(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto o = std::make_shared<GenerateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "generate", "Write a parametric test hull (wigley, round-bilge, chine) as IGES 128 patches");
  cmd->add_option("kind", o->kind, "wigley | round-bilge | chine")->required();
  cmd->add_option("-o,--output", o->output, "Output IGES file")->required();
  cmd->add_option("--patches", o->spec.patches, "Number of patches (1 to 1000)")
      ->check(CLI::Range(1, 1000));
  cmd->add_flag("--full", o->spec.full_hull, "Both sides (default: the port half, y >= 0)");
  cmd->add_option("--length", o->spec.length, "Length L (m)")->check(CLI::PositiveNumber);
  cmd->add_option("--beam", o->spec.beam, "Beam B (m)")->check(CLI::PositiveNumber);
  cmd->add_option("--depth", o->spec.depth, "Depth D, keel to deck (m)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--draft", o->spec.draft, "Design draft T (m)")->check(CLI::PositiveNumber);
  cmd->add_option("--gap", o->spec.defects.gap,
                  "Defect: gaps between patches, at most this wide (m)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--overlap", o->spec.defects.overlap,
                  "Defect: overlap of neighbouring patches (fraction of a patch)")
      ->check(CLI::Range(0.0, 0.5));
  cmd->add_flag("--duplicate-points", o->spec.defects.duplicate_points,
                "Defect: repeated rows of control points");
  cmd->add_option("--flip-every", o->spec.defects.flip_every,
                  "Defect: reverse the orientation of every n-th patch")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--lie-units", o->lie_units,
                  "Defect: declare this unit (mm, cm, in, ft, km) while writing metres");
  cmd->add_option("--seed", o->spec.defects.seed, "Seed for random defects");
  cmd->callback(
      [o, &global, &action] { action = [o, &global] { return run_generate(*o, global); }; });
}

}  // namespace hm::cli
