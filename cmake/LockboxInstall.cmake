# LockboxInstall.cmake: what `cmake --install` puts next to the libraries and headers that
# lockbox_add_module installs (included by the top-level CMakeLists.txt when LOCKBOX_INSTALL):
#
#   include/lockbox/Version.h                      generated version header
#   <libdir>/cmake/lockbox/lockboxConfig.cmake     find_package(lockbox ... COMPONENTS ...)
#   <libdir>/cmake/lockbox/lockboxConfigVersion.cmake   SameMajorVersion
#   <libdir>/cmake/lockbox/lockbox-<module>-targets*.cmake   one export set per module
#   <libdir>/cmake/lockbox/LockboxFindLibrary.cmake      how the config finds xxHash, zstd, ENet
#   <libdir>/pkgconfig/lockbox.pc, lockbox-<module>.pc   pkg-config
#   <docdir>/examples/first_match/main.cpp         the first-match example (docs/first-match.md)
include_guard(GLOBAL)

include(CMakePackageConfigHelpers)

get_property(_lockbox_modules GLOBAL PROPERTY LOCKBOX_MODULES)

install(FILES "${PROJECT_BINARY_DIR}/include/lockbox/Version.h" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/lockbox")
if("net" IN_LIST _lockbox_modules)
    install(FILES "${PROJECT_SOURCE_DIR}/samples/first_match/main.cpp" DESTINATION "${CMAKE_INSTALL_DOCDIR}/examples/first_match")
endif()

# --- CMake package -------------------------------------------------------------------------------

# Third-party libraries that a component's static archive needs at link time (none for a
# shared build: the shared libraries carry their own dependencies).
set(LOCKBOX_LINK_DEPS_core xxhash)
set(LOCKBOX_LINK_DEPS_scenefile xxhash)
set(LOCKBOX_LINK_DEPS_replay xxhash zstd)
set(LOCKBOX_LINK_DEPS_net xxhash zstd enet)
get_target_property(_lockbox_fixed_type lockbox_fixed TYPE)
if(_lockbox_fixed_type STREQUAL "SHARED_LIBRARY")
    set(LOCKBOX_SHARED TRUE)
else()
    set(LOCKBOX_SHARED FALSE)
endif()
set(LOCKBOX_BUILT_COMPONENTS "${_lockbox_modules}")

configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/lockboxConfig.cmake.in"
    "${PROJECT_BINARY_DIR}/lockboxConfig.cmake"
    INSTALL_DESTINATION "${LOCKBOX_INSTALL_CMAKEDIR}"
    NO_SET_AND_CHECK_MACRO NO_CHECK_REQUIRED_COMPONENTS_MACRO)
write_basic_package_version_file("${PROJECT_BINARY_DIR}/lockboxConfigVersion.cmake"
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES
    "${PROJECT_BINARY_DIR}/lockboxConfig.cmake"
    "${PROJECT_BINARY_DIR}/lockboxConfigVersion.cmake"
    "${CMAKE_CURRENT_LIST_DIR}/LockboxFindLibrary.cmake"
    DESTINATION "${LOCKBOX_INSTALL_CMAKEDIR}")

# --- pkg-config ----------------------------------------------------------------------------------
# One file per module, so that a physics-only user (lockbox-core) needs neither libzstd.pc nor
# libenet.pc, and lockbox.pc for everything that was built. Paths are relative to the .pc file's
# own folder (${pcfiledir}), so an installed tree can be moved, and the .deb built by CPack
# (which installs into a staging folder) holds the right paths.

