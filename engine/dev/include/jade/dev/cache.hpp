// jade/dev/cache.hpp - an on-disk cache of bakes, keyed by the content of what the bake depends
// on: what `jade scene --cache`, `jade bench` and the tests bake a static scene once with (later
// runs read the cached AO and t_m and create no bake pipelines or buffers, counted by
// jade/dev/context.hpp). A host keeps its bakes in its assets (`jade bake`, jade/io.hpp) or plugs
// its own storage into a scene (StaticBakeSource, jade/scene.hpp). Declared for jade::dev,
// defined in jade::io (it reads and writes files): link both.
//
// Key: a 64-bit FNV-1a hash of the prepared mesh (positions, normals, areas, indices), the
// material's three scattering profiles (albedo, strength and the specular parameters only
// affect shading and are left out) and every BakeSettings field, plus kBakeCacheVersion.
// Entry file DIR/<16 hex digits of the key>.jbake:
//   header  "JADEBAKE", uint32 format version, uint32 method_used, uint64 key,
//           uint64 vertex count, uint64 FNV-1a checksum of the payload   (little-endian)
//   payload vertex count floats of AO, then 3 × vertex count floats of t_m (RGB interleaved)
// An entry whose magic, version, key, size or checksum does not match is stale or corrupt:
// load() reports why and bake_with_cache() bakes again and replaces it. Entries are written with
// write_file_atomically (jade/io.hpp), so readers never see a half-written entry.
//
// Threading: a BakeCache holds only its folder; concurrent processes may share a folder
// (rename is atomic; the last writer of a key wins with identical content).
#pragma once

#include <jade/bake.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>
#include <jade/scene.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace jade::dev {

/// Bump when the bake's results change for the same inputs (shaders, discretisation): old
/// entries then no longer match any key and are re-baked.
inline constexpr uint32_t kBakeCacheVersion =
    3;  // 2: the thickness follows t_m when the bake has one; 3: then the scattering normals and normal spreads

/// The cache key of a bake (see the header comment).
uint64_t bake_key(const PreparedMesh& mesh, const Material& material, const BakeSettings& settings);

class BakeCache {
public:
    /// Uses (and creates, when missing) the folder `dir`. Throws jade::Error naming the folder
    /// when it cannot be created.
    explicit BakeCache(std::filesystem::path dir);

    /// The entry for `key` if present and valid for `vertex_count` bake vertices; otherwise
    /// nullopt and, when `why` is given, the reason ("missing", "bad magic", "version 3, expected
    /// 1", "key mismatch", "truncated", "checksum mismatch", ...). Never throws for bad files.
    std::optional<BakeResult> load(uint64_t key, size_t vertex_count, std::string* why = nullptr) const;
    /// Writes the entry (temp + rename). `result.ao` and `result.tm` must have one value per
    /// bake vertex. Throws jade::Error naming the file when it cannot be written.
    void store(uint64_t key, const BakeResult& result) const;
    std::filesystem::path entry_path(uint64_t key) const;
    const std::filesystem::path& folder() const { return dir_; }

private:
    std::filesystem::path dir_;
};

/// The bake step of a static mesh: skips opaque materials, else reads the cache, else bakes
/// and stores (CachedBake and BakeSource: jade/scene.hpp). Bakes as Baker::bake (submits to
/// the Context's queue and waits).
CachedBake bake_with_cache(Context& context, const BakeCache& cache, const PreparedMesh& mesh, const Material& material,
                           const BakeSettings& settings = {});

/// Static bakes of a scene through a BakeCache (bake_with_cache; `lookup` loads and checks the
/// entry), for plan_scene and SceneRenderer (jade/scene.hpp).
StaticBakeSource cached_bakes(const BakeCache& cache);

}  // namespace jade::dev
