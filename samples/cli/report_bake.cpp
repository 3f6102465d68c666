// report_bake.cpp - the AO and t_m steps of `jade report`.
//
// AO: every (rays, sampling, max distance) against a 4096-ray low-discrepancy GPU AO of the
// same distance, absolute per-vertex error. One GPU pass is also compared with reference_ao.
// t_m: from the reference AO (4096 rays, default distance) so that only the far field's
// approximation and float32 are measured, against reference_tm (float64) on a fixed sample of
// vertices, relative per-vertex error (max over the colour channels). Then the presets end to
// end (their own AO), against the same reference.
#include "report.hpp"

#include <jade/dev/context.hpp>
#include <jade/dev/bake.hpp>
#include <jade/dev/clock.hpp>
#include <jade/dev/names.hpp>
#include <jade/dev/reference.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

namespace jade::cli::report {
namespace {

std::string sampling_name(bool low_discrepancy) { return low_discrepancy ? "low-discrepancy" : "i.i.d."; }
std::string distance_case(float d) { return strf("d=%g", double(d)); }

constexpr Quality kQualities[] = {Quality::Draft, Quality::Default, Quality::High};

std::vector<double> ao_errors(const std::vector<float>& ao, const std::vector<float>& reference)
{
    std::vector<double> e(ao.size());
    for (size_t i = 0; i < ao.size(); ++i) e[i] = std::abs(double(ao[i]) - double(reference[i]));
    return e;
}

/// Relative error per sampled vertex, the worst of the colour channels.
std::vector<double> tm_errors(const std::vector<glm::vec3>& tm, const MeshState& st, const MaterialCase& mc)
{
    std::vector<double> e(st.sample.size());
    for (size_t k = 0; k < st.sample.size(); ++k)
        for (int c = 0; c < 3; ++c) {
            const double ref = mc.reference[k][c];
            e[k] = std::max(e[k], std::abs(double(tm[st.sample[k]][c]) - ref) / std::max(ref, 1e-12));
        }
    return e;
}

/// The GPU AO; passes under 300 ms are repeated (3 in all) and the fastest kept.
std::vector<float> timed_ao(Session& s, const MeshState& st, const AoSettings& ao, BakeTimings& best)
{
    std::vector<float> out;
    for (int rep = 0; rep < 3; ++rep) {
        BakeTimings t;
        out = dev::bake_ao(s.baker, st.mesh, ao, &t);
        if (rep == 0 || t.gpu_total_ms < best.gpu_total_ms) best = t;
        if (best.gpu_total_ms >= 300) break;
    }
    return out;
}

std::string mesh_label(const TriangleMesh& m, const std::string& source)
{
    std::string stem = std::filesystem::path(m.name.empty() ? source : m.name).stem().string();
    return stem.empty() ? "mesh" : stem;
}

std::string grey_label(double d) { return strf("burley d=%g%%", 100 * d); }

std::vector<std::string> material_labels(const Plan& plan)
{
    std::vector<std::string> out;
    if (plan.tm_jade) out.push_back("jade");
    for (double d : plan.tm_grey_d) out.push_back(grey_label(d));
    return out;
}

/// The materials of material_labels(), for `mesh`: jade as a 10 cm object, grey Burleys with
/// d a fraction of the diagonal.
std::vector<MaterialCase> material_cases(const Plan& plan, const PreparedMesh& mesh)
{
    std::vector<MaterialCase> out;
    if (plan.tm_jade) out.push_back({"jade", material_preset("jade", 100.0 / mesh.diagonal), {}, {}});
    for (double d : plan.tm_grey_d)
        out.push_back(
            {grey_label(d), burley_material(glm::dvec3(d * mesh.diagonal), glm::vec3(0.8f), grey_label(d)), {}, {}});
    return out;
}

void add_prepare_step(Session& s, MeshState& st, std::vector<Step>& steps)
{
    steps.push_back({"load and prepare", [&s, &st] {
                         TriangleMesh m = load_mesh_arg(st.source);
                         st.mesh = prepare_mesh(m);
                         if (st.label.empty()) st.label = mesh_label(m, st.source);
                         const size_t n = st.mesh.vertex_count(), k = std::min<size_t>(n, s.plan.tm_sample);
                         st.sample.clear();
                         for (size_t i = 0; i < k; ++i)
                             st.sample.push_back(uint32_t(i * n / k));  // evenly spread, fixed
                         st.materials = material_cases(s.plan, st.mesh);
                         Row r;
                         r.notes = strf("\"%s\", %zu vertices, %zu triangles, diagonal %.4g", st.label.c_str(), n,
                                        st.mesh.triangle_count(), double(st.mesh.diagonal));
                         return r;
                     }});
}

void add_ao_steps(Session& s, MeshState& st, std::vector<Step>& steps)
{
    const Plan& plan = s.plan;
    for (float d : plan.ao_distances) {
        AoSettings reference;
        reference.rays = plan.ao_reference_rays;
        reference.max_distance_rel = d;
        steps.push_back({strf("AO reference %u rays %s", reference.rays, distance_case(d).c_str()),
                         [&s, &st, reference] {
            BakeTimings t;
            auto& ao = st.ao_reference[reference.max_distance_rel] = dev::bake_ao(s.baker, st.mesh, reference, &t);
            double mean = 0;
            for (float a : ao) mean += a / double(ao.size());
            Row r;
            r.notes = strf("mean AO %.3f, GPU %s", mean, format_ms(t.gpu_total_ms).c_str());
            return r;
                         }});
        for (bool ld : {true, false}) {
            if (!ld && !plan.iid_every_distance && d != plan.ao_default_distance) continue;
            for (uint32_t rays : plan.ao_rays) {
                AoSettings ao = reference;
                ao.rays = rays;
                ao.low_discrepancy = ld;
                std::string method = sampling_name(ld) + " (" + distance_case(d) + ")";
                steps.push_back({strf("AO %u rays, ", rays) + method, [&s, &st, ao, method] {
                                     BakeTimings t;
                                     auto v = timed_ao(s, st, ao, t);
                                     Row r{st.label,
                                           "ao_rays",
                                           std::to_string(ao.rays),
                                           method,
                                           t.gpu_total_ms,
                                           t.wall_ms,
                                           error_stats(ao_errors(v, st.ao_reference.at(ao.max_distance_rel))),
                                           ""};
                                     r.notes =
                                         strf("absolute; vs %u-ray low-discrepancy GPU AO", s.plan.ao_reference_rays);
                                     return r;
                                 }});
            }
        }
    }
    AoSettings ao;
    ao.rays = plan.ao_agreement_rays;
    ao.max_distance_rel = plan.ao_default_distance;
    steps.push_back({strf("AO %u rays: GPU vs float64 reference_ao", ao.rays), [&s, &st, ao] {
                         BakeTimings t;
                         auto gpu = timed_ao(s, st, ao, t);
                         auto t0 = Clock::now();
                         auto cpu = reference_ao(st.mesh, ao);
                         const double cpu_ms = ms_since(t0);
                         size_t same = 0;
                         for (size_t i = 0; i < gpu.size(); ++i) same += gpu[i] == cpu[i];
                         Row r{st.label,
                               "ao_float64",
                               std::to_string(ao.rays),
                               "GPU vs reference_ao (" + distance_case(ao.max_distance_rel) + ")",
                               t.gpu_total_ms,
                               cpu_ms,
                               error_stats(ao_errors(gpu, cpu)),
                               ""};
                         r.notes =
                             strf("%.3f%% of vertices identical; gpu_ms: GPU pass, wall_ms: float64 CPU reference",
                                  100.0 * double(same) / double(gpu.size()));
                         return r;
                     }});
}

/// A t_m row from `settings` on the reference AO; keeps the all-pairs result.
Step tm_step(Session& s, MeshState& st, size_t k, std::string knob, std::string value, std::string method,
             BakeSettings settings, std::string label)
{
    std::string what = "t_m " + method + " " + value + " (" + label + ")";
    return {what, [&s, &st, k, knob, value, method, settings, label] {
                MaterialCase& mc = st.materials[k];
                const auto& ao = st.ao_reference.at(s.plan.ao_default_distance);
                BakeResult b = dev::bake_tm(s.baker, st.mesh, ao, mc.material, settings);
                Row r{st.label,
                      knob,
                      value,
                      method + " (" + label + ")",
                      b.timings.gpu_total_ms,
                      b.timings.wall_ms,
                      error_stats(tm_errors(b.tm, st, mc)),
                      ""};
                r.notes = strf("relative, vs float64 on %zu vertices", st.sample.size());
                if (dev::study_of(settings).tm_float64_sums) {
                    r.notes += "; float32 pair values, float64 sums";
                } else if (settings.method == TmMethod::Exact) {
                    r.notes += "; float32 with compensated summation";
                    mc.exact = std::move(b.tm);
                } else if (settings.method == TmMethod::Auto) {
                    r.notes += b.method_used == TmMethod::Exact ? std::string("; auto chose exact")
                               : b.method_used == TmMethod::Grid
                                   ? strf("; auto chose grid, resolution %g", double(settings.tm_grid_resolution))
                                   : strf("; auto chose clustered eps=%g", double(settings.tm_opening_ratio));
                }
                return r;
            }};
}

void add_tm_steps(Session& s, MeshState& st, std::vector<Step>& steps)
{
    const Plan& plan = s.plan;
    const auto labels = material_labels(plan);
    for (size_t k = 0; k < labels.size(); ++k) {
        steps.push_back({"t_m float64 reference (" + labels[k] + ")",
                         [&s, &st, k] {
            MaterialCase& mc = st.materials[k];
            auto t0 = Clock::now();
            mc.reference =
                reference_tm(st.mesh, st.ao_reference.at(s.plan.ao_default_distance), mc.material, st.sample);
            const double ms = ms_since(t0);
            Row r{st.label,
                  "tm_reference",
                  std::to_string(st.sample.size()),
                  "float64 CPU reference_tm (" + mc.label + ")",
                  kNaN,
                  ms,
                  {},
                  ""};
            r.notes = strf("on %zu vertices; all vertices would take ~%s", st.sample.size(),
                           format_ms(ms * double(st.mesh.vertex_count()) / double(st.sample.size())).c_str());
            return r;
                         }});
        BakeSettings exact;
        exact.method = TmMethod::Exact;
        steps.push_back(tm_step(s, st, k, "tm_exact", "all pairs", "exact", exact, labels[k]));
        if (dev::device_info(s.context).float64) {  // float32 against float64 accumulation
            dev::set_study(exact, {.tm_float64_sums = true});
            steps.push_back(tm_step(s, st, k, "tm_exact", "all pairs, float64 sums", "exact", exact, labels[k]));
        }
        for (float eps : plan.tm_epsilons) {
            BakeSettings clustered;
            clustered.method = TmMethod::Clustered;
            clustered.tm_opening_ratio = eps;
            steps.push_back(
                tm_step(s, st, k, "tm_epsilon", strf("%g", double(eps)), "clustered", clustered, labels[k]));
        }
        for (Quality q : kQualities) {  // the grid at each preset's resolution
            BakeSettings grid = BakeSettings::preset(q);
            grid.method = TmMethod::Grid;
            steps.push_back(tm_step(s, st, k, "tm_grid_resolution", strf("%g", double(grid.tm_grid_resolution)), "grid",
                                    grid, labels[k]));
        }
        for (Quality q : kQualities)
            steps.push_back(
                tm_step(s, st, k, "tm_auto", dev::quality_name(q), "auto", BakeSettings::preset(q), labels[k]));
    }
}

/// The presets end to end on materials[0]: their own AO (rays, distance) and t_m.
void add_quality_steps(Session& s, MeshState& st, std::vector<Step>& steps)
{
    const std::string label = material_labels(s.plan).front();
    for (Quality q : kQualities) {
        steps.push_back({std::string("bake, preset ") + dev::quality_name(q) + " (" + label + ")",
                         [&s, &st, q] {
            const MaterialCase& mc = st.materials.front();
            BakeSettings settings = BakeSettings::preset(q);
            BakeResult b = s.baker.bake(st.mesh, mc.material, settings);
            Row r{st.label,
                  "quality",
                  dev::quality_name(q),
                  "bake auto (" + mc.label + ")",
                  b.timings.gpu_total_ms,
                  b.timings.wall_ms,
                  error_stats(tm_errors(b.tm, st, mc)),
                  ""};
            const auto& ref_ao = st.ao_reference.at(settings.ao.max_distance_rel);
            ErrorStats ao = error_stats(ao_errors(b.ao, ref_ao));
            r.notes = strf(
                "t_m relative vs float64 on %zu vertices (%u-ray AO); this bake: %u AO rays (AO RMS %.3g), eps=%g, %s",
                st.sample.size(), s.plan.ao_reference_rays, settings.ao.rays, ao.rms, double(settings.tm_opening_ratio),
                dev::tm_method_name(b.method_used));
            st.quality[dev::quality_name(q)] = std::move(b);
            return r;
                         }});
    }
}

}  // namespace

void add_bake_steps(Session& session, MeshState& state, std::vector<Step>& steps)
{
    add_prepare_step(session, state, steps);
    add_ao_steps(session, state, steps);
    add_tm_steps(session, state, steps);
    add_quality_steps(session, state, steps);
}

void warm_up(Session& session)
{
    PreparedMesh tiny = prepare_mesh(procedural::sphere(1.0f, 6, 12));
    Material grey = burley_material(glm::dvec3(0.1), glm::vec3(0.8f)), rgb = material_preset("jade", 50.0);
    for (TmMethod method : {TmMethod::Exact, TmMethod::Clustered, TmMethod::Grid}) {
        BakeSettings s;
        s.ao.rays = 4;
        s.method = method;
        session.baker.bake(tiny, grey, s);
        session.baker.bake(tiny, rgb, s);
    }
}

}  // namespace jade::cli::report
