// io/common.cpp - helpers shared by the readers and writers; see common.hpp.
#include "io/common.hpp"

#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>

#include <optional>
#include <random>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace jade::io {

std::string display_name(const std::filesystem::path& path)
{
    auto name = path.filename().string();
    return name.empty() ? path.string() : name;
}

void fail(std::string_view file, std::string_view what)
{
    std::string message(file);
    message += ": ";
    message += what;
    throw Error(message);
}

std::string read_file(const std::filesystem::path& path, uint64_t max_bytes)
{
    const auto name = display_name(path);
    std::error_code ec;
    auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) fail(name, "cannot open: file not found (" + path.string() + ")");
    if (!std::filesystem::is_regular_file(status)) fail(name, "cannot open: not a regular file");
    const uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) fail(name, "cannot read the file size: " + ec.message());
    if (size > max_bytes)
        fail(name, "file is " + std::to_string(size) + " bytes, more than the limit of " + std::to_string(max_bytes));

    std::ifstream in(path, std::ios::binary);
    if (!in) fail(name, "cannot open for reading");
    std::string bytes(size, '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    // A file that shrank between file_size and read is a read error, not a short mesh.
    if (static_cast<uint64_t>(in.gcount()) != size)
        fail(name, "read " + std::to_string(in.gcount()) + " of " + std::to_string(size) + " bytes");
    return bytes;
}

void check_count(std::string_view file, std::string_view what, uint64_t count, uint64_t min_bytes_each,
                 uint64_t bytes_left)
{
    if (min_bytes_each == 0 || count <= bytes_left / min_bytes_each) return;
    // Phrased with the count first: it is the number the user sees in the header.
    fail(file, "header declares " + std::to_string(count) + " " + std::string(what) + ", which need at least " +
                   std::to_string(min_bytes_each) + " bytes each, but only " + std::to_string(bytes_left) +
                   " bytes follow");
}

void append_fan(std::span<const uint32_t> polygon, std::vector<uint32_t>& indices)
{
    for (size_t i = 1; i + 1 < polygon.size(); ++i) {
        indices.push_back(polygon[0]);
        indices.push_back(polygon[i]);
        indices.push_back(polygon[i + 1]);
    }
}

BadNormal first_bad_normal(const TriangleMesh& mesh)
{
    for (size_t v = 0; v < mesh.normals.size(); ++v) {
        const glm::vec3 n = mesh.normals[v];
        if (!(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z))) return {(long long)v, "not finite"};
        if (n == glm::vec3(0.0f)) return {(long long)v, "zero"};
    }
    return {};
}

void repair_normals(TriangleMesh& mesh, std::vector<std::string>* warnings)
{
    const BadNormal first = first_bad_normal(mesh);
    if (first.vertex < 0 || mesh.normals.size() != mesh.positions.size()) return;
    std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        if (i0 >= sum.size() || i1 >= sum.size() || i2 >= sum.size()) return;  // validate_mesh names it
        const glm::dvec3 p0 = mesh.positions[i0], p1 = mesh.positions[i1], p2 = mesh.positions[i2];
        const glm::dvec3 area = glm::cross(p1 - p0, p2 - p0);  // twice the area, along the normal
        for (uint32_t i : {i0, i1, i2}) sum[i] += area;
    }
    size_t count = 0;
    for (size_t v = 0; v < mesh.normals.size(); ++v) {
        const glm::vec3 n = mesh.normals[v];
        if (std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) && n != glm::vec3(0.0f)) continue;
        const double len = glm::length(sum[v]);
        mesh.normals[v] = len > 0.0 && std::isfinite(len) ? glm::vec3(sum[v] / len) : glm::vec3(0.0f, 0.0f, 1.0f);
        ++count;
    }
    if (warnings)
        warnings->push_back(mesh.name + ": " + std::to_string(count) +
                            " normals are not finite or zero (the first: "
                            "vertex " +
                            std::to_string(first.vertex) + ", " + first.what + "); recomputed from the triangles");
}

void validate_loaded(const TriangleMesh& mesh)
{
    validate_mesh(mesh);
    if (mesh.indices.empty()) fail(mesh.name, "contains no triangles");
}

