#include "decode.h"

#include "latlong.h"
#include "text.h"
#include "mipgloss/ibl/parallel.h"
#include "mipgloss/ibl/colour.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <Imath/half.h>

#include <algorithm>
#include <optional>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <fstream>
#include <limits>
#include <sstream>

#include <unistd.h>

namespace mipgloss::io_detail {

namespace fs = std::filesystem;

namespace {

const std::vector<float>& srgbTable(int bits) {
    static const std::vector<float> t8 = [] {
        std::vector<float> t(256);
        for (std::size_t i = 0; i < t.size(); ++i) t[i] = static_cast<float>(srgbToLinear(static_cast<double>(i) / 255.0));
        return t;
    }();
    static const std::vector<float> t16 = [] {
        std::vector<float> t(65536);
        for (std::size_t i = 0; i < t.size(); ++i)
            t[i] = static_cast<float>(srgbToLinear(static_cast<double>(i) / 65535.0));
        return t;
    }();
    return bits == 8 ? t8 : t16;
}


// Bytes of memory a decode may take: three quarters of the machine's physical memory. A header
// asking for more is refused before anything is allocated (a truncated or hostile file can claim
// 1e6 × 1e6 pixels in a few bytes).
std::uint64_t decodeBudgetBytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long pageSize = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return std::uint64_t{1} << 34;  // unknown: 16 GiB
    return static_cast<std::uint64_t>(pages) / 4 * 3 * static_cast<std::uint64_t>(pageSize);
}

std::string bytesText(std::uint64_t bytes) {
    std::ostringstream s;
    s.precision(3);
    if (bytes >= (std::uint64_t{1} << 40)) s << static_cast<double>(bytes) / 1099511627776.0 << " TiB";
    else if (bytes >= (std::uint64_t{1} << 30)) s << static_cast<double>(bytes) / 1073741824.0 << " GiB";
    else s << static_cast<double>(bytes) / 1048576.0 << " MiB";
    return s.str();
}

// OpenEXR 3.1 allocates each header attribute at the size the header declares before reading
// it, so a 1 kB file whose attribute claims 2 GB costs 13 s and 1.8 GB before it is refused
// (found by the environment fuzzer, tests/fuzz/regressions). Every attribute's declared size is
// checked against the bytes the file has before OpenImageIO opens it. `read(pos, n, out)` reads
// n bytes at pos and says whether it could; `size` is the file's size. Not an EXR: nothing to do.
void checkExrHeader(const std::function<bool(std::uint64_t, std::size_t, unsigned char*)>& read,
                    std::uint64_t size, const fs::path& name) {
    unsigned char head[8];
    if (size < 8 || !read(0, 8, head) || head[0] != 0x76 || head[1] != 0x2f || head[2] != 0x31 || head[3] != 0x01)
        return;
    const bool multipart = (head[5] & 0x10) != 0;  // version field bit 12
    std::uint64_t at = 8;
    // A NUL-terminated string of at most 255 bytes at `at`; "" when the first byte is NUL.
    auto string = [&](const char* what) {
        std::string out;
        unsigned char c = 0;
        while (true) {
            if (at >= size || !read(at, 1, &c))
                throw EnvError(name, std::string("OpenEXR header ends inside an attribute ") + what +
                                         " (truncated or corrupt file)");
            ++at;
            if (c == 0) return out;
            if (out.size() == 255)
                throw EnvError(name, std::string("OpenEXR header has an attribute ") + what +
                                         " longer than 255 bytes (corrupt file)");
            out.push_back(static_cast<char>(c));
        }
    };
    while (true) {
        std::string attribute = string("name");
        if (attribute.empty()) return;  // the end of the header (of the list of headers: multi-part)
        while (!attribute.empty()) {
            const std::string type = string("type");
            unsigned char b[4];
            if (at + 4 > size || !read(at, 4, b))
                throw EnvError(name, "OpenEXR header ends inside attribute '" + attribute + "' (truncated file)");
            at += 4;
            const std::int64_t declared = static_cast<std::int32_t>(
                static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
                static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24);
            if (declared < 0 || static_cast<std::uint64_t>(declared) > size - at)
                throw EnvError(name, "OpenEXR header attribute '" + attribute + "' (" + type + ") claims " +
                                         std::to_string(declared) + " bytes, but the file has " +
                                         std::to_string(size - at) + " after it (corrupt file)");
            at += static_cast<std::uint64_t>(declared);
            attribute = string("name");
        }
        if (!multipart) return;
    }
}

// Rows decoded per strip: the image is read strip by strip, so the decode holds one copy of the
// image plus a strip of the file's own samples (or, streamed, only strips), and progress (and
// cancelling) runs during the decode. 256 rows is a multiple of every OpenEXR chunk height and
// gives OpenEXR's decompression threads enough chunks per call: an 8192 × 4096 half zip file
// reads in the time of one whole-image read (0.77 s against 0.75 s; 64 rows took 0.84 s). The
// lat-long scatter takes images in the same strips (kLatLongStripRows), so that a streamed file
// and the same image in memory give the same cube.
constexpr int kStripRows = kLatLongStripRows;

// The sanitising rule's quick test, value by value: clean means not NaN, not negative and at most
// kMaxRadiance. Almost every image is clean, so a branch-free pass of add() decides whether the
// exact pass of sanitiseRows is needed at all; it also sums the clean values, the image's energy
// that a warning's percentages are of.
struct CleanScan {
    std::size_t notClean = 0;
    float sum = 0.0f;  // of the clean values seen (a chunk's: 16384 pixels keep float's sum within 1e-3)
    void add(float v) {
        const bool clean = (v >= 0.0f) & (v <= kMaxRadiance);  // false for NaN
        notClean += clean ? 0u : 1u;
        sum += clean ? v : 0.0f;
    }
};

// An opened image read strip by strip: read() takes the file's own samples on the calling thread
// (OpenImageIO and OpenEXR decompress there), convert() makes them linear float RGB and can run
// elsewhere. Float files are read straight into the output pixels (a stride of one Rgb), half
// files as half and widened here (OpenImageIO's own conversion ran on the reading thread), 8-
// and 16-bit files through the exact sRGB table.
class StripReader {
public:
    StripReader(OIIO::ImageInput& in, const fs::path& name) : in_(in), name_(name), spec_(in.spec()) {
        if (spec_.width <= 0 || spec_.height <= 0 || spec_.nchannels <= 0)
            throw EnvError(name, "image has no pixels (" + sizeText(spec_.width, spec_.height) + ")");
        if (spec_.depth > 1) throw EnvError(name, "volume images are not environments");
        nc_ = std::min(spec_.nchannels, 3);
        const std::uint64_t count = static_cast<std::uint64_t>(spec_.width) * static_cast<std::uint64_t>(spec_.height);
        const std::uint64_t needed = count * sizeof(Rgb);
        if (needed > decodeBudgetBytes())
            throw EnvError(name, "is " + sizeText(spec_.width, spec_.height) + " pixels: decoding it needs " +
                                     bytesText(needed) + ", more than this machine can spare (" +
                                     bytesText(decodeBudgetBytes()) + ", three quarters of its memory)");
        const auto base = static_cast<OIIO::TypeDesc::BASETYPE>(spec_.format.basetype);
        kind_ = base == OIIO::TypeDesc::UINT8    ? Kind::Srgb8
                : base == OIIO::TypeDesc::UINT16 ? Kind::Srgb16
                : base == OIIO::TypeDesc::HALF   ? Kind::Half
                                                 : Kind::Float;
        otherInteger_ = base == OIIO::TypeDesc::INT8 || base == OIIO::TypeDesc::INT16 ||
                        base == OIIO::TypeDesc::UINT32 || base == OIIO::TypeDesc::INT32;
        tiled_ = spec_.tile_width > 0;
        // Tiled files are read by rows of tiles, scanline files by strips of kStripRows.
        rowsPerStrip_ = tiled_ ? std::max(1, spec_.tile_height) * std::max(1, kStripRows / std::max(1, spec_.tile_height))
                               : kStripRows;
    }

