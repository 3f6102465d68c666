// io/gltf_asset.cpp - GltfAsset::load: a glTF file read whole, and what to bake of it (the
// instance rule of jade/io.hpp). The writer is io/gltf_asset_save.cpp.
#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include "io/common.hpp"
#include "io/gltf_asset.hpp"
#include "io/gltf_materials.hpp"
#include "io/gltf_model.hpp"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace jade {

namespace {

using io::fail;

std::string described(const std::string& kind, int index, const std::string& name)
{
    return kind + " " + std::to_string(index) + (name.empty() ? "" : " '" + io::printable(name, 48) + "'");
}

/// The JSON text of the file: all of a .gltf, the first chunk of a .glb (parse_gltf checked
/// the container).
std::string_view json_text(const std::string& bytes, bool binary)
{
    if (!binary) return bytes;
    uint32_t length;
    std::memcpy(&length, bytes.data() + 12, 4);
    return std::string_view(bytes).substr(20, length);
}

/// Every external image must have been read: the output embeds it.
void check_images(const GltfAssetImpl& a)
{
    for (size_t i = 0; i < a.model.images.size(); ++i) {
        const auto& image = a.model.images[i];
        if (image.bufferView >= 0 || image.uri.rfind("data:", 0) == 0) continue;
        if (a.image_bytes[i].empty())
            fail(a.name, described("image", int(i), image.name) + ": external file '" + io::printable(image.uri, 64) +
                             "' cannot be read (the baked file embeds it)");
    }
}

/// What the writer reads back from the input's own JSON must have the type the glTF schema gives
/// it, so that a bad input is refused naming the input, not the output.
void check_written_back_types(const GltfAssetImpl& a)
{
    const auto& doc = a.doc;
    // asset.version: this reader and writer are glTF 2.x.
    const auto asset = doc.find("asset");
    if (asset == doc.end() || !asset->is_object() || !asset->contains("version") || !(*asset)["version"].is_string() ||
        (*asset)["version"].get<std::string>().rfind("2.", 0) != 0)
        fail(a.name, "asset.version is not \"2.x\" (only glTF 2 is read)");
    auto count = [&](const char* array) {
        const auto it = doc.find(array);
        return it != doc.end() && it->is_array() ? it->size() : size_t(0);
    };
    // Indices that nodes and primitives carry, in range even where no scene reaches them: the
    // output writes every node and mesh back.
    if (const auto nodes = doc.find("nodes"); nodes != doc.end() && nodes->is_array())
        for (size_t n = 0; n < nodes->size(); ++n)
            for (const auto& [key, array] :
                 {std::pair<const char*, const char*>{"mesh", "meshes"}, {"skin", "skins"}, {"camera", "cameras"}}) {
                const auto& node = (*nodes)[n];
                if (!node.is_object() || !node.contains(key)) continue;
                const auto& v = node[key];
                if (!v.is_number_integer() || v.get<int64_t>() < 0 || uint64_t(v.get<int64_t>()) >= count(array))
                    fail(a.name, "node " + std::to_string(n) + ": " + key + " " + io::printable(v.dump(), 32) +
                                     " is not an index into " + array);
            }
    if (const auto meshes = doc.find("meshes"); meshes != doc.end() && meshes->is_array())
        for (size_t m = 0; m < meshes->size(); ++m) {
            const auto& mesh = (*meshes)[m];
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
            for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
                const auto& prim = mesh["primitives"][p];
                if (!prim.is_object() || !prim.contains("mode")) continue;
                const auto& v = prim["mode"];
                if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > 6)
                    fail(a.name, "mesh " + std::to_string(m) + " primitive " + std::to_string(p) + ": mode " +
                                     io::printable(v.dump(), 32) + " is not 0 to 6");
            }
        }
    const auto images = doc.find("images");
    if (images == doc.end()) return;
    if (!images->is_array()) fail(a.name, "images is not an array");
    for (size_t i = 0; i < images->size(); ++i) {
        const auto& image = (*images)[i];
        if (!image.is_object()) fail(a.name, "image " + std::to_string(i) + " is not an object");
        for (const char* key : {"mimeType", "uri", "name"})
            if (image.contains(key) && !image[key].is_string())
                fail(a.name, "image " + std::to_string(i) + ": " + key + " is not a string");
    }
}

