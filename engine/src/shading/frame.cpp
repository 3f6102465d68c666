// shading/frame.cpp - see frame.hpp.
#include "shading/frame.hpp"

#include "gpu/context.hpp"

#include <jade/dev/renderer.hpp>
#include <jade/dev/burley_diffusion.hpp>
#include <jade/context.hpp>
#include <jade/error.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

namespace jade::shading {

void check_settings(const gpu::Context& ctx, const RenderSettings& s, std::span<const Light> lights)
{
    if (s.width == 0 || s.height == 0 || s.width > 16384 || s.height > 16384)
        throw Error("render settings: size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                    " is outside 1..16384");
    if (uint32_t(s.mode) > uint32_t(ShadingMode::Burley))
        throw Error("render settings: unknown shading mode " + std::to_string(uint32_t(s.mode)));
    if (!(s.filament_thickness <= 1.0f))  // NaN too
        throw Error("render settings: filament_thickness " + std::to_string(s.filament_thickness) +
                    " is not in [0, 1] (or negative: the baked thickness)");
    if (s.mode == ShadingMode::Separable && s.separable_taps != 11 && s.separable_taps != 17 && s.separable_taps != 25)
        throw Error("render settings: separable_taps must be 11, 17 or 25 (got " + std::to_string(s.separable_taps) +
                    ")");
    if (s.mode == ShadingMode::Burley && (s.burley_samples < 1 || s.burley_samples > JADE_BURLEY_MAX_SAMPLES))
        throw Error("render settings: burley_samples must be in 1..80 (got " + std::to_string(s.burley_samples) + ")");
    if (lights.size() > kMaxLights)
        throw Error("render: " + std::to_string(lights.size()) + " lights, at most " + std::to_string(kMaxLights));
    for (size_t k = 0; k < lights.size(); ++k) {
        const Light& l = lights[k];
        bool ok = std::isfinite(l.vector.x + l.vector.y + l.vector.z) &&
                  std::isfinite(l.color.r + l.color.g + l.color.b) &&
                  (l.type == Light::Type::Point || glm::length(l.vector) > 0.0f);
        if (!ok) throw Error("render: light " + std::to_string(k) + " has a non-finite value or a zero direction");
    }
    const VkSampleCountFlags supported =
        ctx.limits().framebufferColorSampleCounts & ctx.limits().framebufferDepthSampleCounts;
    if ((s.samples != 1 && s.samples != 2 && s.samples != 4 && s.samples != 8) || !(supported & s.samples))
        throw Error("render settings: " + std::to_string(s.samples) + " MSAA samples are not supported by " +
                    ctx.info().name + " (supported mask " + std::to_string(supported) + ")");
}

FramePush frame_push(const Camera& cam, glm::vec3 bbox_min, glm::vec3 bbox_max, uint32_t width, uint32_t height,
                     uint32_t light_count)
{
    const glm::vec3 back = cam.eye - cam.target;
    if (!(glm::length(back) > 0.0f)) throw Error("camera: eye and target are the same point");
    if (!(glm::length(glm::cross(cam.up, back)) > 1e-6f * glm::length(back) * glm::length(cam.up)))
        throw Error("camera: up is zero or parallel to the view direction");
    if (!(cam.fov_y_degrees > 0.0f && cam.fov_y_degrees < 180.0f))
        throw Error("camera: fov " + std::to_string(cam.fov_y_degrees) + " degrees is outside (0, 180)");
    const Camera fitted = fit_depth_range(cam, bbox_min, bbox_max);
    return {fitted.view_projection(float(width) / float(height)), cam.eye, light_count};
}

Camera fit_depth_range(const Camera& camera, glm::vec3 lo, glm::vec3 hi)
{
    Camera fitted = camera;
    if (camera.near_plane > 0.0f && camera.far_plane > camera.near_plane) return fitted;
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-30f) * 1.01f;
    const float distance = glm::length(camera.eye - centre);
    fitted.far_plane = distance + radius;
    fitted.near_plane = std::max(distance - radius, fitted.far_plane * 1e-4f);
    return fitted;
}

FrameData material_constants(const Material& m)
{
    FrameData d{};
    d.albedo_strength = glm::vec4(m.albedo, m.strength);
    const float f0 = std::pow((m.ior - 1.0f) / (m.ior + 1.0f), 2.0f);
    d.specular = glm::vec4(f0, std::max(m.roughness * m.roughness, 1e-3f), m.specular, m.spread_strength);
    const Transmission& tr = m.transmission;
    d.transmission_shape = glm::vec4(tr.lobe, (tr.lobe + 1.0f) / (2.0f * float(std::numbers::pi)), tr.normal_mix,
                                     m.boundary_transmittance ? 1.0f : 0.0f);
    // The dipole of the diffused transmission from the medium's depths: z_r = 1/σ_t' = z_s − z_b,
    // α' = σ_s' z_r, z_b = 2AD (D = 1/(3σ_t')).
    float smallest = 0.0f;
    for (int c = 0; c < 3; ++c) {
        const float z0 = std::max(tr.source_depth[c] - tr.extrapolation[c], 0.0f);
        const float albedo = z0 > 0.0f ? std::clamp(tr.sigma_s_reduced[c] * z0, 0.0f, 1.0f) : 0.0f;
        d.dipole_albedo[c] = albedo / (4.0f * float(std::numbers::pi));
        d.dipole_sigma[c] = tr.sigma_tr[c];
        d.dipole_real[c] = z0;
        d.dipole_boundary[c] = tr.extrapolation[c];
        if (albedo > 0.0f && (smallest == 0.0f || tr.sigma_tr[c] < smallest)) smallest = tr.sigma_tr[c];
    }
    d.dipole_albedo.w = tr.diffusion_weight;
    d.dipole_sigma.w = smallest > 0.0f ? 3.0f / smallest : 3.0e38f;
    return d;
}

}  // namespace jade::shading

