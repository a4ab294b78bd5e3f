// The temporal-reuse planner (src/reuse/Reuse.h) as a state machine, on the CPU: modes and their
// reasons frame by frame, the four states P_dd/P_ds/P_sd/P_ss, what makes an instance dynamic
// (its world matrix, its material, its place in the draw list, a NaN), the shape of each plan
// (steps, rectangles, the order of the draws) and the frame statistics against the plan they
// describe. Where a plan's effect matters it is rendered on the software reference.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ReuseSupport.h"
#include "pipeline/IndexRanges.h"
#include "software/SoftwareBackend.h"

namespace frugal::test {
namespace {

using reuse::Box;

constexpr int kW = 160, kH = 120;
const std::uint64_t kScreen = std::uint64_t(kW) * kH;

std::uint64_t triangles(const DrawList& list) {
    std::uint64_t n = 0;
    for (const DrawCommand& c : list)
        for (const IndexRange& r : c.ranges) n += r.triangleCount;
    return n;
}

std::uint64_t area(const std::vector<Rect>& rects) {
    std::uint64_t n = 0;
    for (const Rect& r : rects) n += std::uint64_t(r.width) * std::uint64_t(r.height);
    return n;
}

// The pixels of `rects` as a mask over the target.
std::vector<std::uint8_t> maskOf(const std::vector<Rect>& rects) {
    std::vector<std::uint8_t> mask(kScreen, 0);
    for (const Rect& r : rects)
        for (int y = r.y; y < r.y + r.height; ++y)
            for (int x = r.x; x < r.x + r.width; ++x) mask[std::size_t(y) * kW + std::size_t(x)] += 1;
    return mask;
}

// Every pixel of `box` is in `mask`.
bool covers(const std::vector<std::uint8_t>& mask, const Box& box) {
    for (int y = box.y0; y < box.y1; ++y)
        for (int x = box.x0; x < box.x1; ++x)
            if (!mask[std::size_t(y) * kW + std::size_t(x)]) return false;
    return true;
}

std::vector<const PlanStep*> stepsOf(const FramePlan& plan, PlanStep::Op op) {
    std::vector<const PlanStep*> steps;
    for (const PlanStep& s : plan)
        if (s.op == op) steps.push_back(&s);
    return steps;
}

std::vector<Rect> rectsOf(const FramePlan& plan, PlanStep::Op op, PlanTarget from, PlanTarget to) {
    std::vector<Rect> rects;
    for (const PlanStep& s : plan)
        if (s.op == op && s.from == from && s.to == to) rects.insert(rects.end(), s.rects.begin(), s.rects.end());
    return rects;
}

// What a Draw step draws: its own list, or the one it points to (pipeline/Plan.h).
const DrawList& drawsOf(const PlanStep& step) { return step.list ? *step.list : step.draws; }

std::string describe(const FramePlan& plan) {
    std::string text;
    for (const PlanStep& s : plan) {
        text += s.op == PlanStep::Op::Clear ? " clear" : s.op == PlanStep::Op::Copy ? " copy" : " draw";
        if (s.op == PlanStep::Op::Copy) text += s.from == PlanTarget::Static ? "(static->render)" : "(render->static)";
        else text += s.to == PlanTarget::Static ? "[static]" : "[render]";
        if (s.op == PlanStep::Op::Draw) text += "(" + std::to_string(drawsOf(s).size()) + " instances)";
        else text += "(" + std::to_string(s.rects.size()) + " rects)";
    }
    return text;
}

// The screen extent of a whole instance at `model`, as the planner computes it.
Box instanceExtent(const Scene& scene, int instance, const FrameParams& frame, const glm::mat4& model) {
    const Mesh& mesh = scene.meshes[std::size_t(scene.instances[std::size_t(instance)].mesh)];
    reuse::ExtentBuilder builder(kW, kH);
    builder.project(frame.projection * frame.view * model, mesh.positions);
    Box box;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        box.add(builder.triangle(mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]));
    return box;
}

std::vector<Rect> clearsOf(const FramePlan& plan) {
    std::vector<Rect> rects;
    for (const PlanStep& s : plan)
        if (s.op == PlanStep::Op::Clear) rects.insert(rects.end(), s.rects.begin(), s.rects.end());
    return rects;
}

// The draws into `to`.
std::vector<const DrawCommand*> drawsInto(const FramePlan& plan, PlanTarget to) {
    std::vector<const DrawCommand*> draws;
    for (const PlanStep& s : plan)
        if (s.op == PlanStep::Op::Draw && s.to == to)
            for (const DrawCommand& c : drawsOf(s)) draws.push_back(&c);
    return draws;
}

// The planner with an independent reading of "dynamic" beside it (Reuse.h): an instance whose
// world matrix, material (factor, texture, sidedness) or drawn triangles differ from the previous
// frame's, compared exactly; everything static on the first frame. It gives each frame's expected
// states and which instances are dynamic in it, to judge the plan with.
class Planned {
public:
    Planned(const Scene& scene, int width, int height, const ReuseOptions& options = {})
        : reuse_(scene, width, height, options), scene_(&scene) {}

    FramePlan plan(const FrameParams& frame, const std::vector<glm::mat4>& world, const DrawList& list,
                   const glm::vec4& background) {
        track(world, list);
        return reuse_.plan(frame, world, list, background);
    }
    // Through the whole-scene overload.
    FramePlan plan(const FrameParams& frame, const std::vector<glm::mat4>& world, const glm::vec4& background) {
        track(world, fullDrawList(*scene_));
        return reuse_.plan(frame, world, background);
    }