/// The space a mesh is baked in, from its first instance (see GltfAsset).
struct Placement {
    glm::dmat4 world{1.0};
    std::string space;
};

std::vector<Placement> placements(const GltfAssetImpl& a)
{
    const auto& model = a.model;
    std::vector<Placement> out(model.meshes.size());
    std::vector<int> first(model.meshes.size(), -1), count(model.meshes.size(), 0);
    std::vector<glm::dmat4> world(model.meshes.size());
    for (const auto& instance : io::scene_mesh_instances(a.name, model)) {
        const size_t m = size_t(instance.mesh);
        if (count[m]++ == 0) first[m] = instance.node, world[m] = instance.world;
    }
    for (size_t m = 0; m < out.size(); ++m) {
        if (first[m] < 0) {
            out[m].space = "its own coordinates (no node of the default scene shows it)";
            continue;
        }
        const auto& node = model.nodes[size_t(first[m])];
        const std::string where = described("node", first[m], node.name);
        if (node.skin >= 0) {
            out[m].space = "its bind pose (the skinned " + where + "; the stored positions)";
        } else {
            out[m].world = world[m];
            out[m].space = "world space of " + where +
                           (count[m] > 1 ? " (first of " + std::to_string(count[m]) + " instances)" : "");
        }
    }
    return out;
}

/// The bake targets of one mesh: its triangle primitives merged, one target per material group.
void add_targets(GltfAssetImpl& a, int mesh_index, const Placement& placement, std::vector<std::string>* warnings)
{
    const auto& mesh = a.model.meshes[size_t(mesh_index)];
    const std::string mesh_name = described("mesh", mesh_index, mesh.name);
    TriangleMesh merged;
    merged.name = a.name + ": " + mesh_name;
    std::vector<GltfAssetImpl::Span> spans(mesh.primitives.size());
    std::vector<int> groups;            // group key per primitive: translucent material, or -1
    std::map<int, std::string> opaque;  // materials of the caller's group, for its description
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const auto& prim = mesh.primitives[p];
        groups.push_back(-2);
        if (!io::is_triangle_mode(prim.mode)) continue;
        if (prim.material >= int(a.model.materials.size()))
            fail(a.name, mesh_name + " primitive " + std::to_string(p) + ": material " + std::to_string(prim.material) +
                             " does not exist (" + std::to_string(a.model.materials.size()) + " materials)");
        const TriangleMesh part = io::read_gltf_primitive(a.name, a.model, mesh_index, p, placement.world);
        // The asset is written back with its own NORMAL accessors: a bad one would go out as read.
        if (const auto bad = io::first_bad_normal(part); bad.vertex >= 0)
            fail(a.name, mesh_name + " primitive " + std::to_string(p) + ": NORMAL of vertex " +
                             std::to_string(bad.vertex) + " is " + bad.what +
                             " (a normal must be finite and non-zero)");
        if (part.positions.size() > io::kMaxVertices - merged.positions.size())
            fail(a.name, mesh_name + ": more vertices in total than 32-bit indices can address");
        const size_t base = merged.positions.size();
        spans[p] = {base, part.positions.size(), true};
        merged.positions.insert(merged.positions.end(), part.positions.begin(), part.positions.end());
        for (uint32_t i : part.indices) merged.indices.push_back(uint32_t(base + i));
        const bool translucent = prim.material >= 0 && a.translucent[size_t(prim.material)];
        groups.back() = translucent ? prim.material : -1;
        if (!translucent)
            opaque[prim.material] =
                prim.material < 0 ? "no material"
                                  : described("material", prim.material, a.model.materials[size_t(prim.material)].name);
    }
    if (merged.indices.empty()) {
        if (warnings && !mesh.primitives.empty())
            warnings->push_back(a.name + ": " + mesh_name + " has no triangles; not baked");
        return;
    }
    validate_mesh(merged);   // finite positions, indices in range; the message names file and mesh
    std::vector<int> order;  // group keys in order of first appearance
    for (int g : groups)
        if (g != -2 && std::find(order.begin(), order.end(), g) == order.end()) order.push_back(g);
    for (int key : order) {
        GltfAsset::BakeTarget t;
        t.mesh = merged;
        t.mesh_index = mesh_index;
        t.space = placement.space;
        for (size_t p = 0; p < groups.size(); ++p)
            if (groups[p] == key) t.primitives.push_back(int(p));
        if (key >= 0) {
            t.material = a.translucent[size_t(key)];
            t.material_name = described("material", key, a.model.materials[size_t(key)].name);
        } else {
            for (const auto& [index, text] : opaque)
                t.material_name += std::string(t.material_name.empty() ? "" : ", ") + text;
            t.material_name += " (opaque for Jade)";
        }
        std::vector<GltfAssetImpl::Span> own = spans;
        for (size_t p = 0; p < own.size(); ++p) own[p].baked = own[p].baked && groups[p] == key;
        a.targets.push_back(std::move(t));
        a.spans.push_back(std::move(own));
        // A length of the bake's space in the mesh's own units: 1 / the instance's mean scale.
        const double det = std::abs(glm::determinant(glm::dmat3(placement.world)));
        a.mesh_units_per_bake_unit.push_back(det > 0.0 && std::isfinite(det) ? 1.0 / std::cbrt(det) : 1.0);
    }
}

}  // namespace

