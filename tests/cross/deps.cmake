# Target libraries the cross test builds need and Debian has no package of for every
# target (big-endian MIPS left Debian with bookworm): built from Debian's own source
# tarballs (the .orig tarball named in the bookworm .dsc, the same version as the
# host's libjansson-dev). Nothing is vendored: ExternalProject downloads
# the tarball from the Debian archive once and checks its SHA-256.
set(SVA_DEBIAN_POOL "http://deb.debian.org/debian/pool/main" CACHE STRING
    "Debian archive pool the cross test builds download library sources from")
# Unity needs no entry here: each sub-build compiles it from the sources this build
# fetched (FETCHCONTENT_SOURCE_DIR_UNITY, tests/cross/CMakeLists.txt).
set(SVA_CROSS_DEP_NAMES jansson)
set(SVA_CROSS_DEP_jansson_URL "${SVA_DEBIAN_POOL}/j/jansson/jansson_2.14.orig.tar.gz")
set(SVA_CROSS_DEP_jansson_SHA256 c739578bf6b764aa0752db9a2fdadcfe921c78f1228c7ec0bb47fa804c55d17b)
set(SVA_CROSS_DEP_jansson_ARGS -DJANSSON_BUILD_DOCS=OFF -DJANSSON_WITHOUT_TESTS=ON
    -DJANSSON_EXAMPLES=OFF -DJANSSON_BUILD_SHARED_LIBS=OFF)
