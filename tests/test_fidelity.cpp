// Does it look right? Jade's shading modes against the committed path-traced references
// (tools/groundtruth: Mitsuba 3, a homogeneous medium behind a rough dielectric; 3 training and
// 2 validation meshes, front, side and back light; and the held-out regimes: skin at a head's
// and a hand's scale, Jensen et al.'s media in millimetres, point lights), through
// `jade fidelity` with validation on. The numbers and what does not meet the targets yet:
// docs/fidelity.md.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <vector>

using namespace jade;

namespace {

const nlohmann::json& scenes()
{
    static nlohmann::json doc = [] {
        const auto out = test::out("fidelity.json");
        const auto refs = test::data("../../tools/groundtruth/references");
        const auto r =
            // Jade's modes and the peers (docs/peers.md); filament-flat and the shadowless columns
            // of the peers' table are left out here to keep the test's time.
            test::run_cli({"fidelity", "--validation", "--references", refs.string(), "--json", out.string(), "--modes",
                           "lambert,curvature,tm,default,filament,separable,burley"});
        EXPECT_EQ(r.exit_code, 0) << r.output;
        std::ifstream f(out);
        return f ? nlohmann::json::parse(f)["scenes"] : nlohmann::json::array();
    }();
    return doc;
}

double flip(const nlohmann::json& s, const char* mode) { return s[mode]["flip_masked"].get<double>(); }

// The scenes of the training and validation sets (the regimes are held out and judged apart).
std::vector<nlohmann::json> committed()
{
    std::vector<nlohmann::json> out;
    for (const auto& s : scenes())
        if (s["set"] != "regimes") out.push_back(s);
    return out;
}

void back_lit_scenes_are_far_closer_than_lambert_and_curvature()
{
    ASSERT_EQ(committed().size(), 39u) << "27 training and 12 validation scenes are committed";
    int back = 0, thirty_percent = 0, helped = 0, closer_than_curvature = 0;
    double sum_ours = 0, sum_lambert = 0;
    for (const auto& s : committed()) {
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
    EXPECT_EQ(thirty_percent, 13) << "measured: elephant_jade_back, the nearest (0.57 of Lambert)";
    EXPECT_GE(helped, 12) << "measured 13";
    EXPECT_LE(sum_ours, 0.50 * sum_lambert) << "mean masked FLIP, back light: measured 0.320 against Lambert's 0.740";
}

void front_and_side_lit_scenes_are_closer_than_lambert_and_curvature_everywhere()
{
    ASSERT_EQ(committed().size(), 39u);
    std::map<std::string, double> ours, lambert, curvature;
    int closer = 0, closer_than_curvature = 0, lit = 0, not_worse_than_tm = 0;
    for (const auto& s : committed()) {
        if (s["light"] == "back") continue;
        const std::string light = s["light"];
        ours[light] += flip(s, "default"), lambert[light] += flip(s, "lambert"),
            curvature[light] += flip(s, "curvature");
        closer += flip(s, "default") < flip(s, "lambert") ? 1 : 0;
        closer_than_curvature += flip(s, "default") < flip(s, "curvature") ? 1 : 0;
        not_worse_than_tm += flip(s, "default") < flip(s, "tm") ? 1 : 0;
        ++lit;
    }
    for (const char* light : {"front", "side"}) {
        EXPECT_LT(ours[light], curvature[light]) << light;
        EXPECT_LT(curvature[light], lambert[light]) << light;
    }
    EXPECT_EQ(lit, 26);
    EXPECT_EQ(closer, 26);
    EXPECT_EQ(closer_than_curvature, 26);
    EXPECT_GE(not_worse_than_tm, 25) << "measured 26";
    EXPECT_LT(ours["front"] / 13.0, 0.17) << "measured 0.165";
    EXPECT_LT(ours["side"] / 13.0, 0.215) << "measured 0.203";
}

void thin_parts_lit_from_behind_carry_the_path_tracers_radiance()
{
    ASSERT_EQ(committed().size(), 39u);
    int back = 0, within = 0, nearer = 0;
    for (const auto& s : committed()) {
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
    // 10 with the slab model of the diffused part; the gather took camel_marble_back out (1.30 /
    // 1.27 / 1.23: its legs are not as wide as the silhouette behind them, docs/fidelity.md).
    EXPECT_GE(within, 9) << "measured 9 of 13 within 25 % in every channel (docs/fidelity.md)";
}

// The peers' table (docs/peers.md): per light class, Jade's default against the Filament peer
// (Filament's subsurface model fed Jade's baked thickness and the medium's colour), mean masked
// FLIP over the 39 committed scenes, and how many scenes of each class the default wins.
void closer_than_the_filament_peer_in_every_light_class()
{
    ASSERT_EQ(committed().size(), 39u);
    std::map<std::string, double> ours, filament;
    std::map<std::string, int> wins;
    for (const auto& s : committed()) {
        const std::string light = s["light"];
        ours[light] += flip(s, "default") / 13.0, filament[light] += flip(s, "filament") / 13.0;
        wins[light] += flip(s, "default") < flip(s, "filament") ? 1 : 0;
    }
    EXPECT_LT(ours["front"], 0.40 * filament["front"]) << "measured 0.165 against 0.536";
    EXPECT_LT(ours["side"], 0.55 * filament["side"]) << "measured 0.203 against 0.405";
    EXPECT_LT(ours["back"], 0.70 * filament["back"]) << "measured 0.320 against 0.565";
    EXPECT_EQ(wins["front"], 13);
    EXPECT_EQ(wins["side"], 13);
    EXPECT_GE(wins["back"], 12) << "measured 13";
}

// The screen-space peers (Jimenez's separable SSS, HDRP's Burley diffusion, docs/peers.md): per
// light class, the mean masked FLIP of Jade's default as a share of the peer's, and how many of
// the 13 scenes the default wins.
void against_the_screen_space_peers()
{
    ASSERT_EQ(committed().size(), 39u);
    for (const char* peer : {"separable", "burley"}) {
        std::map<std::string, double> ours, theirs;
        std::map<std::string, int> wins;
        for (const auto& s : committed()) {
            const std::string light = s["light"];
            ours[light] += flip(s, "default"), theirs[light] += flip(s, peer);
            wins[light] += flip(s, "default") < flip(s, peer) ? 1 : 0;
        }
        SCOPED_TRACE(peer);
        EXPECT_LT(ours["front"], 0.55 * theirs["front"]) << "measured 0.455 (separable), 0.446 (burley)";
        EXPECT_LT(ours["back"], 0.65 * theirs["back"]) << "measured 0.552 (separable), 0.513 (burley)";
        EXPECT_EQ(wins["front"], 13);
        EXPECT_EQ(wins["back"], 13);
        // Side light: the default's mean is 0.86 of the separable peer's and 0.77 of the Burley
        // peer's (it wins 12 of 13 against each): the diffused transmission carries the lit
        // flank's light, and the light past the terminator stops within the profile's angle.
        EXPECT_LT(ours["side"], 0.92 * theirs["side"]) << "measured 0.863 (separable), 0.765 (burley)";
        EXPECT_GE(wins["side"], 11) << "measured 12";
    }
}

// The held-out regimes: no constant was chosen on them. What holds there, and what does not yet
// (docs/fidelity.md, *Held-out regimes*).
void held_out_regimes()
{
    int count = 0, nearer_than_tm = 0, nearer_than_lambert = 0, away_right = 0, away_count = 0;
    for (const auto& s : scenes()) {
        if (s["set"] != "regimes") continue;
        ++count;
        nearer_than_tm += flip(s, "default") < flip(s, "tm") ? 1 : 0;
        nearer_than_lambert += flip(s, "default") < flip(s, "lambert") ? 1 : 0;
        if (s["light"] == "front")
            EXPECT_LT(flip(s, "default"), flip(s, "lambert")) << s["scene"] << ": front light, held out";
        if (!s.contains("away_reference")) continue;
        // Surfaces that face away from the light: the path tracer's radiance within 25 %, or
        // both below 0.002 (black); a scale-free blur lit a back-lit head's face.
        ++away_count;
        bool right = true;
        for (int c = 0; c < 3; ++c) {
            const double ref = s["away_reference"][c], ours = s["default"]["away"][c];
            right = right && (std::abs(ours - ref) <= 0.25 * ref || (ref < 0.002 && ours < 0.002));
        }
        away_right += right ? 1 : 0;
        if (s["scene"] == "head_skin1_back") {
            const double tm_away = s["tm"]["away"][0], ours_away = s["default"]["away"][0];
            EXPECT_LT(ours_away, 0.002) << "the back-lit head's face stays black";
            EXPECT_GT(tm_away, 5.0 * ours_away) << "the poster's scale-free blur lights it";
        }
        if (s["scene"] == "head_skin1_back" || s["scene"] == "head_skin1_backpoint" ||
            s["scene"] == "head_skin2_back") {
            // The ear glows the path tracer's red: within 30 % in every channel (measured 0.74 / 0.72
            // / 0.86, 0.71 / 0.80 / 1.22 and 0.85 / 0.94 / 0.94), and the back-lit head is nearer than
            // Lambert's (0.022, 0.017, 0.020 against 0.033, 0.029, 0.032).
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(s["default"]["thin"][c].get<double>(), s["thin_reference"][c].get<double>(),
                            0.30 * s["thin_reference"][c].get<double>())
                    << s["scene"] << ": the ear, channel " << c;
            EXPECT_LT(flip(s, "default"), flip(s, "lambert")) << s["scene"];
        }
    }
    EXPECT_EQ(count, 14) << "14 held-out regime scenes are committed";
    EXPECT_EQ(nearer_than_tm, 14) << "nearer than the poster's model on every held-out scene";
    // Not yet: the milk and marble bunnies lit from behind (too bright where they are thin), the
    // fist under the point light and the side-lit head (docs/fidelity.md).
    EXPECT_GE(nearer_than_lambert, 10) << "measured 10 of 14";
    // Measured 6 of 14. The light past the terminator stops within the profile's own angle, so the
    // fist's fingers and a head's far side are dark, as the path tracer's are. What it misses is a
    // rim's glow just past the terminator (hand_skin1_back: 0.0015 red against 0.0029).
    EXPECT_GE(away_right, 6) << "measured 6 of 14 within 25 % or black";
    EXPECT_EQ(away_count, 14);
}

}  // namespace

// One test, so the 39 scenes are rendered once (ctest runs every TEST in a process of its own).
TEST(Fidelity, AgainstThePathTracedReferences)
{
    ASSERT_EQ(committed().size(), 39u) << "27 training and 12 validation scenes are committed";
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
    {
        SCOPED_TRACE("the Filament peer");
        closer_than_the_filament_peer_in_every_light_class();
    }
    {
        SCOPED_TRACE("the screen-space peers");
        against_the_screen_space_peers();
    }
    {
        SCOPED_TRACE("held-out regimes");
        held_out_regimes();
    }
}
