#include "lab/Trades.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include <frugal/Renderer.h>

#include "lab/ImageCompare.h"
#include "renderer/Research.h"

namespace frugal {

namespace {

TradeCandidate with(const Settings& base, std::string name, std::string family,
                    const std::function<void(Settings&)>& change, bool floor = false) {
    TradeCandidate c{std::move(name), std::move(family), base, floor};
    change(c.settings);
    return c;
}

// A frame's planes as Buffers (moved in; give them back with giveBack).
Buffers lend(Frame& frame) {
    Buffers b;
    b.width = frame.color.width;
    b.height = frame.color.height;
    b.rgba = std::move(frame.color.rgba);
    b.depth = std::move(frame.depth.values);
    b.ids = std::move(frame.ids.ids);
    b.depthFormat = frame.depth.format;
    return b;
}
void giveBack(Buffers& b, Frame& frame) {
    frame.color.rgba = std::move(b.rgba);
    frame.depth.values = std::move(b.depth);
    frame.ids.ids = std::move(b.ids);
}

// Triangles the plain render shows that another image lacks, from the id planes (0 background,
// else the triangle's id). A triangle a method drew stays visible wherever the plain render shows
// it, since leaving triangles out only removes occluders: for culling these are the visible
// triangles it did not submit (the misses, RVS minus PVS); for a hidden-surface mode, the triangles
// its order wrongly hid.
class MissCounter {
public:
    void reference(const std::vector<std::uint32_t>& ids) {
        plain_.clear();
        ++now_;
        for (const std::uint32_t id : ids)
            if (id != 0 && mark(id)) plain_.push_back(id);
    }
    std::uint64_t missing(const std::vector<std::uint32_t>& ids) {
        ++now_;
        for (const std::uint32_t id : ids)
            if (id != 0) mark(id);
        std::uint64_t missed = 0;
        for (const std::uint32_t id : plain_) missed += stamp_[id] != now_;
        return missed;
    }

private:
    // Stamps `id` with the current pass; true when it was not stamped in it yet.
    bool mark(std::uint32_t id) {
        if (id >= stamp_.size()) stamp_.resize(std::size_t(id) + 1, 0);
        if (stamp_[id] == now_) return false;
        stamp_[id] = now_;
        return true;
    }
    std::vector<std::uint32_t> stamp_;  // per id: the pass that last saw it
    std::uint32_t now_ = 0;
    std::vector<std::uint32_t> plain_;  // the ids the reference shows, each once
};

// The candidates' last frames of `shot`, judged against the plain render's (row 0).
Result<bool> judge(std::vector<TradeRow>& rows, std::vector<Frame>& frames, const TradeShot& shot,
                   const glm::vec4& background, MissCounter& misses) {
    Buffers reference = lend(frames[0]);
    misses.reference(reference.ids);
    CompareOptions options;
    options.background = colorBytes(background);
    Result<bool> judged = true;
    for (std::size_t i = 1; i < rows.size() && judged; ++i) {
        Buffers actual = lend(frames[i]);
        Result<ImageComparison> c = compareBuffers(actual, reference, options);
        rows[i].misses += misses.missing(actual.ids);
        giveBack(actual, frames[i]);
        if (!c) {
            judged = Error{rows[i].candidate.name + ": " + c.error().message};
            break;
        }
        TradeRow& row = rows[i];
        row.differingPx += c->failingPixels;
        if (c->failingPixels > row.worstFramePx) {
            row.worstFramePx = c->failingPixels;
            row.worstMask = std::move(c->mask);
            row.worstShot = shot.label;
        }
        row.worstPsnr = std::min(row.worstPsnr, c->psnr);
        if (c->depth) row.worstDepth = std::max(row.worstDepth, c->depth->maxDifference);
    }
    giveBack(reference, frames[0]);
    return judged;
}

// `value` with `places` decimals ("0.891"), as the printed intervals give them.
std::string decimals(double value, int places) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", places, value);
    return buf;
}

// SplitMix64 (Steele, Lea and Flood, OOPSLA 2014): a generator defined by these few lines, so a
// seed gives the same draws on every platform and standard library (std's distributions do not).
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, n) up to a bias of n / 2^64, nothing at the counts of shots and rounds drawn here.
    std::size_t below(std::size_t n) { return std::size_t(next() % n); }

private:
    std::uint64_t state_;
};

