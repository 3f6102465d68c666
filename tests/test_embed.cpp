// Embedding: a jade::Context that adopts a host's Vulkan objects, and samples/embed,
// the host program that draws its own ground and Jade's sphere into one frame.
// The host instance here has the validation layer on and every test fails on any message.
#include "test_support.hpp"

#include "embed/scene.hpp"  // the sample's frame size, ground and camera
#include "vk_instance.hpp"  // samples/common: the hosts' instance and device choice

#include <jade/dev/bake.hpp>
#include <jade/dev/context.hpp>
#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/render.hpp>

#include <gtest/gtest.h>
// The sample's PNG is read with OpenImageIO, which jade::io links already.
#include <OpenImageIO/imageio.h>

#include <glm/mat4x4.hpp>

#include <cmath>
#include <cstdlib>
#include <sys/wait.h>
#include <string>
#include <vector>

using namespace jade;

namespace {

uint32_t host_messages = 0;

VKAPI_ATTR VkBool32 VKAPI_CALL count_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void*)
{
    ++host_messages;
    ADD_FAILURE() << "validation: " << (data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

samples::Instance validated_instance()
{
    samples::InstanceOptions options;
    options.validation = true;
    options.on_message = &count_message;
    return samples::create_instance(options);
}

// A minimal host: its own instance (validation on) and a device with or without what Jade needs.
struct Host {
    samples::Instance instance = validated_instance();
    // The same device Jade's own Context picks when JADE_DEVICE names one.
    samples::DeviceChoice choice = samples::find_device(instance.instance, std::getenv("JADE_DEVICE"));
    HostDeviceSetup setup;  // Jade's features and extensions, or none
    samples::Owned<VkDevice> device;
    VkQueue queue = VK_NULL_HANDLE;

    explicit Host(bool with_jade_requirements, bool timeline_semaphores = false) : setup(with_jade_requirements)
    {
        setup.f12.timelineSemaphore = timeline_semaphores ? VK_TRUE : VK_FALSE;
        device = samples::Owned<VkDevice>(setup.create(choice.physical, choice.family),
                                          [](VkDevice d) { vkDestroyDevice(d, nullptr); });
        vkGetDeviceQueue(device, choice.family, 0, &queue);
    }
    AdoptedVulkan adopted() const
    {
        return setup.adopted(instance.instance, choice.physical, device, choice.family, queue);
    }
};

class Embed : public ::testing::Test {
protected:
    void SetUp() override { host_messages = 0; }
    void TearDown() override { EXPECT_EQ(host_messages, 0u) << "Vulkan validation reported messages"; }
};

}  // namespace

TEST_F(Embed, AdoptionListsEverythingTheHostsDeviceLacks)
{
    Host host(false);  // a Vulkan 1.3 device created with no extension and no 1.2/1.3 feature
    try {
        Context context(host.adopted());
        FAIL() << "adopting a device without Jade's features must throw";
    } catch (const Error& e) {
        const std::string msg = e.what();
        for (const char* missing : {"VK_KHR_push_descriptor", "dynamicRendering", "synchronization2", "maintenance4",
                                    "scalarBlockLayout", "hostQueryReset"})
            EXPECT_NE(msg.find(missing), std::string::npos) << missing << " not named in: " << msg;
        EXPECT_NE(msg.find("adopted Vulkan device"), std::string::npos) << msg;
    }
    AdoptedVulkan bad = host.adopted();
    bad.device = VK_NULL_HANDLE;
    EXPECT_THROW(Context{bad}, Error);
    bad = host.adopted();
    bad.api_version = VK_API_VERSION_1_1;
    bad.queue_family = 999;
    try {
        Context context(bad);
        FAIL() << "must throw";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("apiVersion 1.3"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("queue family 999"), std::string::npos) << e.what();
    }
}

TEST_F(Embed, AdoptedContextBakesLikeAnOwnedOneAndLeavesTheDeviceAlive)
{
    const PreparedMesh sphere = prepare_mesh(procedural::sphere(1.0f, 12, 16));
    const Material material = burley_material({0.3, 0.2, 0.1}, glm::vec3(0.8f));
    const BakeSettings settings = BakeSettings::preset(Quality::Draft);
    BakeResult owned;
    {
        ContextOptions o;
        o.validation = true;
        Context context(o);
        owned = Baker(context).bake(sphere, material, settings);
        EXPECT_EQ(dev::validation_messages(context), 0u);
    }
    Host host(true);
    BakeResult adopted;
    {
        Context context(host.adopted());
        EXPECT_TRUE(context.adopted());
        adopted = Baker(context).bake(sphere, material, settings);
    }
    ASSERT_EQ(adopted.tm.size(), sphere.vertex_count());
    ASSERT_EQ(owned.tm.size(), adopted.tm.size());
    // Same shaders, same inputs, same kind of device: the same numbers (up to the device's
    // reduction order, which is deterministic for a fixed device).
    for (size_t i = 0; i < owned.tm.size(); ++i)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(adopted.tm[i][c], owned.tm[i][c], 1e-5f * (1.0f + owned.tm[i][c])) << i;
    EXPECT_GT(adopted.tm[0].r, 0.0f);
    // The device and queue are still the host's and usable after ~Context.
    EXPECT_EQ(vkQueueWaitIdle(host.queue), VK_SUCCESS);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateFence(host.device, &fci, nullptr, &fence), VK_SUCCESS);
    vkDestroyFence(host.device, fence, nullptr);
}

