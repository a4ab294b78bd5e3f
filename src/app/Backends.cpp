#include "app/Backends.h"

#include <cstdlib>

#include "software/SoftwareBackend.h"

namespace frugal {

Result<BackendSelection> parseBackendSelection(const std::string& text) {
    if (text == "software") return BackendSelection{true, BackendChoice::Auto};
    Result<BackendChoice> gl = parseBackendChoice(text);
    if (!gl) return Error{"unknown backend '" + text + "' (expected " + kBackendNames + ")"};
    return BackendSelection{false, *gl};
}

std::string backendSelectionName(const BackendSelection& selection) {
    if (selection.software) return "software";
    switch (selection.gl) {
        case BackendChoice::Auto: return "auto";
        case BackendChoice::Egl: return "egl";
        case BackendChoice::EglDevice: return "egl-device";
        case BackendChoice::EglSurfaceless: return "egl-surfaceless";
        case BackendChoice::OsMesa: return "osmesa";
    }
    return "auto";
}

Result<std::unique_ptr<Backend>> openBackend(const BackendSelection& selection, std::vector<std::string>* log,
                                             int threads) {
    if (!selection.software) {
        if (threads > 0) setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
        return createGlBackend(selection.gl, log);
    }
    SoftwareOptions options;
    options.threads = threads;
    std::unique_ptr<Backend> backend = makeSoftwareBackend(options);
    if (!backend) return Error{"software: could not be created"};
    if (log) log->push_back("software: ok");
    return backend;
}

}  // namespace frugal
