#include "lab/RenderRecord.h"

#include <nlohmann/json.hpp>


namespace frugal {

nlohmann::json stateChangesJson(const StateChanges& c) {
    return {{"draws", c.draws},       {"programs", c.programs}, {"meshes", c.meshes},
            {"textures", c.textures}, {"toggles", c.toggles},   {"uniforms", c.uniforms}};
}

nlohmann::json reuseStatsJson(const ReuseStats& s) {
    return {{"mode", toString(s.mode)},
            {"reason", s.reason},
            {"p_dd", s.triangles.dd},
            {"p_ds", s.triangles.ds},
            {"p_sd", s.triangles.sd},
            {"p_ss", s.triangles.ss},
            {"instances",
             {{"p_dd", s.instances.dd},
              {"p_ds", s.instances.ds},
              {"p_sd", s.instances.sd},
              {"p_ss", s.instances.ss}}},
            {"copied_px", s.copiedPx},
            {"cleared_px", s.clearedPx},
            {"redrawn_tris", s.redrawnTris},
            {"static_redrawn_tris", s.staticRedrawnTris},
            {"rects", s.rects},
            {"plan_ms", s.planMs},
            {"overlap_ms", s.overlapMs},
            {"extent_ms", s.extentMs}};
}

nlohmann::json hsrJson(Hsr mode, const HsrStats& stats) {
    return {{"mode", toString(mode)},
            {"polygons", stats.polygons},
            {"zbuffered_polygons", stats.zbuffered(mode)},
            {"zbuffered_share", stats.zbufferedShare(mode)},
            {"draws", stats.draws},
            {"plan_ms", stats.ms}};
}

nlohmann::json stateCostsJson(const StateCosts& costs) {
    return {{"kinds", costs.kinds},
            {"start_us", costs.startUs},
            {"us", costs.us},
            {"rounds", costs.rounds},
            {"refine_every", costs.refineEvery}};
}

nlohmann::json frameStatsJson(const FrameStats& stats, const Settings& settings) {
    nlohmann::json j = {{"time", stats.time}, {"render_ms", stats.renderMs}, {"readback_ms", stats.readbackMs}};
    if (stats.cull) {
        j.update({{"tos", stats.cull->tos}, {"pvs", stats.cull->pvs}, {"cull_ms", stats.cull->ms}});
        if (!traitsOf(settings.cull).idPass) j["ranges"] = stats.cull->ranges;
        if (const std::optional<OcclusionFrameStats>& o = stats.cull->occlusion) {
            j["occlusion"] = {{"ran", o->ran}, {"ms", o->ms}, {"triangles_hidden", o->trianglesHidden}};
            if (traitsOf(settings.cull).ahead)
                j["occlusion"].update({{"ahead", o->ahead}, {"ahead_wait_ms", o->aheadWaitMs}});
        }
    }
    if (stats.reuse) j["reuse"] = reuseStatsJson(*stats.reuse);
    if (stats.hsr) j["hsr"] = hsrJson(settings.hsr, *stats.hsr);
    j["state_changes"] = stateChangesJson(stats.stateChanges);
    if (stats.interp)
        j["interp"] = {
            {"mode", toString(settings.interp)}, {"spans", stats.interp->spans}, {"overflow", stats.interp->overflow}};
    return j;
}

nlohmann::json refinementJson(const FrameStats& next) {
    if (!next.refinedCostsUs) return nullptr;
    return {{"refined_state_costs_us", *next.refinedCostsUs}, {"refine_ms", next.refineMs}};
}

nlohmann::json renderJsonMeta(const Renderer& renderer, const std::string& sceneName, const nlohmann::json& camera) {
    const Scene& scene = renderer.scene();
    const Settings& s = renderer.settings();
    const std::optional<StateCosts> costs = renderer.stateCosts();
    const ReuseSettings& reuse = s.reuseSettings;
    return {
        {"scene", sceneName},
        {"counts",
         {{"nodes", scene.nodes.size()},
          {"meshes", scene.meshes.size()},
          {"instances", scene.instances.size()},
          {"triangles", scene.triangleCount()},
          {"materials", scene.materials.size()},
          {"textures", scene.textures.size()},
          {"animations", scene.animations.size()}}},
        {"unsupported", scene.unsupported},
        {"size", {s.width, s.height}},
        {"backend", renderer.backendName()},
        {"renderer", renderer.backendRenderer()},
        {"backend_log", renderer.backendLog()},
        {"camera", camera},
        {"cull", toString(s.cull)},
        {"hsr", toString(s.hsr)},
        {"draw_order", toString(s.order)},
        {"state_costs", costs ? stateCostsJson(*costs) : nlohmann::json(nullptr)},
        {"reuse", s.reuse ? nlohmann::json{{"grain", reuse.grain},
                                           {"cell", reuse.cell},
                                           {"fallback", reuse.fallback},
                                           {"static_pair_bytes", renderer.staticPairBytes()}}
                          : nlohmann::json(nullptr)},
    };
}

nlohmann::json viewJson(const View& view, const Settings& s) {
    return {{"source", view.source},
            {"eye", nlohmann::json{view.eye.x, view.eye.y, view.eye.z}},
            {"forward", nlohmann::json{view.forward.x, view.forward.y, view.forward.z}},
            {"perspective", view.perspective},
            {"yfov_degrees", glm::degrees(view.yfov)},
            {"znear", view.znear},
            {"zfar", view.zfar},
            {"depth_range", depthRangeName(view.depthRange)},
            {"given_znear", view.givenNear},
            {"given_zfar", view.givenFar},
            {"depth_format", depthFormatName(view.depthFormat)},
            {"aspect_ratio", view.aspect},
            {"file_aspect_ratio", view.fileAspect > 0.0f ? nlohmann::json(view.fileAspect) : nlohmann::json(nullptr)},
            {"aspect_ratio_differs", aspectDiffers(view.fileAspect, s.width, s.height)}};
}



Result<bool> RenderJsonFile::add(nlohmann::json record, const FrameStats& stats) {
    if (!enabled()) return true;
    if (!spool_) {
        Result<Spool> made = Spool::create(path_);
        if (!made) return made.error();
        spool_.emplace(std::move(*made));
    }
    if (pending_) {
        if (const nlohmann::json refined = refinementJson(stats); !refined.is_null()) pending_->update(refined);
        if (Result<bool> put = flush(); !put) return put;
    }
    pending_ = std::make_unique<nlohmann::json>(std::move(record));
    return true;
}

Result<bool> RenderJsonFile::finish(nlohmann::json meta) {
    if (!enabled()) return true;
    if (Result<bool> put = flush(); !put) return put;
    meta["frames"] = nlohmann::json::array();
    const std::string text = meta.dump(2) + "\n";
    const std::string marker = "\"frames\": []";
    const std::size_t at = text.find(marker);
    const std::string head = text.substr(0, at) + "\"frames\": [\n";
    const std::string tail = "\n  ]" + text.substr(at + marker.size());
    return writeFileAtomic(path_, Content(Bytes(head.begin(), head.end()), *spool_, Bytes(tail.begin(), tail.end())));
}

// The pending record, indented as an element of "frames" (two levels: four spaces).
Result<bool> RenderJsonFile::flush() {
    if (!pending_) return true;
    std::string text = (first_ ? "" : ",\n") + std::string("    ");
    for (const char c : pending_->dump(2)) {
        text += c;
        if (c == '\n') text += "    ";
    }
    first_ = false;
    pending_.reset();
    return spool_->append(text);
}

}  // namespace frugal
