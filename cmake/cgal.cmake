# CGAL 5.5 (Debian: libcgal-dev, header-only; provides CGAL::CGAL, adds -frounding-math) and
# Eigen 3 (libeigen3-dev; the Garland-Heckbert policies need it). Optional: sets
# MESHDEV_CGAL_FOUND. Include after openmesh.cmake: CGAL's FindOpenMesh.cmake would otherwise
# shadow OpenMesh's config file (../shared/research/simplifiers.md §1).
if(NOT TARGET CGAL::CGAL)
  find_package(CGAL QUIET)
endif()
if(NOT TARGET Eigen3::Eigen)
  find_package(Eigen3 3.3 QUIET NO_MODULE)
endif()
if(TARGET CGAL::CGAL AND TARGET Eigen3::Eigen)
  set(MESHDEV_CGAL_FOUND TRUE)
else()
  set(MESHDEV_CGAL_FOUND FALSE)
endif()
