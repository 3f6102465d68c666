// io/gltf_model.cpp - tinygltf set-up: restricted file access, the GLB container check, and
// the required-extension check.
#include "io/gltf_model.hpp"

#include "io/common.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <optional>
#include <string_view>

namespace jade::io {

namespace {

/// tinygltf's file access, limited to the glTF's own folder and below (tinygltf would also
/// search the current directory); URIs are never shell-expanded. tinygltf asks for
/// `basedir + "/" + uri` (uri percent-decoded), so the URI is recovered from the path and judged
/// lexically: absolute paths, URIs with a scheme (`file:`, `C:`) and relative paths whose `..`
/// climb above the folder are refused and remembered, so that the load fails naming them instead
/// of with tinygltf's "File not found". Then the real path of the target is judged (symbolic
/// links resolved, in the folder's path too): a link inside the folder that leads out of it would
/// otherwise put any file the user can read into a baked asset that is then shared.
struct FsContext {
    std::filesystem::path folder;                         ///< absolute, lexically normal, no trailing separator
    std::filesystem::path real_folder;                    ///< `folder` with its links resolved
    std::string prefix;                                   ///< folder + "/": what tinygltf puts before every URI
    bool allow_outside_links = false;                     ///< ReadOptions::allow_outside_links
    std::string refused_uri;                              ///< the first URI refused, percent-decoded
    std::string refused_why;                              ///< why, e.g. "is an absolute path (...)"
    std::vector<std::filesystem::path>* files = nullptr;  ///< receives what was read (real paths)
};

bool inside(const std::filesystem::path& folder, const std::filesystem::path& target)
{
    return std::mismatch(folder.begin(), folder.end(), target.begin(), target.end()).first == folder.end();
}

/// Why the file at `uri` (relative to the glTF's folder) may not be read; empty if it may.
std::string outside_reason(const FsContext& ctx, const std::string& uri)
{
    static const std::string kOnlyBelow = " (only files in the glTF file's folder or below it are read)";
    if (uri.empty()) return {};  // names the folder itself: not a file, tinygltf says "File not found"
    if (uri.front() == '/' || uri.front() == '\\') return "is an absolute path" + kOnlyBelow;
    const auto colon = uri.find(':');
    if (colon != std::string::npos && uri.find_first_of("/\\") > colon)
        return "is not a relative file path (it has a scheme or drive '" + printable(uri.substr(0, colon + 1), 16) +
               "')" + kOnlyBelow;
    if (!inside(ctx.folder, (ctx.folder / uri).lexically_normal()))
        return "points outside the glTF file's folder" + kOnlyBelow;
    if (ctx.allow_outside_links) return {};
    std::error_code ec;
    const auto real = std::filesystem::weakly_canonical(ctx.folder / uri, ec);
    if (ec) return {};  // nothing there to read: tinygltf reports the missing file
    if (!inside(ctx.real_folder, real))
        return "resolves to '" + printable(real.string(), 512) +
               "', outside the glTF file's folder (a symbolic link out of the folder is followed only when allowed: "
               "jade --allow-outside-links, ReadOptions::allow_outside_links)";
    return {};
}

/// The URI in a path tinygltf built, or nullopt for its other candidates (the current directory).
std::optional<std::string> uri_of(const FsContext& ctx, const std::string& path)
{
    if (!path.starts_with(ctx.prefix)) return std::nullopt;
    return path.substr(ctx.prefix.size());
}

bool fs_exists(const std::string& path, void* user)
{
    auto& ctx = *static_cast<FsContext*>(user);
    const auto uri = uri_of(ctx, path);
    if (!uri) return false;
    if (auto why = outside_reason(ctx, *uri); !why.empty()) {
        if (ctx.refused_uri.empty()) ctx.refused_uri = *uri, ctx.refused_why = std::move(why);
        return false;
    }
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}

std::string fs_expand(const std::string& path, void*) { return path; }

bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user)
{
    const auto& ctx = *static_cast<const FsContext*>(user);
    const auto uri = uri_of(ctx, path);
    if (!uri || !outside_reason(ctx, *uri).empty()) {  // tinygltf reads only what fs_exists accepted
        if (err) *err += "refused to read a file outside the glTF file's folder";
        return false;
    }
    try {
        // The real path that was judged is what is read, so a link changed in between is not followed.
        std::error_code ec;
        auto real = std::filesystem::canonical(path, ec);
        if (ec) real = path;
        const auto bytes = read_file(real);
        out->assign(bytes.begin(), bytes.end());
        if (ctx.files) ctx.files->push_back(real);
        return true;
    } catch (const std::exception& e) {
        if (err) *err += e.what();
        return false;
    }
}

/// `%XX` escapes decoded (as tinygltf does before it looks a URI up), to match image URIs.
std::string percent_decoded(const std::string& uri)
{
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) &&
            std::isxdigit(uint8_t(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

/// Fails naming the buffer or image whose URI was refused. Buffers are parsed (and their files
/// read) in order and the first failure stops the parse, so a refused URI that is no image's
/// belongs to the buffer after the last one parsed.
void fail_refused_uri(const std::string& name, const FsContext& ctx, const tinygltf::Model& model)
{
    std::string element = "buffer " + std::to_string(model.buffers.size());
    for (size_t i = 0; i < model.images.size(); ++i)
        if (percent_decoded(model.images[i].uri) == ctx.refused_uri) element = "image " + std::to_string(i);
    fail(name, element + ": URI '" + printable(ctx.refused_uri, 64) + "' " + ctx.refused_why);
}

bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*)
{
    if (err) *err += "writing is not supported";
    return false;
}

/// Images are not geometry: they are never decoded; their bytes are kept when asked for.
bool keep_image(tinygltf::Image*, const int index, std::string*, std::string*, int, int, const unsigned char* bytes,
                int size, void* user)
{
    if (auto* images = static_cast<std::vector<std::vector<unsigned char>>*>(user); images && index >= 0 && size >= 0) {
        if (images->size() <= size_t(index)) images->resize(size_t(index) + 1);
        (*images)[size_t(index)].assign(bytes, bytes + size);
    }
    return true;
}

uint32_t read_u32(const std::string& bytes, size_t offset)
{
    uint32_t v;
    std::memcpy(&v, bytes.data() + offset, 4);
    return v;
}

/// Checks the GLB container and returns the length to parse (the header's total length).
uint32_t check_glb(const std::string& name, const std::string& bytes)
{
    if (bytes.size() < 20) fail(name, "too short for a binary glTF (" + std::to_string(bytes.size()) + " bytes)");
    if (bytes.compare(0, 4, "glTF") != 0) fail(name, "not a binary glTF file (no 'glTF' magic)");
    if (read_u32(bytes, 4) != 2)
        fail(name, "GLB version " + std::to_string(read_u32(bytes, 4)) + " is not supported (only 2)");
    const uint32_t length = read_u32(bytes, 8);
    if (length > bytes.size())
        fail(name, "GLB header declares " + std::to_string(length) + " bytes but the file has " +
                       std::to_string(bytes.size()) + " (truncated?)");
    uint64_t offset = 12;
    for (int chunk = 0; offset < length; ++chunk) {
        if (length - offset < 8) fail(name, "byte " + std::to_string(offset) + ": truncated GLB chunk header");
        const uint64_t chunk_length = read_u32(bytes, size_t(offset));
        const uint32_t type = read_u32(bytes, size_t(offset) + 4);
        if (chunk == 0 && type != 0x4E4F534Au) fail(name, "the first GLB chunk is not JSON");
        if (chunk_length > length - offset - 8)
            fail(name, "byte " + std::to_string(offset) + ": GLB chunk " + std::to_string(chunk) + " of " +
                           std::to_string(chunk_length) + " bytes runs past the end of the file");
        offset += 8 + chunk_length;
    }
    if (offset == 12) fail(name, "GLB has no JSON chunk");
    return length;
}

/// tinygltf converts `extras` recursively and overflows the stack on deeply nested JSON (a
/// crash at a few ten thousand levels), so nesting is limited before it parses anything.
/// glTF itself nests less than ten levels; the limit leaves room for structured extras.
void check_json_depth(const std::string& name, std::string_view json)
{
    constexpr int kMaxDepth = 128;
    int depth = 0;
    bool in_string = false, escaped = false;
    for (size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxDepth)
                fail(name, "JSON nested more than " + std::to_string(kMaxDepth) + " levels deep (at byte " +
                               std::to_string(i) + ")");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

/// Extensions that change only materials or textures, which the bake does not read.
bool geometry_neutral(const std::string& ext)
{
    return ext.starts_with("KHR_materials_") || ext == "KHR_texture_transform" || ext == "KHR_texture_basisu" ||
           ext == "EXT_texture_webp";
}

}  // namespace

tinygltf::Model parse_gltf(const std::filesystem::path& path, const std::string& name, const std::string& bytes,
                           bool binary, const ReadOptions& options, std::vector<std::vector<unsigned char>>* images,
                           std::vector<std::filesystem::path>* files)
{
    tinygltf::TinyGLTF loader;
    FsContext ctx;
    std::error_code ec;
    ctx.folder = std::filesystem::absolute(path, ec).parent_path().lexically_normal();
    if (ctx.folder.has_relative_path() && ctx.folder.filename().empty()) ctx.folder = ctx.folder.parent_path();
    const std::string folder = ctx.folder.string();
    ctx.prefix = folder.ends_with('/') ? folder : folder + "/";
    ctx.real_folder = std::filesystem::weakly_canonical(ctx.folder, ec);
    if (ec) ctx.real_folder = ctx.folder;
    ctx.allow_outside_links = options.allow_outside_links;
    ctx.files = files;
    loader.SetFsCallbacks({&fs_exists, &fs_expand, &fs_read, &fs_write, &ctx});
    loader.SetImageLoader(&keep_image, images);

    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        if (binary) {
            const uint32_t length = check_glb(name, bytes);
            check_json_depth(name, std::string_view(bytes).substr(20, read_u32(bytes, 12)));
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                             length, folder);
        } else {
            check_json_depth(name, bytes);
            ok = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()),
                                            folder);
        }
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail(name, std::string("tinygltf: ") + e.what());
    }
    if (!ctx.refused_uri.empty()) fail_refused_uri(name, ctx, model);
    if (!ok) fail(name, "tinygltf: " + one_line(err.empty() && warn.empty() ? "parse failed" : err + warn));
    if (images) images->resize(model.images.size());
    return model;
}

void check_required_extensions(const std::string& name, const tinygltf::Model& model)
{
    for (const auto& ext : model.extensionsRequired) {
        if (geometry_neutral(ext)) continue;
        std::string why;
        if (ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression")
            why = " (compressed geometry: decompress it first, e.g. with gltf-transform)";
        fail(name, "required extension " + printable(ext, 64) + " is not supported" + why);
    }
}

}  // namespace jade::io
