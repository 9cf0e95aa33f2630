// The individual writers behind write_mesh (internal to io/).
#pragma once

#include <ostream>

#include "io/write_mesh.h"

namespace hm::io {

void write_vtu(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
void write_stl_binary(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
void write_obj(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);

}  // namespace hm::io