// The median of `values`, reordering them (no copy: the bootstrap takes millions).
double middle(std::vector<double>& values) {
    const std::size_t n = values.size(), half = n / 2;
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(half), values.end());
    if (n % 2 == 1) return values[half];
    const double upper = values[half];
    return (*std::max_element(values.begin(), values.begin() + std::ptrdiff_t(half)) + upper) / 2.0;
}

// The mean of `values` without the lowest and the highest kTrim of them (rounded down; none of 4 or
// fewer), reordering them: robust to a few shots that load hit, yet unlike the median it moves
// smoothly with every shot it keeps, so a gain that differs from view to view (culling) does not
// leave the estimate jumping between two clusters of shots (R. Wilcox, Introduction to Robust
// Estimation and Hypothesis Testing: the percentile bootstrap suits a 20 % trimmed mean).
double trimmedMean(std::vector<double>& values) {
    std::sort(values.begin(), values.end());
    const auto cut = std::size_t(kTrim * double(values.size()));
    double sum = 0.0;
    for (std::size_t i = cut; i < values.size() - cut; ++i) sum += values[i];
    return sum / double(values.size() - 2 * cut);
}

// Whether `a` only adds to `b`: every method setting `b` changes from `plain`, `a` changes the same
// way (so `a` does `b`'s planning and more). Every candidate adds to the plain render; the floor
// neither adds nor is added to. A cull and its ahead form are two culls, not one added to another.
bool addsTo(const TradeCandidate& a, const TradeCandidate& b, const Settings& plain) {
    if (&a == &b || a.floor || b.floor) return false;
    const Settings &x = a.settings, &y = b.settings;
    return (y.cull == plain.cull || x.cull == y.cull) && (y.order == plain.order || x.order == y.order) &&
           (y.hsr == plain.hsr || x.hsr == y.hsr) && (y.interp == plain.interp || x.interp == y.interp) &&
           (y.reuse == plain.reuse || x.reuse == y.reuse);
}

// The rows each pick chooses from: the exact ones, and those within the budget of differing pixels.
bool exactRow(const TradeRow& r) { return r.exact(); }
std::function<bool(const TradeRow&)> withinBudget(const TradeSettings& settings) {
    return [budget = settings.budgetPx](const TradeRow& r) { return r.worstFramePx <= budget; };
}

// The candidate that culls as candidate `i` does and adds nothing after the cull (no order, no
// hidden-surface mode, no reuse, the exact interpolator): the plain render when `i` does not cull.
// None when there is no such candidate, or it is `i` itself.
std::optional<std::size_t> cullAlone(const std::vector<TradeCandidate>& candidates, std::size_t i) {
    const Settings& plain = candidates[0].settings;
    const Settings& s = candidates[i].settings;
    for (std::size_t j = 0; j < candidates.size(); ++j) {
        const Settings& c = candidates[j].settings;
        if (j != i && !candidates[j].floor && c.cull == s.cull && c.order == plain.order && c.hsr == plain.hsr &&
            c.reuse == plain.reuse && c.interp == plain.interp)
            return j;
    }
    return std::nullopt;
}

// Among the rows that pay and that `eligible` accepts, the one with the lowest estimate of its paired
// ratio; on a tie the one surer of it (the lower upper end), then the earlier row.
std::optional<std::size_t> fastest(const TradeReport& report, const std::function<bool(const TradeRow&)>& eligible) {
    std::optional<std::size_t> best;
    for (std::size_t i = 1; i < report.rows.size(); ++i) {
        if (!report.pays(i) || !eligible(report.rows[i])) continue;
        const PairedRatio& p = report.rows[i].paired;
        const PairedRatio* b = best ? &report.rows[*best].paired : nullptr;
        if (!b || p.estimate < b->estimate || (p.estimate == b->estimate && p.high < b->high)) best = i;
    }
    return best;
}

// Rows no other row beats in both median time and differing pixels (the floor left out).
std::vector<std::size_t> paretoFront(const std::vector<TradeRow>& rows) {
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].candidate.floor) continue;
        bool beaten = false;
        for (std::size_t j = 0; j < rows.size() && !beaten; ++j)
            beaten = j != i && !rows[j].candidate.floor && rows[j].medianMs <= rows[i].medianMs &&
                     rows[j].differingPx <= rows[i].differingPx &&
                     (rows[j].medianMs < rows[i].medianMs || rows[j].differingPx < rows[i].differingPx);
        if (!beaten) front.push_back(i);
    }
    return front;
}