    int width() const { return spec_.width; }
    int height() const { return spec_.height; }
    int rowsPerStrip() const { return rowsPerStrip_; }

    // The file's samples of rows [y0, y1): into `raw`, or straight into `out` for float files.
    void read(int y0, int y1, std::vector<unsigned char>& raw, Rgb* out) {
        const std::size_t samples = static_cast<std::size_t>(y1 - y0) * static_cast<std::size_t>(spec_.width) *
                                    static_cast<std::size_t>(nc_);
        bool ok = false;
        switch (kind_) {
        case Kind::Srgb8: raw.resize(samples); ok = rows(y0, y1, OIIO::TypeDesc::UINT8, raw.data(), OIIO::AutoStride); break;
        case Kind::Srgb16: raw.resize(samples * 2); ok = rows(y0, y1, OIIO::TypeDesc::UINT16, raw.data(), OIIO::AutoStride); break;
        case Kind::Half: raw.resize(samples * 2); ok = rows(y0, y1, OIIO::TypeDesc::HALF, raw.data(), OIIO::AutoStride); break;
        case Kind::Float: ok = rows(y0, y1, OIIO::TypeDesc::FLOAT, out, sizeof(Rgb)); break;
        }
        if (!ok) {
            std::string err = in_.geterror();
            if (err.empty()) err = "unknown error";
            throw EnvError(name_, "cannot read the pixels (corrupt or truncated file?): " + err);
        }
    }

