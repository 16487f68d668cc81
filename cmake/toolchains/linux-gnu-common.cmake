# Shared part of the Linux cross toolchain files (aarch64, i686, mips). Uses Debian's
# cross compilers (gcc-<triple>) and their sysroot /usr/<triple>; the including file
# sets SVA_CROSS_TRIPLE, SVA_CROSS_PROCESSOR and SVA_CROSS_QEMU first.
#
# Test programs run under qemu-user: CMAKE_CROSSCOMPILING_EMULATOR makes add_test()
# and try_run() prefix them with `qemu-<arch> -L /usr/<triple>` (package qemu-user),
# so no binfmt registration is needed. pkg-config looks only in the target's
# directories (Debian multiarch and the sysroot) plus CMAKE_PREFIX_PATH, never the
# host's.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR ${SVA_CROSS_PROCESSOR})
set(CMAKE_LIBRARY_ARCHITECTURE ${SVA_CROSS_TRIPLE})

find_program(CMAKE_C_COMPILER NAMES ${SVA_CROSS_TRIPLE}-gcc REQUIRED)
find_program(CMAKE_NM NAMES ${SVA_CROSS_TRIPLE}-nm)
find_program(CMAKE_OBJDUMP NAMES ${SVA_CROSS_TRIPLE}-objdump)

set(SVA_CROSS_SYSROOT /usr/${SVA_CROSS_TRIPLE})
# Appended, so a -DCMAKE_FIND_ROOT_PATH=<prefix of cross-built libraries> stays searched.
list(APPEND CMAKE_FIND_ROOT_PATH ${SVA_CROSS_SYSROOT})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

find_program(SVA_CROSS_QEMU_PROGRAM NAMES ${SVA_CROSS_QEMU})
if(SVA_CROSS_QEMU_PROGRAM)
    set(CMAKE_CROSSCOMPILING_EMULATOR ${SVA_CROSS_QEMU_PROGRAM} -L ${SVA_CROSS_SYSROOT})
endif()

set(ENV{PKG_CONFIG_LIBDIR}
    "/usr/lib/${SVA_CROSS_TRIPLE}/pkgconfig:${SVA_CROSS_SYSROOT}/lib/pkgconfig:/usr/share/pkgconfig")