// A timed frame of shot `shot` added to its row (the means are taken at the end).
void note(TradeRow& row, std::size_t shot, const FrameStats& stats, double triangles) {
    row.shotMs[shot].push_back(stats.renderMs);
    row.submittedShare += stats.cull ? double(stats.cull->pvs) / triangles : 1.0;
    const StateChanges& c = stats.stateChanges;
    row.stateChanges += double(c.programs + c.meshes + c.textures + c.toggles);
}

}  // namespace

bool TradeReport::onFront(std::size_t row) const { return std::find(pareto.begin(), pareto.end(), row) != pareto.end(); }

bool TradeReport::pays(std::size_t row) const {
    if (row == 0 || row >= rows.size()) return false;
    const TradeRow& r = rows[row];
    return !r.candidate.floor && !r.sameDrawsAs && r.paired.known() && r.paired.high < kPays;
}

PairedRatio pairedRatio(const std::vector<std::vector<double>>& ms, const std::vector<std::vector<double>>& plainMs,
                        std::uint64_t seed) {
    PairedRatio out;
    out.estimate = out.low = out.high = std::numeric_limits<double>::quiet_NaN();
    std::vector<std::vector<double>> shots;  // per shot, its pairs' log ratios
    for (std::size_t s = 0; s < std::min(ms.size(), plainMs.size()); ++s) {
        std::vector<double> logs;
        for (std::size_t r = 0; r < std::min(ms[s].size(), plainMs[s].size()); ++r)
            if (ms[s][r] > 0 && plainMs[s][r] > 0 && std::isfinite(ms[s][r]) && std::isfinite(plainMs[s][r]))
                logs.push_back(std::log(ms[s][r] / plainMs[s][r]));
        out.pairs += logs.size();
        if (!logs.empty()) shots.push_back(std::move(logs));
    }
    if (shots.empty()) return out;
    std::vector<double> perShot, scratch;
    for (std::vector<double> logs : shots) perShot.push_back(middle(logs));  // a copy: middle reorders
    out.estimate = std::exp(trimmedMean(perShot));
    if (!out.known()) return out;

    // Shots drawn with replacement, and each drawn shot's rounds: the rounds' spread is counted
    // again on top of the shots' (which already holds it), which widens the interval a little. A
    // wider interval only withholds a pick; resampling the shots alone would give a single shot
    // (one camera, --repeat K) no interval at all.
    SplitMix64 rng(seed);
    std::vector<double> estimates(kBootstrapResamples);
    for (double& estimate : estimates) {
        for (double& value : perShot) {
            const std::vector<double>& shot = shots[rng.below(shots.size())];
            if (shot.size() == 1) {
                value = shot[0];
                continue;
            }
            scratch.resize(shot.size());
            for (double& round : scratch) round = shot[rng.below(shot.size())];
            value = middle(scratch);
        }
        estimate = trimmedMean(perShot);
    }
    std::sort(estimates.begin(), estimates.end());
    const auto cut = std::size_t(std::llround(double(estimates.size()) * (1.0 - kIntervalLevel) / 2.0));
    out.low = std::exp(estimates[cut]);
    out.high = std::exp(estimates[estimates.size() - 1 - cut]);
    return out;
}

std::vector<std::optional<std::size_t>> repeatedDraws(const std::vector<TradeCandidate>& candidates,
                                                      const std::vector<std::vector<DrawRecord>>& rounds) {
    // repeats[i][j]: candidate i adds to candidate j and drew what j drew in every round.
    // idleAfterCull[i]: what candidate i does after its cull (an order, a hidden-surface plan,
    // reuse) changed nothing in any round. The second holds where the first cannot be seen:
    // occlusion culling skips its pass where its timing says it does not pay, so two renderers
    // that both cull by occlusion need not draw alike, though neither's order did anything.
    const std::size_t n = candidates.size();
    std::vector<std::vector<char>> repeats(n, std::vector<char>(n, 0));
    std::vector<char> idleAfterCull(n, 0);
    for (std::size_t i = 1; i < n; ++i) {
        idleAfterCull[i] = !rounds.empty() && !candidates[i].floor;
        for (std::size_t j = 0; j < n; ++j)
            repeats[i][j] = !rounds.empty() && addsTo(candidates[i], candidates[j], candidates[0].settings);
    }
    for (const std::vector<DrawRecord>& drew : rounds) {
        const auto at = [&drew](std::size_t k) { return k < drew.size() ? drew[k] : DrawRecord{}; };
        for (std::size_t i = 1; i < n; ++i) {
            const std::uint64_t mine = at(i).drawn;
            idleAfterCull[i] = idleAfterCull[i] && mine != 0 && mine == at(i).culled;
            for (std::size_t j = 0; j < n; ++j) repeats[i][j] = repeats[i][j] && mine != 0 && mine == at(j).drawn;
        }
    }
    std::vector<std::optional<std::size_t>> out(n);
    for (std::size_t i = 1; i < n; ++i) {
        const std::optional<std::size_t> alone = idleAfterCull[i] ? cullAlone(candidates, i) : std::nullopt;
        for (std::size_t j = 0; j < n && !out[i]; ++j)  // the plain render first
            if (repeats[i][j] || alone == j) out[i] = j;
    }
    return out;
}

