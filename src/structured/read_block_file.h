// The JSON block file of `hullmesh structured --blocks`: block planes and per-block panel sizes.
//
//   {
//     "size": [dx, dy, dz],                       optional, m: the global panel sizes
//     "planes": [                                 cut stations and lateral borders
//       {"name": "st 10", "x": 50.0},             a station x = 50
//       {"name": "WL 3", "z": 3.0},               a waterline; "y" gives a buttock
//       {"name": "p", "point": [x, y, z], "normal": [nx, ny, nz]}
//     ],
//     "blocks": [                                 sizes inside boxes (first match wins)
//       {"name": "bow", "min": [x, y, z], "max": [x, y, z], "size": [dx, dy, dz]}
//     ]
//   }
#pragma once

#include <string>

#include "structured/structured.h"

namespace hm {

// Fills options.planes, options.size_boxes and (when given) options.size. Throws InputError
// naming the file, the key and what is allowed; IoError when the file cannot be read.
void read_block_file(const std::string& path, StructuredOptions& options);

}  // namespace hm
