// scene/plan.cpp - plan_scene: which passes each object needs and what they allocate.
//
// Memory estimate. Every byte count below is the size of a buffer that engine/src/bake,
// engine/src/deform or engine/src/shading creates, written with the struct sizes those files
// use (float3 = 12 bytes, GpuProfile = 72, ray items 3 texels of 16 bytes, ...). What depends on
// the geometry rather than on the counts is estimated with three constants measured on the
// test meshes (sphere, box, grid, bunny; tests/test_scene.cpp compares the total with the bytes
// the Context really allocated, Context::created_objects().device_buffer_bytes):
//   - the triangle BVH (leaves of ≤ 4 triangles) has about kRayNodesPerTriangle nodes per
//     triangle, the point tree (leaves of ≤ 8 points) kPointNodesPerVertex nodes per vertex;
//   - a near-field list holds about kNearEntriesPerVertex sources per vertex on a regular mesh
//     (sources within 4 disk radii: π·(4·0.56 h)² / (0.87 h²) ≈ 18 neighbours at spacing h),
//     times margin² for the dynamic bake's 1.5× margin.
// Images (the LUTs) are listed but are not buffers; host-visible staging is not counted.
#include "shading/transmission_table.hpp"
#include <jade/scene.hpp>

#include "bake/gpu_profile.hpp"
#include "bake/grid_field.hpp"

#include <jade/error.hpp>

#include <algorithm>
#include <optional>
#include <cstdio>
#include <sstream>

