#include "tools/measure/grey_png.h"

#include <png.h>

#include "format/file_io.h"

namespace srcodec {

StatusOr<std::string> grey_png_bytes(const GreyImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height))
    return invalid_argument("PNG: the image has no pixels or the wrong number of them");
  // The simplified API reports errors in `png.message` instead of by longjmp.
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_GRAY;
  png_alloc_size_t size = 0;
  if (!png_image_write_get_memory_size(png, size, 0, image.pixels.data(), image.width, nullptr))
    return internal_error(std::string("PNG: libpng cannot size the file: ") + png.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), image.width, nullptr))
    return internal_error(std::string("PNG: libpng failed: ") + png.message);
  bytes.resize(size);
  return bytes;
}

Status write_grey_png(const GreyImage& image, const std::string& path) {
  SRCODEC_ASSIGN_OR_RETURN(const std::string bytes, grey_png_bytes(image));
  return write_file_atomically(path, bytes);
}

}  // namespace srcodec
