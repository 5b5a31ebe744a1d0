include(GNUInstallDirs)

# Installed libraries and tools find the project's libraries beside them
# ($ORIGIN), and libMLIR, which Debian keeps out of the loader's path, in
# LLVM's library folder.
set(SIMIT_INSTALL_LIBRARY_RPATH "\$ORIGIN;${LLVM_LIBRARY_DIR}")
set(SIMIT_INSTALL_TOOL_RPATH "\$ORIGIN/../${CMAKE_INSTALL_LIBDIR};${LLVM_LIBRARY_DIR}")

# simit_add_library(<name> <sources>... [NO_MLIR] [DEPENDS <targets>...]
#                   [LINK <libs>...])
#
# A shared library of the project. Every library links the shared libLLVM,
# and those that use MLIR the shared libMLIR (never the static component
# archives), so the build stays small and one copy of LLVM's global state
# exists in every process. NO_MLIR: the library uses LLVM's support library
# only (the frontend, the runtime), so neither it nor its users link MLIR.
function(simit_add_library name)
  cmake_parse_arguments(ARG "NO_MLIR" "" "DEPENDS;LINK" ${ARGN})
  add_library(${name} SHARED ${ARG_UNPARSED_ARGUMENTS})
  if(ARG_DEPENDS)
    add_dependencies(${name} ${ARG_DEPENDS})
  endif()
  if(ARG_NO_MLIR)
    target_link_libraries(${name} PUBLIC ${ARG_LINK} LLVM)
  else()
    target_link_libraries(${name} PUBLIC ${ARG_LINK} MLIR LLVM)
  endif()
  target_include_directories(${name} PUBLIC
    $<BUILD_INTERFACE:${SIMIT_SOURCE_DIR}/include>
    $<BUILD_INTERFACE:${SIMIT_BINARY_DIR}/include>
    $<INSTALL_INTERFACE:include>)
  # Users of an installed library need LLVM's (and MLIR's) headers too.
  target_include_directories(${name} SYSTEM PUBLIC ${LLVM_INCLUDE_DIRS})
  if(NOT ARG_NO_MLIR)
    target_include_directories(${name} SYSTEM PUBLIC ${MLIR_INCLUDE_DIRS})
  endif()
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
