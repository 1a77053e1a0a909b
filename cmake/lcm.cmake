# LCM message bindings (spec 00 §5). Included from hil_host/CMakeLists.txt, host builds only.
#
# The .lcm files in hil_host/lcmtypes are the single source. One lcm-gen run at BUILD time writes
# the C, C++ and Python bindings into the build tree (${FSW_LCM_GEN_DIR}); nothing generated is
# committed.
#
# Provides
#   gnc_lcmtypes_c      static library of the generated C (encode/decode/fingerprint; the
#                       generated _publish/_subscribe are there too, but the bridge encodes into
#                       static buffers: _publish and _copy allocate). Headers: "gnc_<type>.h".
#   gnc_lcmtypes_cpp    INTERFACE target: generated C++ headers, <gnc/<type>.hpp>, + lcm-cpp.
#   FSW_LCM_PYTHON_DIR  directory to put on PYTHONPATH to `import gnc` (also the global property
#                       FSW_LCM_PYTHON_DIR); depend on target gnc_lcmtypes_gen to have it built.
#   PkgConfig::LCM      liblcm (C API, eventlog) from pkg-config.
#   fsw_lcm_url(<var>)  a private udpm URL for one concurrently runnable test.
#
# Safe to include more than once (e.g. from the top level before tests/, and from hil_host/).
include_guard(GLOBAL)

find_program(FSW_LCM_GEN lcm-gen)
if(NOT FSW_LCM_GEN)
  message(FATAL_ERROR
    "lcm-gen not found: install the Debian package liblcm-bin (tools/bootstrap.sh), "
    "or pass -DFSW_LCM_GEN=/path/to/lcm-gen. It generates the LCM bindings in hil_host/lcmtypes.")
endif()

find_package(PkgConfig REQUIRED)
# liblcm-dev ships pkg-config metadata only. lcm.pc requires glib-2.0 and gthread-2.0, so this
# fails without libglib2.0-dev (spec 00 §5.3).
pkg_check_modules(LCM REQUIRED IMPORTED_TARGET lcm)

set(FSW_LCM_TYPES_DIR ${PROJECT_SOURCE_DIR}/hil_host/lcmtypes)
set(FSW_LCM_GEN_DIR   ${CMAKE_BINARY_DIR}/lcmtypes)
set(FSW_LCM_PYTHON_DIR ${FSW_LCM_GEN_DIR}/python)
set_property(GLOBAL PROPERTY FSW_LCM_PYTHON_DIR ${FSW_LCM_PYTHON_DIR})

# Explicit list (no glob): adding a type is a reviewed change to this list.
set(FSW_LCM_TYPES
  sensor_frame_t actuator_cmd_t fsw_tlm_frame_t sim_truth_t table_upload_t table_ack_t sil_ctl_t
  sensor_frame_v2_t actuator_cmd_v2_t table_upload_v2_t fsw_cmd_v2_t
  fsw_cmd_t)

set(_lcm_src "")
set(_lcm_c "")
set(_lcm_h "")
set(_lcm_hpp "")
set(_lcm_py ${FSW_LCM_PYTHON_DIR}/gnc/__init__.py)
foreach(t IN LISTS FSW_LCM_TYPES)
  list(APPEND _lcm_src ${FSW_LCM_TYPES_DIR}/${t}.lcm)
  list(APPEND _lcm_c   ${FSW_LCM_GEN_DIR}/c/gnc_${t}.c)
  list(APPEND _lcm_h   ${FSW_LCM_GEN_DIR}/c/gnc_${t}.h)
  list(APPEND _lcm_hpp ${FSW_LCM_GEN_DIR}/cpp/gnc/${t}.hpp)
  list(APPEND _lcm_py  ${FSW_LCM_PYTHON_DIR}/gnc/${t}.py)
endforeach()

# One run for all languages. The output tree is wiped first: lcm-gen appends to an existing
# Python __init__.py, and a renamed type must not leave stale bindings behind. lcm-gen does not
# create the C output directory itself.
add_custom_command(
  OUTPUT ${_lcm_c} ${_lcm_h} ${_lcm_hpp} ${_lcm_py}
  COMMAND ${CMAKE_COMMAND} -E rm -rf ${FSW_LCM_GEN_DIR}/c ${FSW_LCM_GEN_DIR}/cpp ${FSW_LCM_PYTHON_DIR}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${FSW_LCM_GEN_DIR}/c ${FSW_LCM_GEN_DIR}/cpp ${FSW_LCM_PYTHON_DIR}
  COMMAND ${FSW_LCM_GEN}
          --c --c-cpath ${FSW_LCM_GEN_DIR}/c --c-hpath ${FSW_LCM_GEN_DIR}/c
          --cpp --cpp-std c++11 --cpp-hpath ${FSW_LCM_GEN_DIR}/cpp
          --python --ppath ${FSW_LCM_PYTHON_DIR}
          ${_lcm_src}
  DEPENDS ${_lcm_src} ${CMAKE_CURRENT_LIST_FILE}
  COMMENT "lcm-gen: C, C++ and Python bindings for ${FSW_LCM_TYPES}"
  VERBATIM)
