// The bake cache: a second run of a static mesh reads the cache and creates
// no bake pipelines or buffers (counted by the Context); stale and corrupt entries are detected
// and re-baked; opaque materials bake nothing.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include <jade/dev/cache.hpp>
#include <jade/dev/context.hpp>
#include <jade/context.hpp>

#include <jade/error.hpp>

#include <fstream>
#include <iterator>
#include <cstring>
#include <cmath>

using namespace jade;

namespace {

class BakeCacheTest : public test::GpuTest {
protected:
    // Made when the test's fixture is (the test's name is known then), emptied of earlier runs.
    const std::filesystem::path dir = test::test_folder("bake_cache");
    const PreparedMesh sphere = prepare_mesh(procedural::sphere(1.0f, 10, 14));
    const Material material = burley_material({0.3, 0.2, 0.1}, glm::vec3(0.8f));
    const BakeSettings settings = BakeSettings::preset(Quality::Draft);
};

size_t files_in(const std::filesystem::path& dir)
{
    size_t n = 0;
    for (auto& e : std::filesystem::directory_iterator(dir)) n += e.is_regular_file();
    return n;
}

}  // namespace

TEST_F(BakeCacheTest, SecondRunReadsTheCacheAndCreatesNoBakeObjects)
{
    dev::BakeCache cache(dir);
    const CachedBake first = dev::bake_with_cache(context(), cache, sphere, material, settings);
    EXPECT_EQ(first.source, BakeSource::Baked);
    EXPECT_EQ(first.note, "missing");
    ASSERT_EQ(first.result.tm.size(), sphere.vertex_count());
    EXPECT_TRUE(std::filesystem::exists(cache.entry_path(dev::bake_key(sphere, material, settings))));
    EXPECT_EQ(files_in(dir), 1u);  // no temporary file left behind

    const ObjectCounts before = dev::created_objects(context());
    // A new BakeCache on the same folder: what a restarted process sees.
    const CachedBake second = dev::bake_with_cache(context(), dev::BakeCache(dir), sphere, material, settings);
    const ObjectCounts after = dev::created_objects(context());
    EXPECT_EQ(second.source, BakeSource::Cache);
    EXPECT_EQ(after.compute_pipelines, before.compute_pipelines);
    EXPECT_EQ(after.buffers, before.buffers);
    EXPECT_EQ(after.images, before.images);
    ASSERT_EQ(second.result.tm.size(), first.result.tm.size());
    for (size_t i = 0; i < first.result.tm.size(); ++i) {
        ASSERT_EQ(second.result.tm[i], first.result.tm[i]) << i;
        ASSERT_EQ(second.result.ao[i], first.result.ao[i]) << i;
    }
    EXPECT_EQ(second.result.method_used, first.result.method_used);

    // The counters do count: a miss creates pipelines and buffers.
    BakeSettings other = settings;
    other.ao.seed = 7;
    const CachedBake third = dev::bake_with_cache(context(), cache, sphere, material, other);
    EXPECT_EQ(third.source, BakeSource::Baked);
    EXPECT_GT(dev::created_objects(context()).compute_pipelines, after.compute_pipelines);
    EXPECT_GT(dev::created_objects(context()).buffers, after.buffers);
}

TEST_F(BakeCacheTest, KeyCoversMeshProfilesAndSettingsButNotShadingParameters)
{
    const uint64_t key = dev::bake_key(sphere, material, settings);
    EXPECT_EQ(key, dev::bake_key(sphere, material, settings));
    Material shading_only = material;
    shading_only.albedo = glm::vec3(0.1f);
    shading_only.strength = 3.0f;
    shading_only.roughness = 0.9f;
    EXPECT_EQ(dev::bake_key(sphere, shading_only, settings), key);
    Material other_profile = material;
    other_profile.profile[1] = ChannelProfile::burley(0.21);
    EXPECT_NE(dev::bake_key(sphere, other_profile, settings), key);
    BakeSettings more_rays = settings;
    more_rays.ao.rays += 1;
    EXPECT_NE(dev::bake_key(sphere, material, more_rays), key);
    BakeSettings eps = settings;
    eps.tm_opening_ratio *= 0.5f;
    EXPECT_NE(dev::bake_key(sphere, material, eps), key);
    PreparedMesh moved = sphere;
    moved.positions[5].x += 1e-6f;
    EXPECT_NE(dev::bake_key(moved, material, settings), key);
}

