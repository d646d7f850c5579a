# OpenMesh 9.0 (Debian: libopenmesh-dev). Plain target names OpenMeshCore / OpenMeshTools.
# CONFIG and no version: the package ships no version file, and CGAL's FindOpenMesh.cmake
# would otherwise shadow the config file (see ../shared/research/simplifiers.md §1).
if(NOT TARGET OpenMeshCore)
  find_package(OpenMesh CONFIG REQUIRED)
endif()
