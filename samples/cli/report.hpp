// report.hpp - `jade report`: the error of every approximation of the bake and the shading
// against what it costs, measured in one run.
//
// A run is a list of steps (one configuration each: a GPU pass, a reference, a render),
// executed in order; each step may give one CSV row. Steps of one mesh share a MeshState
// (the prepared mesh, the reference AO, the float64 t_m references) that earlier steps fill.
// cmd_report.cpp builds the plan and runs it, report_bake.cpp makes the AO and t_m steps,
// report_render.cpp the LUT and final-image steps, report_write.cpp the CSV and summary.md.
#pragma once

#include "commands.hpp"

#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace jade::cli::report {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Per-item error statistics. NaN where not measured.
struct ErrorStats {
    double rms = kNaN, p99 = kNaN, max = kNaN;
};
/// RMS, 99th percentile (nearest rank) and maximum of `errors` (all NaN when empty).
ErrorStats error_stats(std::vector<double> errors);

/// One configuration: a CSV row. `method` is "algorithm (case)", the case being what the
/// configuration is measured on: the AO max distance, the material, the image.
struct Row {
    std::string mesh, knob, value, method;
    double gpu_ms = kNaN, wall_ms = kNaN;
    ErrorStats err;
    std::string notes;
};

/// What a run sweeps: full (the default), --quick or --tiny (for tests).
struct Plan {
    std::string name;                   ///< "full", "quick", "tiny"
    std::vector<uint32_t> ao_rays;      ///< rays per vertex of the sweep
    uint32_t ao_reference_rays = 4096;  ///< low-discrepancy reference of every AO row
    std::vector<float> ao_distances;    ///< AO max distance, fraction of the diagonal
    float ao_default_distance = 0.1f;   ///< the distance t_m, the presets and images use
    bool iid_every_distance = true;     ///< false: the i.i.d. sweep only at the default distance
    uint32_t ao_agreement_rays = 64;    ///< GPU vs reference_ao (float64) comparison
    std::vector<float> tm_epsilons;     ///< clustered far-field θ (BakeSettings::tm_opening_ratio), descending
    bool tm_jade = true;                ///< the "jade" preset (RGB) besides the grey Burleys
    std::vector<double> tm_grey_d;      ///< grey Burley d, fractions of the diagonal
    uint32_t tm_sample = 300;           ///< vertices the float64 t_m reference runs on
    std::vector<uint32_t> lut_sizes;    ///< LUT N: (N + 1) × N texels
    uint32_t image_size = 512;          ///< final-image rows: width = height
    uint32_t deform_frames = 6;         ///< frames of the twist the deformation rows play
    std::vector<uint32_t> deform_slices{2, 4, 8};  ///< amortised modes (AO and t_m slices)
};

/// "full", "quick" or "tiny"; `epsilons` replaces the default ε list when not empty.
Plan make_plan(const std::string& name, uint32_t tm_sample, std::vector<float> epsilons);

/// One material of the t_m sweep and what the steps found for it.
struct MaterialCase {
    std::string label;  ///< "jade", "burley d=5%"
    Material material;
    std::vector<glm::dvec3> reference;  ///< reference_tm on MeshState::sample (reference AO)
    std::vector<glm::vec3> exact;       ///< the GPU all-pairs t_m on every vertex
};

/// Everything the steps of one mesh share.
struct MeshState {
    std::string label;   ///< file stem, e.g. "bunny00"
    std::string source;  ///< what load_mesh_arg gets
    PreparedMesh mesh;
    std::vector<uint32_t> sample;                      ///< vertices of the float64 t_m reference
    std::map<float, std::vector<float>> ao_reference;  ///< per max distance: 4096-ray GPU AO
    std::vector<MaterialCase> materials;
    std::map<std::string, BakeResult> quality;  ///< end-to-end preset bakes of materials[0], by name
};

/// What every step runs with.
struct Session {
    Context& context;
    Baker& baker;
    const Plan& plan;
};

/// A step returns its row; a row with an empty knob is a status line only (not in the CSV).
struct Step {
    std::string what;
    std::function<Row()> run;
};

// report_bake.cpp
void add_bake_steps(Session& session, MeshState& state, std::vector<Step>& steps);
/// Compiles every bake pipeline on a tiny mesh so no configuration's wall time includes it.
void warm_up(Session& session);

// report_render.cpp
/// The LUT's interpolation error against lut_reference for each size (mesh-independent).
void add_lut_steps(Session& session, std::vector<Step>& steps);
/// Final images of materials[0] with each preset's t_m and each LUT size, against the
/// all-pairs t_m with the 4096-ray AO and the largest LUT.
void add_image_steps(Session& session, MeshState& state, std::vector<Step>& steps);

// report_deform.cpp
/// Refit, rebuild and amortised re-bakes of a twisting mesh (materials[0], 32 AO rays).
void add_deform_steps(Session& session, MeshState& state, std::vector<Step>& steps);

// report_write.cpp
std::string csv(const std::vector<Row>& rows);
/// Reads what csv() wrote (throws jade::Error naming the file and line).
std::vector<Row> read_csv(const std::filesystem::path& path);
std::string summary_markdown(const std::vector<Row>& rows, const Plan& plan, const std::string& device);

/// Splits "algorithm (case)" into its two parts (case empty when there is none).
std::pair<std::string, std::string> split_method(const std::string& method);
/// "%.3g" of x, or "" for NaN.
std::string num(double x);
/// printf into a std::string.
std::string strf(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace jade::cli::report