    // Linear float RGB of `pixels` pixels from what read() left (in `raw` or already in `out`).
    // Where it converts, it also checks the values as they are written (the first pass of
    // sanitiseRows, done while they are in registers and on every core): their sum when all are
    // clean, nothing when some need fixing or the floats were read in place (then the caller runs
    // sanitiseRows).
    std::optional<double> convert(const std::vector<unsigned char>& raw, std::size_t pixels, Rgb* out) const {
        const std::size_t nc = static_cast<std::size_t>(nc_);
        auto each = [&](auto sample) -> std::optional<double> {  // out[i] from the samples sample(k), k = i·nc + c
            const int chunks = static_cast<int>((pixels + kChunk - 1) / kChunk);
            std::vector<CleanScan> scans(static_cast<std::size_t>(chunks));
            parallelFor(0, chunks, [&](int chunk) {
                const std::size_t i0 = static_cast<std::size_t>(chunk) * kChunk, i1 = std::min(pixels, i0 + kChunk);
                CleanScan scan;
                for (std::size_t i = i0; i < i1; ++i) {
                    const std::size_t k = i * nc;
                    const Rgb v = nc >= 3 ? Rgb(sample(k), sample(k + 1), sample(k + 2)) : Rgb(sample(k));
                    out[i] = v;
                    for (int c = 0; c < 3; ++c) scan.add(v[c]);
                }
                scans[static_cast<std::size_t>(chunk)] = scan;
            });
            double sum = 0.0;
            for (const CleanScan& scan : scans) {
                if (scan.notClean != 0) return std::nullopt;
                sum += scan.sum;
            }
            return sum;
        };
        switch (kind_) {
        case Kind::Srgb8: {
            const float* t = srgbTable(8).data();
            return each([&](std::size_t k) { return t[raw[k]]; });
        }
        case Kind::Srgb16: {
            const float* t = srgbTable(16).data();
            const auto* r = reinterpret_cast<const std::uint16_t*>(raw.data());
            return each([&](std::size_t k) { return t[r[k]]; });
        }
        case Kind::Half: {
            const auto* r = reinterpret_cast<const Imath::half*>(raw.data());
            return each([&](std::size_t k) { return static_cast<float>(r[k]); });
        }
        case Kind::Float:
            // Floats are in place; integers other than 8/16 bits are sRGB in [0, 1]; grey replicated.
            if (otherInteger_)
                for (std::size_t i = 0; i < pixels; ++i)
                    for (int c = 0; c < nc_; ++c)
                        out[i][c] = static_cast<float>(srgbToLinear(std::clamp(static_cast<double>(out[i][c]), 0.0, 1.0)));
            if (nc_ < 3)
                for (std::size_t i = 0; i < pixels; ++i) out[i] = Rgb(out[i].x);
            break;
        }
        return std::nullopt;
    }

private:
    enum class Kind { Srgb8, Srgb16, Half, Float };
    static constexpr std::size_t kChunk = 16384;

