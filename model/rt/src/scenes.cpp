// SPDX-License-Identifier: MIT
// Built-in scenes: Newell's teapot, the 'Spheres' scene and UV spheres of any
// size, plus make_scene(), the one entry point that also loads files.
#include "pluecker/mesh.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

namespace pluecker {

namespace {

// ---------------------------------------------------------------------------
// The Utah teapot. Control points and patches are Martin Newell's 1975 data
// set (University of Utah), as published by Frank Crow, "The Origins of the
// Teapot", IEEE CG&A 7(1), 1987, and Jim Blinn's distribution; public domain.
// 306 control points (x, y, z; z up), 32 bicubic Bezier patches of 16 one-based
// indices: rim 4, body 8, handle 4, spout 4, lid 8, bottom 4.
constexpr float kTeapotPoints[306][3] = {
    {1.4f, 0.0f, 2.4f}, {1.4f, -0.784f, 2.4f}, {0.784f, -1.4f, 2.4f}, {0.0f, -1.4f, 2.4f},
    {1.3375f, 0.0f, 2.53125f}, {1.3375f, -0.749f, 2.53125f}, {0.749f, -1.3375f, 2.53125f}, {0.0f, -1.3375f, 2.53125f},
    {1.4375f, 0.0f, 2.53125f}, {1.4375f, -0.805f, 2.53125f}, {0.805f, -1.4375f, 2.53125f}, {0.0f, -1.4375f, 2.53125f},
    {1.5f, 0.0f, 2.4f}, {1.5f, -0.84f, 2.4f}, {0.84f, -1.5f, 2.4f}, {0.0f, -1.5f, 2.4f},
    {-0.784f, -1.4f, 2.4f}, {-1.4f, -0.784f, 2.4f}, {-1.4f, 0.0f, 2.4f}, {-0.749f, -1.3375f, 2.53125f},  // 17-20
    {-1.3375f, -0.749f, 2.53125f}, {-1.3375f, 0.0f, 2.53125f}, {-0.805f, -1.4375f, 2.53125f}, {-1.4375f, -0.805f, 2.53125f},
    {-1.4375f, 0.0f, 2.53125f}, {-0.84f, -1.5f, 2.4f}, {-1.5f, -0.84f, 2.4f}, {-1.5f, 0.0f, 2.4f},
    {-1.4f, 0.784f, 2.4f}, {-0.784f, 1.4f, 2.4f}, {0.0f, 1.4f, 2.4f}, {-1.3375f, 0.749f, 2.53125f},  // 29-32
    {-0.749f, 1.3375f, 2.53125f}, {0.0f, 1.3375f, 2.53125f}, {-1.4375f, 0.805f, 2.53125f}, {-0.805f, 1.4375f, 2.53125f},
    {0.0f, 1.4375f, 2.53125f}, {-1.5f, 0.84f, 2.4f}, {-0.84f, 1.5f, 2.4f}, {0.0f, 1.5f, 2.4f},
    {0.784f, 1.4f, 2.4f}, {1.4f, 0.784f, 2.4f}, {0.749f, 1.3375f, 2.53125f}, {1.3375f, 0.749f, 2.53125f},  // 41-44
    {0.805f, 1.4375f, 2.53125f}, {1.4375f, 0.805f, 2.53125f}, {0.84f, 1.5f, 2.4f}, {1.5f, 0.84f, 2.4f},
    {1.75f, 0.0f, 1.875f}, {1.75f, -0.98f, 1.875f}, {0.98f, -1.75f, 1.875f}, {0.0f, -1.75f, 1.875f},  // 49-52
    {2.0f, 0.0f, 1.35f}, {2.0f, -1.12f, 1.35f}, {1.12f, -2.0f, 1.35f}, {0.0f, -2.0f, 1.35f},
    {2.0f, 0.0f, 0.9f}, {2.0f, -1.12f, 0.9f}, {1.12f, -2.0f, 0.9f}, {0.0f, -2.0f, 0.9f},
    {-0.98f, -1.75f, 1.875f}, {-1.75f, -0.98f, 1.875f}, {-1.75f, 0.0f, 1.875f}, {-1.12f, -2.0f, 1.35f},  // 61-64
    {-2.0f, -1.12f, 1.35f}, {-2.0f, 0.0f, 1.35f}, {-1.12f, -2.0f, 0.9f}, {-2.0f, -1.12f, 0.9f},
    {-2.0f, 0.0f, 0.9f}, {-1.75f, 0.98f, 1.875f}, {-0.98f, 1.75f, 1.875f}, {0.0f, 1.75f, 1.875f},
    {-2.0f, 1.12f, 1.35f}, {-1.12f, 2.0f, 1.35f}, {0.0f, 2.0f, 1.35f}, {-2.0f, 1.12f, 0.9f},  // 73-76
    {-1.12f, 2.0f, 0.9f}, {0.0f, 2.0f, 0.9f}, {0.98f, 1.75f, 1.875f}, {1.75f, 0.98f, 1.875f},
    {1.12f, 2.0f, 1.35f}, {2.0f, 1.12f, 1.35f}, {1.12f, 2.0f, 0.9f}, {2.0f, 1.12f, 0.9f},
    {2.0f, 0.0f, 0.45f}, {2.0f, -1.12f, 0.45f}, {1.12f, -2.0f, 0.45f}, {0.0f, -2.0f, 0.45f},  // 85-88
    {1.5f, 0.0f, 0.225f}, {1.5f, -0.84f, 0.225f}, {0.84f, -1.5f, 0.225f}, {0.0f, -1.5f, 0.225f},
    {1.5f, 0.0f, 0.15f}, {1.5f, -0.84f, 0.15f}, {0.84f, -1.5f, 0.15f}, {0.0f, -1.5f, 0.15f},
    {-1.12f, -2.0f, 0.45f}, {-2.0f, -1.12f, 0.45f}, {-2.0f, 0.0f, 0.45f}, {-0.84f, -1.5f, 0.225f},  // 97-100
    {-1.5f, -0.84f, 0.225f}, {-1.5f, 0.0f, 0.225f}, {-0.84f, -1.5f, 0.15f}, {-1.5f, -0.84f, 0.15f},
    {-1.5f, 0.0f, 0.15f}, {-2.0f, 1.12f, 0.45f}, {-1.12f, 2.0f, 0.45f}, {0.0f, 2.0f, 0.45f},
    {-1.5f, 0.84f, 0.225f}, {-0.84f, 1.5f, 0.225f}, {0.0f, 1.5f, 0.225f}, {-1.5f, 0.84f, 0.15f},  // 109-112
    {-0.84f, 1.5f, 0.15f}, {0.0f, 1.5f, 0.15f}, {1.12f, 2.0f, 0.45f}, {2.0f, 1.12f, 0.45f},
    {0.84f, 1.5f, 0.225f}, {1.5f, 0.84f, 0.225f}, {0.84f, 1.5f, 0.15f}, {1.5f, 0.84f, 0.15f},
    {-1.6f, 0.0f, 2.025f}, {-1.6f, -0.3f, 2.025f}, {-1.5f, -0.3f, 2.25f}, {-1.5f, 0.0f, 2.25f},  // 121-124
    {-2.3f, 0.0f, 2.025f}, {-2.3f, -0.3f, 2.025f}, {-2.5f, -0.3f, 2.25f}, {-2.5f, 0.0f, 2.25f},
    {-2.7f, 0.0f, 2.025f}, {-2.7f, -0.3f, 2.025f}, {-3.0f, -0.3f, 2.25f}, {-3.0f, 0.0f, 2.25f},
    {-2.7f, 0.0f, 1.8f}, {-2.7f, -0.3f, 1.8f}, {-3.0f, -0.3f, 1.8f}, {-3.0f, 0.0f, 1.8f},  // 133-136
    {-1.5f, 0.3f, 2.25f}, {-1.6f, 0.3f, 2.025f}, {-2.5f, 0.3f, 2.25f}, {-2.3f, 0.3f, 2.025f},
    {-3.0f, 0.3f, 2.25f}, {-2.7f, 0.3f, 2.025f}, {-3.0f, 0.3f, 1.8f}, {-2.7f, 0.3f, 1.8f},
    {-2.7f, 0.0f, 1.575f}, {-2.7f, -0.3f, 1.575f}, {-3.0f, -0.3f, 1.35f}, {-3.0f, 0.0f, 1.35f},  // 145-148
    {-2.5f, 0.0f, 1.125f}, {-2.5f, -0.3f, 1.125f}, {-2.65f, -0.3f, 0.9375f}, {-2.65f, 0.0f, 0.9375f},
    {-2.0f, -0.3f, 0.9f}, {-1.9f, -0.3f, 0.6f}, {-1.9f, 0.0f, 0.6f}, {-3.0f, 0.3f, 1.35f},
    {-2.7f, 0.3f, 1.575f}, {-2.65f, 0.3f, 0.9375f}, {-2.5f, 0.3f, 1.125f}, {-1.9f, 0.3f, 0.6f},  // 157-160
    {-2.0f, 0.3f, 0.9f}, {1.7f, 0.0f, 1.425f}, {1.7f, -0.66f, 1.425f}, {1.7f, -0.66f, 0.6f},
    {1.7f, 0.0f, 0.6f}, {2.6f, 0.0f, 1.425f}, {2.6f, -0.66f, 1.425f}, {3.1f, -0.66f, 0.825f},
    {3.1f, 0.0f, 0.825f}, {2.3f, 0.0f, 2.1f}, {2.3f, -0.25f, 2.1f}, {2.4f, -0.25f, 2.025f},  // 169-172
    {2.4f, 0.0f, 2.025f}, {2.7f, 0.0f, 2.4f}, {2.7f, -0.25f, 2.4f}, {3.3f, -0.25f, 2.4f},
    {3.3f, 0.0f, 2.4f}, {1.7f, 0.66f, 0.6f}, {1.7f, 0.66f, 1.425f}, {3.1f, 0.66f, 0.825f},
    {2.6f, 0.66f, 1.425f}, {2.4f, 0.25f, 2.025f}, {2.3f, 0.25f, 2.1f}, {3.3f, 0.25f, 2.4f},  // 181-184
    {2.7f, 0.25f, 2.4f}, {2.8f, 0.0f, 2.475f}, {2.8f, -0.25f, 2.475f}, {3.525f, -0.25f, 2.49375f},
    {3.525f, 0.0f, 2.49375f}, {2.9f, 0.0f, 2.475f}, {2.9f, -0.15f, 2.475f}, {3.45f, -0.15f, 2.5125f},
    {3.45f, 0.0f, 2.5125f}, {2.8f, 0.0f, 2.4f}, {2.8f, -0.15f, 2.4f}, {3.2f, -0.15f, 2.4f},  // 193-196
    {3.2f, 0.0f, 2.4f}, {3.525f, 0.25f, 2.49375f}, {2.8f, 0.25f, 2.475f}, {3.45f, 0.15f, 2.5125f},
    {2.9f, 0.15f, 2.475f}, {3.2f, 0.15f, 2.4f}, {2.8f, 0.15f, 2.4f}, {0.0f, 0.0f, 3.15f},
    {0.0f, -0.002f, 3.15f}, {0.002f, 0.0f, 3.15f}, {0.8f, 0.0f, 3.15f}, {0.8f, -0.45f, 3.15f},  // 205-208
    {0.45f, -0.8f, 3.15f}, {0.0f, -0.8f, 3.15f}, {0.0f, 0.0f, 2.85f}, {0.2f, 0.0f, 2.7f},
    {0.2f, -0.112f, 2.7f}, {0.112f, -0.2f, 2.7f}, {0.0f, -0.2f, 2.7f}, {-0.002f, 0.0f, 3.15f},
    {-0.45f, -0.8f, 3.15f}, {-0.8f, -0.45f, 3.15f}, {-0.8f, 0.0f, 3.15f}, {-0.112f, -0.2f, 2.7f},  // 217-220
    {-0.2f, -0.112f, 2.7f}, {-0.2f, 0.0f, 2.7f}, {0.0f, 0.002f, 3.15f}, {-0.8f, 0.45f, 3.15f},
    {-0.45f, 0.8f, 3.15f}, {0.0f, 0.8f, 3.15f}, {-0.2f, 0.112f, 2.7f}, {-0.112f, 0.2f, 2.7f},
    {0.0f, 0.2f, 2.7f}, {0.45f, 0.8f, 3.15f}, {0.8f, 0.45f, 3.15f}, {0.112f, 0.2f, 2.7f},  // 229-232
    {0.2f, 0.112f, 2.7f}, {0.4f, 0.0f, 2.55f}, {0.4f, -0.224f, 2.55f}, {0.224f, -0.4f, 2.55f},
    {0.0f, -0.4f, 2.55f}, {1.3f, 0.0f, 2.55f}, {1.3f, -0.728f, 2.55f}, {0.728f, -1.3f, 2.55f},
    {0.0f, -1.3f, 2.55f}, {1.3f, 0.0f, 2.4f}, {1.3f, -0.728f, 2.4f}, {0.728f, -1.3f, 2.4f},  // 241-244
    {0.0f, -1.3f, 2.4f}, {-0.224f, -0.4f, 2.55f}, {-0.4f, -0.224f, 2.55f}, {-0.4f, 0.0f, 2.55f},
    {-0.728f, -1.3f, 2.55f}, {-1.3f, -0.728f, 2.55f}, {-1.3f, 0.0f, 2.55f}, {-0.728f, -1.3f, 2.4f},
    {-1.3f, -0.728f, 2.4f}, {-1.3f, 0.0f, 2.4f}, {-0.4f, 0.224f, 2.55f}, {-0.224f, 0.4f, 2.55f},  // 253-256
    {0.0f, 0.4f, 2.55f}, {-1.3f, 0.728f, 2.55f}, {-0.728f, 1.3f, 2.55f}, {0.0f, 1.3f, 2.55f},
    {-1.3f, 0.728f, 2.4f}, {-0.728f, 1.3f, 2.4f}, {0.0f, 1.3f, 2.4f}, {0.224f, 0.4f, 2.55f},
    {0.4f, 0.224f, 2.55f}, {0.728f, 1.3f, 2.55f}, {1.3f, 0.728f, 2.55f}, {0.728f, 1.3f, 2.4f},  // 265-268
    {1.3f, 0.728f, 2.4f}, {0.0f, 0.0f, 0.0f}, {1.5f, 0.0f, 0.15f}, {1.5f, 0.84f, 0.15f},
    {0.84f, 1.5f, 0.15f}, {0.0f, 1.5f, 0.15f}, {1.5f, 0.0f, 0.075f}, {1.5f, 0.84f, 0.075f},
    {0.84f, 1.5f, 0.075f}, {0.0f, 1.5f, 0.075f}, {1.425f, 0.0f, 0.0f}, {1.425f, 0.798f, 0.0f},  // 277-280
    {0.798f, 1.425f, 0.0f}, {0.0f, 1.425f, 0.0f}, {-0.84f, 1.5f, 0.15f}, {-1.5f, 0.84f, 0.15f},
    {-1.5f, 0.0f, 0.15f}, {-0.84f, 1.5f, 0.075f}, {-1.5f, 0.84f, 0.075f}, {-1.5f, 0.0f, 0.075f},
    {-0.798f, 1.425f, 0.0f}, {-1.425f, 0.798f, 0.0f}, {-1.425f, 0.0f, 0.0f}, {-1.5f, -0.84f, 0.15f},  // 289-292
    {-0.84f, -1.5f, 0.15f}, {0.0f, -1.5f, 0.15f}, {-1.5f, -0.84f, 0.075f}, {-0.84f, -1.5f, 0.075f},
    {0.0f, -1.5f, 0.075f}, {-1.425f, -0.798f, 0.0f}, {-0.798f, -1.425f, 0.0f}, {0.0f, -1.425f, 0.0f},
    {0.84f, -1.5f, 0.15f}, {1.5f, -0.84f, 0.15f}, {0.84f, -1.5f, 0.075f}, {1.5f, -0.84f, 0.075f},  // 301-304
    {0.798f, -1.425f, 0.0f}, {1.425f, -0.798f, 0.0f},
};

constexpr std::uint16_t kTeapotPatches[32][16] = {
    // rim
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    // body
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    // handle
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69},
    // spout
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194},
    // lid
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212},
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242},
    // bottom
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271},
};

