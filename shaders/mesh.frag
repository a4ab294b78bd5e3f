// Mesh fragment stage: the shading model of pipeline/Backend.h (`Lighting`): glTF's
// metallic-roughness BRDF as the Khronos glTF Sample Renderer computes it, under one directional
// light and a uniform environment, written the same way in the software backend, in linear values.
// Every mix() is written out as a·(1 − t) + b·t, the form the software backend repeats. The split-sum
// table's fit dfg() comes before this text, generated from pipeline/Brdf.h (GlPrograms.cpp).
// The colour written is encoded for display as the Khronos glTF Sample Renderer encodes it,
// rgb^(1/2.2) (its linearTosRGB), so that an 8-bit image looks as viewers show the file.
//
// Variants (see mesh.vert): without FRUGAL_COLORS the vertex colour is exactly white and without
// FRUGAL_TEXTURE the texel is, so their factors are left out; each other map (FRUGAL_*_MAP) is read
// only by the materials that have it; without FRUGAL_IDS there is no id output; FRUGAL_UNLIT
// (KHR_materials_unlit) writes the base colour, FRUGAL_UNLIT with FRUGAL_BARE (segments or points
// without normals, as the Khronos renderer draws them) the emission plus the base colour; FRUGAL_ALPHA_MASK discards a fragment whose alpha is
// below the cutoff (GLSL's discard writes no colour, depth or id); alpha is written as it is only by
// FRUGAL_ALPHA_BLEND (the draw blends), else 1, as glTF's OPAQUE and MASK ask. Sampling a 1×1
// white texture instead cost +0.64 ms per bunny frame on llvmpipe. The maps are read as the
// Khronos renderer reads them: metallic × blue and roughness × green of the metallic-roughness map;
// the occlusion map's red darkens the environment's light only, by 1 + strength · (red − 1);
// emission × the emissive map's rgb; the normal map's rgb · 2 − 1, x and y × scale, normalised, in
// the basis (tangent, bitangent, normal), each normalised and flipped with the normal on back
// faces. FRUGAL_SPECULAR_GLOSSINESS
// (KHR_materials_pbrSpecularGlossiness, as the Khronos renderer's getSpecularGlossinessInfo reads
// it): no metal terms; the dielectric's f0 is the specular colour (× the map's rgb with
// FRUGAL_SPECULAR_GLOSSINESS_MAP), per channel, and r = 1 − glossiness (× the map's alpha).
// FRUGAL_CLEARCOAT (KHR_materials_clearcoat, as the Khronos renderer's getClearCoatInfo and main()
// draw it): k = factor (× the map's red) × Schlick(0.04, 1, nc·v), nc the coat's normal (its map in
// the tangent basis, not normalised after it, or the normal before the base normal map); the
// environment's colour becomes env·(1 − k) + L·k before occlusion, the light's light·(1 − k) +
// the coat's GGX specular (roughness factor × the map's green; no Fresnel)·k, the emission
// emission·(1 − k). FRUGAL_TONEMAP_NEUTRAL and FRUGAL_TONEMAP_ACES map the linear colour before its
// encoding, as the Khronos renderer's tonemapping.glsl does (FrameParams::tonemap).
// FRUGAL_NO_ENVIRONMENT_SPECULAR (Lighting::environmentSpecular false): the environment lights the
// diffuse lobe alone, dielectric = base · L, no metal term, no coat term L·k.
// FRUGAL_ENVIRONMENT_MAP (Lighting::map): the environment's diffuse L is E(n)/π from the map's
// spherical harmonics, its specular L the prefiltered map at the reflected view direction (the
// coat's at its normal and roughness), for the Lambert model the diffuse alone.
// FRUGAL_DIELECTRIC and FRUGAL_METAL (a metallic factor of exactly 0 or 1 and no metallic-roughness
// map): the dielectric or the metal side alone, the other's terms left out (metalMix).
// FRUGAL_LINEAR_OUTPUT (a float target, ColorFormat::Rgba32F): the linear colour is written as it is,
// unencoded and unclamped, a blended draw's alpha clamped to [0, 1] as an 8-bit target would.
#version 330 core

in vec3 v_normal;
in vec3 v_position;

