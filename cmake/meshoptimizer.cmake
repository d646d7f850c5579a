# meshoptimizer 0.18 (Debian: libmeshoptimizer-dev). Provides meshoptimizer::meshoptimizer.
# Optional: sets MESHDEV_MESHOPT_FOUND; the meshopt backends are listed as unavailable without it.
if(NOT TARGET meshoptimizer::meshoptimizer)
  find_package(meshoptimizer CONFIG QUIET)
endif()
set(MESHDEV_MESHOPT_FOUND ${meshoptimizer_FOUND})