    bool dynamic(int instance) const { return dynamic_[std::size_t(instance)] != 0; }
    const ReuseCounts& expectedStates() const { return expected_; }
    const ReuseFrameStats& stats() const { return reuse_.stats(); }
    const ReuseOptions& options() const { return reuse_.options(); }
    bool staticValid() const { return reuse_.staticValid(); }
    void invalidate() { reuse_.invalidate(); }
    const TemporalReuse& planner() const { return reuse_; }

private:
    struct Key {
        glm::mat4 model{1.0f};
        Material material;
        std::vector<IndexRange> ranges;  // normalised; empty: not drawn
        // The model bit for bit (Reuse.h): -0 differs from +0, a NaN equals the same NaN; the
        // material by value, every member (Scene.h).
        bool operator==(const Key& o) const {
            return std::memcmp(&model, &o.model, sizeof model) == 0 && material == o.material &&
                   std::equal(ranges.begin(), ranges.end(), o.ranges.begin(), o.ranges.end(),
                              [](const IndexRange& a, const IndexRange& b) {
                                  return a.firstTriangle == b.firstTriangle && a.triangleCount == b.triangleCount;
                              });
        }
    };
    void track(const std::vector<glm::mat4>& world, const DrawList& list) {
        const std::size_t n = scene_->instances.size();
        std::vector<Key> now(n);
        for (std::size_t i = 0; i < n; ++i) {
            const Instance& instance = scene_->instances[i];
            const Mesh& mesh = scene_->meshes[std::size_t(instance.mesh)];
            const Material material = mesh.material >= 0 ? scene_->materials[std::size_t(mesh.material)] : Material{};
            now[i].model = world[std::size_t(instance.node)];
            now[i].material = material;
        }
        for (const DrawCommand& c : list) {
            std::vector<IndexRange>& ranges = now[std::size_t(c.instance)].ranges;
            const Mesh& mesh = scene_->meshes[std::size_t(scene_->instances[std::size_t(c.instance)].mesh)];
            if (normalizeRanges(c.ranges, std::uint32_t(mesh.triangleCount()), ranges) == 0) ranges.clear();
        }
        std::vector<std::uint8_t> was = dynamic_;
        was.resize(n, 0);
        dynamic_.assign(n, 0);
        expected_ = {};
        for (std::size_t i = 0; i < n; ++i) {
            dynamic_[i] = !previous_.empty() && !(now[i] == previous_[i]) ? 1 : 0;
            countOf(expected_, (was[i] ? 0 : 2) + (dynamic_[i] ? 0 : 1)) += 1;
        }
        previous_ = std::move(now);
    }

