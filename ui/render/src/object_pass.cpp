// The object pass: each visible object drawn with object.frag (or aov.frag for the AOV), its
// material's uniforms set and its lookups bound as the lookup plan says (lookup_plan.h).
#include "renderer_impl.h"
#include "shaders.h"

#include "mipgloss/ibl/ggx_sampling.h"
#include "mipgloss/ibl/phong.h"
#include "mipgloss/scene/layered.h"
#include "mipgloss/scene/lobes.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mipgloss::ui {

// Where a program takes a layered material's values, resolved once per drawObjects call (a
// name lookup per uniform per object would sit in the draw loop).
struct Renderer::Impl::LayeredUniforms {
    explicit LayeredUniforms(QOpenGLShaderProgram& p)
        : f0(p.uniformLocation("uF0")),
          f90(p.uniformLocation("uF90")),
          diffuseF0(p.uniformLocation("uDiffuseF0")),
          diffuseColour(p.uniformLocation("uDiffuseColour")),
          specularRoughness(p.uniformLocation("uSpecularRoughness")),
          coat(p.uniformLocation("uCoat")),
          coatRoughness(p.uniformLocation("uCoatRoughness")),
          useCoatStack(p.uniformLocation("uUseCoatStack")),
          useDiffuseStack(p.uniformLocation("uUseDiffuseStack")),
          diffuseIrradiance(p.uniformLocation("uDiffuseIrradiance")),
          specularEntries(p.uniformLocation("uSpecularEntries")),
          coatEntries(p.uniformLocation("uCoatEntries")),
          specularRemainder(p.uniformLocation("uSpecularRemainder")),
          coatRemainder(p.uniformLocation("uCoatRemainder")),
          specularHeld(p.uniformLocation("uSpecularHeld")),
          coatHeld(p.uniformLocation("uCoatHeld")),
          specularLookups(p.uniformLocation("uSpecularLookups")),
          coatLookups(p.uniformLocation("uCoatLookups")),
          specularMeanShare(p.uniformLocation("uSpecularMeanShare")),
          coatMeanShare(p.uniformLocation("uCoatMeanShare")),
          specularFitted(p.uniformLocation("uSpecularFitted")),
          coatFitted(p.uniformLocation("uCoatFitted")) {}
    int f0, f90, diffuseF0, diffuseColour, specularRoughness, coat, coatRoughness, useCoatStack, useDiffuseStack,
        diffuseIrradiance, specularEntries, coatEntries, specularRemainder, coatRemainder, specularHeld, coatHeld,
        specularLookups, coatLookups, specularMeanShare, coatMeanShare, specularFitted, coatFitted;
};

// The uniforms a single-lobe material shares with a layered one's specular layer.
struct Renderer::Impl::LobeUniforms {
    int useStack, exponent;
};

// What drawing one object read: the stack's exact lobes (the settled picture), or the chain
// standing in for a lobe while its entries are made.
struct Renderer::Impl::ObjectRead {
    bool settled = false;
    bool fromChain = false;
};

// Where a program takes a material's maps (material_maps.glsl), resolved once per drawObjects call.
struct Renderer::Impl::MapUniforms {
    explicit MapUniforms(QOpenGLShaderProgram& p)
        : metallicChannel(p.uniformLocation("uMetallicChannel")),
          roughnessChannel(p.uniformLocation("uRoughnessChannel")),
          baseColor(p.uniformLocation("uBaseColor")),
          baseAlpha(p.uniformLocation("uBaseAlpha")),
          metallic(p.uniformLocation("uMetallic")),
          roughness(p.uniformLocation("uRoughness")),
          dielectricF0(p.uniformLocation("uDielectricF0")),
          dielectricF90(p.uniformLocation("uDielectricF90")),
          diffuseDielectricF0(p.uniformLocation("uDiffuseDielectricF0")),
          normalScale(p.uniformLocation("uNormalScale")),
          occlusionStrength(p.uniformLocation("uOcclusionStrength")),
          emissive(p.uniformLocation("uEmissive")),
          alphaMode(p.uniformLocation("uAlphaMode")),
          alphaCutoff(p.uniformLocation("uAlphaCutoff")),
          texCoords(p.uniformLocation("uMapTexCoord")),
          transforms(p.uniformLocation("uMapTransform")) {
        const char* use[kMapCount] = {"uUseBaseColorMap", "uUseMetallicMap", "uUseRoughnessMap",
                                      "uUseNormalMap", "uUseOcclusionMap", "uUseEmissiveMap"};
        for (int i = 0; i < kMapCount; ++i) uses[i] = p.uniformLocation(use[i]);
    }
    int metallicChannel, roughnessChannel, baseColor, baseAlpha, metallic, roughness, dielectricF0, dielectricF90,
        diffuseDielectricF0, normalScale, occlusionStrength, emissive, alphaMode, alphaCutoff, texCoords, transforms;
    int uses[kMapCount];  // the samplers' units are set once (texture_units.h)
};

