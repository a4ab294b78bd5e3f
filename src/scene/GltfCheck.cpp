#include "scene/GltfCheck.h"

namespace frugal::gltf {

std::string plural(std::size_t n, const char* singular, const char* pluralForm) {
    return cat(n, " ", n == 1 ? singular : pluralForm);
}

const Json& member(const Json& object, const char* key) {
    static const Json kNull;
    const auto it = object.find(key);
    return it == object.end() ? kNull : *it;
}

std::string describe(const Json& v) {
    switch (v.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return v.get<bool>() ? "true" : "false";
        case Json::value_t::string:
            return cat("string \"", oneLine(v.get_ref<const std::string&>(), 40), "\"");
        case Json::value_t::object:
            return "an object";
        case Json::value_t::array:
            return "an array";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float:
            return v.dump();
        default:
            return "an unexpected value";
    }
}

std::string child(const std::string& where, std::string_view key) {
    return where.empty() ? std::string(key) : cat(where, ".", key);
}
std::string element(const std::string& where, std::size_t i) { return cat(where, "[", i, "]"); }

}  // namespace frugal::gltf