    bool rows(int y0, int y1, OIIO::TypeDesc type, void* data, OIIO::stride_t xstride) {
        const int yb = spec_.y + y0, ye = spec_.y + y1;
        return tiled_ ? in_.read_tiles(0, 0, spec_.x, spec_.x + spec_.width, yb, ye, spec_.z, spec_.z + 1, 0, nc_, type, data,
                                       xstride)
                      : in_.read_scanlines(0, 0, yb, ye, spec_.z, 0, nc_, type, data, xstride);
    }

    OIIO::ImageInput& in_;
    const fs::path& name_;
    const OIIO::ImageSpec& spec_;
    int nc_ = 3;
    Kind kind_ = Kind::Float;
    bool otherInteger_ = false, tiled_ = false;
    int rowsPerStrip_ = kStripRows;
};

// sanitiseRows for pixels just converted: nothing to do when the conversion found them all clean
// (`cleanSum`, their sum), else the whole rule.
SanitiseCounts sanitiseConverted(std::span<Rgb> px, int width, std::optional<double> cleanSum) {
    if (cleanSum) {
        SanitiseCounts n;
        n.energy = *cleanSum;
        return n;
    }
    return sanitiseRows(px, width);
}

// Reads the first subimage of an opened input; `name` is what error messages call it.
// Each strip is sanitised while it is in cache (sanitiseRows: every rule is row-local).
// With a consumer (chosen from the size), the image is never whole: each strip goes to it in the
// background while the next is read (two strips in flight).
Image readOpened(OIIO::ImageInput& in, const fs::path& name, SanitiseCounts& counts, const Progress& progress,
                 float p0, float p1, const ChooseStrips& choose) {
    StripReader reader(in, name);
    const int width = reader.width(), height = reader.height(), step = reader.rowsPerStrip();
    const std::size_t w = static_cast<std::size_t>(width);
    const StripConsumer consume = choose ? choose(width, height) : StripConsumer{};
    auto report = [&](int y1) {
        reportProgress(progress, "import", p0 + (p1 - p0) * static_cast<float>(y1) / static_cast<float>(height));
    };
    if (consume) {
        const std::size_t stripPixels = static_cast<std::size_t>(std::min(step, height)) * w;
        struct Slot {
            std::vector<unsigned char> raw;
            std::vector<Rgb> px;
        };
        std::array<Slot, 2> slots;
        for (Slot& s : slots) s.px.resize(stripPixels);
        Background background;  // declared after the slots: it is waited for before they go
        for (int y0 = 0, k = 0; y0 < height; y0 += step, ++k) {
            const int y1 = std::min(height, y0 + step);
            Slot& slot = slots[static_cast<std::size_t>(k % 2)];
            reader.read(y0, y1, slot.raw, slot.px.data());
            background.run([&, y0, y1] {
                const std::size_t n = static_cast<std::size_t>(y1 - y0) * w;
                counts += sanitiseConverted({slot.px.data(), n}, width, reader.convert(slot.raw, n, slot.px.data()));
                consume(y0, y1, {slot.px.data(), n});
            });
            report(y1);
        }
        background.wait();
        return {};
    }
    Image img;
    img.width = width;
    img.height = height;
    try {
        img.px.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    } catch (const std::bad_alloc&) {
        throw EnvError(name, "not enough memory to decode " + sizeText(width, height) + " pixels (" +
                                 bytesText(static_cast<std::uint64_t>(img.px.size()) * sizeof(Rgb)) + ")");
    }
    std::vector<unsigned char> raw;
    for (int y0 = 0; y0 < height; y0 += step) {
        const int y1 = std::min(height, y0 + step);
        Rgb* out = img.px.data() + static_cast<std::size_t>(y0) * w;
        const std::size_t n = static_cast<std::size_t>(y1 - y0) * w;
        reader.read(y0, y1, raw, out);
        counts += sanitiseConverted({out, n}, width, reader.convert(raw, n, out));
        report(y1);
    }
    return img;
}

// Colour as stored: alpha is ignored, so it must not be multiplied in.
const OIIO::ImageSpec& readConfig() {
    static const OIIO::ImageSpec config = [] {
        OIIO::ImageSpec c;
        c.attribute("oiio:UnassociatedAlpha", 1);
        return c;
    }();
    return config;
}

// The end every read shares: the input as opened (null: OpenImageIO refused it), decoded,
// sanitised, counted and recorded in the report.
Image readInput(std::unique_ptr<OIIO::ImageInput> in, const fs::path& name, ImportReport& report,
                const Progress& progress, float p0, float p1, const ChooseStrips& choose = {}) {
    if (!in) {
        std::string err = OIIO::geterror();
        if (err.empty()) err = "unknown error";
        throw EnvError(name, "not a readable image: " + err);
    }
    SanitiseCounts counts;
    Image img = readOpened(*in, name, counts, progress, p0, p1, choose);
    in->close();
    addCounts(report, name, counts);
    report.files.push_back(name);
    return img;
}

}  // namespace

