#pragma once
// Files of the motiongraph library. JSON documents carry the emoface envelope:
//   emoface.landmark_database 1.0 — Database (see docs/motiongraph.md for the fields)
//   emoface.landmark_layout   1.0 — LandmarkLayout (data/motiongraph/layout_ibug68.json)
//   emoface.motion_graph      1.0 — MotionGraph
// CSV landmark databases: header "sequence,subject,label,frame,x0,y0[,z0],x1,..." one row per frame.
// CK+ directory layout reader: Landmarks/<S>/<seq>/*_landmarks.txt + Emotion/<S>/<seq>/*_emotion.txt.
#include <string>
#include <string_view>

#include "emoface/motiongraph/database.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/layout.hpp"

namespace emoface::motiongraph {

std::string database_to_json(const Database& db);
Database parse_database_json(std::string_view text, const std::string& file = "<memory>");
std::string database_to_csv(const Database& db);
/// `frame_rate` is not stored in CSV; pass it.
Database parse_database_csv(std::string_view text, const std::string& file = "<memory>",
                            double frame_rate = 30.0);
/// By extension: ".csv" = CSV, anything else JSON. Outputs are written atomically.
Database read_database(const std::string& path, double csv_frame_rate = 30.0);
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
};

/// Reads the CK+ layout under `root` (directories Landmarks/ and Emotion/). CK+ emotion codes:
/// 0 neutral, 1 anger, 2 contempt, 3 disgust, 4 fear, 5 happy, 6 sadness, 7 surprise. Frames are
/// ordered by file name. Throws IoError / FormatError (file, line) on bad content.
Database read_ck_plus(const std::string& root, const CkPlusOptions& options = {});

}  // namespace emoface::motiongraph
