# cnclab_module(NAME SOURCES ... DEPENDS ...): one library target per module,
# cnclab_<NAME>, exporting src/ as include root ("cnclab/<module>/x.hpp").
function(cnclab_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_library(cnclab_${name} STATIC ${ARG_SOURCES})
  add_library(cnclab::${name} ALIAS cnclab_${name})
  target_include_directories(cnclab_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(cnclab_${name} PUBLIC ${ARG_DEPENDS} PRIVATE cnclab_warnings)
endfunction()

# cnclab_test(NAME SOURCES ... DEPENDS ...): one GoogleTest executable,
# registered with ctest test by test.
function(cnclab_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} GTest::gtest GTest::gtest_main cnclab_warnings)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_compile_definitions(${name} PRIVATE
    CNCLAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    CNCLAB_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
endfunction()
