# hdhair_add_test(NAME SOURCES file... [LIBRARIES target...] [DEFINITIONS def...] [TIMEOUT seconds])
# A GoogleTest executable, linked with GTest's main and hdHair's warnings,
# whose tests CTest discovers when it runs them (so a test binary that cannot
# start shows up as a failure, not as a build error).
function(hdhair_add_test name)
  cmake_parse_arguments(TEST "" "TIMEOUT" "SOURCES;LIBRARIES;DEFINITIONS" ${ARGN})
  add_executable(${name} ${TEST_SOURCES})
  target_link_libraries(${name} PRIVATE ${TEST_LIBRARIES} GTest::gtest_main hdhair_warnings)
  if(TEST_DEFINITIONS)
    target_compile_definitions(${name} PRIVATE ${TEST_DEFINITIONS})
  endif()
  if(TEST_TIMEOUT)
    gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT ${TEST_TIMEOUT})
  else()
    gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST)
  endif()
endfunction()