using DVec = std::array<double, 3>;

// Newell's data is z-up; the scenes here are y-up (as the shared teapot.obj):
// (x, y, z) -> (x, z, -y).
DVec teapot_point(int one_based) {
    const float* p = kTeapotPoints[one_based - 1];
    return {p[0], p[2], -double(p[1])};
}

// Cubic Bernstein weights at s = k/t, written so that k and t - k give the
// same weights in reverse order bit for bit (r = (t-k)/t, not 1 - s).
std::array<double, 4> bernstein(int k, int t) {
    const double s = double(k) / t, r = double(t - k) / t;
    return {r * (r * r), 3.0 * (s * (r * r)), 3.0 * (r * (s * s)), s * (s * s)};
}

// Symmetric sum: reversing both weights and points gives the same bits, so
// patches that share an edge (in either direction) produce the same points.
DVec cubic(const std::array<double, 4>& w, const DVec (&p)[4]) {
    DVec out;
    for (int a = 0; a < 3; ++a) out[a] = (w[0] * p[0][a] + w[3] * p[3][a]) + (w[1] * p[1][a] + w[2] * p[2][a]);
    return out;
}

// Welds points by exact float position (-0 folded into +0).
struct Welder {
    Mesh& m;
    std::map<std::tuple<float, float, float>, std::uint32_t> ids;
    std::uint32_t id(const DVec& p) {
        const Vec3 v(static_cast<float>(p[0]) + 0.0f, static_cast<float>(p[1]) + 0.0f,
                     static_cast<float>(p[2]) + 0.0f);
        auto [it, added] = ids.try_emplace({v.x, v.y, v.z}, std::uint32_t(m.vertices.size()));
        if (added) m.vertices.push_back(v);
        return it->second;
    }
};

