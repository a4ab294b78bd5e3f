#include "reuse/Reuse.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "pipeline/IndexRanges.h"

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Region bits of a grid cell.
constexpr std::uint8_t kClear = 1;  // a previous extent of P_sd (exact static: or of P_ds): cleared, redrawn
constexpr std::uint8_t kCopy = 2;   // a previous extent of P_dd: copied from the static pair
constexpr std::uint8_t kBack = 4;   // paper's steps: an extent of P_ds (not cleared), copied back (step 5)
constexpr int kSlotClear = 0;       // sealed mask kClear: what P_ss (exact static: every static) meets
constexpr int kSlotDirty = 1;       // paper's steps: kClear | kCopy, what P_ds is tested against

bool sameFrame(const FrameParams& a, const FrameParams& b) {
    return a.view == b.view && a.projection == b.projection && a.lighting == b.lighting && a.tonemap == b.tonemap &&
           a.shading == b.shading && a.writeIds == b.writeIds;
}

bool sameRanges(const std::vector<IndexRange>& a, const std::vector<IndexRange>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const IndexRange& x, const IndexRange& y) {
        return x.firstTriangle == y.firstTriangle && x.triangleCount == y.triangleCount;
    });
}

}  // namespace

TemporalReuse::TemporalReuse(const Scene& scene, int width, int height, ReuseOptions options)
    : scene_(&scene), width_(width), height_(height), options_(options), records_(scene.instances.size()),
      fullList_(fullDrawList(scene)), builder_(width, height), grid_(width, height, options.cell),
      nowDynamic_(records_.size(), 0),
      wasDynamic_(records_.size(), 0) {
    std::uint32_t groups = 0;
    info_.resize(records_.size());
    models_.resize(records_.size());
    for (std::size_t i = 0; i < records_.size(); ++i) {
        const Mesh& mesh = scene.meshes[scene.instances[i].mesh];
        const std::uint32_t triangles = std::uint32_t(mesh.primitiveCount());
        info_[i] = InstanceInfo{scene.instances[i].node, mesh.material, triangles};
        const std::uint32_t size = groupSize(int(i));
        records_[i].firstGroup = groups;
        records_[i].groups = triangles == 0 ? 0 : (triangles + size - 1) / size;
        groups += records_[i].groups;
    }
    extents_.assign(groups, reuse::Box{});
    instanceBoxes_.assign(records_.size(), reuse::Box{});
    weights_.resize(records_.size());
    joints_.resize(records_.size());
    posed_.resize(records_.size());
}

std::uint32_t TemporalReuse::groupSize(int instance) const {
    const std::uint32_t triangles = info_[std::size_t(instance)].triangles;
    return options_.grain <= 0 ? std::max<std::uint32_t>(1, triangles) : std::uint32_t(options_.grain);
}

void TemporalReuse::computeExtents(int instance, const glm::mat4& viewProjection, const std::vector<glm::mat4>& world) {
    const Record& record = records_[instance];
    reuse::Box* groups = extents_.data() + record.firstGroup;
    reuse::Box& whole = instanceBoxes_[instance];
    whole = reuse::Box{};
    std::fill(groups, groups + record.groups, reuse::Box{});
    if (!record.drawn) return;
    const Instance& inst = scene_->instances[instance];
    const Mesh& mesh = scene_->meshes[inst.mesh];
    builder_.project(viewProjection * world[inst.node],
                     posed_[std::size_t(instance)].empty() ? mesh.positions : posed_[std::size_t(instance)]);
    const std::uint32_t size = groupSize(instance);
    const std::uint32_t triangles = std::uint32_t(mesh.primitiveCount());
    const std::uint32_t* index = mesh.indices.data();
    const std::uint32_t corners = std::uint32_t(verticesPerPrimitive(mesh.topology));
    const auto primitiveBox = [&](std::uint32_t t) {
        const std::uint32_t* at = index + std::size_t(t) * corners;
        return corners == 3 ? builder_.triangle(at[0], at[1], at[2]) : builder_.segment(at[0], at[corners - 1]);
    };
    for (std::uint32_t g = 0; g < record.groups; ++g) {
        reuse::Box box;
        const std::uint32_t end = std::min(triangles, (g + 1) * size);
        for (std::uint32_t t = g * size; t < end; ++t) box.add(primitiveBox(t));
        groups[g] = box;
        whole.add(box);
    }
}

