// `jade report`: a --tiny run on a small procedural scene (a
// ball resting over a slab, so AO is not zero) writes report.csv and summary.md with the
// expected columns and tables, and its errors fall with more rays and a smaller ε.
#include "test_support.hpp"

#include <jade/mesh.hpp>
#include <jade/dev/mesh.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace jade;
namespace fs = std::filesystem;

namespace {

// A ball of radius 0.4 hovering 0.05 above a 2 × 2 × 0.2 slab: ~900 vertices, occluded where
// they face each other.
fs::path write_scene()
{
    TriangleMesh slab = dev::procedural::box({-1.0f, -1.0f, -0.2f}, {1.0f, 1.0f, 0.0f}, 8);
    TriangleMesh ball = procedural::sphere(0.4f, 14, 28);
    std::ostringstream off;
    off << "OFF\n"
        << slab.positions.size() + ball.positions.size() << " " << slab.triangle_count() + ball.triangle_count()
        << " 0\n";
    for (auto p : slab.positions) off << p.x << " " << p.y << " " << p.z << "\n";
    for (auto p : ball.positions) off << p.x << " " << p.y << " " << p.z + 0.45f << "\n";
    auto faces = [&](const TriangleMesh& m, size_t offset) {
        for (size_t t = 0; t < m.triangle_count(); ++t)
            off << "3 " << m.indices[3 * t] + offset << " " << m.indices[3 * t + 1] + offset << " "
                << m.indices[3 * t + 2] + offset << "\n";
    };
    faces(slab, 0);
    faces(ball, slab.positions.size());
    fs::path path = test::out("report/scene.off");
    std::ofstream(path) << off.str();
    return path;
}

struct CsvRow {
    std::string mesh, knob, value, method;
    double gpu_ms, wall_ms, rms, p99, max;
    std::string notes;
};

// One CSV line (RFC 4180 quoting; no field of report.csv spans lines).
std::vector<std::string> fields(const std::string& line)
{
    std::vector<std::string> v(1);
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        if (quoted && line[i] == '"' && i + 1 < line.size() && line[i + 1] == '"')
            v.back() += '"', ++i;
        else if (line[i] == '"')
            quoted = !quoted;
        else if (!quoted && line[i] == ',')
            v.emplace_back();
        else
            v.back() += line[i];
    }
    return v;
}

std::vector<CsvRow> read_rows(const fs::path& path, std::string& header)
{
    std::ifstream f(path);
    std::getline(f, header);
    std::vector<CsvRow> rows;
    for (std::string line; std::getline(f, line);) {
        const auto v = fields(line);
        EXPECT_EQ(v.size(), 10u) << line;
        if (v.size() != 10) continue;
        auto d = [](const std::string& s) { return s.empty() ? -1.0 : std::stod(s); };
        rows.push_back({v[0], v[1], v[2], v[3], d(v[4]), d(v[5]), d(v[6]), d(v[7]), d(v[8]), v[9]});
    }
    return rows;
}

std::string read_text(const fs::path& path)
{
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// The rows of `knob` with `method`, in CSV order.
std::vector<CsvRow> series(const std::vector<CsvRow>& rows, const std::string& knob, const std::string& method)
{
    std::vector<CsvRow> out;
    for (const auto& r : rows)
        if (r.knob == knob && r.method == method) out.push_back(r);
    return out;
}

}  // namespace

