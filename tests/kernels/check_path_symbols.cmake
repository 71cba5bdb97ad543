# Fails when an object file of a kernel path defines a symbol with external
# linkage outside the path's namespaces (animat::isa_<path>:: for the inline
# math, animat::kernels::isa_<path>:: for the kernels).
#   cmake -DNM=nm -DOBJECTS=a.o;b.o -P check_path_symbols.cmake
foreach(object IN LISTS OBJECTS)
  execute_process(COMMAND ${NM} -C --defined-only --extern-only ${object}
                  OUTPUT_VARIABLE symbols RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${NM} failed on ${object}")
  endif()
  string(REGEX MATCH "kernels_([a-z0-9]+)\\.cc" _ "${object}")
  set(path ${CMAKE_MATCH_1})
  string(REPLACE "\n" ";" lines "${symbols}")
  set(count 0)
  foreach(line IN LISTS lines)
    if(line STREQUAL "")
      continue()
    endif()
    if(NOT line MATCHES "animat::(kernels::)?isa_${path}::")
      message(SEND_ERROR "${object}: ${line} is outside isa_${path}")
    endif()
    math(EXPR count "${count} + 1")
  endforeach()
  if(count EQUAL 0)
    message(FATAL_ERROR "${object}: no symbols (path ${path})")
  endif()
  message(STATUS "${object}: ${count} symbols, all in isa_${path}")
endforeach()