set(_lockbox_pc_dir "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
    set(LOCKBOX_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
    file(RELATIVE_PATH _lockbox_pc_up "/prefix/${_lockbox_pc_dir}" "/prefix")
    string(REGEX REPLACE "/$" "" _lockbox_pc_up "${_lockbox_pc_up}")
    set(LOCKBOX_PC_PREFIX "\${pcfiledir}/${_lockbox_pc_up}")
endif()
foreach(_dir IN ITEMS INCLUDEDIR LIBDIR)
    if(IS_ABSOLUTE "${CMAKE_INSTALL_${_dir}}")
        set(LOCKBOX_PC_${_dir} "${CMAKE_INSTALL_${_dir}}")
    else()
        set(LOCKBOX_PC_${_dir} "\${prefix}/${CMAKE_INSTALL_${_dir}}")
    endif()
endforeach()

# pkg-config names of the third-party libraries (Debian's libxxhash-dev, libzstd-dev,
# libenet-dev ship these .pc files).
set(_lockbox_pc_xxhash libxxhash)
set(_lockbox_pc_zstd libzstd)
set(_lockbox_pc_enet libenet)
set(_lockbox_pc_base_core lockbox-fixed)
set(_lockbox_pc_base_scenefile lockbox-core)
set(_lockbox_pc_base_replay lockbox-core)
set(_lockbox_pc_base_net lockbox-replay)

# Defines that change the ABI, as lockbox::fixed passes them on.
set(_lockbox_pc_defines "")
if(LOCKBOX_CHECKED)
    string(APPEND _lockbox_pc_defines " -DLOCKBOX_CHECKED=1")
endif()
if(LOCKBOX_PORTABLE_INT128)
    string(APPEND _lockbox_pc_defines " -DLOCKBOX_PORTABLE_INT128=1")
endif()

set(_lockbox_pc_all "")
set(_lockbox_pc_files "")
foreach(_module IN LISTS _lockbox_modules)
    set(LOCKBOX_PC_NAME "lockbox-${_module}")
    set(LOCKBOX_PC_DESCRIPTION "lockbox::${_module}: ${PROJECT_DESCRIPTION}")
    set(LOCKBOX_PC_REQUIRES "${_lockbox_pc_base_${_module}}")
    set(_third_party "")
    foreach(_dep IN LISTS LOCKBOX_LINK_DEPS_${_module})
        list(APPEND _third_party ${_lockbox_pc_${_dep}})
    endforeach()
    list(JOIN _third_party " " _third_party)
    # A static archive needs its dependencies on every link line, so they are plain Requires
    # (`pkg-config --libs` gives them without --static); a shared library carries them itself.
    if(LOCKBOX_SHARED)
        set(LOCKBOX_PC_REQUIRES_PRIVATE "${_third_party}")
    else()
        string(STRIP "${LOCKBOX_PC_REQUIRES} ${_third_party}" LOCKBOX_PC_REQUIRES)
        set(LOCKBOX_PC_REQUIRES_PRIVATE "")
    endif()
    set(LOCKBOX_PC_CFLAGS "-I\${includedir}")
    if(_module STREQUAL "fixed")
        string(APPEND LOCKBOX_PC_CFLAGS "${_lockbox_pc_defines}")
    endif()
    set(LOCKBOX_PC_LIBS "-L\${libdir} -llockbox_${_module}")
    configure_file("${CMAKE_CURRENT_LIST_DIR}/lockbox.pc.in" "${PROJECT_BINARY_DIR}/pkgconfig/lockbox-${_module}.pc" @ONLY)
    list(APPEND _lockbox_pc_all "lockbox-${_module}")
    list(APPEND _lockbox_pc_files "${PROJECT_BINARY_DIR}/pkgconfig/lockbox-${_module}.pc")
endforeach()

set(LOCKBOX_PC_NAME "lockbox")
list(JOIN _lockbox_modules ", " _lockbox_pc_list)
set(LOCKBOX_PC_DESCRIPTION "${PROJECT_DESCRIPTION}: ${_lockbox_pc_list}")
list(JOIN _lockbox_pc_all " " LOCKBOX_PC_REQUIRES)
set(LOCKBOX_PC_REQUIRES_PRIVATE "")
set(LOCKBOX_PC_CFLAGS "")
set(LOCKBOX_PC_LIBS "")
configure_file("${CMAKE_CURRENT_LIST_DIR}/lockbox.pc.in" "${PROJECT_BINARY_DIR}/pkgconfig/lockbox.pc" @ONLY)

install(FILES ${_lockbox_pc_files} "${PROJECT_BINARY_DIR}/pkgconfig/lockbox.pc" DESTINATION "${_lockbox_pc_dir}")
