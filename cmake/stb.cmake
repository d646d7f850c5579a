# stb (Debian: libstb-dev) header-only image libraries. Provides stb::stb (include path only); the
# implementations are compiled once, in metric/texture_image.cpp (stb_image) and
# metric/io/write_png.cpp (stb_image_write).
if(NOT TARGET stb::stb)
  find_path(STB_INCLUDE_DIR stb/stb_image.h PATHS /usr/include REQUIRED)
  add_library(stb::stb INTERFACE IMPORTED)
  target_include_directories(stb::stb SYSTEM INTERFACE "${STB_INCLUDE_DIR}")
endif()
