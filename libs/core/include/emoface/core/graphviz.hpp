#pragma once
// Graphviz DOT helpers shared by the libraries that draw graphs (mind maps, motion graphs): quoting
// of IDs and labels, and rendering DOT text to SVG/PNG/PDF through the `dot` program (Debian
// `graphviz`, scripts/setup.sh), as core/video.hpp does with ffmpeg. No Graphviz library is linked.
#include <string>
#include <string_view>

namespace emoface::core {

/// `text` as a DOT double-quoted string ("…" with \" and \\ escaped, newlines as \n).
std::string dot_quote(std::string_view text);

/// True if `binary -V` runs (Graphviz installed).
bool graphviz_available(const std::string& binary = "dot");

/// Renders `dot` with `binary -T<format>` into `path`; the format comes from the extension (.svg,
/// .png, .pdf). Written atomically (a temporary file beside `path`, renamed on success). Throws
/// InvalidInput for another extension, IoError when the program is missing or fails (its first
/// error line quoted).
void render_dot(std::string_view dot, const std::string& path, const std::string& binary = "dot");

/// DOT text to `path`: rendered by render_dot for .svg, .png and .pdf, written as text otherwise
/// (atomically; "-" = standard output). The one writer of `mgraph dot` and `mindmap dot`.
void write_dot(std::string_view dot, const std::string& path, const std::string& binary = "dot");

}  // namespace emoface::core
