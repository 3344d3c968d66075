# Finds TetGen 1.5 as Debian ships it (libtet1.5-dev: tetgen.h + libtet.so) and creates TetGen::TetGen.
find_path(TETGEN_INCLUDE_DIR tetgen.h)
find_library(TETGEN_LIBRARY tet)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(TetGen REQUIRED_VARS TETGEN_LIBRARY TETGEN_INCLUDE_DIR
  REASON_FAILURE_MESSAGE "install libtet1.5-dev")
if(TetGen_FOUND AND NOT TARGET TetGen::TetGen)
  add_library(TetGen::TetGen UNKNOWN IMPORTED)
  # Debian builds libtet with TETLIBRARY; the header needs the same define to declare the library API.
  set_target_properties(TetGen::TetGen PROPERTIES
    IMPORTED_LOCATION "${TETGEN_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${TETGEN_INCLUDE_DIR}"
    INTERFACE_COMPILE_DEFINITIONS TETLIBRARY)
endif()