// The grid far field splats with two 64-bit atomics a tap where the device has
// shaderBufferInt64Atomics, and with four 32-bit ones where it does not (a host's device that
// did not enable them): the same fixed-point sums either way, so the same bake, bit for bit.
TEST_F(Embed, GridSplatWithoutInt64AtomicsBakesTheSameBits)
{
    const PreparedMesh sphere = prepare_mesh(procedural::sphere(1.0f, 48, 64));
    const Material material = burley_material({0.4, 0.2, 0.1}, glm::vec3(0.8f));
    BakeSettings settings = BakeSettings::preset(Quality::Default);
    settings.method = TmMethod::Grid;
    std::vector<float> ao(sphere.vertex_count());
    for (size_t i = 0; i < ao.size(); ++i) ao[i] = 0.5f + 0.4f * std::sin(0.37f * float(i));
    BakeResult packed;
    {
        ContextOptions o;
        o.validation = true;
        Context context(o);
        if (!dev::device_info(context).int64_atomics)
            GTEST_SKIP() << dev::device_info(context).name << " has no 64-bit buffer atomics";
        packed = [&] {
            Baker baker(context);
            return dev::bake_tm(baker, sphere, ao, material, settings);
        }();
        EXPECT_EQ(dev::validation_messages(context), 0u);
    }
    Host host(true);  // Jade's required features only: no shaderInt64, no 64-bit atomics
    BakeResult four;
    {
        Context context(host.adopted());
        EXPECT_FALSE(dev::device_info(context).int64_atomics);
        four = [&] {
            Baker baker(context);
            return dev::bake_tm(baker, sphere, ao, material, settings);
        }();
    }
    ASSERT_EQ(packed.method_used, TmMethod::Grid);
    ASSERT_EQ(four.method_used, TmMethod::Grid);
    ASSERT_EQ(packed.tm.size(), four.tm.size());
    ASSERT_GT(packed.tm_bytes, (1u << 20)) << "the profile must reach past the near field: grids in use";
    for (size_t i = 0; i < packed.tm.size(); ++i) {
        ASSERT_EQ(packed.tm[i], four.tm[i]) << "vertex " << i;
        ASSERT_EQ(packed.scattering_normal[i], four.scattering_normal[i]) << "vertex " << i;
        ASSERT_EQ(packed.normal_spread[i], four.normal_spread[i]) << "vertex " << i;
    }
}

