#pragma once
// A 4-wide bounding-volume hierarchy over a triangle mesh for exact nearest-point queries with
// ties.
//
// Build: binned SAH (16 bins) on the centres of the faces' boxes into a binary tree with leaves of
//        at most 4 triangles (subtrees of at most 32 faces: sorted along the axis and split where
//        SAH is least among the splits into full blocks of 4, which keeps leaf blocks full), then
//        collapsed into 4-wide nodes with the least summed half area (a dynamic programme whose
//        plans the splits make, metric/wide_collapse.h; children kept in order, so the leaves stay
//        in the face records' order and the leaf blocks are numbered as the records are).
//        Boxes and triangle corners are stored in single precision, 4 per block (structure of
//        arrays), in a frame centred on the mesh and scaled to [-1, 1]. The binning works on
//        32-byte face records (float box rounded outwards, face index) partitioned in place, with
//        SSE box unions. O(F log F) time, subtrees and leaf blocks built in parallel (OpenMP);
//        memory_bytes() is about 55-60 bytes per face. Meshes of 4,096 faces or more stored in no
//        spatial order (probed on pairs of consecutive faces) are instead sorted along a Morton
//        curve (30-bit codes, radix sort on the team) and split above 32 faces where their codes'
//        highest differing bit changes (an LBVH; Lauterbach et al. 2009), below as above: on such
//        orders binning costs most and the trees query within a few per cent of SAH's
//        (morton_splits()).
// Query: depth-first, nearer child first, starting from the upper bound of hint.start_face. Four
//        boxes or four triangles are tested per step with SSE (metric/simd4.h). A box or a
//        triangle is skipped only when a conservative single-precision lower bound on its
//        distance exceeds the current tie limit; every face that survives is evaluated exactly in
//        double (detail::FaceEvaluator), so the distance and the tie set are those of the
//        brute-force oracle. O(log F) expected near the surface, O(F) worst case.
// Why float cannot change the result (docs/metric.md "Culling in single precision"):
//   boxes are rounded outwards; the query's own rounding and the corners' rounding are measured
//   and added to the radius; the triangle lower bound sqrt(h^2 + max_e out_e^2) (distance to the
//   supporting plane and to the edge half-planes) gets a margin 64 u (2 + kappa) (|ap|+|bp|+|cp|)
//   that covers its rounding error (u = 2^-24, kappa = |ab||ac| / |ab x ac|; offsets are
//   normalised before squaring, so nothing that matters underflows); slivers (kappa > 1e6),
//   triangles under ~1e-5 of the mesh and queries beyond 1e12 mesh sizes are never culled by it;
//   meshes under 1e-140 or over 1e140 in size are searched without culling (double underflow).
// Batches (find_batch): consecutive queries within about kPacketExtent (4) typical triangles of
//        each other (2 once there are 24) form a packet of up to 64. The packet's centre query
//        runs as above and gives every other query an upper bound (triangle inequality); one
//        traversal with the packet's box collects the faces within reach of any of them; each
//        query then tests only those, with a float lower bound from precomputed unit plane and
//        edge normals (one multiply-add per coordinate; SIMD kernels chosen at run time,
//        metric/plane_bounds.h), and evaluates the survivors exactly, nearest bound first; where
//        the packet has fewer than 3 queries per gathered leaf block, each query bounds only
//        the faces of the blocks within its own reach. Same answers as find(); packets whose
//        reach holds too many blocks fall back to find(). Runs
//        of 2 or 3 (queries sparse on the target) form a block packet instead: the centre query
//        bounds the others as above, one traversal gathers the leaf blocks within reach, and
//        each query searches those blocks as find() does, nearest box first.
//        Where the last answers were near B (3 times their largest distance under half the
//        packet's diagonal), a packet guesses instead: its reach is that multiple, there is no
//        centre query, and any query whose tie limit comes out beyond the guess is searched
//        again from the root (so a wrong guess costs time only, never an answer).
//        Neither kind of packet changes any answer.
// Ref: Wald, "On fast construction of SAH-based bounding volume hierarchies" (2007) for binning;
//      Wald et al., "Getting rid of packets" (2008) and Embree for 4-wide nodes.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "metric/leaf_blocks.h"
#include "metric/leaf_gather.h"
#include "metric/nearest_point.h"
#include "metric/plane_bounds.h"
#include "metric/raw_storage_allocator.h"

