// Lat-long (equirectangular) image -> cube, filtered (the method is described in latlong.cpp and
// docs/latlong-conversion.md; the orientation convention and the public entry points are
// mipgloss/io/latlong.h). Internal to the io library.
#pragma once

#include "sanitise.h"

#include <memory>
#include <span>

namespace mipgloss::io_detail {

// Converts at face size `faceSize`, reporting progress from p0 to p1. Borders are left for the
// caller's makeSeamless.
CubeMap latLongToCube(const Image& img, int faceSize, const Progress& progress, float p0, float p1);

// Rows per strip in which the scatter takes an image (the decoder's strips: decode.cpp).
inline constexpr int kLatLongStripRows = 256;

// Whether a width × height lat-long converts at face size `faceSize` by the scatter, which can
// take the image strip by strip as it is decoded (LatLongStream); otherwise the whole image is
// needed (the gather: a cube about as fine as the image or finer).
bool latLongStreams(int width, int height, int faceSize);

// The scatter fed strip by strip (latlong_scatter.cpp, "Scatter, strip by strip"): the same
// cube, to the bit, as latLongToCube of the whole image in strips of kLatLongStripRows. Strips
// come in order, each sanitised.
// Throws std::invalid_argument for strips out of order or finish before the last row.
class LatLongStream {
public:
    LatLongStream(int width, int height, int faceSize);
    ~LatLongStream();
    LatLongStream(const LatLongStream&) = delete;
    LatLongStream& operator=(const LatLongStream&) = delete;
    void addStrip(int y0, int y1, std::span<const Rgb> rows);
    // Borders are left for the caller's makeSeamless; reports stage "import" from p0 to p1.
    CubeMap finish(const Progress& progress, float p0, float p1);

    // What took which path, for tests and benchmarks.
    struct Stats {
        int strips = 0, deferred = 0;  // strips taken, and kept whole for the end
        int promoted = 0;              // strips deferred when they came, clamped after a later one
        std::size_t candidates = 0;    // pixels of the other strips above their clamp T_k
        std::size_t corrected = 0;     // of those, the ones whose D = min(L, T) − min(L, T_k) was not 0
        std::size_t excess = 0;        // pixels above T, splatted
    };
    const Stats& stats() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mipgloss::io_detail
