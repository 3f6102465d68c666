#include "bake/grid_field.hpp"

#include "bake/near_field.hpp"

#include <jade/dev/material.hpp>
#include <jade/error.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace jade::bake {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr size_t kFitSamples = 256;  // radii of the fit, log-spaced over [r_cut, r_max]
// The fit ignores what lies beyond this tail of the profile (its share of t_m).
constexpr double kNegligibleTail = 1e-7;
// r_cut in mean vertex spacings per unit of resolution: near lists of ~π·(2.5·resolution)²
// entries on an even mesh (44 at resolution 1.5, 79 at 2), the disk pairs among them.
constexpr double kCutSpacingsPerResolution = 2.5;
// A deforming mesh may gather up to this many times a cell's rest mass before the fixed-point
// sums could wrap (grid_splat_body.glsl).
constexpr double kSplatHeadroom = 2.0;

// Gaussian g normalised as a surface kernel, times 2πr² (t_m per unit of ln r).
double basis(double sigma, double r) { return (r * r) / (sigma * sigma) * std::exp(-r * r / (2 * sigma * sigma)); }

// Least squares on the columns `active` of A (modified Gram–Schmidt QR); other entries 0.
std::vector<double> least_squares(const std::vector<double>& A, const std::vector<double>& b, size_t rows, size_t cols,
                                  const std::vector<bool>& active)
{
    std::vector<size_t> idx;
    for (size_t j = 0; j < cols; ++j)
        if (active[j]) idx.push_back(j);
    const size_t k = idx.size();
    std::vector<double> Q(rows * k), R(k * k, 0.0), x(cols, 0.0);
    for (size_t c = 0; c < k; ++c)
        for (size_t i = 0; i < rows; ++i) Q[i * k + c] = A[i * cols + idx[c]];
    for (size_t c = 0; c < k; ++c) {
        for (size_t p = 0; p < c; ++p) {
            double dot = 0;
            for (size_t i = 0; i < rows; ++i) dot += Q[i * k + p] * Q[i * k + c];
            R[p * k + c] = dot;
            for (size_t i = 0; i < rows; ++i) Q[i * k + c] -= dot * Q[i * k + p];
        }
        double norm = 0;
        for (size_t i = 0; i < rows; ++i) norm += Q[i * k + c] * Q[i * k + c];
        norm = std::sqrt(norm);
        R[c * k + c] = norm;
        if (norm > 0)
            for (size_t i = 0; i < rows; ++i) Q[i * k + c] /= norm;
    }
    std::vector<double> y(k, 0.0);
    for (size_t c = 0; c < k; ++c)
        for (size_t i = 0; i < rows; ++i) y[c] += Q[i * k + c] * b[i];
    for (size_t c = k; c-- > 0;) {
        double s = y[c];
        for (size_t p = c + 1; p < k; ++p) s -= R[c * k + p] * x[idx[p]];
        // A column dependent on the others (to rounding) gets no weight.
        x[idx[c]] = R[c * k + c] > 1e-12 * R[0] ? s / R[c * k + c] : 0.0;
    }
    return x;
}

}  // namespace

std::vector<double> nnls(const std::vector<double>& A, const std::vector<double>& b, size_t rows, size_t cols)
{
    std::vector<double> x(cols, 0.0);
    std::vector<bool> active(cols, false);
    double scale = 0;
    for (double v : b) scale = std::max(scale, std::abs(v));
    for (size_t iter = 0; iter < 4 * cols + 8; ++iter) {
        // Gradient of the residual; the most promising inactive column joins.
        std::vector<double> residual(b);
        for (size_t i = 0; i < rows; ++i)
            for (size_t j = 0; j < cols; ++j) residual[i] -= A[i * cols + j] * x[j];
        size_t best = cols;
        double best_w = 1e-12 * scale;
        for (size_t j = 0; j < cols; ++j) {
            if (active[j]) continue;
            double w = 0;
            for (size_t i = 0; i < rows; ++i) w += A[i * cols + j] * residual[i];
            if (w > best_w) best_w = w, best = j;
        }
        if (best == cols) break;
        active[best] = true;
        // Inner loop: step towards the unconstrained solution on the active set, dropping the
        // columns that would turn negative.
        for (size_t inner = 0; inner < cols + 1; ++inner) {
            std::vector<double> z = least_squares(A, b, rows, cols, active);
            bool feasible = true;
            for (size_t j = 0; j < cols; ++j) feasible = feasible && (!active[j] || z[j] > 0);
            if (feasible) {
                x = z;
                break;
            }
            double alpha = 1;
            for (size_t j = 0; j < cols; ++j)
                if (active[j] && z[j] <= 0) alpha = std::min(alpha, x[j] / (x[j] - z[j]));
            for (size_t j = 0; j < cols; ++j) {
                x[j] += alpha * (z[j] - x[j]);
                if (active[j] && x[j] <= 1e-300) active[j] = false, x[j] = 0;
            }
        }
    }
    return x;
}

