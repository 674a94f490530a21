# evoslam_module(NAME DEPS <targets...>)
# Builds the library evoslam_<NAME> from the *.cc files of the calling folder (a program's
# *_main.cc excepted) and, with tests on,
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
# Test binaries' own code is set-up and assertions; what they exercise runs in the libraries. In
# the sanitizer build they compile at -Og, which halves their compile time against -O1 without
# slowing the libraries' hot loops.
set(EVOSLAM_TEST_OPTIONS ${EVOSLAM_WARNINGS})
if(EVOSLAM_SANITIZE)
  list(APPEND EVOSLAM_TEST_OPTIONS -Og)
endif()
# ctest runs test binaries side by side; OpenMP threads that spin while waiting would then steal
# the cores the other binary's threads need and slow both by an order of magnitude.
set(EVOSLAM_TEST_ENVIRONMENT "OMP_WAIT_POLICY=PASSIVE")
set(EVOSLAM_DATA_DIR "${CMAKE_SOURCE_DIR}/../shared/data" CACHE PATH
    "Folder of the real laser logs; tests that need it skip when it is absent")

function(evoslam_module NAME)
  cmake_parse_arguments(ARG "" "" "DEPS;TEST_DEPS" ${ARGN})
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
  if(sources)
    target_compile_options(${target} PRIVATE ${EVOSLAM_WARNINGS})
  endif()
  if(EVOSLAM_BUILD_TESTS AND tests)
    add_executable(${target}_tests ${tests})
    target_compile_options(${target}_tests PRIVATE ${EVOSLAM_TEST_OPTIONS})
    target_compile_definitions(${target}_tests PRIVATE
      EVOSLAM_DATA_DIR="${EVOSLAM_DATA_DIR}"
      EVOSLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
    target_link_libraries(${target}_tests PRIVATE ${target} ${ARG_TEST_DEPS} GTest::gtest GTest::gtest_main GTest::gmock)
    gtest_discover_tests(${target}_tests DISCOVERY_TIMEOUT 60
      PROPERTIES ENVIRONMENT ${EVOSLAM_TEST_ENVIRONMENT})
  endif()
endfunction()
