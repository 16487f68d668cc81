# Target libraries the cross test builds need and Debian has no package of for every
# target (big-endian MIPS left Debian with bookworm): built from Debian's own source
# tarballs (the .orig tarball named in the bookworm .dsc, same versions as the host's
# libcmocka-dev and libjansson-dev). Nothing is vendored: ExternalProject downloads
# the tarball from the Debian archive once and checks its SHA-256.
set(SVA_DEBIAN_POOL "http://deb.debian.org/debian/pool/main" CACHE STRING
    "Debian archive pool the cross test builds download library sources from")
set(SVA_CROSS_DEP_NAMES cmocka jansson)
set(SVA_CROSS_DEP_cmocka_URL "${SVA_DEBIAN_POOL}/c/cmocka/cmocka_1.1.5.orig.tar.xz")
set(SVA_CROSS_DEP_cmocka_SHA256 f0ccd8242d55e2fd74b16ba518359151f6f8383ff8aef4976e48393f77bba8b6)
set(SVA_CROSS_DEP_cmocka_ARGS -DWITH_EXAMPLES=OFF -DUNIT_TESTING=OFF)
set(SVA_CROSS_DEP_jansson_URL "${SVA_DEBIAN_POOL}/j/jansson/jansson_2.14.orig.tar.gz")
set(SVA_CROSS_DEP_jansson_SHA256 c739578bf6b764aa0752db9a2fdadcfe921c78f1228c7ec0bb47fa804c55d17b)
set(SVA_CROSS_DEP_jansson_ARGS -DJANSSON_BUILD_DOCS=OFF -DJANSSON_WITHOUT_TESTS=ON
    -DJANSSON_EXAMPLES=OFF -DJANSSON_BUILD_SHARED_LIBS=OFF)
