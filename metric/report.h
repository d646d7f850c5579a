#pragma once
// Reports of a comparison: a text block like the paper's Table 1, versioned JSON, a summary CSV
// and the per-sample CSV. Numbers in JSON/CSV are printed to round-trip (17 significant digits).
#include <ostream>
#include <string>

#include "metric/compare.h"

namespace meshdev {

inline constexpr const char* kCompareSchema = "meshdev.compare/1";

// The human-readable report (paper Table 1: both meshes' vertices, faces and area beside the
// deviation statistics), for every measure and direction. O(measures).
std::string format_report(const ComparisonResult& result);

// JSON document with schema kCompareSchema: tool version, meshes, options, measures, per
// direction statistics (absolute, plus relative to the bbox diagonal of A for geometry), where
// the maxima are, histograms, the symmetric summary and timings. O(measures x bins).
std::string to_json(const ComparisonResult& result);

// One row per direction (forward, backward, symmetric) and measure. Columns: see docs/metric.md.
std::string to_summary_csv(const ComparisonResult& result);

// One row per sample and direction: position, face, kind, nearest point and face, feature, ties,
// weight and every measure's deviation. Requires keep_samples (throws InvalidInput otherwise).
// O(samples x measures).
void write_samples_csv(std::ostream& out, const ComparisonResult& result);

}  // namespace meshdev
