#include "material_args.h"

#include "mipgloss/ibl/phong.h"
#include "mipgloss/ibl/specular.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace mipgloss::app {

float parseFloat(const std::string& flag, const std::string& value, float lo, float hi) {
    char* end = nullptr;
    const float v = std::strtof(value.c_str(), &end);
    if (end == value.c_str() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
        throw UsageError(flag + " needs a number from " + std::to_string(lo) + " to " +
                         std::to_string(hi) + ", got '" + value + "'");
    return v;
}

int parseWholeNumber(const std::string& flag, const std::string& value, int lo, int hi) {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(value.c_str(), &end, 10);
    if (value.empty() || end == value.c_str() || *end != '\0' || errno == ERANGE || v < lo || v > hi)
        throw UsageError(flag + " needs a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                         ", got '" + value + "'");
    return static_cast<int>(v);
}

void parseSize(const std::string& flag, const std::string& text, int& w, int& h) {
    const auto x = text.find('x');
    auto whole = [&](const std::string& part, const char* axis) {
        char* end = nullptr;
        errno = 0;
        const long long v = part.empty() ? 0 : std::strtoll(part.c_str(), &end, 10);
        if (part.empty() || *end != '\0' || errno == ERANGE || v > 1'000'000'000)
            throw UsageError(flag + " needs WxH, two whole numbers such as 800x600, got '" + text + "'");
        if (v < 1) throw UsageError(flag + " " + text + ": the " + axis + " " + part + " must be at least 1");
        return static_cast<int>(v);
    };
    if (x == std::string::npos)
        throw UsageError(flag + " needs WxH, two whole numbers such as 800x600, got '" + text + "'");
    w = whole(text.substr(0, x), "width");
    h = whole(text.substr(x + 1), "height");
}

std::string lowerExtension(const std::filesystem::path& file) {
    std::string s = file.extension().string();
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

float parseLambda(const std::string& flag, const std::string& value) {
    return parseFloat(flag, value, 0.0f, static_cast<float>(kMaxLambda));
}

float parseExponentAsLambda(const std::string& flag, const std::string& value) {
    if (value == "mirror" || value == "inf") return 0.0f;
    const float n = parseFloat(flag, value, 0.0f, 1e9f);
    return static_cast<float>(exponentToLambda(n));
}

LookupMode parseMode(const std::string& flag, const std::string& value) {
    return parseChoice<LookupMode>(flag, value, {LookupMode::Reflect, LookupMode::Normal}, lookupModeName);
}

Rgb parseTint(const std::string& flag, const std::string& value) {
    const std::string rule =
        flag + " needs three numbers >= 0 separated by commas (linear RGB, e.g. 1,0.8,0.3), got '" + value + "'";
    std::vector<float> parts;
    std::stringstream in(value);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const float v = std::strtof(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(v) || v < 0.0f) throw UsageError(rule);
        parts.push_back(v);
    }
    if (parts.size() != 3 || value.back() == ',') throw UsageError(rule);
    return Rgb(parts[0], parts[1], parts[2]);
}

bool readLayerFlag(const std::string& flag, const std::function<std::string()>& value, LayerFlags& flags) {
    auto unit = [&] { return parseFloat(flag, value(), 0.0f, 1.0f); };
    if (flag == "--base-color") {
        const Rgb c = parseTint(flag, value());
        if (c.r > 1.0f || c.g > 1.0f || c.b > 1.0f)
            throw UsageError(flag + " needs three numbers from 0 to 1 (linear RGB; a surface reflects at most what "
                                    "reaches it), got " + std::to_string(c.r) + "," + std::to_string(c.g) + "," +
                             std::to_string(c.b));
        flags.baseColor = c;
    } else if (flag == "--metallic") flags.metallic = unit();
    else if (flag == "--roughness") flags.roughness = unit();
    else if (flag == "--specular") flags.specular = unit();
    else if (flag == "--specular-weight") flags.specularWeight = unit();
    else if (flag == "--specular-color") {
        const Rgb c = parseTint(flag, value());
        if (c.r > kMaxSpecularColour || c.g > kMaxSpecularColour || c.b > kMaxSpecularColour)
            throw UsageError(flag + " needs three numbers from 0 to " + std::to_string(int(kMaxSpecularColour)) +
                             " (it multiplies F0, which is then at most 1), got " + std::to_string(c.r) + "," +
                             std::to_string(c.g) + "," + std::to_string(c.b));
        flags.specularColor = c;
    }
    else if (flag == "--coat") flags.coat = unit();
    else if (flag == "--coat-roughness") flags.coatRoughness = unit();
    else return false;
    return true;
}

void applyLayerFlags(const LayerFlags& flags, std::optional<float> lambda, const std::string& lambdaFlag,
                     Material& material) {
    if (flags.roughness && lambda)
        throw UsageError(lambdaFlag + " and --roughness both set the specular lobe; give one");
    if (!material.layered) material.layers = Layers{};
    material.layered = true;
    Layers& l = material.layers;
    if (flags.baseColor) l.baseColor = *flags.baseColor;
    if (flags.metallic) l.metallic = *flags.metallic;
    if (flags.roughness) l.roughness = *flags.roughness;
    if (lambda) l.roughness = static_cast<float>(exponentToRoughness(lambdaToExponent(*lambda)));
    if (flags.specular) l.specular = *flags.specular;
    if (flags.specularWeight) l.specularWeight = *flags.specularWeight;
    if (flags.specularColor) l.specularColor = *flags.specularColor;
    if (flags.coat) l.coat = *flags.coat;
    if (flags.coatRoughness) l.coatRoughness = *flags.coatRoughness;
}

}  // namespace mipgloss::app
