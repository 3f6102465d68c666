// The interactive viewer (samples/viewer, `jade view`) in a real window, under Xvfb: it opens
// the window, renders frames with the validation layer on, reads back the presented swapchain
// image and compares it with the headless `jade render` of the same camera, lights, material
// and shading. Run by tests/run_under_xvfb.sh (ctest: viewer_xvfb), which starts Xvfb and sets
// DISPLAY; without DISPLAY every test here is skipped with a message.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace jade {
namespace {

// An 8-bit RGB image as stored in the PNG (sRGB values).
struct Image8 {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    const unsigned char* px(int x, int y) const { return rgb.data() + (size_t(y) * width + x) * 3; }
};

Image8 read_png(const std::filesystem::path& path)
{
    Image8 img;
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return img;
    img.width = in->spec().width;
    img.height = in->spec().height;
    img.rgb.resize(size_t(img.width) * img.height * 3);
    if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, img.rgb.data())) img.rgb.clear();
    return img;
}

struct Rect {
    int x = 0, y = 0, w = 0, h = 0;
    bool contains(int px, int py) const { return px >= x && px < x + w && py >= y && py < y + h; }
};
using Rects = std::vector<Rect>;
bool inside(const Rects& rects, int x, int y)
{
    for (const Rect& r : rects)
        if (r.contains(x, y)) return true;
    return false;
}

// How two images differ over the pixels outside `excluded`: the largest channel difference in
// 8-bit steps, how many pixels differ by more than `tolerance` steps, how many pixels are not
// background (any channel > 8) in `a`.
struct Difference {
    int max_steps = 0;
    size_t over_tolerance = 0, compared = 0, covered = 0;
};

Difference compare(const Image8& a, const Image8& b, int tolerance, const Rects& excluded = {})
{
    Difference d;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (inside(excluded, x, y)) continue;
            ++d.compared;
            int worst = 0;
            bool covered = false;
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, std::abs(int(a.px(x, y)[c]) - int(b.px(x, y)[c])));
                covered |= a.px(x, y)[c] > 8;
            }
            d.max_steps = std::max(d.max_steps, worst);
            d.over_tolerance += worst > tolerance;
            d.covered += covered;
        }
    std::printf("  compared %zu pixels: max difference %d steps, %zu over %d steps, %zu not background\n", d.compared,
                d.max_steps, d.over_tolerance, tolerance, d.covered);
    return d;
}

// The viewer's frame is the headless render to within one 8-bit step (the blit's and the PNG
// writer's rounding of the same RGBA16F values) but for a few pixels.
void expect_one_step_apart(const Difference& d)
{
    EXPECT_LE(d.max_steps, 2);
    EXPECT_LE(d.over_tolerance, d.compared / 1000) << "pixels more than one step apart";
}

class ViewerXvfb : public ::testing::Test {
protected:
    static std::string bunny() { return test::asset("bunny00.off").string(); }
    void SetUp() override
    {
        const char* display = std::getenv("DISPLAY");
        if (!display || !*display) GTEST_SKIP() << "no DISPLAY: run under tests/run_under_xvfb.sh (ctest viewer_xvfb)";
    }
    // The viewer with the validation layer on; fails the test on any validation message.
    test::CliResult view(std::vector<std::string> args)
    {
        args.insert(args.begin(), "view");
        args.push_back("--validation");
        test::CliResult r = test::run_cli(args);
        EXPECT_EQ(r.exit_code, 0) << r.output;  // 2: the validation layer said something
        EXPECT_EQ(r.output.find("validation:"), std::string::npos) << r.output;
        return r;
    }
    // The headless reference: `jade render` with its defaults (framed from +z, default lights,
    // jade material at 100 mm across, default bake quality, tm shading, 4× MSAA, no tone map).
    Image8 reference(const std::string& mesh, const std::string& name, std::vector<std::string> extra = {},
                     const std::string& size = "400x300")
    {
        const auto png = test::out("viewer/" + name + "_reference.png");
        std::vector<std::string> args{"render", mesh, "--size", size, "--out", png.string()};
        args.insert(args.end(), extra.begin(), extra.end());
        const test::CliResult r = test::run_cli(args);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        return read_png(png);
    }
};

// Without the panel the whole presented frame is Jade's draw: it matches the headless render
// to within one 8-bit step (the blit's and the PNG writer's rounding of the same RGBA16F
// values).
TEST_F(ViewerXvfb, PresentedFrameMatchesHeadlessRender)
{
    const auto shot = test::out("viewer/bunny_no_ui.png");
    view({bunny(), "--size", "400x300", "--frames", "3", "--no-ui", "--screenshot", shot.string()});
    const Image8 viewer = read_png(shot), ref = reference(bunny(), "bunny");
    ASSERT_EQ(viewer.width, 400);
    ASSERT_EQ(viewer.height, 300);
    ASSERT_EQ(ref.width, 400);
    ASSERT_EQ(ref.height, 300);
    const Difference d = compare(viewer, ref, 1);
    expect_one_step_apart(d);
    // The bunny is there (not two black frames): it covers a good part of the frame.
    EXPECT_GT(d.covered, d.compared / 10);
}

