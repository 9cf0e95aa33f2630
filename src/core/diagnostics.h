// Import diagnostics: problems worth telling the user that do not stop the run. Each carries the
// IGES entity (DE number) and parameter-section line it came from, where there is one.
#pragma once

#include <string>
#include <vector>

namespace hm {

enum class Severity { kNote, kWarning, kError };

const char* to_string(Severity s);

struct Diagnostic {
  Severity severity = Severity::kWarning;
  int de = 0;           // directory-entry sequence number (odd, 1-based); 0 when not tied to one
  int line = 0;         // first parameter-section line of the entity; 0 when not known
  int entity_type = 0;  // IGES entity type number; 0 when not tied to one
  std::string message;
};

// Formats "warning: DE 37 (type 128, P line 12): message".
std::string format(const Diagnostic& d);

class Diagnostics {
 public:
  void add(Severity s, int de, int line, int entity_type, std::string message);
  void note(std::string message) { add(Severity::kNote, 0, 0, 0, std::move(message)); }
  void warn(std::string message) { add(Severity::kWarning, 0, 0, 0, std::move(message)); }
  const std::vector<Diagnostic>& items() const { return items_; }
  std::size_t count(Severity s) const;
  void append(const Diagnostics& other);

 private:
  std::vector<Diagnostic> items_;
};

}  // namespace hm
