# Installation and packages: the CMake package (find_package(sva), components for the
# ports), pkg-config files, the programs, the wire definitions, systemd units and the
# Debian package (CPack). Included by the top-level CMakeLists.txt after every target
# exists; docs/packaging.md describes the installed tree.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(SVA_CMAKE_INSTALL_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/sva")
set(SVA_PC_INSTALL_DIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
set(SVA_SHARE_INSTALL_DIR "${CMAKE_INSTALL_DATADIR}/sva")
set(SVA_INSTALLED_COMPONENTS "")
set(_pkg "${PROJECT_SOURCE_DIR}/packaging")
set(_pc_out "${PROJECT_BINARY_DIR}/packaging/pkgconfig")

# pkg-config files find the prefix from their own place (${pcfiledir}), so a tree
# installed with any prefix or DESTDIR, or unpacked from the .deb, needs no editing.
file(RELATIVE_PATH SVA_PC_PREFIX_REL "/root/${SVA_PC_INSTALL_DIR}" "/root")
string(REGEX REPLACE "/$" "" SVA_PC_PREFIX_REL "${SVA_PC_PREFIX_REL}")

# One port library as component COMPONENT of the package: target(s) exported as
# sva::<name>, public headers under include/sva (HEADER_DIR: a folder below it), the
# export set and, with PC, packaging/pkgconfig/<PC>.in configured and installed.
macro(sva_install_component COMPONENT)
    cmake_parse_arguments(_c "" "HEADER_DIR;PC" "TARGETS;HEADERS" ${ARGN})
    install(TARGETS ${_c_TARGETS} EXPORT sva_${COMPONENT}Targets
            ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}")
    if(_c_HEADERS)
        install(FILES ${_c_HEADERS} DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/sva${_c_HEADER_DIR}")
    endif()
    install(EXPORT sva_${COMPONENT}Targets NAMESPACE sva:: DESTINATION "${SVA_CMAKE_INSTALL_DIR}")
    if(_c_PC)
        configure_file("${_pkg}/pkgconfig/${_c_PC}.in" "${_pc_out}/${_c_PC}" @ONLY)
        install(FILES "${_pc_out}/${_c_PC}" DESTINATION "${SVA_PC_INSTALL_DIR}")
    endif()
    list(APPEND SVA_INSTALLED_COMPONENTS ${COMPONENT})
endmacro()

# --- core (sva::core, installed by core/CMakeLists.txt) --------------------------------
install(EXPORT svaTargets NAMESPACE sva:: DESTINATION "${SVA_CMAKE_INSTALL_DIR}")
configure_file("${_pkg}/pkgconfig/sva.pc.in" "${_pc_out}/sva.pc" @ONLY)
install(FILES "${_pc_out}/sva.pc" DESTINATION "${SVA_PC_INSTALL_DIR}")

# --- mission frame (sva::frame: PROJ, found with pkg-config) ----------------------------
if(TARGET sva_frame)
    set_target_properties(sva_frame PROPERTIES EXPORT_NAME frame)
    sva_install_component(frame TARGETS sva_frame PC sva-frame.pc
                          HEADERS "${PROJECT_SOURCE_DIR}/port/frame/include/sva/sva_frame.h")
endif()

# --- CAN port (sva::can), its node and the DBC -----------------------------------------
if(TARGET sva_can)
    set_target_properties(sva_can PROPERTIES EXPORT_NAME can)
    sva_install_component(can TARGETS sva_can PC sva-can.pc
                          HEADERS "${PROJECT_SOURCE_DIR}/port/can/include/sva/sva_can.h"
                                  "${PROJECT_SOURCE_DIR}/port/can/include/sva/sva_can_mission_frame.h"
                                  "${PROJECT_SOURCE_DIR}/port/can/include/sva/sva_can_transport.h")
    install(FILES "${PROJECT_SOURCE_DIR}/port/can/sva.dbc" DESTINATION "${SVA_SHARE_INSTALL_DIR}")
endif()
if(TARGET sva_can_node)
    install(TARGETS sva_can_node RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
endif()

# --- LCM port (sva::lcm with its wire types), its node and the .lcm definitions --------
if(TARGET sva_lcm)
    set_target_properties(sva_lcm PROPERTIES EXPORT_NAME lcm)
    set_target_properties(sva_lcm_types PROPERTIES EXPORT_NAME lcm_types)
    # The pkg-config file names the lcm this build used (lcm ships none); another one:
    #   pkg-config --define-variable=lcm_prefix=/path/to/site-packages sva-lcm
    get_filename_component(SVA_LCM_PREFIX "${SVA_LCM_CMAKE_DIR}/../../.." ABSOLUTE)
    sva_install_component(lcm TARGETS sva_lcm sva_lcm_types PC sva-lcm.pc
                          HEADERS "${PROJECT_SOURCE_DIR}/port/lcm/include/sva/sva_lcm.h"
                                  ${SVA_LCM_GEN_HEADERS})
    file(GLOB _sva_lcm_types "${PROJECT_SOURCE_DIR}/port/lcm/types/*.lcm")
    install(FILES ${_sva_lcm_types} DESTINATION "${SVA_SHARE_INSTALL_DIR}/lcm")
    if(SVA_LCM_JAVA_JAR)
        # lcm-spy's class path entry for sva's messages (docs/lcm.md).
        install(FILES "${SVA_LCM_JAVA_JAR}" DESTINATION "${CMAKE_INSTALL_DATADIR}/java")
    endif()
endif()
if(TARGET sva_node)
    install(TARGETS sva_node RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
endif()

# --- JSON layer (sva::json) --------------------------------------------------------------
if(TARGET sva_json)
    set_target_properties(sva_json PROPERTIES EXPORT_NAME json)
    get_target_property(_json_src sva_json SOURCE_DIR)
    get_target_property(_json_inc sva_json INTERFACE_INCLUDE_DIRECTORIES)
    if(NOT _json_inc MATCHES "INSTALL_INTERFACE")
        # Its include directory is a source directory: the build keeps it, the installed
        # package points at include/sva/json.
        set(_json_new "")
        foreach(_d IN LISTS _json_inc)
            list(APPEND _json_new "$<BUILD_INTERFACE:${_d}>")
        endforeach()
        list(APPEND _json_new "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/sva/json>")
        set_target_properties(sva_json PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_json_new}")
    endif()
    file(GLOB _json_headers "${_json_src}/*json*.h" "${_json_src}/input.h")
    sva_install_component(json TARGETS sva_json HEADER_DIR /json HEADERS ${_json_headers})
endif()

# --- MAVLink bridge (sva::mavlink with mavgen's headers) and its program ---------------
# sva_mavlink.h includes "common/mavlink.h" (its parser and message types are in the
# public structs): the headers mavgen generated for this build go to include/sva/mavlink,
# the installed target's SYSTEM include directory (port/mavlink/CMakeLists.txt).
if(TARGET sva_mavlink)
    set_target_properties(sva_mavlink PROPERTIES EXPORT_NAME mavlink)
    sva_install_component(mavlink TARGETS sva_mavlink PC sva-mavlink.pc
                          HEADERS "${PROJECT_SOURCE_DIR}/port/mavlink/include/sva/sva_mavlink.h")
    install(DIRECTORY "${SVA_MAVLINK_GEN_DIR}/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/sva/mavlink"
            FILES_MATCHING PATTERN "*.h")
endif()
if(TARGET sva_mavlink_bridge)
    install(TARGETS sva_mavlink_bridge RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
endif()

# --- svaConfig.cmake ------------------------------------------------------------------
list(JOIN SVA_INSTALLED_COMPONENTS " " SVA_INSTALLED_COMPONENTS_TEXT)  # for its messages
configure_package_config_file("${_pkg}/svaConfig.cmake.in" "${PROJECT_BINARY_DIR}/svaConfig.cmake"
    INSTALL_DESTINATION "${SVA_CMAKE_INSTALL_DIR}")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/svaConfigVersion.cmake"
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/svaConfig.cmake" "${PROJECT_BINARY_DIR}/svaConfigVersion.cmake"
        DESTINATION "${SVA_CMAKE_INSTALL_DIR}")

if(NOT SVA_IS_TOP_LEVEL)
    return()  # a project that add_subdirectory()s sva installs the core only
endif()

# --- systemd units -----------------------------------------------------------------------
# ExecStart= needs the absolute path of the installed program, known only at install
# time (cpack installs with prefix /usr, a plain install with CMAKE_INSTALL_PREFIX).
set(_units "")
if(TARGET sva_node)
    list(APPEND _units sva-node)
endif()
if(TARGET sva_can_node)
    list(APPEND _units sva-can-node)
endif()
foreach(_u IN LISTS _units)
    # Written straight to its destination (DESTDIR honoured): a shared intermediate file
    # would race between two installs with different prefixes.
    install(CODE "
        set(SVA_BINDIR \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}\")
        set(_dst \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/lib/systemd/system/${_u}.service\")
        message(STATUS \"Installing: \${_dst}\")
        configure_file(\"${_pkg}/systemd/${_u}.service.in\" \"\${_dst}\" @ONLY)
        list(APPEND CMAKE_INSTALL_MANIFEST_FILES \"\${_dst}\")")
endforeach()

# --- Debian package (cpack -G DEB in build/, or the package test) ----------------------
install(FILES "${_pkg}/debian/copyright" DESTINATION "${CMAKE_INSTALL_DATADIR}/doc/sva")
set(SVA_DEB_MAINTAINER "sva maintainers <maintainers@example.invalid>"
    CACHE STRING "Maintainer field of the Debian package")
set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "sva")
set(CPACK_PACKAGE_VENDOR "sva")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "on-board mission planner for UAV fleets")
# Stage with DESTDIR and prefix /usr (not a staging prefix), so the units' ExecStart=
# says /usr/bin.
set(CPACK_SET_DESTDIR ON)
set(CPACK_INSTALL_PREFIX "/usr")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_PACKAGE_DIRECTORY "${PROJECT_BINARY_DIR}/deb")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${SVA_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
# The summary is the Description's first line; CPack indents this body below it.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "sva assigns UAVs to target areas with time windows and orders their visits
(Semiz and Polat's Simplex VRP Algorithm, with greedy, exhaustive and min-cost
flow planners). The planning core is C99 with static allocation only.

This package holds the sva command-line tool, the LCM and CAN nodes with their
systemd units, the MAVLink mission bridge, the core and port libraries with
headers, CMake and pkg-config files, and the LCM message definitions and CAN DBC.")
# Run-time dependencies (libc6, libglib2.0-0, libjansson4, and PROJ's library for
# sva_mavlink_bridge, which places the routes with the frame's geodesy) from the
# programs' ELF dependencies with dpkg-shlibdeps; a consumer linking the installed
# static sva::frame needs PROJ's development files.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libproj-dev")
include(CPack)
