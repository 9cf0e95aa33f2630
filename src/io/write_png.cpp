#include "io/write_png.h"

#include <png.h>

#include <cstring>
#include <ostream>

#include "core/error.h"
#include "io/atomic_file.h"

namespace hm {

std::vector<std::uint8_t> encode_png(std::uint32_t width, std::uint32_t height,
                                     std::span<const std::uint8_t> rgb) {
  if (width == 0 || height == 0 || rgb.size() != std::size_t{width} * height * 3) {
    throw IoError("PNG: " + std::to_string(rgb.size()) + " bytes do not make a " +
                  std::to_string(width) + " x " + std::to_string(height) + " RGB picture");
  }
  // The simplified API keeps libpng's setjmp/longjmp error handling inside libpng, so no C++
  // frame is jumped over; failures come back as a return value and image.message.
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  const png_int_32 stride = static_cast<png_int_32>(width) * 3;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, rgb.data(), stride, nullptr)) {
    throw IoError(std::string("PNG: libpng failed: ") + image.message);
  }
  std::vector<std::uint8_t> bytes(size);
  if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, rgb.data(), stride, nullptr)) {
    throw IoError(std::string("PNG: libpng failed: ") + image.message);
  }
  bytes.resize(size);
  return bytes;
}

void write_png(const std::string& path, std::uint32_t width, std::uint32_t height,
               std::span<const std::uint8_t> rgb) {
  const std::vector<std::uint8_t> bytes = encode_png(width, height, rgb);
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
  });
}

}  // namespace hm
