#pragma once
// Queries in the BVH's float frame (metric/triangle_bvh.h): a query's coordinates rounded to
// float and how far that rounding may have moved it, one query at a time (TriangleBvh::find) or
// for the consecutive queries of a packet with the box they span (TriangleBvh::find_batch). The
// packet's has two versions with the same results, bit for bit: two SSE2 lanes per query
// (frame_packet, any x86-64) and query by query (frame_packet_scalar, the test oracle and the
// path of builds without SSE2).
#include <cstddef>

#include "metric/leaf_blocks.h"
#include "metric/vec3.h"

namespace meshdev::detail {

// Queries farther out than this on an axis (float frame) are never culled.
constexpr double kMaxFrameQuery = 1e12;

// Query p in the frame: qf = ((p - origin) * scale) rounded to float, each axis, and slack =
// corner_error + |qf - q|_1 + 4e-16 (|q|_1 + 3), which covers the rounding of qf and of q
// itself (q computed in double). Returns false where p cannot be culled (NaN, or |q| >=
// kMaxFrameQuery on an axis); qf is written then too, and slack is corner_error. O(1).
bool frame_query(const Vec3& p, const FrameMap& frame, double corner_error, float qf[3],
                 double& slack);

// How far a packet may grow: the squared diagonal of its box (float frame) at most max_diag2,
// and at most full_diag2 once it holds full_from queries.
struct PacketExtent {
  double max_diag2;
  double full_diag2;
  std::size_t full_from;
};

// The packet that starts at points[0]: frame_query of points[0], points[1], ... while they can be
// culled and the box of their qf (its diagonal computed in double from the float corners) stays
// within `extent`, at most `count` of them. Writes qf[k] and slack[k] of every query taken (and
// may write those of the query that ended the packet) and lo, hi: the box of the queries taken
// (untouched if none). Returns how many were taken: 0 where points[0] cannot be culled.
// Precondition: count >= 1. O(queries taken).
std::size_t frame_packet(const Vec3* points, std::size_t count, const FrameMap& frame,
                         double corner_error, const PacketExtent& extent, float (*qf)[3],
                         double* slack, float lo[3], float hi[3]);
// The same, query by query with frame_query, as the packets grew before frame_packet.
std::size_t frame_packet_scalar(const Vec3* points, std::size_t count, const FrameMap& frame,
                                double corner_error, const PacketExtent& extent, float (*qf)[3],
                                double* slack, float lo[3], float hi[3]);

}  // namespace meshdev::detail