uniform vec4 u_baseColorFactor;
uniform vec2 u_metallicRoughness;  // each in [0, 1]
uniform vec3 u_eye;                // world space
uniform vec3 u_toLight;            // world space, unit
uniform float u_light;             // the directional light's intensity
uniform float u_environment;       // the uniform environment's radiance
uniform vec3 u_emissive;           // the material's emission
#ifdef FRUGAL_LIGHTS
// The scene's punctual lights (pipeline/Backend.h, FrameLight), four vec4 each: position and type
// (0 directional, 1 point, 2 spot); where it shines and its range (0 = none); intensity and the
// outer cone's cosine; the inner cone's cosine. Then their count.
uniform vec4 u_lights[4 * FRUGAL_LIGHTS + 1];
#endif
#ifdef FRUGAL_ALPHA_MASK
uniform float u_alphaCutoff;
#endif
#ifdef FRUGAL_ENVIRONMENT_MAP
// The environment map (pipeline/Environment.h): E(n)/π's coefficients and the prefiltered levels,
// read at level roughness · FRUGAL_ENVIRONMENT_MAP (the last level's number).
uniform vec3 u_environmentSh[9];
uniform sampler2D u_environmentMap;  // unit 9
#endif
#ifdef FRUGAL_SPECULAR_GLOSSINESS
uniform vec4 u_specularGlossiness;  // rgb the specular colour, a the glossiness
#endif
#ifdef FRUGAL_SPECULAR_GLOSSINESS_MAP
uniform sampler2D u_specularGlossinessMap;  // unit 5
#endif
#ifdef FRUGAL_CLEARCOAT
uniform vec3 u_clearcoat;  // the factor, the roughness factor, the normal map's scale
#endif
#ifdef FRUGAL_CLEARCOAT_MAP
uniform sampler2D u_clearcoatMap;  // unit 6
#endif
#ifdef FRUGAL_CLEARCOAT_ROUGHNESS_MAP
uniform sampler2D u_clearcoatRoughnessMap;  // unit 7
#endif
#ifdef FRUGAL_CLEARCOAT_NORMAL_MAP
uniform sampler2D u_clearcoatNormalMap;  // unit 8
#endif

layout(location = 0) out vec4 o_color;

#ifdef FRUGAL_COLORS
in vec4 v_color;
#endif
#ifdef FRUGAL_UV
in vec2 v_uv;
#endif
#ifdef FRUGAL_TEXTURE
uniform sampler2D u_baseColor;  // texture unit 0
#endif
#ifdef FRUGAL_METALLIC_ROUGHNESS_MAP
uniform sampler2D u_metallicRoughnessMap;  // unit 1
#endif
#ifdef FRUGAL_OCCLUSION_MAP
uniform sampler2D u_occlusionMap;  // unit 2
uniform float u_occlusionStrength;
#endif
#ifdef FRUGAL_EMISSIVE_MAP
uniform sampler2D u_emissiveMap;  // unit 3
#endif
#ifdef FRUGAL_TANGENTS
in vec3 v_tangent;
in vec3 v_bitangent;
#endif
#ifdef FRUGAL_NORMAL_MAP
uniform sampler2D u_normalMap;  // unit 4
uniform float u_normalScale;
#endif
#ifdef FRUGAL_IDS
flat in uint v_id;
layout(location = 1) out uint o_id;
#endif

const float kPi = 3.14159265;
const float kDielectricF0 = 0.04;

float clampedDot(vec3 a, vec3 b) { return clamp(dot(a, b), 0.0, 1.0); }
float pow5(float x) { float x2 = x * x; return (x2 * x2) * x; }

// The GGX specular lobe's V·D (the Khronos renderer's BRDF_specularGGX): height-correlated Smith
// visibility times the distribution, at alpha² = r⁴.
float ggx(float nl, float nv, float nh, float alpha2) {
    float sum = nl * sqrt((nv * nv) * (1.0 - alpha2) + alpha2) + nv * sqrt((nl * nl) * (1.0 - alpha2) + alpha2);
    float visibility = sum > 0.0 ? 0.5 / sum : 0.0;
    float f = (nh * nh) * (alpha2 - 1.0) + 1.0;
    return visibility * (alpha2 / max(kPi * (f * f), 1.0e-30));
}

