#include "query/hull_query.h"

#include "query/query_scene.h"

namespace hm {

HullQuery::HullQuery(std::span<const Patch> patches, const SurfaceMesh& mesh)
    : impl_(std::make_unique<Impl>(patches, mesh)) {}

HullQuery::~HullQuery() = default;
HullQuery::HullQuery(HullQuery&&) noexcept = default;
HullQuery& HullQuery::operator=(HullQuery&&) noexcept = default;

BBox3d HullQuery::bbox() const { return impl_->box; }
double HullQuery::length_scale() const { return impl_->length; }
std::size_t HullQuery::triangle_count() const { return impl_->tri.size(); }

}  // namespace hm