double SmoothFit::S(int channel, double r) const
{
    double s = 0;
    for (size_t g = 0; g < sigma.size(); ++g)
        s += weight[g][channel] / (2 * kPi * sigma[g] * sigma[g]) * std::exp(-r * r / (2 * sigma[g] * sigma[g]));
    return s;
}

uint32_t levels_per_octave(double resolution) { return resolution >= kTwoLevelsPerOctaveFrom ? 2 : 1; }

SmoothFit fit_smooth_part(const Material& material, int channels, double r_cut, double r_max, double resolution,
                          uint32_t per_octave)
{
    const double ratio = std::pow(2.0, 1.0 / double(per_octave));  // between consecutive Gaussians
    SmoothFit fit;
    double extent = 0;  // beyond it the profiles hold less than kNegligibleTail
    for (int c = 0; c < channels; ++c)
        extent = std::max(extent, dev::radius_for_tail(material.profile[c], kNegligibleTail));
    const double top = std::min(r_max, extent);
    if (!(top > r_cut)) return fit;  // every source that matters is within r_cut: S = 0
    std::vector<double> sigmas;
    for (double s = r_cut / resolution; s <= 2 * top; s *= ratio) sigmas.push_back(s);
    const size_t rows = kFitSamples, cols = sigmas.size();
    std::vector<double> radii(rows), A(rows * cols);
    for (size_t i = 0; i < rows; ++i) {
        radii[i] = r_cut * std::pow(top / r_cut, double(i) / double(rows - 1));
        for (size_t g = 0; g < cols; ++g) A[i * cols + g] = basis(sigmas[g], radii[i]);
    }
    std::vector<glm::dvec3> weights(cols, glm::dvec3(0));
    for (int c = 0; c < channels; ++c) {
        std::vector<double> b(rows);
        for (size_t i = 0; i < rows; ++i)
            b[i] = dev::profile_value(material.profile[c], radii[i]) * 2 * kPi * radii[i] * radii[i];
        std::vector<double> a = nnls(A, b, rows, cols);
        for (size_t g = 0; g < cols; ++g) weights[g][c] = a[g];
    }
    // Every σ up to the widest with a weight: each grid is restricted from the one two below.
    size_t used = 0;
    for (size_t g = 0; g < cols; ++g) {
        if (channels == 1) weights[g] = glm::dvec3(weights[g][0]);
        if (weights[g][0] > 0 || weights[g][1] > 0 || weights[g][2] > 0) used = g + 1;
    }
    fit.sigma.assign(sigmas.begin(), sigmas.begin() + used);
    fit.weight.assign(weights.begin(), weights.begin() + used);
    // ∫|R − S| 2πr dr = ∫|R − S| 2πr² d(ln r), trapezoids over the fit's radii.
    for (int c = 0; c < 3; ++c) {
        const int pc = channels == 1 ? 0 : c;
        double sum = 0, prev = 0;
        for (size_t i = 0; i < rows; ++i) {
            const double r = radii[i];
            const double e = std::abs(dev::profile_value(material.profile[pc], r) - fit.S(c, r)) * 2 * kPi * r * r;
            if (i > 0) sum += 0.5 * (e + prev) * std::log(radii[i] / radii[i - 1]);
            prev = e;
        }
        fit.residual[c] = sum;
    }
    return fit;
}

uint64_t GridPlan::near_entries(size_t vertices, double margin) const
{
    // Sources within margin·r_cut on a surface of that spacing, plus the disk pairs (~18).
    return uint64_t(double(vertices) *
                    (std::numbers::pi * std::pow(margin * r_cut / spacing, 2) + 18.0 * margin * margin));
}