    TemporalReuse reuse_;
    const Scene* scene_;
    std::vector<Key> previous_;
    std::vector<std::uint8_t> dynamic_;
    ReuseCounts expected_;
};

// The checks every plan must pass, whatever its mode: rectangles inside the target, the stats
// equal to what the plan does, draws in list order and inside the list's ranges, the steps in the
// order of Reuse.h (steps a–d, or the paper's 1–6 with paperSteps).
void checkPlan(const FramePlan& plan, const Planned& reuse, const DrawList& list, const std::string& label) {
    SCOPED_TRACE(label + ":" + describe(plan));
    const ReuseFrameStats& s = reuse.stats();
    std::map<int, std::size_t> position;
    for (std::size_t k = 0; k < list.size(); ++k) position[list[k].instance] = k;
    EXPECT_EQ(s.drawnTris, triangles(list));
    std::uint64_t copied = 0, cleared = 0, drawn = 0, staticDrawn = 0, rects = 0;
    for (const PlanStep& step : plan) {
        for (const Rect& r : step.rects) {
            EXPECT_FALSE(r.empty());
            EXPECT_GE(r.x, 0);
            EXPECT_GE(r.y, 0);
            EXPECT_LE(r.x + r.width, kW);
            EXPECT_LE(r.y + r.height, kH);
        }
        // No rectangle of one step overlaps another of the same step.
        const std::vector<std::uint8_t> mask = maskOf(step.rects);
        EXPECT_EQ(std::count_if(mask.begin(), mask.end(), [](std::uint8_t m) { return m > 1; }), 0);
        switch (step.op) {
        case PlanStep::Op::Clear:
            cleared += area(step.rects);
            rects += step.rects.size();
            EXPECT_TRUE(step.draws.empty());
            EXPECT_FALSE(step.rects.empty()) << "no empty step";
            break;
        case PlanStep::Op::Copy:
            EXPECT_NE(step.from, step.to);
            copied += area(step.rects);
            rects += step.rects.size();
            EXPECT_TRUE(step.draws.empty());
            EXPECT_FALSE(step.rects.empty()) << "no empty step";
            break;
        case PlanStep::Op::Draw: {
            EXPECT_TRUE(step.rects.empty());
            if (reuse.stats().mode == ReuseMode::Reuse) {
                EXPECT_FALSE(drawsOf(step).empty()) << "no empty step";
            }
            std::size_t last = 0;
            bool firstDraw = true;
            for (const DrawCommand& c : drawsOf(step)) {
                ASSERT_TRUE(position.count(c.instance)) << "instance " << c.instance << " is not in the list";
                const std::size_t at = position[c.instance];
                EXPECT_TRUE(firstDraw || at > last) << "instance " << c.instance << " drawn out of list order";
                firstDraw = false;
                last = at;
                EXPECT_FALSE(c.ranges.empty());
                // Every range drawn lies inside one of the list's ranges of the instance, ascending.
                const std::vector<IndexRange>& allowed = list[at].ranges;
                std::uint64_t end = 0;
                for (const IndexRange& r : c.ranges) {
                    EXPECT_GT(r.triangleCount, 0u);
                    EXPECT_GE(r.firstTriangle, end) << "ranges of instance " << c.instance << " out of order";
                    end = std::uint64_t(r.firstTriangle) + r.triangleCount;
                    const bool inside = std::any_of(allowed.begin(), allowed.end(), [&r](const IndexRange& a) {
                        return r.firstTriangle >= a.firstTriangle &&
                               r.firstTriangle + r.triangleCount <= a.firstTriangle + a.triangleCount;
                    });
                    EXPECT_TRUE(inside) << "instance " << c.instance << " range " << r.firstTriangle << "+" << r.triangleCount
                                        << " is not in the list";
                    drawn += r.triangleCount;
                    staticDrawn += reuse.dynamic(c.instance) ? 0 : r.triangleCount;
                }
            }
            break;
        }
        }
    }
    // (Full frames: see FullFramesReportWhatTheyDo.)
    if (s.mode != ReuseMode::Full) {
        EXPECT_EQ(s.copiedPx, copied);
        EXPECT_EQ(s.rects, rects) << "rectangles issued (clears and copies)";
        EXPECT_EQ(s.staticRedrawnTris, staticDrawn);
    }
    EXPECT_EQ(s.clearedPx, cleared);
    EXPECT_EQ(s.redrawnTris, drawn);
    EXPECT_LE(s.staticRedrawnTris, s.redrawnTris);
    EXPECT_FALSE(s.reason.empty()) << "every decision has a reason";
    using Op = PlanStep::Op;
    constexpr PlanTarget R = PlanTarget::Render, S = PlanTarget::Static;
    switch (s.mode) {
    case ReuseMode::Full:
        ASSERT_EQ(plan.size(), 2u);
        EXPECT_EQ(plan[0].op, Op::Clear);
        EXPECT_EQ(plan[0].to, R);
        EXPECT_EQ(area(plan[0].rects), kScreen);
        EXPECT_EQ(plan[1].op, Op::Draw);
        EXPECT_EQ(plan[1].to, R);
        EXPECT_EQ(triangles(drawsOf(plan[1])), triangles(list));
        EXPECT_EQ(s.redrawnTris, s.drawnTris);
        break;
    case ReuseMode::Rebuild: {
        // Clear, the static instances (a step only when there are any), the whole target into the
        // static pair, the dynamic ones (only when there are any).
        ASSERT_GE(plan.size(), 2u);
        EXPECT_EQ(plan[0].op, Op::Clear);
        EXPECT_EQ(area(plan[0].rects), kScreen);
        const std::size_t copy = plan[1].op == Op::Draw ? 2 : 1;
        ASSERT_GT(plan.size(), copy);
        EXPECT_EQ(plan[copy].op, Op::Copy);
        EXPECT_EQ(plan[copy].from, R);
        EXPECT_EQ(plan[copy].to, S);
        EXPECT_EQ(area(plan[copy].rects), kScreen);
        for (const PlanStep& step : plan) EXPECT_TRUE(step.op != Op::Draw || !drawsOf(step).empty()) << "no empty step";
        EXPECT_EQ(s.redrawnTris, s.drawnTris);
        for (const PlanStep& step : plan) EXPECT_EQ(step.to == S, step.op == Op::Copy);
        break;
    }
    case ReuseMode::Reuse: {
        // Dynamic instances are drawn into the render target, last; static ones are redrawn into
        // the static pair (steps a–d) or into the render target before the copy back (paper).
        const bool paper = reuse.options().paperSteps;
        for (const DrawCommand* c : drawsInto(plan, S)) EXPECT_FALSE(reuse.dynamic(c->instance)) << c->instance;
        if (paper) {
            EXPECT_TRUE(drawsInto(plan, S).empty());
        }
        bool dynamicSeen = false;
        for (const DrawCommand* c : drawsInto(plan, R)) {
            if (reuse.dynamic(c->instance)) dynamicSeen = true;
            else EXPECT_FALSE(dynamicSeen) << "static instance " << c->instance << " drawn after the dynamic ones";
        }
        // Step kinds in order.
        std::vector<std::string> order;
        for (const PlanStep& step : plan) {
            std::string kind = step.op == Op::Clear ? "clear" : step.op == Op::Copy ? "copy" : "draw";
            kind += step.op == Op::Copy ? (step.from == S ? " S>R" : " R>S") : (step.to == S ? " S" : " R");
            if (step.op == Op::Draw && step.to == R)
                kind += reuse.dynamic(drawsOf(step).front().instance) ? " dynamic" : " static";
            order.push_back(kind);
        }
        const std::vector<std::string> allowed =
            paper ? std::vector<std::string>{"copy S>R", "clear R", "draw R static", "copy R>S", "draw R dynamic"}
                  : std::vector<std::string>{"clear S", "draw S", "copy S>R", "draw R dynamic"};
        std::size_t k = 0;
        for (const std::string& kind : order) {
            while (k < allowed.size() && allowed[k] != kind) ++k;
            EXPECT_LT(k, allowed.size()) << "step '" << kind << "' out of order or unexpected";
        }
        const std::vector<std::uint8_t> clearedMask = maskOf(clearsOf(plan));
        if (paper) {
            // Step 1 leaves out what step 2 clears; what is cleared is copied back.
            const std::vector<std::uint8_t> in = maskOf(rectsOf(plan, Op::Copy, S, R));
            const std::vector<std::uint8_t> back = maskOf(rectsOf(plan, Op::Copy, R, S));
            for (std::size_t p = 0; p < in.size(); ++p) {
                ASSERT_FALSE(in[p] && clearedMask[p]) << "pixel " << p << " copied and cleared";
                ASSERT_TRUE(!clearedMask[p] || back[p]) << "pixel " << p << " cleared, not copied back";
            }
        } else {
            // What the static pair changed in is copied into the render target.
            const std::vector<std::uint8_t> in = maskOf(rectsOf(plan, Op::Copy, S, R));
            for (std::size_t p = 0; p < in.size(); ++p) ASSERT_TRUE(!clearedMask[p] || in[p]) << "pixel " << p;
            EXPECT_TRUE(rectsOf(plan, Op::Copy, R, S).empty());
        }
        break;
    }
    }
}

class ReusePlanner : public ::testing::Test {
protected:
    void SetUp() override {
        scene = loadOrFail("builtin:dominoes?polygons=804&static=0.5544");
        ASSERT_FALSE(scene.instances.empty());
        Result<FrameSetup> setup = setUpFrame(scene, {}, 0.0, kW, kH, true);
        ASSERT_TRUE(setup) << setup.error().message;
        params = setup->params;
        world0 = setup->world;
        list = fullDrawList(scene);
        for (const Instance& instance : scene.instances)
            total += scene.meshes[std::size_t(instance.mesh)].triangleCount();
    }
    std::size_t n() const { return scene.instances.size(); }
    int nodeOf(int instance) const { return scene.instances[std::size_t(instance)].node; }
    // world0 with `instances` shifted sideways by `dx`.
    std::vector<glm::mat4> moved(const std::vector<int>& instances, float dx) const {
        std::vector<glm::mat4> world = world0;
        for (int i : instances) world[std::size_t(nodeOf(i))] = glm::translate(glm::mat4(1.0f), {dx, 0.0f, 0.0f}) * world0[std::size_t(nodeOf(i))];
        return world;
    }
    // Plans one frame and checks it; returns the plan.
    FramePlan step(Planned& reuse, const std::vector<glm::mat4>& world, const std::string& label,
                   const DrawList* drawList = nullptr, const FrameParams* frame = nullptr,
                   const glm::vec4& background = kReuseBackground) {
        const DrawList& l = drawList ? *drawList : list;
        FramePlan plan = reuse.plan(frame ? *frame : params, world, l, background);
        checkPlan(plan, reuse, l, label);
        const ReuseFrameStats& s = reuse.stats();
        std::uint64_t instances = 0, tris = 0;
        for (int k = 0; k < 4; ++k) {
            instances += countOf(s.instances, k);
            tris += countOf(s.triangles, k);
        }
        EXPECT_EQ(instances, n()) << label;
        EXPECT_EQ(tris, total) << label;
        EXPECT_EQ(s.instances, reuse.expectedStates()) << label << ": the states of the instances";
        return plan;
    }

