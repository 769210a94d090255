// `mipgloss render --turntable N --out PATTERN`: the frames' file names, a printf pattern with
// exactly one integer conversion ("frame_%03d.png", "%d.exr", "turn-%4i.png"). The pattern is
// parsed and checked once, then formatted here (never handed to printf, so no user text is ever
// a format string).
#pragma once

#include <string>

namespace mipgloss::app {

struct FramePattern {
    std::string prefix, suffix;  // around the conversion, "%%" already made "%"
    bool leftAlign = false, zeroPad = false, plus = false, space = false;
    int width = 0;
    int precision = -1;  // none

    // The file name of frame `index` (>= 0), as printf would write it.
    std::string format(int index) const {
        std::string digits = std::to_string(index);
        if (precision >= 0 && static_cast<int>(digits.size()) < precision)
            digits.insert(0, static_cast<std::size_t>(precision) - digits.size(), '0');
        if (precision == 0 && index == 0) digits.clear();
        const std::string sign = plus ? "+" : space ? " " : "";
        std::string body = sign + digits;
        const int pad = width - static_cast<int>(body.size());
        if (pad > 0) {
            if (leftAlign) body.append(static_cast<std::size_t>(pad), ' ');
            else if (zeroPad && precision < 0) body.insert(sign.size(), static_cast<std::size_t>(pad), '0');
            else body.insert(0, static_cast<std::size_t>(pad), ' ');
        }
        return prefix + body + suffix;
    }
};

// Reads `pattern` into `out`: "" when it holds exactly one integer conversion (%[flags -0+ ]
// [width][.precision][length hh h l ll j z t]d|i|u, width and precision at most 32) in its file
// name, the folder part holding none; otherwise the reason, for a usage error.
inline std::string parseFramePattern(const std::string& pattern, FramePattern& out) {
    out = FramePattern{};
    const std::size_t slash = pattern.rfind('/');
    int conversions = 0;
    std::string* text = &out.prefix;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            *text += pattern[i];
            continue;
        }
        const std::size_t start = i++;
        if (i < pattern.size() && pattern[i] == '%') {
            *text += '%';
            continue;
        }
        FramePattern spec;
        for (; i < pattern.size(); ++i) {
            const char c = pattern[i];
            if (c == '-') spec.leftAlign = true;
            else if (c == '0') spec.zeroPad = true;
            else if (c == '+') spec.plus = true;
            else if (c == ' ') spec.space = true;
            else break;
        }
        auto number = [&](int& value) {
            const std::size_t from = i;
            value = 0;
            while (i < pattern.size() && pattern[i] >= '0' && pattern[i] <= '9' && i - from < 3)
                value = value * 10 + (pattern[i++] - '0');
            return i > from;
        };
        number(spec.width);
        if (i < pattern.size() && pattern[i] == '.') {
            ++i;
            number(spec.precision);
        }
        while (i < pattern.size() && std::string("hljzt").find(pattern[i]) != std::string::npos) ++i;
        const std::string conversion = pattern.substr(start, i + 1 - start);
        if (i >= pattern.size() || (pattern[i] != 'd' && pattern[i] != 'i' && pattern[i] != 'u'))
            return "'" + conversion + "' is not an integer conversion (%d, %03d, %i, %u; %% for a percent sign)";
        if (spec.width > 32 || spec.precision > 32) return "'" + conversion + "' is wider than 32 characters";
        if (slash != std::string::npos && start < slash)
            return "the frame number '" + conversion + "' must be in the file name, not the folder";
        if (++conversions > 1) return "it holds more than one integer conversion ('" + conversion + "' is the second)";
        spec.prefix = std::move(out.prefix);
        out = std::move(spec);
        text = &out.suffix;
    }
    if (conversions == 0) return "it has no frame number: put one printf integer conversion in it, e.g. frame_%03d.png";
    return {};
}

}  // namespace mipgloss::app
