# LockboxPackaging.cmake: `cpack` in a build tree makes lockbox-dev_<version>_<arch>.deb, which
# installs exactly what `cmake --install` installs (LockboxInstall.cmake), under /usr. Configure
# with -DCMAKE_INSTALL_PREFIX=/usr so that the libraries go to Debian's multiarch folder
# (lib/<triplet>); samples/consumer and scripts/check-consumer.sh show the whole path.
#
# The package depends on the -dev packages of the libraries that the built components link
# (xxHash for core, zstd for replay, ENet for net): a static archive needs them on the
# consumer's link line, and the package config and pkg-config files look for them. Cereal is not
# among them: it is header-only and used by lockbox's own sources only. A shared build depends on
# the runtime packages instead, found by dpkg-shlibdeps.
include_guard(GLOBAL)

get_property(_lockbox_modules GLOBAL PROPERTY LOCKBOX_MODULES)
set(_lockbox_deb_xxhash libxxhash-dev)
set(_lockbox_deb_zstd libzstd-dev)
set(_lockbox_deb_enet libenet-dev)
set(_lockbox_deb_depends "")
if(NOT LOCKBOX_SHARED)
    foreach(_module IN LISTS _lockbox_modules)
        foreach(_dep IN LISTS LOCKBOX_LINK_DEPS_${_module})
            list(APPEND _lockbox_deb_depends ${_lockbox_deb_${_dep}})
        endforeach()
    endforeach()
    list(REMOVE_DUPLICATES _lockbox_deb_depends)
endif()
list(JOIN _lockbox_deb_depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME lockbox-dev)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR lockbox)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}: headers, libraries, CMake package and pkg-config files")
set(CPACK_PACKAGE_DESCRIPTION
    "lockbox runs the Box2D v2.2.1 pipeline on Q16.16 fixed-point integers, so that a step gives the same bits on every machine, compiler and optimisation level. Components: ${_lockbox_pc_list}.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "lockbox developers")
set(CPACK_DEBIAN_PACKAGE_SECTION libdevel)
if(LOCKBOX_SHARED)
    set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
endif()
set(CPACK_PACKAGE_DIRECTORY "${PROJECT_BINARY_DIR}/packages")
include(CPack)