uint64_t GridPlan::bytes() const
{
    // Four fields per cell (the weight, and times each normal coordinate: grid_splat_body.glsl):
    // fixed-point splats of the two finest grids, every grid's cells, two buffers for the
    // separable passes of the largest.
    uint64_t splat = 0;
    for (size_t g = 0; g < std::min<size_t>(levels.size(), per_octave); ++g)
        splat += uint64_t(levels[g].dims.x) * levels[g].dims.y * levels[g].dims.z;
    const uint64_t cell = 4 * kGridFields;
    return cell * (splat + cells + 2 * max_level_cells) + levels.size() * sizeof(GpuGridLevel) +
           table.size() * sizeof(glm::vec3);
}

namespace {

// The grids of `fit` over the mesh's bounds, or the cube of side `cube_side` about their centre
// (> 0); cells counted before anything is allocated.
std::vector<GpuGridLevel> make_levels(const PreparedMesh& mesh, const SmoothFit& fit, double resolution,
                                      double cube_side, uint64_t& cells, uint64_t& max_cells)
{
    glm::dvec3 lo(mesh.positions[0]), hi(mesh.positions[0]);
    for (size_t i = 0; i < mesh.vertex_count(); ++i) {
        lo = glm::min(lo, glm::dvec3(mesh.positions[i]));
        hi = glm::max(hi, glm::dvec3(mesh.positions[i]));
    }
    if (cube_side > 0) {
        const glm::dvec3 centre = 0.5 * (lo + hi);
        lo = centre - 0.5 * cube_side, hi = centre + 0.5 * cube_side;
    }
    cells = max_cells = 0;
    std::vector<GpuGridLevel> levels;
    for (size_t g = 0; g < fit.sigma.size(); ++g) {
        const double h = fit.sigma[g] / resolution;
        GpuGridLevel l{};
        // Two cells of margin: a cubic B-spline reaches from floor(u) − 1 to floor(u) + 2.
        const glm::dvec3 origin = lo - 2.0 * h;
        l.origin = glm::vec3(origin);
        l.inv_h = float(1.0 / h);
        uint64_t n = 1;
        for (int a = 0; a < 3; ++a) {
            const double cells_on_axis = std::ceil((hi[a] - lo[a]) / h) + 5;
            if (cells_on_axis > 1 << 20) throw Error("t_m grid: more than 2^20 cells along an axis");
            l.dims[a] = uint32_t(cells_on_axis);
            n *= l.dims[a];
        }
        l.offset = uint32_t(std::min<uint64_t>(cells, 0xffffffffu));
        cells += n;
        max_cells = std::max(max_cells, n);
        levels.push_back(l);
        if (cells > (1ull << 31)) return levels;  // the caller coarsens the plan
    }
    for (size_t g = 0; g < levels.size(); ++g) {
        GpuGridLevel& l = levels[g];
        const double h = fit.sigma[g] / resolution;
        l.splat_scale = 1.0f;
        const double sigma_blur = std::sqrt(resolution * resolution - 2.0 / 3.0);  // in cells
        l.half_width = std::min(kGridMaxHalfWidth, uint32_t(std::ceil(4.0 * sigma_blur)));
        double sum = 0;
        for (uint32_t k = 0; k <= l.half_width; ++k) {
            l.blur[k] = float(std::exp(-double(k * k) / (2 * sigma_blur * sigma_blur)));
            sum += (k == 0 ? 1.0 : 2.0) * l.blur[k];
        }
        for (uint32_t k = 0; k <= l.half_width; ++k) l.blur[k] = float(l.blur[k] / sum);
        l.weight = glm::vec3(fit.weight[g] * std::sqrt(2 * kPi) * resolution / (h * h));
    }
    return levels;
}

// Fixed-point scale of the splatted grids: the densest cell's area at rest, ×19 for the
// B-spline's reach (64 cells, weight ≤ (2/3)³ each), with headroom, fills 2^32.
void set_splat_scales(std::vector<GpuGridLevel>& levels, uint32_t per_octave, const PreparedMesh& mesh)
{
    for (size_t g = 0; g < std::min<size_t>(levels.size(), per_octave); ++g) {
        GpuGridLevel& l = levels[g];
        const double h = 1.0 / double(l.inv_h);
        std::vector<float> bins(size_t(l.dims.x) * l.dims.y * l.dims.z, 0.0f);
        double densest = 0;
        for (size_t i = 0; i < mesh.vertex_count(); ++i) {
            const glm::dvec3 u = (glm::dvec3(mesh.positions[i]) - glm::dvec3(l.origin)) / h + 0.5;
            const size_t x = size_t(u.x), y = size_t(u.y), z = size_t(u.z);
            float& bin = bins[(z * l.dims.y + y) * l.dims.x + x];
            bin += mesh.areas[i];
            densest = std::max(densest, double(bin));
        }
        l.splat_scale = float(4294967296.0 / (19.0 * kSplatHeadroom * std::max(densest, 1e-300)));
    }
}

// A sphere holding every vertex (Ritter's: from two far-apart vertices, grown to take in the
// rest), at most ~5 % wider than the smallest. The mesh turned any way about its centre stays
// inside it, so its bounds' widest side never exceeds this diameter.
double bounding_sphere_diameter(const PreparedMesh& mesh)
{
    auto farthest = [&](glm::dvec3 from) {
        glm::dvec3 best = from;
        double d = -1;
        for (const auto& p : mesh.positions)
            if (double e = glm::distance(glm::dvec3(p), from); e > d) d = e, best = glm::dvec3(p);
        return best;
    };
    const glm::dvec3 a = farthest(glm::dvec3(mesh.positions[0])), b = farthest(a);
    glm::dvec3 centre = 0.5 * (a + b);
    double radius = 0.5 * glm::distance(a, b);
    for (const auto& p : mesh.positions) {
        const double d = glm::distance(glm::dvec3(p), centre);
        if (d <= radius) continue;
        const double grown = 0.5 * (radius + d);
        centre += (grown - radius) / d * (glm::dvec3(p) - centre);
        radius = grown;
    }
    return std::min(2.0 * radius, double(mesh.diagonal));
}

}  // namespace

