# hdhair_add_test(NAME SOURCES file... [LIBRARIES target...] [DEFINITIONS def...] [TIMEOUT seconds]
#                 [ENVIRONMENT VAR=value...])
# A GoogleTest executable, linked with GTest's main and hdHair's warnings,
# whose tests CTest discovers when it runs them (so a test binary that cannot
# start shows up as a failure, not as a build error).
function(hdhair_add_test name)
  cmake_parse_arguments(TEST "" "TIMEOUT" "SOURCES;LIBRARIES;DEFINITIONS;ENVIRONMENT" ${ARGN})
  add_executable(${name} ${TEST_SOURCES})
  target_link_libraries(${name} PRIVATE ${TEST_LIBRARIES} GTest::gtest_main hdhair_warnings)
  if(TEST_DEFINITIONS)
    target_compile_definitions(${name} PRIVATE ${TEST_DEFINITIONS})
  endif()
  set(properties)
  if(TEST_TIMEOUT)
    list(APPEND properties TIMEOUT ${TEST_TIMEOUT})
  endif()
  # Built SRBF tables (dome lighting) go to the build tree, never the user's
  # cache; a test may name its own folder.
  list(APPEND TEST_ENVIRONMENT "HDHAIR_CACHE_DIR=${CMAKE_BINARY_DIR}/testCache")
  list(APPEND properties ENVIRONMENT "${TEST_ENVIRONMENT}")
  # Listing a sanitized binary's tests on a loaded two-core machine can take
  # longer than GoogleTest's default five seconds; a slow listing is not a
  # failed test.
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 120
                       PROPERTIES ${properties})
endfunction()
