// io/image.cpp - jade::save_image through OpenImageIO: 8-bit sRGB PNG or half-float linear EXR.
#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include "io/common.hpp"
#include "io/gltf_thickness_map.hpp"

#include <OpenImageIO/filesystem.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace jade {

namespace {

/// Clamps to [0, 1]; NaN becomes 0 so a bad pixel cannot turn into an arbitrary byte.
float clamp01(float v) { return v > 0.0f ? std::min(v, 1.0f) : 0.0f; }

/// The sRGB transfer function (IEC 61966-2-1), piecewise: linear toe, then a 1/2.4 power.
float srgb_encode(float linear)
{
    const float v = clamp01(linear);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

uint8_t to_byte(float unit) { return static_cast<uint8_t>(std::lround(unit * 255.0f)); }

/// Opens, writes and closes one image with OIIO's writer for `format`, at `tmp`.
void write_oiio(const std::string& name, const char* format, const std::filesystem::path& tmp,
                const OIIO::ImageSpec& spec, OIIO::TypeDesc pixel_type, const void* pixels)
{
    auto out = OIIO::ImageOutput::create(format);
    if (!out) io::fail(name, std::string("OpenImageIO has no ") + format + " writer: " + OIIO::geterror());
    // The format is chosen above, not from the temporary file's extension.
    if (!out->open(tmp.string(), spec))
        io::fail(name, "cannot open " + tmp.string() + " for writing: " + out->geterror());
    if (!out->write_image(pixel_type, pixels))
        io::fail(name, "writing " + tmp.string() + " failed: " + out->geterror());
    if (!out->close()) io::fail(name, "closing " + tmp.string() + " failed: " + out->geterror());
}

void write_png(const std::string& name, const std::filesystem::path& tmp, int width, int height,
               const std::vector<float>& rgba)
{
    std::vector<uint8_t> bytes(rgba.size());
    for (size_t i = 0; i < rgba.size(); i += 4) {
        for (size_t c = 0; c < 3; ++c) bytes[i + c] = to_byte(srgb_encode(rgba[i + c]));
        bytes[i + 3] = to_byte(clamp01(rgba[i + 3]));  // alpha is coverage, never gamma-encoded
    }
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // The colours are straight (not premultiplied): stop OIIO from un-premultiplying them.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    write_oiio(name, "png", tmp, spec, OIIO::TypeDesc::UINT8, bytes.data());
}

void write_exr(const std::string& name, const std::filesystem::path& tmp, int width, int height,
               const std::vector<float>& rgba)
{
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::HALF);
    spec.attribute("oiio:ColorSpace", "Linear");
    spec.attribute("compression", "zip");
    // Half's largest finite value: beyond it the conversion gives Inf, which no reader wants
    // (a bright highlight under a strong exposure saturates instead).
    constexpr float kHalfMax = 65504.0f;
    std::vector<float> clamped(rgba.size());
    // A NaN pixel is stored as 0, as the PNG writer stores it (a NaN in a file spreads through
    // every filter that reads it).
    for (size_t i = 0; i < rgba.size(); ++i)
        clamped[i] = std::isnan(rgba[i]) ? 0.0f : std::clamp(rgba[i], -kHalfMax, kHalfMax);
    write_oiio(name, "openexr", tmp, spec, OIIO::TypeDesc::FLOAT, clamped.data());
}

std::vector<uint8_t> to_srgb8(const std::vector<float>& rgba)
{
    std::vector<uint8_t> bytes(rgba.size());
    for (size_t i = 0; i < rgba.size(); i += 4) {
        for (size_t c = 0; c < 3; ++c) bytes[i + c] = to_byte(srgb_encode(rgba[i + c]));
        bytes[i + 3] = to_byte(clamp01(rgba[i + 3]));
    }
    return bytes;
}

/// All frames as subimages of one file: OIIO's GIF writer supports "appendsubimage" (its WebP
/// writer, in OIIO 2.4, writes single images only);
/// the frame rate is the "FramesPerSecond" attribute (a rational; the GIF writer turns it into
/// a delay in 1/100 s), the GIF loops forever.
void write_frames(const std::string& name, const char* format, const std::filesystem::path& tmp, int width, int height,
                  const std::vector<std::vector<float>>& frames, double fps)
{
    auto out = OIIO::ImageOutput::create(format);
    if (!out) io::fail(name, std::string("OpenImageIO has no ") + format + " writer: " + OIIO::geterror());
    if (!out->supports("multiimage") || !out->supports("appendsubimage"))
        io::fail(name, std::string("OpenImageIO's ") + format + " writer cannot write animations");
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("oiio:UnassociatedAlpha", 1);
    const int fps_num = int(std::lround(fps * 100.0)), fps_den = 100;
    const int rational[2] = {std::max(fps_num, 1), fps_den};
    spec.attribute("FramesPerSecond", OIIO::TypeRational, rational);
    spec.attribute("oiio:Movie", 1);
    spec.attribute("gif:LoopCount", 0);
    for (size_t f = 0; f < frames.size(); ++f) {
        const auto mode = f == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendSubimage;
        if (!out->open(tmp.string(), spec, mode))
            io::fail(name, "cannot open " + tmp.string() + " for writing: " + out->geterror());
        const auto bytes = to_srgb8(frames[f]);
        if (!out->write_image(OIIO::TypeDesc::UINT8, bytes.data()))
            io::fail(name,
                     "writing frame " + std::to_string(f) + " of " + tmp.string() + " failed: " + out->geterror());
    }
    if (!out->close()) io::fail(name, "closing " + tmp.string() + " failed: " + out->geterror());
}

}  // namespace