GridPlan plan_grid(const PreparedMesh& mesh, const Material& material, int channels, double resolution, bool deforming,
                   double near_margin)
{
    float max_disk = 0;  // the near lists' widest disk reach: the table covers it
    for (float a : mesh.areas) max_disk = std::max(max_disk, kNearFactor * std::sqrt(a / std::numbers::pi_v<float>));
    const double max_near_reach = near_margin * max_disk;
    if (!(resolution >= 1.5 && resolution <= 4.0))
        throw Error("t_m grid: resolution (cells per Gaussian σ) must be in [1.5, 4], got " +
                    std::to_string(resolution));
    // The mean vertex spacing. A list's length goes as r_cut²/A_i: on a mesh much denser in
    // places the lists there are long (docs/bake.md); a spacing from the densest parts would
    // make the grids of the whole bounds finer instead.
    double area = 0;
    for (float a : mesh.areas) area += a;
    const double spacing = std::sqrt(area / double(mesh.vertex_count()));
    GridPlan plan;
    plan.spacing = spacing;
    plan.per_octave = levels_per_octave(resolution);
    plan.cube_side = deforming ? kDeformingCube * bounding_sphere_diameter(mesh) : 0.0;
    const double r_max = deforming ? std::sqrt(3.0) * plan.cube_side : double(mesh.diagonal);
    const double r_cut = kCutSpacingsPerResolution * resolution * spacing;
    plan.r_cut = r_cut;
    for (int attempt = 0;; ++attempt) {
        plan.fit = fit_smooth_part(material, channels, plan.r_cut, r_max, resolution, plan.per_octave);
        plan.levels = make_levels(mesh, plan.fit, resolution, plan.cube_side, plan.cells, plan.max_level_cells);
        if (attempt == 0) plan.cells_needed = plan.cells;
        if (plan.cells <= kGridMaxCells) break;
        plan.coarsened = true;
        if (plan.r_cut > kGridMaxCoarsening * r_cut) {  // near lists past ~2.25× their length
            plan.feasible = false;
            plan.levels.clear();
            return plan;
        }
        plan.r_cut *= 1.02 * std::cbrt(double(plan.cells) / double(kGridMaxCells));
    }
    set_splat_scales(plan.levels, plan.per_octave, mesh);
    plan.table_range = std::max(plan.r_cut, max_near_reach) * 1.01;
    plan.table.resize(2 * kGridTableSize);
    for (uint32_t k = 0; k < kGridTableSize; ++k) {
        const double r = plan.table_range * k / (kGridTableSize - 1);
        glm::dvec3 S(plan.fit.S(0, r), plan.fit.S(1, r), plan.fit.S(2, r)), Rr;
        for (int c = 0; c < 3; ++c)
            Rr[c] =
                dev::profile_value(material.profile[channels == 1 ? 0 : c], std::max(r, 1e-300 * plan.table_range)) * r;
        plan.table[k] = glm::vec3(S);
        plan.table[kGridTableSize + k] = glm::vec3(Rr - S * r);  // (R − S)·r: finite at 0
    }
    return plan;
}

}  // namespace jade::bake
