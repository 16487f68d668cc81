# Shared part of the bare-metal Arm toolchain files (arm-none-eabi-cortex-m4f.cmake,
# arm-none-eabi-cortex-m7.cmake). Debian packages: gcc-arm-none-eabi and
# libnewlib-arm-none-eabi. The including file sets SVA_ARM_CPU_FLAGS first.
#
# - Optimised for size (-Os) in every build type; sections per function and object so
#   the linker drops what firmware does not call (--gc-sections).
# - newlib-nano with the nosys stubs (--specs=nano.specs --specs=nosys.specs): no
#   operating system; a syscall that firmware pulls in by mistake links to a stub
#   that fails instead of a missing symbol. The sva core itself needs only memset,
#   memcpy and memmove.
# - Executables are not runnable on the host, so try_compile builds static libraries.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(SVA_ARM_PREFIX arm-none-eabi-)
find_program(CMAKE_C_COMPILER NAMES ${SVA_ARM_PREFIX}gcc REQUIRED)
find_program(CMAKE_ASM_COMPILER NAMES ${SVA_ARM_PREFIX}gcc REQUIRED)
find_program(CMAKE_OBJCOPY NAMES ${SVA_ARM_PREFIX}objcopy)
find_program(CMAKE_SIZE NAMES ${SVA_ARM_PREFIX}size)
find_program(CMAKE_NM NAMES ${SVA_ARM_PREFIX}nm)

set(CMAKE_C_FLAGS_INIT "${SVA_ARM_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${SVA_ARM_CPU_FLAGS}")
foreach(config DEBUG RELEASE RELWITHDEBINFO MINSIZEREL)
    set(CMAKE_C_FLAGS_${config}_INIT "-Os")
endforeach()
set(CMAKE_C_FLAGS_RELWITHDEBINFO_INIT "-Os -g")
set(CMAKE_C_FLAGS_DEBUG_INIT "-Os -g")
set(CMAKE_EXE_LINKER_FLAGS_INIT "--specs=nano.specs --specs=nosys.specs -Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