FramePlan TemporalReuse::fullPlan(const DrawList& list, const char* reason) {
    stats_.mode = ReuseMode::Full;
    stats_.reason = reason;
    // What a full frame does, whatever a rejected reuse plan had counted: one clear, every triangle.
    stats_.clearedPx = std::uint64_t(width_) * std::uint64_t(height_);
    stats_.copiedPx = 0;
    stats_.rects = 1;
    stats_.redrawnTris = stats_.drawnTris;
    stats_.staticRedrawnTris = 0;
    staticValid_ = false;
    FramePlan plan;
    plan.push_back({PlanStep::Op::Clear, PlanTarget::Render, PlanTarget::Render, {Rect{0, 0, width_, height_}}, {}});
    // The whole scene's list is the planner's own and outlives the plan; a caller's list is copied.
    if (&list == &fullList_)
        plan.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, {}, &fullList_});
    else
        plan.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, list});
    return plan;
}

FramePlan TemporalReuse::plan(const FrameParams& frame, const std::vector<glm::mat4>& world, const DrawList& list,
                              const glm::vec4& background) {
    const auto start = Clock::now();
    FramePlan plan = makePlan(frame, world, list, background, false);
    stats_.planMs = msSince(start);
    return plan;
}

FramePlan TemporalReuse::plan(const FrameParams& frame, const std::vector<glm::mat4>& world,
                              const glm::vec4& background) {
    const auto start = Clock::now();
    FramePlan plan = makePlan(frame, world, fullList_, background, true);
    stats_.planMs = msSince(start);
    return plan;
}

FramePlan TemporalReuse::makePlan(const FrameParams& frame, const std::vector<glm::mat4>& world, const DrawList& list,
                                  const glm::vec4& background, bool wholeScene) {
    stats_ = ReuseFrameStats{};
    const bool still = history_ && sameFrame(frame, lastFrame_) && background == lastBackground_;
    const bool first = !history_;
    // The whole scene twice in a row: every instance draws its whole mesh, as before.
    const bool wholeAgain = wholeScene && lastWhole_;
    lastWhole_ = wholeScene;
    history_ = true;
    lastFrame_ = frame;
    lastBackground_ = background;

    if (scene_->deforms()) frameWeights_ = scene_->morphWeights(frame.time);
    Changes changes;
    if (!classify(list, world, first, wholeAgain, changes)) {
        // Not a list reuse can split into static and dynamic instances: draw it as it is, and
        // start afresh (the next frame is a first frame).
        history_ = false;
        std::fill(wasDynamic_.begin(), wasDynamic_.end(), std::uint8_t(0));
        return fullPlan(list, "the draw list names an instance twice or one the scene does not have");
    }
    const ReuseCosts& cost = options_.costs;
    const double fullCost = double(stats_.drawnTris) + cost.draw * double(list.size()) +
                            cost.pixelCleared * double(width_) * double(height_);
    const glm::mat4 viewProjection = frame.projection * frame.view;
    FramePlan plan;
    if (!first && !still)
        plan = fullPlan(list, "camera, light or background changed");
    else if (!staticValid_ && options_.fallback && 2 * changes.triangles > stats_.drawnTris)
        plan = fullPlan(list, "too dynamic to rebuild the static pair (over half the triangles changed)");
    else if (!staticValid_)
        plan = rebuildPlan(list, world, viewProjection, first, changes);
    else if (options_.fallback && double(changes.triangles) + cost.draw * double(changes.draws) >= fullCost)
        plan = fullPlan(list, "too dynamic: the changed triangles alone cost a full render");
    else
        plan = reusePlan(list, world, viewProjection, fullCost, changes);
    // This frame's flags become the previous frame's.
    wasDynamic_.swap(nowDynamic_);
    return plan;
}

