#include "io/render_legend.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace hm {
namespace {

// A glyph is 5 rows of 3 bits, the top row first, the high bit the left cell.
struct Glyph {
  char c;
  std::uint8_t rows[5];
};

constexpr Glyph kFont[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}},
    {'+', {0, 2, 7, 2, 0}}, {'_', {0, 0, 0, 0, 7}}, {':', {0, 2, 0, 2, 0}}, {'/', {1, 1, 2, 4, 4}},
    {'e', {0, 2, 7, 4, 3}}, {'A', {2, 5, 7, 5, 5}}, {'B', {6, 5, 6, 5, 6}}, {'C', {3, 4, 4, 4, 3}},
    {'D', {6, 5, 5, 5, 6}}, {'E', {7, 4, 6, 4, 7}}, {'F', {7, 4, 6, 4, 4}}, {'G', {3, 4, 5, 5, 3}},
    {'H', {5, 5, 7, 5, 5}}, {'I', {7, 2, 2, 2, 7}}, {'J', {1, 1, 1, 5, 2}}, {'K', {5, 5, 6, 5, 5}},
    {'L', {4, 4, 4, 4, 7}}, {'M', {5, 7, 7, 5, 5}}, {'N', {6, 5, 5, 5, 5}}, {'O', {2, 5, 5, 5, 2}},
    {'P', {6, 5, 6, 4, 4}}, {'Q', {2, 5, 5, 6, 3}}, {'R', {6, 5, 6, 5, 5}}, {'S', {3, 4, 2, 1, 6}},
    {'T', {7, 2, 2, 2, 2}}, {'U', {5, 5, 5, 5, 7}}, {'V', {5, 5, 5, 5, 2}}, {'W', {5, 5, 7, 7, 5}},
    {'X', {5, 5, 2, 5, 5}}, {'Y', {5, 5, 2, 2, 2}}, {'Z', {7, 1, 2, 4, 7}},
};

const Glyph* find_glyph(char c) {
  // 'e' keeps its own lower-case glyph (exponents); other letters draw upper case.
  if (c != 'e') c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kFont) {
    if (g.c == c) return &g;
  }
  return nullptr;
}

constexpr Rgb8 kText{30, 30, 30};

// Titles in capitals: the font's lower-case 'e' is kept for exponents.
std::string capitals(std::string_view text) {
  std::string s(text);
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

void fill_rect(RgbImage& img, int x0, int y0, int w, int h, Rgb8 c) {
  for (int y = std::max(0, y0); y < std::min<int>(img.height, y0 + h); ++y) {
    for (int x = std::max(0, x0); x < std::min<int>(img.width, x0 + w); ++x) {
      img.set(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), c);
    }
  }
}

// Adds `rows` rows of background below the picture; returns the first new row.
int grow(RgbImage& img, int rows) {
  const int first = static_cast<int>(img.height);
  img.height += static_cast<std::uint32_t>(rows);
  img.rgb.resize(std::size_t{img.width} * img.height * 3, 255);
  return first;
}

}  // namespace

int legend_scale(std::uint32_t width) { return std::clamp(static_cast<int>(width / 500), 2, 6); }

int text_width(std::string_view text, int scale) {
  return text.empty() ? 0 : (4 * static_cast<int>(text.size()) - 1) * scale;
}

void draw_text(RgbImage& img, int x, int y, std::string_view text, int scale, Rgb8 colour) {
  for (char c : text) {
    if (const Glyph* g = find_glyph(c)) {
      for (int r = 0; r < 5; ++r) {
        for (int k = 0; k < 3; ++k) {
          if (g->rows[r] & (4 >> k))
            fill_rect(img, x + k * scale, y + r * scale, scale, scale, colour);
        }
      }
    }
    x += 4 * scale;
  }
}

std::string legend_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void append_scalar_legend(RgbImage& img, std::string_view title, const ScalarRange& range) {
  const int s = legend_scale(img.width);
  const int bar_h = 6 * s;
  const int y0 = grow(img, 26 * s) + 3 * s;
  const int x0 = 4 * s;
  draw_text(img, x0, y0, capitals(title), s, kText);
  const int bar_y = y0 + 7 * s;
  const int bar_w = std::max(1, std::min(static_cast<int>(img.width) - 8 * s, 300 * s));
  for (int k = 0; k < bar_w; ++k) {
    fill_rect(img, x0 + k, bar_y, 1, bar_h, sequential_colour((k + 0.5) / bar_w));
  }
  // Ticks and numbers at both ends and the middle.
  const int num_y = bar_y + bar_h + 2 * s;
  const double values[3] = {range.lo, 0.5 * (range.lo + range.hi), range.hi};
  for (int i = 0; i < 3; ++i) {
    const int tx = x0 + (i == 2 ? bar_w - 1 : i * (bar_w / 2));
    fill_rect(img, tx, bar_y + bar_h, 1, s, kText);
    const std::string text = range.valid ? legend_number(values[i]) : std::string("-");
    const int w = text_width(text, s);
    const int left = i == 0 ? x0 : (i == 1 ? tx - w / 2 : tx + 1 - w);
    draw_text(img, left, num_y + s, text, s, kText);
  }
}

void append_swatch_legend(RgbImage& img, std::string_view title,
                          std::span<const LegendEntry> entries, bool more) {
  const int s = legend_scale(img.width);
  const int margin = 4 * s, line_h = 8 * s, swatch = 5 * s;
  const int right = static_cast<int>(img.width) - margin;
  // Lay out first (title, then entries and "..."), to know how many lines to add.
  struct Item {
    int x, line;
    const LegendEntry* entry;  // nullptr: the "..." after the last entry
  };
  std::vector<Item> items;
  int x = margin + text_width(title, s) + 4 * s, line = 0;
  auto place = [&](int w, const LegendEntry* e) {
    if (x + w > right && x > margin) {
      ++line;
      x = margin;
    }
    items.push_back({x, line, e});
    x += w + 4 * s;
  };
  for (const LegendEntry& e : entries) place(swatch + 2 * s + text_width(e.label, s), &e);
  if (more) place(text_width("...", s), nullptr);
  const int y0 = grow(img, (line + 1) * line_h + 3 * s) + 2 * s;
  draw_text(img, margin, y0 + s, capitals(title), s, kText);
  for (const Item& it : items) {
    const int y = y0 + it.line * line_h;
    if (!it.entry) {
      draw_text(img, it.x, y + s, "...", s, kText);
      continue;
    }
    fill_rect(img, it.x, y, swatch, swatch + 2 * s, kText);
    fill_rect(img, it.x + s / 2, y + s / 2, swatch - s / 2 * 2, swatch + 2 * s - s / 2 * 2,
              it.entry->colour);
    draw_text(img, it.x + swatch + 2 * s, y + s, capitals(it.entry->label), s, kText);
  }
}

}  // namespace hm
