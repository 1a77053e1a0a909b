# Cortex-M3 (no FPU) on QEMU mps2-an385: soft-float multilib thumb/v7-m/nofp, where every FP
# operation would become an __aeabi_* call that the nm proof catches.
set(FSW_CPU_FLAGS -mcpu=cortex-m3 -mthumb -mfloat-abi=soft)
set(FSW_TARGET_BOARD mps2-an385)
set(FSW_TARGET_NAME cortex-m3)
include(${CMAKE_CURRENT_LIST_DIR}/toolchain-arm-common.cmake)
