// The third-party parsers the loaders hand bytes to, compiled into the fuzzers with instrumentation
// (see CMakeLists.txt): tinygltf (JSON via nlohmann, images via stb_image), tinyobjloader, and the
// stb_image that io/ImageIO.cpp decodes PNGs with. Same headers and defaults as Debian's build.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
