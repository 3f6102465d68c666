// jade/render.hpp - shading with the translucency magnitude (the poster's f_r), on the GPU.
//
// What is drawn: a mesh with per-vertex t_m (RGB), lit by directional and point lights, with
//   diffuse_c = (k_d,c / π) · F(cos θ, strength · t_m,c) · E_c     per light and colour channel c
// where F is a look-up table of f(θ, t) (docs/shading.md; F = max(cos θ, 0) for t = 0, i.e.
// exactly Lambert), plus a GGX specular lobe (Smith height-correlated visibility, Schlick
// Fresnel with F0 from Material::ior, α = Material::roughness², weight Material::specular).
// Modes: Lambert; Curvature (Kubo et al. 2010 / pre-integrated: F replaced by the curvature
// LUT D(cos θ, 1/κ), κ the vertex's mean curvature); Tm (ours); TmFalseColor;
// Filament (google/filament's subsurface model, a peer to compare with: docs/peers.md).
//
// Units: positions, camera and point lights in mesh units (no normalisation anywhere);
// directional light irradiance E and point light intensity I (E = I / d²) are linear RGB in
// arbitrary but consistent units; images are linear RGB (HDR, unclamped) unless tone mapped.
//
// Threading and lifetime: a Renderer uses its Context's queue and is not thread-safe; use it
// from the thread that uses the Context, and destroy it before the Context. Errors are
// jade::Error naming the setting or element at fault.
#pragma once

#include <jade/camera.hpp>
#include <jade/error.hpp>
#include <jade/light.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>
#include <jade/noncopyable.hpp>

#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace jade {

struct BakeResult;  // jade/bake.hpp

class Context;

/// What the fragment shader computes (see the header comment).
enum class ShadingMode : uint32_t {
    Lambert = 0,       ///< (k_d/π) max(cos θ, 0) E
    Curvature = 1,     ///< curvature-dependent reflectance (Kubo et al. 2010), needs no bake
    Tm = 2,            ///< translucency magnitude (Kubo, Tokoi, Mukaigawa 2015)
    TmFalseColor = 3,  ///< t_m (mean of the channels) as the viridis colour map, unlit
    Filament = 4,      ///< Filament's subsurface shading model (a peer; docs/peers.md), fed Jade's baked thickness
    /// A peer: Jimenez et al. 2015's separable subsurface scattering, the Lambert diffuse light
    /// (and SSSSTransmittance's) blurred on screen by two 1-D passes of a kernel fitted to the
    /// material's profiles (docs/peers_separable.md); needs no bake.
    Separable = 5,
    /// A peer: screen-space Burley diffusion as Unity HDRP does it (Golubev 2018): the same
    /// irradiance target, one pass of importance-sampled taps (docs/peers_separable.md).
    Burley = 6,
};

/// Host-side tone mapping of render()'s result (never applied by record()).
enum class ToneMap : uint32_t {
    None = 0,        ///< linear HDR, as rendered
    Reinhard = 1,    ///< x / (1 + x) per channel
    AcesFitted = 2,  ///< Narkowicz's fit of the ACES filmic curve, clamped to [0, 1]
};

/// An RGBA float image, rows top to bottom, 4 floats per pixel.
struct RenderedImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
    double gpu_ms = 0;   ///< GPU time of the draw (timestamps around the rendering)
    double wall_ms = 0;  ///< host time of the whole render() call, read-back included
    float* pixel(uint32_t x, uint32_t y) { return rgba.data() + (size_t(y) * width + x) * 4; }
    const float* pixel(uint32_t x, uint32_t y) const { return rgba.data() + (size_t(y) * width + x) * 4; }
};

