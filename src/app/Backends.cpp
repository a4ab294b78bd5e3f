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

Result<span::Interp> parseInterp(const std::string& text) {
    for (span::Interp mode : {span::Interp::Exact, span::Interp::Span, span::Interp::Dda})
        if (text == span::interpName(mode)) return mode;
    return Error{"--interp " + text + ": not a mode (" + kInterpNames + ")"};
}

std::optional<std::string> interpConflict(const BackendSelection& selection, span::Interp interp) {
    if (selection.software || interp == span::Interp::Exact) return std::nullopt;
    return std::string("--interp ") + span::interpName(interp) +
           ": only the software backend models the span interpolator (use --backend software)";
}

Result<std::unique_ptr<Backend>> openBackend(const BackendSelection& selection, std::vector<std::string>* log,
                                             int threads, span::Interp interp) {
    if (std::optional<std::string> conflict = interpConflict(selection, interp)) return Error{*conflict};
    if (!selection.software) {
        if (threads > 0) setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
        return createGlBackend(selection.gl, log);
    }
    SoftwareOptions options;
    options.threads = threads;
    options.interp = interp;
    std::unique_ptr<Backend> backend = makeSoftwareBackend(options);
    if (!backend) return Error{"software: could not be created"};
    if (log) log->push_back("software: ok");
    return backend;
}

}  // namespace frugal
