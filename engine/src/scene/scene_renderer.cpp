// scene/scene_renderer.cpp - SceneRenderer: runs a ScenePlan.
//
// Construction runs the once-only passes (cache reads, static bakes with a Baker that is
// destroyed before the constructor returns, so no BVH, cluster tree or bake buffer outlives
// it) and gives every object a Renderer holding only its vertices (with t_m), indices and LUT.
// Deforming objects also keep a MeshDeformer and a DynamicBake. render() runs the per-frame
// passes, then records every object's draw into one set of targets (the first clears them,
// the others load them) and reads the image back.
#include <jade/dev/clock.hpp>
#include <jade/dev/names.hpp>
#include <jade/dev/overlay.hpp>
#include <jade/dev/scene.hpp>
#include <jade/scene.hpp>

#include "gpu/buffer.hpp"
#include "gpu/context.hpp"
#include "gpu/image.hpp"
#include "gpu/timer.hpp"
#include "shading/frame.hpp"
#include "shading/offscreen.hpp"

#include <jade/error.hpp>

#include <glm/geometric.hpp>

#include <chrono>
#include <optional>

namespace jade {

using dev::ObjectPlan;
using dev::PassKind;
using dev::PassPlan;
using dev::PassRecord;

namespace {

// An earlier instance's prepared mesh at this instance's place: its bake vertices, welding and
// triangles, moved rigidly (so that the shared bake's per-vertex values fit it).
PreparedMesh moved(const PreparedMesh& from, const InstanceOf& to)
{
    PreparedMesh m = from;
    for (glm::vec3& p : m.positions) p = to.rotation * p + to.translation;
    for (glm::vec3& n : m.normals) n = glm::normalize(to.rotation * n);
    m.bbox_min = m.bbox_max = m.positions.empty() ? glm::vec3(0.0f) : m.positions[0];
    for (const glm::vec3& p : m.positions) m.bbox_min = glm::min(m.bbox_min, p), m.bbox_max = glm::max(m.bbox_max, p);
    return m;
}

}  // namespace

struct SceneRenderer::Impl {
    Context& context;
    SceneSettings settings;
    ScenePlan plan;
    const std::vector<ObjectPlan>& planned;  // the plan's objects (plan.details)
    std::vector<PassRecord> passes;
    // The DynamicBakes use its pipelines: kept, and declared before the objects so that it
    // outlives them.
    std::unique_ptr<Baker> dynamic_baker;

    struct Object {
        PreparedMesh rest;
        mutable std::vector<glm::vec3> tm;                        // deforming: read back from the GPU by tm() only
        std::vector<float> thickness;                             // static objects with transmission
        std::vector<glm::vec3> scattering_normal, normal_spread;  // static translucent objects
        std::unique_ptr<Renderer> renderer;
        // Deforming objects only.
        std::optional<ProceduralDeformer> deformer;
        std::unique_ptr<MeshDeformer> mesh_deformer;
        std::unique_ptr<DynamicBake> dynamic_bake;
    };
    std::vector<Object> objects;
    glm::vec3 lo{0.0f}, hi{0.0f};

    shading::OffscreenTarget targets;  // RGBA32F: read back without conversion
    std::optional<gpu::GpuTimer> timer;

