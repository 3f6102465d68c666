// jade_deform_demo [MESH] [OUT.gif] - a twisting mesh with translucency re-baked every frame,
// using only the public API: MeshDeformer (GPU deform + normals/areas), Baker, Renderer.
// Draft bake quality, 12 frames of 192x192. `jade deform --help` has every option.
//
// INTERIM: the deformed vertices are read back and baked through Baker::bake (a CPU round trip
// per frame) until the GPU-resident re-bake replaces that path.
#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/deform.hpp>
#include <jade/error.hpp>
#include <jade/io.hpp>
#include <jade/material.hpp>
#include <jade/render.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv)
{
    try {
        const char* mesh_path = argc > 1 ? argv[1] : "assets/bunny00.off";
        const char* out_path = argc > 2 ? argv[2] : "deform_demo.gif";
        constexpr int kFrames = 12, kSize = 192;

        jade::Context context;
        const jade::PreparedMesh rest = jade::prepare_mesh(jade::load_mesh(mesh_path));
        jade::ProceduralDeformer twist = jade::ProceduralDeformer::fit(jade::DeformerKind::Twist, rest, 1);
        jade::MeshDeformer deformer(context, rest);
        jade::Baker baker(context);
        jade::Renderer renderer(context);
        // The material is sized by the rest mesh (100 mm across), so it does not change per frame.
        const jade::Material material = jade::material_preset("jade", 100.0 / rest.diagonal);
        renderer.set_material(material);
        const jade::BakeSettings settings = jade::BakeSettings::preset(jade::Quality::Draft);

        // A margin around the rest bounds keeps the twisting mesh in view.
        const glm::vec3 margin = 0.15f * (rest.bbox_max - rest.bbox_min);
        const jade::Camera camera = jade::Camera::framing(rest.bbox_min - margin, rest.bbox_max + margin);
        const auto lights = jade::figure1_lights(camera);
        jade::RenderSettings render;
        render.width = render.height = kSize;
        render.tone_map = jade::ToneMap::AcesFitted;

        std::vector<std::vector<float>> frames;
        for (int f = 0; f < kFrames; ++f) {
            const double t = twist.period * double(f) / kFrames;
            const jade::DeformTimings d = deformer.deform(twist, t);
            const jade::PreparedMesh deformed = jade::deformed_mesh(rest, deformer.read());
            const jade::BakeResult baked = baker.bake(deformed, material, settings);
            renderer.set_mesh(deformed, baked);
            jade::RenderedImage image = renderer.render(camera, lights, render);
            std::printf("frame %2d  t = %.2f s  deform+normals %.2f ms  bake %.0f ms  draw %.1f ms (GPU)\n", f, t,
                        d.deform_ms + d.normals_ms, baked.timings.gpu_total_ms, image.gpu_ms);
            frames.push_back(std::move(image.rgba));
        }
        jade::save_animation(out_path, kSize, kSize, frames, kFrames / twist.period);
        std::printf("%s: %d frames\n", out_path, kFrames);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "jade_deform_demo: error: %s\n", e.what());
        return 1;
    }
}
