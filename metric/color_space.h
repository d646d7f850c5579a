#pragma once
// Colour conversions for perceptual colour deviation (the paper's future work: "measurements in
// the real attribute space"). sRGB (IEC 61966-2-1, D65) -> CIE XYZ -> CIELAB.
#include "metric/vec3.h"

namespace meshdev {

// CIELAB (L* in [0,100], a*, b*) of an sRGB colour with components in [0, 1] (clamped).
Vec3 srgb_to_lab(const Vec3& rgb);

// CIE76 colour difference: Euclidean distance in CIELAB. ~2.3 is a just-noticeable difference.
double delta_e76(const Vec3& lab1, const Vec3& lab2);

// CIEDE2000 colour difference (Sharma, Wu, Dalal 2005, with kL = kC = kH = 1).
double delta_e2000(const Vec3& lab1, const Vec3& lab2);

}  // namespace meshdev
