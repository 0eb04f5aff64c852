# lockbox_add_module(NAME <name> [DEPS <targets>...])
# One library per top-level folder: sources are every .cpp below <folder>/src, public headers
# live in <folder>/include/lockbox/. Creates lockbox_<name> with the alias lockbox::<name>.
include_guard(GLOBAL)

function(lockbox_add_module)
    cmake_parse_arguments(ARG "" "NAME" "DEPS" ${ARGN})
    file(GLOB_RECURSE _sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp")
    set(_target lockbox_${ARG_NAME})
    if(_sources)
        add_library(${_target} STATIC ${_sources})
        target_include_directories(${_target} PUBLIC
            "$<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>"
            PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/src")
        target_link_libraries(${_target} PUBLIC ${ARG_DEPS} PRIVATE lockbox_compile_options)
        # Consumers get the determinism flags and option defines too.
        target_link_libraries(${_target} INTERFACE lockbox_compile_options)
    else()
        add_library(${_target} INTERFACE)
        target_include_directories(${_target} INTERFACE
            "$<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>")
        target_link_libraries(${_target} INTERFACE ${ARG_DEPS} lockbox_compile_options)
    endif()
    add_library(lockbox::${ARG_NAME} ALIAS ${_target})
endfunction()

# lockbox_add_test_suite(NAME <exe> DIR <folder> LIBS <targets>... [LABELS <labels>...])
# One GoogleTest executable from every *.cpp directly in DIR, registered with
# gtest_discover_tests and the given ctest labels.
function(lockbox_add_test_suite)
    cmake_parse_arguments(ARG "" "NAME;DIR" "LIBS;LABELS" ${ARGN})
    file(GLOB _sources CONFIGURE_DEPENDS "${ARG_DIR}/*.cpp")
    if(NOT _sources)
        return()
    endif()
    add_executable(${ARG_NAME} ${_sources})
    target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gmock GTest::gtest_main lockbox_compile_options)
    target_include_directories(${ARG_NAME} PRIVATE "${CMAKE_SOURCE_DIR}/tests/support")
    set(_props)
    if(ARG_LABELS)
        set(_props PROPERTIES LABELS "${ARG_LABELS}")
    endif()
    gtest_discover_tests(${ARG_NAME} DISCOVERY_TIMEOUT 60 ${_props})
endfunction()