namespace {

// How far from a negative value its magnitude is taken (pixels, each side in its row): ringing
// (a DCT block's, a sharpening filter's) lies within a few pixels of what rang.
constexpr int kRepairReach = 16;

// One channel of one row, NaN and values above kMaxRadiance already handled: +Inf, then negatives.
void sanitiseRowChannel(Rgb* row, int width, int c, SanitiseCounts& n) {
    auto at = [&](int x) -> float& { return row[x][c]; };
    // +Inf: a run of them becomes the mean of the finite values bordering it in the row (the
    // least a saturated pixel can have held is what its neighbours hold; the image's largest
    // value, the old rule, added 24 % to one map's energy for four pixels).
    for (int x = 0; x < width;) {
        if (!std::isinf(at(x)) || at(x) < 0.0f) {
            ++x;
            continue;
        }
        int end = x;
        while (end < width && std::isinf(at(end)) && at(end) > 0.0f) ++end;
        double sum = 0.0;
        int count = 0;
        if (x > 0) sum += std::max(at(x - 1), 0.0f), ++count;
        if (end < width && std::isfinite(at(end))) sum += std::max(at(end), 0.0f), ++count;
        const float value = count > 0 ? static_cast<float>(sum / count) : 0.0f;
        for (int k = x; k < end; ++k) {
            at(k) = value;
            ++n.inf;
            n.infAdded += value;
        }
        x = end;
    }
    // Negatives (ringing beside bright pixels, a camera's black level): each becomes 0 and its
    // magnitude is taken from the positive values within kRepairReach pixels of it in the row, in
    // proportion to each (the bright pixel that rang pays nearly all), so the row keeps its
    // energy (clamping alone added 6–13 % to some maps') and nothing beyond the ringing's own
    // neighbourhood changes. The old rule took it from the nearest values outward, half each
    // side: a sun's large negative blue lobes drained a sky's blue along the whole row, a lime
    // band in every render (issue 34). What the neighbourhood cannot give is added, and counted.
    bool any = false;
    for (int x = 0; x < width; ++x) any = any || at(x) < 0.0f;
    if (!any) return;
    std::vector<std::pair<int, double>> debts;
    for (int x = 0; x < width; ++x)
        if (at(x) < 0.0f) {
            ++n.negative;
            debts.emplace_back(x, -static_cast<double>(at(x)));
            at(x) = 0.0f;
        }
    for (const auto& [x, debt] : debts) {
        const int from = std::max(0, x - kRepairReach), to = std::min(width - 1, x + kRepairReach);
        double pool = 0.0;
        for (int k = from; k <= to; ++k) pool += at(k);
        const double paid = std::min(debt, pool);
        if (paid > 0.0) {
            const double keep = 1.0 - paid / pool;  // every positive value keeps this share of itself
            for (int k = from; k <= to; ++k) at(k) = static_cast<float>(at(k) * keep);
        }
        n.negativeMoved += paid;
        n.negativeAdded += debt - paid;
    }
}

}  // namespace

