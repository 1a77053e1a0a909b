# Cortex-M builds: bring the host build's golden-vector headers into this build tree (one
# module's header per call from golden_vectors() in CMakeLists.txt; NAMES may list several).
#   cmake -DSRC=<host build>/golden/gen -DDST=<this build>/golden/gen -DNAMES=<h1;h2> -P import_vectors.cmake
# copy_if_different keeps the timestamps of unchanged headers, so the replay tests recompile
# only when the host regenerated its vectors. A missing header is replaced by a stub that
# defines GV_MISSING, and the replay test then fails at test time with this message (the build
# itself still succeeds, as it does without host digests). The stub names no record layout: the
# replay includes its module's gv_<prefix>.h itself and, under GV_MISSING, uses no record.
cmake_minimum_required(VERSION 3.25)
file(MAKE_DIRECTORY "${DST}")
foreach(h IN LISTS NAMES)
  if(EXISTS "${SRC}/${h}")
    file(COPY_FILE "${SRC}/${h}" "${DST}/${h}" ONLY_IF_DIFFERENT)
  else()
    message(WARNING "golden: ${SRC}/${h} not found: build the host preset first (tools/test.sh does), "
                    "or set FSW_HOST_BUILD_DIR")
    set(stub "/* stub: the host build has not generated ${h} */\n#define GV_MISSING \"${SRC}/${h}\"\n")
    set(old "")
    if(EXISTS "${DST}/${h}")
      file(READ "${DST}/${h}" old)
    endif()
    if(NOT old STREQUAL stub)
      file(WRITE "${DST}/${h}" "${stub}")
    endif()
  endif()
endforeach()
