# doctest_ctest.cmake: registers every doctest case of a test binary as one CTest test (run as
# `<binary> --test-case=<name>`, one case per process), with its doctest test suite as CTest
# labels (the suite name split at spaces: TEST_SUITE("opencl shared-scenes") gives both labels).
# Unlike Debian's doctest_discover_tests (2.4.9), names holding ';' or ',' work: its script split
# "a; b" into two tests that matched nothing and so passed without running anything.
#
# Script mode (run after each build of the binary): -DEXE= -DOUT= -DWORKDIR= -DREQUIRED_LABELS=a|b|c
#   Every case must carry exactly one of REQUIRED_LABELS; tests get SKIP_RETURN_CODE 77 and
#   MONTECL_TEST_SKIP_CODE=77 in their environment (tests/fixtures/skip.h).
cmake_minimum_required(VERSION 3.18)
execute_process(COMMAND "${EXE}" --list-test-cases --reporters=xml
                OUTPUT_VARIABLE out RESULT_VARIABLE rc WORKING_DIRECTORY "${WORKDIR}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "listing the test cases of ${EXE} failed (${rc}):\n${out}")
endif()
string(REPLACE ";" "@SEMICOLON@" out "${out}")
string(REGEX MATCHALL "<TestCase [^>]*>" cases "${out}")
string(REPLACE "|" ";" required "${REQUIRED_LABELS}")
set(script "")
set(count 0)
foreach(c IN LISTS cases)
  foreach(attr name testsuite)
    string(REGEX MATCH " ${attr}=\"([^\"]*)\"" unused "${c}")
    set(v "${CMAKE_MATCH_1}")
    # The entities' ';' is already @SEMICOLON@ (above): matched as such, or names holding '<' or '"'
    # would be registered as "&lt;..." and filter nothing, passing without running.
    foreach(pair "&quot@SEMICOLON@|\"" "&apos@SEMICOLON@|'" "&lt@SEMICOLON@|<" "&gt@SEMICOLON@|>" "&amp@SEMICOLON@|&")
      string(REPLACE "|" ";" pair "${pair}")
      list(GET pair 0 from)
      list(GET pair 1 to)
      string(REPLACE "${from}" "${to}" v "${v}")
    endforeach()
    set(${attr} "${v}")
  endforeach()
  string(REPLACE "@SEMICOLON@" ";" name "${name}")
  string(REPLACE " " ";" labels "${testsuite}")
  set(classes 0)
  foreach(l IN LISTS required)
    if(l IN_LIST labels)
      math(EXPR classes "${classes} + 1")
    endif()
  endforeach()
  if(NOT classes EQUAL 1)
    message(FATAL_ERROR "test case \"${name}\" has labels \"${testsuite}\": it needs exactly one of ${REQUIRED_LABELS} "
                        "(its TEST_SUITE or * doctest::test_suite(...))")
  endif()
  # doctest filters: ',' separates patterns and '\' escapes.
  string(REPLACE "\\" "\\\\" filter "${name}")
  string(REPLACE "," "\\," filter "${filter}")
  string(APPEND script
    "add_test([==[${name}]==] [==[${EXE}]==] [==[--test-case=${filter}]==])\n"
    "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKDIR}]==] "
    "LABELS [==[${labels}]==] SKIP_RETURN_CODE 77 ENVIRONMENT MONTECL_TEST_SKIP_CODE=77)\n")
  math(EXPR count "${count} + 1")
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "no test cases listed by ${EXE}")
endif()
file(WRITE "${OUT}" "${script}")