SanitiseCounts& SanitiseCounts::operator+=(const SanitiseCounts& o) {
    nan += o.nan;
    inf += o.inf;
    negative += o.negative;
    huge += o.huge;
    energy += o.energy;
    infAdded += o.infAdded;
    negativeMoved += o.negativeMoved;
    negativeAdded += o.negativeAdded;
    hugeRemoved += o.hugeRemoved;
    return *this;
}

SanitiseCounts sanitiseRows(std::span<Rgb> px, int width) {
    if (width <= 0 || px.size() % static_cast<std::size_t>(width) != 0)
        throw std::invalid_argument("sanitiseRows: " + std::to_string(px.size()) + " pixels are not rows of " +
                                    std::to_string(width));
    // Almost every image is clean: one branch-free pass (CleanScan) finds whether anything needs
    // fixing and the sum; the exact pass below runs only when something does. On an 8k panorama
    // this is 0.03 s instead of 0.25 s.
    SanitiseCounts n;
    {
        const float* f = &px.data()->x;
        const std::size_t count = px.size() * 3;
        constexpr std::size_t kChunk = 16384 * 3;
        std::size_t notClean = 0;
        for (std::size_t i0 = 0; i0 < count; i0 += kChunk) {
            CleanScan scan;
            for (std::size_t i = i0; i < std::min(count, i0 + kChunk); ++i) scan.add(f[i]);
            notClean += scan.notClean;
            n.energy += scan.sum;
        }
        if (notClean == 0) return n;
        n.energy = 0.0;
    }
    const std::size_t w = static_cast<std::size_t>(width);
    for (std::size_t r = 0; r < px.size() / w; ++r) {
        Rgb* row = px.data() + r * w;
        bool special = false;
        for (std::size_t x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                float& v = row[x][c];
                if (std::isnan(v)) {
                    v = 0.0f;
                    ++n.nan;
                } else if (std::isinf(v) || v < 0.0f) {
                    special = true;  // +Inf and negatives (−Inf among them), row by row below
                } else if (v > kMaxRadiance) {
                    n.hugeRemoved += static_cast<double>(v) - kMaxRadiance;
                    v = kMaxRadiance;
                    ++n.huge;
                }
            }
        if (special)
            for (int c = 0; c < 3; ++c) {
                // −Inf is a negative of unknown size: 0, with nothing to take from the neighbours.
                for (std::size_t x = 0; x < w; ++x)
                    if (std::isinf(row[x][c]) && row[x][c] < 0.0f) {
                        row[x][c] = 0.0f;
                        ++n.negative;
                    }
                sanitiseRowChannel(row, width, c, n);
            }
        for (std::size_t x = 0; x < w; ++x) n.energy += static_cast<double>(row[x].x) + row[x].y + row[x].z;
    }
    return n;
}

namespace {

// "1.3 %" of the image's energy (or "<0.01 %").
std::string shareOf(double amount, double energy) {
    const double share = energy > 0.0 ? 100.0 * amount / energy : (amount > 0.0 ? 100.0 : 0.0);
    std::ostringstream out;
    out.precision(2);
    if (share > 0.0 && share < 0.01) out << "<0.01 %";
    else out << std::fixed << share << " %";
    return out.str();
}

}  // namespace

