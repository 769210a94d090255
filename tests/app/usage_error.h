// The message of the UsageError a parser throws: what the parsers' tests compare word for word.
#pragma once

#include "cli_args.h"

#include <string>

namespace mipgloss::app {

// The message of the UsageError `f` throws; "" when it throws none.
template <class F>
std::string usageError(F f) {
    try {
        f();
    } catch (const UsageError& e) {
        return e.what();
    }
    return "";
}

}  // namespace mipgloss::app