namespace jade {
namespace {

constexpr double kRayNodesPerTriangle = 0.6;
constexpr double kPointNodesPerVertex = 0.3;
constexpr double kNearEntriesPerVertex = 20.0;
constexpr double kStaticNearMargin = 1.05, kDynamicNearMargin = 1.5;  // bake/baker.cpp
constexpr size_t kExactBelow = 2048;                                 // bake/baker.cpp: TmMethod::Auto

uint64_t at_least_16(double bytes) { return std::max<uint64_t>(16, uint64_t(bytes + 0.5)); }

// The buffers of Baker::Impl::MeshState (bake/baker.cpp upload_mesh, prepare_ao,
// prepare_thickness when the material has a transmission term, prepare_tm).
std::vector<BufferEstimate> bake_buffers(const PreparedMesh& mesh, const Material& material, const BakeSettings& s,
                                         bool dynamic, bool thickness)
{
    const size_t n = mesh.vertex_count(), tris = mesh.triangle_count();
    const double ray_nodes = kRayNodesPerTriangle * double(tris);
    const double ray_items = ray_nodes + double(tris);
    const double margin = dynamic ? kDynamicNearMargin : kStaticNearMargin;
    double near_entries = kNearEntriesPerVertex * double(n) * (margin * margin) / (kStaticNearMargin * kStaticNearMargin);
    const bool exact = s.method == TmMethod::Exact || (s.method == TmMethod::Auto && n < kExactBelow);
    // The grid far field: its own plan (bake/grid_field.hpp), as Baker::Impl::prepare_tm makes it.
    std::optional<bake::GridPlan> grid;
    if (!exact && (s.method == TmMethod::Grid || s.method == TmMethod::Auto)) {
        grid = bake::plan_grid(mesh, material, material.grey() ? 1 : 3, s.tm_grid_resolution, dynamic, margin);
        if (s.method == TmMethod::Auto && grid->coarsened) grid.reset();
    }
    if (grid) near_entries = double(grid->near_entries(n, margin));
    std::vector<BufferEstimate> b = {
        {"positions", at_least_16(12.0 * n)},
        {"normals", at_least_16(12.0 * n)},
        {"areas", at_least_16(4.0 * n)},
        {"ray items (BVH nodes and triangles)", at_least_16(48.0 * ray_items)},
        {"ao hit counts", at_least_16(4.0 * n)},
        {"ao", at_least_16(4.0 * n)},
        {"profiles", at_least_16(3.0 * sizeof(bake::GpuProfile))},
        {"t_m", at_least_16(12.0 * n)},
        {"t_m partial sums", at_least_16(12.0 * n)},
        {"t_m partial compensation", at_least_16(12.0 * n)},
        {"scattering normal sums (per channel)", at_least_16(36.0 * n)},
        {"near-field offsets", at_least_16(4.0 * (n + 1))},
        {"near-field disk candidates", at_least_16(4.0 * n)},
        {"near-field sources", at_least_16(4.0 * (near_entries + 64))},
        {"point order", at_least_16(4.0 * n)},
    };
    if (thickness && s.thickness.enabled()) {
        b.push_back({"thickness sums (per ray slice)", at_least_16(4.0 * n)});
        b.push_back({"thickness", at_least_16(4.0 * n)});
    }
    if (exact) {
        b.push_back({"t_m sources", at_least_16(32.0 * n)});
    } else if (grid) {
        b.push_back({"t_m sources", at_least_16(32.0 * n)});
        b.push_back({"t_m grid", at_least_16(double(grid->bytes()))});
    } else {
        const double nodes = kPointNodesPerVertex * double(n);
        const double first_point = std::ceil(4.0 * nodes / 16.0) * 16.0;
        b.push_back({"point tree nodes", at_least_16(32.0 * nodes)});  // bake::BvhNode: 2 × (vec3 + uint32)
        b.push_back({"point tree levels", at_least_16(4.0 * nodes)});
        b.push_back({"t_m cluster tree and sources", at_least_16(16.0 * first_point + 32.0 * n)});
        b.push_back({"t_m traversal resume state", at_least_16(12.0 * n)});
    }
    if (dynamic) {  // refit data (prepare_ao with refittable = true)
        b.push_back({"triangle indices", at_least_16(12.0 * tris)});
        b.push_back({"ray item origins", at_least_16(4.0 * ray_items)});
        b.push_back({"ray refit work", at_least_16(8.0 * ray_items)});
    }
    return b;
}

// deform/mesh_deformer.cpp: rest, triangles, adjacency, cross products, deformed outputs.
std::vector<BufferEstimate> deform_buffers(size_t n, size_t tris)
{
    return {{"deform: rest positions", at_least_16(12.0 * n)},
            {"deform: triangles", at_least_16(12.0 * tris)},
            {"deform: adjacency offsets", at_least_16(4.0 * (n + 1))},
            {"deform: adjacent triangles", at_least_16(12.0 * tris)},
            {"deform: triangle cross products", at_least_16(16.0 * tris)},
            {"deform: deformed positions", at_least_16(12.0 * n)},
            {"deform: deformed normals", at_least_16(12.0 * n)},
            {"deform: deformed areas", at_least_16(4.0 * n)}};
}

// shading/renderer.cpp: what one Renderer holds of its own while it draws.
std::vector<BufferEstimate> draw_buffers(size_t n, size_t tris, const Material& material)
{
    return {{"mesh vertices", at_least_16(double(kRendererVertexBytes) * n)},
            {"mesh indices", at_least_16(12.0 * tris)},
            {"frame data", kRendererFrameDataBytes},
            {"transmission table", shading::TransmissionTable::bytes(material.transmission)},
            {"curvature LUT placeholder (image)", 16, true}};
}

// shading/lut.cpp: the translucency LUT, shared by every Renderer of the scene.
std::vector<BufferEstimate> shared_buffers(const RendererOptions& o)
{
    const LutLayout& l = o.lut;
    return {{"translucency LUT quads", at_least_16(16.0 * (l.width - 1) * (l.height - 1))},
            {"translucency LUT (image)", uint64_t(l.width) * l.height * 4, true},
            {"translucency LUT, 16 bit (image)", uint64_t(l.width) * l.height * 2, true}};
}

std::string bytes_text(uint64_t b)
{
    char buf[32];
    if (b >= (1u << 20)) std::snprintf(buf, sizeof buf, "%.2f MiB", double(b) / double(1u << 20));
    else if (b >= 1024) std::snprintf(buf, sizeof buf, "%.1f KiB", double(b) / 1024.0);
    else std::snprintf(buf, sizeof buf, "%llu B", (unsigned long long)b);
    return buf;
}

}  // namespace

std::string_view pass_kind_name(PassKind kind)
{
    switch (kind) {
    case PassKind::CacheRead: return "cache read";
    case PassKind::StaticBake: return "static bake";
    case PassKind::Deform: return "deform";
    case PassKind::DynamicBake: return "dynamic bake";
    case PassKind::Draw: return "draw";
    }
    return "unknown";
}

uint64_t PassPlan::bytes() const
{
    uint64_t sum = 0;
    for (const auto& b : buffers) sum += b.bytes;
    return sum;
}

uint64_t PassPlan::buffer_bytes() const
{
    uint64_t sum = 0;
    for (const auto& b : buffers) sum += b.image ? 0 : b.bytes;
    return sum;
}

uint64_t ObjectPlan::resident_bytes() const
{
    uint64_t sum = 0;
    for (const auto& p : passes) sum += p.resident ? p.bytes() : 0;
    return sum;
}

uint64_t ObjectPlan::transient_bytes() const
{
    uint64_t peak = 0;
    for (const auto& p : passes) peak = std::max(peak, p.resident ? 0 : p.bytes());
    return peak;
}

bool ObjectPlan::runs(PassKind kind) const
{
    return std::any_of(passes.begin(), passes.end(), [&](const PassPlan& p) { return p.kind == kind; });
}

uint64_t ScenePlan::shared_buffer_bytes() const
{
    uint64_t sum = 0;
    for (const auto& b : shared) sum += b.image ? 0 : b.bytes;
    return sum;
}

uint64_t ScenePlan::resident_bytes() const
{
    uint64_t sum = 0;
    for (const auto& o : objects) sum += o.resident_bytes();
    for (const auto& b : shared) sum += b.bytes;
    return sum;
}

uint64_t ScenePlan::transient_peak_bytes() const
{
    uint64_t peak = 0;
    for (const auto& o : objects) peak = std::max(peak, o.transient_bytes());
    return peak;
}

std::string ScenePlan::describe() const
{
    std::ostringstream out;
    for (size_t k = 0; k < objects.size(); ++k) {
        const ObjectPlan& o = objects[k];
        out << "object " << k << " '" << o.name << "': " << o.bake_vertices << " vertices, " << o.triangles << " triangles, "
            << (o.opaque ? "opaque" : o.deforming ? "deforming" : "static") << ", "
            << (o.opaque ? std::string("no t_m") : std::to_string(o.channels) + (o.channels == 1 ? " channel (grey)" : " channels"))
            << "\n  shader variant: mode " << shading_mode_name(o.variant.mode) << ", CHANNELS=" << o.variant.channels;
        if (!o.opaque && !o.deforming) {
            char key[24];
            std::snprintf(key, sizeof key, "%016llx", (unsigned long long)o.bake_key);
            out << "\n  static bake: " << (o.bake_key ? "key " + std::string(key) + ", " : std::string("no cache, "))
                << (o.cached ? "in the cache (no bake will run)" : "not cached (bakes once)");
        }
        out << "\n";
        for (const PassPlan& p : o.passes) {
            out << "  pass " << pass_kind_name(p.kind) << (p.per_frame ? " (every frame)" : " (once)")
                << (p.resident ? ", kept" : p.buffers.empty() ? "" : ", freed after") << ": " << p.buffers.size() << " buffers, "
                << bytes_text(p.bytes()) << "\n";
            for (const auto& b : p.buffers) out << "      " << b.name << "  " << bytes_text(b.bytes) << "\n";
        }
        out << "  GPU memory: " << bytes_text(o.resident_bytes()) << " kept, " << bytes_text(o.transient_bytes())
            << " peak during the once-only passes\n";
    }
    if (!shared.empty()) {
        uint64_t sum = 0;
        for (const auto& b : shared) sum += b.bytes;
        out << "shared by every object while drawing: " << shared.size() << " buffers and images, " << bytes_text(sum) << "\n";
        for (const auto& b : shared) out << "      " << b.name << "  " << bytes_text(b.bytes) << "\n";
    }
    out << "scene: " << objects.size() << " objects, " << bytes_text(resident_bytes()) << " kept while drawing, "
        << bytes_text(transient_peak_bytes()) << " peak of once-only passes (estimates: see scene/plan.cpp)\n";
    return out.str();
}

StaticBakeSource never_baked()
{
    StaticBakeSource s;
    s.lookup = [](const PreparedMesh&, const Material&, const BakeSettings&) { return StaticBakeSource::Lookup{0, true}; };
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
        throw Error("scene settings: mode " + std::string(shading_mode_name(settings.mode)) +
                    " is not a scene mode (tm or tm-false-color; opaque objects use lambert)");
    if (scene.objects.empty()) throw Error(scene.name + ": the scene has no objects");
    ScenePlan plan;
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
        o.deforming = obj.deforming() && !o.opaque;
        const size_t n = o.bake_vertices, tris = o.triangles;
        if (o.opaque) {
            // Lambert needs neither AO nor t_m: no bake, and a deformer would move an
            // untextured Lambert surface only, which the scene does not animate (documented).
            o.channels = 0;
            o.variant = {ShadingMode::Lambert, 3};
        } else {
            o.channels = obj.material.grey() ? 1 : 3;
            o.variant = {settings.mode, settings.mode == ShadingMode::Tm ? o.channels : 3};
            if (o.deforming) {
                auto deform = deform_buffers(n, tris);
                o.passes.push_back({PassKind::Deform, true, true, std::move(deform)});
                o.passes.push_back({PassKind::DynamicBake, true, true, bake_buffers(prepared, obj.material, settings.bake, true, obj.material.transmission.enabled())});
            } else {
                if (source.lookup) {
                    const auto found = source.lookup(prepared, obj.material, settings.bake);
                    o.bake_key = found.key, o.cached = found.holds;
                }
                if (o.cached) o.passes.push_back({PassKind::CacheRead, false, false, {}});
                else o.passes.push_back({PassKind::StaticBake, false, false, bake_buffers(prepared, obj.material, settings.bake, false, obj.material.transmission.enabled())});
            }
        }
        o.passes.push_back({PassKind::Draw, true, true, draw_buffers(n, tris, obj.material)});
        plan.objects.push_back(std::move(o));
    }
    if (!plan.objects.empty()) plan.shared = shared_buffers(settings.renderer);
    return plan;
}

}  // namespace jade
