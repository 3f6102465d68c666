// jade/dev/io.hpp - what jade::io's writers share, for the CLI's own outputs and the tests: the
// atomic file writer and its check before long work; images read back (references, golden
// images, what a render wrote); and what a GltfAsset was read from. Declared for jade::dev,
// defined in jade::io: link both.
#pragma once

#include <jade/io.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace jade::dev {

/// Writes `bytes` to `path` atomically, as every writer of jade/io.hpp does: a temporary file
/// "<path>.tmp-<pid>-<random>" in the same folder is created exclusively (never through a link
/// planted under its name), written, given the mode (and where allowed the owner) of the file it
/// replaces, synced to disk (fsync), renamed to `path` (a link at `path` is replaced, not
/// followed) and the folder synced. A failure or a crash at any moment leaves the old file (or none) or
/// the complete new one; a crash may leave the temporary file behind. Throws jade::Error
/// naming the file.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// Creates and removes the temporary file that write_file_atomically would create for `path`,
/// to learn before long work whether the write can happen (a read-only or full file system,
/// a missing permission). Throws jade::Error with the reason.
void check_writable(const std::filesystem::path& path);

/// An image read by load_image: linear RGBA floats, rows top to bottom.
struct LoadedImage {
    int width = 0, height = 0;
    std::vector<float> rgba;  ///< width*height*4, linear (8-bit files are sRGB-decoded; alpha as stored)
    bool srgb_8bit = false;   ///< the file held 8-bit sRGB values (PNG), decoded here
};

/// Reads a .png (8-bit sRGB, decoded to linear with the IEC 61966-2-1 curve) or .exr (linear)
/// through OpenImageIO; 1 to 4 channels (grey is copied to RGB, missing alpha is 1). Throws
/// jade::Error naming the file.
LoadedImage load_image(const std::filesystem::path& path);

/// The file name of the asset, for messages.
const std::string& asset_name(const GltfAsset& asset);
/// Every file the asset was read from: the asset itself, then its external buffers and images
/// (as resolved, symbolic links followed), so that a writer can refuse to replace one.
const std::vector<std::filesystem::path>& asset_files(const GltfAsset& asset);
/// The `asset.extras` JSON object of the file (empty when it has none), where `jade bake` keeps
/// what it baked with.
std::string asset_extras_json(const GltfAsset& asset);

}  // namespace jade::dev
