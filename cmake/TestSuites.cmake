# One CTest test per GoogleTest suite: `mimic_add_test_suites(TARGET TIMEOUT seconds [ENVIRONMENT
# VAR=value...])` runs `TARGET --gtest_filter=Suite.*` for every suite the built program lists
# when ctest starts.
#
# Why not gtest_discover_tests (one process per test): every process of the learning tests loads
# LibTorch, 1 s in the release build and 3.3 s under ASan with leak checking, which was a quarter
# of the suite's time. A failing suite's output names the failing test; to run one test, run the
# program with --gtest_filter=Suite.Name.
#
# A suite named `...Learning` holds long learning checks (a policy trained for dozens of
# iterations until it does the task): it gets the CTest label `learning`, which the sanitizer
# pass of scripts/test.sh leaves out (the same code runs under the sanitizers in the short tests).
function(mimic_add_test_suites target)
  cmake_parse_arguments(ARG "" "TIMEOUT" "ENVIRONMENT" ${ARGN})
  set(script "${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.cmake")
  file(GENERATE OUTPUT "${script}" CONTENT "\
set(program [==[$<TARGET_FILE:${target}>]==])
set(environment [==[${ARG_ENVIRONMENT}]==])
if(NOT EXISTS \"\${program}\")
  add_test(${target}.NOT_BUILT \"\${program}\")
  return()
endif()
execute_process(COMMAND \"\${program}\" --gtest_list_tests OUTPUT_VARIABLE listing
  RESULT_VARIABLE status TIMEOUT 120)
if(NOT status EQUAL 0)
  add_test(${target}.LISTING_FAILED \"\${program}\" --gtest_list_tests)
  return()
endif()
string(REPLACE \"\\n\" \";\" lines \"\${listing}\")
foreach(line IN LISTS lines)
  # A suite is a line that does not start with a space: `Suite.` or `Instance/Suite.`.
  if(line MATCHES \"^([^ #][^ ]*)\\\\.\")
    set(suite \"\${CMAKE_MATCH_1}\")
    add_test(\"\${suite}\" \"\${program}\" \"--gtest_filter=\${suite}.*\")
    set_tests_properties(\"\${suite}\" PROPERTIES TIMEOUT ${ARG_TIMEOUT} ENVIRONMENT \"\${environment}\")
    if(suite MATCHES \"Learning\$\")
      set_tests_properties(\"\${suite}\" PROPERTIES LABELS learning)
    endif()
  endif()
endforeach()
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${script}")
endfunction()