void add_triangle(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint16_t mat) {
    m.triangles.push_back({a, b, c});
    m.tri_material.push_back(mat);
}

// One patch: (t+1)^2 grid points, row index v, column index u. A patch edge
// whose four control points are one point is collapsed onto it exactly, so
// the triangles at the lid and bottom poles weld into degenerate ones, which
// are dropped.
void tessellate_patch(const std::uint16_t (&idx)[16], int t, Welder& w) {
    DVec cp[4][4];
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) cp[r][c] = teapot_point(idx[4 * r + c]);
    auto same = [&](int i0, int step) {
        for (int k = 1; k < 4; ++k)
            if (idx[i0 + k * step] != idx[i0]) return false;
        return true;
    };
    const bool v0 = same(0, 1), v1 = same(12, 1), u0 = same(0, 4), u1 = same(3, 4);

    std::vector<std::uint32_t> grid(std::size_t(t + 1) * std::size_t(t + 1));
    for (int j = 0; j <= t; ++j) {
        const auto bv = bernstein(j, t);
        DVec col[4];
        for (int c = 0; c < 4; ++c) {
            const DVec pc[4] = {cp[0][c], cp[1][c], cp[2][c], cp[3][c]};
            col[c] = cubic(bv, pc);
        }
        for (int i = 0; i <= t; ++i) {
            DVec p = cubic(bernstein(i, t), col);
            if (j == 0 && v0) p = cp[0][0];
            if (j == t && v1) p = cp[3][0];
            if (i == 0 && u0) p = cp[0][0];
            if (i == t && u1) p = cp[0][3];
            grid[std::size_t(j) * (t + 1) + i] = w.id(p);
        }
    }
    for (int j = 0; j < t; ++j)
        for (int i = 0; i < t; ++i) {
            const auto at = [&](int ii, int jj) { return grid[std::size_t(jj) * (t + 1) + ii]; };
            const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (a != b && b != c && a != c) add_triangle(w.m, a, b, c, 0);
            if (a != c && c != d && a != d) add_triangle(w.m, a, c, d, 0);
        }
}

