// The translucency LUT built on the GPU against the float64 reference jade::lut_reference:
// every texel, and the error of the linearly filtered LUT over the
// whole domain, for the default size and a table of others.
#include "gpu_fixture.hpp"

#include <jade/dev/renderer.hpp>
#include <jade/dev/lut.hpp>
#include <jade/render.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace jade;
using jade::test::GpuTest;

namespace {

class Lut : public GpuTest {};

struct Query {
    double cos_theta, t, reference;
};

// ~100k points over the whole domain: uniform in t ∈ [0, 40], uniform in the LUT's own axis
// (most of them at small t, where f changes fastest), and packed around the kink cos θ = 0 at
// t < 2.5e-3, where bilinear interpolation is worst. Reference values are computed once.
const std::vector<Query>& queries()
{
    static const std::vector<Query> q = [] {
        std::mt19937_64 rng(42);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::vector<Query> out;
        const double v_max = std::pow(40.0 / LutLayout::kMaxVariance, 0.25);
        for (int k = 0; k < 100000; ++k) {
            double c = 2.0 * unit(rng) - 1.0, t;
            if (k % 3 == 0)
                t = 40.0 * unit(rng);
            else if (k % 3 == 1)
                t = LutLayout::kMaxVariance * std::pow(v_max * unit(rng), 4.0);
            else
                c *= 0.02, t = LutLayout::kMaxVariance * std::pow(0.1 * unit(rng), 4.0);
            if (k == 0) t = 40.0, c = -1.0;  // the corners and the clamped region
            if (k == 1) t = 0.0, c = 1.0;
            out.push_back({c, t, lut_reference(c, t)});
        }
        return out;
    }();
    return q;
}

// What mesh.frag does: continuous texel indices in float32, x = cos θ·(W − 1)/2 + (W − 1)/2 and
// y = (t/t_max)^¼·(H − 1) (clamped to the last row), then bilinear interpolation of the quad
// (i, j) … (i + 1, j + 1) with i = min(⌊x⌋, W − 2), j = min(⌊y⌋, H − 2), weights x − i, y − j.
double sample(const std::vector<float>& lut, const LutLayout& layout, double cos_theta, double t)
{
    const float W = float(layout.width), H = float(layout.height);
    const float x = std::clamp(float(cos_theta), -1.0f, 1.0f) * (0.5f * (W - 1.0f)) + 0.5f * (W - 1.0f);
    const float y = std::min(std::sqrt(std::sqrt(float(t) * float(1.0 / LutLayout::kMaxVariance))), 1.0f) * (H - 1.0f);
    const float i = std::min(std::floor(x), W - 2.0f), j = std::min(std::floor(y), H - 2.0f);
    const double a = double(x - i), b = double(y - j);
    auto texel = [&](float ii, float jj) { return double(lut[size_t(jj) * layout.width + size_t(ii)]); };
    return (1 - b) * ((1 - a) * texel(i, j) + a * texel(i + 1, j)) +
           b * ((1 - a) * texel(i, j + 1) + a * texel(i + 1, j + 1));
}

struct MaxError {
    double error = 0, cos_theta = 0, t = 0;
};
MaxError interpolation_error(const std::vector<float>& lut, const LutLayout& layout)
{
    MaxError e;
    for (const Query& q : queries()) {
        const double d = std::abs(sample(lut, layout, q.cos_theta, q.t) - q.reference);
        if (d > e.error) e = {d, q.cos_theta, q.t};
    }
    return e;
}

}  // namespace