    Scene scene;
    FrameParams params;
    std::vector<glm::mat4> world0;
    DrawList list;
    std::uint64_t total = 0;
};

TEST_F(ReusePlanner, FirstFrameRebuildsWithEverythingStatic) {
    Planned reuse(scene, kW, kH);
    EXPECT_FALSE(reuse.staticValid());
    // Even an instance that differs from nothing: the first frame has no previous one.
    const FramePlan plan = step(reuse, moved({3}, 0.5f), "frame 0");
    const ReuseFrameStats& s = reuse.stats();
    EXPECT_EQ(s.mode, ReuseMode::Rebuild);
    EXPECT_EQ(s.reason, "first frame");
    EXPECT_EQ(s.instances.ss, n());
    EXPECT_EQ(s.triangles.ss, total);
    ASSERT_EQ(plan.size(), 3u) << "nothing dynamic: no fourth step";
    EXPECT_EQ(drawsOf(plan[1]).size(), list.size());
    EXPECT_EQ(s.copiedPx, kScreen);
    EXPECT_EQ(s.clearedPx, kScreen);
    EXPECT_EQ(s.staticRedrawnTris, total);
    EXPECT_TRUE(reuse.staticValid());
}

TEST_F(ReusePlanner, NothingChangedIsAnEmptyReuse) {
    Planned reuse(scene, kW, kH);
    step(reuse, world0, "frame 0");
    for (int i = 1; i < 4; ++i) {
        const FramePlan plan = step(reuse, world0, "frame " + std::to_string(i));
        const ReuseFrameStats& s = reuse.stats();
        EXPECT_EQ(s.mode, ReuseMode::Reuse);
        EXPECT_EQ(s.reason, "camera still");
        EXPECT_TRUE(plan.empty()) << describe(plan);
        EXPECT_EQ(s.instances.ss, n());
        EXPECT_EQ(s.redrawnTris, 0u);
        EXPECT_EQ(s.copiedPx + s.clearedPx + s.rects, 0u);
        EXPECT_EQ(s.drawnTris, total);
    }
}

TEST_F(ReusePlanner, OneInstanceMovesStopsAndRests) {
    const int j = 40;
    using Op = PlanStep::Op;
    constexpr PlanTarget R = PlanTarget::Render, S = PlanTarget::Static;
    for (bool paper : {false, true}) {
        SCOPED_TRACE(paper ? "the paper's steps" : "steps a-d");
        Planned reuse(scene, kW, kH, reuseOptions(1, 8, true, paper));
        step(reuse, world0, "frame 0");
        const std::vector<glm::mat4> w1 = moved({j}, 0.3f), w2 = moved({j}, 0.6f);
        const Box old0 = instanceExtent(scene, j, params, world0[std::size_t(nodeOf(j))]);
        const Box old1 = instanceExtent(scene, j, params, w1[std::size_t(nodeOf(j))]);
        const Box rest = instanceExtent(scene, j, params, w2[std::size_t(nodeOf(j))]);
        ASSERT_FALSE(old0.empty());

        // Frame 1, P_sd: its old extent cleared, the static instances there redrawn, it drawn last.
        FramePlan plan = step(reuse, w1, "frame 1");
        const ReuseFrameStats* s = &reuse.stats();
        EXPECT_EQ(s->mode, ReuseMode::Reuse);
        EXPECT_EQ(s->instances.sd, 1u);
        EXPECT_EQ(s->instances.ss, n() - 1);
        EXPECT_EQ(s->triangles.sd, 12u);
        EXPECT_TRUE(reuse.dynamic(j));
        EXPECT_TRUE(covers(maskOf(clearsOf(plan)), old0));
        if (paper) {
            EXPECT_TRUE(rectsOf(plan, Op::Copy, S, R).empty()) << "no P_dd: nothing copied in";
            EXPECT_TRUE(covers(maskOf(rectsOf(plan, Op::Copy, R, S)), old0)) << "copied back";
        } else {
            EXPECT_TRUE(covers(maskOf(rectsOf(plan, Op::Clear, S, S)), old0)) << "cleared in the static pair";
            EXPECT_TRUE(covers(maskOf(rectsOf(plan, Op::Copy, S, R)), old0)) << "copied to the render target";
        }
        ASSERT_FALSE(plan.empty());
        ASSERT_EQ(plan.back().op, Op::Draw);
        EXPECT_EQ(plan.back().to, R);
        ASSERT_EQ(plan.back().draws.size(), 1u);
        EXPECT_EQ(plan.back().draws[0].instance, j);
        EXPECT_EQ(triangles(plan.back().draws), 12u);
        EXPECT_EQ(s->redrawnTris, s->staticRedrawnTris + 12u);
        EXPECT_GT(s->staticRedrawnTris, 0u) << "the dominoes overlap their neighbours' extents";

        // Frame 2, P_dd: the static pair copied over its frame-1 extent, nothing cleared or redrawn.
        plan = step(reuse, w2, "frame 2");
        s = &reuse.stats();
        EXPECT_EQ(s->mode, ReuseMode::Reuse);
        EXPECT_EQ(s->instances.dd, 1u);
        EXPECT_EQ(s->instances.ss, n() - 1);
        EXPECT_TRUE(clearsOf(plan).empty());
        EXPECT_TRUE(covers(maskOf(rectsOf(plan, Op::Copy, S, R)), old1));
        EXPECT_EQ(s->staticRedrawnTris, 0u);
        EXPECT_EQ(plan.back().draws.size(), 1u);

        // Frame 3, P_ds: it joins the static pair.
        plan = step(reuse, w2, "frame 3");
        s = &reuse.stats();
        EXPECT_EQ(s->mode, ReuseMode::Reuse);
        EXPECT_EQ(s->instances.ds, 1u);
        EXPECT_FALSE(reuse.dynamic(j));
        if (paper) {
            // Its pixels from frame 2 are kept and copied back; nothing cleared, nothing drawn.
            EXPECT_TRUE(covers(maskOf(rectsOf(plan, Op::Copy, R, S)), rest));
            EXPECT_TRUE(clearsOf(plan).empty());
            EXPECT_EQ(s->redrawnTris, 0u);
        } else {
            // Its extent cleared in the static pair, every static instance there redrawn in list
            // order (itself included), and copied to the render target.
            EXPECT_TRUE(covers(maskOf(rectsOf(plan, Op::Clear, S, S)), rest));
            EXPECT_TRUE(covers(maskOf(rectsOf(plan, Op::Copy, S, R)), rest));
            const std::vector<const DrawCommand*> redraws = drawsInto(plan, S);
            EXPECT_TRUE(std::any_of(redraws.begin(), redraws.end(), [&](const DrawCommand* c) { return c->instance == j; }));
            EXPECT_GT(redraws.size(), 1u);
            EXPECT_EQ(s->redrawnTris, s->staticRedrawnTris);
            EXPECT_TRUE(drawsInto(plan, R).empty());
        }

        // Frame 4, P_ss: nothing at all.
        plan = step(reuse, w2, "frame 4");
        EXPECT_EQ(reuse.stats().instances.ss, n());
        EXPECT_TRUE(plan.empty()) << describe(plan);
    }
}

TEST_F(ReusePlanner, CameraMoveIsFullThenRebuildThenReuse) {
    Planned reuse(scene, kW, kH);
    FrameParams other = params;
    other.view = glm::translate(params.view, {0.2f, 0.0f, 0.0f});
    struct Frame {
        const FrameParams* frame;
        ReuseMode mode;
        const char* reason;
    };
    const Frame frames[] = {
        {&params, ReuseMode::Rebuild, "first frame"},
        {&params, ReuseMode::Reuse, "camera still"},
        {&other, ReuseMode::Full, "camera, light or background changed"},
        {&other, ReuseMode::Rebuild, "first still frame"},
        {&other, ReuseMode::Reuse, "camera still"},
        {&params, ReuseMode::Full, "camera, light or background changed"},
        {&other, ReuseMode::Full, "camera, light or background changed"},
        {&other, ReuseMode::Rebuild, "first still frame"},
        {&other, ReuseMode::Reuse, "camera still"},
    };
    for (std::size_t i = 0; i < std::size(frames); ++i) {
        // One domino moves every frame, so that every reuse frame has something to do.
        step(reuse, moved({int(i % n())}, 0.1f * float(i)), "frame " + std::to_string(i), nullptr, frames[i].frame);
        EXPECT_EQ(reuse.stats().mode, frames[i].mode) << "frame " << i << ": " << reuse.stats().reason;
        EXPECT_EQ(reuse.stats().reason, frames[i].reason) << "frame " << i;
        EXPECT_EQ(reuse.staticValid(), frames[i].mode != ReuseMode::Full) << "frame " << i;
    }
}

TEST_F(ReusePlanner, LightBackgroundOrIdsChangedIsAFullRender) {
    for (int what = 0; what < 5; ++what) {
        SCOPED_TRACE(what);
        Planned reuse(scene, kW, kH);
        step(reuse, world0, "frame 0");
        FrameParams changed = params;
        glm::vec4 background = kReuseBackground;
        if (what == 0) changed.lighting.toLight = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
        if (what == 1) changed.lighting.environment = 0.31f;
        if (what == 2) changed.lighting.light = 2.2f;
        if (what == 3) changed.writeIds = false;
        if (what == 4) background = {0.1f, 0.15f, 0.2f, 0.5f};
        step(reuse, world0, "frame 1", nullptr, &changed, background);
        EXPECT_EQ(reuse.stats().mode, ReuseMode::Full) << reuse.stats().reason;
        EXPECT_FALSE(reuse.staticValid());
        step(reuse, world0, "frame 2", nullptr, &changed, background);
        EXPECT_EQ(reuse.stats().mode, ReuseMode::Rebuild) << reuse.stats().reason;
    }
}

TEST_F(ReusePlanner, InvalidateForcesARebuild) {
    Planned reuse(scene, kW, kH);
    step(reuse, world0, "frame 0");
    step(reuse, world0, "frame 1");
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Reuse);
    reuse.invalidate();
    EXPECT_FALSE(reuse.staticValid());
    step(reuse, world0, "frame 2");
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Rebuild);
    EXPECT_EQ(reuse.stats().reason, "first still frame");
    EXPECT_TRUE(reuse.staticValid());
}

