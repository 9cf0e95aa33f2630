#include "query/query_scene.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "core/error.h"
#include "core/limits.h"
#include "core/parallel.h"
#include "query/embree_device.h"

namespace hm {
namespace {

void check_mesh(std::span<const Patch> patches, const SurfaceMesh& mesh) {
  const std::size_t nv = mesh.positions.size();
  if (mesh.faces.empty()) throw GeometryError("hull query: the mesh has no faces");
  if (mesh.face_patch.size() != mesh.faces.size()) {
    throw GeometryError("hull query: face_patch has " + std::to_string(mesh.face_patch.size()) +
                        " entries for " + std::to_string(mesh.faces.size()) + " faces");
  }
  if (!mesh.vertex_uv.empty() && mesh.vertex_uv.size() != nv) {
    throw GeometryError("hull query: vertex_uv does not have one entry per vertex");
  }
  if (!mesh.vertex_patch.empty() && mesh.vertex_patch.size() != nv) {
    throw GeometryError("hull query: vertex_patch does not have one entry per vertex");
  }
  for (const Vec3d& p : mesh.positions) {
    if (!is_finite(p)) throw GeometryError("hull query: a vertex position is not finite");
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (mesh.face_patch[f] >= patches.size()) {
      throw GeometryError("hull query: face " + std::to_string(f) + " names patch " +
                          std::to_string(mesh.face_patch[f]) + " of " +
                          std::to_string(patches.size()));
    }
    for (int k = 0; k < corner_count(mesh.faces[f]); ++k) {
      if (mesh.faces[f][k] >= nv) {
        throw GeometryError("hull query: face " + std::to_string(f) +
                            " has a vertex index out of"
                            " range");
      }
    }
  }
}

}  // namespace

Vec2d HullQuery::Impl::uv_at(Index t, double b1, double b2) const {
  const auto& c = tri_uv[t];
  return domains[tri_patch[t]].map((1 - b1 - b2) * c[0] + b1 * c[1] + b2 * c[2]);
}

Vec3d HullQuery::Impl::oriented_normal(PatchId p, Vec2d uv) const {
  const Vec3d n = normal(patches[p].surface, uv.x, uv.y);
  return patches[p].reversed ? -n : n;
}

void HullQuery::Impl::project_corners(const SurfaceMesh& mesh) {
  // Corner (u, v): the vertex's own when it lies on this triangle's patch. Otherwise the vertex
  // is projected onto the patch, once per (patch, vertex) pair: a border vertex of the merged
  // mesh names one patch and is a corner of several triangles of each neighbour, and each
  // projection is a Newton solve on the NURBS (the most costly part of building the query).
  const bool has_uv = !mesh.vertex_uv.empty();
  auto own = [&](Index v, PatchId p) {
    return has_uv && (mesh.vertex_patch.empty() || mesh.vertex_patch[v] == p);
  };
  struct Request {
    PatchId patch;
    Index vertex;
    Index slot;  // 3 t + k: corner k of triangle t
  };
  const std::size_t total = tri.size();
  // Count -> scan -> scatter: each triangle writes its own slice of the requests.
  std::vector<Index> first(total + 1, 0);
  parallel_for(0, total, [&](std::size_t t) {
    Index n = 0;
    for (int k = 0; k < 3; ++k) n += !own(tri[t][k], tri_patch[t]);
    first[t + 1] = n;
  });
  for (std::size_t t = 0; t < total; ++t) first[t + 1] += first[t];
  std::vector<Request> req(first.back());
  parallel_for(0, total, [&](std::size_t t) {
    Index r = first[t];
    for (int k = 0; k < 3; ++k) {
      const Index v = tri[t][k];
      if (own(v, tri_patch[t])) {
        tri_uv[t][k] = mesh.vertex_uv[v];
      } else {
        req[r++] = {tri_patch[t], v, static_cast<Index>(3 * t + k)};
      }
    }
  });
  // Requests grouped by pair, each group in slot order (a strict order: the same groups and
  // starts for any thread count).
  parallel_sort(req.begin(), req.end(), [](const Request& a, const Request& b) {
    return std::tie(a.patch, a.vertex, a.slot) < std::tie(b.patch, b.vertex, b.slot);
  });
  std::vector<Index> group;
  for (std::size_t r = 0; r < req.size(); ++r) {
    if (r == 0 || req[r].patch != req[r - 1].patch || req[r].vertex != req[r - 1].vertex) {
      group.push_back(static_cast<Index>(r));
    }
  }
  group.push_back(static_cast<Index>(req.size()));
  parallel_for(0, group.size() - 1, [&](std::size_t g) {
    const Request& head = req[group[g]];
    const NurbsSurface& surface = patches[head.patch].surface;
    const Vec3d& q = mesh.positions[head.vertex];
    // Start from the mean (u, v) of the own corners of the first triangle in the group that has
    // any; a global search only when none has.
    SurfaceProjection proj;
    bool started = false;
    for (Index r = group[g]; r < group[g + 1] && !started; ++r) {
      const Index t = req[r].slot / 3;
      Vec2d sum;
      int n = 0;
      for (int k = 0; k < 3; ++k) {
        if (own(tri[t][k], head.patch)) {
          sum += mesh.vertex_uv[tri[t][k]];
          ++n;
        }
      }
      if (n > 0) {
        proj = hm::closest_point(surface, q, sum.x / n, sum.y / n, nets[head.patch]);
        started = true;
      }
    }
    if (!started) proj = hm::closest_point(surface, q);
    for (Index r = group[g]; r < group[g + 1]; ++r) {
      tri_uv[req[r].slot / 3][req[r].slot % 3] = {proj.u, proj.v};
    }
  });
  parallel_for(0, total, [&](std::size_t t) {
    query::unwrap_corners(domains[tri_patch[t]], tri_uv[t].data(), 3);
  });
}

HullQuery::Impl::Impl(std::span<const Patch> in_patches, const SurfaceMesh& mesh)
    : patches(in_patches.begin(), in_patches.end()) {
  check_mesh(in_patches, mesh);

  for (const Vec3d& p : mesh.positions) box.add(p);
  centre = box.center();
  const Vec3d ext = box.extent();
  length = std::max({ext.x, ext.y, ext.z});
  if (!(length > 0)) throw GeometryError("hull query: the mesh has zero extent");

  local.resize(mesh.positions.size());
  local_f.resize(mesh.positions.size());
  for (std::size_t i = 0; i < local.size(); ++i) {
    local[i] = mesh.positions[i] - centre;
    local_f[i] = {static_cast<float>(local[i].x), static_cast<float>(local[i].y),
                  static_cast<float>(local[i].z), 0.0f};
  }

  // Triangles grouped by patch, in face order within a patch (counting sort).
  patch_first.assign(patches.size() + 1, 0);
  std::uint64_t total = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Index n = is_triangle(mesh.faces[f]) ? 1 : 2;
    patch_first[mesh.face_patch[f] + 1] += n;
    total += n;
  }
  if (total > ResourceLimits{}.max_triangles) {
    throw LimitError("hull query: " + std::to_string(total) + " triangles exceed the limit");
  }
  for (std::size_t p = 0; p < patches.size(); ++p) patch_first[p + 1] += patch_first[p];
  tri.resize(total);
  tri_face.resize(total);
  tri_patch.resize(total);
  std::vector<Index> fill(patch_first.begin(), patch_first.end() - 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    const PatchId p = mesh.face_patch[f];
    auto put = [&](Index a, Index b, Index c) {
      const Index t = fill[p]++;
      tri[t] = {a, b, c};
      tri_face[t] = static_cast<Index>(f);
      tri_patch[t] = p;
    };
    put(face[0], face[1], face[2]);
    if (!is_triangle(face)) put(face[0], face[2], face[3]);
  }