/// Per-draw settings of render() and record(); validated at each call (jade::Error naming the
/// setting: unsupported sample count, size 0, more than 64 lights).
struct RenderSettings {
    uint32_t width = 512, height = 512;
    ShadingMode mode = ShadingMode::Tm;
    uint32_t samples = 4;                 ///< MSAA samples: 1, 2, 4 or 8 (as the device supports)
    bool float32 = false;                 ///< render in RGBA32F instead of RGBA16F
    glm::vec3 background{0.0f};           ///< linear RGB
    bool transparent_background = false;  ///< alpha 0 where no surface is drawn (else alpha is 1)
    ToneMap tone_map = ToneMap::None;     ///< applied on the host after read-back (render() only)
    float exposure = 1.0f;                ///< multiplies the linear colour before tone mapping
    /// TmFalseColor: the colour map spans mean(t_m) ∈ [false_color_min, false_color_max]; when
    /// max ≤ min (the default 0, 0) it spans the mesh's range. render() draws a colour bar.
    float false_color_min = 0.0f, false_color_max = 0.0f;
    bool legend = true;  ///< TmFalseColor: draw the colour bar (render() only)
    /// Tm: add the material's Transmission term (light through thin parts) when the material
    /// has one, the mesh has a thickness, and a light is behind the object as the camera sees
    /// it; otherwise the pipeline without it is drawn (no cost). false: the poster's model alone.
    bool transmission = true;
    /// Lambert, Curvature, Tm: each light's diffuse and specular light is shadowed by the mesh
    /// (the light's depth tile, filtered; Tm widens the filter by the material's reach). At most
    /// 4 lights cast shadows (the first 4 that can; a point light inside or near the bounding
    /// sphere cannot), the rest are unshadowed; the mesh shadows itself only (not other objects
    /// of a scene). false, or no light that can: the pipeline without shadows (no cost).
    bool shadows = true;
    /// Filament: the `thickness` Filament's subsurface model reads, in [0, 1] (0 thin: the most
    /// subsurface light; 1 thick: none). Negative (the default): Jade's baked per-vertex thickness
    /// t̄ normalised as t̄ · σ_tr,min / 2, clamped to 1 (docs/peers.md), or Filament's default 0.5
    /// where the mesh has no baked thickness. 0.5 stands for a material without a thickness map.
    float filament_thickness = -1.0f;
    /// Separable: taps of each of the two 1-D passes, 11, 17 or 25 (docs/peers_separable.md).
    uint32_t separable_taps = 17;
    /// Burley: samples per pixel, 1 … 80 (HDRP's low, medium, high: 20, 40, 80).
    uint32_t burley_samples = 40;
};

namespace dev {
struct RendererStudy;  // jade/dev/renderer.hpp: LUT sizes, evaluation paths and light path sampling, for studies
struct RendererAccess;
}  // namespace dev

/// Fixed at Renderer construction.
struct RendererOptions {
    /// Mean curvature smoothing: iterations of 1-ring averaging after the cotangent Laplacian.
    uint32_t curvature_smoothing = 2;
    /// Transmission and shadows: texels of one light's depth tile (how far light travels inside
    /// the object before it reaches a point, and what shadows it: the depths of the first four
    /// surfaces along the light, RGBA32F, and two D32 buffers to peel them; 4 lights at most,
    /// 24·size² bytes each).
    uint32_t light_depth_size = 512;
    /// Set by the tools and tests only (jade/dev/renderer.hpp); null: the defaults.
    std::shared_ptr<const dev::RendererStudy> study;
};