// A UV sphere with `rings` vertex rings between the poles and `slices`
// vertices per ring: 2 * slices * rings triangles, outward-facing (counter-
// clockwise seen from outside), pole fans first and last.
void append_uv_sphere(Mesh& m, std::size_t rings, std::size_t slices, const Vec3& centre, float radius,
                      std::uint16_t mat) {
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    std::vector<double> cphi(slices), sphi(slices);
    for (std::size_t j = 0; j < slices; ++j) {
        const double phi = 2.0 * std::numbers::pi * double(j) / double(slices);
        cphi[j] = std::cos(phi);
        sphi[j] = std::sin(phi);
    }
    m.vertices.reserve(m.vertices.size() + 2 + rings * slices);
    m.vertices.push_back(centre + Vec3(0.0f, radius, 0.0f));
    for (std::size_t i = 1; i <= rings; ++i) {
        const double theta = std::numbers::pi * double(i) / double(rings + 1);
        const double y = std::cos(theta), rr = std::sin(theta);
        for (std::size_t j = 0; j < slices; ++j)
            m.vertices.push_back(centre + radius * Vec3(float(rr * cphi[j]), float(y), float(rr * sphi[j])));
    }
    const auto south = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.push_back(centre - Vec3(0.0f, radius, 0.0f));

    auto ring = [&](std::size_t i, std::size_t j) {
        return static_cast<std::uint32_t>(base + 1 + (i - 1) * slices + (j % slices));
    };
    m.triangles.reserve(m.triangles.size() + 2 * rings * slices);
    m.tri_material.reserve(m.triangles.capacity());
    for (std::size_t j = 0; j < slices; ++j) add_triangle(m, base, ring(1, j + 1), ring(1, j), mat);
    for (std::size_t i = 1; i < rings; ++i)
        for (std::size_t j = 0; j < slices; ++j) {
            const std::uint32_t a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j + 1), d = ring(i + 1, j);
            add_triangle(m, a, b, c, mat);
            add_triangle(m, a, c, d, mat);
        }
    for (std::size_t j = 0; j < slices; ++j) add_triangle(m, ring(rings, j), ring(rings, j + 1), south, mat);
}