// Jade never waits for the host's device: what it lets go of while recorded work is pending
// outlives that work. The host's command buffer waits on a timeline semaphore that only the host
// signals, after the Jade calls, so a vkDeviceWaitIdle (or a wait for the queue) in any of them
// would never return; and the validation layer reports any object destroyed while the command
// buffer that uses it is pending.
TEST_F(Embed, ReleasesWhatRecordedWorkUsesWithoutWaitingForTheHost)
{
    const PreparedMesh sphere = prepare_mesh(procedural::sphere(1.0f, 12, 16));
    const Material material = burley_material({0.3, 0.2, 0.1}, glm::vec3(0.8f));
    Host host(true, true);
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.queueFamilyIndex = host.choice.family;
    VkCommandPool pool = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateCommandPool(host.device, &pci, nullptr, &pool), VK_SUCCESS);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateCommandBuffers(host.device, &ai, &cmd), VK_SUCCESS);
    VkSemaphoreTypeCreateInfo timeline{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    timeline.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, &timeline};
    VkSemaphore gate = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateSemaphore(host.device, &sci, nullptr, &gate), VK_SUCCESS);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence done = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateFence(host.device, &fci, nullptr, &done), VK_SUCCESS);
    {
        Context context(host.adopted());
        Baker baker(context);
        auto renderer = std::make_unique<Renderer>(context);
        renderer->set_mesh(sphere);
        renderer->set_material(material);
        auto rebake = std::make_unique<DynamicBake>(baker, sphere, material, BakeSettings::preset(Quality::Draft));

        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        ASSERT_EQ(vkBeginCommandBuffer(cmd, &bi), VK_SUCCESS);
        rebake->record(cmd);
        ASSERT_EQ(vkEndCommandBuffer(cmd), VK_SUCCESS);
        VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        wait.semaphore = gate;
        wait.value = 1;
        wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        cbi.commandBuffer = cmd;
        VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        si.waitSemaphoreInfoCount = 1;
        si.pWaitSemaphoreInfos = &wait;
        si.commandBufferInfoCount = 1;
        si.pCommandBufferInfos = &cbi;
        ASSERT_EQ(vkQueueSubmit2(host.queue, 1, &si, done), VK_SUCCESS);

        // While the re-bake waits for the gate: new per-slice sums (the recorded work writes
        // the old ones), then the whole DynamicBake and the Renderer go. Each call returns.
        rebake->set_amortisation({2, 1});
        rebake.reset();
        renderer.reset();
        EXPECT_EQ(vkGetFenceStatus(host.device, done), VK_NOT_READY) << "the gated work ran early";

        VkSemaphoreSignalInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO};
        signal.semaphore = gate;
        signal.value = 1;
        ASSERT_EQ(vkSignalSemaphore(host.device, &signal), VK_SUCCESS);
        ASSERT_EQ(vkWaitForFences(host.device, 1, &done, VK_TRUE, UINT64_MAX), VK_SUCCESS);
        // A later bake on the same Context frees what the GPU is done with; ~Context the rest.
        EXPECT_GT(baker.bake(sphere, material, BakeSettings::preset(Quality::Draft)).tm.size(), 0u);
    }
    vkDestroyFence(host.device, done, nullptr);
    vkDestroySemaphore(host.device, gate, nullptr);
    vkDestroyCommandPool(host.device, pool, nullptr);
}

namespace {

// samples/embed's binary: JADE_EMBED (the out-of-tree consumer tests point it at theirs), else
// the one built with the suite.
std::string embed_executable()
{
    const char* v = std::getenv("JADE_EMBED");
    return v && *v ? v : JADE_DEFAULT_EMBED;
}

std::vector<float> read_png(const std::filesystem::path& path, int& width, int& height)
{
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return {};
    width = in->spec().width;
    height = in->spec().height;
    std::vector<float> pixels(size_t(width) * height * 4);
    if (in->spec().nchannels != 4 || !in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data())) return {};
    return pixels;
}

}  // namespace

