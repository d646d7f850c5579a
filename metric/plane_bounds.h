#pragma once
// Float lower bounds on the distances from one point to many triangles, from each triangle's
// supporting plane and edge half-planes: the culling step of a packet query
// (metric/triangle_bvh.cpp, "Packets of coherent queries" in docs/metric.md). The kernels are
// SIMD, with the instruction set picked at run time: SSE2 (any x86-64; plain C++ elsewhere),
// AVX2 + FMA where the CPU and OS support it, AVX-512F on request. All variants compute the same
// formula; they differ only in rounding (FMA rounds less often), which the caller's margin
// covers, so the BVH's answers do not depend on the variant.
#include <cstddef>
#include <cstdint>

namespace meshdev {

// Rows of the planes' structure of arrays (row r of candidate i at rows[r * stride + i]):
// unit normal n (kNx..kNz) and offset d, so that h = n.p - d is the signed distance to the plane;
// for each edge e the outward unit normal m_e within the plane and its offset md_e, so that
// out_e = m_e.p - md_e is the distance beyond the edge's line. Padding lanes (count <= i <
// stride) hold n = m_e = md_e = 0 and d = -inf, which gives them a bound of +inf.
enum PlaneRow : int { kNx, kNy, kNz, kD, kM0x, kM0y, kM0z, kMd0 };  // edge e: kM0x + 4 e ...
constexpr int kPlaneRows = 16;
constexpr std::size_t kPlaneLanes = 16;  // stride must be a multiple of this (widest kernel)

enum class SimdLevel { kBaseline, kAvx2, kAvx512 };

// Triangles the bounds must never cull (their planes are all zeros, a bound of 0): slivers, whose
// conditioning kappa = |ab| |ac| / |ab x ac| exceeds kMaxCullKappa, and triangles with
// |ab x ac|^2 < kMinCullNormal2 (float frame, where the target spans [-1, 1]). The rounding
// analysis of the bounds (docs/metric.md) holds for the others.
constexpr double kMaxCullKappa = 1e6;
constexpr double kMinCullNormal2 = 1e-20;

// The planes (the rows above) of the up to four triangles of a BVH leaf block, by lane: computed
// in double from the block's float corners and rounded to float (max_offset rounded up: the
// largest |d|, |md_e|). Lanes never to be culled, empty lanes included: all zeros.
struct alignas(16) BlockPlanes {  // aligned: the baseline kernels load its rows as SSE vectors
  float row[kPlaneRows][4];       // [PlaneRow][lane]
  float max_offset[4];
};

// The smallest of a set of bounds and the next: `first` the index of the smallest (the first of
// equal ones; 0 if all are +inf), `runner_up` the smallest bound at any other index (+inf if
// there is none). A caller whose cutoff lies below runner_up knows that no candidate but `first`
// survives it, without a scan.
struct LeastBounds {
  std::size_t first = 0;
  float runner_up = 0.0f;
};

// The kernels of one instruction set.
struct PlaneKernels {
  // bound[i] = max(h^2 + max(out_0, out_1, out_2, 0)^2, 0), the square of a lower bound on the
  // distance from q to candidate i (all in the float frame), for i < count rounded up to the
  // kernel's width (padding lanes: +inf); a NaN bound is stored as 0 (never culled). Returns the
  // smallest bound's index and the runner-up among i < count (LeastBounds).
  // Preconditions: stride a multiple of kPlaneLanes, stride >= count > 0; q finite. O(count).
  LeastBounds (*bounds)(const float* rows, std::size_t stride, std::size_t count, const float q[3],
                        float* bound);
  // Writes to `out` the indices i < count, i != skip, with bound[i] <= cutoff, in increasing
  // order, and returns how many. bound: as written by `bounds` of the same kernels. O(count).
  std::size_t (*survivors)(const float* bound, std::size_t count, float cutoff, std::size_t skip,
                           std::uint32_t* out);
  // bound[4 j + lane] for the four lanes of *blocks[which[j]], j < count: the bound of `bounds`
  // above, read from each block's own rows (a packet's blocks, no per-packet rows), bit for bit
  // what `bounds` of the same kernels gives for the same coefficients. Returns the smallest's
  // index 4 j + lane and the runner-up among the 4 count bounds (LeastBounds). `bound` must have
  // room for 4 count rounded up to kPlaneLanes floats (`survivors` reads that far).
  // Preconditions: count > 0; q finite. O(count).
  LeastBounds (*block_bounds)(const BlockPlanes* const* blocks, const std::uint8_t* which,
                              std::size_t count, const float q[3], float* bound);
  // The planes of the four triangles whose corners are corner[corner][axis][lane] (float frame):
  // the normal n = ab x ac made unit, d = n.a, and per edge e (a->b, b->c, c->a) the unit
  // m_e = e x n (computed as e x (ab x ac), then made unit: the same direction) and md_e =
  // m_e.(its first corner); all in double, four lanes at once where the instruction set
  // allows. Every variant rounds each double operation once or less (FMA), so
  // the rows differ between them only in the last float bit, within the caller's margin (and,
  // for a triangle at one of the two limits above, in whether it is kept). O(1).
  void (*block_planes)(const float corner[3][3][4], BlockPlanes& out);
};

// The kernels' instruction set: AVX2 if this build has it and the CPU and OS support it, else
// the baseline. AVX-512 only on request: the environment variable MESHDEV_SIMD (baseline, avx2 or
// avx512; a level the CPU lacks falls back to the default) chooses. Decided once, at first call.
// Throws InvalidInput for any other value of MESHDEV_SIMD.
SimdLevel simd_level();
// True if this build has the kernels of `level` and the CPU and OS can run them.
bool simd_supported(SimdLevel level);
const char* simd_level_name(SimdLevel level);
// The kernels of `level`; precondition: simd_supported(level).
const PlaneKernels& plane_kernels(SimdLevel level);

namespace detail {
// The x86 kernels, each in its own translation unit compiled for its instruction set
// (plane_bounds_avx2.cpp, plane_bounds_avx512.cpp); only called after the CPU check.
extern const PlaneKernels kPlaneKernelsAvx2;
extern const PlaneKernels kPlaneKernelsAvx512;
// The AVX2 + FMA block planes and block bounds, which the AVX-512 kernels share (every AVX-512F
// CPU has both).
void block_planes_avx2(const float corner[3][3][4], BlockPlanes& out);
LeastBounds block_bounds_avx2(const BlockPlanes* const* blocks, const std::uint8_t* which,
                              std::size_t count, const float q[3], float* bound);
}  // namespace detail

}  // namespace meshdev
