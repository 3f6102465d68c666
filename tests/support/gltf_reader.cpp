#include "gltf_reader.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <sys/wait.h>

namespace jade::test {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what)
{
    throw std::runtime_error(path.filename().string() + ": " + what);
}

std::vector<unsigned char> read_bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<unsigned char> unbase64(const std::filesystem::path& path, const std::string& text)
{
    std::vector<unsigned char> out;
    uint32_t bits = 0;
    int n = 0;
    for (char c : text) {
        int v;
        if (c >= 'A' && c <= 'Z')
            v = c - 'A';
        else if (c >= 'a' && c <= 'z')
            v = c - 'a' + 26;
        else if (c >= '0' && c <= '9')
            v = c - '0' + 52;
        else if (c == '+')
            v = 62;
        else if (c == '/')
            v = 63;
        else if (c == '=')
            break;
        else
            fail(path, "bad base64 character");
        bits = (bits << 6) | uint32_t(v);
        if ((n += 6) >= 8) out.push_back(uint8_t(bits >> (n -= 8)));
    }
    return out;
}

/// The bytes a URI names: a base64 data URI or a file beside the glTF.
std::vector<unsigned char> uri_bytes(const std::filesystem::path& path, const std::string& uri)
{
    if (uri.rfind("data:", 0) == 0) {
        const auto comma = uri.find(',');
        if (comma == std::string::npos || uri.substr(0, comma).find(";base64") == std::string::npos)
            fail(path, "data URI without base64");
        return unbase64(path, uri.substr(comma + 1));
    }
    return read_bytes(path.parent_path() / uri);
}

size_t component_size(int type) { return type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : 4; }

size_t components(const std::string& type)
{
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4" || type == "MAT2") return 4;
    if (type == "MAT3") return 9;
    return 16;
}

uint32_t read_index(const unsigned char* p, int type)
{
    if (type == 5121) return *p;
    if (type == 5123) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
    }
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

}  // namespace

std::vector<std::vector<unsigned char>> GltfFile::elements(int index) const
{
    const auto& a = doc.at("accessors").at(size_t(index));
    const size_t size = component_size(a.at("componentType").get<int>()) * components(a.at("type").get<std::string>());
    const size_t count = a.at("count").get<size_t>();
    std::vector<std::vector<unsigned char>> out(count, std::vector<unsigned char>(size, 0));
    auto view_data = [&](int view, size_t offset) {
        const auto& v = doc.at("bufferViews").at(size_t(view));
        const auto& buffer = buffers.at(v.at("buffer").get<size_t>());
        const size_t start = v.value("byteOffset", size_t(0)) + offset;
        if (start > buffer.size()) fail(path, "bufferView " + std::to_string(view) + " past its buffer");
        return std::make_pair(buffer.data() + start, v.value("byteStride", size_t(0)));
    };
    if (a.contains("bufferView")) {
        auto [data, stride] = view_data(a["bufferView"].get<int>(), a.value("byteOffset", size_t(0)));
        for (size_t i = 0; i < count; ++i) std::memcpy(out[i].data(), data + i * (stride ? stride : size), size);
    }
    if (a.contains("sparse")) {
        const auto& s = a["sparse"];
        const int itype = s["indices"]["componentType"].get<int>();
        auto [idx, unused1] =
            view_data(s["indices"]["bufferView"].get<int>(), s["indices"].value("byteOffset", size_t(0)));
        auto [val, unused2] =
            view_data(s["values"]["bufferView"].get<int>(), s["values"].value("byteOffset", size_t(0)));
        for (size_t k = 0; k < s["count"].get<size_t>(); ++k)
            std::memcpy(out.at(read_index(idx + k * component_size(itype), itype)).data(), val + k * size, size);
    }
    return out;
}

std::vector<float> GltfFile::floats(int index) const
{
    std::vector<float> out;
    for (const auto& e : elements(index))
        for (size_t c = 0; c < e.size(); c += 4) {
            float f;
            std::memcpy(&f, e.data() + c, 4);
            out.push_back(f);
        }
    return out;
}