TEST(Report, TinyRunWritesCsvSummaryAndErrorsFallWithEffort)
{
    const fs::path scene = write_scene();
    const fs::path dir = scene.parent_path() / "tiny";
    fs::remove_all(dir);
    auto r = test::run_cli({"report", scene.string(), "--out", dir.string(), "--tiny", "--sample", "120", "--no-plot"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("[1/"), std::string::npos) << "progress lines with an index: " << r.output;
    ASSERT_TRUE(fs::exists(dir / "report.csv"));
    ASSERT_TRUE(fs::exists(dir / "summary.md"));
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_NE(e.path().extension(), ".tmp") << "left over: " << e.path();

    std::string header;
    const auto rows = read_rows(dir / "report.csv", header);
    EXPECT_EQ(header, "mesh,knob,value,method,gpu_ms,wall_ms,err_rms,err_p99,err_max,notes");
    std::map<std::string, int> knobs;
    for (const auto& row : rows) ++knobs[row.knob];
    for (const char* k : {"ao_rays", "ao_float64", "tm_reference", "tm_exact", "tm_epsilon", "tm_auto", "quality",
                          "image", "image_lut", "lut_size"})
        EXPECT_GT(knobs[k], 0) << "no row for " << k;

    // AO: RMS falls with the ray count (both samplings); low-discrepancy beats i.i.d.
    for (const char* method : {"low-discrepancy (d=0.1)", "i.i.d. (d=0.1)"}) {
        const auto ao = series(rows, "ao_rays", method);
        ASSERT_EQ(ao.size(), 3u) << method;
        for (size_t k = 1; k < ao.size(); ++k) {
            EXPECT_LT(ao[k].rms, ao[k - 1].rms) << method << " at " << ao[k].value << " rays";
            EXPECT_GT(ao[k].gpu_ms, 0.0);
        }
        EXPECT_GT(ao.front().rms, 0.01) << "the scene must be occluded for the AO rows to mean anything";
    }
    EXPECT_LT(series(rows, "ao_rays", "low-discrepancy (d=0.1)").back().rms,
              series(rows, "ao_rays", "i.i.d. (d=0.1)").back().rms);

    // t_m: the error falls (within float32 noise) as ε falls, and stays within the documented bound.
    const auto eps = series(rows, "tm_epsilon", "clustered (burley d=5%)");
    ASSERT_EQ(eps.size(), 3u);
    for (size_t k = 1; k < eps.size(); ++k)
        EXPECT_LE(eps[k].max, eps[k - 1].max * 1.2 + 2e-6) << "eps " << eps[k].value;
    EXPECT_LT(eps.front().max, 0.05);
    const auto exact = series(rows, "tm_exact", "exact (burley d=5%)");
    ASSERT_GE(exact.size(), 1u);  // and a float64-sums row where the device has shaderFloat64
    EXPECT_EQ(exact[0].value, "all pairs");
    EXPECT_LT(exact[0].max, 1e-4) << "float32 with compensated summation against float64";

    // float64 sums (devices with shaderFloat64, lavapipe among them) err no more than float32's.
    for (const auto& row : rows)
        if (row.knob == "tm_exact" && row.value == "all pairs, float64 sums") EXPECT_LT(row.max, 1e-4);

    // Final images carry PSNR and SSIM; the high preset's image is closer to the reference than draft's.
    auto psnr_of = [&](const std::string& preset) {
        for (const auto& row : rows)
            if (row.knob == "image" && row.value == preset) {
                const auto at = row.notes.find("PSNR ");
                EXPECT_NE(row.notes.find("SSIM "), std::string::npos) << row.notes;
                return at == std::string::npos ? 0.0 : std::strtod(row.notes.c_str() + at + 5, nullptr);
            }
        ADD_FAILURE() << "no image row for " << preset;
        return 0.0;
    };
    EXPECT_GT(psnr_of("draft"), 30.0) << "PSNR in dB against the reference image";
    EXPECT_GE(psnr_of("high"), psnr_of("draft"));

    // The LUT's error falls with its size.
    const auto lut = series(rows, "lut_size", "linear filtering (f)");
    ASSERT_GE(lut.size(), 2u);
    EXPECT_LT(lut[1].max, lut[0].max);

    // Deformation: a refit traces the same rays over the same triangles as a rebuild, so its AO
    // is identical; an amortised re-bake lags behind the moving mesh, so it errs.
    const auto refit_ao = series(rows, "deform_ao", "refit (burley d=5%)");
    const auto lagging_ao = series(rows, "deform_ao", "amortised (burley d=5%)");
    ASSERT_EQ(refit_ao.size(), 1u);
    ASSERT_EQ(lagging_ao.size(), 1u);
    EXPECT_EQ(refit_ao[0].max, 0.0) << "refit AO against the from-scratch bake";
    EXPECT_GT(lagging_ao[0].rms, 0.0) << "an amortised re-bake of a moving mesh should lag";
    EXPECT_LT(lagging_ao[0].rms, 0.1);
    const auto refit_tm = series(rows, "deform_tm", "refit (burley d=5%)");
    ASSERT_EQ(refit_tm.size(), 1u);
    EXPECT_LT(refit_tm[0].max, 2e-2) << "refit and rebuild t_m";

    const std::string md = read_text(dir / "summary.md");
    for (const char* s : {"## Recommended settings", "### draft", "### default", "### high",
                          "| rays | method | GPU | wall | RMS | p99 | max |", "Translucency LUT size", "120 vertices",
                          "### Deformation: refit, rebuild, amortised re-bakes"})
        EXPECT_NE(md.find(s), std::string::npos) << "summary.md lacks: " << s;
}

TEST(Report, UsageErrorsNameTheFlag)
{
    auto r = test::run_cli({"report", "--tiny"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
    r = test::run_cli({"report", "--out", test::out("report/never").string(), "--tiny", "--quick"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--quick"), std::string::npos) << r.output;
    r = test::run_cli({"report", "--out", test::out("report/never").string(), "--sample", "0"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--sample"), std::string::npos) << r.output;
}
