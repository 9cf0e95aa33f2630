// The IGES import driver: parse -> orientations -> which entities become patches -> convert
// (in parallel, one slot per patch) -> names and groups -> units -> collapsed patches left out ->
// skipped counts.
#include "iges/read_iges.h"

#include <filesystem>
#include <fstream>
#include <optional>
#include <unordered_map>

#include "core/error.h"
#include "core/parallel.h"
#include "iges/convert_surfaces.h"
#include "iges/convert_trims.h"
#include "iges/find_collapsed.h"
#include "iges/iges_context.h"
#include "iges/iges_model.h"
#include "iges/transforms.h"
#include "iges/units.h"
#include "iges/work_budget.h"

namespace hm {
namespace {

using iges::Context;
using iges::EntityFault;
using iges::Params;

void add_fault(const Context& ctx, const EntityFault& f, int job, Severity sev, Diagnostics& d) {
  const iges::DirEntry& e = ctx.entry(f.index());
  std::string msg = f.what();
  if (f.index() != job) {
    msg += "; skipped " + iges::describe(ctx.model, job);
  } else {
    msg += "; entity skipped";
  }
  d.add(sev, e.de, e.param_line, e.type, std::move(msg));
}

// Orientation of each 510 face from its 514 shell (OF = 0: the face uses the surface reversed)
// and the 186 solid (SOF/VOF = 0: the whole shell is reversed).
std::unordered_map<int, bool> face_orientations(const Context& ctx, Diagnostics& diags) {
  std::unordered_map<int, bool> shell_flip, face_reversed;
  const int n = static_cast<int>(ctx.model.size());
  for (int i = 0; i < n; ++i) {
    if (ctx.entry(i).type != 186) continue;
    try {
      ctx.mark(i);
      const Params p(ctx.model, i);
      shell_flip[p.pointer_to(1, {514}, "shell")] = p.integer(2) == 0;
      const std::int64_t voids = p.integer_or(3, 0);
      if (voids < 0 || static_cast<std::uint64_t>(voids) > p.size())
        p.fault("bad void shell count");
      for (std::int64_t k = 0; k < voids; ++k) {
        shell_flip[p.pointer_to(4 + 2 * static_cast<std::size_t>(k), {514}, "void shell")] =
            p.integer(5 + 2 * static_cast<std::size_t>(k)) == 0;
      }
    } catch (const EntityFault& f) {
      add_fault(ctx, f, i, Severity::kWarning, diags);
    }
  }
  for (int i = 0; i < n; ++i) {
    if (ctx.entry(i).type != 514) continue;
    try {
      ctx.mark(i);
      const Params p(ctx.model, i);
      const std::int64_t faces = p.integer(1);
      if (faces < 0 || static_cast<std::uint64_t>(faces) > p.size()) p.fault("bad face count");
      p.require(1 + 2 * static_cast<std::uint64_t>(faces), "the shell's faces");
      const auto it = shell_flip.find(i);
      const bool flip = it != shell_flip.end() && it->second;
      for (std::int64_t k = 0; k < faces; ++k) {
        const int face = p.pointer_to(2 + 2 * static_cast<std::size_t>(k), {510}, "face");
        if (face >= 0)
          face_reversed[face] = (p.integer(3 + 2 * static_cast<std::size_t>(k)) == 0) != flip;
      }
    } catch (const EntityFault& f) {
      add_fault(ctx, f, i, Severity::kWarning, diags);
    }
  }
  return face_reversed;
}

// Name from a 406 form 15 property that the entity points to after its own parameters.
std::string property_name(const Context& ctx, int index) {
  try {
    const Params p(ctx.model, index);
    const std::size_t own = iges::own_parameter_count(p);
    if (own == 0 || own >= p.size()) return {};
    std::size_t k = own + 1;
    const std::int64_t na = p.integer(k);
    if (na < 0 || static_cast<std::uint64_t>(na) >= p.size()) return {};
    k += 1 + static_cast<std::size_t>(na);
    if (k > p.size()) return {};
    const std::int64_t np = p.integer(k);
    if (np < 0 || static_cast<std::uint64_t>(np) > p.size() - k) return {};
    for (std::int64_t j = 1; j <= np; ++j) {
      const int q = p.pointer(k + static_cast<std::size_t>(j));
      if (q < 0 || ctx.entry(q).type != 406 || ctx.entry(q).form != 15) continue;
      ctx.mark(q);
      const Params name(ctx.model, q);
      std::string s = name.text(2);
      if (!s.empty()) return s;
    }
  } catch (const EntityFault&) {
  }
  return {};
}

std::string label_name(const iges::DirEntry& e) {
  if (e.label.empty()) return {};
  return e.subscript != 0 ? e.label + "(" + std::to_string(e.subscript) + ")" : e.label;
}

std::string patch_name(const Context& ctx, int wrapper, int surface) {
  for (int i : {wrapper, surface}) {
    if (i < 0) continue;
    std::string s = property_name(ctx, i);
    if (!s.empty()) return s;
  }
  for (int i : {wrapper, surface}) {
    if (i < 0) continue;
    std::string s = label_name(ctx.entry(i));
    if (!s.empty()) return s;
  }
  return {};
}

struct JobResult {
  std::optional<Patch> patch;
  Diagnostics diags;
  bool failed = false;
};

JobResult convert_job(const Context& ctx, int i, bool reversed) {
  const iges::BudgetScope budget;
  JobResult r;
  const iges::DirEntry& e = ctx.entry(i);
  try {
    if (iges::is_wrapper_type(e.type)) {
      r.patch = iges::convert_wrapped(ctx, i, reversed, r.diags);
      if (r.patch) {
        r.patch->name = patch_name(ctx, i, ctx.model.index_of(r.patch->de));
      }
    } else {
      auto cs = iges::convert_surface(ctx, i, nullptr, r.diags);
      if (cs) {
        Patch p;
        p.surface = std::move(cs->surface);
        p.loops = std::move(cs->loops);
        if (p.loops.size() == 1 && iges::is_natural_boundary(p.loops.front(), p.surface)) {
          p.loops.clear();
        }
        p.wrapping = Wrapping::kPlain;
        p.source_type = e.type;
        p.de = e.de;
        p.name = patch_name(ctx, -1, i);
        r.patch = std::move(p);
      }
    }
    if (!r.patch) {
      r.diags.add(Severity::kNote, e.de, e.param_line, e.type,
                  "unbounded plane: no hull surface to import");
      r.failed = true;
    }
  } catch (const EntityFault& f) {
    add_fault(ctx, f, i, Severity::kError, r.diags);
    r.failed = true;
  } catch (const GeometryError& g) {
    // A geometric operation refused this entity's data (the operations check their own
    // preconditions): the patch is skipped, the rest of the file still imports.
    r.diags.add(Severity::kError, e.de, e.param_line, e.type, std::string(g.what()) + "; skipped");
    r.failed = true;
  }
  return r;
}

std::vector<IgesGroup> read_groups(const Context& ctx, Diagnostics& diags) {
  std::vector<IgesGroup> groups;
  for (int i = 0; i < static_cast<int>(ctx.model.size()); ++i) {
    const iges::DirEntry& e = ctx.entry(i);
    if (e.type != 402 || !(e.form == 1 || e.form == 7 || e.form == 14 || e.form == 15)) continue;
    try {
      const Params p(ctx.model, i);
      const std::int64_t n = p.integer(1);
      if (n < 0 || static_cast<std::uint64_t>(n) > p.size())
        p.fault("group with " + std::to_string(n) + " members");
      p.require(1 + static_cast<std::uint64_t>(n), "the group's members");
      ctx.mark(i);
      IgesGroup g;
      g.de = e.de;
      for (std::int64_t k = 0; k < n; ++k) {
        const std::int64_t de = p.integer(2 + static_cast<std::size_t>(k));
        if (ctx.model.index_of(de) < 0) {
          diags.add(Severity::kWarning, e.de, e.param_line, e.type,
                    "dangling pointer: group member DE " + std::to_string(de) +
                        " does not exist; member dropped");
          continue;
        }
        g.member_des.push_back(static_cast<int>(de));
      }
      g.name = property_name(ctx, i);
      if (g.name.empty()) g.name = label_name(e);
      groups.push_back(std::move(g));
    } catch (const EntityFault& f) {
      add_fault(ctx, f, i, Severity::kWarning, diags);
    }
  }
  return groups;
}

// A used entity's 124 chain is used too.
void mark_transforms(const Context& ctx) {
  for (int i = 0; i < static_cast<int>(ctx.model.size()); ++i) {
    if (!ctx.used[i]) continue;
    int t = ctx.model.index_of(ctx.entry(i).transform);
    for (std::uint64_t depth = 0; t >= 0 && depth <= ctx.options.limits.max_pointer_depth;
         ++depth) {
      ctx.mark(t);
      t = ctx.model.index_of(ctx.entry(t).transform);
    }
  }
}

std::string skipped_summary(const std::map<int, int>& skipped) {
  int total = 0;
  std::string list;
  for (const auto& [type, count] : skipped) {
    total += count;
    list += (list.empty() ? "" : ", ") + std::to_string(type) + " x " + std::to_string(count);
  }
  return std::to_string(total) + " entities carry no hull surface and were skipped (" + list + ")";
}

// Leaves out the patches whose surface collapses to a point or a line, each reported as an error
// on its entity (the wrapper's, when wrapped). Keeps extents and patch_job in step with patches.
void drop_collapsed(const Context& ctx, std::vector<PatchExtent>& extents,
                    std::vector<int>& patch_job, std::vector<std::uint8_t>& failed,
                    ImportResult& r) {
  const std::vector<std::string> why = iges::find_collapsed(extents);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < why.size(); ++i) {
    if (why[i].empty()) {
      if (kept != i) {
        r.patches[kept] = std::move(r.patches[i]);
        extents[kept] = extents[i];
        patch_job[kept] = patch_job[i];
      }
      ++kept;
      continue;
    }
    const iges::DirEntry& e = ctx.entry(patch_job[i]);
    const int surface_de = r.patches[i].de;
    const std::string which =
        surface_de != e.de ? " (surface DE " + std::to_string(surface_de) + ")" : "";
    r.diagnostics.add(Severity::kError, e.de, e.param_line, e.type, why[i] + which + "; skipped");
    failed[static_cast<std::size_t>(patch_job[i])] = 1;
  }
  r.patches.resize(kept);
  extents.resize(kept);
  patch_job.resize(kept);
}

[[noreturn]] void no_surface(const std::string& source, const ImportResult& r) {
  std::string why;
  for (const Diagnostic& d : r.diagnostics.items()) {
    if (d.severity == Severity::kError) {
      why = format(d);
      break;
    }
  }
  if (why.empty()) {
    why = "the file holds no surface entity (";
    bool first = true;
    for (const auto& [type, count] : r.entities_by_type) {
      why += (first ? "" : ", ") + std::to_string(type) + " x " + std::to_string(count);
      first = false;
    }
    why += ")";
  }
  throw IgesError(source + ": no readable surface: " + why);
}

}  // namespace

