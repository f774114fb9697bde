# Finds the Open Dynamics Engine. Debian's libode-dev ships no CMake config, only pkg-config.
# Defines the imported target ODE::ODE (double precision, as Debian builds it).
find_package(PkgConfig REQUIRED)
pkg_check_modules(PC_ODE QUIET ode)

find_path(ODE_INCLUDE_DIR ode/ode.h HINTS ${PC_ODE_INCLUDE_DIRS})
find_library(ODE_LIBRARY NAMES ode HINTS ${PC_ODE_LIBRARY_DIRS})
set(ODE_VERSION ${PC_ODE_VERSION})

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(ODE REQUIRED_VARS ODE_LIBRARY ODE_INCLUDE_DIR VERSION_VAR ODE_VERSION)

if(ODE_FOUND AND NOT TARGET ODE::ODE)
  add_library(ODE::ODE UNKNOWN IMPORTED)
  set_target_properties(ODE::ODE PROPERTIES
    IMPORTED_LOCATION "${ODE_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${ODE_INCLUDE_DIR}"
    INTERFACE_COMPILE_DEFINITIONS "dDOUBLE")
endif()
mark_as_advanced(ODE_INCLUDE_DIR ODE_LIBRARY)
