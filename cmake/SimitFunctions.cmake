include(GNUInstallDirs)

# Installed libraries and tools find the project's libraries beside them
# ($ORIGIN), and libMLIR, which Debian keeps out of the loader's path, in
# LLVM's library folder.
set(SIMIT_INSTALL_LIBRARY_RPATH "\$ORIGIN;${LLVM_LIBRARY_DIR}")
set(SIMIT_INSTALL_TOOL_RPATH "\$ORIGIN/../${CMAKE_INSTALL_LIBDIR};${LLVM_LIBRARY_DIR}")

# simit_add_library(<name> <sources>... [DEPENDS <targets>...] [LINK <libs>...])
#
# A shared library of the project. Every library links the shared libMLIR and
# libLLVM (never the static component archives), so the build stays small and
# one copy of LLVM's global state exists in every process.
function(simit_add_library name)
  cmake_parse_arguments(ARG "" "" "DEPENDS;LINK" ${ARGN})
  add_library(${name} SHARED ${ARG_UNPARSED_ARGUMENTS})
  if(ARG_DEPENDS)
    add_dependencies(${name} ${ARG_DEPENDS})
  endif()
  target_link_libraries(${name} PUBLIC ${ARG_LINK} MLIR LLVM)
  target_include_directories(${name} PUBLIC
    $<BUILD_INTERFACE:${SIMIT_SOURCE_DIR}/include>
    $<BUILD_INTERFACE:${SIMIT_BINARY_DIR}/include>
    $<INSTALL_INTERFACE:include>)
  # Users of an installed library need MLIR's and LLVM's headers too.
  target_include_directories(${name} SYSTEM PUBLIC
    ${LLVM_INCLUDE_DIRS} ${MLIR_INCLUDE_DIRS})
  set_target_properties(${name} PROPERTIES
    EXPORT_NAME ${name}
    BUILD_RPATH "${CMAKE_BINARY_DIR}/lib"
    INSTALL_RPATH "${SIMIT_INSTALL_LIBRARY_RPATH}")
endfunction()

# simit_add_tool(<name> <sources>... [LINK <libs>...])
function(simit_add_tool name)
  cmake_parse_arguments(ARG "" "" "LINK" ${ARGN})
  add_executable(${name} ${ARG_UNPARSED_ARGUMENTS})
  target_link_libraries(${name} PRIVATE ${ARG_LINK} MLIR LLVM)
  set_target_properties(${name} PROPERTIES
    INSTALL_RPATH "${SIMIT_INSTALL_TOOL_RPATH}")
endfunction()