// The stack's table and atlas for `program` (object, AOV and background programs).
void Renderer::Impl::bindStack(QOpenGLShaderProgram& program) {
    const bool current = stackCurrent();
    std::array<glm::vec4, kStackSlots> table = stackTable;
    if (!current)
        for (glm::vec4& e : table) e.w = 0.0f;
    gl->glUniform4fv(program.uniformLocation("uStackEntry"), kStackSlots, glm::value_ptr(table[0]));
    gl->glUniform1fv(program.uniformLocation("uStackExponent"), kStackSlots, stackExponents.data());
    gl->glUniform1fv(program.uniformLocation("uStackScale"), kStackSlots, stackScales.data());
    std::array<glm::vec4, kStackSlots> remainder = remainderTable;
    if (!current) remainder.fill(glm::vec4(0.0f));
    gl->glUniform4fv(program.uniformLocation("uRemainderEntry"), kStackSlots, glm::value_ptr(remainder[0]));
    gl->glUniform1i(program.uniformLocation("uStackTop"), stackTop(std::max(stackBaseSize, 1)));
    gl->glActiveTexture(GL_TEXTURE0 + unitIndex(TextureUnit::Stack));
    gl->glBindTexture(GL_TEXTURE_2D, stackTexture);
    gl->glBindSampler(unitIndex(TextureUnit::Stack), 0);
    gl->glActiveTexture(GL_TEXTURE0);
}

// Binds the chain (or, for a mirror, the mirror texture) to `unit` with the sampler holding
// the plan's MIN_LOD; unit 0 stays active.
void Renderer::Impl::bindChain(const ObjectLookup& plan, GLuint unit) {
    gl->glActiveTexture(GL_TEXTURE0 + unit);
    gl->glBindTexture(GL_TEXTURE_CUBE_MAP, plan.mirror ? mirrorTexture : environmentTexture);
    gl->glBindSampler(unit, sampler(plan.minLevel));
    gl->glActiveTexture(GL_TEXTURE0);
}

