#pragma once
// Files of the motiongraph library. JSON documents carry the emoface envelope and are read through
// core::JsonReader (unknown fields: errors in 1.0 documents, ignored in newer minors):
//   emoface.landmark_database 1.0 — Database (see docs/motiongraph.md for the fields)
//   emoface.landmark_layout   1.0 — LandmarkLayout (data/motiongraph/layout_ibug68.json)
//   emoface.motion_graph      1.0 — MotionGraph
// CSV landmark databases: header "sequence,subject,label,frame,x0,y0[,z0],x1,..." one row per
// frame. CK+ directory layout reader: Landmarks/<S>/<seq>/*_landmarks.txt +
// Emotion/<S>/<seq>/*_emotion.txt.
#include <string>
#include <string_view>
#include <vector>

#include "emoface/core/text.hpp"
#include "emoface/motiongraph/database.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/layout.hpp"

namespace emoface::motiongraph {

/// What a database reader does with a bad sequence (a record): throw (Stop, the default) or leave
/// the sequence out and report it (Skip). Errors outside sequences (envelope, header, dimensions)
/// always throw. The one OnError of emoface (core/text.hpp: to_string, on_error_from_string).
using core::on_error_from_string;  // "stop" | "skip" → OnError; nothing otherwise
using core::OnError;
using core::to_string;

/// Sequences a reader skipped, one message each naming the file and line or JSON pointer.
struct ReadReport {
  std::vector<std::string> skipped;
};

std::string database_to_json(const Database& db);
Database parse_database_json(std::string_view text, const std::string& file = "<memory>",
                            OnError on_error = OnError::Stop, ReadReport* report = nullptr);
std::string database_to_csv(const Database& db);
/// `frame_rate` is not stored in CSV; pass it. With Skip, a bad row drops its whole sequence.
Database parse_database_csv(std::string_view text, const std::string& file = "<memory>",
                            double frame_rate = 30.0, OnError on_error = OnError::Stop,
                            ReadReport* report = nullptr);
/// By extension: ".csv" = CSV, anything else JSON. Outputs are written atomically.
Database read_database(const std::string& path, double csv_frame_rate = 30.0, OnError on_error = OnError::Stop,
                       ReadReport* report = nullptr);
void write_database(const std::string& path, const Database& db);

std::string layout_to_json(const LandmarkLayout& layout);
LandmarkLayout parse_layout_json(std::string_view text, const std::string& file = "<memory>");
LandmarkLayout read_layout(const std::string& path);

std::string graph_to_json(const MotionGraph& graph);
MotionGraph parse_graph_json(std::string_view text, const std::string& file = "<memory>");
MotionGraph read_graph(const std::string& path);
void write_graph(const std::string& path, const MotionGraph& graph);

struct CkPlusOptions {
  /// Sequences without an Emotion file: skipped (default) or kept with label neutral.
  bool keep_unlabelled = false;
  double frame_rate = 30.0;
  /// A sequence with a bad landmark or emotion file: throw (Stop) or skip it and report (Skip).
  OnError on_error = OnError::Stop;
};

/// Reads the CK+ layout under `root` (directories Landmarks/ and Emotion/). CK+ emotion codes:
/// 0 neutral, 1 anger, 2 contempt, 3 disgust, 4 fear, 5 happy, 6 sadness, 7 surprise. Frames are
/// ordered by file name. Throws IoError / FormatError (file, line) on bad content.
Database read_ck_plus(const std::string& root, const CkPlusOptions& options = {},
                      ReadReport* report = nullptr);

/// The per-file parsers of the CK+ reader (exposed for tests and fuzzing): whitespace-separated
/// finite numbers, `per_line` on every non-empty line; FormatError naming `file`, line and column.
std::vector<std::vector<double>> parse_ck_numbers(std::string_view text, const std::string& file,
                                                  std::size_t per_line);
/// One CK+ landmark file (x y per line) → n by 2 pose; `expected` landmarks (0 = any, >= 1).
Pose parse_ck_landmarks(std::string_view text, const std::string& file, std::size_t expected = 0);
/// One CK+ emotion file (one code 0..7) → label.
Label parse_ck_emotion(std::string_view text, const std::string& file);

}  // namespace emoface::motiongraph
