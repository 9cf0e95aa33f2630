#include "cli/load_hull.h"

#include <chrono>
#include <cstdio>

namespace hm::cli {

ImportResult load_hull(const std::string& path, const std::string& units, bool quiet) {
  ImportOptions options;
  options.force_units = units;
  ImportResult r = read_iges_file(path, options);
  if (!quiet) {
    for (const Diagnostic& d : r.diagnostics.items())
      if (d.severity != Severity::kNote)
        std::fprintf(stderr, "%s: %s\n", path.c_str(), format(d).c_str());
  }
  return r;
}

long long now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double seconds_since(long long start_ns) { return 1e-9 * double(now_ns() - start_ns); }

}  // namespace hm::cli
