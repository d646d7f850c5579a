#include "metric/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>

#include "metric/errors.h"
#include "metric/io/read_obj.h"
#include "metric/io/read_off.h"
#include "metric/io/read_ply.h"
#include "metric/io/read_stl.h"
#include "metric/io/text_scan.h"

namespace meshdev {
namespace {

enum class Format { kUnknown, kObj, kPly, kOff, kStl };

const char* format_name(Format f) {
  switch (f) {
    case Format::kObj:
      return "OBJ";
    case Format::kPly:
      return "PLY";
    case Format::kOff:
      return "OFF";
    case Format::kStl:
      return "STL";
    case Format::kUnknown:
      break;
  }
  return "unknown";
}

Format by_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return Format::kObj;
  if (ext == ".ply") return Format::kPly;
  if (ext == ".off") return Format::kOff;
  if (ext == ".stl") return Format::kStl;
  return Format::kUnknown;
}

// The format the first bytes announce: the PLY magic line, an OFF keyword as the first token
// (after comments), or "solid" / an exact binary STL size. kUnknown if nothing is announced.
Format by_content(std::string_view data) {
  std::string_view text = io_detail::strip_bom(data);
  if (text.substr(0, 4) == "ply\n" || text.substr(0, 5) == "ply\r\n") return Format::kPly;
  io_detail::LineReader lines(text.substr(0, 4096));
  std::string_view line;
  while (lines.next(line)) {
    line = io_detail::trim(io_detail::strip_comment(line));
    if (line.empty()) continue;
    std::string_view first = line.substr(0, line.find_first_of(" \t"));
    if (first.size() >= 3 && first.size() <= 7 && first.substr(first.size() - 3) == "OFF" &&
        first.find_first_not_of("STCNOF") == std::string_view::npos)
      return Format::kOff;
    break;
  }
  if (data.size() >= 84) {
    std::uint32_t count = static_cast<std::uint8_t>(data[80]) |
                          static_cast<std::uint32_t>(static_cast<std::uint8_t>(data[81])) << 8 |
                          static_cast<std::uint32_t>(static_cast<std::uint8_t>(data[82])) << 16 |
                          static_cast<std::uint32_t>(static_cast<std::uint8_t>(data[83])) << 24;
    if (84 + 50 * std::uint64_t{count} == data.size()) return Format::kStl;
  }
  if (io_detail::trim(text.substr(0, 6)).substr(0, 5) == "solid") return Format::kStl;
  return Format::kUnknown;
}

}  // namespace

TriMesh read_mesh(const std::string& path, int threads) {
  const io_detail::FileBytes bytes(path);
  const std::string_view data = bytes.view();
  if (data.empty()) throw ParseError(path, "", "empty file");
  const Format ext = by_extension(path);
  Format content = by_content(data);
  // A binary STL size or "solid" is weak evidence; an explicit extension wins over it.
  if (content == Format::kStl && ext != Format::kUnknown) content = Format::kUnknown;
  Format format = content != Format::kUnknown ? content : ext;
  if (format == Format::kUnknown)
    throw ParseError(path, "",
                     "unknown mesh format (not PLY/OFF/STL by content, and the extension is not "
                     ".obj, .ply, .off or .stl)");
  if (ext != Format::kUnknown && ext != format)
    std::cerr << "meshdev: warning: " << path << ": the content is " << format_name(format)
              << ", not " << format_name(ext) << " as the extension says; reading it as "
              << format_name(format) << '\n';
  switch (format) {
    case Format::kObj:
      return read_obj(path, data, threads);
    case Format::kPly:
      return read_ply(path, data);
    case Format::kOff:
      return read_off(path, data, threads);
    case Format::kStl:
      return read_stl(path, data);
    case Format::kUnknown:
      break;
  }
  throw ParseError(path, "", "unknown mesh format");
}

}  // namespace meshdev
