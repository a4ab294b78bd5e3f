#include "lab/Stages.h"

#include <utility>

namespace frugal {

Result<std::optional<Stage>> openStageIfAvailable(const Settings& settings, std::string& unavailable) {
    Result<Stage> opened = Stage::open(settings);
    if (opened) return std::optional<Stage>(std::move(*opened));
    // Stage::open names the backend first only when openBackend failed (renderer/Stage.h).
    const std::string prefix = std::string("backend ") + toString(settings.backend) + ": ";
    if (opened.errorKind() != ErrorKind::BackendUnavailable || opened.error().rfind(prefix, 0) != 0)
        return opened.failure();
    unavailable = opened.error().substr(prefix.size());
    return std::optional<Stage>();
}

}  // namespace frugal
