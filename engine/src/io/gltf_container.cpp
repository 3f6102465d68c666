// io/gltf_container.cpp - base64 and the GLB container; see gltf_container.hpp.
#include "io/gltf_container.hpp"

#include "io/common.hpp"

#include <cstdint>
#include <cstring>

namespace jade::io {

namespace {

void append_u32(std::string& out, uint32_t v)
{
    char raw[4];
    std::memcpy(raw, &v, 4);
    out.append(raw, 4);
}

}  // namespace

std::string base64(const std::vector<unsigned char>& data)
{
    static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((data.size() + 2) / 3 * 4);
    for (size_t i = 0; i < data.size(); i += 3) {
        const uint32_t a = data[i], b = i + 1 < data.size() ? data[i + 1] : 0,
                       c = i + 2 < data.size() ? data[i + 2] : 0;
        const uint32_t triple = (a << 16) | (b << 8) | c;
        out += kDigits[(triple >> 18) & 63];
        out += kDigits[(triple >> 12) & 63];
        out += i + 1 < data.size() ? kDigits[(triple >> 6) & 63] : '=';
        out += i + 2 < data.size() ? kDigits[triple & 63] : '=';
    }
    return out;
}

std::string glb_container(const std::string& name, std::string text, const std::vector<unsigned char>& buffer)
{
    text.resize((text.size() + 3) / 4 * 4, ' ');
    const size_t bin = (buffer.size() + 3) / 4 * 4;
    const uint64_t total = 12 + 8 + text.size() + (buffer.empty() ? 0 : 8 + bin);
    if (total > 0xffffffffu) fail(name, "the GLB would exceed 4 GiB");
    std::string out;
    out.reserve(size_t(total));
    out += "glTF";
    append_u32(out, 2);
    append_u32(out, uint32_t(total));
    append_u32(out, uint32_t(text.size()));
    append_u32(out, 0x4E4F534Au);  // "JSON"
    out += text;
    if (buffer.empty()) return out;
    append_u32(out, uint32_t(bin));
    append_u32(out, 0x004E4942u);  // "BIN\0"
    out.append(reinterpret_cast<const char*>(buffer.data()), buffer.size());
    out.append(bin - buffer.size(), '\0');
    return out;
}

}  // namespace jade::io