namespace io {

std::vector<unsigned char> encode_thickness_png(const std::string& file, const ThicknessMap& map)
{
    std::vector<uint8_t> rgb(map.texels.size() * 3, 0);
    for (size_t i = 0; i < map.texels.size(); ++i) rgb[3 * i + 1] = map.texels[i];
    OIIO::ImageSpec spec(int(map.size), int(map.size), 3, OIIO::TypeDesc::UINT8);
    // Data, not colour: no colour space is named, so the file has no gAMA or sRGB chunk for a
    // decoder to apply (glTF reads the bytes as they are).
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    auto out = OIIO::ImageOutput::create("png");
    if (!out || !out->supports("ioproxy"))
        io::fail(file, std::string("OpenImageIO cannot write a PNG into memory: ") + OIIO::geterror());
    if (!out->set_ioproxy(&memory) || !out->open("thickness.png", spec) ||
        !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) || !out->close())
        io::fail(file, "cannot encode the thickness map as PNG: " + out->geterror());
    return bytes;
}

}  // namespace io

void save_animation(const std::filesystem::path& path, int width, int height,
                    const std::vector<std::vector<float>>& frames, double fps)
{
    const auto name = io::display_name(path);
    const auto ext = io::lower_extension(path);
    if (ext != ".gif") io::fail(name, "unsupported animation format '" + ext + "' (supported: .gif)");
    if (width <= 0 || height <= 0 || frames.empty())
        io::fail(name, "animation of " + std::to_string(frames.size()) + " frames of " + std::to_string(width) + "x" +
                           std::to_string(height) + " is empty");
    if (!(fps > 0.0) || !(fps <= 100.0)) io::fail(name, "frame rate " + std::to_string(fps) + " is not in (0, 100]");
    const uint64_t expected = uint64_t(width) * uint64_t(height) * 4;
    for (size_t f = 0; f < frames.size(); ++f)
        if (frames[f].size() != expected)
            io::fail(name, "frame " + std::to_string(f) + " has " + std::to_string(frames[f].size()) +
                               " floats, expected " + std::to_string(expected));
    io::write_atomically(
        path, [&](const std::filesystem::path& tmp) { write_frames(name, "gif", tmp, width, height, frames, fps); });
}

void save_image(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgba)
{
    const auto name = io::display_name(path);
    const auto ext = io::lower_extension(path);
    if (ext != ".png" && ext != ".exr")
        io::fail(name, "unsupported image format '" + ext + "' (supported: .png, .exr)");
    if (width <= 0 || height <= 0)
        io::fail(name, "image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
    const uint64_t expected = uint64_t(width) * uint64_t(height) * 4;
    if (rgba.size() != expected)
        io::fail(name, std::to_string(rgba.size()) + " floats for a " + std::to_string(width) + "x" +
                           std::to_string(height) + " RGBA image (expected " + std::to_string(expected) + ")");
    io::write_atomically(path, [&](const std::filesystem::path& tmp) {
        if (ext == ".png")
            write_png(name, tmp, width, height, rgba);
        else
            write_exr(name, tmp, width, height, rgba);
    });
}

dev::LoadedImage dev::load_image(const std::filesystem::path& path)
{
    const std::string name = path.string();
    auto in = OIIO::ImageInput::open(name);
    if (!in) io::fail(name, "cannot open: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels < 1 || spec.nchannels > 4)
        io::fail(name, "unsupported image: " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ", " +
                           std::to_string(spec.nchannels) + " channels");
    const int channels = spec.nchannels;
    LoadedImage img;
    img.width = spec.width, img.height = spec.height;
    img.srgb_8bit = spec.format == OIIO::TypeDesc::UINT8;
    std::vector<float> pixels(size_t(img.width) * img.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
        io::fail(name, "cannot read: " + in->geterror());
    in->close();
    auto decode = [&](float v) {
        if (!img.srgb_8bit) return std::isfinite(v) ? v : 0.0f;
        return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
    };
    img.rgba.resize(size_t(img.width) * img.height * 4);
    for (size_t i = 0, n = size_t(img.width) * img.height; i < n; ++i) {
        const float* p = &pixels[i * channels];
        for (int c = 0; c < 3; ++c) img.rgba[4 * i + c] = decode(p[channels >= 3 ? c : 0]);
        img.rgba[4 * i + 3] = channels == 4 ? p[3] : channels == 2 ? p[1] : 1.0f;
    }
    return img;
}

}  // namespace jade