void decideTrades(TradeReport& report, const TradeSettings& settings) {
    if (report.rows.empty()) return;
    for (TradeRow& row : report.rows) {
        row.ms.clear();
        for (const std::vector<double>& shot : row.shotMs) row.ms.insert(row.ms.end(), shot.begin(), shot.end());
        row.medianMs = row.ms.empty() ? 0.0 : median(row.ms);
    }
    const std::vector<std::vector<double>>& plain = report.rows.front().shotMs;
    for (TradeRow& row : report.rows) row.paired = pairedRatio(row.shotMs, plain);
    report.bestExact = fastest(report, exactRow);
    report.bestWithinBudget = fastest(report, withinBudget(settings));
    report.pareto = paretoFront(report.rows);
}

std::optional<double> TradeReport::floorMs() const {
    for (const TradeRow& r : rows)
        if (r.candidate.floor) return r.medianMs;
    return std::nullopt;
}

double TradeReport::xPlain(const TradeRow& row) const {
    const double plain = rows.front().medianMs;
    return plain > 0 ? row.medianMs / plain : 0.0;
}

std::optional<double> TradeReport::xFloor(const TradeRow& row) const {
    const std::optional<double> floor = floorMs();
    return floor && *floor > 0 ? std::optional<double>(row.medianMs / *floor) : std::nullopt;
}

std::vector<TradeCandidate> tradeCandidates(const Settings& base, bool sequence, bool software, bool mipmapped,
                                            bool deforms) {
    std::vector<TradeCandidate> out{with(base, "plain", "plain", [](Settings&) {})};
    // Every culling method by its traits: the plain render has none; an id pass is the floor, not a
    // method; a plan made ahead needs a sequence (below).
    const auto cullCandidate = [&base](Cull cull, const char* family, bool floor = false) {
        return with(base, std::string("cull ") + toString(cull), family, [cull](Settings& s) { s.cull = cull; }, floor);
    };
    for (const Cull cull : kCulls)
        if (traitsOf(cull).prepares && !traitsOf(cull).idPass && !traitsOf(cull).ahead) out.push_back(cullCandidate(cull, "cull"));
    for (const Cull cull : kCulls)
        if (traitsOf(cull).idPass) out.push_back(cullCandidate(cull, "floor", true));
    for (const Order order : {Order::Key, Order::Greedy})
        out.push_back(with(base, std::string("order ") + toString(order), "order", [order](Settings& s) { s.order = order; }));
    for (const Hsr hsr : {Hsr::DepthSort, Hsr::Adaptive})
        if (!deforms)
            out.push_back(with(base, std::string("hsr ") + toString(hsr), "hsr", [hsr](Settings& s) { s.hsr = hsr; }));
    if (software && base.depthFormat == DepthFormat::D24)
        for (const DepthInterp interp : {DepthInterp::Span, DepthInterp::Dda})
            out.push_back(with(base, std::string("interp ") + toString(interp), "interp",
                               [interp](Settings& s) { s.interp = interp; }));
    // The shading trades, against the base's full shading: the Lambert approximation, the
    // environment's diffuse lobe alone, one sample a pixel where the base has more, base levels only
    // where the scene has mipmaps.
    if (base.shading == ShadingModel::Full)
        out.push_back(with(base, "shading lambert", "shading", [](Settings& s) { s.shading = ShadingModel::Lambert; }));
    if (base.shading == ShadingModel::Full && base.environmentSpecular && base.environment > 0.0f)
        out.push_back(
            with(base, "no environment specular", "shading", [](Settings& s) { s.environmentSpecular = false; }));
    if (base.samples > 1) out.push_back(with(base, "samples 1", "shading", [](Settings& s) { s.samples = 1; }));
    if (base.mipmaps && mipmapped)
        out.push_back(with(base, "no mipmaps", "shading", [](Settings& s) { s.mipmaps = false; }));
    out.push_back(with(base, "cull conservative + order key", "combination", [](Settings& s) {
        s.cull = Cull::Conservative;
        s.order = Order::Key;
    }));
    out.push_back(with(base, "cull occlusion + order key", "combination", [](Settings& s) {
        s.cull = Cull::Occlusion;
        s.order = Order::Key;
    }));
    if (sequence) {
        // A plan made while the frame before draws: only a sequence knows its next frame.
        for (const Cull cull : kCulls)
            if (traitsOf(cull).ahead) out.push_back(cullCandidate(cull, "cull"));
        out.push_back(with(base, "reuse", "reuse", [](Settings& s) { s.reuse = true; }));
        out.push_back(with(base, "cull conservative + reuse", "combination", [](Settings& s) {
            s.cull = Cull::Conservative;
            s.reuse = true;
        }));
    }
    // Those the base's settings rule out (occlusion culling and the oracle with several samples).
    std::erase_if(out, [](const TradeCandidate& c) { return settingsProblem(c.settings).has_value(); });
    return out;
}

