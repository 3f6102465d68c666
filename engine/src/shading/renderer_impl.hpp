// shading/renderer_impl.hpp - Renderer::Impl, what a jade::Renderer holds and how it draws (the
// draw, its transmission and shadow set-up, the frame constants, render() and the inputs pass),
// shared by the Renderer's members (shading/renderer.cpp) and the introspection of
// jade/dev/renderer.hpp (shading/renderer_dev.cpp). Private to the engine.
//
// Per draw the GPU sees: the vertex buffer (shading::Vertex: position, normal, t_m, curvature,
// thickness, scattering normal, normal spread), the index buffer, push constants {view-projection, eye, light count}, and one
// uniform buffer FrameData {material, LUT mappings, colour map, lights, transmitters} written
// with vkCmdUpdateBuffer inside the command buffer (so record() needs no per-frame buffers).
// Pipeline variants and their rules: mesh_pipeline.hpp; per-draw checks: frame.hpp.
#pragma once

#include "gpu/buffer.hpp"
#include "gpu/context.hpp"
#include "gpu/image.hpp"
#include "gpu/kernel.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/timer.hpp"
#include "shading/light_depth.hpp"
#include "shading/lut.hpp"
#include "shading/frame.hpp"
#include "shading/mesh_pipeline.hpp"
#include "shading/mesh_vertices.hpp"
#include "shading/offscreen.hpp"
#include "shading/separable.hpp"
#include "shading/transmission_table.hpp"

#include <jade/dev/material.hpp>
#include <jade/dev/clock.hpp>
#include <jade/dev/overlay.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/render.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace jade {

// Members are destroyed in reverse order: targets and pipelines first, the LUTs and sampler
// last. Draws recorded with record() may still be running: ~Renderer hands the Impl to the
// Context's release queue, and set_mesh/set_material hand it what they replace.
struct Renderer::Impl {
    using FrameData = shading::FrameData;
    using FramePush = shading::FramePush;
    using GpuLight = shading::GpuLight;
    using Vertex = shading::Vertex;

    static VkFormat color_format(const RenderSettings& s)
    {
        return s.float32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
    }

    gpu::Context& ctx;
    RendererOptions options;
    gpu::OwnedSampler sampler, nearest;
    std::shared_ptr<shading::TranslucencyLut> lut;         // shared by the Renderers of this device and layout
    std::optional<shading::CurvatureLut> curvature_lut;    // made on demand: curvature_image()
    std::array<ChannelProfile, 3> curvature_lut_profiles;  // what curvature_lut was built for
    gpu::Image placeholder;                                // 1×1, bound when curvature_lut is not

    // Mesh.
    gpu::Buffer vertices, indices;
    uint32_t index_count = 0, vertex_count = 0;
    std::optional<gpu::Kernel> pack_vertices;  // record_vertex_update(): made on first use
    glm::vec3 bbox_min{0.0f}, bbox_max{0.0f};
    std::vector<float> curvature;
    float tm_min_mean = 0.0f, tm_max_mean = 0.0f;  // range of mean(t_m) over the vertices
    glm::vec3 tm_min{0.0f};  // per channel over the vertices; 0 after record_vertex_update (not known)
    bool has_mesh = false, has_thickness = false;
    dev::LightPathSampling light_path = dev::LightPathSampling::PerFragment;  // resolved for this mesh
    uint64_t geometry_version = 0;  // changes with set_mesh and record_vertex_update (light-depth reuse)

    std::optional<shading::LightDepth> light_depth;  // made on the first draw with transmission or shadows
    std::optional<Material> material;
    shading::SoftShadowKernel soft_shadow;  // the material's, for the Tm mode's shadows
    gpu::Buffer frame_data;
    TmEvaluation evaluation;
    shading::MeshPipelines pipelines;
    shading::TransmissionTable transmission_table;  // of the material's Transmission
    shading::SeparablePasses separable_passes;      // the Separable mode's targets, kernel and blur passes

