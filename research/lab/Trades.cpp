#include "lab/Trades.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include <frugal/Renderer.h>

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
            judged = Error{rows[i].candidate.name + ": " + c.error()};
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

// The fastest row among those `eligible` accepts that pays against the plain render.
std::optional<std::size_t> fastest(const std::vector<TradeRow>& rows, const std::function<bool(const TradeRow&)>& eligible) {
    std::optional<std::size_t> best;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const TradeRow& r = rows[i];
        if (r.candidate.floor || !eligible(r) || !(r.medianMs < kPays * rows[0].medianMs)) continue;
        if (!best || r.medianMs < rows[*best].medianMs) best = i;
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

// A timed frame's figures added to its row (the means are taken at the end).
void note(TradeRow& row, const FrameStats& stats, double triangles) {
    row.ms.push_back(stats.renderMs);
    row.submittedShare += stats.cull ? double(stats.cull->pvs) / triangles : 1.0;
    const StateChanges& c = stats.stateChanges;
    row.stateChanges += double(c.programs + c.meshes + c.textures + c.toggles);
}

}  // namespace

bool TradeReport::onFront(std::size_t row) const { return std::find(pareto.begin(), pareto.end(), row) != pareto.end(); }

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

std::vector<TradeCandidate> tradeCandidates(const Settings& base, bool sequence, bool software) {
    std::vector<TradeCandidate> out{with(base, "plain", "plain", [](Settings&) {})};
    for (const Cull cull : {Cull::Sphere, Cull::Backface, Cull::Cones, Cull::Paper, Cull::Conservative, Cull::Occlusion})
        out.push_back(with(base, std::string("cull ") + toString(cull), "cull", [cull](Settings& s) { s.cull = cull; }));
    out.push_back(with(base, "cull oracle", "floor", [](Settings& s) { s.cull = Cull::Oracle; }, true));
    for (const Order order : {Order::Key, Order::Greedy})
        out.push_back(with(base, std::string("order ") + toString(order), "order", [order](Settings& s) { s.order = order; }));
    for (const Hsr hsr : {Hsr::DepthSort, Hsr::Adaptive})
        out.push_back(with(base, std::string("hsr ") + toString(hsr), "hsr", [hsr](Settings& s) { s.hsr = hsr; }));
    if (software && base.depthFormat == DepthFormat::D24)
        for (const DepthInterp interp : {DepthInterp::Span, DepthInterp::Dda})
            out.push_back(with(base, std::string("interp ") + toString(interp), "interp",
                               [interp](Settings& s) { s.interp = interp; }));
    out.push_back(with(base, "cull conservative + order key", "combination", [](Settings& s) {
        s.cull = Cull::Conservative;
        s.order = Order::Key;
    }));
    out.push_back(with(base, "cull occlusion + order key", "combination", [](Settings& s) {
        s.cull = Cull::Occlusion;
        s.order = Order::Key;
    }));
    if (sequence) {
        // Occlusion's plan made while the frame before draws: only a sequence knows its next frame.
        out.push_back(with(base, "cull occlusion-ahead", "cull", [](Settings& s) { s.cull = Cull::OcclusionAhead; }));
        out.push_back(with(base, "reuse", "reuse", [](Settings& s) { s.reuse = true; }));
        out.push_back(with(base, "cull conservative + reuse", "combination", [](Settings& s) {
            s.cull = Cull::Conservative;
            s.reuse = true;
        }));
    }
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
        if (!made) return Error{c.name + ": " + made.error(), made.errorKind(), made.failure().aboutSetting};
        TradeRow row;
        row.candidate = c;
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
    MissCounter misses;
    // Candidate i's render of `shot` into its frame; an error names both.
    const auto renderShot = [&](std::size_t i, const TradeShot& shot) -> Result<bool> {
        if (Result<bool> done = renderers[i].render(shot.camera, shot.time, frames[i]); !done)
            return Error{candidates[i].name + ": " + shot.label + ": " + done.error(), done.errorKind()};
        return true;
    };
    // One untimed render of the first shot each: llvmpipe compiles a state's shaders on its first
    // draw, and a cost-driven order measures its costs; neither belongs to a frame's time. (A
    // sequence then starts again from its first frame, which reuse sees as a still camera.)
    if (!settings.shots.empty())
        for (std::size_t i = 0; i < candidates.size(); ++i)
            if (Result<bool> done = renderShot(i, settings.shots[0]); !done) return done.failure();
    const int repeat = settings.sequence ? 1 : std::max(settings.repeat, 1);
    for (std::size_t s = 0; s < settings.shots.size(); ++s) {
        const TradeShot& shot = settings.shots[s];
        for (int r = 0; r < repeat; ++r)
            for (std::size_t k = 0; k < candidates.size(); ++k) {
                const std::size_t i = (k + s + std::size_t(r)) % candidates.size();  // the order rotates
                if (settings.sequence && s + 1 < settings.shots.size())  // occlusion-ahead's next frame
                    renderers[i].setNextFrame(settings.shots[s + 1].camera, settings.shots[s + 1].time);
                if (Result<bool> done = renderShot(i, shot); !done) return done.failure();
                note(report.rows[i], frames[i].stats, triangles);
            }
        if (Result<bool> judged = judge(report.rows, frames, shot, candidates[0].settings.background, misses); !judged)
            return judged.failure();
        progress(shot.label + " (" + std::to_string(s + 1) + "/" + std::to_string(settings.shots.size()) + ")");
    }
    for (TradeRow& row : report.rows) {
        row.medianMs = median(row.ms);
        const double timed = double(std::max<std::size_t>(row.ms.size(), 1));
        row.submittedShare /= timed;
        row.stateChanges /= timed;
    }
    report.bestExact = fastest(report.rows, [](const TradeRow& r) { return r.exact(); });
    report.bestWithinBudget =
        fastest(report.rows, [&settings](const TradeRow& r) { return r.worstFramePx <= settings.budgetPx; });
    report.pareto = paretoFront(report.rows);
    return report;
}

