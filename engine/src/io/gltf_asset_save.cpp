// io/gltf_asset_save.cpp - save_baked_asset: the asset as read, plus the baked attributes.
//
// The output starts from the input's JSON (every property kept, key order included) and changes
// only what the round trip needs (jade/io.hpp, docs/gltf.md):
// - buffers: one buffer holding every bufferView's bytes, each view 4-byte aligned (glTF requires
//   accessor offsets to be multiples of their component size, which a view's own offset already
//   is, so moving views to multiples of 4 keeps every accessor aligned; byteStride is kept);
// - external images embedded (a bufferView in .glb, a data URI in .gltf);
// - per baked primitive a new tightly packed float accessor per attribute. An earlier `_AO`,
//   `_TM` or `_THICKNESS` accessor whose bufferView nothing else uses is overwritten in place, so
//   that baking a baked file again does not grow it;
// - required bounds the input lacks, the materials' extensions (io/gltf_asset_materials.hpp), and
//   the caller's keys in asset.extras.
#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include "io/common.hpp"
#include "io/gltf_accessors.hpp"
#include "io/gltf_asset.hpp"
#include "io/gltf_asset_materials.hpp"
#include "io/gltf_container.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>

namespace jade {

namespace {

using json = nlohmann::ordered_json;
using io::fail;

constexpr int kFloat = 5126;
constexpr int kArrayBuffer = 34962;
constexpr const char* kAttributes[] = {"_AO", "_TM", "_THICKNESS", "_SCATTERING_NORMAL", "_NORMAL_SPREAD"};

/// The attribute `name`'s values in `b` (floats; `size` elements, 0 when not given).
const void* attribute_data(const BakedAttributes& b, const std::string& name, size_t& size)
{
    if (name == "_AO") return size = b.ao.size(), b.ao.data();
    if (name == "_TM") return size = b.tm.size(), b.tm.data();
    if (name == "_THICKNESS") return size = b.thickness.size(), b.thickness.data();
    if (name == "_SCATTERING_NORMAL") return size = b.scattering_normal.size(), b.scattering_normal.data();
    return size = b.normal_spread.size(), b.normal_spread.data();
}

int as_index(const json& j) { return j.is_number_integer() ? j.get<int>() : -1; }

/// j[key], or null (which iterates as empty) when j is no object or lacks it.
const json& member(const json& j, const char* key)
{
    static const json none;
    if (!j.is_object()) return none;
    const auto it = j.find(key);
    return it == j.end() ? none : *it;
}

/// How often each bufferView is named anywhere in the document (extensions included), and each
/// accessor by the core schema: what may be overwritten without breaking another reference.
struct References {
    std::vector<int> views, accessors;

    explicit References(const json& doc)
    {
        views.assign(member(doc, "bufferViews").size(), 0);
        accessors.assign(member(doc, "accessors").size(), 0);
        count_views(doc);
        auto accessor = [&](const json& j) {
            if (const int i = as_index(j); i >= 0 && size_t(i) < accessors.size()) ++accessors[size_t(i)];
        };
        for (const auto& mesh : member(doc, "meshes"))
            for (const auto& prim : member(mesh, "primitives")) {
                for (const auto& [key, value] : member(prim, "attributes").items()) accessor(value);
                accessor(member(prim, "indices"));
                for (const auto& target : member(prim, "targets"))
                    for (const auto& [key, value] : target.items()) accessor(value);
            }
        for (const auto& skin : member(doc, "skins")) accessor(member(skin, "inverseBindMatrices"));
        for (const auto& animation : member(doc, "animations"))
            for (const auto& sampler : member(animation, "samplers"))
                for (const char* key : {"input", "output"}) accessor(member(sampler, key));
    }

private:
    void count_views(const json& j)
    {
        if (j.is_object()) {
            for (const auto& [key, value] : j.items()) {
                if (key == "bufferView" && value.is_number_integer()) {
                    if (const int i = value.get<int>(); i >= 0 && size_t(i) < views.size()) ++views[size_t(i)];
                } else {
                    count_views(value);
                }
            }
        } else if (j.is_array()) {
            for (const auto& v : j) count_views(v);
        }
    }
};

std::string mime_type(const std::vector<unsigned char>& b)
{
    auto starts = [&](std::initializer_list<int> magic, size_t at = 0) {
        if (b.size() < at + magic.size()) return false;
        size_t i = at;
        for (int c : magic)
            if (b[i++] != c) return false;
        return true;
    };
    if (starts({0x89, 'P', 'N', 'G'})) return "image/png";
    if (starts({0xFF, 0xD8, 0xFF})) return "image/jpeg";
    if (starts({'R', 'I', 'F', 'F'}) && starts({'W', 'E', 'B', 'P'}, 8)) return "image/webp";
    if (starts({0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB})) return "image/ktx2";
    return {};
}

class Writer {
public:
    Writer(const GltfAssetImpl& a, std::string out_name, bool glb)
        : a_(a), out_(std::move(out_name)), glb_(glb), doc_(a.doc), refs_(a.doc), reader_(a.name, a.model)
    {
    }

