// `frugal report`'s pick (lab/Trades.h: pairedRatio, decideTrades) on timings made by hand: a method
// is picked only when the bootstrap interval of its time paired with the plain render's lies below
// kPays, never when it is a no-op, and the same timings give the same interval. No test here times
// anything: every duration is synthetic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "lab/Trades.h"

namespace frugal {
namespace {

using Timings = std::vector<std::vector<double>>;  // per shot, per round (TradeRow::shotMs)

// A fixed generator for the synthetic noise (its own lines, so the timings are the same everywhere).
class Noise {
public:
    explicit Noise(std::uint64_t seed) : state_(seed) {}
    double uniform() {  // [0, 1)
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    }
    double around(double spread) { return 1.0 + spread * (2.0 * uniform() - 1.0); }  // 1 ± spread

private:
    std::uint64_t state_;
};

// The plain render's shots: views that differ (2 to 11 ms), each round hit by a load common to every
// method of that round (up to +30 %), and by the render's own noise (± 3 %).
struct Shots {
    Timings plain;
    std::vector<std::vector<double>> load, base;
};
Shots plainShots(std::size_t shots, std::size_t rounds, Noise& noise) {
    Shots s;
    for (std::size_t i = 0; i < shots; ++i) {
        s.base.push_back({});
        s.load.push_back({});
        s.plain.push_back({});
        const double base = 2.0 + 9.0 * double(i) / double(shots);
        for (std::size_t r = 0; r < rounds; ++r) {
            s.base.back().push_back(base);
            s.load.back().push_back(1.0 + 0.3 * noise.uniform());
            s.plain.back().push_back(base * s.load.back().back() * noise.around(0.03));
        }
    }
    return s;
}
// A method `factor` times the plain render's work, under the same rounds' loads, with its own noise.
Timings methodShots(const Shots& s, double factor, Noise& noise, double spread = 0.03) {
    Timings out = s.plain;
    for (std::size_t i = 0; i < out.size(); ++i)
        for (std::size_t r = 0; r < out[i].size(); ++r) out[i][r] = factor * s.base[i][r] * s.load[i][r] * noise.around(spread);
    return out;
}

TradeRow row(const std::string& name, Timings ms, bool exact = true) {
    TradeRow r;
    r.candidate.name = name;
    r.candidate.family = name.substr(0, name.find(' '));
    r.shotMs = std::move(ms);
    r.differingPx = exact ? 0 : 40;
    r.worstFramePx = r.differingPx;
    return r;
}

TradeReport decided(std::vector<TradeRow> rows, std::uint64_t budgetPx = 0) {
    TradeReport report;
    report.rows = std::move(rows);
    TradeSettings settings;
    settings.budgetPx = budgetPx;
    decideTrades(report, settings);
    return report;
}

std::string pickName(const TradeReport& report, const std::optional<std::size_t>& pick) {
    return pick ? report.rows[*pick].candidate.name : "plain";
}

TEST(TradePickTest, AMethodTenPercentFasterUnderNoiseIsPicked) {
    Noise noise(1);
    const Shots s = plainShots(32, 3, noise);
    const TradeReport report = decided({row("plain", s.plain), row("cull cones", methodShots(s, 0.9, noise))});
    const PairedRatio& p = report.rows[1].paired;
    EXPECT_EQ(p.pairs, 96u);
    EXPECT_NEAR(p.estimate, 0.9, 0.02);
    EXPECT_LE(p.low, p.estimate);
    EXPECT_GE(p.high, p.estimate);
    EXPECT_LT(p.low, 0.9) << "the interval holds the true ratio";
    EXPECT_GT(p.high, 0.9);
    EXPECT_LT(p.high, kPays);
    EXPECT_TRUE(report.pays(1));
    EXPECT_EQ(pickName(report, report.bestExact), "cull cones");
    EXPECT_EQ(pickName(report, report.bestWithinBudget), "cull cones");
}

// The user's case: a method that does the plain render's work (an order of a single draw), timed
// while load hit the plain render's renders more often. Its median over all renders is well below
// 0.97 of the plain render's, which the old rule took as a gain; paired round by round, the load
// falls in one round of a shot and the shot's median ignores it.
TEST(TradePickTest, ALoadThatFoolsTheMediansDoesNotFoolThePairs) {
    Noise noise(2);
    Shots s = plainShots(32, 3, noise);
    for (auto& shot : s.load) std::fill(shot.begin(), shot.end(), 1.0);
    s.plain = methodShots(s, 1.0, noise);
    Timings same = methodShots(s, 1.0, noise);
    for (std::size_t i = 0; i < s.plain.size(); ++i)
        if (i % 3 != 2) s.plain[i][i % 3] *= 1.6;  // a burst of load in one round of two shots in three
    TradeRow fooled = row("order greedy", same);
    const TradeReport report = decided({row("plain", s.plain), fooled});

    const double medianRatio = report.rows[1].medianMs / report.rows[0].medianMs;
    ASSERT_LT(medianRatio, kPays) << "the medians alone would pick it";
    const PairedRatio& p = report.rows[1].paired;
    EXPECT_NEAR(p.estimate, 1.0, 0.03);
    EXPECT_GT(p.high, kPays);
    EXPECT_FALSE(report.pays(1));
    EXPECT_FALSE(report.bestExact) << "picked at " << medianRatio << "x the plain render's median";
    EXPECT_FALSE(report.bestWithinBudget);
}

TEST(TradePickTest, AnEstimateBelowTheLineWithAnIntervalAcrossItIsNotPicked) {
    Noise noise(3);
    const Shots s = plainShots(32, 3, noise);
    const TradeReport report = decided({row("plain", s.plain), row("order key", methodShots(s, 0.95, noise, 0.15))});
    const PairedRatio& p = report.rows[1].paired;
    ASSERT_LT(p.estimate, kPays) << "a rule on the estimate alone would pick it";
    EXPECT_GT(p.high, kPays);
    EXPECT_FALSE(report.bestExact);
}

TEST(TradePickTest, ANoOpIsNeverPickedEvenWhenItIsFaster) {
    Noise noise(4);
    const Shots s = plainShots(32, 3, noise);
    TradeRow noOp = row("order greedy", methodShots(s, 0.8, noise));
    noOp.sameDrawsAs = 0;
    TradeRow noOpInexact = row("cull sphere", methodShots(s, 0.7, noise), false);
    noOpInexact.sameDrawsAs = 0;
    // A combination that drew what cull cones alone drew: its order added nothing.
    TradeRow addsNothing = row("cull cones + order key", methodShots(s, 0.85, noise));
    addsNothing.sameDrawsAs = 3;
    const TradeReport report = decided({row("plain", s.plain), noOp, noOpInexact,
                                        row("cull cones", methodShots(s, 0.9, noise)), addsNothing},
                                       100);
    EXPECT_LT(report.rows[1].paired.high, kPays) << "its time alone would pay";
    EXPECT_LT(report.rows[4].paired.high, report.rows[3].paired.low) << "its time alone would beat cones";
    EXPECT_TRUE(report.rows[1].noOp());
    EXPECT_FALSE(report.rows[4].noOp());
    EXPECT_FALSE(report.pays(1));
    EXPECT_FALSE(report.pays(2));
    EXPECT_TRUE(report.pays(3));
    EXPECT_FALSE(report.pays(4));
    EXPECT_EQ(pickName(report, report.bestExact), "cull cones");
    EXPECT_EQ(pickName(report, report.bestWithinBudget), "cull cones");
}

TEST(TradePickTest, ThePickIsTheLowestEstimateAmongThoseThatPay) {
    // conservative: 0.85 of the plain render in every shot. cones: 0.8 in the middle, but from
    // 0.8 e^-0.5 to 0.8 e^0.5 from view to view: a lower estimate, a wider interval.
    Timings plain, conservative, cones, paper, oracle;
    for (int i = 0; i < 40; ++i) {
        const double base = 3.0 + 0.2 * i, gain = 0.8 * std::exp(-0.5 + double(i % 10) / 9.0);
        plain.push_back({base, base, base});
        conservative.push_back({0.85 * base, 0.85 * base, 0.85 * base});
        cones.push_back({gain * base, gain * base, gain * base});
        paper.push_back({0.5 * base, 0.5 * base, 0.5 * base});
        oracle.push_back({0.3 * base, 0.3 * base, 0.3 * base});
    }
    TradeRow floor = row("cull oracle", oracle);
    floor.candidate.floor = true;
    const TradeReport report = decided(
        {row("plain", plain), row("cull conservative", conservative), row("cull cones", cones), row("cull paper", paper, false), floor},
        50);
    ASSERT_LT(report.rows[2].paired.estimate, report.rows[1].paired.estimate);
    ASSERT_GT(report.rows[2].paired.high, report.rows[1].paired.high) << "cones is less sure of its gain";
    ASSERT_LT(report.rows[2].paired.high, kPays) << "but sure that it pays";
    EXPECT_EQ(pickName(report, report.bestExact), "cull cones");
    EXPECT_EQ(pickName(report, report.bestWithinBudget), "cull paper") << "40 px a frame is within 50";
    EXPECT_FALSE(report.pays(4)) << "the floor is a bound, never a pick";
    const TradeReport strict = decided(report.rows, 39);
    EXPECT_EQ(pickName(strict, strict.bestWithinBudget), "cull cones") << "40 px a frame is over 39";
}

TEST(TradePickTest, TheIntervalComesFromTheTimingsAndTheSeedAlone) {
    Noise noise(6);
    const Shots s = plainShots(24, 3, noise);
    const Timings m = methodShots(s, 0.93, noise, 0.05);
    const PairedRatio a = pairedRatio(m, s.plain), b = pairedRatio(m, s.plain);
    EXPECT_EQ(a.estimate, b.estimate);
    EXPECT_EQ(a.low, b.low);
    EXPECT_EQ(a.high, b.high);
    const PairedRatio c = pairedRatio(m, s.plain, kBootstrapSeed + 1);
    EXPECT_EQ(c.estimate, a.estimate) << "the estimate does not resample";
    EXPECT_TRUE(c.low != a.low || c.high != a.high) << "the seed draws the resamples";
    EXPECT_NEAR(c.low, a.low, 0.01);
    EXPECT_NEAR(c.high, a.high, 0.01);
}

TEST(TradePickTest, TheEstimateIsATrimmedGeometricMeanOfEachShotsMedianRatio) {
    // Ten shots whose rounds' median ratios are these (the other two rounds 1.25 and 0.8 times it):
    // the lowest two and the highest two are left out, the other six averaged on a log scale.
    const std::vector<double> ratios{0.1, 0.2, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 3.0, 9.0};
    const auto timings = [](const std::vector<double>& r) {
        Timings method;
        for (const double x : r) method.push_back({12.5 * x, 10.0 * x, 8.0 * x});
        return method;
    };
    const Timings plain(ratios.size(), {10.0, 10.0, 10.0});
    const PairedRatio p = pairedRatio(timings(ratios), plain);
    EXPECT_EQ(p.pairs, 30u);
    const double middleSix = std::pow(0.5 * 0.6 * 0.7 * 0.8 * 0.9 * 1.0, 1.0 / 6.0);
    EXPECT_NEAR(p.estimate, middleSix, 1e-12) << "not the median " << (0.7 + 0.8) / 2 << ", nor the mean of all ten";
    EXPECT_LT(p.low, p.estimate);
    EXPECT_GT(p.high, p.estimate);
    std::vector<double> wilder = ratios;
    wilder.front() = 0.001;
    wilder.back() = 900.0;
    EXPECT_NEAR(pairedRatio(timings(wilder), plain).estimate, middleSix, 1e-12) << "a trimmed shot does not count";

    // Every pair the same ratio: no spread, the interval is that ratio.
    const PairedRatio flat = pairedRatio(Timings(10, {4.5, 9.0}), Timings(10, {5.0, 10.0}));
    EXPECT_NEAR(flat.low, 0.9, 1e-12);
    EXPECT_NEAR(flat.high, 0.9, 1e-12);
}

TEST(TradePickTest, TooFewPairsGiveNoIntervalAndNoPick) {
    // One camera, three rounds: half the plain render's time, but three pairs make no interval.
    TradeReport report = decided({row("plain", {{10.0, 11.0, 10.5}}), row("cull cones", {{5.0, 5.5, 5.2}})});
    EXPECT_EQ(report.rows[1].paired.pairs, 3u);
    EXPECT_FALSE(report.rows[1].paired.known());
    EXPECT_TRUE(std::isnan(report.rows[1].paired.high));
    EXPECT_FALSE(report.bestExact);
    // One camera and kMinPairs rounds: the rounds are resampled, and it pays.
    report = decided({row("plain", {std::vector<double>(kMinPairs, 10.0)}),
                      row("cull cones", {{5.0, 5.5, 5.2, 4.9, 5.1, 5.0, 5.3, 5.4}})});
    ASSERT_TRUE(report.rows[1].paired.known());
    EXPECT_LT(report.rows[1].paired.low, report.rows[1].paired.high) << "the rounds' spread";
    EXPECT_EQ(pickName(report, report.bestExact), "cull cones");
}

// What each candidate repeats, from fingerprints made up round by round (lab/Trades.h repeatedDraws).
TEST(TradePickTest, ACandidateThatRepeatsTheDrawsOfOneItAddsToIsFound) {
    const std::vector<TradeCandidate> candidates = tradeCandidates(Settings{}, true, false);
    const auto at = [&candidates](const std::string& name) {
        for (std::size_t i = 0; i < candidates.size(); ++i)
            if (candidates[i].name == name) return i;
        ADD_FAILURE() << "no candidate " << name;
        return std::size_t(0);
    };
    const Settings plainSettings = candidates[0].settings;
    std::vector<std::vector<DrawRecord>> rounds;
    for (std::uint64_t r = 0; r < 3; ++r) {
        // By default: the cull's list is the cull's own (the whole scene's, the plain render's
        // draws, without a cull), and a candidate that adds an order, a plan or reuse draws
        // otherwise.
        const std::uint64_t plain = 1000 * (r + 1);
        std::vector<DrawRecord>& drew = rounds.emplace_back();
        for (std::size_t i = 0; i < candidates.size(); ++i) {
            const Settings& c = candidates[i].settings;
            const std::uint64_t culled = c.cull == Cull::None ? plain : plain + 100 + std::uint64_t(c.cull);
            const bool after = c.order != plainSettings.order || c.hsr != plainSettings.hsr || c.reuse;
            drew.push_back({after ? plain + 500 + i : culled, culled});
        }
        drew[at("order key")].drawn = plain;    // one draw ordered
        drew[at("cull sphere")] = {plain, plain};  // everything in view
        if (r < 2) drew[at("order greedy")].drawn = plain;  // reordered in the last round
        // Occlusion culling skipped its pass in one round in one renderer: the combination drew
        // otherwise than occlusion alone there, but its order never changed its culled list.
        drew[at("cull occlusion + order key")] = drew[at("cull occlusion")];
        if (r == 1) drew[at("cull occlusion + order key")] = {77, 77};
        // The ahead form draws what occlusion does: another cull, not one added to it.
        drew[at("cull occlusion-ahead")] = drew[at("cull occlusion")];
        // Conservative culling kept everything, in one run, and the order changed nothing.
        drew[at("cull conservative + order key")] = {plain, plain};
        drew[at("cull oracle")] = {};  // the floor draws its own scene
    }
    const std::vector<std::optional<std::size_t>> same = repeatedDraws(candidates, rounds);
    ASSERT_EQ(same.size(), candidates.size());
    EXPECT_FALSE(same[0]) << "the plain render";
    EXPECT_EQ(same[at("order key")], 0u);
    EXPECT_EQ(same[at("cull sphere")], 0u);
    EXPECT_FALSE(same[at("order greedy")]) << "not in every round";
    EXPECT_EQ(same[at("cull occlusion + order key")], at("cull occlusion"));
    EXPECT_FALSE(same[at("cull occlusion-ahead")]);
    EXPECT_EQ(same[at("cull conservative + order key")], 0u) << "its draws were the plain render's";
    EXPECT_FALSE(same[at("hsr depthsort")]);
    EXPECT_FALSE(same[at("cull oracle")]);
    EXPECT_FALSE(same[at("cull conservative")]);
    EXPECT_FALSE(same[at("reuse")]);

    // Conservative culling kept everything and the key order reordered: the combination draws what
    // the order alone draws, not the plain render's draws.
    for (std::vector<DrawRecord>& drew : rounds) {
        drew[at("order key")].drawn = 9000;
        drew[at("cull conservative + order key")] = {9000, drew[0].drawn};
    }
    EXPECT_EQ(repeatedDraws(candidates, rounds)[at("cull conservative + order key")], at("order key"));
    rounds.back().resize(3);
    EXPECT_FALSE(repeatedDraws(candidates, rounds)[at("cull conservative + order key")])
        << "a round without it draws otherwise";
}

}  // namespace
}  // namespace frugal
