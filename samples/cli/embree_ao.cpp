// embree_ao.cpp - see embree_ao.hpp.
#include "embree_ao.hpp"

#include "commands.hpp"

#include <jade/error.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#ifdef JADE_CLI_HAVE_EMBREE
#include <embree3/rtcore.h>

#include <glm/geometric.hpp>

#include <memory>
#endif

namespace jade::cli {

#ifndef JADE_CLI_HAVE_EMBREE

std::optional<EmbreeAo> embree_ao(const PreparedMesh&, const AoSettings&, unsigned) { return std::nullopt; }

#else

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// One owner per Embree handle.
struct DeviceDeleter {
    void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
    void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using DeviceHandle = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using SceneHandle = std::unique_ptr<RTCSceneTy, SceneDeleter>;

void check(RTCDevice device, const char* what)
{
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) throw Error(std::string("Embree: ") + what + " failed (RTCError " + std::to_string(int(e)) + ")");
}

}  // namespace

std::optional<EmbreeAo> embree_ao(const PreparedMesh& mesh, const AoSettings& settings, unsigned repeat)
{
    EmbreeAo out;
    out.version = RTC_VERSION_STRING;
    const size_t n = mesh.vertex_count();
    DeviceHandle device(rtcNewDevice(nullptr));
    if (!device) throw Error("Embree: rtcNewDevice failed");

    auto t0 = Clock::now();
    SceneHandle scene(rtcNewScene(device.get()));
    check(device.get(), "rtcNewScene");
    rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_HIGH);  // a static bake: best tree
    RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    // rtcSetNewGeometryBuffer pads the vertex buffer for Embree's 16-byte loads.
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), n));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.triangle_count()));
    check(device.get(), "rtcSetNewGeometryBuffer");
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) vertices[3 * i + c] = mesh.positions[i][c];
    std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene.get(), geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene.get());
    check(device.get(), "rtcCommitScene");
    out.build_ms = ms_since(t0);

    const float eps = settings.epsilon_rel * mesh.diagonal;           // mesh units
    const float t_max = settings.max_distance_rel * mesh.diagonal;    // mesh units
    out.threads = std::max(1u, std::thread::hardware_concurrency());
    out.ao.assign(n, 0.0f);
    // The ray directions are made before the clock starts: Embree is timed on the queries
    // alone (the GPU pass's time includes making its rays), the strictest yardstick.
    std::vector<glm::vec3> directions(n * settings.rays);
    for (size_t v = 0; v < n; ++v)
        for (uint32_t k = 0; k < settings.rays; ++k)
            directions[v * settings.rays + k] = ao_ray_direction(mesh.normals[v], uint32_t(v), k, settings);
    for (unsigned rep = 0; rep < std::max(1u, repeat); ++rep) {
        std::atomic<size_t> next{0};
        auto worker = [&] {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            constexpr size_t kChunk = 64;
            for (size_t b; (b = next.fetch_add(kChunk)) < n;)
                for (size_t v = b, e = std::min(n, b + kChunk); v < e; ++v) {
                    const glm::vec3 normal = mesh.normals[v];
                    const glm::vec3 origin = mesh.positions[v] + eps * normal;
                    uint32_t hits = 0;
                    for (uint32_t k = 0; k < settings.rays; ++k) {
                        const glm::vec3 d = directions[v * settings.rays + k];
                        RTCRay ray{};
                        ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
                        ray.dir_x = d.x, ray.dir_y = d.y, ray.dir_z = d.z;
                        ray.tnear = 0.0f;
                        ray.tfar = t_max;
                        ray.mask = ~0u;
                        rtcOccluded1(scene.get(), &context, &ray);
                        hits += ray.tfar < 0.0f ? 1u : 0u;  // Embree sets tfar to -inf on a hit
                    }
                    out.ao[v] = float(double(hits) / double(settings.rays));
                }
        };
        t0 = Clock::now();
        std::vector<std::thread> pool;
        for (unsigned t = 1; t < out.threads; ++t) pool.emplace_back(worker);
        worker();
        for (auto& t : pool) t.join();
        const double ms = ms_since(t0);
        out.trace_ms = rep == 0 ? ms : std::min(out.trace_ms, ms);
    }
    check(device.get(), "rtcOccluded1");
    return out;
}

#endif

void print_embree_line(const PreparedMesh& p, const AoSettings& ao, double gpu_ao_ms, std::span<const float> gpu_ao)
{
    const auto embree = embree_ao(p, ao);
    if (!embree) {
        std::printf("Embree CPU AO          (not built in: install libembree-dev and reconfigure)\n");
        return;
    }
    const double rays = double(p.vertex_count()) * ao.rays;
    std::printf("Embree %s CPU AO   %10s   %.2f Mrays/s, %u rays/vertex on %u threads (BVH build %s not counted); "
                "GPU AO takes %.2fx Embree's time",
                embree->version.c_str(), format_ms(embree->trace_ms).c_str(), rays / (embree->trace_ms * 1e3), ao.rays,
                embree->threads, format_ms(embree->build_ms).c_str(), gpu_ao_ms / embree->trace_ms);
    if (gpu_ao.size() == embree->ao.size()) {
        size_t same = 0;
        for (size_t i = 0; i < gpu_ao.size(); ++i) same += embree->ao[i] == gpu_ao[i];
        std::printf("; %.2f%% of vertices identical", 100.0 * double(same) / double(gpu_ao.size()));
    }
    std::printf("\n");
}

}  // namespace jade::cli
