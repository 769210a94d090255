// What every `mipgloss` subcommand shares: its arguments, one at a time, and the usage error that
// main() turns into exit status 2 (any other exception is status 1, its message naming the file);
// one wording for a flag that takes one of a few names (parseChoice).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
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
    explicit Args(std::vector<std::string> items) : items_(std::move(items)) {}
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

// "a", "a or b", "a, b or c": the names a choice flag takes, as its usage error lists them.
inline std::string choiceList(const std::vector<std::string>& names) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
        list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return list;
}

// The value of a flag that takes one of a few names (--builder phong, --tonemap aces, ...): the
// enumerator named `value`, or a UsageError "FLAG is a, b or c, got 'VALUE'".
template <class Enum>
Enum parseChoice(const std::string& flag, const std::string& value,
                 const std::vector<std::pair<std::string, Enum>>& choices) {
    std::vector<std::string> names;
    for (const auto& [name, e] : choices) {
        if (name == value) return e;
        names.push_back(name);
    }
    throw UsageError(flag + " is " + choiceList(names) + ", got '" + value + "'");
}

// The same for enumerators named by the enum's own name function (builderName, toneMapName, ...),
// so the names a flag takes are those the files and messages use.
template <class Enum, class NameOf>
Enum parseChoice(const std::string& flag, const std::string& value, const std::vector<Enum>& all, NameOf nameOf) {
    std::vector<std::pair<std::string, Enum>> choices;
    for (const Enum e : all) choices.emplace_back(nameOf(e), e);
    return parseChoice(flag, value, choices);
}

}  // namespace mipgloss::app
