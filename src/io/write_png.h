// PNG output of 8-bit RGB pictures (libpng's simplified API).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace hm {

// The PNG bytes of a width x height picture; rgb holds 3 bytes per pixel, row-major from the top
// row. Throws IoError when the sizes do not match or libpng fails. The same pixels give the same
// bytes (no time stamp).
std::vector<std::uint8_t> encode_png(std::uint32_t width, std::uint32_t height,
                                     std::span<const std::uint8_t> rgb);

// Writes the picture to path atomically (io/atomic_file.h): a failed write leaves the old file
// or none, never a partial one. Throws IoError naming the path.
void write_png(const std::string& path, std::uint32_t width, std::uint32_t height,
               std::span<const std::uint8_t> rgb);

}  // namespace hm
