// io/bake_cache.cpp - the on-disk bake cache of jade/dev/cache.hpp.
#include <jade/context.hpp>
#include <jade/dev/bake.hpp>
#include <jade/dev/cache.hpp>
#include <jade/error.hpp>
#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>
#include <vector>

namespace jade::dev {
namespace {

constexpr char kMagic[8] = {'J', 'A', 'D', 'E', 'B', 'A', 'K', 'E'};

// 64-bit FNV-1a: simple, stable across platforms and builds (std::hash is not).
struct Fnv {
    uint64_t h = 0xcbf29ce484222325ull;
    void bytes(const void* p, size_t n)
    {
        const auto* b = static_cast<const unsigned char*>(p);
        for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ull;
    }
    template <class T> void value(const T& v) { bytes(&v, sizeof v); }
    template <class T> void span(const std::vector<T>& v)
    {
        value(uint64_t(v.size()));
        bytes(v.data(), v.size() * sizeof(T));
    }
};

struct Header {
    char magic[8];
    uint32_t version;
    uint32_t method_used;
    uint64_t key;
    uint64_t vertex_count;
    uint64_t checksum;
};
static_assert(sizeof(Header) == 40);

uint64_t payload_checksum(const BakeResult& r)
{
    Fnv f;
    f.bytes(r.ao.data(), r.ao.size() * sizeof(float));
    f.bytes(r.tm.data(), r.tm.size() * sizeof(glm::vec3));
    f.bytes(r.thickness.data(), r.thickness.size() * sizeof(float));
    f.bytes(r.scattering_normal.data(), r.scattering_normal.size() * sizeof(glm::vec3));
    f.bytes(r.normal_spread.data(), r.normal_spread.size() * sizeof(glm::vec3));
    return f.h;
}

// Header::method_used holds the TmMethod in its low 16 bits and these flags: a thickness per
// vertex follows t_m; then a scattering normal and a normal spread per vertex.
constexpr uint32_t kHasThickness = 1u << 16;
constexpr uint32_t kHasScatteringNormal = 1u << 17;

}  // namespace

uint64_t bake_key(const PreparedMesh& mesh, const Material& material, const BakeSettings& s)
{
    Fnv f;
    f.value(kBakeCacheVersion);
    f.span(mesh.positions);
    f.span(mesh.normals);
    f.span(mesh.areas);
    f.span(mesh.indices);
    f.value(material.opaque);
    for (const ChannelProfile& p : material.profile) {
        f.value(p.kind);
        f.value(p.d);
        f.value(p.sigma_tr);
        f.value(p.z_r);
        f.value(p.z_v);
        f.value(p.dipole_total);
        f.value(p.gaussian_count);
        f.value(p.weight);
        f.value(p.variance);
    }
    f.value(s.ao.rays);
    f.value(s.ao.low_discrepancy);
    f.value(s.ao.seed);
    f.value(s.ao.max_distance_rel);
    f.value(s.ao.ray_offset_rel);
    f.value(s.method);
    f.value(s.tm_opening_ratio);
    f.value(s.tm_grid_resolution);
    f.value(dev::study_of(s).tm_float64_sums);
    // The thickness pass runs only for a material with transmission (jade/bake.hpp).
    const bool thickness = material.transmission.enabled() && s.thickness.enabled();
    f.value(thickness);
    if (thickness) {
        f.value(s.thickness.rays);
        f.value(s.thickness.cone_degrees);
        f.value(s.thickness.max_distance_rel);
        f.value(s.thickness.ray_offset_rel);
        f.value(s.thickness.seed);
    }
    return f.h;
}

BakeCache::BakeCache(std::filesystem::path dir) : dir_(std::move(dir))
{
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    if (ec || !std::filesystem::is_directory(dir_))
        throw Error(dir_.string() + ": cannot create the bake cache folder (" + ec.message() + ")");
}

std::filesystem::path BakeCache::entry_path(uint64_t key) const
{
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.jbake", static_cast<unsigned long long>(key));
    return dir_ / name;
}

namespace {

/// The first vertex with a non-finite AO, t_m, thickness or scattering-normal value; -1 if none.
long long first_non_finite(const BakeResult& r)
{
    const auto finite3 = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    for (size_t v = 0; v < r.ao.size(); ++v)
        if (!std::isfinite(r.ao[v]) || (v < r.tm.size() && !finite3(r.tm[v])) ||
            (v < r.thickness.size() && !std::isfinite(r.thickness[v])) ||
            (v < r.scattering_normal.size() && !finite3(r.scattering_normal[v])) ||
            (v < r.normal_spread.size() && !finite3(r.normal_spread[v])))
            return (long long)v;
    return -1;
}

}  // namespace

std::optional<BakeResult> BakeCache::load(uint64_t key, size_t vertex_count, std::string* why) const
{
    auto fail = [&](std::string reason) -> std::optional<BakeResult> {
        if (why) *why = std::move(reason);
        return std::nullopt;
    };
    std::ifstream in(entry_path(key), std::ios::binary);
    if (!in) return fail("missing");
    Header h{};
    if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) return fail("truncated header");
    if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0) return fail("bad magic");
    if (h.version != kBakeCacheVersion)
        return fail("version " + std::to_string(h.version) + ", expected " + std::to_string(kBakeCacheVersion));
    if (h.key != key) return fail("key mismatch");
    if (h.vertex_count != vertex_count)
        return fail("vertex count " + std::to_string(h.vertex_count) + ", expected " + std::to_string(vertex_count));
    const uint32_t method = h.method_used & ~(kHasThickness | kHasScatteringNormal);
    if (method > uint32_t(TmMethod::Grid)) return fail("bad method");
    BakeResult r;
    r.ao.resize(vertex_count);
    r.tm.resize(vertex_count);
    if (h.method_used & kHasThickness) r.thickness.resize(vertex_count);
    if (h.method_used & kHasScatteringNormal)
        r.scattering_normal.resize(vertex_count), r.normal_spread.resize(vertex_count);
    if (!in.read(reinterpret_cast<char*>(r.ao.data()), std::streamsize(vertex_count * sizeof(float))) ||
        !in.read(reinterpret_cast<char*>(r.tm.data()), std::streamsize(vertex_count * sizeof(glm::vec3))) ||
        !in.read(reinterpret_cast<char*>(r.thickness.data()), std::streamsize(r.thickness.size() * sizeof(float))) ||
        !in.read(reinterpret_cast<char*>(r.scattering_normal.data()),
                 std::streamsize(r.scattering_normal.size() * sizeof(glm::vec3))) ||
        !in.read(reinterpret_cast<char*>(r.normal_spread.data()),
                 std::streamsize(r.normal_spread.size() * sizeof(glm::vec3))))
        return fail("truncated");
    if (in.peek() != std::char_traits<char>::eof()) return fail("trailing bytes");
    if (payload_checksum(r) != h.checksum) return fail("checksum mismatch");
    // A valid checksum proves the bytes are as stored, not that the bake was sound: an entry
    // with a NaN or an Inf (written by an older version, or by hand) is stale, baked again.
    if (const long long v = first_non_finite(r); v >= 0)
        return fail("stale: values of vertex " + std::to_string(v) + " are not finite");
    r.method_used = TmMethod(method);
    if (why) why->clear();
    return r;
}

