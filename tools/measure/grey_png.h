// 8-bit grey images and their PNG files (libpng's simplified API): the
// pictures `srcodec render` writes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "format/status.h"

namespace srcodec {

struct GreyImage {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;  // row by row from the top, 0 black, 255 white

  GreyImage() = default;
  GreyImage(int w, int h, uint8_t fill) : width(w), height(h), pixels(static_cast<size_t>(w) * h, fill) {}
  uint8_t& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
  uint8_t at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

// The image as PNG bytes; kInternal when libpng fails.
StatusOr<std::string> grey_png_bytes(const GreyImage& image);

// Writes the PNG beside `path` and renames it into place
// (write_file_atomically): a failure leaves no partial file.
Status write_grey_png(const GreyImage& image, const std::string& path);

}  // namespace srcodec
