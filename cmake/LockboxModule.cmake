# LockboxModule.cmake: one library per top-level module folder, and one test executable per test
# folder.
include_guard(GLOBAL)

include(GNUInstallDirs)

# lockbox_add_module(NAME <name> SOURCES <file>...
#                    [PUBLIC_DEPS <target>...] [PRIVATE_DEPS <target>...])
#
# Creates lockbox_<name> (alias lockbox::<name>, exported as lockbox::<name>) from the listed
# sources, which are relative to the calling folder: its public headers are <folder>/include
# (installed as they are), its own headers <folder>/src. STATIC unless BUILD_SHARED_LIBS is ON.
# With LOCKBOX_INSTALL, the library, its headers and its exported targets are installed.
# PUBLIC_DEPS are lockbox modules whose headers the public headers include. PRIVATE_DEPS are
# third-party libraries used by the sources only; a static library still passes their link
# step on to consumers, a shared one does not. A header-only dependency goes in as
# $<BUILD_INTERFACE:...> so that consumers do not look for it at all.
function(lockbox_add_module)
    cmake_parse_arguments(PARSE_ARGV 0 arg "" "NAME" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS")
    if(NOT arg_NAME OR NOT arg_SOURCES)
        message(FATAL_ERROR "lockbox_add_module: NAME and SOURCES are required")
    endif()
    set(target lockbox_${arg_NAME})
    add_library(${target} ${arg_SOURCES})
    add_library(lockbox::${arg_NAME} ALIAS ${target})
    set_target_properties(${target} PROPERTIES
        EXPORT_NAME ${arg_NAME}
        VERSION ${PROJECT_VERSION}
        # Before 1.0 a minor release may change the ABI.
        SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
        # A shared lockbox library finds the others it needs in its own folder, wherever the
        # prefix is.
        INSTALL_RPATH "$ORIGIN"
        # Only what carries LOCKBOX_API (lockbox/Export.h) is exported from a shared library.
        CXX_VISIBILITY_PRESET hidden
        VISIBILITY_INLINES_HIDDEN ON)
    target_compile_features(${target} PUBLIC cxx_std_20)
    target_include_directories(${target}
        PUBLIC "$<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>"
               "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>"
        PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/src")
    target_link_libraries(${target}
        PUBLIC ${arg_PUBLIC_DEPS}
        PRIVATE ${arg_PRIVATE_DEPS} "$<BUILD_INTERFACE:lockbox_compile_options>")
    target_compile_options(${target} PRIVATE ${LOCKBOX_LIBRARY_COMPILE_OPTIONS})
    set_property(GLOBAL APPEND PROPERTY LOCKBOX_MODULES ${arg_NAME})
    if(LOCKBOX_INSTALL)
        # One export set per module, so that the package config loads only the components asked
        # for and a consumer of core never looks for zstd or ENet.
        install(TARGETS ${target} EXPORT lockbox-${arg_NAME}-targets
            ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
            LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
            RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
        # The include tree is the public surface: headers only the engine needs live in src/.
        install(DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}/include/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
        install(EXPORT lockbox-${arg_NAME}-targets NAMESPACE lockbox:: DESTINATION "${LOCKBOX_INSTALL_CMAKEDIR}")
    endif()
endfunction()

# lockbox_add_test_suite(NAME <exe> DIR <folder> LIBS <targets>... [LABELS <labels>...])
# One GoogleTest executable from every *.cpp directly in DIR, registered with
# gtest_discover_tests and the given ctest labels, as unity sources (or with precompiled common
# headers when LOCKBOX_TEST_UNITY_BUILD is OFF). A suite labelled heavy is left out when
# LOCKBOX_BUILD_HEAVY_TESTS is OFF.
function(lockbox_add_test_suite)
    cmake_parse_arguments(ARG "" "NAME;DIR" "LIBS;LABELS" ${ARGN})
    if("heavy" IN_LIST ARG_LABELS AND NOT LOCKBOX_BUILD_HEAVY_TESTS)
        return()
    endif()
    file(GLOB _sources CONFIGURE_DEPENDS "${ARG_DIR}/*.cpp")
    if(NOT _sources)
        return()
    endif()
    add_executable(${ARG_NAME} ${_sources})
    # Test files are independent units: each keeps its helpers and tests in
    # `namespace LOCKBOX_TEST_FILE`, which a unity build names uniquely per file (so the files
    # of one unity source cannot collide) and which is anonymous otherwise.
    set_target_properties(${ARG_NAME} PROPERTIES UNITY_BUILD ${LOCKBOX_TEST_UNITY_BUILD}
                                                 UNITY_BUILD_UNIQUE_ID LOCKBOX_TEST_FILE)
    if(LOCKBOX_TEST_UNITY_BUILD)
        # Float Box2D's b2 names are global, so a file that includes it (the differential tests)
        # cannot share a unity source with files that write `using namespace lockbox;`: it is
        # compiled on its own, as is any file marked so beforehand.
        foreach(_source IN LISTS _sources)
            file(STRINGS "${_source}" _float_includes REGEX "#include \"[^\"]*(Box2DFloat|diff_common)\\.h\"")
            get_source_file_property(_alone "${_source}" SKIP_UNITY_BUILD_INCLUSION)
            if(_float_includes OR _alone)
                set_source_files_properties("${_source}" PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON
                                                                    COMPILE_DEFINITIONS LOCKBOX_TEST_FILE=)
            endif()
        endforeach()
    else()
        target_compile_definitions(${ARG_NAME} PRIVATE LOCKBOX_TEST_FILE=)
    endif()
    target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gmock GTest::gtest_main lockbox_compile_options)
    target_include_directories(${ARG_NAME} PRIVATE "${PROJECT_SOURCE_DIR}/tests/support")
    # GoogleTest, the standard headers most tests use and, for suites over the engine, its public
    # header take more than half of a lone test file's compile time: without a unity build each
    # suite parses them once, as a precompiled header. A unity source already parses them once
    # for all its files, and building the precompiled header then costs more than it saves.
    if(NOT LOCKBOX_TEST_UNITY_BUILD)
        set(_pch <gtest/gtest.h> <algorithm> <array> <cstdint> <functional> <memory> <string> <vector>)
        if(NOT ARG_LIBS MATCHES "^lockbox::(fixed|cli)$")
            list(APPEND _pch <lockbox/lockbox.h>)
        endif()
        target_precompile_headers(${ARG_NAME} PRIVATE ${_pch})
    endif()
    set(_props)
    if(ARG_LABELS)
        set(_props PROPERTIES LABELS "${ARG_LABELS}")
    endif()
    # Tests find their golden files next to __FILE__. A compiler launcher such as ccache with a
    # base directory makes __FILE__ relative to the directory the build tool runs the compiler
    # in, which is the top of the build tree: run the tests from there.
    gtest_discover_tests(${ARG_NAME} DISCOVERY_TIMEOUT 60 WORKING_DIRECTORY "${CMAKE_BINARY_DIR}" ${_props})
endfunction()