std::string printable(std::string_view text, size_t max)
{
    std::string out(text.substr(0, max));
    for (auto& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    if (text.size() > max) out += "...";
    return out;
}

std::string one_line(const std::string& message)
{
    constexpr size_t kLongWord = 64;
    std::string out, word;
    auto flush = [&] {
        out += printable(word, kLongWord);
        word.clear();
    };
    for (char c : message) {
        if (c == '\n' || c == '\r' || c == ' ') {
            flush();
            if (!out.empty() && out.back() != ' ') out += ' ';
        } else {
            word += c;
        }
    }
    flush();
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

namespace {

/// Flushes a file's data and metadata to the disk (fsync), so that a rename published after it
/// never names a file whose bytes a crash could still lose. Never through a link: the temporary
/// file is Jade's own, and a link in its place would be someone else's.
void sync_path(std::string_view name, const std::filesystem::path& path, bool folder)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | (folder ? O_DIRECTORY : O_NOFOLLOW));
    if (fd < 0) fail(name, "cannot open " + path.string() + " to sync it: " + std::strerror(errno));
    const int rc = ::fsync(fd);
    const int error = errno;
    ::close(fd);
    // Some file systems cannot sync a folder (EINVAL): the rename is then as durable as they allow.
    if (rc != 0 && !(folder && (error == EINVAL || error == ENOTSUP)))
        fail(name, "cannot sync " + path.string() + " to disk: " + std::strerror(error));
}

/// `count` random lower-case hex digits from the kernel's generator (std::random_device reads
/// it), for names nobody can plant a file or link under in advance.
std::string random_hex(int count)
{
    static std::random_device device;
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    while (int(out.size()) < count) {
        auto bits = device();
        for (int i = 0; i < 8 && int(out.size()) < count; ++i, bits >>= 4) out += kHex[bits & 15];
    }
    return out;
}

/// The mode and owner a replacement of `path` should have: those of the file it replaces, so
/// that replacing a private file (mode 600) does not publish it; nullopt for a new file.
std::optional<struct stat> replaced_file(const std::filesystem::path& path)
{
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
    return st;
}

}  // namespace

TemporaryFile create_temporary_beside(const std::filesystem::path& path)
{
    const auto name = display_name(path);
    // O_EXCL makes the name ours alone and refuses any link planted under it; O_NOFOLLOW says so
    // again. The name cannot be guessed in advance, and a collision is retried with another.
    for (int attempt = 0; attempt < 100; ++attempt) {
        auto tmp = path;
        tmp += ".tmp-" + std::to_string(::getpid()) + "-" + random_hex(12);
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0) return {tmp, fd};
        if (errno != EEXIST) fail(name, "cannot create " + tmp.string() + ": " + std::strerror(errno));
    }
    fail(name, "cannot create a temporary file beside it: 100 names were taken");
}

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&, int fd)>& write)
{
    const auto name = display_name(path);
    const auto [tmp, fd] = create_temporary_beside(path);
    bool fd_open = true;
    try {
        write(tmp, fd);
        // After writing: a writer that opens the file by its name could not if it were read-only.
        if (const auto old = replaced_file(path)) {
            if (::fchmod(fd, old->st_mode & 07777) != 0)
                fail(name,
                     "cannot give " + tmp.string() + " the mode of the file it replaces: " + std::strerror(errno));
            // Keeping the owner needs privileges (or changes nothing for one's own files): best effort.
            [[maybe_unused]] const int ignored = ::fchown(fd, old->st_uid, old->st_gid);
        }
        fd_open = false;
        if (::close(fd) != 0) fail(name, "writing " + tmp.string() + " failed: " + std::strerror(errno));
        sync_path(name, tmp, false);
        std::filesystem::rename(tmp, path);
    } catch (const std::exception& e) {
        if (fd_open) ::close(fd);
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        if (dynamic_cast<const Error*>(&e)) throw;
        fail(name, std::string("cannot write: ") + e.what());
    }
    // The new name must reach the disk too, or a crash could bring back the old file (or none).
    const auto folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    sync_path(name, folder, true);
}

void write_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write)
{
    write_atomically(path, [&](const std::filesystem::path& tmp, int) { write(tmp); });
}

std::string lower_extension(const std::filesystem::path& path)
{
    auto ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace jade::io

namespace jade {

void dev::write_file_atomically(const std::filesystem::path& path, std::string_view bytes)
{
    const auto name = io::display_name(path);
    io::write_atomically(path, [&](const std::filesystem::path& tmp, int fd) {
        // Through the descriptor that created the file: the name is never opened again.
        for (size_t done = 0; done < bytes.size();) {
            const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) io::fail(name, "writing " + tmp.string() + " failed: " + std::strerror(errno));
            done += size_t(n);
        }
    });
}

void dev::check_writable(const std::filesystem::path& path)
{
    const auto [tmp, fd] = io::create_temporary_beside(path);
    ::close(fd);
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
}

}  // namespace jade
