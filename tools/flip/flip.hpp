// LDR-FLIP image difference metric (standard library only).
//
// Implements the LDR variant of FLIP from P. Andersson, J. Nilsson, T. Akenine-Möller,
// M. Oskarsson, K. Åström and M. D. Fairchild, "FLIP: A Difference Evaluator for Alternating
// Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2) (HPG 2020), and follows NVIDIA's
// reference implementation (PyPI `flip-evaluator` 1.7, `evaluate(reference, test, "LDR")`)
// in every numerical choice: float32 arithmetic, separable filters, clamp-to-edge borders.
// tests/test_flip.cpp checks agreement against values written by tools/flip/make_expected.py.
//
// FLIP is a per-pixel error in [0, 1]: 0 = indistinguishable when flipping between the two
// images at the given viewing condition, 1 = maximal perceived difference.
#pragma once

#include <cstdint>
#include <vector>

namespace jade::flip {

/// An image in sRGB encoding: 3 floats per pixel (R, G, B) in [0, 1], rows top to bottom,
/// rgb.size() == width * height * 3. ldr_flip() clamps values outside [0, 1].
struct Image {
    uint32_t width = 0, height = 0;
    std::vector<float> rgb;
};

/// 8-bit sRGB pixels (channels = 3 for RGB or 4 for RGBA; alpha is ignored) to an Image,
/// value = code / 255 exactly as the reference's 8-bit loader does.
/// Throws std::invalid_argument for a zero size, a null pointer or channels other than 3/4.
Image from_srgb8(uint32_t w, uint32_t h, const uint8_t* rgb_or_rgba, uint32_t channels);

/// Linear-light RGB floats (channels = 3 or 4; alpha ignored) to an Image: each value is
/// clamped to [0, 1] (NaN becomes 0) and sRGB-encoded with the IEC 61966-2-1 curve.
/// Throws std::invalid_argument like from_srgb8().
Image from_linear(uint32_t w, uint32_t h, const float* rgba, uint32_t channels);

/// Pixels per degree of visual angle for an observer at distance_m metres from a monitor
/// monitor_width_m metres wide showing monitor_pixels pixels across, computed like the
/// reference (distance * pixels / width * pi / 180, in float): the default viewing
/// condition (0.7 m, 0.7 m, 3840 px) gives 67.0206...
double pixels_per_degree(double distance_m = 0.7, double monitor_width_m = 0.7, double monitor_pixels = 3840);

/// Mean LDR-FLIP error of `test` against `reference` (both sRGB-encoded, same size) at `ppd`
/// pixels per degree. With `mask` (width * height bytes, row-major like the image), the mean
/// is taken only over pixels whose mask byte is non-zero; the filters still see every pixel.
/// With `error_map`, it is resized to width * height and receives the per-pixel errors.
/// Throws std::invalid_argument for empty images, inconsistent rgb sizes, a size mismatch
/// between the images, ppd not finite and positive, a mask of the wrong size, or a mask with
/// no non-zero byte (an empty selection has no mean; a value such as 0 would read as
/// "no error").
double ldr_flip(const Image& reference, const Image& test, double ppd = pixels_per_degree(),
                const std::vector<uint8_t>* mask = nullptr, std::vector<float>* error_map = nullptr);

}  // namespace jade::flip