namespace meshdev {
namespace detail {
struct FaceRecords;
}  // namespace detail

class TriangleBvh final : public NearestPointIndex {
 public:
  // threads: OpenMP threads for the build (0 = OpenMP's default); the structure is the same for
  // any thread count.
  TriangleBvh(const TriMesh& target, const TieOptions& ties = {}, int threads = 0);
  std::string name() const override { return "bvh"; }
  double find(const Vec3& p, const QueryHint& hint, std::vector<SurfaceHit>& ties) const override;
  std::size_t find_batch(const Vec3* points, const QueryHint* hints, std::size_t count,
                         BatchHits& out) const override;

  std::size_t node_count() const { return nodes_.size(); }
  std::size_t leaf_count() const { return leaves_.size(); }
  // Bytes of the structure (nodes and leaf blocks), without the mesh it indexes.
  std::size_t memory_bytes() const;
  int depth() const { return depth_; }  // levels of 4-wide nodes, leaves included
  // Whether the build split along a Morton curve (faces stored in no spatial order) rather than
  // by binned SAH above 32 faces. The answers are the same either way; for tests and reports.
  bool morton_splits() const { return morton_splits_; }
  // The structure's invariants, for tests: every face of the target in exactly one leaf lane,
  // every child box holding its node's child boxes or its leaf's float corners, no empty leaf,
  // empty lanes last. Returns "" or the first violation found. O(F) time and memory.
  std::string check_structure() const;

 private:
  // Four child boxes, [axis][child]; child refs: a node index, kLeaf | leaf index, or kEmpty
  // (metric/leaf_gather.h).
  using Node = detail::WideNode;
  // Up to four triangles in SIMD lanes (metric/leaf_blocks.h).
  using Leaf = detail::LeafBlock;

  // A leaf block's planes in a packet's cache (block kNoFace: an empty slot).
  struct CachedPlanes {
    BlockPlanes planes;
    std::uint32_t block = kNoFace;
  };
  struct PacketScratch;
  struct Search;                         // one query's search state (triangle_bvh.cpp)
  static constexpr int kCacheBits = 10;  // plane cache slots (leaf blocks) of a batch: 2^kCacheBits