add_custom_target(gnc_lcmtypes_gen DEPENDS ${_lcm_c} ${_lcm_h} ${_lcm_hpp} ${_lcm_py})

# Generated C is third-party-generated code (lcm-gen's emitter, not ours): it is compiled with
# relaxed warnings instead of FSW_C_WARNINGS (it trips -Wconversion, -Wsign-conversion,
# -Wmissing-prototypes, -Wpedantic), and consumers see its headers as SYSTEM headers so their
# own -Werror builds are not affected by it.
add_library(gnc_lcmtypes_c STATIC ${_lcm_c})
add_dependencies(gnc_lcmtypes_c gnc_lcmtypes_gen)
set_target_properties(gnc_lcmtypes_c PROPERTIES C_STANDARD 99 C_EXTENSIONS OFF)
target_compile_options(gnc_lcmtypes_c PRIVATE -w)
target_include_directories(gnc_lcmtypes_c SYSTEM PUBLIC ${FSW_LCM_GEN_DIR}/c)
target_link_libraries(gnc_lcmtypes_c PUBLIC PkgConfig::LCM)

add_library(gnc_lcmtypes_cpp INTERFACE)
add_dependencies(gnc_lcmtypes_cpp gnc_lcmtypes_gen)
target_include_directories(gnc_lcmtypes_cpp SYSTEM INTERFACE ${FSW_LCM_GEN_DIR}/cpp)
target_link_libraries(gnc_lcmtypes_cpp INTERFACE PkgConfig::LCM)

# udpm URLs for tests (spec 00 §5.3). Every call hands out the next port of this build tree's
# block, counted at configure time, so tests that may run concurrently under `ctest -j` never
# hear each other. Different build trees on one machine (host, asan-ubsan, ...) may also run at
# the same time, so the default base port is derived from the build directory: 7700 + 100*k,
# k = hash(CMAKE_BINARY_DIR) mod 100. Override with -DFSW_LCM_PORT_BASE=<port>.
string(MD5 _lcm_dir_hash "${CMAKE_BINARY_DIR}")
string(SUBSTRING "${_lcm_dir_hash}" 0 4 _lcm_dir_hash)
math(EXPR _lcm_default_base "7700 + 100 * (0x${_lcm_dir_hash} % 100)" OUTPUT_FORMAT DECIMAL)
set(FSW_LCM_PORT_BASE ${_lcm_default_base} CACHE STRING
    "First udpm port handed out by fsw_lcm_url() (block of FSW_LCM_PORT_BLOCK ports)")
set(FSW_LCM_PORT_BLOCK 100 CACHE STRING "Number of udpm ports fsw_lcm_url() may hand out")
set(FSW_LCM_GROUP 239.255.76.67 CACHE STRING "udpm multicast group for tests")
set_property(GLOBAL PROPERTY FSW_LCM_PORT_NEXT 0)

# fsw_lcm_url(<var>): sets <var> in the caller to udpm://GROUP:PORT?ttl=0 with a fresh PORT.
# Use it once per test (or per set of processes that must talk to each other), and pass it
# to the test as ENVIRONMENT LCM_DEFAULT_URL=<url> or as an argument.
function(fsw_lcm_url var)
  get_property(n GLOBAL PROPERTY FSW_LCM_PORT_NEXT)
  if(n GREATER_EQUAL FSW_LCM_PORT_BLOCK)
    message(FATAL_ERROR "fsw_lcm_url: more than ${FSW_LCM_PORT_BLOCK} udpm test ports requested; "
                        "raise FSW_LCM_PORT_BLOCK (and check FSW_LCM_PORT_BASE leaves room)")
  endif()
  math(EXPR port "${FSW_LCM_PORT_BASE} + ${n}")
  math(EXPR n "${n} + 1")
  set_property(GLOBAL PROPERTY FSW_LCM_PORT_NEXT ${n})
  set(${var} "udpm://${FSW_LCM_GROUP}:${port}?ttl=0" PARENT_SCOPE)
endfunction()
