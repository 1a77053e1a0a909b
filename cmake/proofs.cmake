# Build-time proofs of spec 00 §4 as CTest tests (label `lint`). Included last from the
# top-level CMakeLists.txt (include(proofs OPTIONAL)), so every target already exists.
#
#   host builds (not sanitizer builds, whose flags differ on purpose):
#     lint_includes                 freestanding only: allowed <...> headers in fsw/
#     lint_float_scan               no float: token scan of the preprocessed fsw/
#     lint_cppcheck_misra           MISRA C:2012 (cppcheck + misra addon, stub headers)
#     lint_clang_tidy               clang-tidy with the checks of .clang-tidy
#     lint_general_regs_only_flag   -mgeneral-regs-only is really on fsw's compile line
#   cross builds (Cortex-M):
#     lint_freestanding_flags       -ffreestanding -nostdinc (+ -mgeneral-regs-only on M4)
#     lint_float_scan               same scan with the cross compile lines (covers fsw/target)
#     lint_nm_forbidden_symbols     libfsw.a needs only 64-bit divide and mem* from outside
#     lint_nm_no_mutable_globals    no B b D d C symbols in libfsw.a
#     lint_stack_sum                worst-path stack of every libfsw.a function (report;
#                                   fails on recursion, dynamic frames, unresolved callees)
#   self-test of the checkers (tests/proofs): lint_selftest_<case>
#
# fsw_stack_proof(<test> [LIB <archive target>] [OBJECTS <object library>...]
#                 [DIRS <target>...] [ROOTS <function>...])
#   registers one more stack_sum run, e.g. for the PIL board image:
#     fsw_stack_proof(lint_stack_sum_pil LIB fsw OBJECTS fsw_board_qemu_obj DIRS fsw_pil
#                     ROOTS board_reset_handler board_fault_entry)
#   (the image's own sources must then be compiled with -fstack-usage -fcallgraph-info=su).

set(FSW_LINT_DIR ${CMAKE_SOURCE_DIR}/tools/lint)
set(FSW_PROOF_TIMEOUT 600)

