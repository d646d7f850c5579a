#pragma once
// Wall-clock bounds in tests ("reads buildings.obj in under 1 s") are set for optimized,
// uninstrumented builds. AddressSanitizer and ThreadSanitizer run the same code 2-3x slower:
// io.ReadObjReal.BuildingsLoadsFast reads in 0.19 s in Release, 0.37-0.56 s with ASan+UBSan,
// and 1.1 s with ASan+UBSan while another build shared the 2-core machine. That last run failed
// the 1 s bound. Tests multiply their bounds by kTimeBoundScale, which is 1 in an uninstrumented
// build, so the bound there is unchanged.

namespace meshdev::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;  // gcc
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kSanitizedBuild = true;  // clang
#else
inline constexpr bool kSanitizedBuild = false;
#endif
#else
inline constexpr bool kSanitizedBuild = false;
#endif

inline constexpr double kTimeBoundScale = kSanitizedBuild ? 4.0 : 1.0;

}  // namespace meshdev::test
