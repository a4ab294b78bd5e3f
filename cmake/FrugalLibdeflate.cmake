# frugal::libdeflate: libdeflate (Debian libdeflate-dev), the PNG encoder's deflate. Its static
# archive is preferred, so that the command line and the Python module need no libdeflate at run
# time (Debian builds the archive position-independent); the shared library where there is none.
# Included by the build and by the installed package's config (frugal's libraries are static, so
# their users link it too).
if(NOT TARGET frugal::libdeflate)
  find_path(FRUGAL_LIBDEFLATE_INCLUDE_DIR libdeflate.h)
  find_library(FRUGAL_LIBDEFLATE_LIBRARY NAMES libdeflate.a deflate)
  if(NOT FRUGAL_LIBDEFLATE_INCLUDE_DIR OR NOT FRUGAL_LIBDEFLATE_LIBRARY)
    message(FATAL_ERROR "libdeflate was not found (Debian: apt-get install libdeflate-dev)")
  endif()
  add_library(frugal::libdeflate UNKNOWN IMPORTED)
  set_target_properties(frugal::libdeflate PROPERTIES
    IMPORTED_LOCATION "${FRUGAL_LIBDEFLATE_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${FRUGAL_LIBDEFLATE_INCLUDE_DIR}")
endif()