constexpr std::size_t kMaxSphereTriangles = 200'000'000;

}  // namespace

Mesh make_teapot(int tessellation) {
    if (tessellation < 1 || tessellation > 256)
        throw InputError("teapot: tessellation " + std::to_string(tessellation) + " out of range [1, 256]");
    Mesh m;
    m.name = "teapot";
    m.materials.push_back(Material{});
    Welder w{m, {}};
    for (const auto& patch : kTeapotPatches) tessellate_patch(patch, tessellation, w);
    return m;
}

Mesh make_uv_sphere(std::size_t approx_triangles) {
    if (approx_triangles == 0 || approx_triangles > kMaxSphereTriangles)
        throw InputError("sphere: triangle count " + std::to_string(approx_triangles) +
                         " out of range [1, " + std::to_string(kMaxSphereTriangles) + "]");
    // 2 * slices * rings triangles with slices ~ 2 * rings (square-ish cells).
    const double n = double(approx_triangles);
    const auto rings = std::max<std::size_t>(1, std::size_t(std::llround(std::sqrt(n / 4.0))));
    const auto slices = std::max<std::size_t>(3, std::size_t(std::llround(n / (2.0 * double(rings)))));
    Mesh m;
    m.name = "sphere:" + std::to_string(approx_triangles);
    m.materials.push_back(Material{});
    append_uv_sphere(m, rings, slices, Vec3(0.0f), 1.0f, 0);
    return m;
}

