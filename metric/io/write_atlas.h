#pragma once
// Writes a deviation texture atlas (metric/deviation_atlas.h) so any viewer shows it.
#include <string>

#include "metric/deviation_atlas.h"

namespace meshdev {

// Writes <stem>.png (the atlas), <stem>.obj + <stem>.mtl (material "deviation", map_Kd
// <stem>.png) and <stem>.ply (per-corner texcoord, "comment TextureFile <stem>.png"), each through
// write_file_atomically. Throws WriteError. O(S^2 + F).
void write_deviation_atlas(const std::string& stem, const DeviationAtlas& atlas);

}  // namespace meshdev
