#include "bake_options.h"

#include "material_args.h"

#include "mipgloss/io/cube_exr.h"
#include "mipgloss/io/import.h"

namespace mipgloss::app {

BakeOptions parseBakeOptions(Args args) {
    BakeOptions o;
    BakeRequest& req = o.request;
    std::string ddsOption, exrOption;  // the last format-specific option given, to refuse a mismatch
    const std::vector<Builder> builders(kAllBuilders.begin(), kAllBuilders.end());
    while (!args.empty()) {
        const std::string a = args.next();
        auto value = [&] { return args.value(a); };
        if (a == "--out") req.outDir = value();
        else if (a == "--builder" || a == "--method") req.builder = parseChoice(a, value(), builders, builderName);
        else if (a == "--size") req.import.faceSize = parseWholeNumber(a, value(), 1, 16384);
        else if (a == "--layout")
            req.import.layout = parseChoice<EnvLayout>(
                a, value(),
                {EnvLayout::Auto, EnvLayout::Faces, EnvLayout::HorizontalCross, EnvLayout::VerticalCross,
                 EnvLayout::HorizontalStrip, EnvLayout::VerticalStrip, EnvLayout::LatLong},
                layoutName);
        else if (a == "--handedness")
            req.import.handedness = parseChoice<Handedness>(a, value(), {Handedness::Right, Handedness::Left}, handednessName);
        else if (a == "--irradiance") req.irradiance = true;
        else if (a == "--format")
            req.format = parseChoice<BakeFormat>(a, value(), {BakeFormat::Exr, BakeFormat::Dds}, bakeFormatName);
        else if (a == "--dds-type") {
            req.ddsType = parseChoice<DdsType>(a, value(), {DdsType::Half, DdsType::Float}, ddsTypeName);
            ddsOption = a;
        } else if (a == "--exr-compression") {
            const std::string v = value();
            if (!isExrCompression(v)) throw UsageError("unknown OpenEXR compression '" + v + "'");
            req.exr.compression = v;
            exrOption = a;
        } else if (a == "--exr-type") {
            req.exr.half = parseChoice<bool>(a, value(), {{"float", false}, {"half", true}});
            exrOption = a;
        } else if (a == "--serial-write") req.parallelWrite = false;
        else if (a == "--quiet") o.quiet = true;
        else if (a == "--help" || a == "-h") {
            o.help = true;
            return o;
        }
        else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "'");
        else if (req.environment.empty()) req.environment = a;
        else throw UsageError("more than one environment given ('" + req.environment.string() + "', '" + a + "')");
    }
    if (req.outDir.empty()) throw UsageError("bake needs --out DIR");
    if (req.format == BakeFormat::Exr && !ddsOption.empty()) throw UsageError(ddsOption + " needs --format dds");
    if (req.format == BakeFormat::Dds && !exrOption.empty()) throw UsageError(exrOption + " needs --format exr");
    return o;
}

}  // namespace mipgloss::app
