#pragma once
// meshdev's metric in one include: read meshes, compare them, get statistics.
#include "metric/attribute_deviation.h"  // per-sample deviations (paper Eq. 3-4)
#include "metric/attributes.h"           // what is measured and how
#include "metric/compare.h"              // both directions + symmetric summary (paper §3.3)
#include "metric/errors.h"               // InvalidInput, IoError, ParseError, WriteError
#include "metric/io/mesh_io.h"           // read_mesh
#include "metric/mesh.h"                 // TriMesh
#include "metric/nearest_point.h"        // nearest point with ties (BVH / brute force)
#include "metric/sampling.h"             // vertices, edges, scan conversion (Eq. 5-6), Monte Carlo
#include "metric/statistics.h"           // min, max, mean, variance, RMS, quantiles, histogram