/// Where record() draws: the caller's images, described by views.
///   color    samples × colour format (RGBA16F, or RGBA32F with RenderSettings::float32), layout
///            COLOR_ATTACHMENT_OPTIMAL (cleared to the background, or loaded with `load`; then
///            discarded when `resolve` is set and not `keep`, else stored)
///   resolve  1 sample, same format, COLOR_ATTACHMENT_OPTIMAL, or VK_NULL_HANDLE when samples = 1
///   depth    samples × D32_SFLOAT, DEPTH_ATTACHMENT_OPTIMAL (cleared to 1 and not stored, or
///            with `load` loaded, depth-tested LESS and stored; stored also with `keep`)
/// All three stay in these layouts after the draw.
struct RenderTarget {
    VkImageView color = VK_NULL_HANDLE, resolve = VK_NULL_HANDLE, depth = VK_NULL_HANDLE;
    uint32_t width = 0, height = 0;
    /// Draw over what the host already rendered into color and depth (embedding): no clear.
    /// Depth is only comparable when the camera has explicit near/far planes that the host
    /// used too (Camera::view_projection).
    bool load = false;
    /// More draws into the same images follow (a scene of several meshes): store the
    /// multisampled colour and the depth too, so that the next draw can load them.
    bool keep = false;
};

/// Draws one mesh with one material. Owns its GPU buffers, LUT images and pipelines (created
/// lazily per mode, sample count and format). Threading and lifetime as in the header comment.
class Renderer : NonCopyable {
public:
    /// Builds the translucency LUT on the GPU (submits to the Context's queue and waits), or
    /// shares the one another living Renderer of the same device and LUT size already built
    /// (it does not depend on the material: a scene of many objects keeps one).
    /// Throws jade::Error for missing format support.
    explicit Renderer(Context& context, const RendererOptions& options = {});
    ~Renderer();

    /// The mesh to draw, with t_m per bake vertex (empty: zero, i.e. Lambert in every mode but
    /// Curvature). Shading uses the prepared mesh's area-weighted vertex normals (so normal
    /// seams of the input are smoothed over). Computes the mean curvature. Does not wait for
    /// draws recorded earlier: the old buffers are released once the GPU has finished what was
    /// submitted to the Context's queue before this call (Context: "Releasing objects"), so
    /// command buffers recorded earlier must have been submitted to that queue by then, or never be.
    /// `thickness` (mesh units, per bake vertex, BakeResult::thickness; empty: none, and no
    /// transmission is drawn) feeds Material::transmission. `scattering_normal` (per bake
    /// vertex, BakeResult::scattering_normal; empty: the vertex normals) is what the `Tm`
    /// mode's diffuse term is lit along; specular, Lambert and Curvature use the vertex normals.
    /// `normal_spread` (per bake vertex, BakeResult::normal_spread, each channel in [0, 1];
    /// empty: 0) adds Material::spread_strength · spread to the blur.
    void set_mesh(const PreparedMesh& mesh, std::span<const glm::vec3> tm = {}, std::span<const float> thickness = {},
                  std::span<const glm::vec3> scattering_normal = {}, std::span<const glm::vec3> normal_spread = {});
    /// The same with everything a bake made (t_m, thickness, scattering normals and spreads).
    void set_mesh(const PreparedMesh& mesh, const BakeResult& bake);
    /// A mesh as loaded, with t_m (and optionally the thickness, scattering normal and normal
    /// spread) per render vertex (e.g. TriangleMesh::baked_tm, baked_thickness,
    /// baked_scattering_normal, baked_normal_spread). It is prepared (welded) and the values are
    /// averaged over the render vertices of each bake vertex.
    void set_mesh(const TriangleMesh& mesh, std::span<const glm::vec3> tm_per_render_vertex,
                  std::span<const float> thickness_per_render_vertex = {},
                  std::span<const glm::vec3> scattering_normal_per_render_vertex = {},
                  std::span<const glm::vec3> normal_spread_per_render_vertex = {});
    /// A deforming mesh, kept on the GPU: records a compute pass that copies new positions,
    /// normals and t_m - tightly packed float3 per bake vertex of the mesh given to set_mesh,
    /// in storage buffers such as MeshDeformer::buffers().positions/normals and
    /// DynamicBake::buffers().tm - into the renderer's vertex buffer. t_m is clamped to
    /// [0, 3e38] (NaN to 0). What set_mesh computed on the host stays: the curvature, the bounds
    /// that fit the near/far planes, the false-colour range. Synchronisation, in `cmd`: a barrier
    /// after earlier compute-shader and transfer writes to the inputs (and earlier draws' vertex
    /// reads), and one before the vertex input of later draws on the same queue (record() or
    /// render() after it). `thickness` (float per bake vertex, DynamicBake::buffers().thickness)
    /// is optional: VK_NULL_HANDLE keeps the thickness set_mesh was given. `scattering_normal`
    /// (the per-channel normal sums, three float3 per bake vertex:
    /// DynamicBake::buffers().scattering_normal) gives the scattering normal and the normal
    /// spread as BakeResult defines them; VK_NULL_HANDLE: the new vertex normals, spread 0. The
    /// light-depth tiles of the transmission term stay placed about set_mesh's bounds, with room
    /// for 1.1 × its bounding sphere: a part deformed beyond that takes its local thickness as
    /// its light path (it is not shadowed by the rest of the body). Throws jade::Error without a
    /// mesh or with a null positions, normals or t_m buffer.
    void record_vertex_update(VkCommandBuffer cmd, VkBuffer positions, VkBuffer normals, VkBuffer tm,
                              VkBuffer thickness = VK_NULL_HANDLE, VkBuffer scattering_normal = VK_NULL_HANDLE);
    /// The same in a submission of its own (waits).
    void update_vertices(VkBuffer positions, VkBuffer normals, VkBuffer tm, VkBuffer thickness = VK_NULL_HANDLE,
                         VkBuffer scattering_normal = VK_NULL_HANDLE);
    /// Albedo, strength, specular parameters and profiles (the curvature LUT is rebuilt, on
    /// the CPU in float64, when the profiles change). Replaced GPU objects are released like
    /// set_mesh's, without waiting for recorded draws.
    void set_material(const Material& material);

