// shading/transmission_table.hpp - the transmission's forward attenuation A_b(t) of one material,
// tabulated on the GPU by shaders/transmission_table.comp from the formula in attenuation.glsl, for
// mesh.frag to interpolate at each fragment's path t (one texel fetch instead of three exponentials).
#pragma once

#include "gpu/buffer.hpp"
#include "gpu/kernel.hpp"
#include "gpu/texel_view.hpp"

#include <jade/material.hpp>

#include <glm/vec4.hpp>

#include <optional>

namespace jade::shading {

class TransmissionTable {
public:
    /// A table of four texels (A = 0) until the first update().
    explicit TransmissionTable(gpu::Context& ctx);

    /// Tabulates `tr` unless it is the one held: one submission, waited for. The caller makes
    /// sure no draw reading the table is in flight (Renderer::set_material waits for the device).
    void update(const Transmission& tr);

    /// The device bytes the table holds for a material with `tr` (for scene plans).
    static uint64_t bytes(const Transmission& tr);

    /// What attenuation_at() indexes with: x = 1/step (per mesh unit), y = last texel, z = last
    /// interval, w unused.
    glm::vec4 shader_map() const { return map_; }
    const gpu::TexelView& texels() const { return view_; }

private:
    struct Layout {
        uint32_t count;  // texels
        double step;     // mesh units between them
    };
    static Layout table_layout(const Transmission& tr);

    gpu::Context& ctx_;
    std::optional<gpu::Kernel> kernel_;
    gpu::Buffer buffer_;
    gpu::TexelView view_;  // destroyed before buffer_
    glm::vec4 map_{0.0f, 1.0f, 0.0f, 0.0f};
    std::optional<Transmission> held_;
};

}  // namespace jade::shading