TEST_F(ReusePlanner, EverythingDynamicFallsBackToFull) {
    std::vector<int> all;
    for (int i = 0; i < int(n()); ++i) all.push_back(i);
    Planned reuse(scene, kW, kH);
    step(reuse, world0, "frame 0");
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Rebuild);
    std::string modes;
    for (int i = 1; i < 8; ++i) {
        step(reuse, moved(all, 0.05f * float(i)), "frame " + std::to_string(i));
        const ReuseFrameStats& s = reuse.stats();
        EXPECT_EQ(s.instances.sd + s.instances.dd, n()) << "frame " << i;
        EXPECT_EQ(s.mode, ReuseMode::Full) << "frame " << i << ": everything moves, reuse cannot pay; " << s.reason
                                           << " (copied " << s.copiedPx << ", cleared " << s.clearedPx << ")";
        modes += toString(s.mode) + std::string(" ");
    }
    // With the camera moving too, a rebuild would be followed by everything dynamic: no rebuild.
    FrameParams other = params;
    other.view = glm::translate(params.view, {0.2f, 0.0f, 0.0f});
    step(reuse, moved(all, 1.0f), "moved", nullptr, &other);
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Full);
    step(reuse, moved(all, 1.1f), "still, all dynamic", nullptr, &other);
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Full);
    EXPECT_NE(reuse.stats().reason.find("too dynamic"), std::string::npos) << reuse.stats().reason;
}