Mesh make_spheres() {
    Mesh m;
    m.name = "spheres";
    m.materials = {
        Material{MaterialKind::Diffuse, Vec3(0.75f), 1.5f},               // 0 floor
        Material{MaterialKind::Diffuse, Vec3(0.8f, 0.25f, 0.2f), 1.5f},  // 1 solid
        Material{MaterialKind::Mirror, Vec3(0.9f), 1.5f},                 // 2 reflective
        Material{MaterialKind::Glass, Vec3(1.0f), 1.5f},                  // 3 refractive
    };
    // Floor quad at y = 0, facing up: triangles 0 and 1.
    const float fx = 4.5f, fz = 3.5f;
    m.vertices = {{-fx, 0.0f, -fz}, {-fx, 0.0f, fz}, {fx, 0.0f, fz}, {fx, 0.0f, -fz}};
    add_triangle(m, 0, 1, 2, 0);
    add_triangle(m, 0, 2, 3, 0);
    // Three spheres of 64 rings x 64 slices = 8,192 triangles, resting on the floor.
    append_uv_sphere(m, 64, 64, Vec3(-2.4f, 1.0f, 0.8f), 1.0f, 1);
    append_uv_sphere(m, 64, 64, Vec3(0.0f, 1.3f, -1.0f), 1.3f, 2);
    append_uv_sphere(m, 64, 64, Vec3(2.4f, 1.0f, 0.8f), 1.0f, 3);
    return m;
}

Mesh make_scene(const std::string& spec) {
    Mesh m;
    if (spec == "teapot") {
        m = make_teapot();
    } else if (spec == "spheres") {
        m = make_spheres();
    } else if (spec.rfind("sphere:", 0) == 0) {
        const std::string num = spec.substr(7);
        std::size_t n = 0;
        const char* end = num.data() + num.size();
        const auto [ptr, ec] = std::from_chars(num.data(), end, n);
        if (num.empty() || ec != std::errc{} || ptr != end || n == 0 || n > kMaxSphereTriangles)
            throw InputError("scene '" + spec + "': expected sphere:N with N a triangle count in [1, " +
                             std::to_string(kMaxSphereTriangles) + "]");
        m = make_uv_sphere(n);
    } else {
        m = load_mesh_file(spec);
    }
    m.name = spec;
    normalize_to_cube(m);
    return m;
}

}  // namespace pluecker
