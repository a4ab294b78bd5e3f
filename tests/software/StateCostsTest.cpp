// State-change costs (gl/StateCosts.h) measured on the software backend: every kind gets a finite
// figure from each round, and the running average the draw orders use follows the last rounds only.
// The figures themselves are timings and are never asserted.
#include <gtest/gtest.h>

#include <cmath>

#include "gl/StateCosts.h"
#include "software/SoftwareBackend.h"

namespace frugal {
namespace {

StateCostSample sample(double us) {
    StateCostSample s;
    s.drawUs = 1.0;
    s.us.fill(us);
    return s;
}

TEST(RunningStateCostsTest, AveragesTheLastRoundsOfTheWindow) {
    RunningStateCosts running(2);
    EXPECT_TRUE(running.costsUs().empty());
    running.add(sample(100.0));
    running.add(sample(2.0));
    running.add(sample(4.0));  // the 100 falls out of the window
    EXPECT_EQ(running.rounds(), 3u);
    ASSERT_EQ(running.costsUs().size(), kStateKinds);
    for (double us : running.costsUs()) EXPECT_DOUBLE_EQ(us, 3.0);

    StateCostSample mixed = sample(-5.0);  // noise around a free change
    mixed.us[1] = 8.0;
    running.add(mixed);
    running.add(mixed);
    const std::vector<double> costs = running.costsUs();
    EXPECT_DOUBLE_EQ(costs[0], 0.01);  // never 0 or below: every kind keeps an order to prefer
    EXPECT_DOUBLE_EQ(costs[1], 8.0);
}

TEST(RunningStateCostsTest, OnePreemptedRoundDoesNotMoveTheAverage) {
    RunningStateCosts running(8);
    for (int r = 0; r < 7; ++r) running.add(sample(2.0));
    running.add(sample(1000.0));  // the scheduler took the core during one kind's loop
    for (double us : running.costsUs()) EXPECT_DOUBLE_EQ(us, 2.0);
    // A drift that lasts moves it: once most of the window reads 6, so does the average.
    for (int r = 0; r < 6; ++r) running.add(sample(6.0));
    for (double us : running.costsUs()) EXPECT_DOUBLE_EQ(us, 6.0);
}

TEST(StateCostProbeTest, EachRoundGivesEveryKindAFiniteCost) {
    const std::unique_ptr<Backend> backend = makeSoftwareBackend();
    Result<std::unique_ptr<StateCostProbe>> probe = StateCostProbe::create(*backend);
    ASSERT_TRUE(probe) << probe.error().message;
    for (int phase = 0; phase < 3; ++phase) {
        const StateCostSample s = (*probe)->round(20, phase);
        EXPECT_GT(s.drawUs, 0.0);
        for (double us : s.us) EXPECT_TRUE(std::isfinite(us));
    }
}

TEST(StateCostProbeTest, TheReportNamesEveryKindAndTimesFirstUse) {
    const std::unique_ptr<Backend> backend = makeSoftwareBackend();
    Result<StateCostReport> report = measureStateCosts(*backend, 2, 10);
    ASSERT_TRUE(report) << report.error().message;
    ASSERT_EQ(report->costs.size(), kStateKinds);
    for (std::size_t k = 0; k < kStateKinds; ++k) {
        EXPECT_EQ(report->costs[k].kind, kStateKindNames[k]);
        EXPECT_LE(report->costs[k].minUs, report->costs[k].us);
        EXPECT_LE(report->costs[k].us, report->costs[k].maxUs);
    }
    EXPECT_EQ(report->rounds, 2);
    EXPECT_GT(report->textureFirstDrawMs, 0.0);
    EXPECT_GT(report->newCombinationMs, 0.0);
    // The probe's target, meshes and textures are gone; the backend still makes and fills a target.
    const TargetHandle target = backend->createTarget(8, 8);
    ASSERT_NE(target, kNoHandle);
    backend->beginFrame(target, FrameParams{});
    backend->finish();
    EXPECT_EQ(backend->readBack(target).width, 8);
    backend->destroyTarget(target);
}

}  // namespace
}  // namespace frugal
