# Debian package of the installed tree (`cpack -G DEB` in the build dir): what cmake --install
# puts under bin/ and share/robodds/ (install component "runtime"), with prefix /usr. Tests and
# benchmarks have no install() rules, so they are never in it.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME robodds)
# CPACK_PACKAGE_VERSION defaults to the version of project().
set(CPACK_PACKAGE_VENDOR "robodds")
set(CPACK_PACKAGE_CONTACT "robodds maintainers <robodds@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "deterministic DDS components for robotics: generic component host")
# The extended description of the control file, one line per string (dpkg wants short lines).
string(JOIN "\n" CPACK_PACKAGE_DESCRIPTION
  "robodds runs estimation and control components that talk only through DDS"
  "topics (Fast DDS 2.9): co-located, as separate processes or across machines,"
  "in deterministic lockstep or in real time. The package holds the robodds"
  "binary with every built-in component, one executable robodds-<type> per"
  "component (that component alone, without a scenario file) and, in"
  "/usr/share/robodds, the QoS profiles, the components' documented parameter"
  "defaults, the example scenarios and the plotting script.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# Only install component "runtime" goes into the package (build dir; project; component; subdir),
# so a later install() without COMPONENT cannot slip test or benchmark files in.
set(CPACK_INSTALL_CMAKE_PROJECTS "${CMAKE_BINARY_DIR};${PROJECT_NAME};runtime;/")
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # robodds_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# Depends: dpkg-shlibdeps reads the binary's shared libraries (Fast DDS, Fast-CDR, yaml-cpp, ...)
# and names the Debian packages that own them, so the list cannot fall behind the link line.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Plus what no library link shows: `robodds security init` runs the openssl program (keys,
# certificates, signed documents; the runtime's own libcrypto comes through shlibdeps), and
# without it a minimal install could not make a secure deployment at all. CPack (3.25,
# Internal/CPack/CPackDeb.cmake) puts this list first and appends the shlibdeps result to it
# with ", ": Depends: openssl, libc6 (>= ...), ...
set(CPACK_DEBIAN_PACKAGE_DEPENDS "openssl")
# Plots (`robodds run` without --no-plots, `robodds report`) need python3 with matplotlib;
# fastdds-tools gives `fastdds discovery` for the Discovery Server deployments.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3, python3-matplotlib")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "fastdds-tools")
include(CPack)