    Impl(Context& c, const Scene& scene, const SceneSettings& s, const StaticBakeSource& source)
        : context(c), settings(s), plan(plan_scene(scene, s, source)), planned(dev::plan_details(plan).objects)
    {
        std::unique_ptr<Baker> static_baker;  // made for the first static bake, gone after the constructor
        bool first = true;
        for (size_t k = 0; k < scene.objects.size(); ++k) {
            const SceneObject& so = scene.objects[k];
            const ObjectPlan& op = planned[k];
            Object o;
            o.rest = op.runs(PassKind::SharedBake) ? moved(objects[so.instance_of->object].rest, *so.instance_of)
                                                   : prepare_mesh(so.mesh);
            if (first) lo = o.rest.bbox_min, hi = o.rest.bbox_max, first = false;
            lo = glm::min(lo, o.rest.bbox_min), hi = glm::max(hi, o.rest.bbox_max);
            for (const PassPlan& p : op.passes) {
                const auto t0 = Clock::now();
                PassRecord r{op.name, p.kind, 0, {}};
                if (p.kind == PassKind::Draw) continue;  // per frame, in render()
                if (p.kind == PassKind::CacheRead || p.kind == PassKind::StaticBake) {
                    CachedBake b;
                    if (source.bake) {
                        b = source.bake(context, o.rest, so.material, settings.bake);
                    } else {
                        if (!static_baker) static_baker = std::make_unique<Baker>(context);
                        b.result = static_baker->bake(o.rest, so.material, settings.bake);
                        b.source = BakeSource::Baked;
                    }
                    // The plan said what should happen; say what did (an entry can go stale in between).
                    r.kind = b.source == BakeSource::Cache ? PassKind::CacheRead : PassKind::StaticBake;
                    r.note = b.note;
                    o.tm = std::move(b.result.tm);
                    o.thickness = std::move(b.result.thickness);
                    o.scattering_normal = std::move(b.result.scattering_normal);
                    o.normal_spread = std::move(b.result.normal_spread);
                } else if (p.kind == PassKind::SharedBake) {
                    // A rigid copy: t_m, AO and thickness are the same; the scattering normal turns.
                    const InstanceOf& of = *so.instance_of;
                    const Object& from = objects[of.object];
                    o.tm = from.tm, o.thickness = from.thickness, o.normal_spread = from.normal_spread;
                    o.scattering_normal.reserve(from.scattering_normal.size());
                    for (const glm::vec3& n : from.scattering_normal) o.scattering_normal.push_back(of.rotation * n);
                    r.note = "from " + planned[of.object].name;
                } else if (p.kind == PassKind::Deform) {
                    o.deformer = *so.deformer;
                    o.mesh_deformer = std::make_unique<MeshDeformer>(context, o.rest);
                    r.note = "set up (runs every frame)";
                } else if (p.kind == PassKind::DynamicBake) {
                    if (!dynamic_baker) dynamic_baker = std::make_unique<Baker>(context);
                    o.dynamic_bake = std::make_unique<DynamicBake>(*dynamic_baker, o.rest, so.material, settings.bake);
                    r.note = "set up (runs every frame)";
                }
                r.wall_ms = ms_since(t0);
                passes.push_back(std::move(r));
            }
            o.renderer = std::make_unique<Renderer>(context, settings.renderer);
            o.renderer->set_mesh(o.rest, o.tm, o.thickness, o.scattering_normal, o.normal_spread);
            o.renderer->set_material(so.material);
            objects.push_back(std::move(o));
        }
    }

    // Per frame: deform, re-bake and the renderer's vertex update in one submission, all on the
    // GPU (Renderer::record_vertex_update): no mesh data goes through the host.
    void run_per_frame(double t)
    {
        for (size_t k = 0; k < objects.size(); ++k) {
            Object& o = objects[k];
            if (!o.mesh_deformer) continue;
            const auto t0 = Clock::now();
            gpu_of(context).submit_and_wait([&](VkCommandBuffer cmd) {
                o.mesh_deformer->record(cmd, *o.deformer, t);
                const MeshDeformer::Buffers d = o.mesh_deformer->buffers();
                const DynamicBake::Buffers b = o.dynamic_bake->buffers();
                o.dynamic_bake->record(cmd, d.positions, d.normals, d.areas);
                o.renderer->record_vertex_update(cmd, d.positions, d.normals, b.tm, b.thickness, b.scattering_normal);
            });
            const double deform_and_bake_ms = ms_since(t0);
            passes.push_back({planned[k].name, PassKind::Deform, 0, "t = " + std::to_string(t) + " s"});
            passes.push_back({planned[k].name, PassKind::DynamicBake, deform_and_bake_ms,
                              "deform + re-bake + vertex update in one submission, on the GPU"});
        }
    }

