// libFuzzer target for one mesh format: fuzz_off, fuzz_ply, fuzz_obj, fuzz_gltf (text .gltf) and
// fuzz_glb are all built from this file with JADE_FUZZ_EXTENSION set to their extension.
//
// Each input is written to a temporary file with that extension (load_mesh dispatches on it,
// and glTF resolves external buffers next to it) and goes through jade::load_mesh and then
// jade::prepare_mesh, as `jade info` and `jade bake` do. A jade::Error is the expected outcome for
// bad input; anything else is a finding:
//   - a crash, sanitizer report (ASan, UBSan; UB aborts in the fuzz preset), assert, timeout or
//     out-of-memory (libFuzzer's -rss_limit_mb / -malloc_limit_mb);
//   - any other exception type escaping (std::terminate -> abort);
//   - an error message that does not start with "<file name>: " or that carries bytes outside
//     printable ASCII (file content must be quoted through io::printable);
//   - a loaded or prepared mesh that breaks the invariants documented in jade/mesh.hpp.
#include <jade/error.hpp>
#include <jade/io.hpp>
#include <jade/mesh.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#ifndef JADE_FUZZ_EXTENSION
#error "define JADE_FUZZ_EXTENSION, e.g. \".off\""
#endif

namespace {

std::filesystem::path g_dir;
std::filesystem::path g_path;
std::string g_name;

[[noreturn]] void finding(const char* what, const std::string& detail)
{
    std::fprintf(stderr, "\n==jade-fuzz== FINDING: %s\n%s\n", what, detail.c_str());
    std::fflush(stderr);
    std::abort();
}

void remove_dir()
{
    std::error_code ec;
    if (!g_dir.empty()) std::filesystem::remove_all(g_dir, ec);
}

void write_input(const uint8_t* data, size_t size)
{
    const int fd = ::open(g_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd < 0) finding("harness", "cannot create " + g_path.string());
    size_t done = 0;
    while (done < size) {
        const ssize_t n = ::write(fd, data + done, size - done);
        if (n <= 0) finding("harness", "cannot write " + g_path.string());
        done += size_t(n);
    }
    ::close(fd);
}

void check_message(const jade::Error& e)
{
    const std::string message = e.what();
    if (message.rfind(g_name + ": ", 0) != 0) finding("error message does not start with the file name", message);
    for (char c : message)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e)
            finding("error message carries a non-printable byte", message);
}

void check_loaded(const jade::TriangleMesh& m)
{
    if (m.indices.empty() || m.indices.size() % 3 != 0) finding("loaded mesh", "bad index count");
    for (uint32_t i : m.indices)
        if (i >= m.positions.size()) finding("loaded mesh", "index out of range");
    if (!m.normals.empty() && m.normals.size() != m.positions.size()) finding("loaded mesh", "normal count");
    if (!m.baked_ao.empty() && m.baked_ao.size() != m.positions.size()) finding("loaded mesh", "_AO count");
    if (!m.baked_tm.empty() && m.baked_tm.size() != m.positions.size()) finding("loaded mesh", "_TM count");
    for (const auto& p : m.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            finding("loaded mesh", "non-finite position");
}

void check_prepared(const jade::TriangleMesh& m, const jade::PreparedMesh& p)
{
    const size_t n = p.vertex_count();
    if (n == 0 || p.indices.empty() || p.indices.size() % 3 != 0) finding("prepared mesh", "empty or bad index count");
    if (p.normals.size() != n || p.areas.size() != n) finding("prepared mesh", "per-vertex array sizes");
    if (p.render_to_bake.size() != m.positions.size()) finding("prepared mesh", "render_to_bake size");
    for (uint32_t i : p.indices)
        if (i >= n) finding("prepared mesh", "index out of range");
    for (uint32_t b : p.render_to_bake)
        if (b != jade::PreparedMesh::kUnused && b >= n) finding("prepared mesh", "render_to_bake out of range");
    if (p.input_vertices != n + p.welded_vertices + p.unused_vertices) finding("prepared mesh", "vertex bookkeeping");
    if (p.input_triangles != p.triangle_count() + p.dropped_triangles) finding("prepared mesh", "triangle bookkeeping");
    for (const auto& v : p.normals)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            finding("prepared mesh", "non-finite normal");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    const char* tmp = std::getenv("TMPDIR");
    std::string templ = std::string(tmp && *tmp ? tmp : "/tmp") + "/jade-fuzz-XXXXXX";
    if (!::mkdtemp(templ.data())) finding("harness", "mkdtemp failed for " + templ);
    g_dir = templ;
    g_name = std::string("input") + JADE_FUZZ_EXTENSION;
    g_path = g_dir / g_name;
    std::atexit(remove_dir);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    write_input(data, size);
    jade::TriangleMesh mesh;
    try {
        mesh = jade::load_mesh(g_path);
    } catch (const jade::Error& e) {
        check_message(e);
        return 0;
    }
    check_loaded(mesh);
    try {
        const jade::PreparedMesh prepared = jade::prepare_mesh(mesh);
        check_prepared(mesh, prepared);
    } catch (const jade::Error& e) {
        check_message(e);
    }
    return 0;
}
