# check_symbols.cmake: the layer rule on the built libraries, run by ctest as
# `layer_symbols`:
#   cmake -DNM=<nm> "-DLIBS=<core.a>;<mesh.a>;..." -P check_symbols.cmake
# LIBS lists the layer archives in the layer order (core first). Every glpgp_
# symbol an archive uses but does not define must be defined by an archive
# before it: a layer calls only its own layers and those below, whatever its
# includes say (a declaration written by hand, a macro, a header that lies).
# Fails (FATAL_ERROR, listing every violation) otherwise.
cmake_minimum_required(VERSION 3.18)
set(defined_below "")
set(errors "")
foreach(lib ${LIBS})
  get_filename_component(name ${lib} NAME_WE)
  execute_process(COMMAND ${NM} -g --defined-only ${lib} OUTPUT_VARIABLE def RESULT_VARIABLE rc1 ERROR_QUIET)
  execute_process(COMMAND ${NM} -u ${lib} OUTPUT_VARIABLE und RESULT_VARIABLE rc2 ERROR_QUIET)
  if(NOT rc1 EQUAL 0 OR NOT rc2 EQUAL 0)
    message(FATAL_ERROR "check_symbols: ${NM} failed on ${lib}")
  endif()
  string(REGEX MATCHALL "[ \t][A-TV-Z][ \t]+glpgp_[A-Za-z0-9_]+" defs "${def}")
  set(own "")
  foreach(d ${defs})
    string(REGEX REPLACE ".*[ \t](glpgp_[A-Za-z0-9_]+)$" "\\1" s "${d}")
    list(APPEND own ${s})
  endforeach()
  string(REGEX MATCHALL "U[ \t]+glpgp_[A-Za-z0-9_]+" uses "${und}")
  list(REMOVE_DUPLICATES uses)
  foreach(u ${uses})
    string(REGEX REPLACE "U[ \t]+" "" s "${u}")
    if(NOT s IN_LIST own AND NOT s IN_LIST defined_below)
      list(APPEND errors "${name} uses ${s}, defined by no layer below it")
    endif()
  endforeach()
  list(APPEND defined_below ${own})
endforeach()
list(LENGTH errors n)
if(n GREATER 0)
  string(REPLACE ";" "\n  " msg "${errors}")
  message(FATAL_ERROR "layer rule violated by symbols (${n}):\n  ${msg}")
endif()
list(LENGTH LIBS nl)
message(STATUS "layer_symbols: ${nl} libraries, every glpgp_ symbol from a layer at or below its user")
