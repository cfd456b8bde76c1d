// Output files of a run (docs/outputs.md). Every file is either written whole
// (temporary file + rename, so a reader never sees half a file) or appended to
// line by line, each line complete and flushed before the next step, so an
// interrupted run leaves every file consistent.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace rheodda::scene {

/// Writes `content` to `path` through `path + ".tmp"` and a rename; throws std::runtime_error.
void write_file_atomic(const std::string& path, const std::string& content);

/// Reads a whole file; throws std::runtime_error.
std::string read_file(const std::string& path);

/// A CSV file appended line by line; each line is flushed whole.
class CsvAppender {
 public:
  CsvAppender() = default;
  /// Opens `path`: truncated to `keep_bytes` bytes (resume) or created empty.
  void open(const std::string& path, std::uint64_t keep_bytes, bool resume);
  ~CsvAppender();
  CsvAppender(const CsvAppender&) = delete;
  CsvAppender& operator=(const CsvAppender&) = delete;
  /// Appends `line` (which must end in '\n') and flushes.
  void append(const std::string& line);
  std::uint64_t bytes() const { return bytes_; }

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::uint64_t bytes_ = 0;
};

/// One polygon of a VTK frame with its fields.
struct FrameBlock {
  std::vector<std::array<double, 2>> vertices;      ///< current [length]
  std::vector<std::array<double, 2>> displacement;  ///< per vertex, current - initial [length]
  std::array<double, 3> stress{};                   ///< (sigma_x, sigma_y, tau_xy) [stress]
  std::array<double, 3> velocity{};                 ///< (vx, vy [length/time], omega [1/time])
  int material = 0;
  bool fixed = false;
};

/// A VTK XML PolyData file (.vtp, ASCII) of the blocks at one time.
std::string vtk_polydata(const std::vector<FrameBlock>& blocks);

/// A ParaView collection (.pvd) listing (time, file) frames.
std::string vtk_collection(const std::vector<std::pair<double, std::string>>& frames);

/// Reads the polygons back from a .vtp written by vtk_polydata (for `rheodda plot`):
/// per block, its current vertices and per-vertex displacement.
std::vector<FrameBlock> read_vtk_polydata(const std::string& path);

/// 64-bit FNV-1a hash of bytes (scene identity in checkpoints).
std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t h = 1469598103934665603ull);

}  // namespace rheodda::scene