  // Only patches with triangles are ever refined on (every hit, section crossing and closest
  // point starts on a triangle): a query over a few faces of a large hull, as the merge's overlap
  // search builds, skips the others.
  domains.resize(patches.size());
  nets.resize(patches.size());
  parallel_for(0, patches.size(), [&](std::size_t p) { nets[p] = net_size(patches[p].surface); });
  std::vector<std::size_t> used;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (patch_first[p + 1] > patch_first[p]) used.push_back(p);
  }
  for (std::size_t p : used) validate_surface(patches[p].surface);
  parallel_for_each_item(used.size(), [&](std::size_t i) {
    domains[used[i]] = query::make_domain(patches[used[i]].surface, accept_tolerance());
  });

  tri_uv.resize(total);
  project_corners(mesh);
  if (!mesh.vertex_uv.empty() && !mesh.vertex_patch.empty()) {
    vertex_patch = mesh.vertex_patch;
    vertex_uv = mesh.vertex_uv;
  }

  // How far the triangles stray from the surface, sampled at their centroids: the closest-point
  // search widens its radius by this much so that it does not miss a patch whose triangles lie
  // slightly farther than the surface does. Only the offset along the triangle's normal counts:
  // on a sheared patch (parameter lines side by side) the surface point at the centroid's
  // (u, v) lies well away from the centroid in the tangent plane, and counting that widened
  // every search to metres.
  std::vector<double> deviation(total);
  parallel_for(0, total, [&](std::size_t t) {
    const Vec2d uv = uv_at(static_cast<Index>(t), 1.0 / 3, 1.0 / 3);
    const Vec3d &a = local[tri[t][0]], &b = local[tri[t][1]], &c = local[tri[t][2]];
    const Vec3d offset =
        evaluate(patches[tri_patch[t]].surface, uv.x, uv.y) - to_model((a + b + c) / 3.0);
    const Vec3d n = cross(b - a, c - a);
    const double len = norm(n);
    deviation[t] = len > 0 ? std::abs(dot(offset, n)) / len : norm(offset);
  });
  for (double d : deviation) max_deviation = std::max(max_deviation, d);

  // One geometry per patch: geomID is the patch index. The vertex buffer is shared by all of
  // them; each index buffer is the patch's slice of tri.
  RTCDevice device = query::embree_device();
  scene.reset(rtcNewScene(device));
  query::check_embree("rtcNewScene");
  rtcSetSceneFlags(scene.get(), static_cast<RTCSceneFlags>(RTC_SCENE_FLAG_ROBUST |
                                                           RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
  rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_HIGH);
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const std::size_t count = patch_first[p + 1] - patch_first[p];
    if (count == 0) continue;
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, local_f.data(),
                               0, sizeof(local_f[0]), local_f.size());
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tri.data(),
                               patch_first[p] * sizeof(tri[0]), sizeof(tri[0]), count);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene.get(), geom, static_cast<unsigned>(p));
    rtcReleaseGeometry(geom);
    query::check_embree("building a patch geometry");
  }
  rtcCommitScene(scene.get());
  query::check_embree("rtcCommitScene");

  plane_bvh.build(local, tri, 1e-7 * length);
}

}  // namespace hm
