// Does it look right? Jade's shading modes against the committed path-traced references
// (tools/groundtruth: Mitsuba 3, a homogeneous medium behind a rough dielectric, 3 training and
// 2 validation meshes, front, side and back light), through `jade fidelity` with validation on.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

using namespace jade;

namespace {

const nlohmann::json& scenes()
{
    static nlohmann::json doc = [] {
        const auto out = test::out("fidelity.json");
        const auto refs = test::data("../../tools/groundtruth/references");
        const auto r = test::run_cli({"fidelity", "--validation", "--references", refs.string(), "--json", out.string()});
        EXPECT_EQ(r.exit_code, 0) << r.output;
        std::ifstream f(out);
        return f ? nlohmann::json::parse(f) : nlohmann::json::object();
    }();
    return doc;
}

}  // namespace

TEST(Fidelity, EveryReferenceSceneIsCloserThanLambertAndCurvature)
{
    ASSERT_TRUE(scenes().contains("scenes")) << "jade fidelity wrote no JSON";
    const auto& list = scenes()["scenes"];
    ASSERT_EQ(list.size(), 39u) << "27 training and 12 validation scenes are committed";
    for (const auto& s : list) {
        const double ours = s["default"]["flip_masked"], lambert = s["lambert"]["flip_masked"],
                     curvature = s["curvature"]["flip_masked"];
        EXPECT_LT(ours, lambert) << s["scene"];
        EXPECT_LT(ours, curvature) << s["scene"];
        if (s["light"] == "back") EXPECT_LE(ours, 0.7 * lambert) << s["scene"] << ": at least 30 % below Lambert when back-lit";
    }
}

TEST(Fidelity, ThinPartsLitFromBehindCarryThePathTracersRadiance)
{
    ASSERT_TRUE(scenes().contains("scenes"));
    int checked = 0;
    for (const auto& s : scenes()["scenes"]) {
        if (s["light"] != "back") continue;
        for (int c = 0; c < 3; ++c) {
            const double ref = s["thin_reference"][c], ours = s["default"]["thin"][c];
            EXPECT_NEAR(ours, ref, 0.25 * ref) << s["scene"] << " channel " << c;
        }
        ++checked;
    }
    EXPECT_EQ(checked, 13);
}
