#include "core/diagnostics.h"

#include <algorithm>

namespace hm {

const char* to_string(Severity s) {
  switch (s) {
    case Severity::kNote:
      return "note";
    case Severity::kWarning:
      return "warning";
    case Severity::kError:
      return "error";
  }
  return "?";
}

std::string format(const Diagnostic& d) {
  std::string out = to_string(d.severity);
  out += ": ";
  if (d.de > 0) {
    out += "DE " + std::to_string(d.de);
    if (d.entity_type > 0) out += " (type " + std::to_string(d.entity_type);
    if (d.line > 0)
      out += (d.entity_type > 0 ? ", " : " (") + std::string("P line ") + std::to_string(d.line);
    if (d.entity_type > 0 || d.line > 0) out += ")";
    out += ": ";
  }
  out += d.message;
  return out;
}

void Diagnostics::add(Severity s, int de, int line, int entity_type, std::string message) {
  items_.push_back({s, de, line, entity_type, std::move(message)});
}

std::size_t Diagnostics::count(Severity s) const {
  return static_cast<std::size_t>(std::count_if(
      items_.begin(), items_.end(), [s](const Diagnostic& d) { return d.severity == s; }));
}

void Diagnostics::append(const Diagnostics& other) {
  items_.insert(items_.end(), other.items_.begin(), other.items_.end());
}

}  // namespace hm
