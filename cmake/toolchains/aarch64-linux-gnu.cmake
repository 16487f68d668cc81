# 64-bit Arm Linux (the usual companion computer: Raspberry Pi 4/5, Jetson, i.MX 8).
# Debian packages: gcc-aarch64-linux-gnu; qemu-user to run the tests on a PC.
set(SVA_CROSS_TRIPLE aarch64-linux-gnu)
set(SVA_CROSS_PROCESSOR aarch64)
set(SVA_CROSS_QEMU qemu-aarch64)
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-common.cmake)