ImportResult read_iges(std::string_view text, const std::string& source,
                       const ImportOptions& options) {
  const iges::IgesModel model = iges::load_model(text, source, options.limits);
  ImportResult r;
  r.header = model.header;
  r.diagnostics.append(model.file_diagnostics);
  for (const iges::DirEntry& e : model.entries) ++r.entities_by_type[e.type];
  const iges::Transforms transforms(model);
  std::vector<std::uint8_t> used(model.size(), 0);
  const Context ctx{model, transforms, options, used.data()};

  const std::unordered_map<int, bool> reversed = face_orientations(ctx, r.diagnostics);
  // A surface that a face or trim wraps is reported once, as that face or trim.
  std::vector<std::uint8_t> wrapped(model.size(), 0);
  for (int i = 0; i < static_cast<int>(model.size()); ++i) {
    if (!iges::is_wrapper_type(ctx.entry(i).type)) continue;
    const int s = iges::wrapped_surface(ctx, i);
    if (s >= 0) wrapped[static_cast<std::size_t>(s)] = 1;
  }
  std::vector<int> jobs;
  for (int i = 0; i < static_cast<int>(model.size()); ++i) {
    const int type = ctx.entry(i).type;
    if (iges::is_wrapper_type(type) ||
        (iges::is_surface_type(type) && !wrapped[static_cast<std::size_t>(i)])) {
      jobs.push_back(i);
    }
  }
  std::vector<JobResult> results(jobs.size());
  parallel_for(
      0, jobs.size(),
      [&](std::size_t k) {
        const auto it = reversed.find(jobs[k]);
        results[k] = convert_job(ctx, jobs[k], it != reversed.end() && it->second);
      },
      8);
  std::vector<std::uint8_t> failed(model.size(), 0);
  std::vector<int> patch_job;  // per patch: the entity index of its job
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    r.diagnostics.append(results[k].diags);
    if (results[k].patch) {
      r.patches.push_back(std::move(*results[k].patch));
      patch_job.push_back(jobs[k]);
    }
    if (results[k].failed) failed[static_cast<std::size_t>(jobs[k])] = 1;
  }
  r.groups = read_groups(ctx, r.diagnostics);
  if (r.patches.empty()) no_surface(source, r);

  BBox3d file_box;
  for (const Patch& p : r.patches) {
    for (const Vec3d& q : p.surface.points) file_box.add(q);
  }
  r.units = iges::resolve_units(r.header, file_box, options, r.diagnostics);
  const double f = r.units.applied_to_metres;
  for (Patch& p : r.patches) {
    if (f != 1.0) {
      for (Vec3d& q : p.surface.points) q *= f;
    }
  }
  // The box of the surfaces themselves: a control net overshoots a curved patch (and the unit
  // check above only needs its order of magnitude).
  std::vector<PatchExtent> extents(r.patches.size());
  parallel_for_each_item(r.patches.size(),
                         [&](std::size_t i) { extents[i] = patch_extent(r.patches[i]); });
  drop_collapsed(ctx, extents, patch_job, failed, r);
  if (r.patches.empty()) no_surface(source, r);
  for (const PatchExtent& e : extents) r.bbox.add(e.box);

  mark_transforms(ctx);
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (!used[i] || failed[i]) ++r.skipped_by_type[model.entries[i].type];
  }
  if (!r.skipped_by_type.empty()) r.diagnostics.note(skipped_summary(r.skipped_by_type));
  return r;
}

ImportResult read_iges_file(const std::string& path, const ImportOptions& options) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(path + ": cannot read: " + ec.message());
  if (size > options.limits.max_file_bytes) {
    throw LimitError(path + ": the file has " + std::to_string(size) +
                     " bytes, over the limit of " + std::to_string(options.limits.max_file_bytes) +
                     " (max_file_bytes)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open for reading");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) throw IoError(path + ": read error");
  return read_iges(text, path, options);
}

}  // namespace hm
