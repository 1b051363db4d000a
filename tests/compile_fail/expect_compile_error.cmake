# Compiles SOURCE with COMPILER and checks the outcome announced on its first line:
#   // expect: <regex>   the compilation must fail and its output match <regex>
#   // expect: success   the compilation must succeed
file(STRINGS ${SOURCE} first_line LIMIT_COUNT 1)
string(REGEX REPLACE "^// expect: " "" expected "${first_line}")
execute_process(
  COMMAND ${COMPILER} -std=c++20 -fsyntax-only -I${INCLUDE_DIR} ${SOURCE}
  RESULT_VARIABLE result
  OUTPUT_VARIABLE output
  ERROR_VARIABLE output)
if(expected STREQUAL "success")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "expected ${SOURCE} to compile, but it failed:\n${output}")
  endif()
elseif(result EQUAL 0)
  message(FATAL_ERROR "expected ${SOURCE} to fail to compile, but it compiled")
elseif(NOT output MATCHES "${expected}")
  message(FATAL_ERROR "compilation failed, but without the message /${expected}/:\n${output}")
else()
  message(STATUS "rejected as expected: /${expected}/")
endif()
