// What every entity converter needs: the parsed file, its transforms, the options, and the
// record of which entities were used (so that the rest can be counted as skipped).
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "iges/iges_model.h"
#include "iges/read_iges.h"
#include "iges/transforms.h"

namespace hm::iges {

struct Context {
  const IgesModel& model;
  const Transforms& transforms;
  const ImportOptions& options;
  std::uint8_t* used;  // one flag per directory entry; set from several threads

  void mark(int index) const {
    std::atomic_ref<std::uint8_t>(used[index]).store(1, std::memory_order_relaxed);
  }
  const DirEntry& entry(int index) const { return model.entries[static_cast<std::size_t>(index)]; }
  // Throws LimitError when a declared size is over its limit: called before allocating.
  void check_limit(int index, std::uint64_t value, std::uint64_t limit, const char* what,
                   const char* limit_name) const {
    if (value > limit) {
      throw LimitError(model.source + ": " + describe(model, index) + ": declares " +
                       std::to_string(value) + " " + what + ", over the limit of " +
                       std::to_string(limit) + " (" + limit_name + ")");
    }
  }
};

}  // namespace hm::iges