    std::string write(const std::vector<BakedAttributes>& baked, const std::string& extras)
    {
        plan_reuse(baked);
        pack_views();
        for (size_t t = 0; t < baked.size(); ++t) add_attributes(t, baked[t]);
        add_bounds();
        embed_images();
        io::MaterialEdits edits{a_, doc_, baked,
                                [this](const std::vector<unsigned char>& bytes, const std::string& mime,
                                       int replacing) { return embedded(bytes, mime, replacing); }};
        io::mark_translucent(edits);
        io::add_translucency_extensions(edits);
        io::add_thickness_maps(edits);
        restore_maps();
        merge_extras(extras);
        return finish();
    }

private:
    json& prim(size_t t, size_t p) { return doc_["meshes"][size_t(a_.targets[t].mesh_index)]["primitives"][p]; }

    /// The earlier baked attributes that may be overwritten in place (see References).
    void plan_reuse(const std::vector<BakedAttributes>& baked)
    {
        recycled_.assign(refs_.views.size(), false);
        for (size_t t = 0; t < baked.size(); ++t)
            for (size_t p = 0; p < a_.spans[t].size(); ++p) {
                if (!a_.spans[t][p].baked || baked[t].ao.empty()) continue;
                const json& attributes = prim(t, p)["attributes"];
                for (const char* name : kAttributes) {
                    size_t size = 0;
                    attribute_data(baked[t], name, size);
                    if (!attributes.contains(name) || size == 0) continue;
                    const int acc = as_index(attributes[name]);
                    if (acc < 0 || size_t(acc) >= refs_.accessors.size() || refs_.accessors[size_t(acc)] != 1) continue;
                    const json& accessor = doc_["accessors"][size_t(acc)];
                    const int view = as_index(member(accessor, "bufferView"));
                    if (accessor.contains("sparse") || view < 0 || size_t(view) >= refs_.views.size() ||
                        refs_.views[size_t(view)] != 1)
                        continue;
                    recycled_[size_t(view)] = true;
                    reuse_[{t, p, std::string(name)}] = {acc, view};
                }
            }
        // An earlier bake's thickness maps: their views are refilled by the new maps (or, where
        // none is made, with their own bytes by restore_maps), so that re-baking does not grow the file.
        const json& images = member(doc_, "images");
        for (size_t i = 0; i < images.size(); ++i) {
            const json& name = member(images[i], "name");
            const int view = as_index(member(images[i], "bufferView"));
            if (name.is_string() && name.get<std::string>().rfind(io::kThicknessMapName, 0) == 0 && view >= 0 &&
                size_t(view) < refs_.views.size() && refs_.views[size_t(view)] == 1)
                recycled_[size_t(view)] = true, map_views_[int(i)] = view;
        }
    }

    /// The views of earlier thickness maps that no new map took: their own bytes again.
    void restore_maps()
    {
        for (const auto& [image, view] : map_views_) {
            const auto& bv = a_.model.bufferViews[size_t(view)];
            const auto& data = a_.model.buffers[size_t(bv.buffer)].data;
            if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
                fail(a_.name, "bufferView " + std::to_string(view) + " runs past the end of its buffer");
            json& v = doc_["bufferViews"][size_t(view)];
            v["buffer"] = 0;
            v["byteOffset"] = append(data.data() + bv.byteOffset, bv.byteLength);
        }
        map_views_.clear();
    }

