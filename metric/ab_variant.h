#pragma once
// A switch for measuring a candidate change against the code it would replace, within one binary
// and one run (docs/performance.md §1, "A/B of a change"). An experiment puts the candidate under
// `if (detail::ab_variant() == 1)` beside the present code; `peer_compare --ab R` then answers the
// same chunks of samples with variant 0 and variant 1 in turn, alternating which goes first, and
// prints the ratio of their times per round, so a shared host's drift over minutes falls on both
// alike (A/A, no code reading the switch: median 1.003 on 2 threads, 0.999 on one). Landed code
// never reads it: a change lands with only its winning version.
namespace meshdev::detail {

// The variant in force: 0 (the present code) unless a measurement set it. A plain global read
// inline, so the test costs a load and a branch that always goes the same way. Not synchronised:
// set it only while no query runs.
extern int g_ab_variant;
inline int ab_variant() {
  return g_ab_variant;
}
inline void set_ab_variant(int variant) {
  g_ab_variant = variant;
}

}  // namespace meshdev::detail
