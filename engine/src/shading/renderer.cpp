// shading/renderer.cpp - jade::Renderer: one draw of the mesh with mesh.vert/mesh.frag into
// MSAA colour + depth, resolved, read back (render) or left to the caller (record). What it
// holds and how it draws: Renderer::Impl, shading/renderer_impl.hpp.
#include "shading/renderer_impl.hpp"

#include <jade/bake.hpp>
#include <jade/context.hpp>

#include "jade_shaders.hpp"

namespace jade {

Renderer::Renderer(Context& context, const RendererOptions& options)
    : impl_(std::make_unique<Impl>(gpu_of(context), options))
{
}
Renderer::~Renderer()
{
    if (impl_) impl_->ctx.release_after_gpu(std::move(impl_));
}

void Renderer::set_mesh(const PreparedMesh& mesh, const BakeResult& bake)
{
    set_mesh(mesh, bake.tm, bake.thickness, bake.scattering_normal, bake.normal_spread);
}

void Renderer::set_mesh(const PreparedMesh& mesh, std::span<const glm::vec3> tm, std::span<const float> thickness,
                        std::span<const glm::vec3> scattering_normal, std::span<const glm::vec3> normal_spread)
{
    const size_t n = mesh.vertex_count();
    if (mesh.normals.size() != n || mesh.indices.empty())
        throw Error("Renderer::set_mesh: the mesh is empty or not prepared (use prepare_mesh)");
    std::vector<float> curvature = mean_curvature(mesh, impl_->options.curvature_smoothing);
    shading::MeshVertices built =
        shading::build_vertices(mesh, tm, thickness, scattering_normal, normal_spread, curvature);
    std::vector<shading::Vertex>& vertices = built.vertices;
    const float tm_min = built.tm_min_mean, tm_max = built.tm_max_mean;
    const glm::vec3 tm_min_channel = built.tm_min;
    Impl& m = *impl_;
    if (m.has_mesh)
        m.ctx.release_after_gpu(std::move(m.vertices), std::move(m.indices));  // recorded draws may read them
    // Storage too: record_vertex_update() rewrites positions, normals and t_m on the GPU.
    m.vertices = gpu::Buffer::from(
        m.ctx, vertices, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "mesh vertices");
    m.vertex_count = uint32_t(n);
    m.indices = gpu::Buffer::from(m.ctx, mesh.indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "mesh indices");
    m.index_count = uint32_t(mesh.indices.size());
    m.bbox_min = mesh.bbox_min, m.bbox_max = mesh.bbox_max;
    m.curvature = std::move(curvature);
    m.tm_min_mean = tm_min, m.tm_max_mean = tm_max;
    m.tm_min = tm_min_channel;
    m.has_mesh = true;
    ++m.geometry_version;
    m.has_thickness = !thickness.empty();
    m.light_path = shading::resolve_light_path(dev::study_of(m.options).light_path, double(built.median_edge),
                                               double(m.bounding_radius()), m.options.light_depth_size);
}

void Renderer::record_vertex_update(VkCommandBuffer cmd, VkBuffer positions, VkBuffer normals, VkBuffer tm,
                                    VkBuffer thickness, VkBuffer scattering_normal)
{
    Impl& m = *impl_;
    if (!m.has_mesh) throw Error("Renderer::record_vertex_update: no mesh (call set_mesh first)");
    if (!positions || !normals || !tm) throw Error("Renderer::record_vertex_update: a buffer is VK_NULL_HANDLE");
    using shading::PackPush;  // shading_interface.h, shared with pack_vertices.comp
    if (!m.pack_vertices)
        m.pack_vertices.emplace(m.ctx,
                                gpu::KernelDesc{"pack_vertices",
                                                shaders::pack_vertices_comp(),
                                                std::vector<VkDescriptorType>(6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER),
                                                sizeof(PackPush),
                                                64,
                                                {}});
    const VkDeviceSize stream = VkDeviceSize(m.vertex_count) * 12;  // one float3 per vertex
    const VkDeviceSize normal_sums = 3 * stream;                    // one float3 per vertex and channel
    // Earlier compute or transfer writes to the inputs, and earlier draws' reads of the vertices.
    gpu::memory_barrier(cmd,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT |
                            VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT,
                        VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT);
    // Without a thickness or scattering-normal stream the binding gets the t_m stream (never read).
    m.pack_vertices->dispatch(
        cmd, m.vertex_count, PackPush{m.vertex_count, thickness ? 1u : 0u, scattering_normal ? 1u : 0u},
        {gpu::Binding(positions, 0, stream), gpu::Binding(normals, 0, stream), gpu::Binding(tm, 0, stream), m.vertices,
         gpu::Binding(thickness ? thickness : tm, 0, stream / 3),
         gpu::Binding(scattering_normal ? scattering_normal : tm, 0, scattering_normal ? normal_sums : stream)});
    if (thickness) m.has_thickness = true;
    m.tm_min = glm::vec3(0.0f);  // t_m now comes from the GPU: the evaluation must hold for any t
    ++m.geometry_version;
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT);
}

void Renderer::update_vertices(VkBuffer positions, VkBuffer normals, VkBuffer tm, VkBuffer thickness,
                               VkBuffer scattering_normal)
{
    impl_->ctx.submit_and_wait(
        [&](VkCommandBuffer cmd) { record_vertex_update(cmd, positions, normals, tm, thickness, scattering_normal); });
}

void Renderer::set_material(const Material& material)
{
    shading::check_material(material);
    Impl& m = *impl_;
    if (m.curvature_lut && m.curvature_lut_profiles != material.profile) {
        m.ctx.release_after_gpu(std::move(*m.curvature_lut));  // recorded draws may read it; rebuilt on demand
        m.curvature_lut.reset();
    }
    if (material.transmission.enabled()) m.transmission_table.update(material.transmission);
    m.material = material;
    m.soft_shadow = shading::soft_shadow_kernel(material);
}

RenderedImage Renderer::render(const Camera& camera, std::span<const Light> lights, const RenderSettings& settings)
{
    return impl_->render(camera, lights, settings, uint32_t(settings.mode));
}

void Renderer::record(VkCommandBuffer cmd, const RenderTarget& target, const Camera& camera,
                      std::span<const Light> lights, const RenderSettings& settings)
{
    impl_->ctx.collect_released();  // once a frame: what earlier set_mesh calls replaced
    impl_->record(cmd, target, camera, lights, settings, uint32_t(settings.mode));
}

}  // namespace jade
