// Where the faces sit in the single-image layouts (crosses and strips) and how a square block of an
// image becomes a face. Internal to the io library. The layouts' pictures are in import.h's
// EnvLayout and cubemap.h's cross.
#pragma once

#include "decode.h"

#include <filesystem>

namespace mipgloss::io_detail {

// How a square block of an image becomes a face: face texel (x, y) reads image texel T(x, y).
enum class Place {
    AsIs,           // (x, y)
    Mirror,         // (n-1-x, y): left-right
    Rotate180,      // (n-1-x, n-1-y)
    Transpose,      // (y, x)
    AntiTranspose,  // (n-1-y, n-1-x)
};

// Copies the n×n block of `img` at (x0, y0) into face f, placed as `place` says.
void copyFace(const Image& img, int x0, int y0, int n, CubeMap& cube, Face f, Place place);

// The layout whose proportions a width × height image has (within 2 %). Throws EnvError naming `file`.
EnvLayout detectLayout(int width, int height, const std::filesystem::path& file);

// A cross or strip -> cube (not lat-long). Throws EnvError when the size does not fit the layout.
CubeMap cubeFromLayout(const Image& img, EnvLayout layout, const std::filesystem::path& file);

}  // namespace mipgloss::io_detail
