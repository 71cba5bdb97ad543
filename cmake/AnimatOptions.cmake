# Compiler flags for every animat target.
#
# -ffp-contract=off and no -ffast-math keep results bit-identical across
# optimisation levels and machines of one architecture: every operation is
# the IEEE operation written in the source, never fused or reassociated.

add_compile_options(-Wall -Wextra -Wpedantic -ffp-contract=off
                    -fno-fast-math)
if(ANIMAT_WERROR)
  add_compile_options(-Werror)
endif()

if(ANIMAT_ARCH AND CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")
  add_compile_options(-march=${ANIMAT_ARCH})
endif()

# Fuzzing (fuzz/): every target gets libFuzzer's coverage instrumentation
# and, unless ANIMAT_SANITIZE says otherwise, ASan and UBSan, so the
# libraries a fuzz target links are checked as closely as the target.
# Only the fuzz targets link libFuzzer itself (-fsanitize=fuzzer).
if(ANIMAT_BUILD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "ANIMAT_BUILD_FUZZ needs clang for libFuzzer "
                        "(CXX=clang++-14); the compiler is "
                        "${CMAKE_CXX_COMPILER_ID}")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
  if(NOT ANIMAT_SANITIZE)
    set(ANIMAT_SANITIZE address,undefined)
  endif()
endif()

if(ANIMAT_SANITIZE)
  add_compile_options(-fsanitize=${ANIMAT_SANITIZE} -fno-omit-frame-pointer
                      -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${ANIMAT_SANITIZE})
  # Under ASan with any optimisation, GCC 12 to 14 report maybe-uninitialized
  # inside libstdc++'s own <regex> (GCC bug 105616, a false positive). Builds
  # without sanitizers keep the warning, as an error under ANIMAT_WERROR.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-maybe-uninitialized)
  endif()
endif()

# animat_library(NAME SOURCES... DEPS...) declares one layer of common/.
function(animat_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
endfunction()
