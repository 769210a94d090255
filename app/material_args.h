// The command-line values every subcommand reads the same way: numbers with limits, and a
// material's parameters (`render --lambda`, `library add --lambda`): one meaning of λ and of the
// Phong exponent (phong.h), one set of limits, usage errors naming the flag.
#pragma once

#include "cli_args.h"

#include "mipgloss/scene/scene.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace mipgloss::app {

// A whole number in [lo, hi] (decimal digits, an optional sign); UsageError naming `flag` and the
// range otherwise.
int parseWholeNumber(const std::string& flag, const std::string& value, int lo, int hi);
// A finite number in [lo, hi]; UsageError naming `flag` otherwise.
float parseFloat(const std::string& flag, const std::string& value, float lo, float hi);
// --size WxH: two whole numbers of at least 1 into `w` and `h`, or a UsageError naming the flag and
// the value. What the OpenGL can draw is checked once a context exists (checkRenderSize).
void parseSize(const std::string& flag, const std::string& text, int& w, int& h);
// A file's extension in lower case (".exr", ".png"): how an output's format is chosen.
std::string lowerExtension(const std::filesystem::path& file);
// --lambda L: λ in [0, kMaxLambda].
float parseLambda(const std::string& flag, const std::string& value);
// --exponent N: the λ of Phong exponent N >= 0; "mirror" or "inf" is the mirror, λ 0.
float parseExponentAsLambda(const std::string& flag, const std::string& value);
// --mode reflect|normal.
LookupMode parseMode(const std::string& flag, const std::string& value);
// --tint R,G,B: three finite numbers >= 0, linear RGB.
Rgb parseTint(const std::string& flag, const std::string& value);

// A layered material's flags (layered.h), the same for `render` and `library add`:
//   --base-color R,G,B (linear, each in [0, 1]), --metallic M, --roughness R, --specular F0,
//   --coat W, --coat-roughness R (each in [0, 1]); KHR_materials_specular's --specular-weight W
//   (in [0, 1]) and --specular-color R,G,B (each in [0, kMaxSpecularColour]).
struct LayerFlags {
    std::optional<Rgb> baseColor, specularColor;
    std::optional<float> metallic, roughness, specular, coat, coatRoughness, specularWeight;
    bool any() const {
        return baseColor || metallic || roughness || specular || coat || coatRoughness || specularColor || specularWeight;
    }
};
// True, with the value read through `value` into `flags`, when `flag` is one of them.
bool readLayerFlag(const std::string& flag, const std::function<std::string()>& value, LayerFlags& flags);
// Makes `material` layered, the flags given over its layers (Layers{} when it was single-lobe). A
// specular lobe set by --lambda/--exponent (`lambda`, from `lambdaFlag`) becomes its roughness
// (exponentToRoughness); with --roughness too it is a UsageError.
void applyLayerFlags(const LayerFlags& flags, std::optional<float> lambda, const std::string& lambdaFlag,
                     Material& material);

}  // namespace mipgloss::app
