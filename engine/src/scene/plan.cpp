// scene/plan.cpp - plan_scene: which passes each object needs and what they allocate.
//
// Memory estimate: each module reports the buffers it will create, named as it names them,
// from its own sizes and constants (bake/buffer_estimate.cpp, which also says what is estimated
// rather than known; deform/buffer_estimate.hpp; shading/buffer_estimate.hpp). The plan only
// puts them together. Images (the LUTs) are listed but are not buffers; host-visible staging
// is not counted.
#include <jade/dev/material.hpp>
#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>  // dev::study_of: the LUT size
#include <jade/dev/scene.hpp>
#include <jade/scene.hpp>

#include "bake/buffer_estimate.hpp"
#include "deform/buffer_estimate.hpp"
#include "shading/buffer_estimate.hpp"

#include <jade/error.hpp>

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace jade {

using dev::BufferEstimate;
using dev::ObjectPlan;
using dev::PassKind;
using dev::PassPlan;
using dev::ScenePlanDetails;

namespace {

std::string bytes_text(uint64_t b)
{
    char buf[32];
    if (b >= (1u << 20))
        std::snprintf(buf, sizeof buf, "%.2f MiB", double(b) / double(1u << 20));
    else if (b >= 1024)
        std::snprintf(buf, sizeof buf, "%.1f KiB", double(b) / 1024.0);
    else
        std::snprintf(buf, sizeof buf, "%llu B", (unsigned long long)b);
    return buf;
}

// Σ of the estimates that are buffers: images (the LUTs) are listed but are not buffers.
uint64_t buffer_bytes_of(const std::vector<BufferEstimate>& estimates)
{
    uint64_t sum = 0;
    for (const auto& b : estimates) sum += b.image ? 0 : b.bytes;
    return sum;
}

// Whether object k takes an earlier instance's static bake (SceneObject::instance_of): both
// static and translucent, the same render vertex count. An instance_of that names no earlier
// object is an error; one whose source cannot lend a bake (deforming, opaque) bakes on its own.
bool shares_bake(const Scene& scene, size_t k, const ScenePlanDetails& plan)
{
    const SceneObject& obj = scene.objects[k];
    if (!obj.instance_of) return false;
    const uint32_t j = obj.instance_of->object;
    if (j >= k)
        throw Error(scene.name + ": object " + std::to_string(k) + " '" + obj.name + "': instance_of names object " +
                    std::to_string(j) + ", not an earlier one");
    const ObjectPlan& source = plan.objects[j];
    return !source.opaque && !source.deforming && scene.objects[j].mesh.positions.size() == obj.mesh.positions.size() &&
           source.channels == (dev::is_grey(obj.material) ? 1u : 3u);
}

}  // namespace

std::string_view dev::pass_kind_name(PassKind kind)
{
    switch (kind) {
    case PassKind::CacheRead: return "cache read";
    case PassKind::StaticBake: return "static bake";
    case PassKind::Deform: return "deform";
    case PassKind::DynamicBake: return "dynamic bake";
    case PassKind::Draw: return "draw";
    case PassKind::SharedBake: return "shared bake";
    }
    return "unknown";
}

uint64_t dev::PassPlan::bytes() const
{
    uint64_t sum = 0;
    for (const auto& b : buffers) sum += b.bytes;
    return sum;
}

uint64_t dev::PassPlan::buffer_bytes() const { return buffer_bytes_of(buffers); }

uint64_t dev::ObjectPlan::resident_bytes() const
{
    uint64_t sum = 0;
    for (const auto& p : passes) sum += p.resident ? p.bytes() : 0;
    return sum;
}

uint64_t dev::ObjectPlan::transient_bytes() const
{
    uint64_t peak = 0;
    for (const auto& p : passes) peak = std::max(peak, p.resident ? 0 : p.bytes());
    return peak;
}

bool dev::ObjectPlan::runs(PassKind kind) const
{
    return std::any_of(passes.begin(), passes.end(), [&](const PassPlan& p) { return p.kind == kind; });
}

uint64_t dev::ScenePlanDetails::shared_buffer_bytes() const { return buffer_bytes_of(shared); }

const ScenePlanDetails& dev::plan_details(const ScenePlan& plan)
{
    static const ScenePlanDetails none;
    return plan.details ? *plan.details : none;
}

uint64_t ScenePlan::resident_bytes() const
{
    const ScenePlanDetails& d = dev::plan_details(*this);
    uint64_t sum = 0;
    for (const auto& o : d.objects) sum += o.resident_bytes();
    for (const auto& b : d.shared) sum += b.bytes;
    return sum;
}

uint64_t ScenePlan::transient_peak_bytes() const
{
    uint64_t peak = 0;
    for (const auto& o : dev::plan_details(*this).objects) peak = std::max(peak, o.transient_bytes());
    return peak;
}

std::string ScenePlan::describe() const
{
    const auto& [objects, shared] = dev::plan_details(*this);
    std::ostringstream out;
    for (size_t k = 0; k < objects.size(); ++k) {
        const ObjectPlan& o = objects[k];
        out << "object " << k << " '" << o.name << "': " << o.bake_vertices << " vertices, " << o.triangles
            << " triangles, "
            << (o.opaque      ? "opaque"
                : o.deforming ? "deforming"
                              : "static")
            << ", "
            << (o.opaque ? std::string("no t_m")
                         : std::to_string(o.channels) + (o.channels == 1 ? " channel (grey)" : " channels"))
            << "\n  shader variant: mode " << dev::shading_mode_name(o.variant.mode)
            << ", CHANNELS=" << o.variant.channels;
        if (o.runs(PassKind::SharedBake)) {
            out << "\n  static bake: shared with an earlier instance (no bake will run)";
        } else if (!o.opaque && !o.deforming) {
            char key[24];
            std::snprintf(key, sizeof key, "%016llx", (unsigned long long)o.bake_key);
            out << "\n  static bake: " << (o.bake_key ? "key " + std::string(key) + ", " : std::string("no cache, "))
                << (o.cached ? "in the cache (no bake will run)" : "not cached (bakes once)");
        }
        out << "\n";
        for (const PassPlan& p : o.passes) {
            out << "  pass " << dev::pass_kind_name(p.kind) << (p.per_frame ? " (every frame)" : " (once)")
                << (p.resident          ? ", kept"
                    : p.buffers.empty() ? ""
                                        : ", freed after")
                << ": " << p.buffers.size() << " buffers, " << bytes_text(p.bytes()) << "\n";
            for (const auto& b : p.buffers) out << "      " << b.name << "  " << bytes_text(b.bytes) << "\n";
        }
        out << "  GPU memory: " << bytes_text(o.resident_bytes()) << " kept, " << bytes_text(o.transient_bytes())
            << " peak during the once-only passes\n";
    }
    if (!shared.empty()) {
        uint64_t sum = 0;
        for (const auto& b : shared) sum += b.bytes;
        out << "shared by every object while drawing: " << shared.size() << " buffers and images, " << bytes_text(sum)
            << "\n";
        for (const auto& b : shared) out << "      " << b.name << "  " << bytes_text(b.bytes) << "\n";
    }
    out << "scene: " << objects.size() << " objects, " << bytes_text(resident_bytes()) << " kept while drawing, "
        << bytes_text(transient_peak_bytes())
        << " peak of once-only passes (estimates: see bake/buffer_estimate.cpp)\n";
    return out.str();
}

StaticBakeSource dev::never_baked()
{
    StaticBakeSource s;
    s.lookup = [](const PreparedMesh&, const Material&, const BakeSettings&) {
        return StaticBakeSource::Lookup{0, true};
    };
    s.bake = [](Context&, const PreparedMesh& mesh, const Material&, const BakeSettings&) {
        CachedBake b;
        b.result.tm.assign(mesh.vertex_count(), glm::vec3(0.0f));
        b.source = BakeSource::Cache;
        b.note = "never baked: t_m = 0";
        return b;
    };
    return s;
}

ScenePlan plan_scene(const Scene& scene, const SceneSettings& settings, const StaticBakeSource& source)
{
    if (settings.mode != ShadingMode::Tm && settings.mode != ShadingMode::TmFalseColor)
        throw Error("scene settings: mode " + std::string(dev::shading_mode_name(settings.mode)) +
                    " is not a scene mode (tm or tm-false-color; opaque objects use lambert)");
    if (scene.objects.empty()) throw Error(scene.name + ": the scene has no objects");
    auto plan = std::make_shared<ScenePlanDetails>();
    for (size_t k = 0; k < scene.objects.size(); ++k) {
        const SceneObject& obj = scene.objects[k];
        PreparedMesh prepared;
        try {
            prepared = prepare_mesh(obj.mesh);
        } catch (const Error& e) {
            throw Error(scene.name + ": object " + std::to_string(k) + " '" + obj.name + "': " + e.what());
        }
        ObjectPlan o;
        o.name = obj.name;
        o.bake_vertices = prepared.vertex_count();
        o.triangles = prepared.triangle_count();
        o.opaque = obj.material.opaque;
        o.deforming = obj.deformer.has_value() && !o.opaque;
        const size_t n = o.bake_vertices, tris = o.triangles;
        if (o.opaque) {
            // Lambert needs neither AO nor t_m: no bake, and a deformer would move an
            // untextured Lambert surface only, which the scene does not animate (documented).
            o.channels = 0;
            o.variant = {ShadingMode::Lambert, 3};
        } else {
            o.channels = dev::is_grey(obj.material) ? 1 : 3;
            o.variant = {settings.mode, settings.mode == ShadingMode::Tm ? o.channels : 3};
            if (o.deforming) {
                o.passes.push_back({PassKind::Deform, true, true, deform::estimate_buffers(n, tris)});
                o.passes.push_back({PassKind::DynamicBake, true, true,
                                    bake::estimate_buffers(prepared, obj.material, settings.bake, true,
                                                           obj.material.transmission.enabled())});
            } else if (shares_bake(scene, k, *plan)) {
                // The earlier object's prepared mesh, moved (its welding, not this copy's own).
                const ObjectPlan& from = plan->objects[obj.instance_of->object];
                o.bake_vertices = from.bake_vertices, o.triangles = from.triangles;
                o.passes.push_back({PassKind::SharedBake, false, false, {}});
            } else {
                if (source.lookup) {
                    const auto found = source.lookup(prepared, obj.material, settings.bake);
                    o.bake_key = found.key, o.cached = found.holds;
                }
                if (o.cached)
                    o.passes.push_back({PassKind::CacheRead, false, false, {}});
                else
                    o.passes.push_back({PassKind::StaticBake, false, false,
                                        bake::estimate_buffers(prepared, obj.material, settings.bake, false,
                                                               obj.material.transmission.enabled())});
            }
        }
        o.passes.push_back({PassKind::Draw, true, true, shading::estimate_draw_buffers(n, tris, obj.material)});
        plan->objects.push_back(std::move(o));
    }
    if (!plan->objects.empty()) {
        const dev::RendererStudy& study = dev::study_of(settings.renderer);
        plan->shared = shading::estimate_lut_buffers(study.lut, study.tm_evaluation);
    }
    ScenePlan result;
    result.details = std::move(plan);
    return result;
}

}  // namespace jade
