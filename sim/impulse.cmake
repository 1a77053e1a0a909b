# Impulse scheduler (spec 50-impulse): the Eigen double reference (switching-time solver and the
# reference FSW of the whole scheduler) and the CW plant with its navigation sensor.
# Included from sim/CMakeLists.txt (host only). The reference reads fsw/impulse/imp.h for names,
# structs and tables only.
add_library(sim_imp_reference STATIC reference/imp_ref.cpp)
target_include_directories(sim_imp_reference PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/reference)
target_link_libraries(sim_imp_reference PUBLIC Eigen3::Eigen fsw PRIVATE sim_cxx_flags)

# CW rendezvous plant (spec 50 §2): closed-form transition, six on/off thrusters, faults, nav
# sensor (noise from the project generator in sim/sensors, part of the sim library).
add_library(sim_cw_plant STATIC plant/cw_plant.cpp)
target_include_directories(sim_cw_plant PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(sim_cw_plant PUBLIC Eigen3::Eigen sim PRIVATE sim_cxx_flags)

# Closed-loop campaigns run thousands of plant steps with Eigen: optimise these two libraries
# even in Debug builds (Eigen at -O0 is ~30x slower); results do not depend on it
# (-ffp-contract=off, no -ffast-math).
if(CMAKE_BUILD_TYPE STREQUAL "Debug")
  target_compile_options(sim_imp_reference PRIVATE -O2)
  target_compile_options(sim_cw_plant PRIVATE -O2)
endif()
