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
