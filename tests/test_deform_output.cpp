// What jade deform writes: the animated GIF (save_animation's frames and frame rate, read back
// byte by byte) and the command's frames, GIF and stage table, and its usage errors.
#include "test_support.hpp"

#include <jade/error.hpp>
#include <jade/io.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace jade {
namespace {

TEST(DeformAnimation, AnimatedGifHasEveryFrameAndTheFrameRate)
{
    const auto path = test::out("deform_anim.gif");
    std::vector<std::vector<float>> frames;
    for (int f = 0; f < 5; ++f) frames.emplace_back(size_t(16 * 8 * 4), float(f) / 4.0f);
    save_animation(path, 16, 8, frames, 4.0);
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 13u);
    EXPECT_EQ(bytes.substr(0, 6), "GIF89a");
    EXPECT_EQ(uint8_t(bytes[6]), 16);  // logical screen width, little-endian
    EXPECT_EQ(uint8_t(bytes[8]), 8);
    // One graphic control extension per frame (21 F9 04 flags delay-lo delay-hi ...), each
    // with a delay of 100/4 = 25 hundredths of a second.
    int frames_found = 0;
    for (size_t at = bytes.find("\x21\xf9\x04"); at != std::string::npos; at = bytes.find("\x21\xf9\x04", at + 3)) {
        ++frames_found;
        EXPECT_EQ(uint8_t(bytes[at + 4]) | (uint8_t(bytes[at + 5]) << 8), 25);
    }
    EXPECT_EQ(frames_found, 5);
    EXPECT_THROW(save_animation(test::out("deform_anim.png"), 16, 8, frames, 4.0), Error);
    EXPECT_THROW(save_animation(path, 16, 8, {}, 4.0), Error);
}

TEST(DeformCli, WritesFramesGifAndTheStageTable)
{
    const auto dir = test::out("deform_cli/frame_000.png").parent_path();
    std::filesystem::remove_all(dir);  // written by the CLI (it creates the folder)
    const auto r = test::run_cli({"deform", test::data("skinned_morph_anim.gltf").string(), "--deformer", "gltf",
                                  "--frames", "3", "--size", "64x64", "--out", dir.string(), "--validation"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* f : {"frame_000.png", "frame_002.png", "deform.gif"})
        EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
    for (const char* word : {"deform", "normals", "bake AO", "bake t_m", "draw", "average"})
        EXPECT_NE(r.output.find(word), std::string::npos) << word << "\n" << r.output;
    const auto twist =
        test::run_cli({"deform", test::data("cube_seams.gltf").string(), "--deformer", "twist", "--frames", "2",
                       "--size", "32x32", "--out", dir.string(), "--anim", "twist.gif"});
    ASSERT_EQ(twist.exit_code, 0) << twist.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "twist.gif"));
}

TEST(DeformCli, BadArgumentsNameTheFlag)
{
    const auto bad = test::run_cli({"deform", "--deformer", "spin"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.output.find("--deformer"), std::string::npos) << bad.output;
    const auto amp =
        test::run_cli({"deform", test::data("cube_seams.gltf").string(), "--deformer", "squash", "--amplitude", "1.5"});
    EXPECT_EQ(amp.exit_code, 2);
    EXPECT_NE(amp.output.find("squash amplitude"), std::string::npos) << amp.output;
    const auto noanim = test::run_cli({"deform", test::data("cube_seams.gltf").string(), "--deformer", "gltf"});
    EXPECT_NE(noanim.exit_code, 0);
    EXPECT_NE(noanim.output.find("has no animation"), std::string::npos) << noanim.output;
}

}  // namespace
}  // namespace jade
