// Reading IGES 5.3 files into hull patches. The public face of the importer.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/bbox.h"
#include "core/diagnostics.h"
#include "core/limits.h"
#include "nurbs/patch.h"

namespace hm {

// Global-section facts an engineer wants to see (IGES G parameters).
struct IgesHeader {
  std::string sending_system;  // G3 product id from sender, or G4 file name when absent
  std::string file_name;       // G4
  std::string native_system;   // G5 native system id
  std::string preprocessor;    // G6
  std::string author;          // G21
  std::string organisation;    // G22
  std::string date;            // G18
  double model_scale = 1.0;    // G13
  int unit_flag = 0;           // G14
  std::string unit_name;       // G15
  double min_resolution = 0;   // G19 (model units)
};

struct UnitReport {
  double declared_to_metres = 1.0;  // factor from the G14/G15 declaration and G13 scale
  double applied_to_metres = 1.0;   // factor actually applied
  bool forced = false;              // the user forced --units
  bool implausible = false;         // the extents do not fit a ship in the declared unit
  std::string suggestion;           // unit that would make the extents plausible, if any
};

struct IgesGroup {
  int de = 0;
  std::string name;
  std::vector<int> member_des;
};

struct ImportOptions {
  // "" = trust the file (with a plausibility warning); otherwise one of m, mm, cm, in, ft, km.
  std::string force_units;
  ResourceLimits limits;
  double trim_tolerance = 1e-6;  // relative to the model size, for sampling and projection
};

struct ImportResult {
  std::vector<Patch> patches;
  IgesHeader header;
  UnitReport units;
  std::vector<IgesGroup> groups;
  std::map<int, int> skipped_by_type;   // entity type -> count of entities carrying no surface
  std::map<int, int> entities_by_type;  // every entity type -> count in the directory
  Diagnostics diagnostics;
  BBox3d bbox;  // of the surfaces (untrimmed domains) after transforms, in metres
};

// Parse from memory. `source_name` names the input in messages. Throws IgesError (malformed),
// LimitError (a declared size over the limits).
ImportResult read_iges(std::string_view text, const std::string& source_name,
                       const ImportOptions& options = {});
// Read a file; throws IoError when it cannot be read, and checks the file size first.
ImportResult read_iges_file(const std::string& path, const ImportOptions& options = {});

// Conversion factor from an IGES unit flag (G14) to metres; 0 when the flag is unknown.
double iges_unit_to_metres(int flag);
// Factor for a unit name (m, mm, cm, in, ft, km, mil, um, mi); 0 when unknown.
double unit_name_to_metres(std::string_view name);

}  // namespace hm
