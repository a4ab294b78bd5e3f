// The shading model of pipeline/Backend.h (`Lighting`) computed in double, written from its
// description and not from either backend's code, for tests that check a backend's colour against
// the number the model gives.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "pipeline/Backend.h"
#include "pipeline/Brdf.h"

namespace frugal::test {

struct ShadedMaterial {
    glm::dvec3 base{1.0};
    double metallic = 1.0, roughness = 1.0;
    glm::dvec3 emissive{0.0};
    double occlusion = 1.0;  // what the occlusion map leaves of the environment's light
    // A clear coat (KHR_materials_clearcoat) of this factor (0: none) and roughness, whose normal
    // is coatNormal (unit), or n where that is 0.
    double coat = 0.0, coatRoughness = 0.0;
    glm::dvec3 coatNormal{0.0};
};

// Linear rgb of `material` at a point with unit normal n, seen along unit v (towards the eye).
inline glm::dvec3 referenceShade(const ShadedMaterial& material, glm::dvec3 n, glm::dvec3 v, const Lighting& lighting) {
    constexpr double kPi = 3.14159265358979323846;
    const auto saturate = [](double x) { return std::clamp(x, 0.0, 1.0); };
    const auto c5 = [](double x) { return std::pow(1.0 - x, 5.0); };
    const glm::dvec3 base = material.base;
    const double r = material.roughness, m = material.metallic;
    const double alpha2 = std::pow(r, 4.0);
    const double nv = saturate(glm::dot(n, v));
    const brdf::Dfg<double> ab = brdf::dfg(nv, r);
    const auto iblFresnel = [&](double f0) {
        const double fss = (f0 + (std::max(1.0 - r, f0) - f0) * c5(nv)) * ab.a + ab.b;
        const double ems = 1.0 - (ab.a + ab.b);
        const double favg = f0 + (1.0 - f0) / 21.0;
        return fss + fss * ems * favg / (1.0 - favg * ems);
    };
    const double env = lighting.environment, fd = iblFresnel(0.04);
    glm::dvec3 dielectric = env * base * (1.0 - fd) + env * fd;
    glm::dvec3 metal;
    for (int c = 0; c < 3; ++c) metal[c] = env * iblFresnel(base[c]);
    // The coat: k of the light reflected by it, the rest passed to what is below.
    const glm::dvec3 nc = material.coatNormal == glm::dvec3(0.0) ? n : material.coatNormal;
    const double k = material.coat * (0.04 + 0.96 * c5(saturate(glm::dot(nc, v))));
    const glm::dvec3 environment = ((dielectric * (1.0 - m) + metal * m) * (1.0 - k) + env * k) * material.occlusion;
    dielectric = metal = glm::dvec3(0.0);

    const glm::dvec3 l = glm::dvec3(lighting.toLight);
    const glm::dvec3 h = glm::normalize(l + v);
    const double nl = saturate(glm::dot(n, l)), nh = saturate(glm::dot(n, h)), vh = saturate(glm::dot(v, h));
    // The GGX lobe's visibility × distribution at alpha² a2.
    const auto lobe = [&](double dl, double dv, double dh, double a2) {
        const double ggx = dl * std::sqrt(dv * dv * (1.0 - a2) + a2) + dv * std::sqrt(dl * dl * (1.0 - a2) + a2);
        const double visibility = ggx > 0.0 ? 0.5 / ggx : 0.0;
        const double f = dh * dh * (a2 - 1.0) + 1.0;
        return visibility * (f > 0.0 ? a2 / (kPi * f * f) : 0.0);
    };
    const double e = double(lighting.light) * nl;
    const double specular = e * lobe(nl, nv, nh, alpha2);
    const double fl = 0.04 + 0.96 * c5(vh);
    dielectric += e * base / kPi * (1.0 - fl) + specular * fl;
    metal += (base + (1.0 - base) * c5(vh)) * specular;
    const double ncl = saturate(glm::dot(nc, l));
    const double coatSpecular =
        double(lighting.light) * ncl *
        lobe(ncl, saturate(glm::dot(nc, v)), saturate(glm::dot(nc, h)), std::pow(material.coatRoughness, 4.0));
    return environment + (dielectric * (1.0 - m) + metal * m) * (1.0 - k) + coatSpecular * k +
           material.emissive * (1.0 - k);
}

// rgb^(1/2.2) in [0, 1], as the backends encode it for an 8-bit image.
inline glm::dvec3 displayedRgb(glm::dvec3 linear) {
    for (int c = 0; c < 3; ++c) linear[c] = std::pow(std::clamp(linear[c], 0.0, 1.0), 1.0 / 2.2);
    return linear;
}

}  // namespace frugal::test