// A layered material's maps: binds each decoded one to its unit (white where none) and sets
// the factors. Returns whether the roughness map is read (each fragment its own lobe).
bool Renderer::Impl::bindMaps(const MapUniforms& u, const Layers& l) {
    const MaterialMaps& m = l.maps;
    if (u.baseColor < 0) return false;  // a program without the maps (material_maps.glsl)
    if (whiteTexture == 0) {
        const std::uint8_t white[4] = {255, 255, 255, 255};
        gl->glGenTextures(1, &whiteTexture);
        gl->glBindTexture(GL_TEXTURE_2D, whiteTexture);
        gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    const TextureRef* refs[kMapCount] = {&m.baseColor, &m.metallic, &m.roughness, &m.normal, &m.occlusion, &m.emissive};
    const bool srgb[kMapCount] = {true, false, false, false, false, true};
    bool used[kMapCount];
    GLuint uploaded[kMapCount];
    // Uploads first (each binds its texture to the active unit), then the units.
    gl->glActiveTexture(GL_TEXTURE0 + mapUnit(kMapCount));
    for (int i = 0; i < kMapCount; ++i) uploaded[i] = mapTexture(*refs[i], srgb[i]);
    for (int i = 0; i < kMapCount; ++i) {
        const GLuint texture = uploaded[i];
        used[i] = texture != 0;
        const GLuint unit = mapUnit(i);
        gl->glActiveTexture(GL_TEXTURE0 + unit);
        gl->glBindTexture(GL_TEXTURE_2D, used[i] ? texture : whiteTexture);
        gl->glBindSampler(unit, used[i] ? mapSampler(m.sampling[static_cast<std::size_t>(i)]) : 0);
        gl->glUniform1i(u.uses[i], used[i] ? 1 : 0);
    }
    // Each map's UV set and KHR_texture_transform (material_maps.glsl, mapUv).
    std::array<GLint, kMapCount> texCoords{};
    std::array<glm::mat3, kMapCount> transforms{};
    for (int i = 0; i < kMapCount; ++i) {
        texCoords[static_cast<std::size_t>(i)] = m.sampling[static_cast<std::size_t>(i)].texCoord;
        transforms[static_cast<std::size_t>(i)] = m.sampling[static_cast<std::size_t>(i)].uvTransform();
    }
    gl->glUniform1iv(u.texCoords, kMapCount, texCoords.data());
    gl->glUniformMatrix3fv(u.transforms, kMapCount, GL_FALSE, glm::value_ptr(transforms[0]));
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glUniform1i(u.metallicChannel, m.metallic.channel);
    gl->glUniform1i(u.roughnessChannel, m.roughness.channel);
    gl->glUniform3fv(u.baseColor, 1, glm::value_ptr(l.baseColor));
    gl->glUniform1f(u.baseAlpha, m.baseAlpha);
    gl->glUniform1f(u.metallic, l.metallic);
    gl->glUniform1f(u.roughness, l.roughness);
    // The dielectric's Fresnel alone; the shader mixes it with the mapped metal's.
    const DielectricFresnel dielectric = dielectricFresnel(l);
    gl->glUniform3fv(u.dielectricF0, 1, glm::value_ptr(dielectric.f0));
    gl->glUniform1f(u.dielectricF90, dielectric.f90);
    gl->glUniform1f(u.diffuseDielectricF0, dielectric.diffuseF0);
    gl->glUniform1f(u.normalScale, m.normalScale);
    gl->glUniform1f(u.occlusionStrength, m.occlusionStrength);
    gl->glUniform3fv(u.emissive, 1, glm::value_ptr(m.emissiveFactor));
    gl->glUniform1i(u.alphaMode, static_cast<int>(m.alphaMode));
    gl->glUniform1f(u.alphaCutoff, m.alphaCutoff);
    return used[2];
}

// Sets a layered material's uniforms and binds its three lookups.
Renderer::Impl::ObjectRead Renderer::Impl::bindLayered(const LayeredUniforms& u, const LobeUniforms& lobeUniforms, const MapUniforms& mapUniforms, const Material& m, bool irradianceReady, int lookups, bool lightsShaded) {
    bindSplitSum();
    LayeredLookup plan = planLayered(m, irradianceReady, environmentFaceSize);
    bindMaps(mapUniforms, m.layers);
    // The GGX layers' lookups (object.frag, readGgx) each read their own lobe per fragment: the
    // stack where it holds it, else the chain at that lobe's level, from level 0 (planLayered).
    const bool diffuseIrradiance = plan.diffuse.lookup == ShaderLookup::Irradiance;
    // How many lookups each GGX layer reads (fewer where a polished layer's K would be sharper than
    // the stack: ggxLayerLookups), the entries they read (ggxEntries), and whether the stack holds
    // them all (else the lookups read the chain).
    const int base = std::max(stackBaseSize, 1);
    const bool mapped = !m.layers.maps.roughness.empty();
    const int specularLookups = ggxLayerLookups(m.layers.roughness, lookups, base, mapped, lightsShaded);
    const int coatLookups = ggxLayerLookups(m.layers.coatRoughness, lookups, base, false, lightsShaded);
    gl->glUniform1i(u.specularLookups, std::max(specularLookups, 1));
    gl->glUniform1i(u.coatLookups, std::max(coatLookups, 1));
    // A rough layer reads its mean lobe (ggx_sampling.h, meanLobeShare); a roughness map's
    // fragments may be any roughness, so that layer reads its K lookups.
    gl->glUniform1f(u.specularMeanShare, mapped ? 0.0f : static_cast<float>(meanLobeShare(m.layers.roughness)));
    gl->glUniform1f(u.coatMeanShare, static_cast<float>(meanLobeShare(m.layers.coatRoughness)));
    auto entryRange = [&](double roughness, int count, bool anyRoughness) {
        const std::vector<int> range = ggxEntries(roughness, count, base, anyRoughness);
        if (range.empty()) return glm::ivec2(kStackSlots, kStackLast);  // none: every lookup reads the chain
        return glm::ivec2(range.front(), range.back());
    };
    auto holds = [&](glm::ivec2 range) {
        if (!stackCurrent() || range.x > range.y) return false;
        for (int j = range.x; j <= range.y; ++j)
            if (!stackHolds(stackExponent(j))) return false;
        return true;
    };
    const glm::ivec2 specularEntries = entryRange(m.layers.roughness, specularLookups, mapped);
    const glm::ivec2 coatEntries = plan.hasCoat ? entryRange(m.layers.coatRoughness, coatLookups, false) : glm::ivec2(kStackSlots, kStackLast);
    const bool specular = plan.specular.readsLobeStack && holds(specularEntries);
    const bool coat = plan.hasCoat && plan.coat.readsLobeStack && holds(coatEntries);
    gl->glUniform2i(u.specularEntries, specularEntries.x, specularEntries.y);
    gl->glUniform2i(u.coatEntries, coatEntries.x, coatEntries.y);
    // Whether the stack holds every lookup of each layer (its lookups read the atlas alone), and
    // whether they read the remainder entries (no lights to subtract in them).
    const bool specularHeld = specular && ggxLookupsHeld(m.layers.roughness, specularLookups, base, mapped);
    const bool coatHeld = coat && ggxLookupsHeld(m.layers.coatRoughness, coatLookups, base);
    gl->glUniform1i(u.specularHeld, specularHeld ? 1 : 0);
    gl->glUniform1i(u.coatHeld, coatHeld ? 1 : 0);
    // Layers read their fitted lobes where the grid has them (ggx_fitted_lobes.h), held or not.
    gl->glUniform1i(u.specularFitted, ggxReadsFittedLobes(m.layers.roughness, specularLookups, mapped) ? 1 : 0);
    gl->glUniform1i(u.coatFitted, plan.hasCoat && ggxReadsFittedLobes(m.layers.coatRoughness, coatLookups, false) ? 1 : 0);
    // A layer reading the remainder reads its entries from ggxHeadOnEntry to its last
    // (remainderEntriesOf, without computing ggxEntries again each draw): its lookups' range.
    const double widest = environment ? widestLight(environment->lights) : 0.0;
    auto remainderRange = [&](bool held, double roughness, int count, glm::ivec2 entries) -> std::optional<glm::ivec2> {
        if (!held || !ggxReadsRemainder(roughness, count, base, false, widest)) return std::nullopt;
        const glm::ivec2 range(ggxHeadOnEntry(roughness, count, base), entries.y);
        if (!remainderHolds(range.x, range.y)) return std::nullopt;
        return range;
    };
    const auto specularRemainder = remainderRange(specularHeld, m.layers.roughness, specularLookups, specularEntries);
    const auto coatRemainder = remainderRange(coatHeld, m.layers.coatRoughness, coatLookups, coatEntries);
    gl->glUniform1i(u.specularRemainder, specularRemainder ? 1 : 0);
    gl->glUniform1i(u.coatRemainder, coatRemainder ? 1 : 0);
    if (specularRemainder) gl->glUniform2i(u.specularEntries, specularRemainder->x, specularRemainder->y);
    if (coatRemainder) gl->glUniform2i(u.coatEntries, coatRemainder->x, coatRemainder->y);
    const bool diffuse = !diffuseIrradiance && plan.diffuse.readsLobeStack && stackServes(plan.diffuse.exponent);
    auto set1i = [&](int location, bool v) { gl->glUniform1i(location, v ? 1 : 0); };
    auto set1f = [&](int location, double v) { gl->glUniform1f(location, static_cast<float>(v)); };
    gl->glUniform3fv(u.f0, 1, glm::value_ptr(specularF0(m.layers)));
    gl->glUniform1f(u.f90, specularF90(m.layers));
    gl->glUniform3fv(u.diffuseF0, 1, glm::value_ptr(diffuseFresnelF0(m.layers)));
    gl->glUniform3fv(u.diffuseColour, 1, glm::value_ptr(diffuseColour(m.layers)));
    set1f(u.specularRoughness, m.layers.roughness);
    set1f(u.coat, plan.hasCoat ? m.layers.coat : 0.0f);
    set1f(u.coatRoughness, m.layers.coatRoughness);
    set1i(lobeUniforms.useStack, specular);
    set1f(lobeUniforms.exponent, plan.specular.exponent);
    set1i(u.useCoatStack, coat);
    set1i(u.useDiffuseStack, diffuse);
    set1i(u.diffuseIrradiance, diffuseIrradiance);
    bindChain(plan.specular, unitIndex(TextureUnit::Chain));
    if (plan.hasCoat) bindChain(plan.coat, unitIndex(TextureUnit::CoatChain));
    if (!diffuseIrradiance) bindChain(plan.diffuse, unitIndex(TextureUnit::DiffuseChain));
    // Settled when the stack holds every entry the GGX layers' lookups read.
    ObjectRead read;
    read.settled = specular && (!plan.hasCoat || coat) && (diffuseIrradiance || stackHolds(plan.diffuse.exponent));
    read.fromChain = !read.settled;
    return read;
}

// Draws the visible objects with `program` (object.frag, or aov.frag when `aov`), each from
// the lobe stack where it holds its lobes, else from the chain at the level standing in for it.
void Renderer::Impl::drawObjects(QOpenGLShaderProgram& program, const Scene& scene, const std::vector<int>& objects,
                                 const glm::vec3& eye, const glm::mat4& viewProjection, const glm::mat3& envRotation,
                                 const Frustum& frustum, bool aov) {
    program.bind();
    gl->glUniformMatrix4fv(program.uniformLocation("uViewProjection"), 1, GL_FALSE,
                           glm::value_ptr(viewProjection));
    gl->glUniformMatrix3fv(program.uniformLocation("uEnvironmentRotation"), 1, GL_FALSE,
                           glm::value_ptr(envRotation));
    gl->glUniform3fv(program.uniformLocation("uCameraPosition"), 1, glm::value_ptr(eye));
    const int locModel = program.uniformLocation("uModel");
    const int locNormal = program.uniformLocation("uNormalMatrix");
    const int locTint = program.uniformLocation("uTint");
    const int locLookup = program.uniformLocation("uLookup");
    const int locGrazing = program.uniformLocation("uSharperAtGrazing");
    const int locLambda = program.uniformLocation("uLambda");
    const int locMeshUv1 = program.uniformLocation("uMeshUv1");
    const int locMeshColours = program.uniformLocation("uMeshColours");
    const LobeUniforms lobeUniforms{program.uniformLocation("uUseStack"), program.uniformLocation("uExponent")};
    bindStack(program);
    const LayeredUniforms layeredUniforms(program);
    const MapUniforms mapUniforms(program);
    // The grazing option's per-fragment λ reads level λ + uLevelOffset (phong.h, regularScheduleLevel).
    gl->glUniform1f(program.uniformLocation("uLevelOffset"),
                    static_cast<float>(regularScheduleLevel(0.0, environmentFaceSize)));
    gl->glUniform1f(program.uniformLocation("uLastLevel"), static_cast<float>(std::max(environmentLevels - 1, 0)));
    const bool irradianceReady = uploadedIrradiance != nullptr;
    gl->glUniform1i(program.uniformLocation("uCompensated"), scene.display.scattering == Scattering::Compensated);
    // The environment's bright lights (bright_lights.h), in its frame, as the shaders read them.
    {
        std::array<glm::vec4, kMaxBrightLights> directions{};
        std::array<glm::vec3, kMaxBrightLights> energies{};
        int count = 0;
        if (environment)
            for (const PointLight& light : environment->lights) {
                if (count == kMaxBrightLights) break;
                directions[static_cast<std::size_t>(count)] = glm::vec4(light.direction, light.radius);
                energies[static_cast<std::size_t>(count)] = light.energy;
                ++count;
            }
        gl->glUniform4fv(program.uniformLocation("uLightDirection"), kMaxBrightLights, glm::value_ptr(directions[0]));
        gl->glUniform3fv(program.uniformLocation("uLightEnergy"), kMaxBrightLights, glm::value_ptr(energies[0]));
        gl->glUniform1i(program.uniformLocation("uLightCount"), scene.display.brightLights ? count : 0);
        // A GGX lobe shades them apart from α = 2/N on (lobes.h, lightsApartMinAlpha); sharper
        // ones read them in the environment.
        gl->glUniform1f(program.uniformLocation("uLightsMinAlpha"), scene.display.brightLights
                                                                        ? static_cast<float>(lightsApartMinAlpha(environmentFaceSize))
                                                                        : std::numeric_limits<float>::infinity());
    }

    for (const int index : objects) {
        const SceneObject& object = scene.objects[static_cast<std::size_t>(index)];
        if (!object.visible || !object.mesh || object.mesh->indices.empty()) continue;
        if (!frustum.intersectsSphere(object.worldCentre(), object.worldRadius())) {
            if (!aov) ++counters.objectsCulled;
            continue;
        }
        const GpuMesh& mesh = gpuMesh(object.mesh);
        const Material& m = scene.materialOf(object);
        const glm::mat4 model = object.transform.matrix();
        const glm::mat3 rotation =
            glm::mat3(model) / std::max(std::abs(object.transform.scale), 1e-30f);
        gl->glUniformMatrix4fv(locModel, 1, GL_FALSE, glm::value_ptr(model));
        gl->glUniformMatrix3fv(locNormal, 1, GL_FALSE, glm::value_ptr(rotation));
        ObjectRead read;
        if (m.layered) {
            read = bindLayered(layeredUniforms, lobeUniforms, mapUniforms, m, irradianceReady, scene.display.ggxLookups,
                               scene.display.brightLights);
        } else {
            const ObjectLookup plan = planLookup(m, irradianceReady, environmentFaceSize);
            const bool stack = plan.readsLobeStack && (plan.sharperAtGrazing ? stackCurrent() : stackServes(plan.exponent));
            gl->glUniform3fv(locTint, 1, glm::value_ptr(m.tint));
            gl->glUniform1i(locLookup, static_cast<int>(plan.lookup));
            gl->glUniform1i(locGrazing, plan.sharperAtGrazing ? 1 : 0);
            gl->glUniform1f(locLambda, plan.lambda);
            gl->glUniform1i(lobeUniforms.useStack, stack ? 1 : 0);
            gl->glUniform1f(lobeUniforms.exponent, static_cast<float>(plan.exponent));
            // The paper's one statement per object: the sampler holding MIN_LOD, here the chain
            // level standing in for the material's lobe where the stack does not hold it; a
            // mirror reads the mirror texture.
            bindChain(plan, unitIndex(TextureUnit::Chain));
            read.settled = plan.readsLobeStack && !plan.sharperAtGrazing && stackHolds(plan.exponent);
            read.fromChain = !read.settled && plan.readsChainForLobe();
        }
        // glTF's doubleSided false: the back faces are not drawn (every other material shows both).
        if (m.layered && !m.layers.maps.doubleSided) gl->glEnable(GL_CULL_FACE);
        else gl->glDisable(GL_CULL_FACE);
        // A mesh without a second UV set or vertex colours: UV (0, 0) and white (object.vert).
        gl->glUniform1i(locMeshUv1, mesh.uvs1 ? 1 : 0);
        gl->glUniform1i(locMeshColours, mesh.colours ? 1 : 0);
        gl->glBindVertexArray(mesh.vao);
        gl->glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
        if (aov) continue;
        ++counters.objectsDrawn;
        ++counters.drawCalls;
        if (read.settled) ++counters.objectsSettled;
        else if (read.fromChain) ++counters.objectsFromChain;
    }
}

// The taps' programs (renderer_impl.h, programOf) are built when an object first needs one: two
// more programs at start-up cost every start (the default scene's render about 0.2 s), whether
// or not a polished material is ever drawn. One that fails to build draws its objects without
// taps (the same material, each pixel at its centre).
QOpenGLShaderProgram* Renderer::Impl::tapsProgram(bool maps) {
    std::unique_ptr<QOpenGLShaderProgram>& program = maps ? objectMapsTapsProgram : objectTapsProgram;
    if (!program && !tapsProgramFailed[maps ? 1 : 0]) {
        std::string error;
        program = buildProgram(QStringLiteral("object.vert"), QStringLiteral("object.frag"), &error,
                               maps ? "#define LAYERED\n#define MATERIAL_MAPS\n#define FOOTPRINT_TAPS\n"
                                    : "#define LAYERED\n#define FOOTPRINT_TAPS\n");
        tapsProgramFailed[maps ? 1 : 0] = !program;
    }
    if (program) return program.get();
    return maps ? objectMapsProgram.get() : objectLayeredProgram.get();
}

// The objects of `set` in their programs (programOf): covering ones grouped by program, so each
// program is bound once; blended ones farthest first, by the distance to each object's (glTF: each
// primitive's) centre, so each is blended over what lies behind it (order-dependent blending:
// overlapping parts of one object, or objects that interpenetrate, can still be out of order).
void Renderer::Impl::drawAllObjects(bool aov, ObjectSet set, const Scene& scene, const glm::vec3& eye,
                                    const glm::mat4& viewProjection, const glm::mat3& envRotation, const Frustum& frustum) {
    auto programFor = [&](ObjectProgram kind) {
        switch (kind) {
            case ObjectProgram::Single: return aov ? aovProgram.get() : objectProgram.get();
            case ObjectProgram::Layered: return aov ? aovLayeredProgram.get() : objectLayeredProgram.get();
            case ObjectProgram::LayeredTaps: return aov ? aovLayeredProgram.get() : tapsProgram(false);
            case ObjectProgram::LayeredMapsTaps: return aov ? aovMapsProgram.get() : tapsProgram(true);
            case ObjectProgram::LayeredMaps: break;
        }
        return aov ? aovMapsProgram.get() : objectMapsProgram.get();
    };
    std::vector<int> chosen;
    std::vector<float> order(scene.objects.size(), 0.0f);  // the sort key of each chosen object
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        if (!o.visible || !o.mesh) continue;
        const bool blended = isBlended(scene.materialOf(o));
        if (set != ObjectSet::All && (set == ObjectSet::Blended) != blended) continue;
        chosen.push_back(static_cast<int>(i));
        order[i] = set == ObjectSet::Blended ? -glm::length(o.worldCentre() - eye) : static_cast<float>(programOf(scene, o));
    }
    std::stable_sort(chosen.begin(), chosen.end(), [&](int a, int b) {
        return order[static_cast<std::size_t>(a)] < order[static_cast<std::size_t>(b)];
    });
    // In that order, each run of one program drawn together.
    for (std::size_t start = 0; start < chosen.size();) {
        const ObjectProgram kind = programOf(scene, scene.objects[static_cast<std::size_t>(chosen[start])]);
        std::size_t end = start + 1;
        while (end < chosen.size() && programOf(scene, scene.objects[static_cast<std::size_t>(chosen[end])]) == kind) ++end;
        const std::vector<int> run(chosen.begin() + static_cast<std::ptrdiff_t>(start),
                                   chosen.begin() + static_cast<std::ptrdiff_t>(end));
        drawObjects(*programFor(kind), scene, run, eye, viewProjection, envRotation, frustum, aov);
        start = end;
    }
}

}  // namespace mipgloss::ui
