// Does it look right? Jade's shading modes against the committed path-traced references
// (tools/groundtruth: Mitsuba 3, a homogeneous medium behind a rough dielectric; 3 training and
// 2 validation meshes, front, side and back light), through `jade fidelity` with validation on.
// The numbers and what does not meet the targets yet: docs/fidelity.md.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <map>

using namespace jade;

namespace {

const nlohmann::json& scenes()
{
    static nlohmann::json doc = [] {
        const auto out = test::out("fidelity.json");
        const auto refs = test::data("../../tools/groundtruth/references");
        const auto r =
            test::run_cli({"fidelity", "--validation", "--references", refs.string(), "--json", out.string()});
        EXPECT_EQ(r.exit_code, 0) << r.output;
        std::ifstream f(out);
        return f ? nlohmann::json::parse(f)["scenes"] : nlohmann::json::array();
    }();
    return doc;
}

double flip(const nlohmann::json& s, const char* mode) { return s[mode]["flip_masked"].get<double>(); }

void back_lit_scenes_are_far_closer_than_lambert_and_curvature()
{
    ASSERT_EQ(scenes().size(), 39u) << "27 training and 12 validation scenes are committed";
    int back = 0, thirty_percent = 0, helped = 0, closer_than_curvature = 0;
    double sum_ours = 0, sum_lambert = 0;
    for (const auto& s : scenes()) {
        if (s["light"] != "back") continue;
        ++back;
        EXPECT_LT(flip(s, "default"), flip(s, "lambert")) << s["scene"];
        closer_than_curvature += flip(s, "default") < flip(s, "curvature") ? 1 : 0;
        helped += flip(s, "default") <= flip(s, "tm") ? 1 : 0;
        thirty_percent += flip(s, "default") <= 0.7 * flip(s, "lambert") ? 1 : 0;
        sum_ours += flip(s, "default"), sum_lambert += flip(s, "lambert");
    }
    EXPECT_EQ(back, 13);
    EXPECT_EQ(closer_than_curvature, 13);
    EXPECT_EQ(thirty_percent, 13) << "measured: dragon_marble_back, the nearest, at 0.67 of Lambert";
    EXPECT_GE(helped, 12) << "transmission and the boundary transmittance make no back-lit scene worse than tm but "
                             "dragon_marble_back (0.351 against 0.348)";
    EXPECT_LE(sum_ours, 0.6 * sum_lambert) << "mean masked FLIP, back light: measured 0.382 against Lambert's 0.735";
}

void front_and_side_lit_scenes_are_closer_than_lambert_and_curvature_everywhere()
{
    ASSERT_EQ(scenes().size(), 39u);
    std::map<std::string, double> ours, lambert, curvature;
    int closer = 0, closer_than_curvature = 0, lit = 0;
    for (const auto& s : scenes()) {
        if (s["light"] == "back") continue;
        const std::string light = s["light"];
        ours[light] += flip(s, "default"), lambert[light] += flip(s, "lambert"),
            curvature[light] += flip(s, "curvature");
        closer += flip(s, "default") < flip(s, "lambert") ? 1 : 0;
        closer_than_curvature += flip(s, "default") < flip(s, "curvature") ? 1 : 0;
        ++lit;
    }
    for (const char* light : {"front", "side"}) {
        EXPECT_LT(ours[light], curvature[light]) << light;
        EXPECT_LT(curvature[light], lambert[light]) << light;
    }
    EXPECT_EQ(lit, 26);
    EXPECT_EQ(closer, 26);
    EXPECT_EQ(closer_than_curvature, 26);
}

void thin_parts_lit_from_behind_carry_the_path_tracers_radiance()
{
    ASSERT_EQ(scenes().size(), 39u);
    int back = 0, within = 0, nearer = 0;
    for (const auto& s : scenes()) {
        if (s["light"] != "back") continue;
        ++back;
        bool all = true, all_nearer = true;
        for (int c = 0; c < 3; ++c) {
            const double ref = s["thin_reference"][c], ours = s["default"]["thin"][c], poster = s["tm"]["thin"][c];
            all = all && std::abs(ours - ref) <= 0.25 * ref;
            all_nearer = all_nearer && std::abs(ours - ref) < std::abs(poster - ref);
            // Within a factor 6 everywhere (the hand's thin region is 89 pixels of a thumb tip).
            EXPECT_GT(ours, ref / 6.0) << s["scene"] << " channel " << c;
            EXPECT_LT(ours, 6.0 * ref) << s["scene"] << " channel " << c;
        }
        within += all ? 1 : 0;
        nearer += all_nearer ? 1 : 0;
    }
    EXPECT_EQ(back, 13);
    EXPECT_EQ(nearer, 13) << "nearer than the poster's model alone everywhere";
    EXPECT_GE(within, 10) << "measured 10 of 13 within 25 % in every channel: not dragon_wax_back and the two fists "
                             "(docs/fidelity.md)";
}

}  // namespace

// One test, so the 39 scenes are rendered once (ctest runs every TEST in a process of its own).
TEST(Fidelity, AgainstThePathTracedReferences)
{
    ASSERT_EQ(scenes().size(), 39u) << "27 training and 12 validation scenes are committed";
    {
        SCOPED_TRACE("back light");
        back_lit_scenes_are_far_closer_than_lambert_and_curvature();
    }
    {
        SCOPED_TRACE("front and side light");
        front_and_side_lit_scenes_are_closer_than_lambert_and_curvature_everywhere();
    }
    {
        SCOPED_TRACE("thin parts");
        thin_parts_lit_from_behind_carry_the_path_tracers_radiance();
    }
}