Result<TradeReport> measureTrades(const Scene& scene, const std::vector<TradeCandidate>& candidates,
                                  const TradeSettings& settings,
                                  const std::function<void(const std::string&)>& progress) {
    TradeReport report;
    std::vector<Renderer> renderers;
    for (const TradeCandidate& c : candidates) {
        // Every candidate writes the id plane, to count misses (in every target anyway: it adds
        // only its read-back, which no frame's time includes).
        Settings measured = c.settings;
        measured.ids = true;
        Result<Renderer> made = Renderer::create(scene, measured);
        if (!made) return Error{c.name + ": " + made.error().message, made.error().kind, made.error().aboutSetting};
        TradeRow row;
        row.candidate = c;
        row.shotMs.resize(settings.shots.size());
        row.worstPsnr = std::numeric_limits<double>::infinity();
        row.extraBytes = made->extraBytes();
        if (const std::optional<Renderer::CullPreparation> prep = made->cullPreparation()) row.prepareMs = prep->totalMs;
        report.rows.push_back(std::move(row));
        renderers.push_back(std::move(*made));
    }
    report.backend = renderers[0].backendName() + " (" + renderers[0].backendRenderer() + ")";
    progress("report: " + std::to_string(candidates.size()) + " candidates on " + report.backend + ", " +
             std::to_string(settings.shots.size()) + (settings.sequence ? " frames" : " views"));

    const double triangles = double(std::max<std::size_t>(scene.triangleCount(), 1));
    std::vector<Frame> frames(candidates.size());
    std::vector<std::vector<DrawRecord>> rounds;  // what every candidate drew, round after round
    MissCounter misses;
    // Candidate i's render of `shot` into its frame; an error names both.
    const auto renderShot = [&](std::size_t i, const TradeShot& shot) -> Result<bool> {
        if (Result<bool> done = renderers[i].render(shot.camera, shot.time, frames[i]); !done)
            return Error{candidates[i].name + ": " + shot.label + ": " + done.error().message, done.error().kind};
        return true;
    };
    // One untimed render of the first shot each: llvmpipe compiles a state's shaders on its first
    // draw, and a cost-driven order measures its costs; neither belongs to a frame's time. (A
    // sequence then starts again from its first frame, which reuse sees as a still camera.)
    if (!settings.shots.empty())
        for (std::size_t i = 0; i < candidates.size(); ++i)
            if (Result<bool> done = renderShot(i, settings.shots[0]); !done) return done.error();
    const int repeat = settings.sequence ? 1 : std::max(settings.repeat, 1);
    for (std::size_t s = 0; s < settings.shots.size(); ++s) {
        const TradeShot& shot = settings.shots[s];
        for (int r = 0; r < repeat; ++r) {
            for (std::size_t k = 0; k < candidates.size(); ++k) {
                const std::size_t i = (k + s + std::size_t(r)) % candidates.size();  // the order rotates
                if (settings.sequence && s + 1 < settings.shots.size())  // occlusion-ahead's next frame
                    renderers[i].setNextFrame(settings.shots[s + 1].camera, settings.shots[s + 1].time);
                if (Result<bool> done = renderShot(i, shot); !done) return done.error();
                note(report.rows[i], s, frames[i].stats, triangles);
            }
            std::vector<DrawRecord>& drew = rounds.emplace_back();
            for (const Frame& frame : frames) drew.push_back({frame.stats.drawFingerprint, frame.stats.culledFingerprint});
        }
        if (Result<bool> judged = judge(report.rows, frames, shot, candidates[0].settings.background, misses); !judged)
            return judged.error();
        progress(shot.label + " (" + std::to_string(s + 1) + "/" + std::to_string(settings.shots.size()) + ")");
    }
    const std::vector<std::optional<std::size_t>> repeated = repeatedDraws(candidates, rounds);
    for (std::size_t i = 0; i < report.rows.size(); ++i) report.rows[i].sameDrawsAs = repeated[i];
    for (TradeRow& row : report.rows) {
        std::size_t timed = 0;
        for (const std::vector<double>& shot : row.shotMs) timed += shot.size();
        row.submittedShare /= double(std::max<std::size_t>(timed, 1));
        row.stateChanges /= double(std::max<std::size_t>(timed, 1));
    }
    decideTrades(report, settings);
    return report;
}