    RenderedImage render(double time, const Camera& camera, std::span<const Light> lights,
                         const RenderSettings& settings_in)
    {
        const auto t0 = Clock::now();
        run_per_frame(time);
        RenderSettings s = settings_in;
        s.float32 = true;
        shading::check_settings(gpu_of(context), s, lights);
        // One depth range for every object: the scene's bounding sphere (as Renderer fits one mesh).
        const Camera cam = shading::fit_depth_range(camera, lo, hi);
        targets.ensure(gpu_of(context), s, VK_FORMAT_R32G32B32A32_SFLOAT, "scene");
        if (!timer) timer.emplace(gpu_of(context), 4);
        gpu_of(context).submit_and_wait([&](VkCommandBuffer cmd) {
            timer->begin(cmd);
            targets.begin(cmd);
            for (size_t k = 0; k < objects.size(); ++k) {
                RenderSettings os = s;
                os.mode = planned[k].variant.mode;
                const RenderTarget target = targets.target(k > 0, k + 1 < objects.size());
                if (k > 0) {
                    // The previous draw's attachment writes before this draw loads them.
                    gpu::memory_barrier(
                        cmd,
                        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                            VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                            VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                            VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
                }
                objects[k].renderer->record(cmd, target, cam, lights, os);
            }
            timer->mark(cmd, "draw");
            targets.copy_out(cmd);
        });
        for (const ObjectPlan& o : planned)
            passes.push_back({o.name, PassKind::Draw, 0,
                              std::string(dev::shading_mode_name(o.variant.mode)) +
                                  ", CHANNELS=" + std::to_string(o.variant.channels)});
        RenderedImage img;
        img.width = s.width, img.height = s.height;
        img.rgba = targets.read_rgba();
        img.gpu_ms = timer->total_ms();
        if (s.tone_map != ToneMap::None || s.exposure != 1.0f) apply_tone_map(img, s.tone_map, s.exposure);
        img.wall_ms = ms_since(t0);
        return img;
    }
};

SceneRenderer::SceneRenderer(Context& context, const Scene& scene, const SceneSettings& settings,
                             const StaticBakeSource& source)
    : impl_(std::make_unique<Impl>(context, scene, settings, source))
{
}
SceneRenderer::~SceneRenderer() = default;

const ScenePlan& SceneRenderer::plan() const { return impl_->plan; }
glm::vec3 SceneRenderer::bbox_min() const { return impl_->lo; }
glm::vec3 SceneRenderer::bbox_max() const { return impl_->hi; }

RenderedImage SceneRenderer::render(double t, const Camera& camera, std::span<const Light> lights,
                                    const RenderSettings& settings)
{
    return impl_->render(t, camera, lights, settings);
}

// What ran and the t_m drawn, for jade/dev/scene.hpp.
struct dev::SceneRendererAccess {
    static const SceneRenderer::Impl& impl(const SceneRenderer& renderer) { return *renderer.impl_; }
};

const std::vector<PassRecord>& dev::passes_run(const SceneRenderer& renderer)
{
    return SceneRendererAccess::impl(renderer).passes;
}

const std::vector<glm::vec3>& dev::object_tm(const SceneRenderer& renderer, size_t object)
{
    const auto& m = SceneRendererAccess::impl(renderer);
    const auto& o = m.objects.at(object);
    if (o.dynamic_bake) {  // the last frame's t_m lives on the GPU: read it back on request only
        const DynamicBake::Buffers b = o.dynamic_bake->buffers();
        gpu::Buffer staging(gpu_of(m.context), VkDeviceSize(b.vertex_count) * 12, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            "scene: t_m read-back", true);
        gpu_of(m.context).submit_and_wait([&](VkCommandBuffer cmd) {
            gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
            const VkBufferCopy region{0, 0, VkDeviceSize(b.vertex_count) * 12};
            vkCmdCopyBuffer(cmd, b.tm, staging.handle(), 1, &region);
            gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        });
        o.tm = staging.read<glm::vec3>(b.vertex_count);
    }
    return o.tm;
}

}  // namespace jade
