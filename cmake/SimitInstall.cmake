# Installation: headers (sources and generated .inc), the libraries, the tools,
# and a CMake package so that another project can `find_package(Simit CONFIG)`
# and link `Simit::MLIRSimitDialect` without the frontend or runtime.
include(CMakePackageConfigHelpers)

set(SIMIT_INSTALL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/simit)

install(DIRECTORY ${SIMIT_SOURCE_DIR}/include/simit
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h" PATTERN "*.td")
install(DIRECTORY ${SIMIT_BINARY_DIR}/include/simit
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.inc")

# Every library and tool by name: a name that is no target is a configure
# error, not a library silently left out of the install.
install(TARGETS MLIRSimitDialect MLIRSimitTransforms SimitFrontend SimitIRGen
    SimitRuntime SimitRuntimeABI SimitEngine
  EXPORT SimitTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS simit-opt simit-translate simit-run
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(EXPORT SimitTargets
  NAMESPACE Simit::
  DESTINATION ${SIMIT_INSTALL_CMAKE_DIR})

configure_package_config_file(
  ${SIMIT_SOURCE_DIR}/cmake/SimitConfig.cmake.in
  ${SIMIT_BINARY_DIR}/SimitConfig.cmake
  INSTALL_DESTINATION ${SIMIT_INSTALL_CMAKE_DIR})
write_basic_package_version_file(
  ${SIMIT_BINARY_DIR}/SimitConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${SIMIT_BINARY_DIR}/SimitConfig.cmake
  ${SIMIT_BINARY_DIR}/SimitConfigVersion.cmake
  DESTINATION ${SIMIT_INSTALL_CMAKE_DIR})
