// What every `mipgloss` subcommand shares: its arguments, one at a time, and the usage error that
// main() turns into exit status 2 (any other exception is status 1, its message naming the file).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace mipgloss::app {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Args {
public:
    Args(int argc, char** argv, int first) {
        for (int i = first; i < argc; ++i) items_.emplace_back(argv[i]);
    }
    bool empty() const { return pos_ >= items_.size(); }
    std::string next() { return items_[pos_++]; }
    std::string value(const std::string& flag) {
        if (empty()) throw UsageError(flag + " needs a value");
        return next();
    }

private:
    std::vector<std::string> items_;
    std::size_t pos_ = 0;
};

}  // namespace mipgloss::app
