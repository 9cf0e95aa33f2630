#include "cli/validate_stage.h"

#include <cstdlib>
#include <string_view>

#include "core/error.h"

namespace hm::cli {

bool validation_from_environment() {
  const char* v = std::getenv("HULLMESH_VALIDATE");
  return v != nullptr && *v != '\0' && std::string_view(v) != "0";
}

void validate_stage(const std::string& file, const char* stage, const SurfaceMesh& mesh,
                    const InvariantOptions& options) {
  const std::vector<InvariantBreak> breaks = find_invariant_breaks(mesh, options);
  if (breaks.empty()) return;
  std::string message = file + ": --validate: the " + stage + " stage broke " +
                        std::to_string(breaks.size()) +
                        (breaks.size() == 1 ? " invariant" : " invariants");
  for (const InvariantBreak& b : breaks) message += "\n  " + b.invariant + ": " + b.detail;
  throw InternalError(message);
}

}  // namespace hm::cli
