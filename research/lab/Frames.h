// The frames a harness measures, from what a command line asks for: each frame's camera and scene
// time, set up as a Renderer sets them up (transforms, View, draw parameters). The commands hand
// the harnesses FrameSetupOf made here, so that they name cameras and times only.
#pragma once

#include <functional>

#include <frugal/Camera.h>
#include <frugal/Scene.h>

#include "renderer/Research.h"

namespace frugal {

// What a command asks of frame `frame`: the camera it is seen through, and its scene time.
struct AskedFrame {
    Camera camera;
    double time = 0.0;
};
using AskedFrameOf = std::function<AskedFrame(int frame)>;

// Frame i set up on a width × height target of `format`, ids drawn or not. Errors as setUpFrame's
// with `name` (the scene as the command line named it) first: "<name>: camera 3: the scene has 1
// camera".
FrameSetupOf frameSetups(const Scene& scene, std::string name, AskedFrameOf asked, int width, int height, bool ids,
                         DepthFormat format);

}  // namespace frugal
