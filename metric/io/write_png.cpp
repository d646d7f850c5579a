#include "metric/io/write_png.h"

#include <ostream>

#include "metric/errors.h"
#include "metric/io/atomic_file.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace meshdev {
namespace {

void append(void* context, void* data, int size) {
  auto* out = static_cast<std::ostream*>(context);
  out->write(static_cast<const char*>(data), size);
}

}  // namespace

void write_png(const std::string& path, const Image& image) {
  if (image.empty()) throw InvalidInput(path + ": cannot write an empty image");
  write_file_atomically(path, [&](std::ostream& out) {
    if (stbi_write_png_to_func(append, &out, image.width, image.height, 3, image.rgb.data(),
                               image.width * 3) == 0)
      throw WriteError(path + ": PNG encoding failed");
  });
}

}  // namespace meshdev