bool TemporalReuse::classify(const DrawList& list, const std::vector<glm::mat4>& world, bool first, bool wholeAgain,
                             Changes& changes) {
    const std::size_t n = records_.size();
    std::vector<const DrawCommand*> byInstance(n, nullptr);
    bool wellFormed = true;
    for (const DrawCommand& command : list) {
        if (command.instance < 0 || std::size_t(command.instance) >= n || byInstance[command.instance] != nullptr)
            wellFormed = false;
        else
            byInstance[command.instance] = &command;
    }
    if (!wellFormed) {
        std::vector<IndexRange> ranges;
        for (const DrawCommand& command : list) {
            const bool known = command.instance >= 0 && std::size_t(command.instance) < n;
            if (known) stats_.drawnTris += normalizeRanges(command.ranges, info_[std::size_t(command.instance)].triangles, ranges);
        }
        return false;
    }

    // Materials first (few): which changed since the previous frame. Index 0 is the default material.
    const std::vector<Material>& materials = scene_->materials;
    const bool resized = materialKeys_.size() != materials.size() + 1;
    materialKeys_.resize(materials.size() + 1);
    materialChanged_.assign(materials.size() + 1, resized ? 1 : 0);
    materialChanged_[0] = 0;
    for (std::size_t m = 0; m < materials.size(); ++m) {
        // Any member: every one of them is drawn (the name too, which costs nothing to compare).
        if (materials[m] == materialKeys_[m + 1]) continue;
        materialChanged_[m + 1] = 1;
        materialKeys_[m + 1] = materials[m];
    }
    std::vector<IndexRange> ranges;
    for (std::size_t i = 0; i < n; ++i) {
        // The ranges live on the heap, one allocation per command: fetch them ahead of the loop.
        constexpr std::size_t kAhead = 16;
        if (!wholeAgain && i + kAhead < n && byInstance[i + kAhead] != nullptr)
            __builtin_prefetch(byInstance[i + kAhead]->ranges.data());
        const InstanceInfo& info = info_[i];
        Record& record = records_[i];
        // The pose, bit for bit.
        const glm::mat4& model = world[std::size_t(info.node)];
        bool changed = !first && (std::memcmp(&model, &models_[i], sizeof model) != 0 ||
                                  materialChanged_[std::size_t(info.material + 1)] != 0);
        if (changed || first) models_[i] = model;
        // The pose of a deforming instance: its morph weights and joint matrices, value for value (a
        // NaN is never equal: dynamic every frame).
        const Instance& instance = scene_->instances[i];
        if (scene_->deforms(instance)) {
            const Mesh& mesh = scene_->meshes[std::size_t(instance.mesh)];
            const std::vector<float>& now = frameWeights_[std::size_t(info.node)];
            std::vector<glm::mat4> joints = scene_->jointMatrices(instance, world);
            if (first || now != weights_[i] || joints != joints_[i]) {
                changed = changed || !first;
                weights_[i] = now;
                poseVertices(mesh, now, joints, poseScratch_, /*frames=*/false);  // positions are all it needs
                posed_[i].swap(poseScratch_.positions);
                joints_[i] = std::move(joints);
            }
        }
        // The drawn ranges: the whole mesh again (the common case), or compared once normalised.
        const DrawCommand* command = byInstance[i];
        const bool same = !first && command && record.drawn && (wholeAgain || sameRanges(command->ranges, record.ranges));
        if (!same) {
            const std::uint64_t drawn = command ? normalizeRanges(command->ranges, info.triangles, ranges) : 0;
            if (!command) ranges.clear();
            const bool rangesChanged = (drawn > 0) != record.drawn || !sameRanges(ranges, record.ranges);
            changed = changed || (!first && rangesChanged);
            if (rangesChanged || first) {
                record.ranges.swap(ranges);
                record.drawn = drawn > 0;
                record.drawnTris = drawn;
            }
        }
        // A blended instance is dynamic in every frame, the first too: it must be drawn after every
        // opaque one, so it never enters the static pair (Reuse.h).
        if (info.material >= 0 && materials[std::size_t(info.material)].alphaMode == AlphaMode::Blend) changed = true;
        nowDynamic_[i] = changed ? 1 : 0;
        const int state = (wasDynamic_[i] ? 0 : 2) + (changed ? 0 : 1);
        countOf(stats_.instances, state) += 1;
        countOf(stats_.triangles, state) += info.triangles;
        stats_.drawnTris += record.drawnTris;
        if (changed) changes.triangles += record.drawnTris;
        if (changed && record.drawn) ++changes.draws;
    }
    return true;
}

