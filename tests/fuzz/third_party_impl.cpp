// The implementations of tinygltf and tinyobjloader, compiled into the fuzz targets so that the
// parsers Jade relies on are instrumented too (coverage feedback for libFuzzer, ASan and UBSan
// checks inside them). Debian ships both as uninstrumented shared libraries; the definitions
// here are linked into each executable as an object library and take precedence over the
// copies in libtinygltf.so / libtinyobjloader.so, which are built from the same headers.
// Images are not decoded by Jade (io/gltf_model.cpp installs a loader that skips them), but the
// default stb_image callbacks are referenced by tinygltf and come from libstb.
#define TINYGLTF_IMPLEMENTATION
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_gltf.h>
#include <tiny_obj_loader.h>