  // The index from the face records (triangle_bvh.cpp), which give the evaluator its boxes.
  TriangleBvh(const TriMesh& target, const TieOptions& ties, int threads,
              detail::FaceRecords&& records);
  void build(int threads, detail::FaceRecords& records);
  // The query in the float frame (detail::frame_query): its coordinates rounded to float, and
  // the culling slack (query + corner rounding). False if the query cannot be culled in float
  // (too far out, or a mesh searched without culling); slack is then corner_error_.
  bool to_frame(const Vec3& p, float qf[3], double& slack) const;
  // Answers queries [base, base + n) of a batch as one packet (their frame coordinates and box
  // are in `scratch`) and returns how many it answered: n, or fewer once BatchHits::kMaxHits ties
  // are held; 0, with nothing written, if the packet's reach holds too many faces. `guess` >= 0:
  // the reach is that distance (absolute) and there is no centre query; each query whose tie
  // limit comes out beyond it is answered by find() (scratch.misses counts them). < 0: the
  // centre query is answered in full and bounds the others.
  std::size_t find_packet(const Vec3* points, const QueryHint* hints, std::size_t base,
                          std::size_t n, std::uint32_t start_face, double guess,
                          PacketScratch& scratch, BatchHits& out) const;
  // Query k of the packet at `base`, whose reach in the packet was not enough (a guess too
  // small), answered by find() from face `from` (else its hint's start face, else the answer
  // before it, else `start_face`); counted in scratch.misses.
  void answer_in_full(const Vec3* points, std::size_t base, std::size_t k, const QueryHint& hint,
                      std::uint32_t from, std::uint32_t start_face, PacketScratch& scratch,
                      BatchHits& out) const;
  // The reach of the identical-triangle check for a query with this hint (FaceEvaluator):
  // the search never narrows below it. 0 without a source triangle.
  double floor_of(const QueryHint& hint) const { return hint.has_source() ? check_reach_ : 0.0; }
  // A tie limit (absolute, not squared) as a culling radius in the float frame: at least
  // `floor`, plus the query's rounding slack (to_frame).
  double frame_reach(double limit, double floor, double slack) const {
    return std::max(limit, floor) * frame_.scale + slack;
  }
  // Answers the centre query of the packet [base, base + n) in full (scratch.center_distance,
  // scratch.center_ties) and bounds every query by it (triangle inequality): limit[k], the tie
  // limit of d(centre) + |p_k - centre| (absolute), and reach[k], that limit as a radius in the
  // float frame. Returns the largest reach.
  double packet_bounds(const Vec3* points, const QueryHint* hints, std::size_t base, std::size_t n,
                       std::uint32_t start_face, PacketScratch& scratch, double* limit,
                       double* reach) const;
  // The bounds of a packet whose queries' distances are guessed (no centre query): every
  // limit[k] is the guess (absolute), reach[k] that limit as a radius in the float frame.
  // Returns the largest reach.
  double guess_bounds(const QueryHint* hints, std::size_t base, std::size_t n, double guess,
                      const PacketScratch& scratch, double* limit, double* reach) const;
  // Narrows the search's culling radii to the tie limit `limit_dist` (absolute, not squared);
  // they never grow.
  void narrow(Search& s, double limit_dist) const;
  // Evaluates `face` exactly and keeps it if it is within the tie limit; a new best narrows.
  void consider(Search& s, std::uint32_t face) const;
  // Tests the (up to) four triangles of a leaf block: a float lower bound per triangle, then
  // the survivors exactly, nearest bound first.
  void search_leaf(const Leaf& leaf, Search& s) const;
  // The planes of leaf block `block` (kernels_->block_planes), with d = -inf in its empty lanes
  // (a bound of +inf).
  void compute_block_planes(std::uint32_t block, BlockPlanes& out) const;
  // The planes of leaf block `block`, from the batch's cache or computed into it; the entry
  // holds them until another block takes its slot.
  const CachedPlanes& block_planes(std::uint32_t block, PacketScratch& scratch) const;
  // Answers queries [base, base + n) of a batch (sparse on the target) as a block packet: the
  // centre query in full, then one traversal gathers the leaf blocks within reach of any query
  // (at most kMaxBlocks), and each other query searches those blocks as find() would, nearest
  // box first, from the centre's upper bound. With `guess` >= 0 the reach is the guess, there
  // is no centre query, and each query starts from the bound given by the one before it and is
  // checked as in find_packet. Returns as find_packet does.
  std::size_t find_block_packet(const Vec3* points, const QueryHint* hints, std::size_t base,
                                std::size_t n, std::uint32_t start_face, double guess,
                                PacketScratch& scratch, BatchHits& out) const;
  // The leaf blocks within `reach` of [lo, hi] into scratch; false if more than kMaxBlocks.
  bool gather_blocks(const float lo[3], const float hi[3], double reach,
                     PacketScratch& scratch) const;
  // Pads the gathered blocks' boxes to a multiple of 8 lanes with boxes never within reach
  // (detail::blocks_near_point reads 8 at a time); returns the count rounded up to 4, the
  // multiple the packets' other per-block rows are padded to.
  static std::size_t pad_blocks(PacketScratch& scratch);

  detail::FaceEvaluator eval_;
  const PlaneKernels* kernels_;  // the packet bounds for this CPU (metric/plane_bounds.h)
  // gather_blocks walks with AVX lane permutations, and a sparse packet's queries choose their
  // blocks eight at a time (the CPU runs AVX2, metric/leaf_gather.h).
  bool avx_gather_;
  std::uint64_t id_;        // unique in the process: owner of the threads' plane caches
  double check_reach_ = 0;  // sqrt(eval_.exact_check_sq): the identical-triangle check's reach
  detail::FrameMap frame_{{0, 0, 0}, 1};  // float frame = (x - origin) * scale (bbox centred)
  bool cull_scale_ = true;         // false: the mesh is too small or large to cull (see kMinExtent)
  double corner_error_ = 0;        // max |float corner - exact corner| in the float frame
  double packet_extent_ = 0;       // largest packet box diagonal (float frame) for find_batch
  double full_packet_extent_ = 0;  // the same for packets of at least kFullPacket queries
  std::uint32_t root_ = 0;         // child ref of the root
  std::vector<Node> nodes_;
  // Every field written by build(), mostly in the storage of its spent binary tree (build()).
  RawArray<Leaf> leaves_;
  int depth_ = 0;
  bool morton_splits_ = false;
};

}  // namespace meshdev