FramePlan TemporalReuse::rebuildPlan(const DrawList& list, const std::vector<glm::mat4>& world,
                                     const glm::mat4& viewProjection, bool first, const Changes& changes) {
    // The static instances, the whole target into the static pair, the dynamic ones; and the
    // extents of everything, as drawn now.
    const auto t0 = Clock::now();
    for (std::size_t i = 0; i < records_.size(); ++i) computeExtents(int(i), viewProjection, world);
    stats_.extentMs = msSince(t0);
    stats_.mode = ReuseMode::Rebuild;
    stats_.reason = first ? "first frame" : "first still frame";
    DrawList statics, dynamics;
    for (const DrawCommand& command : list) (nowDynamic_[command.instance] ? dynamics : statics).push_back(command);
    const Rect whole{0, 0, width_, height_};
    FramePlan plan;
    plan.push_back({PlanStep::Op::Clear, PlanTarget::Render, PlanTarget::Render, {whole}, {}});
    if (!statics.empty())
        plan.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, std::move(statics)});
    plan.push_back({PlanStep::Op::Copy, PlanTarget::Render, PlanTarget::Static, {whole}, {}});
    if (!dynamics.empty())
        plan.push_back({PlanStep::Op::Draw, PlanTarget::Render, PlanTarget::Render, {}, std::move(dynamics)});
    stats_.clearedPx = stats_.copiedPx = std::uint64_t(width_) * std::uint64_t(height_);
    stats_.redrawnTris = stats_.drawnTris;
    stats_.staticRedrawnTris = stats_.drawnTris - changes.triangles;
    stats_.rects = 2;
    staticValid_ = true;
    return plan;
}

