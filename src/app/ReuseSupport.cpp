#include "app/ReuseSupport.h"

#include "app/CameraPath.h"
#include "renderer/Backends.h"

namespace frugal {

const char* reuseOptionsHelp() {
    return R"(temporal reuse (with a still camera only what changed is redrawn; src/reuse/Reuse.h):
  --reuse-grain N       triangles per extent: N consecutive triangles of a mesh share one screen
                        rectangle (default 16; 1 = per triangle as in the paper; 0 = per instance)
  --reuse-cell PX       side of the screen-grid cells that copies and clears are made of
                        (default 16)
  --no-fallback         never fall back to a full render while the camera is still (for measuring)
  --exact-static        keep the static pair exactly the static instances' render (clear and
                        redraw around instances that come to rest) instead of paper 000's steps,
                        with which a depth tie lost while moving can outlive its frame
  --camera-path FILE    a JSON list of {"eye":[x,y,z],"target":[x,y,z],"up":[x,y,z],"fov":deg}:
                        entry i is frame A+i of --frames A:B, the last entry holds (equal entries
                        = still)
)";
}

bool parseReuseOption(const std::string& flag, ArgCursor& cursor, ReuseCliOptions& options, RenderOptions& render,
                      bool withSwitch) {
    if (withSwitch && flag == "--reuse") {
        options.enabled = true;
    } else if (flag == "--no-fallback") {
        options.settings.fallback = false;
    } else if (flag == "--exact-static") {
        options.settings.exactStatic = true;
    } else if (flag == "--reuse-grain") {
        if (auto n = wholeNumber(flag, cursor, 0, 1 << 30)) options.settings.grain = *n;
    } else if (flag == "--reuse-cell") {
        if (auto n = wholeNumber(flag, cursor, 1, 4096)) options.settings.cell = *n;
    } else if (flag == "--camera-path") {
        const std::optional<std::string> path = cursor.value(flag);
        if (!path) return true;
        Result<std::vector<Camera>> cameras = readCameraPath(*path);
        if (!cameras) cursor.fail(cameras.error());
        else render.cameraPath = std::move(*cameras);
    } else {
        return false;
    }
    return true;
}

std::uint64_t staticPairBytes(int width, int height) {
    return std::uint64_t(width) * std::uint64_t(height) * kTargetBytesPerPixel;
}

}  // namespace frugal