    /// Renders one image: draws into MSAA targets it owns (kept for the next call of the same
    /// size), resolves, reads back, then tone maps and draws the legend on the host. Needs
    /// set_mesh and set_material first.
    RenderedImage render(const Camera& camera, std::span<const Light> lights, const RenderSettings& settings);

    /// Records the draw into the caller's command buffer (outside any rendering scope; at most
    /// 64 lights). `settings` gives mode, samples, format (float32) and background; tone
    /// mapping and the legend are not applied. Synchronisation, all in the command buffer:
    /// - before: the caller makes previous uses of the target images available to
    ///   COLOR_ATTACHMENT_OUTPUT (color, resolve) and EARLY/LATE_FRAGMENT_TESTS (depth) and puts
    ///   them in the layouts of RenderTarget.
    /// - inside: a vkCmdUpdateBuffer of the renderer's frame constants (TRANSFER stage), guarded
    ///   by barriers against the previous record()'s shader reads, then one dynamic rendering.
    /// - after: the resolve (or color) image was written at COLOR_ATTACHMENT_OUTPUT with
    ///   COLOR_ATTACHMENT_WRITE; the caller adds the barrier for its next use.
    /// - Separable, Burley: the draw also writes the renderer's own irradiance target, and two more
    ///   renderings (Burley: one; fullscreen, within the mesh's screen bounds) blur it and add it to the resolve
    ///   (or single-sample color) image, still at COLOR_ATTACHMENT_OUTPUT; a multisampled target
    ///   with `keep` is refused (its multisampled colour would lack the blurred light).
    /// The mesh, material and pipelines are the renderer's. Submit the command buffer to the
    /// Context's queue: set_mesh, set_material and the destructor release what they replace
    /// when the GPU has finished the work submitted to that queue before them, never waiting.
    void record(VkCommandBuffer cmd, const RenderTarget& target, const Camera& camera, std::span<const Light> lights,
                const RenderSettings& settings);

private:
    friend struct dev::RendererAccess;  // the introspection of jade/dev/renderer.hpp
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace jade
