# Cortex-M4F (e.g. STM32F4 at 168 MHz): Thumb-2, single-precision FPU, hard-float ABI.
# The sva core uses no floating point; the FPU flags only match the firmware it links
# into (and pick newlib's thumb/v7e-m+fp/hard multilib).
#   cmake -S . -B build-m4 -G Ninja \
#         -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/arm-none-eabi-cortex-m4f.cmake
set(SVA_ARM_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi-common.cmake)
