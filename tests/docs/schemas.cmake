# The JSON report schemas documented beside the code (src/*/*_report.md, src/eval/golden.md)
# against real outputs of this build: tests/docs/check_schemas.py runs glint on the shipped traces
# and scene and fails on any key written but not documented, documented but never written, or of
# another type. Included from tests/CMakeLists.txt; needs Python3_EXECUTABLE.
add_test(NAME docs.schemas
         COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/docs/check_schemas.py
                 $<TARGET_FILE:glint> ${PROJECT_SOURCE_DIR})
set_tests_properties(docs.schemas PROPERTIES LABELS docs TIMEOUT 120
                                             PASS_REGULAR_EXPRESSION "PASS: ")

# `glint synth --json` (src/cli/synth_report.md) runs Yosys: only where it is installed
# (GLINT_YOSYS, looked up by tests/CMakeLists.txt for the rtl tests).
if(GLINT_YOSYS)
  add_test(NAME docs.schemas_synth
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/docs/check_schemas.py
                   $<TARGET_FILE:glint> ${PROJECT_SOURCE_DIR} --synth)
  set_tests_properties(docs.schemas_synth PROPERTIES LABELS docs TIMEOUT 180
                                                     PASS_REGULAR_EXPRESSION "PASS: ")
endif()