TEST_F(Embed, SampleDrawsTheTranslucentSphereIntoTheHostsFrame)
{
    const auto png = test::out("embed/frame.png");
    const std::string cmd = "'" + embed_executable() + "' '" + png.string() + "' --validation 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) output.append(buf, n);
    const int status = pclose(pipe);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd << "\n" << output;  // 2: validation messages

    int w = 0, h = 0;
    const std::vector<float> img = read_png(png, w, h);
    ASSERT_EQ(w, int(samples::embed::kWidth));
    ASSERT_EQ(h, int(samples::embed::kHeight));
    auto px = [&](int x, int y) {
        return glm::vec3(img[(size_t(y) * w + x) * 4], img[(size_t(y) * w + x) * 4 + 1],
                         img[(size_t(y) * w + x) * 4 + 2]);
    };
    // The sample's camera, projected here to find where things are.
    const glm::mat4 clip = samples::embed::camera().view_projection(float(w) / float(h));
    auto to_pixel = [&](glm::vec3 p) {
        glm::vec4 c = clip * glm::vec4(p, 1.0f);
        return glm::ivec2(int((c.x / c.w * 0.5f + 0.5f) * w), int((c.y / c.w * 0.5f + 0.5f) * h));
    };
    // The host's sky (clear colour 0.45, 0.6, 0.85 linear, sRGB-encoded by the PNG writer) in
    // the top-left corner, its grey checkerboard ground below the sphere.
    const glm::vec3 sky = px(2, 2);
    EXPECT_NEAR(sky.r, 0.70, 0.02);
    EXPECT_NEAR(sky.g, 0.80, 0.02);
    EXPECT_NEAR(sky.b, 0.93, 0.02);
    // Ground (plane y = kGroundHeight) in front of and beside the sphere.
    const float ground = samples::embed::kGroundHeight;
    for (glm::vec3 p : {glm::vec3(1.4f, ground, 1.0f), glm::vec3(-1.5f, ground, 0.5f)}) {
        const glm::ivec2 q = to_pixel(p);
        const glm::vec3 g = px(q.x, q.y);
        EXPECT_NEAR(g.r, g.g, 1e-3f) << q.x << "," << q.y;
        EXPECT_NEAR(g.g, g.b, 1e-3f) << q.x << "," << q.y;
        EXPECT_GT(g.r, 0.3f);
    }
    // The sphere (radius 1 at the origin): Jade's jade-green shading, neither sky nor grey,
    // across its projected disk above the ground.
    auto jade_green = [&](glm::vec3 c) {
        const bool greyish = std::abs(c.r - c.g) < 0.02f && std::abs(c.g - c.b) < 0.02f;
        return !greyish && glm::length(c - sky) > 0.05f && c.g > c.r && c.g > c.b;
    };
    int sphere_pixels = 0, tested = 0;
    for (float dx : {-0.6f, -0.3f, 0.0f, 0.3f, 0.6f})
        for (float dy : {-0.3f, 0.0f, 0.3f, 0.6f}) {
            const glm::ivec2 p = to_pixel({dx, dy, std::sqrt(1.0f - dx * dx - dy * dy)});
            ++tested;
            if (jade_green(px(p.x, p.y))) ++sphere_pixels;
        }
    EXPECT_EQ(sphere_pixels, tested) << "the sphere is missing from the host's frame";
    // Depth is shared: the sphere's front surface below the ground plane is hidden by the
    // host's ground, which was drawn first.
    for (glm::vec3 p : {glm::vec3(0.0f, -0.8f, 0.6f), glm::vec3(0.3f, -0.75f, 0.59f)}) {
        const glm::ivec2 q = to_pixel(p);
        const glm::vec3 c = px(q.x, q.y);
        EXPECT_NEAR(c.r, c.g, 1e-3f) << "sphere drawn through the ground at " << q.x << "," << q.y;
        EXPECT_NEAR(c.g, c.b, 1e-3f);
    }
    // A translucent jade sphere is lit: its centre is not black.
    const glm::ivec2 centre = to_pixel({0.0f, 0.0f, 0.0f});
    EXPECT_GT(px(centre.x, centre.y).g, 0.1f);
}

TEST(EmbedCamera, ViewProjectionNeedsExplicitPlanesAndMapsThemToDepthZeroAndOne)
{
    Camera camera;                                      // eye (0, 0, 5) looking at the origin
    EXPECT_THROW(camera.view_projection(1.0f), Error);  // planes 0, 0: fitted per mesh, no matrix
    camera.near_plane = 1.0f;
    camera.far_plane = 9.0f;
    EXPECT_THROW(camera.view_projection(0.0f), Error);
    const glm::mat4 m = camera.view_projection(2.0f);
    auto ndc = [&](glm::vec3 p) {
        glm::vec4 c = m * glm::vec4(p, 1.0f);
        return glm::vec3(c) / c.w;
    };
    EXPECT_NEAR(ndc({0, 0, 4}).z, 0.0f, 1e-6f);   // 1 unit from the eye: the near plane
    EXPECT_NEAR(ndc({0, 0, -4}).z, 1.0f, 1e-6f);  // 9 units: the far plane
    // y flipped for Vulkan: a point above the target lands in the upper half (negative y).
    EXPECT_LT(ndc({0, 1, 0}).y, 0.0f);
    // The top of the field of view (30 degrees) at distance 5 is y = -1.
    EXPECT_NEAR(ndc({0, 5.0f * std::tan(15.0f * 3.14159265f / 180.0f), 0}).y, -1.0f, 1e-5f);
}
