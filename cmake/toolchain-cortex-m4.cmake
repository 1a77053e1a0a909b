# Cortex-M4F on QEMU mps2-an386. Hard-float ABI; the flight library is additionally compiled
# with -mgeneral-regs-only (added in fsw/CMakeLists.txt), which rejects any VFP use in fsw/.
set(FSW_CPU_FLAGS -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16)
set(FSW_TARGET_BOARD mps2-an386)
set(FSW_TARGET_NAME cortex-m4)
include(${CMAKE_CURRENT_LIST_DIR}/toolchain-arm-common.cmake)