// A file written by `jade bake` is drawn with its own t_m, as `jade render` draws it: baked here
// with marble, the viewer's jade material would give another t_m if it baked again.
TEST_F(ViewerXvfb, BakedFileIsDrawnWithItsOwnTm)
{
    const auto baked = test::out("viewer/bunny_marble.glb");
    const test::CliResult b =
        test::run_cli({"bake", bunny(), "--out", baked.string(), "--quality", "draft", "--material", "marble"});
    ASSERT_EQ(b.exit_code, 0) << b.output;
    const auto shot = test::out("viewer/bunny_marble_no_ui.png");
    view({baked.string(), "--size", "200x150", "--frames", "2", "--no-ui", "--screenshot", shot.string()});
    const Image8 viewer = read_png(shot), ref = reference(baked.string(), "bunny_marble", {}, "200x150");
    const Difference d = compare(viewer, ref, 1);
    expect_one_step_apart(d);
    EXPECT_GT(d.covered, d.compared / 10);
}

// With the panel: outside the rectangles the viewer reports for its windows (controls on the
// left, timings overlay bottom right) the frame still matches the headless render; inside,
// the panel was drawn over it.
TEST_F(ViewerXvfb, PanelCoversOnlyItsRectangles)
{
    const auto shot = test::out("viewer/bunny_ui.png");
    const test::CliResult r = view({bunny(), "--size", "800x600", "--frames", "3", "--screenshot", shot.string()});
    Rects panel;
    for (size_t at = r.output.find("panel at "); at != std::string::npos; at = r.output.find("panel at ", at + 1)) {
        Rect p;
        ASSERT_EQ(std::sscanf(r.output.c_str() + at, "panel at %d,%d size %dx%d", &p.x, &p.y, &p.w, &p.h), 4)
            << r.output;
        panel.push_back(p);
    }
    ASSERT_EQ(panel.size(), 2u) << r.output;
    EXPECT_GT(panel[0].w, 100);  // the controls
    EXPECT_GT(panel[0].h, 100);
    const Image8 viewer = read_png(shot), ref = reference(bunny(), "bunny_800", {}, "800x600");
    ASSERT_EQ(viewer.width, 800);
    ASSERT_EQ(ref.width, 800);
    const Difference outside = compare(viewer, ref, 1, panel);
    expect_one_step_apart(outside);
    EXPECT_GT(outside.covered, outside.compared / 20);  // much of the bunny is outside the panel
    // Inside the controls window most pixels differ from Jade's frame (its opaque background
    // where the frame is black, text, widgets).
    const Difference all = compare(viewer, ref, 4);
    EXPECT_GT(all.over_tolerance, size_t(panel[0].w) * size_t(std::min(panel[0].h, 600 - panel[0].y)) / 2);
}

// Material, strength, light preset and bake quality reach the bake and the renderer: marble
// under the back light at draft quality matches `jade render` with the same flags.
TEST_F(ViewerXvfb, SettingsMatchTheCliFlags)
{
    const std::vector<std::string> flags{"--material", "marble",  "--strength", "2",
                                         "--lights",   "figure1", "--quality",  "draft"};
    const auto shot = test::out("viewer/bunny_marble.png");
    std::vector<std::string> args{bunny(), "--size",  "400x300",      "--frames",
                                  "2",     "--no-ui", "--screenshot", shot.string()};
    args.insert(args.end(), flags.begin(), flags.end());
    view(args);
    const Image8 viewer = read_png(shot), ref = reference(bunny(), "bunny_marble", flags);
    ASSERT_EQ(viewer.width, 400);
    ASSERT_EQ(ref.width, 400);
    expect_one_step_apart(compare(viewer, ref, 1));
    // ... and differ from the default settings' frame.
    const Difference from_default = compare(viewer, reference(bunny(), "bunny"), 8);
    EXPECT_GT(from_default.over_tolerance, from_default.compared / 20);
}

// A deforming mesh: MeshDeformer + DynamicBake every frame, validation clean; a bend at its
// full amplitude (t = period/4) moves the silhouette away from the undeformed one.
TEST_F(ViewerXvfb, DeformationRebakesEveryFrame)
{
    const auto bent = test::out("viewer/bunny_bend.png"), rest = test::out("viewer/bunny_rest.png");
    const test::CliResult r =
        view({bunny(), "--size", "200x150", "--frames", "2", "--no-ui", "--quality", "draft", "--deform", "bend",
              "--time", "0.5", "--no-animate", "--screenshot", bent.string()});
    EXPECT_NE(r.output.find("re-bake"), std::string::npos) << r.output;  // the stage table of the per-frame re-bake
    view({bunny(), "--size", "200x150", "--frames", "2", "--no-ui", "--quality", "draft", "--screenshot",
          rest.string()});
    const Image8 a = read_png(bent), b = read_png(rest);
    ASSERT_EQ(a.width, 200);
    ASSERT_EQ(b.width, 200);
    const Difference d = compare(a, b, 16);
    EXPECT_GT(d.over_tolerance, d.compared / 50) << "the bent bunny looks like the resting one";
}

// The layer's synchronization validation over every path of a frame: Jade's draw, the blit,
// the panel's render pass, the screenshot copy, the per-frame deform and re-bake.
TEST_F(ViewerXvfb, SynchronizationValidationIsClean)
{
    const auto shot = test::out("viewer/sync.png");
    setenv("JADE_SYNC_VALIDATION", "1", 1);
    const test::CliResult r = view({"sphere", "--size", "320x240", "--frames", "3", "--quality", "draft", "--deform",
                                    "twist", "--screenshot", shot.string()});
    unsetenv("JADE_SYNC_VALIDATION");
    EXPECT_NE(r.output.find("synchronization validation on"), std::string::npos) << r.output;
    EXPECT_EQ(read_png(shot).width, 320);
}

TEST_F(ViewerXvfb, BadArgumentsExitWithUsage)
{
    const test::CliResult r = test::run_cli({"view", "--frames", "many"});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--frames"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace jade
