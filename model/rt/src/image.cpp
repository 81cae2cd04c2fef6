// SPDX-License-Identifier: MIT
#include "pluecker/image.hpp"

#include <algorithm>
#include <cmath>

// stb's own code trips -Wextra; its warnings are not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace pluecker {

std::uint8_t encode_srgb8(float linear) {
    const float c = std::clamp(std::isnan(linear) ? 0.0f : linear, 0.0f, 1.0f);
    const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(std::clamp(s, 0.0f, 1.0f) * 255.0f));
}

void Image::set(int x, int y, const Vec3& linear) {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    rgb[i] = encode_srgb8(linear.x);
    rgb[i + 1] = encode_srgb8(linear.y);
    rgb[i + 2] = encode_srgb8(linear.z);
}

void write_png(const Image& img, const std::string& path) {
    if (img.width <= 0 || img.height <= 0) throw InputError(path + ": cannot write an empty image");
    if (!stbi_write_png(path.c_str(), img.width, img.height, 3, img.rgb.data(), img.width * 3))
        throw InputError(path + ": cannot write PNG");
}

}  // namespace pluecker