function(fsw_lint_test name)
  add_test(NAME ${name} COMMAND ${ARGN})
  set_tests_properties(${name} PROPERTIES LABELS lint TIMEOUT ${FSW_PROOF_TIMEOUT}
                       WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
endfunction()

function(fsw_stack_proof name)
  cmake_parse_arguments(S "" "LIB" "OBJECTS;DIRS;ROOTS" ${ARGN})
  set(args)
  if(S_LIB)
    get_target_property(bin ${S_LIB} BINARY_DIR)
    list(APPEND args --lib $<TARGET_FILE:${S_LIB}>=${bin}/CMakeFiles/${S_LIB}.dir)
  endif()
  foreach(o IN LISTS S_OBJECTS)
    list(APPEND args $<TARGET_OBJECTS:${o}>)
  endforeach()
  foreach(d IN LISTS S_DIRS)
    get_target_property(bin ${d} BINARY_DIR)
    list(APPEND args ${bin}/CMakeFiles/${d}.dir)
  endforeach()
  foreach(r IN LISTS S_ROOTS)
    list(APPEND args --root ${r})
  endforeach()
  fsw_lint_test(${name} ${FSW_PYTHON} ${CMAKE_SOURCE_DIR}/tools/stack_sum.py
                --json ${CMAKE_BINARY_DIR}/${name}.json ${args})
endfunction()

if(NOT CMAKE_CROSSCOMPILING)
  if(NOT FSW_SANITIZE)
    # --gen: the mission dispatch generated into the build tree is flight code too.
    fsw_lint_test(lint_includes ${FSW_PYTHON} ${FSW_LINT_DIR}/check_includes.py
                  --fsw ${CMAKE_SOURCE_DIR}/fsw --gen ${FSW_GEN_DIR})
    fsw_lint_test(lint_float_scan ${FSW_PYTHON} ${FSW_LINT_DIR}/scan_float.py
                  --fsw ${CMAKE_SOURCE_DIR}/fsw --gen ${FSW_GEN_DIR} -p ${CMAKE_BINARY_DIR} --cc ${CMAKE_C_COMPILER})
    fsw_lint_test(lint_cppcheck_misra bash ${FSW_LINT_DIR}/run_cppcheck.sh --src ${CMAKE_SOURCE_DIR}
                  --gen ${FSW_GEN_DIR})
    fsw_lint_test(lint_clang_tidy bash ${FSW_LINT_DIR}/run_clang_tidy.sh ${CMAKE_BINARY_DIR}
                  --src ${CMAKE_SOURCE_DIR} --gen ${FSW_GEN_DIR})
    # The host no-float proof is just this flag; fail if anyone drops it (or turns
    # FSW_GENERAL_REGS_ONLY off) outside the sanitizer build.
    fsw_lint_test(lint_general_regs_only_flag ${FSW_PYTHON} ${FSW_LINT_DIR}/check_compile_flags.py
                  -p ${CMAKE_BINARY_DIR} --under ${CMAKE_SOURCE_DIR}/fsw --flag=-mgeneral-regs-only
                  --why "spec 00 §4 'no float: host'")
  endif()
else()
  set(_flags --flag=-ffreestanding --flag=-nostdinc)
  if(FSW_TARGET_NAME STREQUAL "cortex-m4")
    list(APPEND _flags --flag=-mgeneral-regs-only)
  endif()
  fsw_lint_test(lint_freestanding_flags ${FSW_PYTHON} ${FSW_LINT_DIR}/check_compile_flags.py
                -p ${CMAKE_BINARY_DIR} --under ${CMAKE_SOURCE_DIR}/fsw ${_flags}
                --why "spec 00 §4 'freestanding only' / 'no float: M4 hard-float'")
  fsw_lint_test(lint_float_scan ${FSW_PYTHON} ${FSW_LINT_DIR}/scan_float.py
                --fsw ${CMAKE_SOURCE_DIR}/fsw --gen ${FSW_GEN_DIR} -p ${CMAKE_BINARY_DIR} --cc ${CMAKE_C_COMPILER})

  # fsw/target objects, should any ever be archived into libfsw.a, are exempt from the
  # no-mutable-globals check (the BSP owns the hardware state).
  get_target_property(_fsw_srcs fsw SOURCES)
  set(_excl)
  foreach(s IN LISTS _fsw_srcs)
    get_filename_component(_abs ${s} ABSOLUTE BASE_DIR ${CMAKE_SOURCE_DIR}/fsw)
    if(_abs MATCHES "^${CMAKE_SOURCE_DIR}/fsw/target/")
      get_filename_component(_n ${s} NAME)
      list(APPEND _excl --exclude-object ${_n}${CMAKE_C_OUTPUT_EXTENSION})
    endif()
  endforeach()
  fsw_lint_test(lint_nm_forbidden_symbols ${FSW_PYTHON} ${CMAKE_SOURCE_DIR}/tools/check_nm.py
                --nm ${CMAKE_NM} --check undefined $<TARGET_FILE:fsw>)
  fsw_lint_test(lint_nm_no_mutable_globals ${FSW_PYTHON} ${CMAKE_SOURCE_DIR}/tools/check_nm.py
                --nm ${CMAKE_NM} --check globals ${_excl} $<TARGET_FILE:fsw>)
  fsw_stack_proof(lint_stack_sum LIB fsw)
  # The PIL board image: reset handler -> main -> the session -> fsw_step, and the fault path. Its
  # worst path is the static bound the pil tests compare the painted high-water mark with
  # (tests/pil/check_stack.py). fx_bench is not registered: its kernel table is called through
  # function pointers (fine for a benchmark, an unresolved callee for stack_sum).
  fsw_stack_proof(lint_stack_sum_pil LIB fsw OBJECTS fsw_board_qemu_obj DIRS fsw_pil
                  ROOTS board_reset_handler board_fault_report)
  set_tests_properties(lint_stack_sum_pil PROPERTIES FIXTURES_SETUP pil_stack_static)
endif()

add_subdirectory(${CMAKE_SOURCE_DIR}/tests/proofs ${CMAKE_BINARY_DIR}/tests/proofs)