TEST_F(Lut, EveryTexelMatchesFloat64Reference)
{
    Renderer renderer(context());
    const LutLayout& layout = dev::lut_layout(renderer);
    const std::vector<float> lut = dev::read_lut(renderer);
    ASSERT_EQ(lut.size(), size_t(layout.width) * layout.height);
    double worst = 0;
    uint32_t wi = 0, wj = 0;
    for (uint32_t j = 0; j < layout.height; ++j)
        for (uint32_t i = 0; i < layout.width; ++i) {
            const double d = std::abs(double(lut[size_t(j) * layout.width + i]) -
                                      lut_reference(layout.cos_theta(i), layout.variance(j)));
            if (d > worst) worst = d, wi = i, wj = j;
        }
    std::printf("LUT %ux%u: max texel error vs float64 %.3g at cos θ = %.6f, t = %.6g\n", layout.width, layout.height,
                worst, layout.cos_theta(wi), layout.variance(wj));
    EXPECT_LE(worst, 2e-6);
    // Row 0 is Lambert exactly, and the kink sits on the centre texel.
    for (uint32_t i = 0; i < layout.width; ++i)
        ASSERT_EQ(lut[i], float(std::max(layout.cos_theta(i), 0.0))) << "texel " << i;
    EXPECT_EQ(layout.cos_theta((layout.width - 1) / 2), 0.0);
}

TEST_F(Lut, DefaultSizeInterpolatesWithin1e4)
{
    Renderer renderer(context());
    const LutLayout& layout = dev::lut_layout(renderer);
    MaxError e = interpolation_error(dev::read_lut(renderer), layout);
    std::printf("LUT %ux%u: max error of the filtered LUT over %zu points %.3g (at cos θ = %.5f, t = %.3g)\n",
                layout.width, layout.height, queries().size(), e.error, e.cos_theta, e.t);
    EXPECT_LE(e.error, 1e-4);
}

TEST_F(Lut, ZeroVarianceIsLambertUnderLinearFiltering)
{
    Renderer renderer(context());
    const LutLayout& layout = dev::lut_layout(renderer);
    const std::vector<float> lut = dev::read_lut(renderer);
    double worst = 0;
    for (int k = 0; k <= 20000; ++k) {
        const double c = -1.0 + 2.0 * k / 20000.0;
        worst = std::max(worst, std::abs(sample(lut, layout, c, 0.0) - std::max(c, 0.0)));
    }
    EXPECT_LE(worst, 1e-6);  // max(cos θ, 0) is linear in cos θ between texels, kink on a texel
}

// The table docs/shading.md quotes: error against size (the first row is the default).
TEST_F(Lut, ErrorTableBySize)
{
    struct Row {
        LutLayout size;
        double documented;  // docs/shading.md, to three digits
    };
    const Row rows[] = {{{}, 9.63e-5},          {{1025, 257}, 1.29e-4}, {{1281, 257}, 1.02e-4},
                        {{1409, 193}, 1.01e-4}, {{1409, 257}, 9.38e-5}, {{1537, 129}, 1.13e-4},
                        {{1537, 193}, 9.22e-5}, {{1537, 257}, 8.74e-5}, {{2049, 129}, 9.26e-5}};
    std::printf("%-12s %-14s %s\n", "LUT size", "max error", "at (cos θ, t)");
    for (const Row& row : rows) {
        RendererOptions o;
        dev::set_study(o, {.lut = row.size});
        Renderer renderer(context(), o);
        MaxError e = interpolation_error(dev::read_lut(renderer), row.size);
        std::printf("%4ux%-7u %-14.3g (%.4f, %.3g)\n", row.size.width, row.size.height, e.error, e.cos_theta, e.t);
        // The table's figure, to three digits: a margin of half its last digit.
        EXPECT_NEAR(e.error, row.documented, 0.006 * row.documented) << row.size.width << "x" << row.size.height;
    }
}

TEST_F(Lut, BadSizeIsAnError)
{
    RendererOptions o;
    dev::set_study(o, {.lut = {1024, 257}});  // even width: cos θ = 0 would fall between texels
    EXPECT_THROW({ Renderer r(context(), o); }, Error);
    dev::set_study(o, {.lut = {1025, 1}});
    EXPECT_THROW({ Renderer r(context(), o); }, Error);
}
