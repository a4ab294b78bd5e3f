#include "lab/Frames.h"

namespace frugal {

FrameSetupOf frameSetups(const Scene& scene, std::string name, AskedFrameOf asked, int width, int height, bool ids,
                         DepthFormat format) {
    return [&scene, name = std::move(name), asked = std::move(asked), width, height, ids,
            format](int frame) -> Result<FrameSetup> {
        const AskedFrame a = asked(frame);
        Result<FrameSetup> setup = setUpFrame(scene, a.camera, a.time, width, height, ids, format);
        if (!setup) return Error{name + ": " + setup.error().message};
        return setup;
    };
}

}  // namespace frugal
