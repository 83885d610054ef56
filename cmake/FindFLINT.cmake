# FindFLINT: the FLINT family as Debian 12 ships it (no pkg-config files).
#
# FLINT 2.9 (libflint-dev: <flint/*.h>, -lflint), Arb 2.23 (libflint-arb-dev: flat <arb.h>,
# -lflint-arb) and Calcium 0.4.1 (libcalcium-dev: <calcium/*.h>, -lcalcium).
# Defines imported targets FLINT::flint, FLINT::arb and (if found) FLINT::calcium.
find_path(FLINT_INCLUDE_DIR flint/flint.h)
find_library(FLINT_LIBRARY flint)
find_path(ARB_INCLUDE_DIR arb.h)
find_library(ARB_LIBRARY flint-arb)
find_path(CALCIUM_INCLUDE_DIR calcium/qqbar.h)
find_library(CALCIUM_LIBRARY calcium)
find_library(GMP_LIBRARY gmp)
find_library(MPFR_LIBRARY mpfr)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(FLINT
  REQUIRED_VARS FLINT_LIBRARY FLINT_INCLUDE_DIR ARB_LIBRARY ARB_INCLUDE_DIR GMP_LIBRARY MPFR_LIBRARY
  FAIL_MESSAGE "FLINT/Arb not found: install the Debian 12 packages libflint-dev libflint-arb-dev libmpfr-dev libgmp-dev (scripts/setup.sh does)")

if(FLINT_FOUND AND NOT TARGET FLINT::flint)
  add_library(FLINT::flint UNKNOWN IMPORTED)
  set_target_properties(FLINT::flint PROPERTIES IMPORTED_LOCATION "${FLINT_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${FLINT_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${MPFR_LIBRARY};${GMP_LIBRARY}")
  add_library(FLINT::arb UNKNOWN IMPORTED)
  set_target_properties(FLINT::arb PROPERTIES IMPORTED_LOCATION "${ARB_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${ARB_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "FLINT::flint")
  if(CALCIUM_LIBRARY AND CALCIUM_INCLUDE_DIR)
    add_library(FLINT::calcium UNKNOWN IMPORTED)
    set_target_properties(FLINT::calcium PROPERTIES IMPORTED_LOCATION "${CALCIUM_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${CALCIUM_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "FLINT::arb")
  endif()
endif()
mark_as_advanced(FLINT_INCLUDE_DIR FLINT_LIBRARY ARB_INCLUDE_DIR ARB_LIBRARY CALCIUM_INCLUDE_DIR CALCIUM_LIBRARY)
