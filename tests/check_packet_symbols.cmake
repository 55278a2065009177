# The AVX2 kernels' object file may define only its own functions (phonglab::packet::*) and
# local data. A weak or inline-function definition there (a template, a glm or std helper not
# inlined) could be picked by the linker for the whole program, and would then run AVX2
# instructions on a CPU without them. Usage: cmake -DNM=nm -DOBJECTS="a.o;b.o" -P this-file
foreach(obj IN LISTS OBJECTS)
  execute_process(COMMAND ${NM} -C --defined-only ${obj} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "nm failed on ${obj}")
  endif()
  string(REPLACE "\n" ";" lines "${out}")
  set(kernels 0)
  foreach(line IN LISTS lines)
    if(line STREQUAL "" OR line MATCHES "^[0-9a-f]* [tbdrn] ")
      continue()  # local symbols
    endif()
    if(line MATCHES "^[0-9a-f]* T phonglab::packet::")
      math(EXPR kernels "${kernels} + 1")
      continue()
    endif()
    message(FATAL_ERROR "${obj} defines a shared symbol: ${line}")
  endforeach()
  if(kernels EQUAL 0)
    message(FATAL_ERROR "${obj} defines no kernel: nm output was\n${out}")
  endif()
  message(STATUS "${obj}: ${kernels} kernels, nothing else shared")
endforeach()