TEST_F(ReusePlanner, WithoutFallbackEverythingDynamicStillReuses) {
    std::vector<int> all;
    for (int i = 0; i < int(n()); ++i) all.push_back(i);
    ReuseOptions options;
    options.fallback = false;
    Planned reuse(scene, kW, kH, options);
    step(reuse, world0, "frame 0");
    for (int i = 1; i < 6; ++i) {
        step(reuse, moved(all, 0.05f * float(i)), "frame " + std::to_string(i));
        EXPECT_EQ(reuse.stats().mode, ReuseMode::Reuse) << "frame " << i << ": " << reuse.stats().reason;
    }
    // A rebuild with everything dynamic, too.
    FrameParams other = params;
    other.view = glm::translate(params.view, {0.2f, 0.0f, 0.0f});
    step(reuse, moved(all, 1.0f), "moved", nullptr, &other);
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Full);
    step(reuse, moved(all, 1.1f), "still", nullptr, &other);
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Rebuild);
}

TEST_F(ReusePlanner, MaterialChangesMakeTheirInstancesDynamic) {
    // Dominoes: instance i draws mesh i % 6 with material i % 6.
    // (No fallback: the states are the point here, not the cost model's decision.)
    Planned reuse(scene, kW, kH, reuseOptions(16, 16, false));
    step(reuse, world0, "frame 0");
    const auto users = [this](int material) {
        std::uint64_t k = 0;
        for (const Instance& instance : scene.instances) k += scene.meshes[std::size_t(instance.mesh)].material == material ? 1 : 0;
        return k;
    };
    scene.materials[2].baseColorFactor.g += 0.01f;
    FramePlan plan = step(reuse, world0, "colour");
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Reuse);
    EXPECT_EQ(reuse.stats().instances.sd, users(2));
    ASSERT_FALSE(plan.empty());
    for (const DrawCommand& c : plan.back().draws) EXPECT_EQ(c.instance % 6, 2);
    step(reuse, world0, "after colour");
    EXPECT_EQ(reuse.stats().instances.ds, users(2));

    scene.materials[4].doubleSided = true;
    step(reuse, world0, "sidedness");
    EXPECT_EQ(reuse.stats().instances.sd, users(4));
    EXPECT_EQ(reuse.stats().instances.ds, 0u);
    step(reuse, world0, "after sidedness");
    EXPECT_EQ(reuse.stats().instances.ds, users(4));

    // Every member counts: here the roughness and an occlusion map's strength.
    scene.materials[3].roughnessFactor *= 0.5f;
    step(reuse, world0, "roughness");
    EXPECT_EQ(reuse.stats().instances.sd, users(3));
    step(reuse, world0, "after roughness");
    scene.materials[3].occlusionStrength = 0.5f;
    step(reuse, world0, "occlusion strength");
    EXPECT_EQ(reuse.stats().instances.sd, users(3));
    step(reuse, world0, "after occlusion strength");

    scene.materials[1].baseColorTexture = 0;  // a texture index (the scene has none: never drawn here)
    step(reuse, world0, "texture");
    EXPECT_EQ(reuse.stats().instances.sd, users(1));
    scene.materials[1].baseColorTexture = -1;
    step(reuse, world0, "texture back");
    EXPECT_EQ(reuse.stats().instances.dd, users(1));
    step(reuse, world0, "rest");
    EXPECT_EQ(reuse.stats().instances.ds, users(1));
    step(reuse, world0, "rest 2");
    EXPECT_EQ(reuse.stats().instances.ss, n());
}

