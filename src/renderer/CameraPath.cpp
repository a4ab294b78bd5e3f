#include <frugal/Camera.h>

#include <cmath>
#include <fstream>
#include <optional>

#include <nlohmann/json.hpp>

#include "base/Format.h"

namespace frugal {
namespace {

std::string point(const glm::vec3& p) { return "(" + fmt(p.x) + ", " + fmt(p.y) + ", " + fmt(p.z) + ")"; }

}  // namespace

Result<std::vector<Camera>> readCameraPath(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{"camera-path " + path + ": cannot read the file", ErrorKind::Io, true};
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        return Error{"camera-path " + path + ": not JSON (" + std::string(e.what()) + ")", ErrorKind::BadInput, true};
    }
    if (doc.is_object() && doc.contains("views")) doc = doc["views"];
    if (!doc.is_array() || doc.empty())
        return Error{"camera-path " + path + ": expected a non-empty list of {\"eye\",\"target\",\"up\",\"fov\"}",
                     ErrorKind::BadInput, true};
    std::vector<Camera> views;
    for (std::size_t i = 0; i < doc.size(); ++i) {
        const nlohmann::json& entry = doc[i];
        const std::string where = "camera-path " + path + ": entry " + std::to_string(i) + ": ";
        const auto bad = [](std::string message) { return Error{std::move(message), ErrorKind::BadInput, true}; };
        auto vec = [&](const char* key, bool required) -> Result<std::optional<glm::vec3>> {
            if (!entry.is_object() || !entry.contains(key)) {
                if (required) return bad(where + key + ": missing");
                return std::optional<glm::vec3>{};
            }
            const nlohmann::json& v = entry[key];
            if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
                return bad(where + key + ": expected 3 numbers");
            const glm::vec3 value(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
            if (!std::isfinite(value.x) || !std::isfinite(value.y) || !std::isfinite(value.z))
                return bad(where + key + ": not a finite point");
            return std::optional<glm::vec3>{value};
        };
        Camera view;
        Result<std::optional<glm::vec3>> eye = vec("eye", true), target = vec("target", true), up = vec("up", false);
        if (!eye) return eye.error();
        if (!target) return target.error();
        if (!up) return up.error();
        view.eye = **eye;
        view.target = **target;
        if (*up) view.up = **up;
        // What makes no view whatever the scene, refused here with the entry rather than at its frame.
        const glm::vec3 forward = **target - **eye;
        const float distance = glm::length(forward);
        if (!(distance > 0.0f)) return bad(where + "eye and target coincide at " + point(**eye));
        if (!std::isfinite(distance))
            return bad(where + "eye " + point(**eye) + " and target " + point(**target) + " are too far apart for float");
        if (!(glm::length(glm::cross(forward / distance, view.up)) >= 1e-6f))
            return bad(where + "up " + point(view.up) + " is parallel to the view direction");
        if (entry.contains("fov")) {
            if (!entry["fov"].is_number() || !(entry["fov"].get<double>() > 0.0 && entry["fov"].get<double>() < 180.0))
                return bad(where + "fov: expected degrees in (0, 180)");
            view.yfovDegrees = entry["fov"].get<float>();
        }
        views.push_back(view);
    }
    return views;
}

}  // namespace frugal