namespace jade {

FilamentSubsurface filament_subsurface(const Material& m)
{
    FilamentSubsurface f;
    const glm::vec3 s = m.transmission.sigma_tr;
    float smallest = 0.0f;
    for (int c = 0; c < 3; ++c)
        if (std::isfinite(s[c]) && s[c] > 0.0f && (smallest == 0.0f || s[c] < smallest)) smallest = s[c];
    for (int c = 0; c < 3; ++c) {
        const float transmitted = std::clamp(1.0f - m.albedo[c], 0.0f, 1.0f);
        f.color[c] = transmitted * (smallest > 0.0f && s[c] > 0.0f ? smallest / s[c] : 1.0f);
    }
    if (smallest == 0.0f) return f;
    f.thickness_per_unit = 0.5f * smallest;
    return f;
}

}  // namespace jade

namespace jade::shading {

namespace {

const double kGoldenAngle = std::numbers::pi * (3.0 - std::sqrt(5.0));

/// Equal weights on a golden-angle disk of uniform density, median radius 0: the kernel of a
/// material without a profile, which the shader widens to a texel (a plain filter of the tile).
SoftShadowKernel uniform_disk_kernel()
{
    SoftShadowKernel k;
    for (uint32_t i = 0; i < JADE_SOFT_SHADOW_TAPS; ++i) {
        const double r = std::sqrt(2.0 * (i + 0.5) / JADE_SOFT_SHADOW_TAPS);
        k.taps[i] =
            glm::vec4(float(r * std::cos(i * kGoldenAngle)), float(r * std::sin(i * kGoldenAngle)), float(r), 0.0f);
        k.weights[i] = glm::vec4(glm::vec3(1.0f / JADE_SOFT_SHADOW_TAPS), 0.0f);
    }
    k.median = 0.0f;
    return k;
}

}  // namespace

SoftShadowKernel soft_shadow_kernel(const Material& m)
{
    if (m.opaque) return uniform_disk_kernel();
    const glm::dvec3 shape = burley_shapes(m);
    const double sampled = std::max({shape.x, shape.y, shape.z});
    if (!(sampled > 0.0) || !std::isfinite(sampled) || !(std::min({shape.x, shape.y, shape.z}) > 0.0))
        return uniform_disk_kernel();
    // R(r) = (e^{−r/d} + e^{−r/(3d)}) / (8π d r): the 8π r cancels in the ratio to the sampled one.
    const auto burley = [](double d, double r) { return (std::exp(-r / d) + std::exp(-r / (3.0 * d))) / d; };
    SoftShadowKernel k;
    glm::dvec3 sum(0.0);
    std::array<glm::dvec3, JADE_SOFT_SHADOW_TAPS> w{};
    for (uint32_t i = 0; i < JADE_SOFT_SHADOW_TAPS; ++i) {
        const double r = burley_sample_radius((i + 0.5) / JADE_SOFT_SHADOW_TAPS, sampled);
        k.taps[i] =
            glm::vec4(float(r * std::cos(i * kGoldenAngle)), float(r * std::sin(i * kGoldenAngle)), float(r), 0.0f);
        for (int c = 0; c < 3; ++c) w[i][c] = burley(shape[c], r) / burley(sampled, r);
        sum += w[i];
    }
    // A channel far narrower than the sampled shape has no weight left at any tap (e^{−r/d} = 0):
    // its nearest tap alone, about a hard shadow.
    for (int c = 0; c < 3; ++c)
        if (!(sum[c] > 0.0)) w[0][c] = sum[c] = 1.0;
    const double median = burley_sample_radius(0.5, sampled);
    for (uint32_t i = 0; i < JADE_SOFT_SHADOW_TAPS; ++i) {
        k.taps[i] = glm::vec4(glm::dvec3(k.taps[i]) / median, 0.0f);  // in median radii
        k.weights[i] = glm::vec4(glm::vec3(w[i] / sum), 0.0f);
    }
    k.median = float(median);
    return k;
}

void check_material(const Material& m)
{
    if (!(m.strength >= 0.0f) || !std::isfinite(m.strength))
        throw Error("material " + m.name + ": strength must be finite and >= 0");
    if (!(m.ior > 0.0f) || !(m.roughness >= 0.0f) || !(m.specular >= 0.0f))
        throw Error("material " + m.name + ": ior must be > 0, roughness and specular >= 0");
}

void check_target(const RenderTarget& t, const RenderSettings& s)
{
    if (t.width != s.width || t.height != s.height || !t.color || !t.depth || (s.samples > 1) != bool(t.resolve))
        throw Error("render target: size or views do not match the settings (" + std::to_string(s.width) + "x" +
                    std::to_string(s.height) + ", " + std::to_string(s.samples) + " samples)");
}

void begin_rendering(VkCommandBuffer cmd, const RenderTarget& t, const RenderSettings& s,
                     const VkRenderingAttachmentInfo* second)
{
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = t.color;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = t.load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = t.resolve && !t.keep ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
    // Only a cleared attachment gets a clear value: lavapipe (Mesa 22.3) clears a LOAD
    // attachment whose clear value is non-zero (seen in samples/embed: the host's frame
    // came back as the background colour).
    if (!t.load)
        color.clearValue.color = {
            {s.background.r, s.background.g, s.background.b, s.transparent_background ? 0.0f : 1.0f}};
    if (t.resolve) {
        color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        color.resolveImageView = t.resolve;
        color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = t.depth;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = t.load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = t.load || t.keep ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    if (!t.load) depth.clearValue.depthStencil = {1.0f, 0};  // as for colour above
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {s.width, s.height}};
    ri.layerCount = 1;
    const VkRenderingAttachmentInfo colors[2] = {color, second ? *second : color};
    ri.colorAttachmentCount = second ? 2 : 1;
    ri.pColorAttachments = colors;
    ri.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &ri);
}

float half_to_float(uint16_t h)
{
    const uint32_t sign = uint32_t(h >> 15) << 31, exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
    uint32_t bits;
    if (exponent == 0x1f)
        bits = sign | 0x7f800000u | (mantissa << 13);  // inf, NaN
    else if (exponent != 0)
        bits = sign | ((exponent + 112) << 23) | (mantissa << 13);
    else if (mantissa == 0)
        bits = sign;  // ±0
    else {            // subnormal
        float f = std::ldexp(float(mantissa), -24);
        return sign ? -f : f;
    }
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

}  // namespace jade::shading