#ifdef FRUGAL_LIGHTS
// Light i's direction l toward it and its intensity e at this pixel (pipeline/Backend.h, FrameLight).
void lightAt(int i, out vec3 l, out vec3 e) {
    vec4 at = u_lights[4 * i], axis = u_lights[4 * i + 1], power = u_lights[4 * i + 2];
    e = power.rgb;
    l = -axis.xyz;
    if (at.w > 0.5) {
        vec3 pointToLight = at.xyz - v_position;
        l = normalize(pointToLight);
        float d2 = dot(pointToLight, pointToLight);
        float fade = 1.0 / d2;
        if (axis.w > 0.0) {
            float q = d2 / (axis.w * axis.w);
            fade = max(min(1.0 - q * q, 1.0), 0.0) / d2;
        }
        e = e * fade;
        if (at.w > 1.5) {
            float c = -dot(axis.xyz, l), innerCos = u_lights[4 * i + 3].x;
            float t = (c - power.w) / (innerCos - power.w);
            e = e * (c > power.w ? (c < innerCos ? t * t : 1.0) : 0.0);
        }
    }
}
#endif

// The Khronos renderer's getIBLGGXFresnel (specular weight 1): single and multiple scattering.
float iblFresnel(float f0, float r, float c5, vec2 ab) {
    float fss = (f0 + (max(1.0 - r, f0) - f0) * c5) * ab.x + ab.y;
    float ems = 1.0 - (ab.x + ab.y);
    float favg = f0 + (1.0 - f0) / 21.0;
    return fss + (ems * fss) * favg / (1.0 - favg * ems);
}
vec3 iblFresnel(vec3 f0, float r, float c5, vec2 ab) {
    vec3 fss = (f0 + (max(vec3(1.0 - r), f0) - f0) * c5) * ab.x + ab.y;
    float ems = 1.0 - (ab.x + ab.y);
    vec3 favg = f0 + (1.0 - f0) / 21.0;
    return fss + (ems * fss) * favg / (1.0 - favg * ems);
}

#ifdef FRUGAL_ENVIRONMENT_MAP
// The diffuse light E(n)/π from the map's coefficients, at least 0.
vec3 environmentDiffuse(vec3 n) {
    vec3 e = u_environmentSh[0] + u_environmentSh[1] * n.y + u_environmentSh[2] * n.z + u_environmentSh[3] * n.x +
             u_environmentSh[4] * (n.x * n.y) + u_environmentSh[5] * (n.y * n.z) +
             u_environmentSh[6] * (3.0 * (n.z * n.z) - 1.0) + u_environmentSh[7] * (n.x * n.z) +
             u_environmentSh[8] * (n.x * n.x - n.y * n.y);
    return max(e, vec3(0.0));
}
// The map's (u, v) of unit direction d: pipeline/Environment.cpp's equirectUv, the same polynomials.
vec2 equirectUv(vec3 d) {
    float ax = abs(d.x), az = abs(d.z);
    float t = min(ax, az) / max(max(ax, az), 1.0e-30);
    float t2 = t * t;
    float a = t * (0.99997726 + t2 * (-0.33262347 + t2 * (0.19354346 + t2 * (-0.11643287 + t2 * (0.05265332 + t2 * -0.01172120)))));
    if (az > ax) a = 1.57079633 - a;
    if (d.x < 0.0) a = kPi - a;
    if (d.z < 0.0) a = -a;
    float ay = min(abs(d.y), 1.0);
    float c = sqrt(1.0 - ay) * (1.5707288 + ay * (-0.2121144 + ay * (0.0742610 + ay * -0.0187293)));
    if (d.y < 0.0) c = kPi - c;
    return vec2(0.5 + a * (0.5 / kPi), c * (1.0 / kPi));
}
// The specular light reflected toward v by a surface of normal n and roughness r.
vec3 environmentSpecular(vec3 n, vec3 v, float r) {
    vec3 d = normalize(n * (2.0 * dot(n, v)) - v);
    return textureLod(u_environmentMap, equirectUv(d), r * FRUGAL_ENVIRONMENT_MAP).rgb;
}
#endif