TEST_F(BakeCacheTest, CorruptOrStaleEntriesAreDetectedAndRebaked)
{
    dev::BakeCache cache(dir);
    const uint64_t key = dev::bake_key(sphere, material, settings);
    const CachedBake good = dev::bake_with_cache(context(), cache, sphere, material, settings);
    const auto path = cache.entry_path(key);
    const auto size = std::filesystem::file_size(path);
    EXPECT_EQ(size, 40 + sphere.vertex_count() * (16 + 24))
        << "header, AO and t_m, scattering normal and normal spread";

    auto patch = [&](std::streamoff offset, char byte) {
        std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
        f.seekp(offset);
        f.put(byte);
    };
    std::string why;
    // One flipped payload byte: checksum.
    patch(40 + 123, 0x5a);
    EXPECT_FALSE(cache.load(key, sphere.vertex_count(), &why));
    EXPECT_EQ(why, "checksum mismatch");
    const CachedBake rebaked = dev::bake_with_cache(context(), cache, sphere, material, settings);
    EXPECT_EQ(rebaked.source, BakeSource::Baked);
    EXPECT_EQ(rebaked.note, "checksum mismatch");
    ASSERT_TRUE(cache.load(key, sphere.vertex_count(), &why)) << why;  // replaced by a valid entry
    EXPECT_EQ(cache.load(key, sphere.vertex_count())->tm, good.result.tm);

    // Another format version (byte 8: the version's low byte).
    patch(8, char(dev::kBakeCacheVersion + 1));
    EXPECT_FALSE(cache.load(key, sphere.vertex_count(), &why));
    EXPECT_EQ(why, "version " + std::to_string(dev::kBakeCacheVersion + 1) + ", expected " +
                       std::to_string(dev::kBakeCacheVersion));
    EXPECT_EQ(dev::bake_with_cache(context(), cache, sphere, material, settings).source, BakeSource::Baked);

    // Truncated (a crash of a writer that did not use temp + rename), and a wrong vertex count.
    std::filesystem::resize_file(path, size - 8);
    EXPECT_FALSE(cache.load(key, sphere.vertex_count(), &why));
    EXPECT_EQ(why, "truncated");
    EXPECT_EQ(dev::bake_with_cache(context(), cache, sphere, material, settings).source, BakeSource::Baked);
    EXPECT_FALSE(cache.load(key, sphere.vertex_count() + 1, &why));
    EXPECT_NE(why.find("vertex count"), std::string::npos) << why;
    // Garbage in place of the entry.
    std::ofstream(path, std::ios::binary | std::ios::trunc) << "not a bake";
    EXPECT_FALSE(cache.load(key, sphere.vertex_count(), &why));
    EXPECT_EQ(dev::bake_with_cache(context(), cache, sphere, material, settings).source, BakeSource::Baked);
    EXPECT_TRUE(cache.load(key, sphere.vertex_count()));
    EXPECT_EQ(files_in(dir), 1u);
}

TEST_F(BakeCacheTest, AnEntryWithNonFiniteValuesUnderAValidChecksumIsStaleAndRebaked)
{
    dev::BakeCache cache(dir);
    const uint64_t key = dev::bake_key(sphere, material, settings);
    dev::bake_with_cache(context(), cache, sphere, material, settings);
    const auto path = cache.entry_path(key);
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    // A NaN t_m for vertex 3 (the payload: AO, then t_m), and Inf AO for vertex 1, and the
    // checksum (64-bit FNV-1a of the payload, at byte 32) made to match.
    const float nan = std::nanf(""), inf = INFINITY;
    std::memcpy(&bytes[40 + sphere.vertex_count() * 4 + 3 * 12 + 4], &nan, 4);
    std::memcpy(&bytes[40 + 1 * 4], &inf, 4);
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 40; i < bytes.size(); ++i) h = (h ^ uint8_t(bytes[i])) * 0x100000001b3ull;
    std::memcpy(&bytes[32], &h, 8);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;

    std::string why;
    EXPECT_FALSE(cache.load(key, sphere.vertex_count(), &why));
    EXPECT_EQ(why, "stale: values of vertex 1 are not finite");
    const CachedBake rebaked = dev::bake_with_cache(context(), cache, sphere, material, settings);
    EXPECT_EQ(rebaked.source, BakeSource::Baked);
    EXPECT_EQ(rebaked.note, why);
    ASSERT_TRUE(cache.load(key, sphere.vertex_count(), &why)) << why;  // replaced by a sound entry

    // Storing one is refused: the cache never holds what it would call stale.
    BakeResult bad = rebaked.result;
    bad.tm[0].x = nan;
    EXPECT_THROW(cache.store(key, bad), Error);
    EXPECT_TRUE(cache.load(key, sphere.vertex_count()));
}

TEST_F(BakeCacheTest, OpaqueMaterialBakesNothing)
{
    dev::BakeCache cache(dir);
    Material opaque = material;
    opaque.opaque = true;
    const ObjectCounts before = dev::created_objects(context());
    const CachedBake r = dev::bake_with_cache(context(), cache, sphere, opaque, settings);
    const ObjectCounts after = dev::created_objects(context());
    EXPECT_EQ(r.source, BakeSource::Opaque);
    EXPECT_TRUE(r.result.tm.empty());
    EXPECT_EQ(after.buffers, before.buffers);  // no t_m (or any) buffer
    EXPECT_EQ(after.compute_pipelines, before.compute_pipelines);
    EXPECT_EQ(files_in(dir), 0u);
}

TEST_F(BakeCacheTest, UnwritableFolderIsAnErrorNamingIt)
{
    const auto file = test::out("bake_cache/plain_file");
    std::ofstream(file) << "x";
    try {
        dev::BakeCache cache(file / "sub");
        FAIL() << "expected jade::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("plain_file"), std::string::npos) << e.what();
    }
}
