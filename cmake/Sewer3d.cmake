# Helpers that keep module targets uniform. Each module folder under src/sewer3d
# is one library `sewer3d_<name>`; its link list states which lower modules it may use.

# sewer3d_module(NAME SOURCES ... [DEPS ...])
function(sewer3d_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(sewer3d_${name} STATIC ${ARG_SOURCES})
  target_include_directories(sewer3d_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(sewer3d_${name} PUBLIC ${ARG_DEPS})
endfunction()

# sewer3d_test(MODULE NAME SOURCES ... [DEPS ...]) -> CTest test "MODULE/NAME"
function(sewer3d_test module name)
  if(NOT SEWER3D_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  set(target test_${module}_${name})
  add_executable(${target} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE sewer3d_${module} ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${target} PRIVATE
    SEWER3D_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data")
  add_test(NAME ${module}/${name} COMMAND ${target})
endfunction()
