// `mipgloss bench --plot`: error against build time, one marker per (builder, face size,
// environment), drawn with QPainter into an SVG (QSvgGenerator) and a PNG beside it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace mipgloss::app {

struct BenchPlotPoint {
    std::string builder;      // series: one colour and marker shape per builder
    std::string env;          // environment name, in the label
    int size = 0;             // base face size, in the label
    double seconds = 0.0;     // x: chain build time (median), log scale
    double worstRead = 0.0;   // y: worst between-centres read error over read levels (fraction), log scale
};

// Writes `svg` and the same picture as PNG beside it (same stem, .png); returns the PNG's path.
// Throws std::runtime_error when a file cannot be written. Built only with Qt Gui and Svg
// (MIPGLOSS_WITH_PLOT); without them `bench --plot` is refused.
std::filesystem::path writeBenchPlot(const std::vector<BenchPlotPoint>& points, const std::filesystem::path& svg,
                                     const std::string& title, const std::string& subtitle);

}  // namespace mipgloss::app