    size_t append(const void* data, size_t size)
    {
        bin_.resize((bin_.size() + 3) / 4 * 4, 0);
        const size_t offset = bin_.size();
        bin_.resize(offset + size);
        if (size) std::memcpy(bin_.data() + offset, data, size);
        return offset;
    }

    void pack_views()
    {
        for (size_t v = 0; v < refs_.views.size(); ++v) {
            json& view = doc_["bufferViews"][v];
            if (recycled_[v]) continue;  // filled by add_attributes
            const auto& bv = a_.model.bufferViews[v];
            const std::string subject = "bufferView " + std::to_string(v);
            if (bv.buffer < 0 || size_t(bv.buffer) >= a_.model.buffers.size())
                fail(a_.name, subject + ": buffer " + std::to_string(bv.buffer) + " does not exist");
            const auto& data = a_.model.buffers[size_t(bv.buffer)].data;
            if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
                fail(a_.name, subject + " runs past the end of buffer " + std::to_string(bv.buffer));
            view["buffer"] = 0;
            view["byteOffset"] = append(data.data() + bv.byteOffset, bv.byteLength);
        }
    }

    /// A view of `floats` and a FLOAT accessor on it, reusing indices (acc, view) when given.
    int add_floats(const std::vector<float>& floats, size_t count, const char* type, std::pair<int, int> reuse)
    {
        json view = {{"buffer", 0},
                     {"byteOffset", append(floats.data(), floats.size() * sizeof(float))},
                     {"byteLength", floats.size() * sizeof(float)},
                     {"target", kArrayBuffer}};
        int v = reuse.second;
        if (v >= 0)
            doc_["bufferViews"][size_t(v)] = std::move(view);
        else
            doc_["bufferViews"].push_back(std::move(view)), v = int(doc_["bufferViews"].size() - 1);
        json accessor = {{"bufferView", v}, {"componentType", kFloat}, {"count", count}, {"type", type}};
        if (reuse.first >= 0) {
            doc_["accessors"][size_t(reuse.first)] = std::move(accessor);
            return reuse.first;
        }
        doc_["accessors"].push_back(std::move(accessor));
        return int(doc_["accessors"].size() - 1);
    }

    void add_attributes(size_t t, const BakedAttributes& b)
    {
        if (b.ao.empty()) return;
        if (!doc_.contains("bufferViews")) doc_["bufferViews"] = json::array();
        if (!doc_.contains("accessors")) doc_["accessors"] = json::array();
        for (size_t p = 0; p < a_.spans[t].size(); ++p) {
            const auto& span = a_.spans[t][p];
            if (!span.baked) continue;
            json& attributes = prim(t, p)["attributes"];
            auto reuse = [&](const char* name) {
                auto it = reuse_.find({t, p, std::string(name)});
                return it == reuse_.end() ? std::pair<int, int>{-1, -1} : it->second;
            };
            for (const std::string name : kAttributes) {
                size_t size = 0;
                const auto* data = static_cast<const float*>(attribute_data(b, name, size));
                if (size == 0) {
                    attributes.erase(name);  // an earlier bake's would no longer match
                    continue;
                }
                const size_t width = name == "_AO" || name == "_THICKNESS" ? 1 : 3;
                const std::vector<float> values(data + width * span.first, data + width * (span.first + span.count));
                attributes[name] = add_floats(values, span.count, width == 1 ? "SCALAR" : "VEC3", reuse(name.c_str()));
            }
        }
    }

    /// min/max of accessor `index` (FLOAT, `type`), computed from its data when it has none.
    void bound(int index, int type, const char* role)
    {
        if (index < 0 || size_t(index) >= a_.model.accessors.size()) return;
        json& accessor = doc_["accessors"][size_t(index)];
        if ((accessor.contains("min") && accessor.contains("max")) ||
            a_.model.accessors[size_t(index)].componentType != kFloat)
            return;
        const auto view = reader_.view("", index, {role, type, {kFloat}});
        const size_t width = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
        std::vector<double> lo(width, std::numeric_limits<double>::infinity()),
            hi(width, -std::numeric_limits<double>::infinity());
        std::vector<float> element(width);
        for (size_t i = 0; i < view.count; ++i) {
            view.bytes(i, element.data(), width * sizeof(float));
            for (size_t c = 0; c < width; ++c) {
                if (!std::isfinite(element[c]))
                    fail(a_.name, "accessor " + std::to_string(index) + " (" + role + "): element " +
                                      std::to_string(i) + " is not finite");
                lo[c] = std::min(lo[c], double(element[c])), hi[c] = std::max(hi[c], double(element[c]));
            }
        }
        if (view.count == 0) return;
        accessor["min"] = lo;
        accessor["max"] = hi;
    }

