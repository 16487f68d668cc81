# Big-endian 32-bit MIPS Linux (o32): the byte-order check of the project.
# Debian packages: gcc-mips-linux-gnu; qemu-user runs the tests. Debian has no
# big-endian MIPS port since bookworm, so target libraries (jansson) are built
# from Debian's source tarballs by tests/cross/.
set(SVA_CROSS_TRIPLE mips-linux-gnu)
set(SVA_CROSS_PROCESSOR mips)
set(SVA_CROSS_QEMU qemu-mips)
include(${CMAKE_CURRENT_LIST_DIR}/linux-gnu-common.cmake)
