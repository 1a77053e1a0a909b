# The missions of this build (README "Design: one module, one folder").
#
# missions.json is the registry: one line per mission. FSW_MISSIONS chooses which of them a build
# contains ("all", or a list such as "DETUMBLE" or "DETUMBLE;RENDEZVOUS"); the flight library then
# holds only those modules, fsw_t only their blocks, and the host only their factories.
# tools/iface writes, at configure time, into ${FSW_GEN_DIR}:
#   missions.cmake          FSW_MISSION_NAMES / _MODULES / _PREFIXES of the configuration
#   fsw_missions_gen.{h,c}  the flight dispatch (a switch per adapter entry point)
#   iface_gen.{hpp,cpp}     the host's name and layout tables (host builds)
# Editing missions.json or an interface description re-runs this at the next build.
set(FSW_MISSIONS "all" CACHE STRING "Missions of this build: all, or a ;-list of names from missions.json")
set(FSW_GEN_DIR ${CMAKE_BINARY_DIR}/gen)
string(REPLACE ";" "," _fsw_missions_arg "${FSW_MISSIONS}")
set(_fsw_iface_args build --missions "${_fsw_missions_arg}" --out ${FSW_GEN_DIR} --cmake)
if(CMAKE_CROSSCOMPILING)
  list(APPEND _fsw_iface_args --no-host)
endif()
execute_process(COMMAND ${FSW_PYTHON} -B -m tools.iface ${_fsw_iface_args}
                WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
                RESULT_VARIABLE _fsw_iface_rc ERROR_VARIABLE _fsw_iface_err)
if(NOT _fsw_iface_rc EQUAL 0)
  message(FATAL_ERROR "missions: tools.iface failed for FSW_MISSIONS='${FSW_MISSIONS}':\n${_fsw_iface_err}")
endif()
include(${FSW_GEN_DIR}/missions.cmake)
message(STATUS "missions: ${FSW_MISSION_NAMES}")
file(GLOB _fsw_iface_inputs ${CMAKE_SOURCE_DIR}/tools/iface/*.py ${CMAKE_SOURCE_DIR}/fsw/app/fsw_iface.py)
foreach(m IN LISTS FSW_MISSION_MODULES_ALL)
  file(GLOB _d ${CMAKE_SOURCE_DIR}/fsw/${m}/*_iface.py)
  list(APPEND _fsw_iface_inputs ${_d})
endforeach()
set_property(DIRECTORY ${CMAKE_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             ${CMAKE_SOURCE_DIR}/missions.json ${_fsw_iface_inputs})
