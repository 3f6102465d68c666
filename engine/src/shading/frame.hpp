// shading/frame.hpp - the per-draw checks and constants of jade::Renderer that need none of its
// state: the settings and lights validated, the push constants with near and far fitted to the
// mesh's bounds, the material's part of the frame constants, the dynamic-rendering begin on a
// RenderTarget, and the half floats of the read-back decoded.
#pragma once

#include "shading/mesh_pipeline.hpp"

#include <jade/render.hpp>

#include <cstdint>
#include <span>

namespace jade::gpu {
class Context;
}

namespace jade::shading {

/// Throws jade::Error naming the setting: size outside 1..16384, unknown mode, more than
/// kMaxLights lights, a non-finite light or a zero direction, an unsupported sample count.
void check_settings(const gpu::Context& ctx, const RenderSettings& s, std::span<const Light> lights);

/// View-projection, eye and light count; near and far hug the bounding sphere of [bbox_min,
/// bbox_max] unless the camera gives both. Throws jade::Error for a degenerate camera.
FramePush frame_push(const Camera& cam, glm::vec3 bbox_min, glm::vec3 bbox_max, uint32_t width, uint32_t height,
                     uint32_t light_count);

/// The shadow filter's tap spacing in texels of the light's tile (shadow.glsl): 1 (a 3×3
/// bilinear PCF), or widened to `reach` (mesh units; the Tm mode passes the material's, the
/// others 0), so that light bleeds into a shadow's edge as far as it travels under the surface,
/// at most 4 texels (the taps stay 9: wider, they would skip over thin occluders). `centre`: the
/// object's, where a point light's texel is measured.
float shadow_spacing(const Light& light, const LightTile& tile, float reach, glm::vec3 centre);

/// Throws jade::Error naming the material: a negative or non-finite strength, ior ≤ 0, a
/// negative roughness or specular weight.
void check_material(const Material& m);

/// The material's part of FrameData (albedo, strength, specular, transmission); the rest is zero.
FrameData material_constants(const Material& m);

/// Throws jade::Error unless the target's size and views match the settings (resolve view
/// exactly when multisampled).
void check_target(const RenderTarget& t, const RenderSettings& s);

/// vkCmdBeginRendering on the target: colour (resolved when t.resolve) and depth, cleared to the
/// background unless t.load, stored as t.keep and t.load ask; `second`: a second colour
/// attachment (the Separable mode's irradiance target).
void begin_rendering(VkCommandBuffer cmd, const RenderTarget& t, const RenderSettings& s,
                     const VkRenderingAttachmentInfo* second = nullptr);

/// The camera with near and far hugging the sphere about [lo, hi] (radius half the diagonal, 1 %
/// margin) unless it gives both; when the eye is inside the sphere, near is 1e-4 of far (D32
/// keeps enough precision there).
Camera fit_depth_range(const Camera& camera, glm::vec3 lo, glm::vec3 hi);

/// IEEE half to float (inf, NaN, subnormals included).
float half_to_float(uint16_t h);

}  // namespace jade::shading