std::string tradeReportJson(const TradeReport& report, const TradeSettings& settings) {
    using Json = nlohmann::json;
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
                        {"settings", settingsObject}});
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
                {"backend", report.backend},
                {"rows", rows},
                {"recommended", {{"exact", pick(report.bestExact)}, {"within_budget", pick(report.bestWithinBudget)}}}};
    return doc.dump(2) + "\n";
}

std::string tradeReportCsv(const TradeReport& report) {
    std::ostringstream out;
    out << "name,family,floor,median_ms,x_plain,x_floor,differing_px,worst_frame_px,worst_psnr,worst_depth,"
           "extra_bytes,prepare_ms,submitted_share,state_changes,exact,pareto,misses\n";
    for (std::size_t i = 0; i < report.rows.size(); ++i) {
        const TradeRow& r = report.rows[i];
        const std::optional<double> xFloor = report.xFloor(r);
        out << r.candidate.name << "," << r.candidate.family << "," << (r.candidate.floor ? 1 : 0) << ","
            << fmt(r.medianMs) << "," << fmt(report.xPlain(r)) << "," << (xFloor ? fmt(*xFloor) : "") << ","
            << r.differingPx << ","
            << r.worstFramePx << "," << (std::isinf(r.worstPsnr) ? "inf" : fmt(r.worstPsnr)) << "," << r.worstDepth
            << "," << r.extraBytes << "," << fmt(r.prepareMs) << "," << fmt(r.submittedShare) << ","
            << fmt(r.stateChanges) << "," << (r.exact() ? 1 : 0) << "," << (report.onFront(i) ? 1 : 0) << "," << r.misses
            << "\n";
    }
    return out.str();
}

std::string tradeRecommendationText(const TradeReport& report, const TradeSettings& settings) {
    const TradeRow& plain = report.rows.front();
    const auto line = [&plain](const char* what, const std::optional<std::size_t>& pick, const TradeReport& r) {
        if (!pick) return std::string(what) + ": plain render (" + fmt(plain.medianMs) + " ms; nothing pays on this scene)\n";
        const TradeRow& row = r.rows[*pick];
        return std::string(what) + ": " + row.candidate.name + " (" + fmt(row.medianMs) + " ms, " +
               fmt(row.medianMs / plain.medianMs) + "x the plain render's " + fmt(plain.medianMs) + " ms, " +
               std::to_string(row.differingPx) + " px differ)\n";
    };
    return line("fastest exact", report.bestExact, report) +
           line(("fastest within " + std::to_string(settings.budgetPx) + " px a frame").c_str(),
                report.bestWithinBudget, report);
}

}  // namespace frugal
