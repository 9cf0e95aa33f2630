// Directory-entry (D section) fields: two 80-column records of 8-column fields per entity.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "iges/iges_records.h"

namespace hm::iges {

struct DirEntry {
  int type = 0;
  int param_line = 0;   // first P line (1-based sequence number within the P section)
  int param_count = 0;  // number of P lines
  int structure = 0;
  int line_font = 0;
  int level = 0;
  int view = 0;
  int transform = 0;  // DE number of a 124 entity, 0 = none
  int label_display = 0;
  int line_weight = 0;
  int color = 0;
  int form = 0;
  // Status number digits: blank (0 visible, 1 blanked), subordinate switch (0 independent,
  // 1 physically dependent, 2 logically dependent, 3 both), use flag (0 geometry, 1 annotation,
  // 2 definition, 3 other, 4 logical/positional, 5 2D parametric, 6 construction), hierarchy.
  int blank = 0;
  int subordinate = 0;
  int use = 0;
  int hierarchy = 0;
  std::string label;  // blanks trimmed
  int subscript = 0;
  int de = 0;  // this entry's DE number (odd)
};

// Parses the directory. Throws IgesError naming the D line for unreadable type, pointer, count
// and form fields, and for P pointers outside the P section (p_lines lines).
std::vector<DirEntry> parse_directory(const std::vector<Record>& d, std::size_t p_lines,
                                      const std::string& source);

}  // namespace hm::iges
