# LockboxFindLibrary.cmake: find a third-party library by its header and/or library file, for
# the dependencies whose Debian packages ship no CMake package (xxHash, ENet) or whose package we
# do not rely on (zstd). Used by this repository's build (cmake/LockboxDependencies.cmake) and,
# installed next to lockboxConfig.cmake, by the package config, so both find them the same way.
include_guard(GLOBAL)

# lockbox_find_library(<target>
#     NAME    <display name>     e.g. "ENet"
#     DEBIAN  <package>          the Debian package that provides it, e.g. libenet-dev
#     [HEADER <file>]            a header to find (its folder becomes an include directory)
#     [LIBRARY <name>]           a library to find and link (lib<name>.so or .a)
#     [GLOBAL]                   make <target> visible in every directory
#     RESULT  <var>)             set to TRUE when found, FALSE otherwise
#
# Creates the INTERFACE IMPORTED target <target> when everything was found (or does nothing if
# <target> exists). The cache variables it sets (LOCKBOX_DEP_<NAME>_INCLUDE_DIR, _LIBRARY) may
# be given on the command line to point at another installation.
function(lockbox_find_library target)
    cmake_parse_arguments(PARSE_ARGV 1 arg "GLOBAL" "NAME;DEBIAN;HEADER;LIBRARY;RESULT" "")
    if(NOT arg_RESULT OR NOT arg_NAME OR NOT arg_DEBIAN OR NOT (arg_HEADER OR arg_LIBRARY))
        message(FATAL_ERROR "lockbox_find_library(${target}): NAME, DEBIAN, RESULT and HEADER or LIBRARY are required")
    endif()
    if(TARGET ${target})
        set(${arg_RESULT} TRUE PARENT_SCOPE)
        return()
    endif()
    string(MAKE_C_IDENTIFIER "${arg_NAME}" var)
    string(TOUPPER "LOCKBOX_DEP_${var}" var)
    set(found TRUE)
    if(arg_HEADER)
        find_path(${var}_INCLUDE_DIR NAMES ${arg_HEADER} DOC "Folder holding ${arg_HEADER} (${arg_DEBIAN})")
        if(NOT ${var}_INCLUDE_DIR)
            set(found FALSE)
        endif()
    endif()
    if(arg_LIBRARY)
        find_library(${var}_LIBRARY NAMES ${arg_LIBRARY} DOC "lib${arg_LIBRARY} (${arg_DEBIAN})")
        if(NOT ${var}_LIBRARY)
            set(found FALSE)
        endif()
    endif()
    if(found)
        if(arg_GLOBAL)
            add_library(${target} INTERFACE IMPORTED GLOBAL)
        else()
            add_library(${target} INTERFACE IMPORTED)
        endif()
        if(arg_HEADER)
            target_include_directories(${target} INTERFACE "${${var}_INCLUDE_DIR}")
        endif()
        if(arg_LIBRARY)
            target_link_libraries(${target} INTERFACE "${${var}_LIBRARY}")
        endif()
    endif()
    set(${arg_RESULT} ${found} PARENT_SCOPE)
endfunction()
