#pragma once
// The mgraph subcommands: glue between parsed arguments and the motiongraph library.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/motiongraph/synthetic.hpp"

namespace emoface::mgraph {

struct Args {
  std::string db, ckplus, layout, graph, out = "-", sheet, plot, frames_dir, idle_label;
  std::string model = "face", projection = "perspective", video, requests, samples_csv;
  std::string shard = "0/1", on_error = "stop";
  double camera_distance = 1.0, fps = 0.0;
  int video_width = 640, video_height = 490;
  bool no_align = false, no_clean = false, no_reverse = false, vary = false, no_sigmoid = false;
  double lambda = 0.5, sample_threshold = -1.0, merge_threshold = -1.0, target_compression = -1.0;
  double replace = 0.0, hint = 1.0, idle_after = 0.0, duration = 4.0, hop_interval = 1.0, dwell = 0.4;
  double noise = 0.4;
  std::uint64_t seed = 1;
  std::size_t per_label = 10, subjects = 20, curve = 0;
  int columns = 8, every = 1, cell_width = 200;
  std::vector<std::string> labels;
  std::vector<double> compressions{0.5753, 0.78, 0.90}, thresholds;
  // capture, capture-example
  std::vector<std::string> openface, mediapipe;
  std::string label_column, labels_file, format = "openface";
  bool use_3d = false, no_stabilise = false, no_trim = false;
  double min_confidence = 0.75, image_width = 640.0, image_height = 490.0;
  std::string region;
  std::size_t depth = 0;
  bool edge_weights = false;
  std::size_t max_gap = 3, min_frames = 10, max_frames = 30, rest_frames = 12, hold_frames = 6, max_takes = 0;
  // weight space (issue 19 item 2)
  std::string space = "landmarks", livelink_out, params_out;
  std::vector<std::string> livelink;
  double weight_noise = 0.01, timecode_fps = 60.0;
  bool raw = false;
};

// The subcommands registered by add_analysis_commands (options.cpp); main.cpp the others.
struct AnalysisCommands {
  CLI::App *eval, *capture, *example, *dot;
};
AnalysisCommands add_analysis_commands(CLI::App& app, Args& a);
/// --db/--ckplus/--layout and preprocessing options (build, eval).
void add_source_options(CLI::App* c, Args& a);

// Glue shared by the subcommands (commands.cpp).
motiongraph::OnError on_error(const Args& a);
/// The skipped records on stderr, then "<n> <what> skipped".
void print_skipped(const motiongraph::ReadReport& report, const char* what = "record(s)");
motiongraph::Database load_database(const Args& a);
/// `clean` = false gives the raw samples (eval --raw).
motiongraph::PreparedDatabase prepare(const Args& a, const motiongraph::Database& db, bool clean,
                                      bool quiet = false);
motiongraph::GraphOptions graph_options(const Args& a, int dimensions);
std::unique_ptr<motiongraph::LandmarkModel> landmark_model(const Args& a);

int generate(const Args& a);
int build(const Args& a);
int synth(const Args& a);
int idle(const Args& a);
int eval(const Args& a);
int capture(const Args& a);
int capture_example(const Args& a);
int dot(const Args& a);

}  // namespace emoface::mgraph
