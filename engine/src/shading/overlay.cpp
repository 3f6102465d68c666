// shading/overlay.cpp - host-side image helpers: tone mapping, the false-colour map and its
// colour bar, and a tiny built-in bitmap font for labels (no font dependency).
#include <jade/dev/overlay.hpp>
#include <jade/render.hpp>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace jade {
namespace {

// 5 × 8 glyphs ('#' = ink), rows top to bottom separated by '|'; row 7 holds descenders and is
// empty when left out. Digits and capitals sit on rows 0–6.
struct Glyph {
    char c;
    const char* rows;
};
constexpr Glyph kFont[] = {
    {' ', "....."},
    {'0', ".###.|#...#|#..##|#.#.#|##..#|#...#|.###."},
    {'1', "..#..|.##..|..#..|..#..|..#..|..#..|.###."},
    {'2', ".###.|#...#|....#|...#.|..#..|.#...|#####"},
    {'3', "#####|...#.|..#..|...#.|....#|#...#|.###."},
    {'4', "...#.|..##.|.#.#.|#..#.|#####|...#.|...#."},
    {'5', "#####|#....|####.|....#|....#|#...#|.###."},
    {'6', "..##.|.#...|#....|####.|#...#|#...#|.###."},
    {'7', "#####|....#|...#.|..#..|.#...|.#...|.#..."},
    {'8', ".###.|#...#|#...#|.###.|#...#|#...#|.###."},
    {'9', ".###.|#...#|#...#|.####|....#|...#.|.##.."},
    {'A', ".###.|#...#|#...#|#####|#...#|#...#|#...#"},
    {'B', "####.|#...#|#...#|####.|#...#|#...#|####."},
    {'C', ".###.|#...#|#....|#....|#....|#...#|.###."},
    {'D', "###..|#..#.|#...#|#...#|#...#|#..#.|###.."},
    {'E', "#####|#....|#....|####.|#....|#....|#####"},
    {'F', "#####|#....|#....|####.|#....|#....|#...."},
    {'G', ".###.|#...#|#....|#.###|#...#|#...#|.####"},
    {'H', "#...#|#...#|#...#|#####|#...#|#...#|#...#"},
    {'I', ".###.|..#..|..#..|..#..|..#..|..#..|.###."},
    {'J', "..###|...#.|...#.|...#.|...#.|#..#.|.##.."},
    {'K', "#...#|#..#.|#.#..|##...|#.#..|#..#.|#...#"},
    {'L', "#....|#....|#....|#....|#....|#....|#####"},
    {'M', "#...#|##.##|#.#.#|#.#.#|#...#|#...#|#...#"},
    {'N', "#...#|#...#|##..#|#.#.#|#..##|#...#|#...#"},
    {'O', ".###.|#...#|#...#|#...#|#...#|#...#|.###."},
    {'P', "####.|#...#|#...#|####.|#....|#....|#...."},
    {'Q', ".###.|#...#|#...#|#...#|#.#.#|#..#.|.##.#"},
    {'R', "####.|#...#|#...#|####.|#.#..|#..#.|#...#"},
    {'S', ".####|#....|#....|.###.|....#|....#|####."},
    {'T', "#####|..#..|..#..|..#..|..#..|..#..|..#.."},
    {'U', "#...#|#...#|#...#|#...#|#...#|#...#|.###."},
    {'V', "#...#|#...#|#...#|#...#|#...#|.#.#.|..#.."},
    {'W', "#...#|#...#|#...#|#.#.#|#.#.#|#.#.#|.#.#."},
    {'X', "#...#|#...#|.#.#.|..#..|.#.#.|#...#|#...#"},
    {'Y', "#...#|#...#|.#.#.|..#..|..#..|..#..|..#.."},
    {'Z', "#####|....#|...#.|..#..|.#...|#....|#####"},
    {'a', ".....|.....|.###.|....#|.####|#...#|.####"},
    {'b', "#....|#....|#.##.|##..#|#...#|#...#|####."},
    {'c', ".....|.....|.###.|#....|#....|#...#|.###."},
    {'d', "....#|....#|.##.#|#..##|#...#|#...#|.####"},
    {'e', ".....|.....|.###.|#...#|#####|#....|.###."},
    {'f', "..##.|.#..#|.#...|###..|.#...|.#...|.#..."},
    {'g', ".....|.....|.####|#...#|#...#|.####|....#|.###."},
    {'h', "#....|#....|#.##.|##..#|#...#|#...#|#...#"},
    {'i', "..#..|.....|.##..|..#..|..#..|..#..|.###."},
    {'j', "...#.|.....|..##.|...#.|...#.|...#.|#..#.|.##.."},
    {'k', "#....|#....|#..#.|#.#..|##...|#.#..|#..#."},
    {'l', ".##..|..#..|..#..|..#..|..#..|..#..|.###."},
    {'m', ".....|.....|##.#.|#.#.#|#.#.#|#...#|#...#"},
    {'n', ".....|.....|#.##.|##..#|#...#|#...#|#...#"},
    {'o', ".....|.....|.###.|#...#|#...#|#...#|.###."},
    {'p', ".....|.....|####.|#...#|#...#|####.|#....|#...."},
    {'q', ".....|.....|.####|#...#|#...#|.####|....#|....#"},
    {'r', ".....|.....|#.##.|##..#|#....|#....|#...."},
    {'s', ".....|.....|.###.|#....|.###.|....#|####."},
    {'t', ".#...|.#...|###..|.#...|.#...|.#..#|..##."},
    {'u', ".....|.....|#...#|#...#|#...#|#..##|.##.#"},
    {'v', ".....|.....|#...#|#...#|#...#|.#.#.|..#.."},
    {'w', ".....|.....|#...#|#...#|#.#.#|#.#.#|.#.#."},
    {'x', ".....|.....|#...#|.#.#.|..#..|.#.#.|#...#"},
    {'y', ".....|.....|#...#|#...#|#...#|.####|....#|.###."},
    {'z', ".....|.....|#####|...#.|..#..|.#...|#####"},
    {'(', "...#.|..#..|.#...|.#...|.#...|..#..|...#."},
    {')', ".#...|..#..|...#.|...#.|...#.|..#..|.#..."},
    {'[', ".###.|.#...|.#...|.#...|.#...|.#...|.###."},
    {']', ".###.|...#.|...#.|...#.|...#.|...#.|.###."},
    {'.', ".....|.....|.....|.....|.....|.##..|.##.."},
    {',', ".....|.....|.....|.....|.##..|.##..|..#..|.#..."},
    {'-', ".....|.....|.....|#####"},
    {'+', ".....|..#..|..#..|#####|..#..|..#.."},
    {'_', ".....|.....|.....|.....|.....|.....|.....|#####"},
    {':', ".....|.##..|.##..|.....|.##..|.##.."},
    {'/', "....#|....#|...#.|..#..|.#...|#....|#...."},
    {'=', ".....|.....|#####|.....|#####"},
    {'%', "##..#|##..#|...#.|..#..|.#...|#..##|#..##"},
    {'*', ".....|..#..|#.#.#|.###.|#.#.#|..#.."},
    {'!', "..#..|..#..|..#..|..#..|..#..|.....|..#.."},
    {'?', ".###.|#...#|....#|...#.|..#..|.....|..#.."},
    {'<', "...#.|..#..|.#...|#....|.#...|..#..|...#."},
    {'>', ".#...|..#..|...#.|....#|...#.|..#..|.#..."},
    {'#', ".#.#.|.#.#.|#####|.#.#.|#####|.#.#.|.#.#."},
    {'\'', "..#..|..#..|....."},
    {'"', ".#.#.|.#.#.|....."},
    {'^', "..#..|.#.#.|#...#"},
};
constexpr const char* kUnknown = "#####|#...#|#...#|#...#|#...#|#...#|#####";
constexpr int kGlyphW = 5, kGlyphH = 8, kAdvance = 6;

const char* glyph_rows(char c)
{
    for (const Glyph& g : kFont)
        if (g.c == c) return g.rows;
    return kUnknown;
}

void fill_rect(RenderedImage& img, int x0, int y0, int w, int h, glm::vec3 color)
{
    for (int y = std::max(y0, 0); y < std::min(y0 + h, int(img.height)); ++y)
        for (int x = std::max(x0, 0); x < std::min(x0 + w, int(img.width)); ++x) {
            float* p = img.pixel(uint32_t(x), uint32_t(y));
            p[0] = color.r, p[1] = color.g, p[2] = color.b, p[3] = 1.0f;
        }
}

float srgb_to_linear(float s) { return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f); }