TEST_F(ReusePlanner, LeavingAndJoiningTheDrawListAreChanges) {
    const int j = 25;
    DrawList without;
    for (const DrawCommand& c : list)
        if (c.instance != j) without.push_back(c);
    Planned reuse(scene, kW, kH, reuseOptions(4, 8, false));
    step(reuse, world0, "frame 0");
    const Box old = instanceExtent(scene, j, params, world0[std::size_t(nodeOf(j))]);

    FramePlan plan = step(reuse, world0, "left", &without);
    EXPECT_EQ(reuse.stats().mode, ReuseMode::Reuse);
    EXPECT_EQ(reuse.stats().instances.sd, 1u);
    EXPECT_EQ(reuse.stats().drawnTris, total - 12);
    EXPECT_TRUE(covers(maskOf(clearsOf(plan)), old));
    for (const PlanStep& s : plan)
        for (const DrawCommand& c : drawsOf(s)) EXPECT_NE(c.instance, j) << "not in the list: never drawn";

    step(reuse, world0, "still away", &without);
    EXPECT_EQ(reuse.stats().instances.ds, 1u);
    plan = step(reuse, world0, "still away 2", &without);
    EXPECT_EQ(reuse.stats().instances.ss, n());
    EXPECT_TRUE(plan.empty());

    plan = step(reuse, world0, "back", &list);
    EXPECT_EQ(reuse.stats().instances.sd, 1u);
    ASSERT_FALSE(plan.empty());
    ASSERT_EQ(plan.back().draws.size(), 1u);
    EXPECT_EQ(plan.back().draws[0].instance, j);

    // Other ranges of the same instance are a change; the same ranges split differently are not.
    step(reuse, world0, "rest");
    DrawList partial = list, split = list;
    for (DrawCommand& c : partial)
        if (c.instance == j) c.ranges = {{0, 6}};
    for (DrawCommand& c : split)
        if (c.instance == j) c.ranges = {{0, 5}, {5, 7}};
    step(reuse, world0, "partial", &partial);
    EXPECT_EQ(reuse.stats().instances.sd, 1u);
    EXPECT_EQ(reuse.stats().drawnTris, total - 6);
    step(reuse, world0, "whole again", &list);
    EXPECT_EQ(reuse.stats().instances.dd, 1u);
    step(reuse, world0, "whole, rest", &list);
    EXPECT_EQ(reuse.stats().instances.ds, 1u);
    step(reuse, world0, "split", &split);
    EXPECT_EQ(reuse.stats().instances.ss, n()) << "{0,5},{5,7} draws what {0,12} draws";
}

TEST_F(ReusePlanner, MatricesAreComparedBitForBit) {
    // Reuse.h: a NaN pose that keeps its bits is static (it draws the same nothing); one whose bits
    // change is dynamic; -0 and +0 differ.
    const int j = 7, k = 9;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Planned reuse(scene, kW, kH);
    std::vector<glm::mat4> world = world0;
    world[std::size_t(nodeOf(j))][3][1] = nan;
    step(reuse, world, "frame 0");
    EXPECT_EQ(reuse.stats().instances.ss, n()) << "the first frame counts everything static";
    step(reuse, world, "frame 1: same NaN");
    EXPECT_EQ(reuse.stats().instances.ss, n());
    world[std::size_t(nodeOf(j))][3][0] += 1.0f;  // a NaN pose, other bits
    step(reuse, world, "frame 2: NaN moved");
    EXPECT_EQ(reuse.stats().instances.sd, 1u);
    step(reuse, world, "frame 3: same NaN");
    EXPECT_EQ(reuse.stats().instances.ds, 1u);
    // -0 for +0 (a model matrix entry that is +0 in world0).
    glm::mat4& m = world[std::size_t(nodeOf(k))];
    int row = -1, column = -1;
    for (int c = 0; c < 4 && row < 0; ++c)
        for (int r = 0; r < 4; ++r)
            if (m[c][r] == 0.0f && !std::signbit(m[c][r])) {
                column = c;
                row = r;
                break;
            }
    ASSERT_GE(row, 0);
    m[column][row] = -0.0f;
    step(reuse, world, "frame 4: -0");
    EXPECT_EQ(reuse.stats().instances.sd, 1u);
    EXPECT_EQ(reuse.stats().instances.ss, n() - 1);
}

TEST_F(ReusePlanner, RedrawsFollowAnyListOrder) {
    // The list reversed, and every other instance cut to its first half: redraws and dynamic
    // draws come in this order and within these ranges (checkPlan), at every grain.
    DrawList odd(list.rbegin(), list.rend());
    for (std::size_t k = 0; k < odd.size(); k += 2) odd[k].ranges = {{0, 6}};
    for (int grain : {0, 1, 4, 16}) {
        SCOPED_TRACE("grain " + std::to_string(grain));
        Planned reuse(scene, kW, kH, reuseOptions(grain, 4, false));
        step(reuse, world0, "frame 0", &odd);
        std::size_t redrawSteps = 0;
        for (int i = 1; i < 6; ++i) {
            const FramePlan plan = step(reuse, moved({10 * i, 10 * i + 1, 10 * i + 30}, 0.2f), "frame " + std::to_string(i), &odd);
            EXPECT_EQ(reuse.stats().mode, ReuseMode::Reuse);
            redrawSteps += stepsOf(plan, PlanStep::Op::Draw).size() >= 2 ? 1 : 0;
            if (grain == 0) {
                // Per instance: a redraw is the instance's ranges as listed.
                for (const PlanStep* s : stepsOf(plan, PlanStep::Op::Draw))
                    for (const DrawCommand& c : s->draws) {
                        const auto it = std::find_if(odd.begin(), odd.end(), [&c](const DrawCommand& d) { return d.instance == c.instance; });
                        ASSERT_NE(it, odd.end());
                        EXPECT_EQ(triangles({c}), triangles({*it}));
                    }
            }
        }
        EXPECT_GT(redrawSteps, 0u) << "some frames redraw static instances";
    }
}

