# 32-bit x86 Linux (ILP32: 32-bit pointers and size_t, 4-byte aligned int64_t).
# Debian packages: gcc-i686-linux-gnu (gcc-multilib conflicts with the other cross
# compilers, so it is not used); qemu-user runs the tests.
set(SVA_CROSS_TRIPLE i686-linux-gnu)
set(SVA_CROSS_PROCESSOR i686)
set(SVA_CROSS_QEMU qemu-i386)
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-common.cmake)