// viridis at 9 equally spaced points (matplotlib's map, as R's viridisLite::viridis(9)), sRGB.
constexpr uint32_t kViridis[9] = {0x440154, 0x472D7B, 0x3B528B, 0x2C728E, 0x21908C,
                                  0x27AD81, 0x5DC863, 0xAADC32, 0xFDE725};

}  // namespace

glm::vec3 false_color(float x)
{
    static const std::array<glm::vec3, 9> stops = [] {
        std::array<glm::vec3, 9> s;
        for (int i = 0; i < 9; ++i)
            for (int c = 0; c < 3; ++c) s[i][c] = srgb_to_linear(float((kViridis[i] >> (16 - 8 * c)) & 0xff) / 255.0f);
        return s;
    }();
    const float s = std::clamp(std::isnan(x) ? 0.0f : x, 0.0f, 1.0f) * 8.0f;
    const int i = std::min(int(s), 7);
    return glm::mix(stops[i], stops[i + 1], s - float(i));
}

void apply_tone_map(RenderedImage& image, ToneMap tone_map, float exposure)
{
    for (size_t i = 0; i < image.rgba.size(); i += 4)
        for (size_t c = 0; c < 3; ++c) {
            float x = std::max(image.rgba[i + c] * exposure, 0.0f);
            switch (tone_map) {
            case ToneMap::None: break;
            case ToneMap::Reinhard: x = x / (1.0f + x); break;
            case ToneMap::AcesFitted:  // Narkowicz 2015, input pre-scaled by 0.6 as he suggests
                x *= 0.6f;
                x = std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
                break;
            }
            image.rgba[i + c] = x;
        }
}

