// Units: the G13 model scale and G14/G15 unit flag and name, converted to metres, and the check
// that the extents fit a ship in that unit (real files lie: millimetres declared, metres written).
#pragma once

#include "core/bbox.h"
#include "core/diagnostics.h"
#include "iges/read_iges.h"

namespace hm::iges {

// Ships (and ship models) measure between these lengths, in metres.
inline constexpr double kMinShipLength = 0.5;
inline constexpr double kMaxShipLength = 500.0;

// `file_box` is the bounding box in file units. Warns in `diags` when the declared unit makes the
// longest extent implausible, with the unit that would fit. Throws UsageError for an unknown
// forced unit.
UnitReport resolve_units(const IgesHeader& header, const BBox3d& file_box,
                         const ImportOptions& options, Diagnostics& diags);

}  // namespace hm::iges