    void add_bounds()
    {
        for (const auto& mesh : a_.model.meshes)
            for (const auto& prim : mesh.primitives) {
                if (auto it = prim.attributes.find("POSITION"); it != prim.attributes.end())
                    bound(it->second, TINYGLTF_TYPE_VEC3, "POSITION");
                for (const auto& target : prim.targets)
                    if (auto it = target.find("POSITION"); it != target.end())
                        bound(it->second, TINYGLTF_TYPE_VEC3, "POSITION");
            }
        for (const auto& animation : a_.model.animations)
            for (const auto& sampler : animation.samplers) bound(sampler.input, TINYGLTF_TYPE_SCALAR, "sampler input");
    }

    void embed_images()
    {
        for (size_t i = 0; i < a_.model.images.size(); ++i) {
            json& image = doc_["images"][i];
            if (!image.contains("uri") || image["uri"].get<std::string>().rfind("data:", 0) == 0) continue;
            const auto& bytes = a_.image_bytes[i];
            std::string mime = image.value("mimeType", mime_type(bytes));
            if (mime.empty())
                fail(a_.name, "image " + std::to_string(i) + ": '" +
                                  io::printable(image["uri"].get<std::string>(), 64) +
                                  "' is not PNG, JPEG, WebP or KTX2 and has no mimeType; it cannot be embedded");
            // Before `image` is written again: embedding may add the document's bufferViews, which
            // moves its members; named, since items() does not keep a temporary alive.
            const json members = embedded(bytes, mime);
            json& embedded_image = doc_["images"][i];
            embedded_image.erase("uri");
            for (const auto& [key, value] : members.items()) embedded_image[key] = value;
        }
    }

    /// An image object holding `bytes`: a bufferView in .glb, a data URI in .gltf.
    /// `replacing`: the image whose view an earlier thickness map had (plan_reuse), or -1.
    json embedded(const std::vector<unsigned char>& bytes, const std::string& mime, int replacing = -1)
    {
        if (!glb_) return {{"uri", "data:" + mime + ";base64," + io::base64(bytes)}};
        json view = {{"buffer", 0}, {"byteOffset", append(bytes.data(), bytes.size())}, {"byteLength", bytes.size()}};
        if (const auto it = map_views_.find(replacing); it != map_views_.end()) {
            const int index = it->second;
            map_views_.erase(it);
            doc_["bufferViews"][size_t(index)] = std::move(view);
            return {{"bufferView", index}, {"mimeType", mime}};
        }
        doc_["bufferViews"].push_back(std::move(view));
        return {{"bufferView", doc_["bufferViews"].size() - 1}, {"mimeType", mime}};
    }

    void merge_extras(const std::string& text)
    {
        if (text.empty()) return;
        json add;
        try {
            add = json::parse(text);
        } catch (const json::exception& e) {
            fail(out_, std::string("asset extras_json is not valid JSON: ") + e.what());
        }
        if (!add.is_object()) fail(out_, "asset extras_json must be a JSON object");
        json& extras = doc_["asset"]["extras"];
        if (extras.is_null()) extras = json::object();
        if (!extras.is_object())
            fail(a_.name, "asset.extras is not a JSON object; the bake's record cannot be added to it");
        for (auto& [key, value] : add.items()) extras[key] = value;
    }

