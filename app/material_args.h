// The command-line values every subcommand reads the same way: numbers with limits, and a
// material's parameters (`render --lambda`, `library add --lambda`): one meaning of λ and of the
// Phong exponent (phong.h), one set of limits, usage errors naming the flag.
#pragma once

#include "cli_args.h"

#include "mipgloss/scene/scene.h"

#include <string>

namespace mipgloss::app {

// A finite number in [lo, hi]; UsageError naming `flag` otherwise.
float parseFloat(const std::string& flag, const std::string& value, float lo, float hi);
// --lambda L: λ in [0, kMaxLambda].
float parseLambda(const std::string& flag, const std::string& value);
// --exponent N: the λ of Phong exponent N >= 0; "mirror" or "inf" is the mirror, λ 0.
float parseExponentAsLambda(const std::string& flag, const std::string& value);
// --mode reflect|normal.
LookupMode parseMode(const std::string& flag, const std::string& value);
// --tint R,G,B: three finite numbers >= 0, linear RGB.
Rgb parseTint(const std::string& flag, const std::string& value);

}  // namespace mipgloss::app
