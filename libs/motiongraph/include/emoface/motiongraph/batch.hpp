#pragma once
// Batches of the mgraph CLI as library calls (issue 18, item 4): the synthesis requests file
// (reader/writer pair), chained synthesis from neutral, and the evaluation table as CSV
// (writer/reader pair, with the sums that merge shards). docs/motiongraph.md, "Batches".
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "emoface/core/bundle.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/evaluate.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/motiongraph/synthesis.hpp"

namespace emoface::motiongraph {

// --- synthesis requests: CSV "id,labels", labels separated by ';' ------------------------------

/// One chain of labels synthesized from neutral; its sequences are named "<id>/synth_<k>_<label>".
struct SynthesisRequest {
  std::string id;                   ///< not empty
  std::vector<std::string> labels;  ///< known label names, as written (they name the sequences)
};

/// One record (data line) of a requests file: a request, or the error that makes it bad. A bad
/// record still counts as an item of the batch, so the shards of a file with bad records line up.
struct RequestRecord {
  std::string file;                  ///< the file it came from (names synthesis errors)
  std::size_t line = 0;              ///< 1-based line number
  SynthesisRequest request;          ///< meaningful when !error
  std::optional<FormatError> error;  ///< "FILE:LINE:FIELD: message"
};

/// Reads a requests file: optional '#' lines before the header (the "# emoface x.y.z" stamp), the
/// header "id,labels", then one request per line (blank lines, '#' lines and a repeated header, as
/// in concatenated files, are skipped). Record errors (malformed CSV, wrong field count, empty id,
/// unknown or missing label) are returned in the record; a missing or wrong header or invalid
/// UTF-8 throws FormatError.
std::vector<RequestRecord> parse_requests_csv(std::string_view text, const std::string& file);
std::vector<RequestRecord> read_requests_csv(const std::string& path);
/// The stamp, the header and one line per request; parse_requests_csv reads it back.
std::string requests_to_csv(const std::vector<SynthesisRequest>& requests);

/// Options of one chained animation.
struct ChainOptions {
  SynthesisOptions synthesis;  ///< seed replaced by the chain's seed
  IdleOptions idle;            ///< used when idle_after > 0 (duration = idle_after, seed replaced)
  double idle_after = 0.0;     ///< seconds of idle motion after each transition; 0 = none
};
/// The default options of a graph's space (weight_synthesis_options / weight_idle_options for a
/// weight graph).
ChainOptions chain_options_for(const MotionGraph& graph);

/// One chained animation from neutral: a transition to each label's peak (each sink the next
/// source), idle after each when asked. Sequence ids "<prefix>synth_<k>_<label>" and
/// "<prefix>idle_<k>_<label>" (k counts the sequences of the chain). All labels are checked first
/// (InvalidInput); an empty list is InvalidInput.
std::vector<Sequence> synthesize_chain(const MotionGraph& graph,
                                       const std::vector<std::string>& labels, std::uint64_t seed,
                                       const std::string& prefix, const ChainOptions& options);

/// The requests of records[block.first, block.second), in order; request r (its index in the
/// whole file) uses the seed stream core::derive_seed(seed, r), so a shard computes what the whole
/// run computes for its records. A bad record or a synthesis failure (as FormatError at the
/// record's labels field) throws with OnError::Stop; with Skip its message goes to
/// report->skipped and the batch goes on.
std::vector<Sequence> synthesize_requests(const MotionGraph& graph,
                                          const std::vector<RequestRecord>& records,
                                          std::pair<std::size_t, std::size_t> block,
                                          std::uint64_t seed, const ChainOptions& options,
                                          OnError on_error = OnError::Stop,
                                          ReadReport* report = nullptr);

// --- evaluation table (mgraph eval --csv) --------------------------------------------------------

/// The rows as CSV: the stamp, the header "threshold,compression_percent,nodes,length_diff_mean,
/// length_diff_std,pose_diff_mean,pose_diff_std,samples,distances,length_sum,length_sum2,pose_sum,
/// pose_sum2" (+ ",raw_pose_diff_mean,raw_pose_diff_std,raw_pose_sum,raw_pose_sum2" when the rows
/// have raw comparisons), statistics to 6 significant digits, sums to 17 (exact). InvalidInput if
/// some rows have raw comparisons and others do not.
std::string evaluation_csv(const std::vector<EvaluationRow>& rows);
/// Reads evaluation_csv back (core::CsvTable: stamps, blank lines and repeated headers skipped, so
/// concatenated shard tables read as one list of rows; merge them with merge_rows). Every field is
/// checked (finite numbers, counts as non-negative integers, compression in [0, 100]);
/// FormatError "FILE:LINE:FIELD: message".
std::vector<EvaluationRow> parse_evaluation_csv(std::string_view text, const std::string& file);
std::vector<EvaluationRow> read_evaluation_csv(const std::string& path);

// --- pictures of an animation -------------------------------------------------------------------

/// Which pictures of a landmark animation to make (empty path = none).
struct AnimationPictures {
  std::string sheet;       ///< contact sheet PNG of every `every`-th frame and the last
  std::string plot;        ///< trajectory plot PNG (y of the most moving landmark per region)
  std::string frames_dir;  ///< one PNG per frame, frame_00000.png … (640 × 490)
  std::string video;       ///< .gif/.mp4/.mov/.mkv through ffmpeg (core::VideoWriter)
  int columns = 8, every = 1, cell_width = 200;
  int video_width = 640, video_height = 490;
  double fps = 0.0;  ///< 0: the graph's frame rate
  bool any() const {
    return !(sheet.empty() && plot.empty() && frames_dir.empty() && video.empty());
  }
};

/// Stages the PNGs and the video of `frames` (poses of the graph's reduced landmarks, coloured by
/// region) into `bundle` (the video rendered into a staged path, renamed on commit). InvalidInput
/// for a weight graph (no landmarks to draw) or no frames.
void stage_animation_pictures(core::OutputBundle& bundle, const MotionGraph& graph,
                              const std::vector<Pose>& frames, const AnimationPictures& pictures);

/// The sequences as a database of the graph's reduced landmarks (or weight channels).
Database animation_database(const MotionGraph& graph, std::vector<Sequence> sequences);

// --- databases and tables of a run --------------------------------------------------------------

/// Stages `db` for `path`: CSV for a ".csv" name, else JSON ("-": JSON on standard output).
void stage_database(core::OutputBundle& bundle, const std::string& path, const Database& db);

/// The sequences [block.first, block.second) of `db` (a shard's contiguous block,
/// core::Shard::block), everything else kept. InvalidInput unless first <= second <= size.
Database database_block(Database db, std::pair<std::size_t, std::size_t> block);

/// The frames of a database's contact sheet (mgraph generate --sheet): the first frame of the first
/// sequence (neutral), then the last (peak) frame of the first sequence of each label, labels in
/// the order they first appear. Empty for a database without sequences.
std::vector<Pose> label_peaks(const Database& db);

/// Stages a contact sheet PNG of label_peaks(db) for a 68-landmark iBUG database: landmarks
/// coloured by the regions of default_layout() (the others grey), iBUG contours drawn, cells
/// `cell_width` by 7/8 of it. InvalidInput for a weight database, another landmark count or no
/// sequences.
void stage_peaks_sheet(core::OutputBundle& bundle, const std::string& path, const Database& db,
                       int columns, int cell_width);

/// The mgraph eval table (paper §7): a header, one line per row ("threshold compression % nodes
/// length-diff mean +- std, pose-diff mean +- std", and the raw comparison when the rows have it),
/// then the paper's CK+ figures for comparison. `unit` names the pose unit ("px", "weight").
std::string evaluation_table(const std::vector<EvaluationRow>& rows, const std::string& unit);

}  // namespace emoface::motiongraph
