// What the mesh file readers share (formats/mesh_formats.h, formats/reading.h).
#include "formats/mesh_formats.h"
#include "formats/reading.h"

#include <algorithm>
#include <utility>

namespace mipgloss::meshfile {

std::vector<std::uint32_t> distinctInOrder(std::span<const std::uint32_t> values) {
    // (value, position) sorted: the first of each run is that value's first appearance.
    std::vector<std::pair<std::uint32_t, std::size_t>> sorted(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) sorted[i] = {values[i], i};
    std::sort(sorted.begin(), sorted.end());
    std::vector<std::size_t> firsts;
    for (std::size_t i = 0; i < sorted.size(); ++i)
        if (i == 0 || sorted[i].first != sorted[i - 1].first) firsts.push_back(sorted[i].second);
    std::sort(firsts.begin(), firsts.end());
    std::vector<std::uint32_t> out;
    out.reserve(firsts.size());
    for (std::size_t i : firsts) out.push_back(values[i]);
    return out;
}

std::string faces(std::size_t n) { return count(n, "face", "faces"); }
std::string vertices(std::size_t n) { return count(n, "vertex", "vertices"); }
std::string atLine(std::size_t line) { return "line " + std::to_string(line) + ": "; }

}  // namespace mipgloss::meshfile