FramePlan TemporalReuse::reusePlan(const DrawList& list, const std::vector<glm::mat4>& world,
                                   const glm::mat4& viewProjection, double fullCost, const Changes& changes) {
    const std::size_t n = records_.size();
    const ReuseCosts& cost = options_.costs;

    // The regions, and the static groups they make us redraw (the ⊗ tests).
    const bool paper = options_.paperSteps;
    const auto t0 = Clock::now();
    grid_.reset();
    for (std::size_t i = 0; i < n; ++i) {
        const int state = (wasDynamic_[i] ? 0 : 2) + (nowDynamic_[i] ? 0 : 1);
        if (state == kSS) continue;
        const std::uint8_t bits = state == kSD ? kClear : state == kDD ? kCopy : paper ? kBack : kClear;
        const Record& record = records_[i];
        for (std::uint32_t g = 0; g < record.groups; ++g) grid_.mark(extents_[record.firstGroup + g], bits);
    }
    grid_.seal(kSlotClear, kClear);
    if (paper) grid_.seal(kSlotDirty, kClear | kCopy);
    DrawList redraws, dynamics;
    std::uint64_t redrawn = 0;
    std::vector<std::uint8_t> hit;
    for (const DrawCommand& command : list) {
        const int i = command.instance;
        if (nowDynamic_[i]) {
            dynamics.push_back(command);
            continue;
        }
        // An instance not drawn has an empty box (and a static one was drawn as when its box was made).
        const int slot = paper && wasDynamic_[i] ? kSlotDirty : kSlotClear;
        if (!grid_.meets(slot, instanceBoxes_[i])) continue;
        const Record& record = records_[i];
        hit.assign(record.groups, 0);
        bool any = false;
        for (std::uint32_t g = 0; g < record.groups; ++g)
            if (grid_.meets(slot, extents_[record.firstGroup + g])) {
                hit[g] = 1;
                any = true;
            }
        if (!any) continue;
        // The drawn ranges, in their order, cut to the groups that were hit.
        const std::uint32_t size = groupSize(i);
        DrawCommand redraw{i, {}};
        for (const IndexRange& range : record.ranges) {
            const std::uint32_t end = range.firstTriangle + range.triangleCount;
            for (std::uint32_t t = range.firstTriangle; t < end;) {
                const std::uint32_t g = t / size, groupEnd = std::min(end, (g + 1) * size);
                if (hit[g]) {
                    if (!redraw.ranges.empty() &&
                        redraw.ranges.back().firstTriangle + redraw.ranges.back().triangleCount == t)
                        redraw.ranges.back().triangleCount += groupEnd - t;
                    else
                        redraw.ranges.push_back({t, groupEnd - t});
                    redrawn += groupEnd - t;
                }
                t = groupEnd;
            }
        }
        redraws.push_back(std::move(redraw));
    }
    std::int64_t copyPx = 0, clearPx = 0, backPx = 0;
    std::vector<Rect> clearRects = grid_.rects(kClear, 0, clearPx);
    // The paper copies the static pair over P_dd's cells not cleared, and copies back later; the
    // exact static pair is copied once, over every cell that changed.
    std::vector<Rect> copyRects = paper ? grid_.rects(kCopy, kClear, copyPx) : grid_.rects(kClear | kCopy, 0, copyPx);
    std::vector<Rect> backRects;
    if (paper) backRects = grid_.rects(kClear | kBack, 0, backPx);
    stats_.overlapMs = msSince(t0);
    stats_.copiedPx = std::uint64_t(copyPx + backPx);
    stats_.clearedPx = std::uint64_t(clearPx);
    stats_.staticRedrawnTris = redrawn;
    stats_.redrawnTris = redrawn + changes.triangles;
    stats_.rects = copyRects.size() + clearRects.size() + backRects.size();

    const double reuseCost = double(redrawn + changes.triangles) + cost.draw * double(redraws.size() + dynamics.size()) +
                             cost.pixelCleared * double(clearPx) + cost.pixelCopied * double(copyPx + backPx) +
                             cost.rect * double(stats_.rects) + (redraws.empty() ? 0.0 : cost.pass);
    if (options_.fallback && reuseCost >= fullCost) {
        const double overlapMs = stats_.overlapMs;
        FramePlan plan = fullPlan(list, "reuse would cost more than a full render");
        stats_.overlapMs = overlapMs;
        return plan;
    }
    stats_.mode = ReuseMode::Reuse;
    stats_.reason = "camera still";
    FramePlan plan;
    const auto step = [&plan](PlanStep::Op op, PlanTarget from, PlanTarget to, std::vector<Rect> rects, DrawList draws) {
        if (!rects.empty() || !draws.empty()) plan.push_back({op, from, to, std::move(rects), std::move(draws)});
    };
    using Op = PlanStep::Op;
    constexpr PlanTarget R = PlanTarget::Render, S = PlanTarget::Static;
    if (paper) {
        step(Op::Copy, S, R, std::move(copyRects), {});    // 1
        step(Op::Clear, R, R, std::move(clearRects), {});  // 2
        step(Op::Draw, R, R, {}, std::move(redraws));      // 3, 4
        step(Op::Copy, R, S, std::move(backRects), {});    // 5
    } else {
        step(Op::Clear, S, S, std::move(clearRects), {});  // a: the static pair becomes this frame's
        step(Op::Draw, S, S, {}, std::move(redraws));      // b
        step(Op::Copy, S, R, std::move(copyRects), {});    // c: the render target's static part too
    }
    step(Op::Draw, R, R, {}, std::move(dynamics));         // 6 (d)

    // The extents of what moved, as drawn now: the previous extents of the next frame.
    const auto t1 = Clock::now();
    for (std::size_t i = 0; i < n; ++i)
        if (nowDynamic_[i]) computeExtents(int(i), viewProjection, world);
    stats_.extentMs = msSince(t1);
    return plan;
}

ReuseOptions reuseOptionsFrom(const ReuseSettings& settings) {
    ReuseOptions options;
    options.grain = settings.grain;
    options.cell = settings.cell;
    options.fallback = settings.fallback;
    options.paperSteps = !settings.exactStatic;
    return options;
}

}  // namespace frugal