GltfAsset::GltfAsset(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GltfAsset::GltfAsset(GltfAsset&&) noexcept = default;
GltfAsset& GltfAsset::operator=(GltfAsset&&) noexcept = default;
GltfAsset::~GltfAsset() = default;

const std::vector<GltfAsset::BakeTarget>& GltfAsset::targets() const { return impl_->targets; }

const std::string& dev::asset_name(const GltfAsset& asset) { return GltfAssetAccess::impl(asset).name; }
const std::vector<std::filesystem::path>& dev::asset_files(const GltfAsset& asset)
{
    return GltfAssetAccess::impl(asset).files;
}

std::string dev::asset_extras_json(const GltfAsset& a)
{
    const nlohmann::ordered_json& doc = GltfAssetAccess::impl(a).doc;
    const auto& asset = doc.find("asset");
    if (asset == doc.end() || !asset->is_object() || !asset->contains("extras")) return {};
    return (*asset)["extras"].dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

GltfAsset GltfAsset::load(const std::filesystem::path& path, std::vector<std::string>* warnings,
                          const ReadOptions& options)
{
    const std::string name = io::display_name(path);
    return io::naming_file(name, [&] {
        const auto ext = io::lower_extension(path);
        if (ext != ".gltf" && ext != ".glb") fail(name, "a glTF asset must be .gltf or .glb, not '" + ext + "'");
        const std::string bytes = io::read_file(path);
        if (bytes.empty()) fail(name, "file is empty");
        auto a = std::make_unique<Impl>();
        a->path = path;
        a->name = name;
        a->files.push_back(path);
        a->model = io::parse_gltf(path, name, bytes, ext == ".glb", options, &a->image_bytes, &a->files);
        io::check_required_extensions(name, a->model);
        try {
            a->doc = nlohmann::ordered_json::parse(json_text(bytes, ext == ".glb"));
        } catch (const nlohmann::json::exception& e) {
            fail(name, std::string("JSON: ") + io::one_line(e.what()));
        }
        if (!a->doc.is_object()) fail(name, "the glTF JSON is not an object");
        check_images(*a);
        check_written_back_types(*a);

        io::MaterialMapper mapper(name, a->model, warnings);
        a->translucent.resize(a->model.materials.size());
        for (size_t m = 0; m < a->model.materials.size(); ++m)
            if (Material jade = mapper.map(int(m)); !jade.opaque) a->translucent[m] = std::move(jade);

        const auto where = placements(*a);
        for (size_t m = 0; m < a->model.meshes.size(); ++m) add_targets(*a, int(m), where[m], warnings);
        return GltfAsset(std::move(a));
    });
}

}  // namespace jade