std::vector<unsigned char> GltfFile::image(int index) const
{
    const auto& image = doc.at("images").at(size_t(index));
    if (image.contains("uri")) return uri_bytes(path, image["uri"].get<std::string>());
    const auto& v = doc.at("bufferViews").at(image.at("bufferView").get<size_t>());
    const auto& buffer = buffers.at(v.at("buffer").get<size_t>());
    const auto begin = buffer.begin() + std::ptrdiff_t(v.value("byteOffset", size_t(0)));
    return {begin, begin + std::ptrdiff_t(v.at("byteLength").get<size_t>())};
}

GltfFile read_gltf_file(const std::filesystem::path& path)
{
    GltfFile f;
    f.path = path;
    const auto bytes = read_bytes(path);
    std::vector<unsigned char> bin;
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
        uint32_t header[5];
        if (bytes.size() < 20) fail(path, "short GLB");
        std::memcpy(header, bytes.data(), 20);
        if (header[2] != bytes.size()) fail(path, "GLB length " + std::to_string(header[2]) + " is not the file size");
        if (header[3] % 4 || header[4] != 0x4E4F534Au) fail(path, "bad JSON chunk");
        f.doc = nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + header[3]);
        const size_t at = 20 + header[3];
        if (at + 8 <= bytes.size()) {
            uint32_t chunk[2];
            std::memcpy(chunk, bytes.data() + at, 8);
            if (chunk[1] != 0x004E4942u || chunk[0] % 4 || at + 8 + chunk[0] != bytes.size())
                fail(path, "bad BIN chunk");
            bin.assign(bytes.begin() + std::ptrdiff_t(at + 8), bytes.end());
        }
    } else {
        f.doc = nlohmann::json::parse(bytes.begin(), bytes.end());
    }
    for (const auto& b : f.doc.value("buffers", nlohmann::json::array())) {
        auto data = b.contains("uri") ? uri_bytes(path, b["uri"].get<std::string>()) : bin;
        if (data.size() < b.at("byteLength").get<size_t>()) fail(path, "buffer shorter than its byteLength");
        f.buffers.push_back(std::move(data));
    }
    return f;
}

std::optional<std::vector<ValidatorReport>> run_gltf_validator(const std::vector<std::filesystem::path>& files,
                                                               std::string* skip)
{
    const std::filesystem::path source = JADE_DEFAULT_SOURCE_DIR,
                                folder = std::filesystem::path(JADE_DEFAULT_BINARY_DIR) / "gltf-validator";
    const auto install = test::run_shell("bash '" + (source / "third_party/install_gltf_validator.sh").string() +
                                         "' '" + folder.string() + "'");
    const int rc = install.exit_code;
    std::string output = install.output;
    if (rc == 77) {
        *skip = output;
        return std::nullopt;
    }
    std::vector<ValidatorReport> reports;
    if (rc != 0) {
        *skip = "installing the glTF Validator failed: " + output;
        return reports;
    }
    std::string cmd =
        "GLTF_VALIDATOR='" + folder.string() + "' node '" + (source / "tests/support/validate_gltf.js").string() + "'";
    for (const auto& f : files) cmd += " '" + f.string() + "'";
    const auto validated = test::run_shell(cmd);
    output = validated.output;
    if (validated.exit_code != 0) {
        *skip = "the glTF Validator failed: " + output;
        return reports;
    }
    size_t start = 0;
    for (size_t end; (end = output.find('\n', start)) != std::string::npos; start = end + 1) {
        const auto j = nlohmann::json::parse(output.substr(start, end - start), nullptr, false);
        if (!j.is_object()) continue;
        ValidatorReport r;
        r.file = j.value("file", "");
        r.errors = j.value("errors", -1), r.warnings = j.value("warnings", -1), r.infos = j.value("infos", -1),
        r.hints = j.value("hints", -1);
        r.issues = j.value("issues", std::vector<std::string>{});
        reports.push_back(std::move(r));
    }
    if (reports.size() != files.size())
        *skip = "the glTF Validator reported on " + std::to_string(reports.size()) + " of " +
                std::to_string(files.size()) + " files: " + output;
    return reports;
}

}  // namespace jade::test