void addCounts(ImportReport& report, const fs::path& file, const SanitiseCounts& n) {
    if (n.nan + n.inf + n.negative + n.huge == 0) return;
    report.nanCount += n.nan;
    report.infCount += n.inf;
    report.negativeCount += n.negative;
    report.hugeCount += n.huge;
    // What each rule did to the energy, as shares of the sanitised image's pixel sum (docs/conventions.md).
    std::vector<std::string> parts;
    if (n.nan > 0) parts.push_back("replaced " + std::to_string(n.nan) + " NaN value(s) by 0 (their energy is unknown)");
    if (n.inf > 0)
        parts.push_back("replaced " + std::to_string(n.inf) + " infinite value(s) by the mean of their row neighbours (adding " +
                        shareOf(n.infAdded, n.energy) + " of the image's energy)");
    if (n.negative > 0) {
        std::string part = "replaced " + std::to_string(n.negative) + " negative value(s) by 0, taking their " +
                           shareOf(n.negativeMoved + n.negativeAdded, n.energy) +
                           " of the image's energy from the positive values within " + std::to_string(kRepairReach) +
                           " pixels of each in its row, in proportion to each";
        if (n.negativeAdded > 0.0) part += " (" + shareOf(n.negativeAdded, n.energy) + " could not be taken and was added)";
        parts.push_back(part);
    }
    if (n.huge > 0) {
        std::ostringstream ceiling;
        ceiling << kMaxRadiance;
        parts.push_back("lowered " + std::to_string(n.huge) + " value(s) above " + ceiling.str() + " to it (removing " +
                        shareOf(n.hugeRemoved, n.energy) + ")");
    }
    std::ostringstream msg;
    msg << file.string() << ": ";
    for (std::size_t i = 0; i < parts.size(); ++i) msg << (i > 0 ? "; " : "") << parts[i];
    report.warnings.push_back(msg.str());
}

Image readImageFile(const fs::path& file, ImportReport& report, const Progress& progress, float p0, float p1) {
    return readImageFile(file, report, progress, p0, p1, {});
}

Image readImageFile(const fs::path& file, ImportReport& report, const Progress& progress, float p0, float p1,
                    const ChooseStrips& choose) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw EnvError(file, kFileNotFound);
    if (fs::is_directory(file, ec)) throw EnvError(file, "is a directory, expected an image file");
    const auto bytes = fs::file_size(file, ec);
    if (ec) throw EnvError(file, "cannot read the file: " + ec.message());
    if (bytes == 0) throw EnvError(file, "file is empty (0 bytes)");
    {
        // The header is read a byte at a time: from the file's first 64 KiB held in memory (a
        // seek per byte on the stream cost 300 seeks and 8 KiB reads, 10–20 ms, on an 8k map),
        // and from the stream beyond them.
        std::ifstream in(file, std::ios::binary);
        std::vector<unsigned char> head(static_cast<std::size_t>(std::min<std::uintmax_t>(bytes, 65536)));
        if (!in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size())))
            throw EnvError(file, "cannot read the file");
        checkExrHeader(
            [&](std::uint64_t pos, std::size_t n, unsigned char* out) {
                if (pos + n <= head.size()) {
                    std::copy_n(head.begin() + static_cast<std::ptrdiff_t>(pos), n, out);
                    return true;
                }
                in.clear();
                in.seekg(static_cast<std::streamoff>(pos));
                return static_cast<bool>(in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n)));
            },
            bytes, file);
    }
    return readInput(OIIO::ImageInput::open(file.string(), &readConfig()), file, report, progress, p0, p1, choose);
}

Image readImageMemory(std::span<const unsigned char> bytes, const std::string& name, ImportReport& report,
                      const Progress& progress, float p0, float p1) {
    if (bytes.empty()) throw EnvError(name, "file is empty (0 bytes)");
    checkExrHeader(
        [&](std::uint64_t pos, std::size_t n, unsigned char* out) {
            if (pos + n > bytes.size()) return false;
            std::copy_n(bytes.begin() + static_cast<std::ptrdiff_t>(pos), n, out);
            return true;
        },
        bytes.size(), name);
    OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(bytes.data()), bytes.size());
    // With a configuration, OpenImageIO 2.4 takes the proxy from it, not from the argument.
    OIIO::ImageSpec config = readConfig();
    void* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    return readInput(OIIO::ImageInput::open(name, &config, &reader), name, report, progress, p0, p1);
}

}  // namespace mipgloss::io_detail
