// The render JSON (`frugal render --json`): frame statistics (frugal/Stats.h) as its records, the
// same objects for the reports that print some of them (order-bench, reuse-bench), and the file
// itself, written as frames finish.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <memory>
#include <optional>
#include <string>

#include <frugal/Renderer.h>
#include <frugal/Settings.h>
#include <frugal/Stats.h>

#include "renderer/Research.h"

namespace frugal {

// {"draws", "programs", "meshes", "textures", "toggles", "uniforms"}.
nlohmann::json stateChangesJson(const StateChanges& changes);

// {"mode", "reason", "p_dd", "p_ds", "p_sd", "p_ss" (triangles), "instances": {...}, "copied_px",
//  "cleared_px", "redrawn_tris", "static_redrawn_tris", "rects", "plan_ms", "overlap_ms", "extent_ms"}.
nlohmann::json reuseStatsJson(const ReuseStats& stats);

// {"mode", "polygons", "zbuffered_polygons", "zbuffered_share", "draws", "plan_ms"}.
nlohmann::json hsrJson(Hsr mode, const HsrStats& stats);

// {"kinds", "start_us", "us", "rounds", "refine_every"}.
nlohmann::json stateCostsJson(const StateCosts& costs);

// One frame's record of the render JSON's "frames", without "frame" and "file" (the command's):
// {"time", "render_ms", "readback_ms", ["tos", "pvs", "cull_ms", "ranges"], ["reuse"], ["hsr"],
//  "state_changes", ["interp"]}; the cost refinement run after this frame is refinementJson's.
nlohmann::json frameStatsJson(const FrameStats& stats, const Settings& settings);
// {"refined_state_costs_us", "refine_ms"} of `next`, the frame after the refinement.
nlohmann::json refinementJson(const FrameStats& next);

// The render JSON's "camera": the view a frame was drawn with, {"source", "eye", "forward",
// "perspective", "yfov_degrees", "znear", "zfar", "depth_range", "given_znear", "given_zfar",
// "depth_format", "aspect_ratio", "file_aspect_ratio", "aspect_ratio_differs"}.
nlohmann::json viewJson(const View& view, const Settings& settings);

// The render JSON's fields besides "frames": {"scene" (`sceneName`), "counts", "unsupported",
// "size", "backend", "renderer", "backend_log", "camera", "cull", "hsr", "draw_order",
// "state_costs", "reuse"}.
nlohmann::json renderJsonMeta(const Renderer& renderer, const std::string& sceneName, const nlohmann::json& camera);

// The render JSON, written as frames finish: their records go to a spool (an anonymous file, so
// that a long sequence holds none of them in memory), and finish() puts the document together,
// byte for byte what one nlohmann dump(2) of it would be. A record waits for the next frame, which
// says whether a cost round ran between the two (it belongs to the earlier record).
class RenderJsonFile {
public:
    explicit RenderJsonFile(std::string path) : path_(std::move(path)) {}
    bool enabled() const { return !path_.empty(); }
    // Adds a frame's record (frameStatsJson, with the command's "frame" and "file"). Error (Io): the spool's.
    Result<bool> add(nlohmann::json record, const FrameStats& stats);
    // The whole document, "frames" filled from the spool. Error (Io): the path's.
    Result<bool> finish(nlohmann::json meta);

private:
    Result<bool> flush();

    std::string path_;
    std::optional<Spool> spool_;
    std::unique_ptr<nlohmann::json> pending_;
    bool first_ = true;
};

}  // namespace frugal