int text_width(std::string_view text, int scale) { return int(text.size()) * kAdvance * scale - scale; }

void draw_text(RenderedImage& image, int x, int y, std::string_view text, glm::vec3 color, int scale)
{
    for (char ch : text) {
        const char* rows = glyph_rows(ch);
        int row = 0, col = 0;
        for (const char* p = rows; *p && row < kGlyphH; ++p) {
            if (*p == '|') {
                ++row, col = 0;
                continue;
            }
            if (*p == '#') fill_rect(image, x + col * scale, y + row * scale, scale, scale, color);
            ++col;
        }
        x += kAdvance * scale;
    }
}

void draw_color_bar(RenderedImage& image, float min_value, float max_value, std::string_view title)
{
    const int scale = std::max(1, int(image.height) / 256);
    const int bar_w = 6 * scale, bar_h = int(image.height) / 2;
    const int margin = 4 * scale + 2;
    const int x0 = int(image.width) - margin - bar_w, y0 = (int(image.height) - bar_h) / 2;
    for (int y = 0; y < bar_h; ++y)  // top = max
        fill_rect(image, x0, y0 + y, bar_w, 1, false_color(1.0f - float(y) / float(std::max(bar_h - 1, 1))));
    char top[32], bottom[32];
    std::snprintf(top, sizeof top, "%.3g", double(max_value));
    std::snprintf(bottom, sizeof bottom, "%.3g", double(min_value));
    const glm::vec3 white(1.0f);
    const int text_h = kGlyphH * scale;
    draw_text(image, x0 - 2 * scale - text_width(top, scale), y0, top, white, scale);
    draw_text(image, x0 - 2 * scale - text_width(bottom, scale), y0 + bar_h - text_h + scale, bottom, white, scale);
    draw_text(image, x0 + bar_w - text_width(title, scale), y0 - text_h - 2 * scale, title, white, scale);
}

}  // namespace jade
