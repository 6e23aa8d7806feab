#pragma once
// Running another program as a separate process (no shell): its standard input from a buffer, its
// standard output and error captured. Used where emoface talks to a tool it must not link (the
// espeak-ng program, which is GPL-3.0: a separate process keeps emoface's libraries MIT).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::core {

struct ProcessResult {
  int exit_code = 0;  ///< the program's exit status; 128 + signal number if it was killed
  std::string out;    ///< everything it wrote to standard output
  std::string err;    ///< everything it wrote to standard error
};

struct ProcessOptions {
  /// Largest standard output accepted, bytes (the program is killed beyond it), > 0.
  std::size_t max_output = std::size_t{1} << 30;
};

/// Runs argv[0] (looked up on PATH by posix_spawnp; no shell, so arguments are never interpreted)
/// with `input` on its standard input. Throws InvalidInput for an empty argv or an argument with a
/// NUL byte, IoError if the program cannot be started (message names it) or its output exceeds
/// max_output. A non-zero exit status is not an error here: the caller reads exit_code.
ProcessResult run_process(const std::vector<std::string>& argv, std::string_view input = {},
                          const ProcessOptions& options = {});

}  // namespace emoface::core
