# Unity (ThrowTheSwitch), the C test framework of the test suite, the CMake way:
# FetchContent from its public repository at a release tag. A build without internet
# points FetchContent at a local copy of that release with
#   -DFETCHCONTENT_SOURCE_DIR_UNITY=<dir>
# (scripts/build.sh passes ../shared/unity beside the checkout when it exists).
#
# Only Unity's sources are used (its own CMakeLists.txt would add install rules to this
# project's): sva_unity_library() compiles src/unity.c, and sva_unity_test_sources()
# gives a test source plus its runner, generated at build time by Unity's own
# generator (auto/generate_test_runner.rb, run by Ruby): a main() that runs every
# `void test_*(void)` of the file in order, with setUp()/tearDown() around each and
# suiteSetUp() before them when the file has one.
include(FetchContent)
FetchContent_Declare(unity
    GIT_REPOSITORY https://github.com/ThrowTheSwitch/Unity.git
    GIT_TAG v2.7.0
    GIT_SHALLOW TRUE)
FetchContent_GetProperties(unity)
if(NOT unity_POPULATED)
    FetchContent_Populate(unity)
endif()
set(SVA_UNITY_DIR "${unity_SOURCE_DIR}" CACHE INTERNAL "Unity's sources")

find_program(SVA_RUBY ruby)
if(NOT SVA_RUBY)
    message(FATAL_ERROR "The C tests need Ruby for Unity's test-runner generator "
                        "(Debian package ruby; scripts/setup.sh installs it)")
endif()

# Unity as a static library: 64-bit integer assertions on every target (the core's
# costs and ticks are int32_t, its sums int64_t), no colour codes in the output.
function(sva_unity_library name)
    add_library(${name} STATIC "${SVA_UNITY_DIR}/src/unity.c")
    set_target_properties(${name} PROPERTIES C_STANDARD 99 C_EXTENSIONS OFF)
    target_include_directories(${name} PUBLIC "${SVA_UNITY_DIR}/src")
    target_compile_definitions(${name} PUBLIC UNITY_SUPPORT_64 ${ARGN})
endfunction()

# Sets `out_var` to the test source `source` (relative to the calling folder) and its
# generated runner; one runner per source and folder, shared by the programs built
# from it (a test built against several cores). Further arguments are options of the
# generator, e.g. --main_name=NAME for an image whose own main() calls the runner
# (tests/target).
function(sva_unity_test_sources out_var source)
    get_filename_component(src "${source}" ABSOLUTE)
    get_filename_component(stem "${source}" NAME_WE)
    set(runner "${CMAKE_CURRENT_BINARY_DIR}/unity_runners/${stem}_runner.c")
    get_property(done DIRECTORY PROPERTY SVA_UNITY_RUNNERS)
    if(NOT runner IN_LIST done)
        add_custom_command(
            OUTPUT "${runner}"
            COMMAND ${CMAKE_COMMAND} -E make_directory "${CMAKE_CURRENT_BINARY_DIR}/unity_runners"
            COMMAND ${SVA_RUBY} "${SVA_UNITY_DIR}/auto/generate_test_runner.rb" ${ARGN} "${src}" "${runner}"
            DEPENDS "${src}" "${SVA_UNITY_DIR}/auto/generate_test_runner.rb"
            COMMENT "Unity runner for ${source}"
            VERBATIM)
        # the runner includes the test file's own headers, found beside it
        get_filename_component(src_dir "${src}" DIRECTORY)
        set_source_files_properties("${runner}" PROPERTIES INCLUDE_DIRECTORIES "${src_dir}")
        set_property(DIRECTORY APPEND PROPERTY SVA_UNITY_RUNNERS "${runner}")
    endif()
    set(${out_var} "${src}" "${runner}" PARENT_SCOPE)
endfunction()

if(NOT TARGET sva_unity)
    sva_unity_library(sva_unity)
endif()