std::string tradeReportJson(const TradeReport& report, const TradeSettings& settings) {
    using Json = nlohmann::json;
    const auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(); };
    Json rows = Json::array();
    for (std::size_t i = 0; i < report.rows.size(); ++i) {
        const TradeRow& r = report.rows[i];
        Json settingsObject = Json::parse(settingsJson(r.candidate.settings));
        rows.push_back({{"name", r.candidate.name},
                        {"family", r.candidate.family},
                        {"floor", r.candidate.floor},
                        {"median_ms", r.medianMs},
                        {"x_plain", report.xPlain(r)},
                        {"x_floor", report.xFloor(r) ? Json(*report.xFloor(r)) : Json()},
                        {"x_plain_paired", number(r.paired.estimate)},
                        {"x_plain_low", number(r.paired.low)},
                        {"x_plain_high", number(r.paired.high)},
                        {"pairs", r.paired.pairs},
                        {"no_op", r.noOp()},
                        {"same_draws_as", r.sameDrawsAs ? Json(report.rows[*r.sameDrawsAs].candidate.name) : Json()},
                        {"pays", report.pays(i)},
                        {"differing_px", r.differingPx},
                        {"worst_frame_px", r.worstFramePx},
                        {"misses", r.misses},
                        {"worst_psnr", std::isinf(r.worstPsnr) ? Json() : Json(r.worstPsnr)},
                        {"worst_depth", r.worstDepth},
                        {"extra_bytes", r.extraBytes},
                        {"prepare_ms", r.prepareMs},
                        {"submitted_share", r.submittedShare},
                        {"state_changes", r.stateChanges},
                        {"worst_shot", r.worstShot.empty() ? Json() : Json(r.worstShot)},
                        {"exact", r.exact()},
                        {"pareto", report.onFront(i)},
                        {"settings", settingsObject},
                        {"shot_ms", r.shotMs}});
    }
    const auto pick = [&report](const std::optional<std::size_t>& i) {
        return i ? report.rows[*i].candidate.name : std::string("plain");
    };
    Json doc = {{"scene", settings.scene},
                {"shots", settings.shots.size()},
                {"sequence", settings.sequence},
                {"repeat", settings.sequence ? 1 : settings.repeat},
                {"budget_px", settings.budgetPx},
                {"pays_below", kPays},
                {"interval",
                 {{"statistic", "20 % trimmed geometric mean over the shots of each shot's median ratio (time / the "
                                "plain render's, same round)"},
                  {"trim", kTrim},
                  {"method", "percentile bootstrap: shots, and each drawn shot's rounds, drawn with replacement"},
                  {"level", kIntervalLevel},
                  {"resamples", kBootstrapResamples},
                  {"seed", kBootstrapSeed},
                  {"generator", "splitmix64"},
                  {"min_pairs", kMinPairs}}},
                {"backend", report.backend},
                {"rows", rows},
                {"recommended", {{"exact", pick(report.bestExact)}, {"within_budget", pick(report.bestWithinBudget)}}}};
    return doc.dump(2) + "\n";
}

