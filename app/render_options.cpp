#include "render_options.h"

#include <glm/vector_relational.hpp>

namespace mipgloss::app {

namespace {

const std::vector<Builder> kBuilders(kAllBuilders.begin(), kAllBuilders.end());

}  // namespace

RenderOptions parseRenderOptions(Args args) {
    RenderOptions o;
    while (!args.empty()) {
        const std::string a = args.next();
        auto value = [&] { return args.value(a); };
        if (a == "--env") o.environment = value();
        else if (a == "--mesh") o.meshes.emplace_back(value());
        else if (a == "--out") o.out = value();
        else if (a == "--lambda") o.lambda = parseLambda(a, value()), o.lambdaFlag = a;
        else if (a == "--exponent") o.lambda = parseExponentAsLambda(a, value()), o.lambdaFlag = a;
        else if (readLayerFlag(a, value, o.layers)) continue;
        else if (a == "--library") o.library = value();
        else if (a == "--material") o.libraryMaterial = value();
        else if (a == "--aov") o.aov = value();
        else if (a == "--exposure") o.exposure = parseFloat(a, value(), -kMaxExposureEv, kMaxExposureEv);
        else if (a == "--background-lambda") o.backgroundLambda = parseLambda(a, value());
        else if (a == "--yaw") o.yaw = parseFloat(a, value(), -360.0f, 360.0f);
        else if (a == "--pitch") o.pitch = parseFloat(a, value(), -89.0f, 89.0f);
        else if (a == "--env-size") o.envSize = static_cast<int>(parseFloat(a, value(), 1.0f, 4096.0f));
        else if (a == "--samples") o.samples = static_cast<int>(parseFloat(a, value(), 0.0f, 16.0f));
        else if (a == "--builder" || a == "--method") o.builder = parseChoice(a, value(), kBuilders, builderName);
        else if (a == "--mode") o.mode = parseMode(a, value());
        else if (a == "--tonemap")
            o.toneMap = parseChoice<ToneMap>(a, value(), {kAllToneMaps.begin(), kAllToneMaps.end()}, toneMapName);
        else if (a == "--scattering")
            o.scattering = parseChoice<Scattering>(a, value(), {kAllScatterings.begin(), kAllScatterings.end()},
                                                   scatteringName);
        else if (a == "--size") parseSize(a, value(), o.width, o.height);
        else if (a == "--spin") o.spin = parseFloat(a, value(), -36000.0f, 36000.0f);
        else if (a == "--turntable") o.turntable = parseWholeNumber(a, value(), 1, 3600);
        else if (a == "--turntable-spin")
            o.spinKind = parseChoice<TurntableSpin>(a, value(), {TurntableSpin::Object, TurntableSpin::Environment},
                                                    turntableSpinName);
        else if (a == "--compare-builder") o.compareBuilder = parseChoice(a, value(), kBuilders, builderName);
        else if (a == "--compare-env") o.compareEnv = value();
        else if (a == "--no-background") o.noBackground = true;
        else if (a == "--background") {
            o.background = parseTint(a, value());
            if (glm::any(glm::greaterThan(*o.background, Rgb(1.0f))))
                throw UsageError(a + " takes a colour as the screen shows it, each of R,G,B in [0, 1]");
        } else if (a == "--camera") o.camera = value();
        else if (a == "--env-rotation") o.envRotation = parseFloat(a, value(), -360.0f, 360.0f);
        else if (a == "--quiet") o.quiet = true;
        else if (a == "--no-settle") o.noSettle = true;
        else if (a == "--no-stack") o.noStack = true;
        else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "'");
        else if (!o.scene) o.scene = a;
        else throw UsageError("more than one scene given");
    }
    if (!o.out) throw UsageError("render needs --out IMAGE");
    if (o.library.has_value() != o.libraryMaterial.has_value())
        throw UsageError("--library LIB.mglib and --material NAME go together");
    const std::string compareFlag = o.compareBuilder ? "--compare-builder" : "--compare-env";
    if (o.compare() && o.turntable)
        throw UsageError(compareFlag + " and --turntable do not go together (one picture or a turn)");
    if (o.compare() && o.aov) throw UsageError(compareFlag + " and --aov do not go together (the AOV of which half?)");
    if (o.camera && o.meshes.empty()) throw UsageError("--camera NAME|INDEX looks through a camera of a --mesh glTF file");
    if (o.camera && (o.yaw || o.pitch)) throw UsageError("--camera and --yaw/--pitch do not go together (whose view?)");
    if (o.turntable && o.aov) throw UsageError("--turntable and --aov do not go together");
    if (o.noSettle && o.noStack)
        throw UsageError("--no-settle and --no-stack do not go together (the stack ahead, or none?)");
    // With --turntable, --out names the frames (frame_pattern.h); the first frame's name stands
    // for all of them in the checks that follow.
    if (o.turntable)
        if (const std::string problem = parseFramePattern(o.out->string(), o.frames); !problem.empty())
            throw UsageError("--out " + o.out->string() + " with --turntable: " + problem);
    return o;
}

}  // namespace mipgloss::app
