// `--validate`: the invariants checked between stages (mesh/check_invariants.h), as the
// commands call them. Also on when the environment sets HULLMESH_VALIDATE to anything but 0
// (the test suite runs every command so).
#pragma once

#include <string>

#include "mesh/check_invariants.h"
#include "mesh/surface_mesh.h"

namespace hm::cli {

// The flag's default: whether HULLMESH_VALIDATE asks for validation.
bool validation_from_environment();

// Throws InternalError (exit 1: a stage broke what it promises) naming the input file, the
// stage and every broken invariant with its place.
void validate_stage(const std::string& file, const char* stage, const SurfaceMesh& mesh,
                    const InvariantOptions& options);

}  // namespace hm::cli
