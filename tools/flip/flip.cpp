// LDR-FLIP (Andersson et al., HPG 2020). See flip.hpp for the contract.
//
// Pipeline per pixel pair (paper's colour pipeline, then feature pipeline):
//   sRGB -> linear RGB -> XYZ (D65) -> YCxCz (opponent space)
//   -> CSF spatial filter (separable Gaussian sums, radius from ppd), clamp-to-edge borders
//   -> back to linear RGB, clamp to [0,1] -> CIELab -> Hunt adjustment -> HyAB distance
//   -> ^0.7, redistributed to [0,1] with c_max (green/blue HyAB), p_c = 0.4, p_t = 0.95
//   feature pipeline on the unfiltered Y normalised to [0,1]: 1st/2nd Gaussian derivatives
//   (edges/points, sigma = 0.5 * 0.082 * ppd) -> feature difference in [0,1]
//   -> FLIP = colour_error ^ (1 - feature_error).
// All pixel arithmetic is float32 in the reference's order of operations so that the error
// maps agree to float rounding; only the final mean is accumulated in double.
#include "flip.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace jade::flip {
namespace {

constexpr float kPi = 3.14159265358979f;

// Constants of the paper (and the reference): colour error exponent q_c, the redistribution
// thresholds p_c and p_t, the feature filter width w (degrees) and feature exponent q_f.
constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f, kW = 0.082f, kQf = 0.5f;

// CSF approximation in the spatial domain: each channel's filter is a sum of Gaussians
// a * sqrt(pi / b) * exp(-pi^2 x^2 / b), x in degrees (paper, "spatial filtering"; the
// b's are in degrees^2). Achromatic (Y) and red-green (Cx) use one Gaussian (their a2 = 0),
// blue-yellow (Cz) two.
constexpr float kA1y = 1.0f, kB1y = 0.0047f;
constexpr float kA1cx = 1.0f, kB1cx = 0.0053f;
constexpr float kA1cz = 34.1f, kB1cz = 0.04f, kA2cz = 13.5f, kB2cz = 0.025f;

// D65 white point in XYZ (Y = 1) and its reciprocal, as the reference spells them.
constexpr float kWhite[3] = {0.950428545f, 1.0f, 1.088900371f};
constexpr float kInvWhite[3] = {1.052156925f, 1.0f, 0.918357670f};

struct C3 {
    float x, y, z;
};

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
float linear_to_srgb(float c) { return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }

C3 linear_to_xyz(C3 c)  // sRGB primaries, D65
{
    return {(10135552.0f / 24577794.0f) * c.x + (8788810.0f / 24577794.0f) * c.y + (4435075.0f / 24577794.0f) * c.z,
            (2613072.0f / 12288897.0f) * c.x + (8788810.0f / 12288897.0f) * c.y + (887015.0f / 12288897.0f) * c.z,
            (1425312.0f / 73733382.0f) * c.x + (8788810.0f / 73733382.0f) * c.y + (70074185.0f / 73733382.0f) * c.z};
}

C3 xyz_to_linear(C3 c)
{
    return {3.241003275f * c.x - 1.537398934f * c.y - 0.498615861f * c.z,
            -0.969224334f * c.x + 1.875930071f * c.y + 0.041554224f * c.z,
            0.055639423f * c.x - 0.204011202f * c.y + 1.057148933f * c.z};
}

// YCxCz (Zhang & Wandell's linearised CIELab): Y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn),
// Cz = 200 (Y/Yn - Z/Zn). Linear in XYZ, so filtering in it is meaningful.
C3 xyz_to_ycxcz(C3 c)
{
    const float X = c.x * kInvWhite[0], Y = c.y * kInvWhite[1], Z = c.z * kInvWhite[2];
    return {116.0f * Y - 16.0f, 500.0f * (X - Y), 200.0f * (Y - Z)};
}

C3 ycxcz_to_xyz(C3 c)
{
    const float Y = (c.x + 16.0f) / 116.0f, Cx = c.y / 500.0f, Cz = c.z / 200.0f;
    return {(Y + Cx) * kWhite[0], Y * kWhite[1], (Y - Cz) * kWhite[2]};
}

C3 xyz_to_lab(C3 c)  // CIELab with the D65 white
{
    constexpr float d = 6.0f / 29.0f;
    const float d3 = d * (d * d), factor = 1.0f / (3.0f * (d * d)), term = 4.0f / 29.0f;
    auto f = [&](float t) { return t > d3 ? std::pow(t, 1.0f / 3.0f) : factor * t + term; };
    const float fx = f(c.x * kInvWhite[0]), fy = f(c.y * kInvWhite[1]), fz = f(c.z * kInvWhite[2]);
    return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

// Hunt effect (paper): chroma shrinks with lightness, a' = 0.01 L a, b' = 0.01 L b.
C3 hunt(C3 lab) { return {lab.x, 0.01f * lab.x * lab.y, 0.01f * lab.x * lab.z}; }

// HyAB distance (Abasi et al.): |dL| + ||(da, db)||, better than Euclidean for large differences.
float hyab(C3 r, C3 t)
{
    const float da = r.y - t.y, db = r.z - t.z;
    return std::fabs(r.x - t.x) + std::sqrt(da * da + db * db);
}

// c_max: the HyAB distance between pure green and pure blue (the largest in the sRGB gamut
// after Hunt), raised to q_c; colour errors are expressed relative to it.
float max_colour_distance()
{
    const C3 g = hunt(xyz_to_lab(linear_to_xyz({0.0f, 1.0f, 0.0f})));
    const C3 b = hunt(xyz_to_lab(linear_to_xyz({0.0f, 0.0f, 1.0f})));
    return std::pow(hyab(g, b), kQc);
}

// a sqrt(pi/b) exp(-pi^2 x^2 / b) with x2 = x^2 in degrees^2.
float gauss_ab(float x2, float a, float b) { return a * std::sqrt(kPi / b) * std::exp(-(kPi * kPi) * x2 / b); }
// The 1D factor whose outer product with itself is the 2D Gaussian above, so that each of the
// two Cz Gaussians is applied separably and the results added (the reference's scheme).
float gauss_ab_sqrt(float x2, float a, float b)
{
    return std::sqrt(a * std::sqrt(kPi / b)) * std::exp(-(kPi * kPi) * x2 / b);
}

// Spatial-filter radius in pixels: 3 standard deviations of the widest Gaussian. The
// Gaussian exp(-pi^2 x^2 / b) has sigma = sqrt(b / (2 pi^2)) degrees; times ppd gives pixels.
int spatial_radius(float ppd)
{
    const float b_max = std::max({kB1y, kB1cx, kB1cz, 1.0e-5f, kB2cz});  // 1e-5: the unused b2 of Y/Cx
    return int(std::ceil(3.0f * std::sqrt(b_max / (2.0f * (kPi * kPi))) * ppd));
}

// Clamp-to-edge indexing, as the reference does on all four borders.
inline int clampi(int v, int hi) { return v < 0 ? 0 : (v > hi ? hi : v); }

void check_image(const Image& im, const char* what)
{
    if (im.width == 0 || im.height == 0)
        throw std::invalid_argument(std::string("ldr_flip: ") + what + " image is empty");
    if (im.rgb.size() != size_t(im.width) * im.height * 3)
        throw std::invalid_argument(
            std::string("ldr_flip: ") + what + " image has " + std::to_string(im.rgb.size()) +
            " floats, expected width*height*3 = " + std::to_string(size_t(im.width) * im.height * 3));
}

void check_input(uint32_t w, uint32_t h, const void* p, uint32_t channels, const char* fn)
{
    if (w == 0 || h == 0) throw std::invalid_argument(std::string(fn) + ": zero width or height");
    if (!p) throw std::invalid_argument(std::string(fn) + ": null pixel pointer");
    if (channels != 3 && channels != 4)
        throw std::invalid_argument(std::string(fn) + ": channels must be 3 or 4, got " + std::to_string(channels));
}

}  // namespace

Image from_srgb8(uint32_t w, uint32_t h, const uint8_t* rgb_or_rgba, uint32_t channels)
{
    check_input(w, h, rgb_or_rgba, channels, "from_srgb8");
    Image im{w, h, std::vector<float>(size_t(w) * h * 3)};
    for (size_t i = 0, n = size_t(w) * h; i < n; ++i)
        for (int c = 0; c < 3; ++c) im.rgb[i * 3 + c] = float(rgb_or_rgba[i * channels + c]) / 255.0f;
    return im;
}

Image from_linear(uint32_t w, uint32_t h, const float* rgba, uint32_t channels)
{
    check_input(w, h, rgba, channels, "from_linear");
    Image im{w, h, std::vector<float>(size_t(w) * h * 3)};
    for (size_t i = 0, n = size_t(w) * h; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = rgba[i * channels + c];
            im.rgb[i * 3 + c] = linear_to_srgb(!(v > 0.0f) ? 0.0f : (v > 1.0f ? 1.0f : v));  // NaN -> 0
        }
    return im;
}

double pixels_per_degree(double distance_m, double monitor_width_m, double monitor_pixels)
{
    // Observer distance times pixels per metre is pixels per radian (small-angle); times
    // pi/180 is pixels per degree. In float like the reference so the default is bit-equal.
    return double(float(distance_m) * (float(monitor_pixels) / float(monitor_width_m)) * (kPi / 180.0f));
}

double ldr_flip(const Image& reference, const Image& test, double ppd_in, const std::vector<uint8_t>* mask,
                std::vector<float>* error_map)
{
    check_image(reference, "reference");
    check_image(test, "test");
    if (reference.width != test.width || reference.height != test.height)
        throw std::invalid_argument("ldr_flip: size mismatch: reference is " + std::to_string(reference.width) + "x" +
                                    std::to_string(reference.height) + ", test is " + std::to_string(test.width) + "x" +
                                    std::to_string(test.height));
    if (!std::isfinite(ppd_in) || !(ppd_in > 0.0)) throw std::invalid_argument("ldr_flip: ppd must be finite and > 0");
    const int w = int(reference.width), h = int(reference.height);
    const size_t n = size_t(w) * h;
    if (mask && mask->size() != n)
        throw std::invalid_argument("ldr_flip: mask has " + std::to_string(mask->size()) +
                                    " bytes, expected width*height = " + std::to_string(n));
    const float ppd = float(ppd_in);

    // 1. sRGB (clamped to [0,1]) -> linear -> XYZ -> YCxCz, both images.
    std::vector<C3> ycc[2] = {std::vector<C3>(n), std::vector<C3>(n)};
    const Image* src[2] = {&reference, &test};
    for (int k = 0; k < 2; ++k)
        for (size_t i = 0; i < n; ++i) {
            float c[3];
            for (int j = 0; j < 3; ++j) {
                const float v = src[k]->rgb[i * 3 + j];
                c[j] = srgb_to_linear(!(v > 0.0f) ? 0.0f : (v > 1.0f ? 1.0f : v));
            }
            ycc[k][i] = xyz_to_ycxcz(linear_to_xyz({c[0], c[1], c[2]}));
        }

    // 2. CSF filters, sampled every 1/ppd degrees over [-r, r] pixels. Y and Cx are normalised
    // to unit sum per 1D pass (so 2D unit sum). The Cz kernel is g1(x)g1(y) + g2(x)g2(y): both
    // 1D factors are scaled by 1/sqrt(S1^2 + S2^2) so that the 2D kernel sums to 1.
    const int rs = spatial_radius(ppd), ws = 2 * rs + 1;
    std::vector<float> fy(ws), fcx(ws), fcz1(ws), fcz2(ws);
    float sy = 0, scx = 0, scz1 = 0, scz2 = 0;
    for (int i = 0; i < ws; ++i) {
        const float x = float(i - rs) * (1.0f / ppd), x2 = x * x;
        sy += fy[i] = gauss_ab(x2, kA1y, kB1y);
        scx += fcx[i] = gauss_ab(x2, kA1cx, kB1cx);
        scz1 += fcz1[i] = gauss_ab_sqrt(x2, kA1cz, kB1cz);
        scz2 += fcz2[i] = gauss_ab_sqrt(x2, kA2cz, kB2cz);
    }
    const float ny = 1.0f / sy, ncx = 1.0f / scx, ncz = 1.0f / std::sqrt(scz1 * scz1 + scz2 * scz2);
    for (int i = 0; i < ws; ++i) fy[i] *= ny, fcx[i] *= ncx, fcz1[i] *= ncz, fcz2[i] *= ncz;

    // 3. Colour difference: horizontal then vertical pass (Y, Cx, Cz via g1, Cz via g2), then
    // back to linear RGB, clamp (the filtered colour may leave the gamut), CIELab + Hunt, HyAB.
    const float cmax = max_colour_distance(), pccmax = kPc * cmax;
    std::vector<float> colour(n);
    {
        struct F4 {
            float y, cx, cz1, cz2;
        };
        std::vector<F4> tmp[2] = {std::vector<F4>(n), std::vector<F4>(n)};
        for (int k = 0; k < 2; ++k)
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    F4 a{0, 0, 0, 0};
                    for (int i = -rs; i <= rs; ++i) {
                        const C3 p = ycc[k][size_t(y) * w + clampi(x + i, w - 1)];
                        a.y += fy[i + rs] * p.x, a.cx += fcx[i + rs] * p.y;
                        a.cz1 += fcz1[i + rs] * p.z, a.cz2 += fcz2[i + rs] * p.z;
                    }
                    tmp[k][size_t(y) * w + x] = a;
                }
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                C3 lab[2];
                for (int k = 0; k < 2; ++k) {
                    F4 a{0, 0, 0, 0};
                    for (int i = -rs; i <= rs; ++i) {
                        const F4& p = tmp[k][size_t(clampi(y + i, h - 1)) * w + x];
                        a.y += fy[i + rs] * p.y, a.cx += fcx[i + rs] * p.cx;
                        a.cz1 += fcz1[i + rs] * p.cz1, a.cz2 += fcz2[i + rs] * p.cz2;
                    }
                    C3 rgb = xyz_to_linear(ycxcz_to_xyz({a.y, a.cx, a.cz1 + a.cz2}));
                    rgb = {std::clamp(rgb.x, 0.0f, 1.0f), std::clamp(rgb.y, 0.0f, 1.0f), std::clamp(rgb.z, 0.0f, 1.0f)};
                    lab[k] = hunt(xyz_to_lab(linear_to_xyz(rgb)));
                }
                // Redistribution (paper): [0, p_c c_max) maps linearly onto [0, p_t), the rest
                // [p_c c_max, c_max] onto [p_t, 1], compressing the large, obvious differences.
                float e = std::pow(hyab(lab[0], lab[1]), kQc);
                e = e < pccmax ? e * (kPt / pccmax) : kPt + ((e - pccmax) / (cmax - pccmax)) * (1.0f - kPt);
                colour[size_t(y) * w + x] = e;
            }
    }

    // 4. Feature filters: Gaussian g, its 1st derivative -x g (edges) and 2nd derivative
    // (x^2/sigma^2 - 1) g (points), sigma = 0.5 w ppd pixels, radius 3 sigma. g sums to 1; the
    // positive and negative lobes of each derivative are scaled to sum to +1 and -1.
    const float sd = 0.5f * kW * ppd;
    const int rf = int(std::ceil(3.0f * sd)), wf = 2 * rf + 1;
    std::vector<float> g(wf), dg(wf), ddg(wf);
    float gs = 0, dpos = 0, dneg = 0, ddpos = 0, ddneg = 0;
    for (int i = 0; i < wf; ++i) {
        const float x = float(i - rf);
        gs += g[i] = std::exp(-(x * x) / (2.0f * sd * sd));
        dg[i] = -x * g[i];
        (dg[i] > 0.0f ? dpos : dneg) += std::fabs(dg[i]);
        ddg[i] = (x * x / (sd * sd) - 1.0f) * g[i];
        (ddg[i] > 0.0f ? ddpos : ddneg) += std::fabs(ddg[i]);
    }
    for (int i = 0; i < wf; ++i) {
        g[i] /= gs;
        dg[i] /= dg[i] > 0.0f ? dpos : dneg;
        ddg[i] /= ddg[i] > 0.0f ? ddpos : ddneg;
    }

    // 5. Feature difference on the unfiltered luminance, Y normalised to [0,1] ((Y + 16)/116,
    // the paper's erratum). Horizontal pass keeps (d/dx, d2/dx2, Gaussian); the vertical pass
    // completes the four separable 2D responses. Edge / point strength = gradient magnitudes;
    // feature error = (max(|edge diff|, |point diff|) / sqrt(2))^q_f in [0,1].
    std::vector<float> result(n);
    {
        std::vector<C3> tmp[2] = {std::vector<C3>(n), std::vector<C3>(n)};
        for (int k = 0; k < 2; ++k)
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    C3 a{0, 0, 0};
                    for (int i = -rf; i <= rf; ++i) {
                        const float l =
                            ycc[k][size_t(y) * w + clampi(x + i, w - 1)].x * (1.0f / 116.0f) + 16.0f / 116.0f;
                        a.x += dg[i + rf] * l, a.y += ddg[i + rf] * l, a.z += g[i + rf] * l;
                    }
                    tmp[k][size_t(y) * w + x] = a;
                }
        const float inv_sqrt2 = 1.0f / std::sqrt(2.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                float edge[2], point[2];
                for (int k = 0; k < 2; ++k) {
                    float dx = 0, ddx = 0, dy = 0, ddy = 0;
                    for (int i = -rf; i <= rf; ++i) {
                        const C3& p = tmp[k][size_t(clampi(y + i, h - 1)) * w + x];
                        dx += g[i + rf] * p.x, ddx += g[i + rf] * p.y;
                        dy += dg[i + rf] * p.z, ddy += ddg[i + rf] * p.z;
                    }
                    edge[k] = std::sqrt(dx * dx + dy * dy);
                    point[k] = std::sqrt(ddx * ddx + ddy * ddy);
                }
                const float fd =
                    std::pow(inv_sqrt2 * std::max(std::fabs(edge[0] - edge[1]), std::fabs(point[0] - point[1])), kQf);
                // 6. Final error (paper): colour error raised to 1 - feature error, so feature
                // differences amplify the colour error (for values in (0,1)).
                const size_t idx = size_t(y) * w + x;
                result[idx] = std::pow(colour[idx], 1.0f - fd);
            }
    }

    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < n; ++i)
        if (!mask || (*mask)[i] != 0) sum += result[i], ++count;
    if (count == 0) throw std::invalid_argument("ldr_flip: mask selects no pixel (no mean over an empty set)");
    if (error_map) *error_map = std::move(result);
    return sum / double(count);
}

}  // namespace jade::flip
