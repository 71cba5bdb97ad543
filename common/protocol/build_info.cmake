# Writes build_info.h from build_info.h.in with the source tree's current
# commit ("-dirty" for uncommitted changes). Run at every build (see
# CMakeLists.txt), so the build id follows the sources without a
# reconfigure; the header is rewritten, and its users rebuilt, only when
# the id changes.
#
# In: SOURCE_DIR, INPUT, OUTPUT, GIT_EXECUTABLE (may be empty),
#     PROJECT_VERSION, CMAKE_CXX_COMPILER_ID, CMAKE_CXX_COMPILER_VERSION,
#     ANIMAT_BUILD_ARCH.
set(ANIMAT_GIT_COMMIT "unknown")
if(GIT_EXECUTABLE)
  execute_process(
    COMMAND ${GIT_EXECUTABLE} describe --always --dirty --abbrev=12
    WORKING_DIRECTORY ${SOURCE_DIR}
    OUTPUT_VARIABLE commit
    OUTPUT_STRIP_TRAILING_WHITESPACE
    ERROR_QUIET)
  if(commit)
    set(ANIMAT_GIT_COMMIT "${commit}")
  endif()
endif()
configure_file(${INPUT} ${OUTPUT} @ONLY)