#ifdef FRUGAL_TONEMAP_NEUTRAL
// The Khronos PBR Neutral operator (the Khronos renderer's toneMap_KhronosPbrNeutral).
vec3 toneMapNeutral(vec3 c) {
    const float start = 0.8 - 0.04;
    const float d = 1.0 - start;
    float x = min(c.r, min(c.g, c.b));
    float offset = x < 0.08 ? x - (6.25 * x) * x : 0.04;
    c = c - offset;
    float peak = max(c.r, max(c.g, c.b));
    if (peak < start) return c;
    float newPeak = 1.0 - (d * d) / ((peak + d) - start);
    c = c * (newPeak / peak);
    float g = 1.0 - 1.0 / (0.15 * (peak - newPeak) + 1.0);
    return c * (1.0 - g) + vec3(newPeak * g);
}
#endif
#ifdef FRUGAL_TONEMAP_ACES
// Stephen Hill's ACES fit (the Khronos renderer's toneMapACES_Hill and its matrices).
const mat3 kAcesInput = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777);
const mat3 kAcesOutput = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602);
vec3 toneMapAces(vec3 c) {
    c = kAcesInput * c;
    vec3 a = c * (c + 0.0245786) - 0.000090537;
    vec3 b = c * (0.983729 * c + 0.4329510) + 0.238081;
    return clamp(kAcesOutput * (a / b), 0.0, 1.0);
}
#endif

// mix(dielectric, metal, metallic), written out; with FRUGAL_DIELECTRIC (metallic exactly 0) the
// dielectric, with FRUGAL_METAL (exactly 1) the metal, as that sum gives them: the other side's
// terms are then never read, and the compiler leaves them out.
vec3 metalMix(vec3 dielectric, vec3 metal, float metallic) {
#if defined(FRUGAL_DIELECTRIC)
    return dielectric;
#elif defined(FRUGAL_METAL)
    return metal;
#else
    return dielectric * (1.0 - metallic) + metal * metallic;
#endif
}

