# Writes the ctest entries of the co-simulation cases the unit kinds declare (kCosimCases in
# src/units/<unit>/<unit>.cpp), as gtest_discover_tests does for test cases: run after the build
# (tests/CMakeLists.txt), it asks units_declared for the cases and writes one
# rtl.<unit>.<case> entry each into OUT, which ctest includes.
#   cmake -D TOOL=units_declared -D GLINT=glint -D COSIM=tests/rtl/cosim.sh -D WORK=build/tests/rtl
#         -D SOURCE=. -D OUT=rtl_cases.cmake -P discover.cmake
execute_process(COMMAND ${TOOL} --cosim-cases OUTPUT_VARIABLE listing RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${TOOL} --cosim-cases failed (${status})")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(entries "")
foreach(line IN LISTS lines)
  if(line STREQUAL "")
    continue()
  endif()
  # NAME|SPEC|INPUT: INPUT is glint rtl's input options, split as a shell would.
  string(REPLACE "|" ";" fields "${line}")
  list(GET fields 0 name)
  list(GET fields 1 spec)
  list(GET fields 2 input)
  separate_arguments(input UNIX_COMMAND "${input}")
  set(command "")
  foreach(arg sh ${COSIM} ${GLINT} ${WORK}/${name} ${spec} ${input})
    string(APPEND command " [==[${arg}]==]")
  endforeach()
  string(APPEND entries "add_test([==[rtl.${name}]==]${command})\n"
         "set_tests_properties([==[rtl.${name}]==] PROPERTIES LABELS rtl TIMEOUT 600 "
         "WORKING_DIRECTORY [==[${SOURCE}]==])\n")
endforeach()
file(WRITE ${OUT} "${entries}")
