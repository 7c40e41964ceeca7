# ctest kernel_symbols: the objects of a non-baseline kernel level
# (nn/kernels_level.cpp compiled for v3 or v4) must define no symbol another
# translation unit could also define: every defined symbol names the level's
# renamed Eigen (cnclab_eigen_<level>) or the level's namespace
# (cnclab::kernels::<level>). Otherwise the linker could keep this level's
# copy of, say, a std:: or Eigen function for the whole program, and baseline
# code would run AVX-512 instructions (nn/kernel_table.hpp).
# Usage: cmake -DNM=nm -DLEVEL=v4 -DOBJECTS="a.o;b.o" -P kernel_symbols.cmake
foreach(object IN LISTS OBJECTS)
  execute_process(COMMAND ${NM} -C --defined-only ${object} OUTPUT_VARIABLE symbols
                  RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${NM} failed on ${object}")
  endif()
  string(REPLACE "\n" ";" lines "${symbols}")
  set(count 0)
  foreach(line IN LISTS lines)
    if(line STREQUAL "")
      continue()
    endif()
    math(EXPR count "${count} + 1")
    # "<address> <type> <name>"; local symbols (lower-case types but u, v, w)
    # cannot clash.
    string(REGEX MATCH "^[0-9a-f]* ([A-Za-z]) (.*)$" _ "${line}")
    set(type "${CMAKE_MATCH_1}")
    set(name "${CMAKE_MATCH_2}")
    if(type MATCHES "^[a-tx-z]$")
      continue()
    endif()
    if(name MATCHES "cnclab_eigen_${LEVEL}::|cnclab::kernels::${LEVEL}::"
       OR name STREQUAL "DW.ref.__gxx_personality_v0")
      continue()
    endif()
    # Type information is data, the same bytes in every translation unit
    # (UBSan's function check emits it for function types): no instructions.
    if(name MATCHES "^typeinfo (name )?for ")
      continue()
    endif()
    message(FATAL_ERROR "${object}: '${name}' (${type}) is not in a ${LEVEL} namespace: another "
                        "translation unit may define it with other instructions")
  endforeach()
  if(count LESS 10)
    message(FATAL_ERROR "${object}: only ${count} symbols; not the kernels?")
  endif()
  message(STATUS "${object}: ${count} symbols, all level-${LEVEL} names")
endforeach()