void BakeCache::store(uint64_t key, const BakeResult& r) const
{
    const std::filesystem::path path = entry_path(key);
    if (r.ao.size() != r.tm.size() || (!r.thickness.empty() && r.thickness.size() != r.ao.size()) ||
        (!r.scattering_normal.empty() &&
         (r.scattering_normal.size() != r.ao.size() || r.normal_spread.size() != r.ao.size())))
        throw Error(path.string() + ": cannot store a bake with " + std::to_string(r.ao.size()) + " AO, " +
                    std::to_string(r.tm.size()) + " t_m and " + std::to_string(r.thickness.size()) +
                    " thickness values");
    if (const long long v = first_non_finite(r); v >= 0)
        throw Error(path.string() + ": cannot store a bake whose values of vertex " + std::to_string(v) +
                    " are not finite");
    Header h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.version = kBakeCacheVersion;
    h.method_used = uint32_t(r.method_used) | (r.thickness.empty() ? 0u : kHasThickness) |
                    (r.scattering_normal.empty() ? 0u : kHasScatteringNormal);
    h.key = key;
    h.vertex_count = r.ao.size();
    h.checksum = payload_checksum(r);
    // The temporary file is unique per process, so concurrent writers never share one.
    std::string bytes(reinterpret_cast<const char*>(&h), sizeof h);
    auto append = [&](const void* data, size_t size) { bytes.append(static_cast<const char*>(data), size); };
    append(r.ao.data(), r.ao.size() * sizeof(float));
    append(r.tm.data(), r.tm.size() * sizeof(glm::vec3));
    append(r.thickness.data(), r.thickness.size() * sizeof(float));
    append(r.scattering_normal.data(), r.scattering_normal.size() * sizeof(glm::vec3));
    append(r.normal_spread.data(), r.normal_spread.size() * sizeof(glm::vec3));
    try {
        write_file_atomically(path, bytes);
    } catch (const Error& e) {
        throw Error(path.string() + ": cannot store the bake cache entry (" + e.what() + ")");
    }
}

CachedBake bake_with_cache(Context& context, const BakeCache& cache, const PreparedMesh& mesh, const Material& material,
                           const BakeSettings& settings)
{
    CachedBake out;
    if (material.opaque) {
        out.source = BakeSource::Opaque;
        return out;
    }
    const uint64_t key = bake_key(mesh, material, settings);
    if (auto hit = cache.load(key, mesh.vertex_count(), &out.note)) {
        out.result = std::move(*hit);
        out.source = BakeSource::Cache;
        return out;
    }
    // The Baker (and its pipelines) exists only for a miss.
    Baker baker(context);
    out.result = baker.bake(mesh, material, settings);
    out.source = BakeSource::Baked;
    cache.store(key, out.result);
    return out;
}

}  // namespace jade::dev
