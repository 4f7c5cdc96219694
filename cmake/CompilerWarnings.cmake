# Warning and sanitizer flags shared by every makeway target (see makeway_target_defaults).
add_library(makeway_warnings INTERFACE)
# Params structs carry defaults for every member; designated initializers that set a few of them
# are the intended use, so the missing-initializer warning is off.
target_compile_options(makeway_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                  -Wno-missing-field-initializers)
# GCC 12 reports -Wrestrict inside libstdc++'s std::string operator+ at -O3 (GCC PR 105651, a
# false positive fixed in GCC 13); silence it there.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(makeway_warnings INTERFACE -Wno-restrict)
endif()
if(MAKEWAY_WERROR)
    target_compile_options(makeway_warnings INTERFACE -Werror)
endif()

# The sanitizer builds compile at -O1 with line tables only (-g1: file and line in every report,
# no variable info): measured on verifier.cpp with ASan+UBSan, -O2 -g took 37 s, -O1 -g1 16 s,
# and the whole sanitizer build is the longest part of CI.
if(MAKEWAY_SANITIZE OR MAKEWAY_TSAN)
    set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O1 -g1 -DNDEBUG")
endif()

# ASan without its use-after-scope check (-fno-sanitize-address-use-after-scope): that check poisons
# and unpoisons the stack slot of every named temporary as its scope opens and closes, and the
# per-point Eigen temporaries of ICP, odometry and ray casting made it a third of the suite's cost
# (measured: the labeller's scrambled-labels test 135 -> 82 s with it off in verification alone;
# the whole suite 2,374 -> 1,623 s of test time, 1,203 -> 812 s on 2 cores). Heap and stack
# overflows, use after free and leaks are still caught; the fuzz build (clang) keeps the check on
# for the parsers.
if(MAKEWAY_SANITIZE)
    set(_san -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
             -fno-sanitize-address-use-after-scope)
    add_compile_options(${_san})
    add_link_options(-fsanitize=address,undefined)
endif()

if(MAKEWAY_TSAN)
    add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
    add_link_options(-fsanitize=thread)
endif()

if(MAKEWAY_FUZZ)
    # Line tables are all a fuzzer's crash report needs (file and line of every frame): the
    # io library's first batch compiled in 30 s at -O2 -g, 24 s with line tables only.
    set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O2 -gline-tables-only -DNDEBUG")
    # Instrument every library for coverage-guided fuzzing; the fuzz executables add the driver.
    add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
    add_link_options(-fsanitize=address,undefined)
endif()
