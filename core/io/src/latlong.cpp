#include "latlong.h"

#include "latlong_internal.h"
#include "mipgloss/io/latlong.h"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

namespace mipgloss {

using namespace latlong_detail;

namespace {

// ---------------------------------------------------------------------------------------------
// Lat-long -> cube at the cost of about one pass (docs/latlong-conversion.md).
//
// A texel is the solid-angle weighted mean of the bilinearly interpolated image over its
// footprint. Two quadratures compute it, and the one that costs less for the two sizes is used
// (gathers()):
//  - Scatter (the image has more pixels than the cube has texels, up to about as many): every
//    pixel is cut into ku × kv strata, spaced at most half the narrowest texel (a corner texel,
//    (2/N)/3 rad) as before, and each stratum, interpolated at its centre, is added with its exact
//    solid angle Δφ·(cos θ0 − cos θ1) to the texel that holds its direction. One pass over the
//    image in row order; ku = kv = 1 once pixels are under half the narrowest texel.
//  - Gather (the cube is finer than the image): a texel is the mean of an Sx × Sy grid of
//    bilinear reads on its face plane, each weighted by the solid-angle density
//    dΩ/(dx dy) = (1 + x² + y²)^(−3/2) at its point, the grid spaced at most half a pixel in u
//    and in v and never coarser than 2 × 2.
// Bright pixels (suns) are split off first and their excess added with exact bookkeeping
// (splitBright, splatExcess).
//
// Determinism: every parallel loop runs over a fixed partition (row blocks, bands, face rows)
// that does not depend on the thread count, and partial sums are combined in a fixed order.
// Scatter and splat write straight into the cube: the image is cut into bands of rows, each
// spanning more θ than any texel, so a texel meets at most two neighbouring bands; the even
// bands run in parallel, then the odd ones, and every texel's sum is made in the same order.

// A gather read costs about this many scatter strata: 41–49 ns against 6–7 ns of CPU time,
// measured on city.exr at N = 64, 256 and 512 on the 2-core development machine
// (docs/latlong-conversion.md).
constexpr double kReadCostInStrata = 7.0;

// Gather when its reads cost less than the scatter's strata (kReadCostInStrata). Both are
// well within the previous conversion's error against the exact texel means
// (docs/latlong-conversion.md); gather is the more accurate of the two where both apply.
bool gathers(int width, int height, int n) {
    const Strata st = strataFor(width, height, n);
    const double strata = static_cast<double>(width) * st.ku * static_cast<double>(height) * st.kv;
    return kReadCostInStrata * gatherReads(width, height, n) < strata;
}

void checkSizes(int width, int height, std::size_t pixels, int faceSize) {
    if (width < 1 || height < 1 || faceSize < 1 || pixels != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw std::invalid_argument("latLongToCube: " + std::to_string(width) + " × " + std::to_string(height) +
                                    " image with " + std::to_string(pixels) + " pixels, face size " +
                                    std::to_string(faceSize));
}

CubeMap convert(const LatLongView& img, int faceSize, const ProgressSpan& progress) {
    checkSizes(img.width, img.height, img.pixels.size(), faceSize);
    if (!gathers(img.width, img.height, faceSize)) {
        // The scatter takes the image in the decoder's strips, so that a decoded file and an image
        // in memory give the same cube to the bit.
        ScatterStream stream(img.width, img.height, faceSize);
        const std::size_t w = static_cast<std::size_t>(img.width);
        for (int y0 = 0; y0 < img.height; y0 += io_detail::kLatLongStripRows) {
            const int y1 = std::min(img.height, y0 + io_detail::kLatLongStripRows);
            stream.addStrip(y0, y1, img.pixels.subspan(static_cast<std::size_t>(y0) * w, static_cast<std::size_t>(y1 - y0) * w));
            progress.report(0.5 * y1 / img.height);
        }
        return stream.finish(progress.sub(0.5, 1.0));
    }
    const BrightSplit split = splitBright(img);
    progress.report(0.05);
    const Source src(img, split.limit);
    CubeMap cube(faceSize);
    gather(src, cube, progress.sub(0.05, 0.9));
    splatExcess(split.excess, img.width, img.height, cube, progress.sub(0.9, 1.0));
    return cube;
}

}  // namespace

LatLongMethod latLongMethod(int width, int height, int faceSize) {
    return gathers(width, height, faceSize) ? LatLongMethod::Gather : LatLongMethod::Scatter;
}

CubeMap latLongToCube(const LatLongView& image, int faceSize, const Progress& progress) {
    CubeMap cube = convert(image, faceSize, {progress, 0.0f, 1.0f});
    cube.makeSeamless();
    return cube;
}

namespace io_detail {

CubeMap latLongToCube(const Image& img, int faceSize, const Progress& progress, float p0, float p1) {
    return convert({img.width, img.height, img.px}, faceSize, {progress, p0, p1});
}

bool latLongStreams(int width, int height, int faceSize) {
    return width >= 1 && height >= 1 && faceSize >= 1 && !gathers(width, height, faceSize);
}

struct LatLongStream::Impl {
    ScatterStream stream;
};

LatLongStream::LatLongStream(int width, int height, int faceSize) {
    checkSizes(width, height, static_cast<std::size_t>(width) * static_cast<std::size_t>(height), faceSize);
    impl_ = std::make_unique<Impl>(Impl{ScatterStream(width, height, faceSize)});
}
LatLongStream::~LatLongStream() = default;

void LatLongStream::addStrip(int y0, int y1, std::span<const Rgb> rows) {
    impl_->stream.addStrip(y0, y1, rows);
}

CubeMap LatLongStream::finish(const Progress& progress, float p0, float p1) {
    return impl_->stream.finish({progress, p0, p1});
}

const LatLongStream::Stats& LatLongStream::stats() const { return impl_->stream.stats(); }

}  // namespace io_detail

}  // namespace mipgloss
