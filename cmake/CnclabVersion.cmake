# The git commit is embedded at build time (re-read on every build, so a new
# commit never leaves a stale hash in result files).
configure_file(${PROJECT_SOURCE_DIR}/cmake/write_build_info.cmake.in
               ${PROJECT_BINARY_DIR}/write_build_info.cmake @ONLY)
add_custom_target(cnclab_build_info
  COMMAND ${CMAKE_COMMAND} -P ${PROJECT_BINARY_DIR}/write_build_info.cmake
  BYPRODUCTS ${PROJECT_BINARY_DIR}/generated/cnclab/build_info.hpp
  COMMENT "Embedding git commit")
