#include "metric/io/text_scan.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "metric/errors.h"
#include "metric/io/mesh_io.h"
#include "tests/metric/io/io_test_util.h"
#include "tests/support/test_data.h"

namespace meshdev::test {
namespace {

using io_detail::FileBytes;

TEST(FileBytes, GivesTheFilesBytesWhetherMappedOrRead) {
  const std::string dir = scratch_dir("file_bytes");
  std::string bytes = "ply\n";
  for (int i = 0; i < 70000; ++i) bytes += static_cast<char>(i * 7 % 256);
  EXPECT_EQ(FileBytes(write_file(dir, "a.bin", bytes)).view(), bytes);
  EXPECT_TRUE(FileBytes(write_file(dir, "empty.bin", "")).view().empty());
  // procfs files say size 0 but have content: read, not mapped.
  EXPECT_NE(FileBytes("/proc/self/status").view().find("Name:"), std::string::npos);
  EXPECT_THROW(FileBytes{dir + "/missing.bin"}, IoError);
  EXPECT_THROW(FileBytes{dir}, IoError);
}

// A mapped file whose size is a whole number of pages ends where its mapping ends: a reader that
// looked one byte past the end would fault here instead of reading the page's zero tail. Every
// format, padded to exactly one or two pages with what it allows (comments, blank lines, a PLY
// header comment).
TEST(FileBytes, MeshesFillingWholePagesAreReadToTheirLastByte) {
  const std::string dir = scratch_dir("file_bytes_pages");
  const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  auto pad_to = [](std::string head, const std::string& tail, std::size_t size, char fill) {
    EXPECT_LT(head.size() + tail.size() + 3, size);
    head += std::string(size - head.size() - tail.size() - 1, fill) + "\n";
    return head + tail;
  };
  for (const std::size_t size : {page, 2 * page}) {
    const std::string obj = pad_to("# padding ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3", size, 'x');
    const std::string off = pad_to("OFF\n# ", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2", size, ' ');
    std::string ply_body;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(ply_body, v);
    put(ply_body, std::uint8_t{3});
    for (std::int32_t i : {0, 1, 2}) put(ply_body, i);
    const std::string ply_tail =
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
        ply_body;
    const std::string ply =
        pad_to("ply\nformat binary_little_endian 1.0\ncomment ", ply_tail, size, 'c');
    const std::string stl = pad_to(
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\n",
        "endsolid t", size, ' ');
    for (const auto& [name, text] : {std::pair<std::string, std::string>{"a.obj", obj},
                                     {"a.off", off},
                                     {"a.ply", ply},
                                     {"a.stl", stl}}) {
      ASSERT_EQ(text.size(), size) << name;
      const TriMesh m = read_mesh(write_file(dir, name, text));
      EXPECT_EQ(m.num_vertices(), 3u) << name;
      ASSERT_EQ(m.num_faces(), 1u) << name;
      EXPECT_EQ(m.positions[2].y, 1.0) << name;
    }
  }
}

// The cuts for a parallel parse are line starts, ascending and distinct, from `begin` to the end
// of the text, about equal in bytes; a text of one line is one chunk.
TEST(LineChunks, CutAtLineStartsIntoAboutEqualParts) {
  std::string text = "header line\n";
  const std::size_t begin = text.size();
  for (int i = 0; i < 1000; ++i) text += "line " + std::to_string(i % 37) + "\n";
  for (int chunks : {1, 2, 3, 7, 50}) {
    SCOPED_TRACE(chunks);
    const std::vector<std::size_t> cuts = io_detail::line_chunks(text, begin, chunks);
    ASSERT_EQ(cuts.size(), static_cast<std::size_t>(chunks) + 1);
    EXPECT_EQ(cuts.front(), begin);
    EXPECT_EQ(cuts.back(), text.size());
    const double share = static_cast<double>(text.size() - begin) / chunks;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      EXPECT_LT(cuts[k], cuts[k + 1]);
      EXPECT_EQ(text[cuts[k] - 1], '\n') << k;
      EXPECT_NEAR(static_cast<double>(cuts[k + 1] - cuts[k]), share, 10.0) << k;
    }
  }
  EXPECT_EQ(io_detail::line_chunks("one line, no newline", 0, 4),
            (std::vector<std::size_t>{0, 20}));
  EXPECT_EQ(io_detail::line_chunks("a\nb\n", 0, 8), (std::vector<std::size_t>{0, 2, 4}));
}

}  // namespace
}  // namespace meshdev::test
