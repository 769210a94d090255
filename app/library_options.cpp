#include "library_options.h"

#include "material_args.h"

#include "mipgloss/scene/library.h"

namespace mipgloss::app {

std::string requireName(const std::string& flag, const std::string& name) {
    if (const std::string problem = materialNameProblem(name); !problem.empty())
        throw UsageError(flag + " '" + name + "': " + problem);
    return name;
}

std::filesystem::path libraryArgument(Args& args, const std::string& command) {
    if (args.empty()) throw UsageError("library " + command + " needs LIB.mglib");
    const std::string file = args.next();
    if (!file.empty() && file[0] == '-')
        throw UsageError("library " + command + " needs LIB.mglib first, got '" + file + "'");
    return file;
}

LibraryAddOptions parseLibraryAddOptions(Args args) {
    LibraryAddOptions o;
    o.file = libraryArgument(args, "add");
    std::optional<std::string> name;
    std::optional<std::string> lambdaFlag;  // which of --lambda and --exponent set it
    Material& material = o.material;
    LayerFlags layerFlags;
    while (!args.empty()) {
        const std::string a = args.next();
        auto value = [&] { return args.value(a); };
        if (a == "--name") name = requireName(a, value());
        else if (readLayerFlag(a, value, layerFlags)) continue;
        else if (a == "--lambda" || a == "--exponent") {
            if (lambdaFlag) throw UsageError(a + ": λ is already set by " + *lambdaFlag + "; give --lambda or --exponent once");
            lambdaFlag = a;
            material.lambda = a == "--lambda" ? parseLambda(a, value()) : parseExponentAsLambda(a, value());
        } else if (a == "--mode") material.mode = parseMode(a, value());
        else if (a == "--tint") material.tint = parseTint(a, value());
        else if (a == "--irradiance") material.useIrradiance = true;
        else if (a == "--grazing") material.sharperAtGrazing = true;
        else throw UsageError("library add: unknown argument '" + a + "'");
    }
    if (!name) throw UsageError("library add needs --name NAME");
    o.name = *name;
    if (layerFlags.any()) {
        const std::optional<float> lambda = lambdaFlag ? std::optional(material.lambda) : std::nullopt;
        material.lambda = 0.0f;
        applyLayerFlags(layerFlags, lambda, lambdaFlag.value_or(""), material);
    }
    return o;
}

LibraryThumbnailOptions parseLibraryThumbnailOptions(Args args) {
    LibraryThumbnailOptions o;
    o.file = libraryArgument(args, "thumbnails");
    bool out = false;
    while (!args.empty()) {
        const std::string a = args.next();
        auto value = [&] { return args.value(a); };
        if (a == "--out") o.outDir = value(), out = true;
        else if (a == "--env") o.environment.source = value();
        else if (a == "--size") o.size = static_cast<int>(parseFloat(a, value(), 16.0f, 4096.0f));
        else if (a == "--env-size") o.environment.faceSize = static_cast<int>(parseFloat(a, value(), 16.0f, 4096.0f));
        else throw UsageError("library thumbnails: unknown argument '" + a + "'");
    }
    if (!out) throw UsageError("library thumbnails needs --out DIR");
    return o;
}

}  // namespace mipgloss::app