    shading::OffscreenTarget targets;  // render()'s own, kept while the size and format stay the same
    std::optional<gpu::GpuTimer> timer;

    Impl(gpu::Context& c, const RendererOptions& o)
        : ctx(c), options(o), sampler(shading::make_lut_sampler(c)),
          nearest(
              gpu::make_sampler(c, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "light depth sampler")),
          lut(shading::shared_translucency_lut(c, dev::study_of(o).lut)),
          placeholder(c,
                      {"curvature LUT placeholder", 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT}),
          frame_data(c, sizeof(FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     "frame data"),
          evaluation(shading::resolve_evaluation(dev::study_of(o).tm_evaluation, c)), pipelines(c),
          transmission_table(c), separable_passes(c)
    {
        if (evaluation == TmEvaluation::Lut) lut->build_quads(c);  // the only path that reads them
        // Sampled-image descriptors need the image in its layout even if never read.
        c.submit_and_wait([&](VkCommandBuffer cmd) { placeholder.transition(cmd, gpu::use::kSampled); });
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    // The pipeline variant of a draw: only the t_m mode reads the channels, the evaluation path
    // and the transmitting lights; the Fourier terms follow the smallest t of the mesh.
    shading::MeshVariant variant(uint32_t mode, uint32_t transmitters, bool shadows) const
    {
        shading::MeshVariant v;
        v.mode = mode;
        v.shadows = shadows;
        if (mode != uint32_t(ShadingMode::Tm) && mode < shading::kInputsMode) return v;
        v.channels = dev::is_grey(*material) ? 1 : 3;
        v.transmission = transmitters;
        v.path_per_vertex = transmitters > 0 && light_path == dev::LightPathSampling::PerVertex;
        if (mode >= shading::kInputsMode) return v;
        v.evaluation = evaluation;
        const float smallest = v.channels == 1 ? tm_min.x : std::min({tm_min.x, tm_min.y, tm_min.z});
        shading::choose_terms(double(material->strength) * double(smallest), v);
        return v;
    }

    void check_ready(const RenderSettings& s, std::span<const Light> lights) const
    {
        if (!has_mesh) throw Error("Renderer: no mesh (call set_mesh first)");
        if (!material) throw Error("Renderer: no material (call set_material first)");
        shading::check_settings(ctx, s, lights);
    }

    // Of the sphere about the bounds' centre that holds them (the light-depth tiles' box).
    float bounding_radius() const { return 0.5f * glm::length(bbox_max - bbox_min); }

    // The transmission variant is drawn only when it can add light: the material has the term,
    // the mesh a thickness, and some light is behind the object as the camera sees it, i.e. the
    // forward lobe max(V·(−L), 0) is non-zero for some V towards the eye from the bounding
    // sphere (exact for directional lights; point lights always count).
    bool transmission_reaches_camera(const Camera& cam, std::span<const Light> lights, const RenderSettings& s) const
    {
        if (s.mode != ShadingMode::Tm || !s.transmission || !has_thickness || !material->transmission.enabled())
            return false;
        const glm::vec3 centre = 0.5f * (bbox_min + bbox_max);
        const float radius = bounding_radius();
        return std::any_of(lights.begin(), lights.end(), [&](const Light& l) {
            return shading::LightDepth::may_transmit(cam.eye, l, centre, radius);
        });
    }

    // Whether this draw shadows its lights: the lit modes (not the false colour, not the inputs pass).
    static bool shadowed(const RenderSettings& s, uint32_t mode)
    {
        return s.shadows && mode != uint32_t(ShadingMode::TmFalseColor) && mode < shading::kInputsMode;
    }

    // The lights' depth tiles (shading/light_depth.hpp: directional lights, and point lights
    // outside the bounding sphere; the atlas is made on the first draw that needs it), for the
    // transmission term's path and for the shadows; and the lights drawn with transmission: the
    // first kMaxTransmitters that may shine through the object towards the eye, each with its
    // tile + 1 in color.w, 0 none. The transmitters take tiles first (their path needs one).
    struct Transmitting {
        std::vector<GpuLight> lights;
        std::vector<uint32_t> index;  // of each in the draw's lights
        std::vector<uint32_t> tile;   // per light of the draw: its depth tile + 1, 0 none
        bool tiles = false;           // some transmitter has a depth tile
        bool shadows = false;         // the draw shadows its lights, and some light has a tile
        bool atlas = false;           // the draw reads the tiles (transmitters, shadows, SSSSTransmittance)
    };
    Transmitting record_transmission(VkCommandBuffer cmd, const Camera& cam, std::span<const Light> lights,
                                     const RenderSettings& s, uint32_t mode)
    {
        Transmitting out;
        out.tile.assign(lights.size(), 0);
        const bool transmission = transmission_reaches_camera(cam, lights, s), shadows = shadowed(s, mode);
        // The screen-space peers' transmittance reads every light's tile.
        const bool separable = mode == uint32_t(ShadingMode::Separable) || mode == uint32_t(ShadingMode::Burley);
        if (!transmission && !shadows && !separable) return out;
        const glm::vec3 centre = 0.5f * (bbox_min + bbox_max);
        const float radius = bounding_radius();
        auto transmits = [&](const Light& l) {
            return transmission && shading::LightDepth::may_transmit(cam.eye, l, centre, radius);
        };
        std::vector<uint8_t> wanted(lights.size(), 0);
        for (size_t k = 0; k < lights.size(); ++k)
            if (shading::LightDepth::can_tile(lights[k], centre, radius))
                wanted[k] = transmits(lights[k]) ? 2 : shadows || separable ? 1 : 0;
        if (std::any_of(wanted.begin(), wanted.end(), [](uint8_t w) { return w != 0; })) {
            if (!light_depth) light_depth.emplace(ctx, options.light_depth_size);
            out.tile = light_depth->record(cmd, lights, wanted, vertices.handle(), sizeof(Vertex), indices.handle(),
                                           index_count, centre, radius, geometry_version);
        }
        for (size_t k = 0; k < lights.size() && out.lights.size() < shading::kMaxTransmitters; ++k)
            if (transmits(lights[k])) {
                out.lights.push_back(shading::gpu_light(lights[k], float(out.tile[k])));
                out.index.push_back(uint32_t(k));
                out.tiles = out.tiles || out.tile[k] != 0;
            }
        const bool tiled = std::any_of(out.tile.begin(), out.tile.end(), [](uint32_t t) { return t != 0; });
        out.shadows = shadows && tiled, out.atlas = out.tiles || out.shadows || (separable && tiled);
        return out;
    }

    std::pair<float, float> false_color_range(const RenderSettings& s) const
    {
        if (s.false_color_max > s.false_color_min) return {s.false_color_min, s.false_color_max};
        if (tm_max_mean > tm_min_mean) return {tm_min_mean, tm_max_mean};
        // Constant t_m: any non-empty range; + 1 alone is lost in rounding for large t_m.
        return {tm_min_mean, tm_min_mean + std::max(1.0f, tm_min_mean)};
    }

    // The curvature LUT is built on the first curvature-mode draw after set_material (it costs
    // CPU time); until then binding 2 holds a 1×1 placeholder, never read by the other modes.
    const gpu::Image& curvature_image()
    {
        if (!curvature_lut && material) {
            curvature_lut.emplace(ctx, *material, dev::study_of(options).curvature_lut_width,
                                  dev::study_of(options).curvature_lut_height);
            curvature_lut_profiles = material->profile;
        }
        return curvature_lut ? curvature_lut->image() : placeholder;
    }

    FrameData frame_constants(std::span<const Light> lights, const RenderSettings& s, const Transmitting& transmitting,
                              uint32_t mode) const
    {
        FrameData d = shading::material_constants(*material);
        d.lut_map = lut->shader_map();
        const auto [lo, hi] = false_color_range(s);
        d.curvature_map = curvature_lut ? curvature_lut->shader_map() : glm::vec4(0.0f);
        d.params =
            glm::vec4(float(1.0 / LutLayout::kMaxVariance), curvature_lut ? float(curvature_lut->scale()) : 0.0f, lo,
                      // finite: the shader multiplies (t_m − lo) by it, 0 · Inf would be NaN
                      float(std::min(1.0 / (double(hi) - double(lo)), double(FLT_MAX))));
        if (light_depth) {
            d.light_depth_map =
                glm::vec4(float(light_depth->tile_size()), float(shading::LightDepth::kMaxLights), 0.0f, 0.0f);
            for (uint32_t t = 0; t < shading::LightDepth::kMaxLights; ++t) d.light_tiles[t] = light_depth->tile(t);
        }
        if (mode == uint32_t(ShadingMode::Tm)) {
            d.soft_shadow = glm::vec4(soft_shadow.median, 0.0f, 0.0f, 0.0f);
            std::copy(std::begin(soft_shadow.taps), std::end(soft_shadow.taps), d.soft_shadow_taps);
            std::copy(std::begin(soft_shadow.weights), std::end(soft_shadow.weights), d.soft_shadow_weights);
        }
        // Filament's inputs: the baked thickness normalised by the medium, or a constant (the
        // setting's, else Filament's default 0.5 where there is nothing to normalise).
        const FilamentSubsurface filament = filament_subsurface(*material);
        d.subsurface = glm::vec4(filament.color, filament.power);
        const bool baked = s.filament_thickness < 0.0f && has_thickness && filament.thickness_per_unit > 0.0f;
        d.subsurface_thickness = glm::vec4(filament.thickness_per_unit,
                                           baked                         ? -1.0f
                                           : s.filament_thickness < 0.0f ? 0.5f
                                                                         : s.filament_thickness,
                                           0.0f, 0.0f);
        for (int i = 0; i < 9; ++i) d.color_map[i] = glm::vec4(false_color(float(i) / 8.0f), 1.0f);
        d.transmission_table_map = transmission_table.shader_map();
        std::copy(transmitting.lights.begin(), transmitting.lights.end(), d.transmitters);
        for (size_t k = 0; k < lights.size(); ++k)
            d.lights[k] = shading::gpu_light(lights[k], float(transmitting.tile.empty() ? 0 : transmitting.tile[k]));
        return d;
    }

    // mode: a ShadingMode, or shading::kInputsMode + k for the inputs pass.
    void record(VkCommandBuffer cmd, const RenderTarget& t, const Camera& cam, std::span<const Light> lights,
                const RenderSettings& s, uint32_t mode)
    {
        check_ready(s, lights);
        shading::check_target(t, s);
        const bool separable = mode == uint32_t(ShadingMode::Separable) || mode == uint32_t(ShadingMode::Burley);
        const FramePush push = shading::frame_push(cam, bbox_min, bbox_max, s.width, s.height, uint32_t(lights.size()));
        const gpu::Image& curvature = s.mode == ShadingMode::Curvature ? curvature_image()
                                      : curvature_lut                  ? curvature_lut->image()
                                                                       : placeholder;
        const Transmitting transmitting = record_transmission(cmd, cam, lights, s, mode);
        const FrameData data = frame_constants(lights, s, transmitting, mode);
        const auto& pipe = pipelines.get(variant(mode, uint32_t(transmitting.lights.size()), transmitting.shadows),
                                         color_format(s), s.samples);
        const gpu::Image& light_depth_image = transmitting.atlas ? light_depth->atlas() : placeholder;

        // The frame constants are rewritten in the command stream: wait for the previous draw's
        // shader reads (write-after-read), then make the new values visible to this draw.
        const size_t bytes = offsetof(FrameData, lights) + lights.size() * sizeof(GpuLight);
        constexpr VkPipelineStageFlags2 shaders =
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
        gpu::memory_barrier(cmd, shaders, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        vkCmdUpdateBuffer(cmd, frame_data.handle(), 0, (bytes + 3) & ~size_t(3), &data);
        gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, shaders,
                            VK_ACCESS_2_UNIFORM_READ_BIT);

        const auto irradiance =
            separable ? separable_passes.prepare(cmd, t, s, *material) : VkRenderingAttachmentInfo{};
        shading::begin_rendering(cmd, t, s, separable ? &irradiance : nullptr);
        pipe.bind(cmd, {s.width, s.height}, push,
                  {frame_data, lut->quads(),
                   gpu::Binding::image(curvature.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler),
                   gpu::Binding::image(light_depth_image.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, nearest),
                   gpu::Binding::image(lut->filtered().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler),
                   transmission_table.texels(), separable_passes.data_or(frame_data)});
        VkBuffer vb = vertices.handle();
        VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
        vkCmdBindIndexBuffer(cmd, indices.handle(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, index_count, 1, 0, 0, 0);
        vkCmdEndRendering(cmd);
        if (separable)
            separable_passes.record_blur(cmd, t, s, color_format(s), cam, push.view_proj, bbox_min, bbox_max);
    }

    RenderedImage render(const Camera& cam, std::span<const Light> lights, const RenderSettings& s, uint32_t mode)
    {
        const auto t0 = Clock::now();
        check_ready(s, lights);
        targets.ensure(ctx, s, color_format(s), "render");
        if (!timer) timer.emplace(ctx, 4);
        ctx.submit_and_wait([&](VkCommandBuffer cmd) {
            timer->begin(cmd);
            targets.begin(cmd);
            record(cmd, targets.target(), cam, lights, s, mode);
            timer->mark(cmd, "draw");
            targets.copy_out(cmd);
        });

        RenderedImage img;
        img.width = s.width, img.height = s.height;
        img.rgba = targets.read_rgba();
        img.gpu_ms = timer->total_ms();
        if (s.tone_map != ToneMap::None || s.exposure != 1.0f) apply_tone_map(img, s.tone_map, s.exposure);
        if (s.mode == ShadingMode::TmFalseColor && s.legend)
            draw_color_bar(img, false_color_range(s).first, false_color_range(s).second);
        img.wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        return img;
    }

    ShadingInputs shading_inputs(const Camera& cam, std::span<const Light> lights, const RenderSettings& settings)
    {
        RenderSettings s = settings;
        s.mode = ShadingMode::Tm;
        s.samples = 1, s.float32 = true, s.transparent_background = true, s.tone_map = ToneMap::None, s.exposure = 1.0f;
        s.background = glm::vec3(0.0f);
        const size_t pixels = size_t(s.width) * s.height;
        ShadingInputs in;
        in.width = s.width, in.height = s.height;
        std::vector<glm::vec4> paths;  // of the transmitting lights, in their order
        std::vector<glm::vec4>* planes[] = {&in.position,          &in.normal,        &in.tm,      &paths,
                                            &in.scattering_normal, &in.normal_spread, &in.diffused};
        for (uint32_t k = 0; k < shading::kInputsSlots; ++k) {
            const RenderedImage img = render(cam, lights, s, shading::kInputsMode + k);
            planes[k]->resize(pixels);
            std::memcpy(planes[k]->data(), img.rgba.data(), pixels * sizeof(glm::vec4));
        }
        // The same selection as record()'s.
        Transmitting transmitting;
        ctx.submit_and_wait([&](VkCommandBuffer cmd) {
            transmitting = record_transmission(cmd, cam, lights, s, shading::kInputsMode);
        });
        in.transmits.assign(lights.size(), 0);
        in.path.assign(lights.size() * pixels, 0.0f);
        for (size_t i = 0; i < transmitting.index.size(); ++i) {
            const uint32_t light = transmitting.index[i];
            in.transmits[light] = 1;
            for (size_t p = 0; p < pixels; ++p) in.path[light * pixels + p] = paths[p][int(i)];
        }
        return in;
    }
};

}  // namespace jade
