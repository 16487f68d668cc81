# Warning sets, applied per target (never global flags).

# The strictest tier: the core and everything that ships with it.
function(sva_strict_warnings target)
    if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
        target_compile_options(${target} PRIVATE
            -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow -Wvla
            -Wundef -Wmissing-prototypes -Wstrict-prototypes -Wcast-qual
            -Wdouble-promotion -Wfloat-equal -Wswitch-enum -Werror)
    endif()
endfunction()

# Host tools and tests: strict, but they may use stdio and floating point.
function(sva_host_warnings target)
    if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
        target_compile_options(${target} PRIVATE
            -Wall -Wextra -Wpedantic -Wshadow -Wvla -Wundef -Wstrict-prototypes -Werror)
    endif()
endfunction()
