# frugal::draco: Debian's libdraco (libdraco-dev), the KHR_draco_mesh_compression codec, linked
# statically without the member that holds its own copies of tinygltf and stb_image.
#
# libdraco is built with its glTF transcoder, which carries a tinygltf and an stb_image of its own:
# exported from libdraco.so, in one member (tiny_gltf_utils.cc.o) of libdraco.a. Linked as it is,
# either could take the place of Debian's libtinygltf and libstb, which frugal's loaders use (a
# program then fails or corrupts memory in tinygltf: the copies are built differently). So the
# archive is copied with that member deleted, at configure time; the codec's members need nothing
# from it. The program needs no libdraco at run time. Included by the build and by the installed
# package's config (frugal's libraries are static, so their users link it too).
if(NOT TARGET frugal::draco)
  find_package(draco CONFIG REQUIRED)
  get_target_property(_frugal_draco_archive draco::draco_static IMPORTED_LOCATION_NONE)
  if(NOT _frugal_draco_archive)
    get_target_property(_frugal_draco_archive draco::draco_static LOCATION)
  endif()
  get_target_property(_frugal_draco_include draco::draco_static INTERFACE_INCLUDE_DIRECTORIES)
  set(_frugal_draco_copy "${CMAKE_BINARY_DIR}/frugal-draco/libdraco-codec.a")
  if(NOT EXISTS "${_frugal_draco_copy}" OR "${_frugal_draco_archive}" IS_NEWER_THAN "${_frugal_draco_copy}")
    file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/frugal-draco")
    file(COPY_FILE "${_frugal_draco_archive}" "${_frugal_draco_copy}")
    execute_process(COMMAND "${CMAKE_AR}" d "${_frugal_draco_copy}" tiny_gltf_utils.cc.o
                    RESULT_VARIABLE _frugal_draco_result OUTPUT_QUIET ERROR_QUIET)
    execute_process(COMMAND "${CMAKE_AR}" t "${_frugal_draco_copy}" OUTPUT_VARIABLE _frugal_draco_members)
    if(_frugal_draco_members MATCHES "tiny_gltf_utils")
      message(FATAL_ERROR "could not remove tiny_gltf_utils.cc.o from ${_frugal_draco_copy} (${CMAKE_AR})")
    endif()
  endif()
  add_library(frugal::draco STATIC IMPORTED)
  set_target_properties(frugal::draco PROPERTIES
    IMPORTED_LOCATION "${_frugal_draco_copy}"
    INTERFACE_INCLUDE_DIRECTORIES "${_frugal_draco_include}")
endif()
