# Shared part of the arm-none-eabi toolchain files. The including file sets FSW_CPU_FLAGS,
# FSW_TARGET_BOARD (QEMU machine) and FSW_TARGET_NAME before including this one.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar)
set(CMAKE_RANLIB arm-none-eabi-ranlib)
set(CMAKE_NM arm-none-eabi-nm)
set(CMAKE_OBJCOPY arm-none-eabi-objcopy)
set(CMAKE_SIZE arm-none-eabi-size CACHE FILEPATH "size tool")
set(CMAKE_EXECUTABLE_SUFFIX_C .elf)
# try_compile cannot link without a board image; a static library is enough to probe the compiler.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

string(JOIN " " _fsw_cpu ${FSW_CPU_FLAGS})
set(CMAKE_C_FLAGS_INIT "${_fsw_cpu}")
set(CMAKE_ASM_FLAGS_INIT "${_fsw_cpu}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${_fsw_cpu} -nostdlib -Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)

# Target test executables run under QEMU through the same add_test() lines as on the host.
set(CMAKE_CROSSCOMPILING_EMULATOR "${CMAKE_CURRENT_LIST_DIR}/../tools/qemu-run.sh;${FSW_TARGET_BOARD}")
