// Legends under a rendered picture, and the tiny bitmap font they are written in.
//
// The font is 3 x 5 cells per glyph (drawn `scale` pixels per cell, advancing 4 cells): digits,
// '.', '-', '+', '_', ':', '/', ' ', 'e' (for exponents) and the letters, drawn upper case.
// Anything else draws as a blank.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "io/render_view.h"

namespace hm {

// Cell size in pixels for legend text on a picture of this width (2 to 6).
int legend_scale(std::uint32_t width);
// Width in pixels of text at scale (no trailing gap).
int text_width(std::string_view text, int scale);
// Draws text with its top-left corner at (x, y); pixels outside the image are skipped.
void draw_text(RgbImage& img, int x, int y, std::string_view text, int scale, Rgb8 colour);
// A number as legends print it: 3 significant digits, "e" exponents when large or small.
std::string legend_number(double v);

// Appends a strip below the picture: the title, the colour bar of sequential_colour from
// range.lo (left) to range.hi (right), and the numbers at its ends and middle. Pixel column
// bar_x + k of the bar's rows shows sequential_colour((k + 0.5) / bar_width).
void append_scalar_legend(RgbImage& img, std::string_view title, const ScalarRange& range);

struct LegendEntry {
  std::string label;
  Rgb8 colour;
};
// Appends a strip below the picture: the title, then a swatch and label per entry, wrapped onto
// as many lines as the width needs; `more` adds "..." after the last entry.
void append_swatch_legend(RgbImage& img, std::string_view title,
                          std::span<const LegendEntry> entries, bool more);

}  // namespace hm