// The real animation: dominoes falling. The states follow from the matrices, frame by frame.
TEST_F(ReusePlanner, StatesFollowTheAnimation) {
    for (int grain : {0, 1, 16}) {
        SCOPED_TRACE("grain " + std::to_string(grain));
        Planned reuse(scene, kW, kH, reuseOptions(grain, 16));
        std::vector<glm::mat4> previous;
        std::vector<bool> wasDynamic(n(), false);
        for (int f = 0; f < 12; ++f) {
            const std::vector<glm::mat4> world = scene.worldTransforms(frameTime(f, scene.fps));
            step(reuse, world, "frame " + std::to_string(f));
            const ReuseFrameStats& s = reuse.stats();
            ReuseCounts expected;
            std::vector<bool> dynamic(n(), false);
            for (std::size_t i = 0; i < n(); ++i) {
                const std::size_t node = std::size_t(nodeOf(int(i)));
                dynamic[i] = f > 0 && world[node] != previous[node];
                countOf(expected, (wasDynamic[i] ? 0 : 2) + (dynamic[i] ? 0 : 1)) += 1;
            }
            EXPECT_EQ(s.instances, expected) << "frame " << f;
            EXPECT_EQ(s.mode, f == 0 ? ReuseMode::Rebuild : ReuseMode::Reuse) << "frame " << f << ": " << s.reason;
            previous = world;
            wasDynamic = dynamic;
        }
    }
}

// Full frames, whatever made them full, report what a full frame does: one clear of the whole
// target, every triangle drawn, nothing copied. Reasons: the camera moved, too dynamic to rebuild,
// reuse would cost more than a full render, a draw list naming an instance twice.
TEST_F(ReusePlanner, FullFramesReportWhatTheyDo) {
    std::vector<int> all;
    for (int i = 0; i < int(n()); ++i) all.push_back(i);
    FrameParams other = params;
    other.view = glm::translate(params.view, {0.2f, 0.0f, 0.0f});
    DrawList twice = list;
    twice.push_back(list[3]);
    Planned reuse(scene, kW, kH);
    struct Frame {
        std::vector<glm::mat4> world;
        const FrameParams* frame;
        const DrawList* list;
        const char* reason;  // of the full frame expected, or nullptr
    };
    const std::vector<Frame> frames = {
        {world0, &params, &list, nullptr},
        {moved(all, 0.1f), &params, &list, "reuse would cost more than a full render"},
        {moved(all, 0.2f), &params, &list, "too dynamic to rebuild the static pair (over half the triangles changed)"},
        {moved(all, 0.2f), &params, &list, nullptr},
        {moved(all, 0.2f), &other, &list, "camera, light or background changed"},
        {moved(all, 0.2f), &other, &list, nullptr},
        {moved(all, 0.2f), &other, &twice, "the draw list names an instance twice or one the scene does not have"},
    };
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Frame& f = frames[i];
        const FramePlan plan = reuse.plan(*f.frame, f.world, *f.list, kReuseBackground);
        const ReuseFrameStats& s = reuse.stats();
        if (!f.reason) {
            EXPECT_NE(s.mode, ReuseMode::Full) << "frame " << i << ": " << s.reason;
            continue;
        }
        SCOPED_TRACE("frame " + std::to_string(i) + ": " + s.reason);
        ASSERT_EQ(s.mode, ReuseMode::Full);
        EXPECT_EQ(s.reason, f.reason);
        ASSERT_EQ(plan.size(), 2u);
        EXPECT_EQ(s.clearedPx, kScreen);
        EXPECT_EQ(s.copiedPx, 0u) << "a full frame copies nothing";
        EXPECT_EQ(s.rects, 1u) << "a full frame issues one rectangle, its clear";
        EXPECT_EQ(s.redrawnTris, triangles(*f.list));
        EXPECT_EQ(s.redrawnTris, s.drawnTris);
    }
}

// The whole-scene overload plans what the list overload plans with fullDrawList.
TEST_F(ReusePlanner, WholeSceneOverloadMatchesTheFullList) {
    TemporalReuse a(scene, kW, kH);
    Planned b(scene, kW, kH);
    FrameParams other = params;
    other.view = glm::translate(params.view, {0.2f, 0.0f, 0.0f});
    for (int f = 0; f < 10; ++f) {
        const std::vector<glm::mat4> world = scene.worldTransforms(frameTime(f, scene.fps));
        const FrameParams& frame = f == 5 ? other : params;
        const FramePlan pa = a.plan(frame, world, list, kReuseBackground);
        const FramePlan pb = b.plan(frame, world, kReuseBackground);
        checkPlan(pb, b, list, "whole scene, frame " + std::to_string(f));
        EXPECT_EQ(a.stats().mode, b.stats().mode) << "frame " << f;
        EXPECT_EQ(a.stats().instances, b.stats().instances) << "frame " << f;
        EXPECT_EQ(a.stats().copiedPx, b.stats().copiedPx) << "frame " << f;
        EXPECT_EQ(a.stats().clearedPx, b.stats().clearedPx) << "frame " << f;
        EXPECT_EQ(a.stats().redrawnTris, b.stats().redrawnTris) << "frame " << f;
        EXPECT_EQ(describe(pa), describe(pb)) << "frame " << f;
        for (std::size_t i = 0; i < n(); ++i) EXPECT_EQ(a.dynamicNow(int(i)), b.planner().dynamicNow(int(i)));
    }
}

// TemporalReuse::dynamicNow (Reuse.h): "After plan(): whether `instance` is dynamic in that frame".
TEST_F(ReusePlanner, DynamicNowNamesThisFramesChanges) {
    const int j = 12;
    TemporalReuse reuse(scene, kW, kH);
    reuse.plan(params, world0, list, kReuseBackground);
    EXPECT_FALSE(reuse.dynamicNow(j)) << "first frame: everything static";
    reuse.plan(params, moved({j}, 0.2f), list, kReuseBackground);
    EXPECT_TRUE(reuse.dynamicNow(j)) << "moved in this frame";
    EXPECT_FALSE(reuse.dynamicNow(j + 1));
    reuse.plan(params, moved({j}, 0.2f), list, kReuseBackground);
    EXPECT_FALSE(reuse.dynamicNow(j)) << "at rest in this frame";
    reuse.plan(params, moved({j}, 0.4f), list, kReuseBackground);
    EXPECT_TRUE(reuse.dynamicNow(j)) << "moved again";
    EXPECT_FALSE(reuse.dynamicNow(-1));
    EXPECT_FALSE(reuse.dynamicNow(int(n())));
}

}  // namespace
}  // namespace frugal::test
