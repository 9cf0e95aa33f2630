// libFuzzer entry for the IGES reader: any input must end in a result or a typed hullmesh error,
// never a crash, hang, leak or undefined behaviour.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "iges/read_iges.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hm::ImportOptions options;
  // Tighter limits than the defaults keep each run fast; the checks themselves are the same.
  options.limits.max_entities = 20'000;
  options.limits.max_params_per_entity = 200'000;
  options.limits.max_control_points = 20'000;
  options.limits.max_knots = 20'000;
  options.limits.max_degree = 12;
  try {
    hm::read_iges(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz", options);
  } catch (const hm::Error&) {
    // Typed errors are the expected outcome for broken input.
  }
  return 0;
}