    std::string finish()
    {
        json buffer = json::object();
        if (const json& old = member(a_.doc, "buffers"); old.is_array() && !old.empty() && old[0].is_object())
            for (const auto& [key, value] : old[0].items())
                if (key != "uri" && key != "byteLength") buffer[key] = value;  // name, extras, extensions
        buffer["byteLength"] = bin_.size();
        if (!glb_) buffer["uri"] = "data:application/octet-stream;base64," + io::base64(bin_);
        if (bin_.empty())
            doc_.erase("buffers");
        else
            doc_["buffers"] = json::array({buffer});
        // Names come from other tools: replace invalid UTF-8 rather than fail on it.
        std::string text = doc_.dump(-1, ' ', false, json::error_handler_t::replace);
        return glb_ ? io::glb_container(out_, std::move(text), bin_) : text;
    }

    const GltfAssetImpl& a_;
    std::string out_;
    bool glb_;
    json doc_;
    References refs_;
    io::AccessorReader reader_;
    std::vector<unsigned char> bin_;
    std::vector<bool> recycled_;
    std::map<std::tuple<size_t, size_t, std::string>, std::pair<int, int>> reuse_;
    std::map<int, int> map_views_;  ///< image → bufferView of an earlier thickness map, until refilled
};

/// Sizes and finiteness of what is to be written, naming the element at fault.
void check_baked(const GltfAssetImpl& a, const std::string& out, const std::vector<BakedAttributes>& baked)
{
    if (baked.size() != a.targets.size())
        fail(out, std::to_string(baked.size()) + " baked attribute sets for " + std::to_string(a.targets.size()) +
                      " bake targets");
    for (size_t t = 0; t < baked.size(); ++t) {
        const auto& b = baked[t];
        const size_t n = a.targets[t].mesh.positions.size();
        const std::string target = a.targets[t].mesh.name.substr(a.name.size() + 2);
        if (b.ao.empty() && b.tm.empty() && b.thickness.empty()) continue;
        if (b.ao.size() != n || b.tm.size() != n || (!b.thickness.empty() && b.thickness.size() != n) ||
            (!b.scattering_normal.empty() && b.scattering_normal.size() != n) ||
            (!b.normal_spread.empty() && b.normal_spread.size() != n))
            fail(out, target + ": " + std::to_string(b.ao.size()) + " _AO, " + std::to_string(b.tm.size()) + " _TM, " +
                          std::to_string(b.thickness.size()) + " _THICKNESS, " +
                          std::to_string(b.scattering_normal.size()) + " _SCATTERING_NORMAL and " +
                          std::to_string(b.normal_spread.size()) + " _NORMAL_SPREAD values for " + std::to_string(n) +
                          " vertices");
        for (size_t p = 0; p < a.spans[t].size(); ++p) {
            const auto& span = a.spans[t][p];
            if (!span.baked) continue;
            for (size_t v = span.first; v < span.first + span.count; ++v) {
                const auto finite3 = [](glm::vec3 x) {
                    return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
                };
                const char* bad = !std::isfinite(b.ao[v])                                  ? "_AO"
                                  : !finite3(b.tm[v])                                      ? "_TM"
                                  : !b.thickness.empty() && !std::isfinite(b.thickness[v]) ? "_THICKNESS"
                                  : !b.scattering_normal.empty() && !finite3(b.scattering_normal[v])
                                      ? "_SCATTERING_NORMAL"
                                  : !b.normal_spread.empty() && !finite3(b.normal_spread[v]) ? "_NORMAL_SPREAD"
                                                                                             : nullptr;
                if (bad)
                    fail(a.name, target + " primitive " + std::to_string(p) + " vertex " +
                                     std::to_string(v - span.first) + ": " + bad +
                                     " is not finite; nothing was written to " + out);
            }
        }
    }
}

}  // namespace

void save_baked_asset(const std::filesystem::path& path, const GltfAsset& asset,
                      const std::vector<BakedAttributes>& baked, const std::string& asset_extras_json)
{
    const auto name = io::display_name(path);
    const auto ext = io::lower_extension(path);
    if (ext != ".glb" && ext != ".gltf")
        fail(name, "unsupported glTF extension '" + ext + "' (supported: .glb, .gltf)");
    const auto& a = *asset.impl_;
    const std::string bytes = io::naming_file(name, [&] {
        check_baked(a, name, baked);
        return Writer(a, name, ext == ".glb").write(baked, asset_extras_json);
    });
    dev::write_file_atomically(path, bytes);
}

}  // namespace jade
