// io/image_none.cpp - jade::save_image and friends in a build without OpenImageIO
// (JADE_WITH_OIIO=OFF, for a binary that must carry few shared libraries, such as the GPU
// benchmark pack in tools/gpu_pack/): every image call fails with a clear message.
#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include "io/common.hpp"
#include "io/gltf_thickness_map.hpp"

namespace jade {

namespace {
[[noreturn]] void no_images(const std::filesystem::path& path)
{
    io::fail(path.string(), "this build of Jade reads and writes no images (configured with JADE_WITH_OIIO=OFF)");
}
}  // namespace

void save_animation(const std::filesystem::path& path, int, int, const std::vector<std::vector<float>>&, double)
{
    no_images(path);
}
void save_image(const std::filesystem::path& path, int, int, const std::vector<float>&) { no_images(path); }
dev::LoadedImage dev::load_image(const std::filesystem::path& path) { no_images(path); }

std::vector<unsigned char> io::encode_thickness_png(const std::string& file, const io::ThicknessMap&)
{
    no_images(file);
}

}  // namespace jade
