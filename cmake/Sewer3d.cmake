# Helpers that keep module targets uniform and the layers enforced.
#
# Each module folder src/sewer3d/<name> is one library `sewer3d_<name>`; its DEPS state which
# lower modules it may use. A target sees only the headers of the modules it links: each
# module publishes its own include root (build/include_roots/<name>/sewer3d/<name> -> the
# folder), so `#include "sewer3d/sim/renderer.hpp"` in a module that does not link sewer3d_sim
# fails to compile. tests/check_layers.py checks the same rules over every file (CTest
# layers/*), including headers no target compiles on its own.

set(SEWER3D_LAYERS_FILE ${PROJECT_BINARY_DIR}/layers.txt)
file(WRITE ${SEWER3D_LAYERS_FILE} "")

# The include root that exposes src/sewer3d/<folder> as "sewer3d/<folder>/...".
function(sewer3d_include_root target folder)
  set(root ${PROJECT_BINARY_DIR}/include_roots/${folder})
  if(NOT EXISTS ${root}/sewer3d/${folder})
    file(MAKE_DIRECTORY ${root}/sewer3d)
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/src/sewer3d/${folder} ${root}/sewer3d/${folder} SYMBOLIC)
  endif()
  target_include_directories(${target} PUBLIC ${root})
endfunction()

# One line per target for tests/check_layers.py: KIND TARGET FOLDER SOURCES... -- LINKED...
function(sewer3d_record_layer kind target folder)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  set(sources "")
  foreach(s ${ARG_SOURCES})
    get_filename_component(abs ${s} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
    file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${abs})
    list(APPEND sources ${rel})
  endforeach()
  set(linked "")
  foreach(d ${ARG_DEPS})
    if(d MATCHES "^sewer3d_(.+)$")
      list(APPEND linked ${CMAKE_MATCH_1})
    endif()
  endforeach()
  string(REPLACE ";" " " sources "${sources}")
  string(REPLACE ";" " " linked "${linked}")
  file(APPEND ${SEWER3D_LAYERS_FILE} "${kind} ${target} ${folder} ${sources} -- ${linked}\n")
endfunction()

# sewer3d_module(NAME SOURCES ... [DEPS ...])
function(sewer3d_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(sewer3d_${name} STATIC ${ARG_SOURCES})
  sewer3d_include_root(sewer3d_${name} ${name})
  target_link_libraries(sewer3d_${name} PUBLIC ${ARG_DEPS})
  sewer3d_record_layer(module sewer3d_${name} ${name} SOURCES ${ARG_SOURCES} DEPS ${ARG_DEPS})
endfunction()

# sewer3d_test(MODULE NAME SOURCES ... [DEPS ...]) -> CTest test "MODULE/NAME".
# A unit test links its own module and the test-support library sewer3d_testing. A test that
# needs the simulator (rendered images, simulated runs) is named *_sim_test.cpp and may add
# sewer3d_sim or sewer3d_simio to
# DEPS; other sewer3d_* DEPS are refused by tests/check_layers.py. Third-party DEPS are free.
function(sewer3d_test module name)
  if(NOT SEWER3D_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  set(target test_${module}_${name})
  add_executable(${target} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE sewer3d_${module} sewer3d_testing ${ARG_DEPS}
                                          GTest::gtest GTest::gtest_main)
  target_compile_definitions(${target} PRIVATE
    SEWER3D_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data")
  add_test(NAME ${module}/${name} COMMAND ${target})
  sewer3d_record_layer(test ${target} ${module} SOURCES ${ARG_SOURCES}
                       DEPS sewer3d_${module} sewer3d_testing ${ARG_DEPS})
endfunction()
