# makeway_add_library(NAME SOURCES ... [DEPS ...])
# One pipeline stage = one library target makeway_<NAME>, aliased makeway::<NAME>.
function(makeway_add_library name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_library(makeway_${name} ${ARG_SOURCES})
    add_library(makeway::${name} ALIAS makeway_${name})
    target_include_directories(makeway_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR})
    target_link_libraries(makeway_${name} PUBLIC ${ARG_DEPS} PRIVATE makeway_warnings)
endfunction()

# makeway_add_test(NAME SOURCES ... DEPS ...): one GoogleTest executable per stage.
function(makeway_add_test name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main makeway_warnings)
    target_compile_definitions(${name} PRIVATE
        MAKEWAY_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
                         WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
endfunction()

# makeway_forbid_links(TARGET PATTERN REASON): configuration fails when TARGET links, directly or
# through any chain of makeway libraries, a makeway library whose name matches PATTERN
# ("sim|eval"). Call it after the libraries TARGET links are defined.
function(makeway_forbid_links target pattern reason)
    set(_seen "")
    set(_queue ${target})
    set(_via_${target} "${target}")
    while(_queue)
        list(POP_FRONT _queue _current)
        if(NOT TARGET ${_current})
            continue()
        endif()
        get_target_property(_deps ${_current} LINK_LIBRARIES)
        if(NOT _deps)
            continue()
        endif()
        foreach(_dep IN LISTS _deps)
            if(NOT _dep MATCHES "^makeway(::|_)")
                continue()
            endif()
            string(REGEX REPLACE "^makeway::" "makeway_" _name "${_dep}")
            if(_name IN_LIST _seen)
                continue()
            endif()
            list(APPEND _seen ${_name})
            set(_via_${_name} "${_via_${_current}} -> ${_name}")
            if(_name MATCHES "^makeway_(${pattern})$")
                message(FATAL_ERROR "${target} must not link ${_name} (${_via_${_name}}): ${reason}")
            endif()
            list(APPEND _queue ${_name})
        endforeach()
    endwhile()
endfunction()

# makeway_position_independent(TARGET ...): compiled as position-independent code, for the
# libraries the networks' module (src/makeway/neural) links into itself. Without semantic
# interposition the compiler still inlines and calls directly as it does for the program (nothing
# replaces a makeway function at load time: the module keeps its copies hidden).
function(makeway_position_independent)
    foreach(_target IN LISTS ARGN)
        set_target_properties(${_target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
        target_compile_options(${_target} PRIVATE -fno-semantic-interposition)
    endforeach()
endfunction()
