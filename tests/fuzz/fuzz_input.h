#pragma once
// Turns fuzzer bytes into small valid-but-weird meshes and query points for the fuzz targets:
// coordinates on a coarse lattice (so points coincide and triangles degenerate often) mixed with
// a few extreme values, face corners taken modulo the vertex count (repeated corners, duplicate
// and non-manifold faces). Every value is finite, so the mesh passes validate().
#include <cstddef>
#include <cstdint>

#include "metric/mesh.h"

namespace meshdev::fuzz {

// Reads bytes front to back; 0 once they run out.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  bool empty() const { return pos_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// One coordinate: a lattice value (b - 120) / 16 in [-7.5, 7.4], or one of 16 special values.
inline double coordinate(ByteReader& in) {
  static constexpr double kSpecial[16] = {0.0,   -0.0,   1e-9, -1e-9,    1e-300, 0.5 + 1e-12,
                                          1e6,   -1e6,   1e15, -1e15,    3e-8,   1.0 / 3.0,
                                          1e100, -1e100, 0.1,  2.0 / 3.0};
  const std::uint8_t b = in.byte();
  if (b >= 240) return kSpecial[b - 240];
  return (static_cast<double>(b) - 120.0) / 16.0;
}

inline Vec3 point(ByteReader& in) {
  const double x = coordinate(in), y = coordinate(in), z = coordinate(in);
  return {x, y, z};
}

// A mesh of 1..16 vertices and 1..32 triangles (corners modulo the vertex count).
inline TriMesh small_mesh(ByteReader& in) {
  TriMesh m;
  const int vertices = 1 + in.byte() % 16;
  for (int v = 0; v < vertices; ++v) m.positions.push_back(point(in));
  const int faces = 1 + in.byte() % 32;
  for (int f = 0; f < faces; ++f) {
    Triangle t;
    for (auto& corner : t) corner = in.byte() % static_cast<std::uint32_t>(vertices);
    m.faces.push_back(t);
  }
  m.source_polygons = m.faces.size();
  return m;
}

}  // namespace meshdev::fuzz
