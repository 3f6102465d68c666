// embree_ao.cpp - see embree_ao.hpp.
#include "embree_ao.hpp"

#include "commands.hpp"

#include <jade/dev/bake.hpp>
#include <jade/dev/clock.hpp>
#include <jade/error.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#ifdef JADE_CLI_HAVE_EMBREE
#include <embree3/rtcore.h>

#include <glm/geometric.hpp>
#endif

namespace jade::cli {
namespace {

#ifdef JADE_CLI_HAVE_EMBREE

// One owner per Embree handle.
struct DeviceDeleter {
    void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
    void operator()(RTCScene s) const { rtcReleaseScene(s); }
};

void check(RTCDevice device, const char* what)
{
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
        throw Error(std::string("Embree: ") + what + " failed (RTCError " + std::to_string(int(e)) + ")");
}

/// A mesh's triangles in an Embree scene (high-quality build), ready to trace AO rays.
class EmbreeAo {
public:
    explicit EmbreeAo(const PreparedMesh& mesh) : mesh_(mesh)
    {
        version = RTC_VERSION_STRING;
        threads = std::max(1u, std::thread::hardware_concurrency());
        device_.reset(rtcNewDevice(nullptr));
        if (!device_) throw Error("Embree: rtcNewDevice failed");
        const auto t0 = Clock::now();
        scene_.reset(rtcNewScene(device_.get()));
        check(device_.get(), "rtcNewScene");
        rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);  // a static bake: the best tree
        RTCGeometry geometry = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
        // rtcSetNewGeometryBuffer pads the vertex buffer for Embree's 16-byte loads.
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertex_count()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangle_count()));
        check(device_.get(), "rtcSetNewGeometryBuffer");
        for (size_t i = 0; i < mesh.vertex_count(); ++i)
            for (int c = 0; c < 3; ++c) vertices[3 * i + c] = mesh.positions[i][c];
        std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_.get(), geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene_.get());
        check(device_.get(), "rtcCommitScene");
        build_ms = ms_since(t0);
    }

    /// A_o per bake vertex, as dev::bake_ao; trace_ms: the queries' wall time.
    std::vector<float> trace(const AoSettings& settings, double& trace_ms)
    {
        const size_t n = mesh_.vertex_count();
        const uint32_t rays = settings.rays;
        const float eps = settings.ray_offset_rel * mesh_.diagonal;      // mesh units
        const float t_max = settings.max_distance_rel * mesh_.diagonal;  // mesh units
        std::vector<glm::vec3> directions(n * rays);
        for (size_t v = 0; v < n; ++v)
            for (uint32_t k = 0; k < rays; ++k)
                directions[v * rays + k] = ao_ray_direction(mesh_.normals[v], uint32_t(v), k, settings);
        std::vector<float> ao(n, 0.0f);
        std::atomic<size_t> next{0};
        auto worker = [&] {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            constexpr size_t kChunk = 64;
            for (size_t b; (b = next.fetch_add(kChunk)) < n;)
                for (size_t v = b, e = std::min(n, b + kChunk); v < e; ++v) {
                    const glm::vec3 origin = mesh_.positions[v] + eps * mesh_.normals[v];
                    uint32_t hits = 0;
                    for (uint32_t k = 0; k < rays; ++k) {
                        const glm::vec3 d = directions[v * rays + k];
                        RTCRay ray{};
                        ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
                        ray.dir_x = d.x, ray.dir_y = d.y, ray.dir_z = d.z;
                        ray.tnear = 0.0f;
                        ray.tfar = t_max;
                        ray.mask = ~0u;
                        rtcOccluded1(scene_.get(), &context, &ray);
                        hits += ray.tfar < 0.0f ? 1u : 0u;  // Embree sets tfar to -inf on a hit
                    }
                    ao[v] = float(double(hits) / double(rays));
                }
        };
        const auto t0 = Clock::now();
        std::vector<std::thread> pool;
        for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
        worker();
        for (auto& t : pool) t.join();
        trace_ms = ms_since(t0);
        check(device_.get(), "rtcOccluded1");
        return ao;
    }

    double build_ms = 0;  ///< the scene (BVH) build, wall
    unsigned threads = 1;
    std::string version;

private:
    const PreparedMesh& mesh_;
    std::unique_ptr<RTCDeviceTy, DeviceDeleter> device_;
    std::unique_ptr<RTCSceneTy, SceneDeleter> scene_;
};

#endif

}  // namespace

#ifndef JADE_CLI_HAVE_EMBREE

void compare_ao_with_embree(Baker&, const PreparedMesh&, const AoSettings&, unsigned)
{
    std::printf("AO vs Embree: not built in (install libembree-dev and reconfigure)\n");
}

#else

void compare_ao_with_embree(Baker& baker, const PreparedMesh& mesh, const AoSettings& settings, unsigned pairs)
{
    EmbreeAo embree(mesh);
    std::vector<double> gpu_ms, cpu_ms, ratio;
    std::vector<float> gpu_ao, cpu_ao;
    for (unsigned i = 0; i < std::max(1u, pairs); ++i) {
        BakeTimings timings;
        gpu_ao = dev::bake_ao(baker, mesh, settings, &timings);
        double embree_ms = 0;
        cpu_ao = embree.trace(settings, embree_ms);
        gpu_ms.push_back(timings.gpu_total_ms);
        cpu_ms.push_back(embree_ms);
        ratio.push_back(timings.gpu_total_ms / embree_ms);
    }
    size_t same = 0;
    for (size_t v = 0; v < gpu_ao.size(); ++v) same += gpu_ao[v] == cpu_ao[v];
    const double rays = double(mesh.vertex_count()) * settings.rays;
    std::printf("AO vs Embree %s on the same %u rays/vertex, %zu alternating runs (Embree: %u threads, queries only, "
                "BVH build %s not counted):\n",
                embree.version.c_str(), settings.rays, ratio.size(), embree.threads,
                format_ms(embree.build_ms).c_str());
    std::printf("  GPU AO pass          %10s median (min %s)   %.2f Mrays/s\n",
                format_ms(quantile(gpu_ms, 0.5)).c_str(), format_ms(quantile(gpu_ms, 0.0)).c_str(),
                rays / (quantile(gpu_ms, 0.5) * 1e3));
    std::printf("  Embree CPU           %10s median (min %s)   %.2f Mrays/s\n",
                format_ms(quantile(cpu_ms, 0.5)).c_str(), format_ms(quantile(cpu_ms, 0.0)).c_str(),
                rays / (quantile(cpu_ms, 0.5) * 1e3));
    std::printf("  GPU / Embree time    %10.2fx median of the per-run ratios (quartiles %.2f-%.2f); %.2f%% of vertices "
                "identical\n",
                quantile(ratio, 0.5), quantile(ratio, 0.25), quantile(ratio, 0.75),
                100.0 * double(same) / double(gpu_ao.size()));
}

#endif

}  // namespace jade::cli
