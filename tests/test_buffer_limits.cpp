// Device limits on buffer sizes: a buffer that cannot exist on the device is refused with a
// jade::Error naming it and the limit, before any Vulkan call (gpu::Buffer's constructor runs
// check_buffer_size first). The rule is checked with made-up limits, then against lavapipe's.
// Lists longer than one texel view are read through several (the near field's windows).
#include "../engine/src/bake/near_field.hpp"
#include "../engine/src/gpu/buffer_limits.hpp"

#include "gpu_fixture.hpp"

#include <jade/dev/context.hpp>
#include <jade/error.hpp>

#include <gtest/gtest.h>

#include <string>

namespace {

using jade::gpu::BufferLimits;
using jade::gpu::StorageBinding;

constexpr VkDeviceSize kMiB = VkDeviceSize(1) << 20;
constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
constexpr VkBufferUsageFlags kVertex = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;

/// The message of the error check_buffer_size throws, or "" when it accepts the size.
std::string refusal(const BufferLimits& l, VkDeviceSize bytes, VkBufferUsageFlags usage,
                    StorageBinding binding = StorageBinding::Whole)
{
    try {
        jade::gpu::check_buffer_size(l, bytes, usage, binding, "t_m sources");
        return "";
    } catch (const jade::Error& e) {
        return e.what();
    }
}

TEST(buffer_limits, EachLimitRefusesTheFirstByteOverIt)
{
    // lavapipe-like: 128 MiB storage range, 1 GiB per allocation, a 4 GiB heap.
    const BufferLimits l{128 * kMiB, 1024 * kMiB, 4096 * kMiB};
    EXPECT_EQ(refusal(l, 128 * kMiB, kStorage), "");
    EXPECT_EQ(refusal(l, 128 * kMiB + 1, kStorage),
              "GPU buffer 't_m sources' of 134217729 bytes (128 MiB) exceeds the device's maxStorageBufferRange of "
              "134217728 bytes (128 MiB) (the largest storage buffer a shader can bind)");
    // The storage range bounds only buffers bound whole, and only storage buffers.
    EXPECT_EQ(refusal(l, 512 * kMiB, kStorage, StorageBinding::Windows), "");
    EXPECT_EQ(refusal(l, 512 * kMiB, kVertex), "");
    EXPECT_EQ(refusal(l, 1024 * kMiB, kVertex), "");
    EXPECT_EQ(refusal(l, 1024 * kMiB + 1, kVertex),
              "GPU buffer 't_m sources' of 1073741825 bytes (1024 MiB) exceeds the device's maxMemoryAllocationSize of "
              "1073741824 bytes (1024 MiB)");
    EXPECT_NE(refusal(l, 1024 * kMiB + 1, kStorage, StorageBinding::Windows).find("maxMemoryAllocationSize"),
              std::string::npos);
    // A heap smaller than the allocation limit (an integrated GPU's carve-out): the heap decides.
    const BufferLimits small_heap{128 * kMiB, 8192 * kMiB, 256 * kMiB};
    EXPECT_EQ(refusal(small_heap, 256 * kMiB, kVertex), "");
    EXPECT_EQ(refusal(small_heap, 256 * kMiB + 1, kVertex),
              "GPU buffer 't_m sources' of 268435457 bytes (256 MiB) exceeds the largest memory heap it can use, "
              "268435456 bytes (256 MiB)");
    // maxMemoryAllocationSize 0 (not reported): only the heap bounds the size.
    EXPECT_EQ(refusal({128 * kMiB, 0, 4096 * kMiB}, 2048 * kMiB, kVertex), "");
    EXPECT_NE(refusal({128 * kMiB, 0, 4096 * kMiB}, 4096 * kMiB + 1, kVertex).find("largest memory heap"),
              std::string::npos);
    // Sizes near 2^64 do not wrap: still refused.
    EXPECT_NE(refusal(l, ~VkDeviceSize(0), kVertex).find("maxMemoryAllocationSize"), std::string::npos);
}

class buffer_limits_device : public jade::test::GpuTest {};

TEST_F(buffer_limits_device, LimitsComeFromTheDevice)
{
    // The limits read for lavapipe are the device's: the storage range is the one DeviceInfo
    // reports, the allocation and heap limits are non-zero, and host-visible memory exists.
    const auto& info = jade::dev::device_info(context());
    for (bool host_visible : {false, true}) {
        const BufferLimits l = jade::gpu::buffer_limits(context(), host_visible);
        EXPECT_EQ(l.max_storage_range, info.max_storage_buffer_range);
        EXPECT_GE(l.max_allocation, 1024 * kMiB)
            << "maxMemoryAllocationSize must be at least 2^30 in Vulkan, got " << l.max_allocation;
        EXPECT_GT(l.heap_bytes, 64 * kMiB);
        EXPECT_EQ(refusal(l, l.max_storage_range, kStorage), "");
        EXPECT_NE(refusal(l, l.max_storage_range + 1, kStorage).find("maxStorageBufferRange"), std::string::npos);
        EXPECT_NE(refusal(l, l.heap_bytes + 1, kStorage, StorageBinding::Windows), "");
    }
}

// The near lists' windows (bake::plan_near_windows): every row in exactly one window, in order;
// each window aligned, within the view size, and holding its rows' entries; the fewest windows.
TEST(NearWindows, CoverEveryRowOnceAlignedAndWithinTheViewSize)
{
    std::vector<uint32_t> offsets{0};
    for (uint32_t k = 0; k < 1000; ++k) offsets.push_back(offsets.back() + 1 + (k * 7919u) % 61u);
    const uint64_t align = 16, max_bytes = 1024;
    const auto windows = jade::bake::plan_near_windows(offsets, align, max_bytes);
    ASSERT_GT(windows.size(), 20u) << "the lists must need many windows here";
    uint32_t next_row = 0;
    for (const auto& w : windows) {
        EXPECT_EQ(w.first_row, next_row);
        EXPECT_GT(w.row_count, 0u);
        EXPECT_EQ(uint64_t(w.first_entry) * 4 % align, 0u);
        EXPECT_LE(w.first_entry, offsets[w.first_row]);
        EXPECT_GE(uint64_t(w.first_entry) * 4 + w.bytes, uint64_t(offsets[w.first_row + w.row_count]) * 4);
        EXPECT_LE(w.bytes, max_bytes);
        // The fewest windows: one more row would not have fitted.
        if (w.first_row + w.row_count < offsets.size() - 1)
            EXPECT_GT(uint64_t(offsets[w.first_row + w.row_count + 1]) * 4 - uint64_t(w.first_entry) * 4,
                      max_bytes - align);
        next_row = w.first_row + w.row_count;
    }
    EXPECT_EQ(next_row, offsets.size() - 1);
    // Lists that fit one view take one window.
    EXPECT_EQ(jade::bake::plan_near_windows(offsets, align, uint64_t(offsets.back()) * 4 + 2 * align).size(), 1u);
    // A row longer than a view is an error that names it.
    try {
        jade::bake::plan_near_windows(std::vector<uint32_t>{0, 10, 1000, 1010}, align, 256);
        ADD_FAILURE() << "expected a jade::Error";
    } catch (const jade::Error& e) {
        EXPECT_NE(std::string(e.what()).find("vertex slot 1"), std::string::npos) << e.what();
    }
}

}  // namespace
