# Installation and the CMake package: `find_package(meshdev)` gives meshdev::metric, meshdev::io
# and meshdev::testing (the header-only GoogleTest assertions, harness/testing/). Headers go to
# <prefix>/include/meshdev/ keeping their folders (#include "metric/compare.h"); the meshdev
# program and harness/plot/plot_curves.py (which `meshdev plot` finds in ../share/meshdev) too.
# The simplifier backends and the harness are not exported: they are the program's parts.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(MESHDEV_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/meshdev")
set(MESHDEV_INSTALL_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}/meshdev")

foreach(target meshdev_metric meshdev_io meshdev_testing)
  target_include_directories(${target} INTERFACE $<INSTALL_INTERFACE:${MESHDEV_INSTALL_INCLUDEDIR}>)
endforeach()
set_target_properties(meshdev_metric PROPERTIES EXPORT_NAME metric)
set_target_properties(meshdev_io PROPERTIES EXPORT_NAME io)
set_target_properties(meshdev_testing PROPERTIES EXPORT_NAME testing)
# The testing target needs GoogleTest only where it is used (the consumer finds GTest).
target_link_libraries(meshdev_testing INTERFACE $<INSTALL_INTERFACE:GTest::gtest>)

install(TARGETS meshdev_metric meshdev_io meshdev_testing
        EXPORT meshdevTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/metric DESTINATION ${MESHDEV_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_SOURCE_DIR}/harness/testing/deviation_assertions.h
        DESTINATION ${MESHDEV_INSTALL_INCLUDEDIR}/harness/testing)
install(EXPORT meshdevTargets NAMESPACE meshdev:: DESTINATION ${MESHDEV_INSTALL_CMAKEDIR})

if(TARGET meshdev)
  install(TARGETS meshdev RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(PROGRAMS ${PROJECT_SOURCE_DIR}/harness/plot/plot_curves.py
          DESTINATION ${CMAKE_INSTALL_DATADIR}/meshdev)
endif()

file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/meshdevConfig.cmake.in [=[
@PACKAGE_INIT@
include(CMakeFindDependencyMacro)
find_dependency(OpenMP COMPONENTS CXX)
find_dependency(nlohmann_json 3)
# The static libraries name these private, header-only dependencies in their link interface
# ($<LINK_ONLY:...>); nothing of them is linked, so an empty stand-in is enough.
if(NOT TARGET stb::stb)
  add_library(stb::stb INTERFACE IMPORTED)
endif()
# meshdev::testing links GTest::gtest; find it only when the consumer has GoogleTest.
find_package(GTest QUIET)
include("${CMAKE_CURRENT_LIST_DIR}/meshdevTargets.cmake")
check_required_components(meshdev)
]=])
configure_package_config_file(${CMAKE_CURRENT_BINARY_DIR}/meshdevConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/meshdevConfig.cmake
                              INSTALL_DESTINATION ${MESHDEV_INSTALL_CMAKEDIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/meshdevConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/meshdevConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/meshdevConfigVersion.cmake
        DESTINATION ${MESHDEV_INSTALL_CMAKEDIR})
