// Human names of IGES entity types, for reports.
#pragma once

namespace hm::cli {

// "rational B-spline surface" for 128; "entity" when the type is not known.
const char* iges_entity_name(int type);

}  // namespace hm::cli
