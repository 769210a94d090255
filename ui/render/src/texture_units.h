// Every texture unit the renderer binds, in one place: the programs' sampler uniforms are set
// from kSamplerUnits (shaders.cpp) and the shaders see the units by these names as
// TEXTURE_UNIT_* (textureUnitDefines), like the other names C++ and GLSL share (shaderDefines).
#pragma once

#include <QOpenGLFunctions>  // GLuint

#include <array>

namespace mipgloss::ui {

enum class TextureUnit : GLuint {
    Chain = 0,         // uEnvironment: the chain (or the mirror texture), the single lobe's and the specular layer's
    Picture = 0,       // uHdr: the resolved HDR picture the tone pass reads (tonemap.frag)
    Irradiance = 1,    // uIrradiance: E/π
    Stack = 2,         // uStack: the lobe stack's atlas
    SplitSum = 3,      // uGgxAlbedo: the GGX albedo table (ggx_sampling.h)
    CoatChain = 4,     // uCoatChain: the chain at the coat's level (or the mirror)
    LobeMean = 5,      // uGgxLobeMean: the GGX lobe's mean light direction (ggx_sampling.h, meanLobe)
    DiffuseChain = 6,  // uDiffuseChain: the chain at the n = 1 level
    FittedLobes = 7,   // uGgxFittedLobes: the fitted lobes' nodes (ggx_fitted_lobes.h), a 2D array
    FirstMap = 8,      // the material's texture maps, kMapCount units from here (material_maps.glsl)
};
constexpr GLuint unitIndex(TextureUnit unit) { return static_cast<GLuint>(unit); }

// A layered material's texture maps in unit order: base colour, metallic, roughness, normal,
// occlusion, emissive.
constexpr int kMapCount = 6;
constexpr GLuint mapUnit(int map) { return unitIndex(TextureUnit::FirstMap) + static_cast<GLuint>(map); }

// Each sampler uniform of the programs and the unit it reads.
struct SamplerUnit {
    const char* uniform;
    GLuint unit;
};
inline constexpr std::array<SamplerUnit, 15> kSamplerUnits{{
    {"uEnvironment", unitIndex(TextureUnit::Chain)},
    {"uHdr", unitIndex(TextureUnit::Picture)},
    {"uIrradiance", unitIndex(TextureUnit::Irradiance)},
    {"uStack", unitIndex(TextureUnit::Stack)},
    {"uGgxAlbedo", unitIndex(TextureUnit::SplitSum)},
    {"uGgxLobeMean", unitIndex(TextureUnit::LobeMean)},
    {"uGgxFittedLobes", unitIndex(TextureUnit::FittedLobes)},
    {"uCoatChain", unitIndex(TextureUnit::CoatChain)},
    {"uDiffuseChain", unitIndex(TextureUnit::DiffuseChain)},
    {"uBaseColorMap", mapUnit(0)},
    {"uMetallicMap", mapUnit(1)},
    {"uRoughnessMap", mapUnit(2)},
    {"uNormalMap", mapUnit(3)},
    {"uOcclusionMap", mapUnit(4)},
    {"uEmissiveMap", mapUnit(5)},
}};

}  // namespace mipgloss::ui
