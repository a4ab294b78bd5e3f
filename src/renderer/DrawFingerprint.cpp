#include "renderer/DrawFingerprint.h"

namespace frugal {

namespace {

// FNV-1a over 64-bit words, each word mixed first (splitmix64's finaliser) so that small counts
// and indices spread over every bit.
class Hasher {
public:
    explicit Hasher(std::uint64_t seed) { add(seed); }
    void add(std::uint64_t v) {
        v += 0x9e3779b97f4a7c15ull;
        v = (v ^ (v >> 30)) * 0xbf58476d1ce4e5b9ull;
        v = (v ^ (v >> 27)) * 0x94d049bb133111ebull;
        v ^= v >> 31;
        h_ = (h_ ^ v) * 0x100000001b3ull;
    }
    std::uint64_t value() const { return h_ == 0 ? 1 : h_; }

private:
    std::uint64_t h_ = 0xcbf29ce484222325ull;
};

enum : std::uint64_t { kClear = 1, kCopy = 2, kDraw = 3, kRun = 4 };

void addRect(Hasher& h, const Rect& r) {
    h.add(std::uint64_t(std::uint32_t(r.x)) << 32 | std::uint32_t(r.y));
    h.add(std::uint64_t(std::uint32_t(r.width)) << 32 | std::uint32_t(r.height));
}

// A draw step's commands as joined runs of triangles.
void addDraws(Hasher& h, const DrawList& list) {
    bool open = false;
    int instance = -1;
    DepthMode depth = DepthMode::Test;
    std::uint64_t first = 0, end = 0;
    const auto flush = [&] {
        if (!open) return;
        h.add(kRun);
        h.add(std::uint64_t(std::uint32_t(instance)) << 8 | std::uint64_t(depth));
        h.add(first << 32 | (end - first));
        open = false;
    };
    for (const DrawCommand& command : list)
        for (const IndexRange& range : command.ranges) {
            if (range.triangleCount == 0) continue;
            const std::uint64_t begin = range.firstTriangle;
            if (open && command.instance == instance && command.depth == depth && begin == end) {
                end += range.triangleCount;
                continue;
            }
            flush();
            open = true;
            instance = command.instance;
            depth = command.depth;
            first = begin;
            end = begin + range.triangleCount;
        }
    flush();
}

}  // namespace

std::uint64_t drawFingerprint(const FramePlan& plan, std::uint64_t seed) {
    Hasher h(seed);
    for (const PlanStep& step : plan) {
        switch (step.op) {
        case PlanStep::Op::Clear:
            h.add(kClear << 8 | std::uint64_t(step.to));
            for (const Rect& r : step.rects) addRect(h, r);
            break;
        case PlanStep::Op::Copy:
            h.add(kCopy << 16 | std::uint64_t(step.from) << 8 | std::uint64_t(step.to));
            for (const Rect& r : step.rects) addRect(h, r);
            break;
        case PlanStep::Op::Draw:
            h.add(kDraw << 8 | std::uint64_t(step.to));
            addDraws(h, step.list ? *step.list : step.draws);
            break;
        }
    }
    return h.value();
}

std::uint64_t drawFingerprint(const DrawList& list, int width, int height, std::uint64_t seed) {
    Hasher h(seed);
    h.add(kClear << 8 | std::uint64_t(PlanTarget::Render));
    addRect(h, Rect{0, 0, width, height});
    h.add(kDraw << 8 | std::uint64_t(PlanTarget::Render));
    addDraws(h, list);
    return h.value();
}

}  // namespace frugal
