# evoslam_module(NAME [COLD] DEPS <targets...> [TEST_DEPS <targets...>])
# Builds the library evoslam_<NAME> from the *.cc files of the calling folder (a program's
# *_main.cc excepted; COLD: the library is cold code, see below) and, with tests on,
# the test binary evoslam_<NAME>_tests from its *_test.cc files. Each module is its own target so
# that one module can be built and tested while another is being changed.
# -Wrestrict is off: GCC 12 reports false positives on std::string concatenation at -O3
# (GCC bug 105651), which would fail the -Werror build on correct code.
set(EVOSLAM_WARNINGS -Wall -Wextra -Wpedantic -Werror)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND EVOSLAM_WARNINGS -Wno-restrict)
  # In a unity build a .cc is no longer the main file, and GCC then mistakes a class that holds a
  # type of that .cc's anonymous namespace for one declared in a header.
  if(CMAKE_UNITY_BUILD)
    list(APPEND EVOSLAM_WARNINGS -Wno-subobject-linkage)
  endif()
  # The sanitizers' instrumentation defeats GCC's flow analysis, which then reports variables
  # inside libstdc++ (std::regex, std::function) as maybe used uninitialized.
  if(EVOSLAM_SANITIZE)
    list(APPEND EVOSLAM_WARNINGS -Wno-maybe-uninitialized)
  endif()
endif()
# Cold code: test binaries (set-up and assertions), the programs' mains and the command line's
# commands (argument parsing, messages). What they run that is hot lives in the libraries, which
# keep the build type's optimisation. Cold code compiles at -Og in optimised and sanitizer builds:
# test units then take 40 % less time to compile than at -O3 (they are half of a Release build),
# and in the sanitizer build half of what -O1 takes (CLI11, header-only, costs some 30 s per file
# that builds a CLI::App at -O1 with the sanitizers). A Debug build keeps -O0 for the debugger.
set(EVOSLAM_COLD_OPTIONS ${EVOSLAM_WARNINGS})
if(EVOSLAM_SANITIZE OR CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo|MinSizeRel)$")
  list(APPEND EVOSLAM_COLD_OPTIONS -Og)
endif()
# ctest runs test binaries side by side; OpenMP threads that spin while waiting would then steal
# the cores the other binary's threads need and slow both by an order of magnitude.
set(EVOSLAM_TEST_ENVIRONMENT "OMP_WAIT_POLICY=PASSIVE")
set(EVOSLAM_DATA_DIR "${CMAKE_SOURCE_DIR}/../shared/data" CACHE PATH
    "Folder of the real laser logs; tests that need it skip when it is absent")

function(evoslam_module NAME)
  cmake_parse_arguments(ARG "COLD" "" "DEPS;TEST_DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*.cc")
  file(GLOB tests CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*_test.cc")
  file(GLOB mains CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*_main.cc")
  if(tests OR mains)
    list(REMOVE_ITEM sources ${tests} ${mains})
  endif()
  set(target evoslam_${NAME})
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  if(sources AND ARG_COLD)
    target_compile_options(${target} PRIVATE ${EVOSLAM_COLD_OPTIONS})
  elseif(sources)
    target_compile_options(${target} PRIVATE ${EVOSLAM_WARNINGS})
  endif()
  if(EVOSLAM_BUILD_TESTS AND tests)
    add_executable(${target}_tests ${tests})
    target_compile_options(${target}_tests PRIVATE ${EVOSLAM_COLD_OPTIONS})
    target_compile_definitions(${target}_tests PRIVATE
      EVOSLAM_DATA_DIR="${EVOSLAM_DATA_DIR}"
      EVOSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
    target_link_libraries(${target}_tests PRIVATE ${target} ${ARG_TEST_DEPS} GTest::gtest GTest::gtest_main GTest::gmock)
    list(LENGTH tests files)
    evoslam_add_gtests(${target}_tests SHARDS ${files})
  endif()
endfunction()

# evoslam_add_gtests(TARGET SHARDS <n> [TIMEOUT <s>] [COST <c>] [LABELS <labels...>])
# Registers a gtest binary with ctest. Each gtest test is a ctest test of its own, so that one can
# be run, timed and reported alone; TIMEOUT applies to each. The sanitizer pass instead runs the
# binary as <n> processes that split its tests with gtest's sharding: a sanitized process takes
# 0.1 s to start, and one per test made a fifth of that pass. A shard's timeout is 10 minutes;
# COST makes ctest start the longest binaries' shards first, so none of them trails at the end.
function(evoslam_add_gtests target)
  cmake_parse_arguments(ARG "" "SHARDS;TIMEOUT;COST" "LABELS" ${ARGN})
  if(NOT EVOSLAM_SANITIZE)
    set(properties ENVIRONMENT ${EVOSLAM_TEST_ENVIRONMENT})
    if(ARG_TIMEOUT)
      list(APPEND properties TIMEOUT ${ARG_TIMEOUT})
    endif()
    if(ARG_LABELS)
      list(APPEND properties LABELS ${ARG_LABELS})
    endif()
    gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
    return()
  endif()
  if(NOT ARG_COST)
    set(ARG_COST 0)
  endif()
  math(EXPR last "${ARG_SHARDS} - 1")
  foreach(shard RANGE ${last})
    set(name "${target}/${shard}")
    add_test(NAME ${name} COMMAND ${target} --gtest_brief=1)
    set_tests_properties(${name} PROPERTIES TIMEOUT 600 COST ${ARG_COST}
      ENVIRONMENT "${EVOSLAM_TEST_ENVIRONMENT};GTEST_TOTAL_SHARDS=${ARG_SHARDS};GTEST_SHARD_INDEX=${shard}")
    if(ARG_LABELS)
      set_tests_properties(${name} PROPERTIES LABELS "${ARG_LABELS}")
    endif()
  endforeach()
endfunction()
