#pragma once
// PNG writer (stb_image_write, Debian's libstb-dev) through write_file_atomically.
#include <string>

#include "metric/texture_image.h"

namespace meshdev {

// Writes `image` as an 8-bit RGB PNG. Throws InvalidInput for an empty image and WriteError on
// any failed write (earlier contents of `path` stay intact). O(pixels).
void write_png(const std::string& path, const Image& image);

}  // namespace meshdev