void main() {
    vec4 base = u_baseColorFactor;
#ifdef FRUGAL_COLORS
    base = base * v_color;
#endif
#ifdef FRUGAL_TEXTURE
    base = base * texture(u_baseColor, v_uv);
#endif
#ifdef FRUGAL_ALPHA_MASK
    if (base.a < u_alphaCutoff) discard;
#endif
#ifdef FRUGAL_UNLIT
    vec3 linear = base.rgb;
#ifdef FRUGAL_BARE
    vec3 emission = u_emissive;
#ifdef FRUGAL_EMISSIVE_MAP
    emission = emission * texture(u_emissiveMap, v_uv).rgb;
#endif
    linear = emission + linear;
#endif
#else
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    vec3 emissive = u_emissive;
#ifdef FRUGAL_EMISSIVE_MAP
    emissive = emissive * texture(u_emissiveMap, v_uv).rgb;
#endif
#ifdef FRUGAL_LAMBERT
    // The diffuse term alone (FrameParams::shading): the environment's radiance and each light's
    // E·(n·l)/π on the base colour, then the emission.
#ifdef FRUGAL_ENVIRONMENT_MAP
    vec3 irradiance = environmentDiffuse(n);
#else
    vec3 irradiance = vec3(u_environment);
#endif
#ifdef FRUGAL_LIGHTS
    int lightCount = int(u_lights[4 * FRUGAL_LIGHTS].x);
    for (int i = 0; i < lightCount; ++i) {
        vec3 l, e;
        lightAt(i, l, e);
        irradiance += e * (clampedDot(n, l) / kPi);
    }
#else
    irradiance += vec3(u_light * (clampedDot(n, u_toLight) / kPi));
#endif
    vec3 linear = base.rgb * irradiance + emissive;
#else
#ifdef FRUGAL_TANGENTS
    vec3 t = normalize(v_tangent), b = normalize(v_bitangent);
    if (!gl_FrontFacing) {
        t = -t;
        b = -b;
    }
#endif
#ifdef FRUGAL_CLEARCOAT
    vec3 nc = n;
#ifdef FRUGAL_CLEARCOAT_NORMAL_MAP
    vec3 mc = texture(u_clearcoatNormalMap, v_uv).rgb * 2.0 - vec3(1.0);
    mc = normalize(mc * vec3(u_clearcoat.z, u_clearcoat.z, 1.0));
    nc = (t * mc.x + b * mc.y) + n * mc.z;
#endif
#endif
#ifdef FRUGAL_NORMAL_MAP
    vec3 m = texture(u_normalMap, v_uv).rgb * 2.0 - vec3(1.0);
    m = normalize(m * vec3(u_normalScale, u_normalScale, 1.0));
    n = normalize((t * m.x + b * m.y) + n * m.z);
#endif
    vec3 v = normalize(u_eye - v_position);
#ifdef FRUGAL_SPECULAR_GLOSSINESS
    vec3 f0 = u_specularGlossiness.rgb;
    float glossiness = u_specularGlossiness.a;
#ifdef FRUGAL_SPECULAR_GLOSSINESS_MAP
    vec4 sg = texture(u_specularGlossinessMap, v_uv);
    f0 = f0 * sg.rgb;
    glossiness = glossiness * sg.a;
#endif
    float r = 1.0 - glossiness;
#else
    float metallic = u_metallicRoughness.x, r = u_metallicRoughness.y;
#ifdef FRUGAL_METALLIC_ROUGHNESS_MAP
    vec4 mr = texture(u_metallicRoughnessMap, v_uv);
    metallic = metallic * mr.b;
    r = r * mr.g;
#endif
#endif
    float alpha2 = (r * r) * (r * r);
    float nv = clampedDot(n, v);
    float cv = pow5(1.0 - nv);

    // The environment: diffuse and specular image-based light of a uniform radiance, or of a map.
#ifdef FRUGAL_ENVIRONMENT_MAP
    vec3 diffuseLight = environmentDiffuse(n);
#else
    vec3 diffuseLight = vec3(u_environment);
#endif
#ifdef FRUGAL_NO_ENVIRONMENT_SPECULAR
    // Its diffuse lobe alone (Lighting::environmentSpecular).
    vec3 dielectric = base.rgb * diffuseLight;
#ifndef FRUGAL_SPECULAR_GLOSSINESS
    vec3 metal = vec3(0.0);
#endif
#else
#ifdef FRUGAL_ENVIRONMENT_MAP
    vec3 specularLight = environmentSpecular(n, v, r);
#else
    vec3 specularLight = vec3(u_environment);
#endif
    vec2 ab = dfg(nv, r);
#ifdef FRUGAL_SPECULAR_GLOSSINESS
    vec3 fd = iblFresnel(f0, r, cv, ab);
    vec3 dielectric = (base.rgb * diffuseLight) * (1.0 - fd) + specularLight * fd;
#else
    float fd = iblFresnel(kDielectricF0, r, cv, ab);
    vec3 dielectric = (base.rgb * diffuseLight) * (1.0 - fd) + specularLight * fd;
    vec3 metal = iblFresnel(base.rgb, r, cv, ab) * specularLight;
#endif
#endif
#ifdef FRUGAL_OCCLUSION_MAP
    float occlusion = 1.0 + u_occlusionStrength * (texture(u_occlusionMap, v_uv).r - 1.0);
#endif
#ifdef FRUGAL_CLEARCOAT
    // The coat over the environment's colour; the light's is gathered from 0 below.
    float coat = u_clearcoat.x, coatRoughness = u_clearcoat.y;
#ifdef FRUGAL_CLEARCOAT_MAP
    coat = coat * texture(u_clearcoatMap, v_uv).r;
#endif
#ifdef FRUGAL_CLEARCOAT_ROUGHNESS_MAP
    coatRoughness = coatRoughness * texture(u_clearcoatRoughnessMap, v_uv).g;
#endif
    float k = coat * (kDielectricF0 + (1.0 - kDielectricF0) * pow5(1.0 - clampedDot(nc, v)));
#ifdef FRUGAL_SPECULAR_GLOSSINESS
    vec3 environment = dielectric;
#else
    vec3 environment = metalMix(dielectric, metal, metallic);
    metal = vec3(0.0);
#endif
#ifdef FRUGAL_NO_ENVIRONMENT_SPECULAR
    environment = environment * (1.0 - k);
#elif defined(FRUGAL_ENVIRONMENT_MAP)
    environment = environment * (1.0 - k) + environmentSpecular(nc, v, coatRoughness) * k;
#else
    environment = environment * (1.0 - k) + u_environment * k;
#endif
#ifdef FRUGAL_OCCLUSION_MAP
    environment = environment * occlusion;
#endif
    dielectric = vec3(0.0);
#elif defined(FRUGAL_OCCLUSION_MAP)
    dielectric = dielectric * occlusion;
#ifndef FRUGAL_SPECULAR_GLOSSINESS
    metal = metal * occlusion;
#endif
#endif

#ifdef FRUGAL_LIGHTS
    // The scene's punctual lights, each as the directional light below with its own l and E.
#ifdef FRUGAL_CLEARCOAT
    vec3 coatSpecular = vec3(0.0);
    float coatAlpha2 = (coatRoughness * coatRoughness) * (coatRoughness * coatRoughness);
    float ncv = clampedDot(nc, v);
#endif
    int lightCount = int(u_lights[4 * FRUGAL_LIGHTS].x);
    for (int i = 0; i < lightCount; ++i) {
        vec3 l, e;
        lightAt(i, l, e);
        vec3 h = normalize(l + v);
        float nl = clampedDot(n, l), nh = clampedDot(n, h), vh = clampedDot(v, h);
        vec3 radiance = e * nl;
        vec3 specular = radiance * ggx(nl, nv, nh, alpha2);
        float ch = pow5(1.0 - vh);
#ifdef FRUGAL_SPECULAR_GLOSSINESS
        vec3 fl = f0 + (1.0 - f0) * ch;
        dielectric += (base.rgb * (radiance / kPi)) * (1.0 - fl) + specular * fl;
#else
        float fl = kDielectricF0 + (1.0 - kDielectricF0) * ch;
        dielectric += (base.rgb * (radiance / kPi)) * (1.0 - fl) + specular * fl;
        metal += (base.rgb + (1.0 - base.rgb) * ch) * specular;
#endif
#ifdef FRUGAL_CLEARCOAT
        float ncl = clampedDot(nc, l);
        coatSpecular += e * (ncl * ggx(ncl, ncv, clampedDot(nc, h), coatAlpha2));
#endif
    }
#else
    // The directional light.
    vec3 l = u_toLight;
    vec3 h = normalize(l + v);
    float nl = clampedDot(n, l), nh = clampedDot(n, h), vh = clampedDot(v, h);
    float radiance = u_light * nl;
    float specular = radiance * ggx(nl, nv, nh, alpha2);
    float ch = pow5(1.0 - vh);
#ifdef FRUGAL_SPECULAR_GLOSSINESS
    vec3 fl = f0 + (1.0 - f0) * ch;
    dielectric += (base.rgb * (radiance / kPi)) * (1.0 - fl) + specular * fl;
#else
    float fl = kDielectricF0 + (1.0 - kDielectricF0) * ch;
    dielectric += (base.rgb * (radiance / kPi)) * (1.0 - fl) + vec3(specular * fl);
    metal += (base.rgb + (1.0 - base.rgb) * ch) * specular;
#endif
#endif

#ifdef FRUGAL_SPECULAR_GLOSSINESS
    vec3 lit = dielectric;
#else
    vec3 lit = metalMix(dielectric, metal, metallic);
#endif
#ifdef FRUGAL_CLEARCOAT
#ifndef FRUGAL_LIGHTS
    float ncl = clampedDot(nc, l);
    float coatAlpha2 = (coatRoughness * coatRoughness) * (coatRoughness * coatRoughness);
    float coatSpecular = u_light * (ncl * ggx(ncl, clampedDot(nc, v), clampedDot(nc, h), coatAlpha2));
#endif
    vec3 linear = (environment + (lit * (1.0 - k) + coatSpecular * k)) + emissive * (1.0 - k);
#else
    vec3 linear = lit + emissive;
#endif
#endif
#endif
#ifdef FRUGAL_TONEMAP_NEUTRAL
    linear = toneMapNeutral(linear);
#elif defined(FRUGAL_TONEMAP_ACES)
    linear = toneMapAces(linear);
#endif
#if defined(FRUGAL_LINEAR_OUTPUT) && defined(FRUGAL_ALPHA_BLEND)
    o_color = vec4(linear, clamp(base.a, 0.0, 1.0));  // a float target clamps nothing
#elif defined(FRUGAL_LINEAR_OUTPUT)
    o_color = vec4(linear, 1.0);
#elif defined(FRUGAL_ALPHA_BLEND)
    o_color = vec4(pow(linear, vec3(1.0 / 2.2)), base.a);
#else
    o_color = vec4(pow(linear, vec3(1.0 / 2.2)), 1.0);
#endif
#ifdef FRUGAL_IDS
    o_id = v_id;
#endif
}
