# Image regression tests for projects that use frugal (installed with the package; find_package(frugal)
# includes it).
#
#   frugal_add_render_test(NAME <name> SCENE <scene> [SIZE WxH] [TOLERANCE N] [ARGS <arg>...])
#
# Adds a CTest test that runs `frugal diff <scene>`: the scene is rendered on a GL backend (auto:
# EGL, then OSMesa) and on frugal's software reference, and the test passes when no pixel of any
# frame differs by more than TOLERANCE 8-bit steps in any channel (default: frugal diff's, 2).
# SCENE is a .gltf/.glb/.obj path or builtin:NAME; ARGS are more `frugal diff` options (--frames,
# --camera, --eye/--target, --backend, ...). The test runs in <build>/frugal-render-tests/<name>/;
# when a frame fails, its actual (GL), reference (software) and mask PNGs are written to
# frugal-diff/ in that folder, and the test output names them.
#
# The frugal executable is the imported target frugal::cli (or, inside frugal's own build, the
# in-tree one); set FRUGAL_EXECUTABLE to use another binary.
include_guard(GLOBAL)

function(frugal_add_render_test)
  cmake_parse_arguments(PARSE_ARGV 0 FRT "" "NAME;SCENE;SIZE;TOLERANCE" "ARGS")
  if(FRT_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "frugal_add_render_test: unexpected arguments: ${FRT_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT FRT_NAME OR NOT FRT_SCENE)
    message(FATAL_ERROR "frugal_add_render_test: NAME and SCENE are required")
  endif()
  if(FRUGAL_EXECUTABLE)
    set(exe "${FRUGAL_EXECUTABLE}")
  elseif(TARGET frugal::cli)
    set(exe "$<TARGET_FILE:frugal::cli>")
  else()
    message(FATAL_ERROR "frugal_add_render_test: no frugal executable: call find_package(frugal) first, "
                        "or set FRUGAL_EXECUTABLE")
  endif()

  set(args diff "${FRT_SCENE}")
  if(FRT_SIZE)
    list(APPEND args --size "${FRT_SIZE}")
  endif()
  if(DEFINED FRT_TOLERANCE)
    list(APPEND args --tolerance "${FRT_TOLERANCE}")
  endif()
  list(APPEND args ${FRT_ARGS})

  # One folder per test, so that failure images of two tests never land in the same place.
  set(dir "${CMAKE_CURRENT_BINARY_DIR}/frugal-render-tests/${FRT_NAME}")
  file(MAKE_DIRECTORY "${dir}")
  add_test(NAME "${FRT_NAME}" COMMAND "${exe}" ${args} WORKING_DIRECTORY "${dir}")
endfunction()
