#include "iges/units.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace hm {

double iges_unit_to_metres(int flag) {
  switch (flag) {
    case 1:
      return 0.0254;  // inch
    case 2:
      return 0.001;  // millimetre
    case 4:
      return 0.3048;  // foot
    case 5:
      return 1609.344;  // mile
    case 6:
      return 1.0;  // metre
    case 7:
      return 1000.0;  // kilometre
    case 8:
      return 2.54e-5;  // mil
    case 9:
      return 1e-6;  // micron
    case 10:
      return 0.01;  // centimetre
    case 11:
      return 2.54e-8;  // microinch
    default:
      return 0.0;  // 3 = named in G15; others unknown
  }
}

double unit_name_to_metres(std::string_view name) {
  std::string n;
  for (char c : name) {
    if (c != ' ') n += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (n == "m" || n == "metre" || n == "meter" || n == "metres" || n == "meters") return 1.0;
  if (n == "mm" || n == "millimetre" || n == "millimeter") return 0.001;
  if (n == "cm" || n == "centimetre" || n == "centimeter") return 0.01;
  if (n == "in" || n == "inch" || n == "inches") return 0.0254;
  if (n == "ft" || n == "foot" || n == "feet") return 0.3048;
  if (n == "km") return 1000.0;
  if (n == "mil") return 2.54e-5;
  if (n == "um" || n == "micron" || n == "mic") return 1e-6;
  if (n == "mi" || n == "mile") return 1609.344;
  if (n == "uin") return 2.54e-8;
  return 0.0;
}

}  // namespace hm

namespace hm::iges {
namespace {

double declared_factor(const IgesHeader& h, Diagnostics& diags) {
  const double by_flag = iges_unit_to_metres(h.unit_flag);
  const double by_name = unit_name_to_metres(h.unit_name);
  double unit = by_flag > 0 ? by_flag : by_name;
  if (by_flag > 0 && by_name > 0 && by_flag != by_name) {
    diags.warn("G14 unit flag " + std::to_string(h.unit_flag) + " and G15 unit name '" +
               h.unit_name + "' disagree; using the flag");
  }
  if (!(unit > 0)) {
    diags.warn("unknown unit (G14 flag " + std::to_string(h.unit_flag) + ", G15 name '" +
               h.unit_name + "'); assuming metres");
    unit = 1.0;
  }
  double scale = h.model_scale;
  if (!(scale > 0) || !std::isfinite(scale)) {
    diags.warn("G13 model scale " + std::to_string(scale) + " is not positive; using 1");
    scale = 1.0;
  }
  return unit / scale;
}

std::string metres_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g m", v);
  return buf;
}

}  // namespace

UnitReport resolve_units(const IgesHeader& header, const BBox3d& file_box,
                         const ImportOptions& options, Diagnostics& diags) {
  UnitReport r;
  r.declared_to_metres = declared_factor(header, diags);
  r.applied_to_metres = r.declared_to_metres;
  if (!options.force_units.empty()) {
    const double f = unit_name_to_metres(options.force_units);
    if (!(f > 0)) {
      throw UsageError("unknown unit '" + options.force_units +
                       "' (use one of m, mm, cm, in, ft, km)");
    }
    r.applied_to_metres = f;
    r.forced = true;
  }
  const Vec3d e = file_box.extent();
  const double extent = std::max({e.x, e.y, e.z});
  const double length = extent * r.declared_to_metres;
  if (file_box.empty() || (length >= kMinShipLength && length <= kMaxShipLength)) return r;
  r.implausible = true;
  for (const char* u : {"m", "mm", "in", "ft", "cm"}) {
    const double l = extent * unit_name_to_metres(u);
    if (l >= kMinShipLength && l <= kMaxShipLength) {
      r.suggestion = u;
      break;
    }
  }
  std::string msg = "the model is " + metres_text(length) + " long in the declared unit '" +
                    header.unit_name + "' (G14 = " + std::to_string(header.unit_flag) +
                    "), implausible for a ship (" + metres_text(kMinShipLength) + " to " +
                    metres_text(kMaxShipLength) + ")";
  if (!r.suggestion.empty()) {
    msg += "; the numbers fit '" + r.suggestion + "' (" +
           metres_text(extent * unit_name_to_metres(r.suggestion)) + ")";
  }
  msg += r.forced ? "; using the forced unit '" + options.force_units + "'"
                  : "; use --units " + (r.suggestion.empty() ? std::string("UNIT") : r.suggestion) +
                        " to override";
  diags.add(r.forced ? Severity::kNote : Severity::kWarning, 0, 0, 0, msg);
  return r;
}

}  // namespace hm::iges
