// SPDX-License-Identifier: MIT
// An 8-bit RGB image and PNG output (stb_image_write).
#pragma once

#include "pluecker/geometry.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace pluecker {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  // row-major, top row first, 3 bytes a pixel

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}
    // Stores a linear colour, clamped to [0,1] and encoded with the sRGB curve.
    void set(int x, int y, const Vec3& linear);
    bool operator==(const Image&) const = default;
};

// sRGB encoding of one linear channel, clamped, rounded to nearest.
std::uint8_t encode_srgb8(float linear);

// Throws InputError naming the path when the file cannot be written.
void write_png(const Image& img, const std::string& path);

}  // namespace pluecker
