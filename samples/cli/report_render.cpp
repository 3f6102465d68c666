// report_render.cpp - the shading steps of `jade report`: the translucency LUT's size and the
// final image.
//
// LUT: a (N + 1) × N table built on the GPU (Renderer, RendererOptions::lut), read back and
// sampled the way the sampler does (linear filtering, clamp-to-edge, in float64) at 100k
// points, against jade::lut_reference; absolute error of f(cos θ, t).
// Images: t_m shading of materials[0] (default lights, framed from +z), error per covered pixel
// in 8-bit sRGB levels (the worst channel, after clamping to [0, 1]) against the image of the
// all-pairs t_m from the 4096-ray AO with a 4097 × 1025 LUT; the notes add PSNR and SSIM (a
// perceptual metric: structure, contrast and luminance over 8×8 windows).
#include "report.hpp"

#include <jade/dev/renderer.hpp>
#include <jade/dev/clock.hpp>
#include <jade/dev/lut.hpp>
#include <jade/render.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

namespace jade::cli::report {
namespace {

const LutLayout kReferenceLut{4097, 1025};

std::string layout_name(const LutLayout& l) { return strf("%ux%u", l.width, l.height); }

/// The layouts of the sweep: (N + 1) × N for each N, then the renderer's default.
std::vector<LutLayout> lut_layouts(const Plan& plan)
{
    std::vector<LutLayout> out;
    for (uint32_t n : plan.lut_sizes) out.push_back({n + 1, n});
    out.push_back(LutLayout{});
    return out;
}

struct LutQuery {
    double cos_theta, t, reference;
};

/// 100k points: a third uniform in t ∈ [0, 40] (past t_max: the clamped region), a third
/// uniform in the LUT's v axis, a third within |cos θ| < 0.02 at t < 2.5e-3, where the kink
/// of max(cos θ, 0) makes interpolation worst. Fixed seed.
std::vector<LutQuery> lut_queries()
{
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double v_max = std::pow(40.0 / LutLayout::kMaxVariance, 0.25);
    std::vector<LutQuery> out;
    for (int k = 0; k < 100000; ++k) {
        double c = 2.0 * unit(rng) - 1.0, t;
        if (k % 3 == 0)
            t = 40.0 * unit(rng);
        else if (k % 3 == 1)
            t = LutLayout::kMaxVariance * std::pow(v_max * unit(rng), 4.0);
        else
            c *= 0.02, t = 2.5e-3 * unit(rng);
        out.push_back({c, t, lut_reference(c, t)});
    }
    return out;
}

/// Linear filtering with clamp-to-edge at the layout's continuous texel coordinates.
double sample_lut(const std::vector<float>& lut, const LutLayout& l, double cos_theta, double t)
{
    auto axis = [](double x, uint32_t n, uint32_t& i0, double& a) {
        x = std::clamp(x, 0.0, double(n - 1));
        i0 = std::min(uint32_t(x), n - 2);
        a = x - i0;
    };
    uint32_t i, j;
    double a, b;
    axis(l.x(cos_theta), l.width, i, a);
    axis(l.y(t), l.height, j, b);
    auto at = [&](uint32_t ii, uint32_t jj) { return double(lut[size_t(jj) * l.width + ii]); };
    return (1 - b) * ((1 - a) * at(i, j) + a * at(i + 1, j)) + b * ((1 - a) * at(i, j + 1) + a * at(i + 1, j + 1));
}

struct LutState {
    std::vector<LutQuery> queries;
};

double srgb(float linear)
{
    const double v = std::clamp(double(linear), 0.0, 1.0);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

/// PSNR (dB) over the covered pixels' sRGB channels in [0, 1] and SSIM (Wang et al. 2004) of
/// the sRGB luma, mean over 8×8 windows (stride 4) whose centre is covered, with the usual
/// constants C1 = (0.01)², C2 = (0.03)². Identical images: PSNR +∞ (written "inf"), SSIM 1.
struct ImageQuality {
    double psnr = 0, ssim = 0;
};

ImageQuality image_quality(const RenderedImage& image, const RenderedImage& reference)
{
    const uint32_t w = reference.width, h = reference.height;
    double se = 0;
    size_t n = 0;
    std::vector<double> a(size_t(w) * h), b(size_t(w) * h);
    for (size_t p = 0; p < a.size(); ++p) {
        const float* x = image.rgba.data() + 4 * p;
        const float* y = reference.rgba.data() + 4 * p;
        double la = 0, lb = 0;
        for (int c = 0; c < 3; ++c) {
            const double u = srgb(x[c]), v = srgb(y[c]), weight = c == 0 ? 0.2126 : c == 1 ? 0.7152 : 0.0722;
            if (y[3] > 0.5f) se += (u - v) * (u - v), ++n;
            la += weight * u, lb += weight * v;
        }
        a[p] = la, b[p] = lb;
    }
    ImageQuality q;
    q.psnr = se == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(double(n) / se);
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double sum = 0;
    size_t windows = 0;
    for (uint32_t y0 = 0; y0 + 8 <= h; y0 += 4)
        for (uint32_t x0 = 0; x0 + 8 <= w; x0 += 4) {
            if (reference.rgba[4 * (size_t(y0 + 4) * w + x0 + 4) + 3] <= 0.5f) continue;
            double ma = 0, mb = 0, vaa = 0, vbb = 0, vab = 0;
            for (uint32_t y = y0; y < y0 + 8; ++y)
                for (uint32_t x = x0; x < x0 + 8; ++x) ma += a[size_t(y) * w + x] / 64, mb += b[size_t(y) * w + x] / 64;
            for (uint32_t y = y0; y < y0 + 8; ++y)
                for (uint32_t x = x0; x < x0 + 8; ++x) {
                    const double da = a[size_t(y) * w + x] - ma, db = b[size_t(y) * w + x] - mb;
                    vaa += da * da / 63, vbb += db * db / 63, vab += da * db / 63;
                }
            sum += (2 * ma * mb + c1) * (2 * vab + c2) / ((ma * ma + mb * mb + c1) * (vaa + vbb + c2));
            ++windows;
        }
    q.ssim = windows ? sum / double(windows) : 1.0;
    return q;
}

std::string quality_note(const RenderedImage& image, const RenderedImage& reference)
{
    const ImageQuality q = image_quality(image, reference);
    return std::isinf(q.psnr) ? strf("PSNR inf, SSIM %.6f", q.ssim) : strf("PSNR %.1f dB, SSIM %.6f", q.psnr, q.ssim);
}

/// Per covered pixel of `reference` (alpha > ½), the worst channel's difference in 8-bit sRGB levels.
std::vector<double> image_errors(const RenderedImage& image, const RenderedImage& reference)
{
    std::vector<double> e;
    for (size_t p = 0; p + 3 < reference.rgba.size(); p += 4) {
        if (reference.rgba[p + 3] <= 0.5f) continue;
        double worst = 0;
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, 255.0 * std::abs(srgb(image.rgba[p + c]) - srgb(reference.rgba[p + c])));
        e.push_back(worst);
    }
    return e;
}

/// What the image steps of one mesh share: the reference image and the default renderer.
struct ImageState {
    RenderedImage reference;
    std::unique_ptr<Renderer> renderer;  ///< default LUT
};

struct Shot {
    Camera camera;
    std::vector<Light> lights;
    RenderSettings settings;
};

Shot make_shot(const Plan& plan, const PreparedMesh& mesh)
{
    Shot s;
    s.camera = Camera::framing(mesh.bbox_min, mesh.bbox_max);
    s.lights = default_lights(s.camera);
    s.settings.width = s.settings.height = plan.image_size;
    s.settings.mode = ShadingMode::Tm;
    s.settings.float32 = true;
    s.settings.transparent_background = true;  // alpha = coverage
    return s;
}

RenderedImage render_with(Renderer& r, const MeshState& st, const std::vector<glm::vec3>& tm, const Plan& plan)
{
    r.set_mesh(st.mesh, tm);
    r.set_material(st.materials.front().material);
    Shot shot = make_shot(plan, st.mesh);
    return r.render(shot.camera, shot.lights, shot.settings);
}

std::unique_ptr<Renderer> make_renderer(Context& ctx, const LutLayout& layout)
{
    RendererOptions o;
    dev::set_study(o, {.lut = layout});
    return std::make_unique<Renderer>(ctx, o);
}

}  // namespace

void add_lut_steps(Session& s, std::vector<Step>& steps)
{
    auto state = std::make_shared<LutState>();
    for (const LutLayout& layout : lut_layouts(s.plan)) {
        steps.push_back({"LUT " + layout_name(layout),
                         [&s, state, layout] {
            if (state->queries.empty()) state->queries = lut_queries();
            auto t0 = Clock::now();
            auto renderer = make_renderer(s.context, layout);
            std::vector<float> lut = dev::read_lut(*renderer);
            const double ms = ms_since(t0);
            std::vector<double> e;
            e.reserve(state->queries.size());
            for (const LutQuery& q : state->queries)
                e.push_back(std::abs(sample_lut(lut, layout, q.cos_theta, q.t) - q.reference));
            Row r{"(any)", "lut_size", layout_name(layout),       "linear filtering (f)",
                  kNaN,    ms,         error_stats(std::move(e)), ""};
            r.notes = strf(
                "absolute, vs lut_reference at %zu points; %.0f KB; wall_ms: build and read back%s",
                state->queries.size(), 4.0 * layout.width * layout.height / 1024.0,
                layout.width == LutLayout{}.width && layout.height == LutLayout{}.height ? "; the default size" : "");
            return r;
                         }});
    }
}

void add_image_steps(Session& s, MeshState& st, std::vector<Step>& steps)
{
    auto state = std::make_shared<ImageState>();
    steps.push_back({"image reference (all-pairs t_m, LUT " + layout_name(kReferenceLut) + ")", [&s, &st, state] {
                         auto renderer = make_renderer(s.context, kReferenceLut);
                         state->reference = render_with(*renderer, st, st.materials.front().exact, s.plan);
                         state->renderer = make_renderer(s.context, LutLayout{});
                         Row r;
                         r.notes = strf("%ux%u, GPU %s", state->reference.width, state->reference.height,
                                        format_ms(state->reference.gpu_ms).c_str());
                         return r;
                     }});
    for (const char* q : {"draft", "default", "high"}) {
        steps.push_back({std::string("image, preset ") + q, [&s, &st, state, q] {
                             const BakeResult& bake = st.quality.at(q);
                             RenderedImage img = render_with(*state->renderer, st, bake.tm, s.plan);
                             Row r{st.label,
                                   "image",
                                   q,
                                   "t_m shading (" + st.materials.front().label + ")",
                                   bake.timings.gpu_total_ms,
                                   bake.timings.wall_ms,
                                   error_stats(image_errors(img, state->reference)),
                                   ""};
                             r.notes = strf("8-bit sRGB levels per covered pixel, %ux%u, default LUT; gpu_ms/wall_ms: "
                                            "the bake (draw: %s GPU); ",
                                            img.width, img.height, format_ms(img.gpu_ms).c_str()) +
                                       quality_note(img, state->reference);
                             return r;
                         }});
    }
    const auto layouts = lut_layouts(s.plan);
    for (size_t k = 0; k < layouts.size(); ++k) {
        const LutLayout layout = layouts[k];
        const bool last = k + 1 == layouts.size();
        steps.push_back({"image, LUT " + layout_name(layout), [&s, &st, state, layout, last] {
                             auto t0 = Clock::now();
                             auto renderer = make_renderer(s.context, layout);
                             RenderedImage img = render_with(*renderer, st, st.materials.front().exact, s.plan);
                             Row r{st.label,
                                   "image_lut",
                                   layout_name(layout),
                                   "t_m shading (" + st.materials.front().label + ")",
                                   img.gpu_ms,
                                   ms_since(t0),
                                   error_stats(image_errors(img, state->reference)),
                                   ""};
                             r.notes = strf("8-bit sRGB levels per covered pixel, %ux%u, all-pairs t_m; gpu_ms: the "
                                            "draw; wall_ms: LUT build + draw; ",
                                            img.width, img.height) +
                                       quality_note(img, state->reference);
                             if (last) *state = {};  // release the renderers before the context goes
                             return r;
                         }});
    }
}

}  // namespace jade::cli::report
