# Embree 3 (Debian 12: libembree-dev 3.13.5, which pulls libtbb-dev). Optional: sets
# MESHDEV_EMBREE_FOUND and provides the imported target `embree` (include dirs + libembree3.so).
# Only the peer comparison (bench/peers, MESHDEV_BUILD_PEERS=ON) uses it; meshdev itself never
# links Embree. Install: apt-get install -y libembree-dev libcgal-dev libtbb-dev
if(NOT TARGET embree)
  find_package(embree 3 QUIET)
endif()
if(TARGET embree)
  set(MESHDEV_EMBREE_FOUND TRUE)
else()
  set(MESHDEV_EMBREE_FOUND FALSE)
endif()
