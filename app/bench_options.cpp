#include "bench_options.h"

#include "material_args.h"

#include "mipgloss/ibl/phong.h"

#include <sstream>

namespace mipgloss::app {

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

BenchOptions parseBenchOptions(Args args) {
    BenchOptions o;
    const std::vector<Builder> all(kAllBuilders.begin(), kAllBuilders.end());
    while (!args.empty()) {
        const std::string a = args.next();
        if (a == "--env") o.environments.emplace_back(args.value(a));
        else if (a == "--sizes") {
            o.sizes.clear();
            for (const auto& s : splitList(args.value(a))) o.sizes.push_back(parseWholeNumber(a, s, 1, 16384));
        } else if (a == "--builders" || a == "--methods") {
            o.builders.clear();
            for (const auto& name : splitList(args.value(a))) o.builders.push_back(parseChoice(a, name, all, builderName));
        } else if (a == "--repeat") o.repeat = parseWholeNumber(a, args.value(a), 1, 16384);
        else if (a == "--directions") o.directions = parseWholeNumber(a, args.value(a), 1, 16384);
        else if (a == "--no-half") o.halfLevels = false;
        else if (a == "--shortcuts") o.shortcuts = true;
        else if (a == "--no-centre") o.centres = false;
        else if (a == "--plot") o.plot = args.value(a);
        else if (a == "--help" || a == "-h") {
            o.help = true;
            return o;
        } else throw UsageError("unknown option '" + a + "'");
    }
    if (o.sizes.empty()) throw UsageError("--sizes needs at least one size");
    if (o.builders.empty()) throw UsageError("--builders needs at least one builder");
    for (int size : o.sizes)
        if (lastReadLevel(size) < 1)
            throw UsageError("--sizes: face " + std::to_string(size) + " has no read level below the base (needs 16 or more)");
    return o;
}

}  // namespace mipgloss::app
