#pragma once
// A set of output files written all or nothing (issue 18, item 4): a CLI that writes a database, a
// contact sheet, a plot and a directory of frames stages them all first, and only when every one
// is on disk (as a temporary file beside its target) are they renamed into place. A failure before
// commit() — an unwritable directory, a full disk, an exception while computing a later output —
// leaves no target touched: the temporary files and the directories the bundle created go away.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::core {

class OutputBundle {
 public:
  OutputBundle() = default;
  OutputBundle(const OutputBundle&) = delete;
  OutputBundle& operator=(const OutputBundle&) = delete;
  /// Without commit(): removes the staged temporary files and the directories add() created.
  ~OutputBundle();

  /// Stages `content` for `path` now: a temporary file beside it is written, flushed and closed
  /// (missing parent directories are created and remembered). "-" stages standard output, written
  /// by commit() after the files; an existing device or FIFO (/dev/null) is written directly by
  /// commit(), never replaced. Throws IoError (the bundle stays uncommitted) or InvalidInput for
  /// a path staged twice.
  void add(const std::string& path, std::string_view content);
  /// Stages a file the caller writes itself (a video through ffmpeg, a glTF writer that takes a
  /// path): returns a temporary path beside `path`, with the same file name extension, for the
  /// caller to write before commit(), which renames it into place (IoError if it was not written).
  /// Missing parent directories are created as in add().
  std::string stage_path(const std::string& path);
  /// Renames every staged file into place, in the order staged, then writes standard output.
  /// Throws IoError if a rename fails (the files renamed before it stay; the rest are removed).
  void commit();

  std::size_t size() const noexcept { return files_.size() + (stdout_ ? 1 : 0); }
  bool committed() const noexcept { return committed_; }

 private:
  struct Staged {
    std::string target, temp;  // temp empty: a device or FIFO, written directly by commit()
    std::string direct;
  };
  std::vector<Staged> files_;
  std::vector<std::string> created_dirs_;  // deepest last
  std::string stdout_text_;
  bool stdout_ = false;
  bool committed_ = false;
};

}  // namespace emoface::core
