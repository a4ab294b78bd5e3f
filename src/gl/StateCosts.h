// Render-state change costs C(s) of paper 004, measured on the backend that runs, not assumed
// (issue 10). Written against the Backend interface alone, so the software backend is measured
// the same way as a GL one (its "changes" cost what its draw set-up does with them: little).
//
// How (measureStateCosts): a 64×64 target and a one-triangle mesh covering a few pixels, so that
// a draw is almost all per-draw work. A round draws `draws` times in one frame and waits for the
// backend (finish); the baseline round repeats one draw exactly, each kind's round alternates
// between two values of that state only:
//   program   a mesh with vertex colours and one without (another shader variant; both rounds
//             switch meshes, the mesh round between two identical meshes, and the program's cost
//             is the difference: program = (colours ↔ plain) − mesh)
//   mesh      two identical meshes (vertex array and buffers)
//   texture   two resident 4×4 textures
//   material  two base colour factors (a uniform)
//   culling   single- and double-sided (face culling on and off)
//   depth     DepthMode Test and Off (the depth test on and off)
// C(kind) = (round time − baseline round time) ÷ draws, the median over `rounds` rounds, kinds
// interleaved within each round so that drift hits all alike; the spread is the range of the
// per-round figures. Where the data lives matters (the paper's texture from disk): also timed once
// each, a 256×256 texture's upload, its first draw (where a GL driver may copy or convert it), and
// a draw in a state combination the backend has not drawn before (llvmpipe compiles a shader
// variant per new combination) against the same draw repeated.
//
// Refined while frames render (StateCostProbe, RunningStateCosts): the probe keeps its target,
// meshes and textures, so one more round between two frames costs 8 × `draws` draws (their time on
// llvmpipe: docs/orders/README.md). The running average over the last rounds follows a backend whose
// costs drift (a warming cache, a loaded machine); it is the interquartile mean, because a round the
// scheduler preempted reads many times too high for one kind (docs/orders/README.md), and a plain
// mean would let that one round reorder frames.
#pragma once

#include <array>
#include <cstddef>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include <frugal/Result.h>

#include "pipeline/Backend.h"

namespace frugal {

struct StateCost {
    std::string kind;        // "program", "mesh", "texture", "material", "culling", "depth"
    double us = 0.0;         // per change, median over rounds (may be ≤ 0 within noise)
    double minUs = 0.0, maxUs = 0.0;  // the range over rounds
};

struct StateCostReport {
    std::string backend, renderer;
    int rounds = 0, draws = 0;
    double drawUs = 0.0;  // one draw with no state change (the baseline), median
    std::vector<StateCost> costs;  // in the order of the list above
    double textureUploadMs = 0.0;      // uploadTexture of a 256×256 RGBA texture
    double textureFirstDrawMs = 0.0;   // the first draw that samples it, to finish
    double textureResidentDrawMs = 0.0;  // the same draw again
    double newCombinationMs = 0.0;     // a draw in a state combination not drawn before, to finish
    double seenCombinationMs = 0.0;    // the same draw again
};

inline constexpr std::size_t kStateKinds = 6;
// The kinds in StateCostReport::costs order.
inline constexpr std::array<const char*, kStateKinds> kStateKindNames = {"program", "mesh",    "texture",
                                                                         "material", "culling", "depth"};

// One round's figures: the baseline draw and each kind's cost per change, microseconds.
struct StateCostSample {
    double drawUs = 0.0;
    std::array<double, kStateKinds> us{};
};

// The micro-benchmark's resources on one backend, kept between rounds. Draws into a 64×64 target of
// its own, so it may run between two frames of a sequence (never inside one: a round ends the
// backend's current frame). Releases everything it made when destroyed.
class StateCostProbe {
public:
    // Error: the backend refused the target, a mesh or a texture ("state costs: <what> refused").
    static Result<std::unique_ptr<StateCostProbe>> create(Backend& backend);
    ~StateCostProbe();
    StateCostProbe(const StateCostProbe&) = delete;
    StateCostProbe& operator=(const StateCostProbe&) = delete;

    // One round of every kind, `draws` ≥ 1 draws each; `phase` rotates which kind goes first, so
    // that drift within a round hits every kind alike over successive rounds.
    StateCostSample round(int draws, int phase = 0);

    // Where the data lives, once (fills the report's *Ms fields): a new 256×256 texture's upload,
    // its first and second draw, and a draw in a combination no round drew, first and second time.
    // Error: the backend refused the texture.
    Result<bool> measureFirstUse(StateCostReport& report);

private:
    struct Impl;
    explicit StateCostProbe(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// The costs a frame order uses: per kind, the interquartile mean of the last `window` rounds (the
// middle half, sorted: the lowest and highest quarter dropped).
class RunningStateCosts {
public:
    explicit RunningStateCosts(std::size_t window = 32) : window_(window ? window : 1) {}
    void add(const StateCostSample& sample);
    std::size_t rounds() const { return total_; }  // every round added, including those dropped
    // Microseconds per kind; a mean at or below 0 (noise around a free change) counts as 0.01 us, so
    // that every kind still has an order to prefer. Empty before the first round.
    std::vector<double> costsUs() const;

private:
    std::size_t window_, total_ = 0;
    std::deque<StateCostSample> last_;
};

// Measures `backend` (which must have no frame in progress that matters: it draws into a target of
// its own, destroyed after). `rounds` ≥ 1, `draws` ≥ 1. Error: as StateCostProbe::create, or the
// backend refused the 256×256 texture.
Result<StateCostReport> measureStateCosts(Backend& backend, int rounds = 9, int draws = 400);

}  // namespace frugal