std::string tradeReportCsv(const TradeReport& report) {
    const auto finite = [](double v) { return std::isfinite(v) ? fmt(v) : std::string(); };
    std::ostringstream out;
    out << "name,family,floor,median_ms,x_plain,x_floor,differing_px,worst_frame_px,worst_psnr,worst_depth,"
           "extra_bytes,prepare_ms,submitted_share,state_changes,exact,pareto,misses,x_plain_paired,x_plain_low,"
           "x_plain_high,pairs,no_op,pays,same_draws_as\n";
    for (std::size_t i = 0; i < report.rows.size(); ++i) {
        const TradeRow& r = report.rows[i];
        const std::optional<double> xFloor = report.xFloor(r);
        out << r.candidate.name << "," << r.candidate.family << "," << (r.candidate.floor ? 1 : 0) << ","
            << fmt(r.medianMs) << "," << fmt(report.xPlain(r)) << "," << (xFloor ? fmt(*xFloor) : "") << ","
            << r.differingPx << ","
            << r.worstFramePx << "," << (std::isinf(r.worstPsnr) ? "inf" : fmt(r.worstPsnr)) << "," << r.worstDepth
            << "," << r.extraBytes << "," << fmt(r.prepareMs) << "," << fmt(r.submittedShare) << ","
            << fmt(r.stateChanges) << "," << (r.exact() ? 1 : 0) << "," << (report.onFront(i) ? 1 : 0) << "," << r.misses
            << "," << finite(r.paired.estimate) << "," << finite(r.paired.low) << "," << finite(r.paired.high) << ","
            << r.paired.pairs << "," << (r.noOp() ? 1 : 0) << "," << (report.pays(i) ? 1 : 0) << ","
            << (r.sameDrawsAs ? report.rows[*r.sameDrawsAs].candidate.name : "") << "\n";
    }
    return out.str();
}

std::string tradeRecommendationText(const TradeReport& report, const TradeSettings& settings) {
    const TradeRow& plain = report.rows.front();
    const auto interval = [](const PairedRatio& p) {
        return "paired " + decimals(p.estimate, 3) + "x, " + std::to_string(int(std::lround(100 * kIntervalLevel))) +
               " % interval [" + decimals(p.low, 3) + ", " + decimals(p.high, 3) + "] over " + std::to_string(p.pairs) +
               " pairs";
    };
    const auto line = [&](const std::string& what, const std::optional<std::size_t>& pick,
                          const std::function<bool(const TradeRow&)>& eligible) {
        if (pick) {
            const TradeRow& row = report.rows[*pick];
            return what + ": " + row.candidate.name + " (" + fmt(row.medianMs) + " ms, " +
                   fmt(row.medianMs / plain.medianMs) + "x the plain render's " + fmt(plain.medianMs) + " ms; " +
                   interval(row.paired) + "; " + std::to_string(row.differingPx) + " px differ)\n";
        }
        // Nothing pays: the candidate that came nearest (the lowest upper end), so the reader sees
        // by how much it missed.
        std::optional<std::size_t> nearest;
        for (std::size_t i = 1; i < report.rows.size(); ++i) {
            const TradeRow& r = report.rows[i];
            if (r.candidate.floor || r.sameDrawsAs || !r.paired.known() || !eligible(r)) continue;
            if (!nearest || r.paired.high < report.rows[*nearest].paired.high) nearest = i;
        }
        std::string why = "no interval lies below " + fmt(kPays) + "x";
        if (nearest)
            why += "; the nearest, " + report.rows[*nearest].candidate.name + ": " + interval(report.rows[*nearest].paired);
        else if (plain.paired.pairs < kMinPairs)
            why = "too few pairs for an interval (" + std::to_string(plain.paired.pairs) + " < " +
                  std::to_string(kMinPairs) + "): raise --repeat";
        return what + ": plain render (" + fmt(plain.medianMs) + " ms; nothing pays on this scene: " + why + ")\n";
    };
    return line("fastest exact", report.bestExact, exactRow) +
           line("fastest within " + std::to_string(settings.budgetPx) + " px a frame", report.bestWithinBudget,
                withinBudget(settings));
}

}  // namespace frugal
