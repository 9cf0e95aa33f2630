// Basic index and id types shared by every stage.
#pragma once

#include <cstdint>

namespace hm {

// Meshes index vertices and faces with 32 bits; kInvalid marks "none" (for example the fourth
// corner of a triangle stored in a four-slot face).
using Index = std::uint32_t;
inline constexpr Index kInvalid = ~Index{0};

// Index of a patch in the imported model (provenance of every face).
using PatchId = std::uint32_t;

}  // namespace hm
