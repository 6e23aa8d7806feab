#pragma once
// Obie end to end (thesis chapter 7, Fig. 7.1; paper Fig. 1): match events → emotions (parlee) →
// emotion displays (fuzzyexpr FMCV through the channels' emotion channel) + utterances spoken through
// espeak-ng in the lip channel + blinks, gaze and head noise (channels) → parameter tracks → deformed
// meshes (muscles) → animated glTF frames, rendered frames (facemesh) → a FrameSink (e.g. MP4 with the
// speech) → charts and the key-moment sheet.
//
//   obie::MatchScript match = obie::read_match_file("data/obie/match_7_4.json");
//   parlee::AgentConfig agent = parlee::read_agent_file("data/parlee/agents/neutral.json");
//   facemesh::Face face = facemesh::make_default_face();
//   obie::VideoSink video("out/obie.mp4", "out/speech.wav");
//   obie::ObieResult r = obie::run_obie(match, agent, face, obie::ObieOptions{}, progress, &video);
//
// The library never prints; progress goes through the callback. Deterministic: the same inputs and
// seed give the same result (speech runs the espeak-ng program, a fresh process per utterance,
// channels/speech.hpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/channels/script.hpp"
#include "emoface/channels/speech.hpp"
#include "emoface/channels/talking_head.hpp"
#include "emoface/core/image.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/obie/match.hpp"
#include "emoface/obie/time_map.hpp"
#include "emoface/obie/utterances.hpp"
#include "emoface/parlee/agent.hpp"
#include "emoface/parlee/chart.hpp"

namespace emoface::obie {

/// How timeline steps become emotion displays in channel 4 (thesis §4.2, §4.4): each step's ESV is
/// held from its event until the next display takes over, with onset Do and offset Dr.
struct DisplayOptions {
  double onset = 0.4;            ///< Do, s, (0, 5]
  double offset = 0.8;           ///< Dr, s, (0, 5]
  double reaction_delay = 0.15;  ///< s from the event to the start of the display, [0, 5]
  double min_intensity = 0.03;   ///< steps whose largest ESV entry is below this show no display, [0, 1)
  double merge_tolerance = 0.02; ///< a step whose ESV differs by less (every entry) extends the previous display, [0, 1)
  /// Reactions: when an emotion rises by at least `reaction_rise` at a step, the display shows the
  /// risen emotions with the others scaled by `background_scale` for `reaction_hold` seconds, then the
  /// full ESV again. Without it a saturated, long-held emotion (fear through the first 40 minutes of
  /// §7.4) would hide every new one in the fuzzy mode selection; see docs/obie.md, deviations.
  bool reactions = true;
  double reaction_rise = 0.15;   ///< (0, 1]
  double reaction_hold = 3.0;    ///< s, (0, 60]
  double background_scale = 0.0; ///< [0, 1]
  double reaction_gain = 1.5;    ///< risen emotions are shown ×gain (clamped to 1) during the reaction, [1, 4]
  /// §4.1 "the smile may also have higher priority than the visual speech when the subject is too
  /// happy": a display showing happiness at or above this has priority 1 (above speech, 2), [0, 2];
  /// above 1 = never.
  double smile_outranks_speech = 0.9;
  void validate() const;
};

struct ObieOptions {
  std::uint64_t seed = 1;          ///< utterance choice, blinks, gaze and head noise
  double fps = 25.0;               ///< frames per second of tracks and video, [1, 120]
  TimeMapOptions time;             ///< match minutes → animation seconds
  DisplayOptions display;
  UtteranceSet utterances = default_utterances();
  bool speech = true;              ///< false: no utterances, silent audio of the right length
  channels::SpeechOptions voice;   ///< espeak-ng voice, rate, pitch
  bool blinks = true;
  bool gaze_noise = true;
  bool head_noise = true;
  muscles::SolverOptions solver;
  int width = 320;                 ///< rendered frame width, pixels, [16, 4096]
  int height = 384;                ///< rendered frame height, pixels, [16, 4096]
  facemesh::View view = facemesh::View::Front;
  bool render_frames = true;       ///< false: deform and render only the glTF and key-moment frames
  double gltf_fps = 4.0;           ///< morph-target frames per second of the glTF, [0, fps] (0 = none)
  /// s after a key moment's animation time: the frame shown, [0, 30]. 0.6 = reaction delay 0.15 +
  /// onset 0.4 + 0.05: the event's own display at its apex, before the next minute's event (1 s
  /// later) replaces it (at 1.2 s the 40.5' goal showed the 41' display, without the surprise).
  double key_moment_delay = 0.6;
  int threads = 0;                 ///< deformation/rendering threads, [0, 64]; 0 = hardware concurrency (≤ 8)
  void validate() const;           ///< throws InvalidInput naming the field
};

/// Progress of a long stage: `done` of `total` units (frames, steps).
struct Progress {
  std::string_view stage;
  std::size_t done = 0;
  std::size_t total = 0;
};
using ProgressCallback = std::function<void(const Progress&)>;

struct StageTiming {
  std::string stage;    ///< "emotions", "displays", "speech+channels", "frames", "glTF", …
  double seconds = 0.0; ///< wall clock
};

struct Goal {
  double minute = 0.0;
  std::string side;      ///< domain side that scored
  std::string team;      ///< its display name
  int for_score = 0;     ///< score after the goal
  int against_score = 0;
};

struct Peak {
  std::string emotion;   ///< ESV name
  double value = 0.0;    ///< largest basic intensity over the match
  double minute = 0.0;   ///< first minute it is reached
};

struct KeyMomentFrame {
  KeyMoment moment;
  double time = 0.0;              ///< animation seconds of the frame
  std::size_t frame = 0;          ///< frame index: round(time·fps), clamped to the last frame
  std::array<double, 6> esv{};    ///< felt: basic emotions of the last step at or before the moment
  std::array<double, 6> shown{};  ///< displayed: intensities of the emotion display active at `time`
  core::Image image;              ///< rendered at options.width × height
};

struct ObieResult {
  std::string agent_name;
  std::vector<parlee::StepRecord> timeline;   ///< step 0 = before kick-off, then one per event
  TimeMap time_map;
  std::vector<double> step_seconds;           ///< animation time of each timeline record
  channels::Script script;                    ///< emotion displays and utterances as channel input
  std::vector<PlannedUtterance> utterances;
  channels::TalkingHead head;                 ///< channel timeline, tracks (fps, 42 parameters), audio
  std::size_t frames = 0;                     ///< == head.tracks.frames()
  std::vector<facemesh::Vertices> gltf_frames;
  std::vector<double> gltf_times;             ///< seconds, strictly increasing
  std::vector<KeyMomentFrame> key_frames;
  std::size_t frames_rendered = 0;            ///< frames passed to the sink
  std::vector<Goal> goals;
  std::array<Peak, 6> peaks;                  ///< ESV order
  std::vector<StageTiming> timings;
  double seconds() const noexcept { return frames == 0 ? 0.0 : static_cast<double>(frames - 1) / head.tracks.fps; }
};

/// Receives the rendered frames in order. begin() is called once the tracks and audio exist.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  virtual void begin(const ObieResult& result, int width, int height, double fps) = 0;
  virtual void frame(const core::Image& image) = 0;
  virtual void finish() = 0;
};

/// Writes the speech as WAV (`wav_path`, atomically) in begin(), then the frames as a video with that
/// audio through core::VideoWriter (container by extension; comment = emoface::kGenerator).
/// Nothing is left at `video_path` unless finish() succeeds.
class VideoSink : public FrameSink {
 public:
  VideoSink(std::string video_path, std::string wav_path, std::string ffmpeg = "ffmpeg");
  ~VideoSink() override;
  void begin(const ObieResult& result, int width, int height, double fps) override;
  void frame(const core::Image& image) override;
  void finish() override;

 private:
  std::string video_path_, wav_path_, ffmpeg_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// ---- the stages, usable one by one -------------------------------------------------------------

/// Stage 1 (thesis ch. 5, §7.4): runs the agent over the match events. Record 0 is the initial
/// state. An event that is not applicable throws FormatError naming `match_file` and /events/i.
std::vector<parlee::StepRecord> run_match(const MatchScript& match, const parlee::AgentConfig& agent,
                                          const std::string& match_file = "<match>");

/// Stage 2: emotion displays (channel 4) from the timeline; records[k] happens at step_seconds[k].
/// Displays are strictly ordered (Ts and Te increasing, thesis §4.5.2).
std::vector<channels::EmotionItem> emotion_displays(const std::vector<parlee::StepRecord>& records,
                                                    const std::vector<double>& step_seconds,
                                                    const DisplayOptions& options);

/// fuzzyexpr's default engine as a channels::EmotionMapper: ESV → FMCV (thesis ch. 6) → both sides.
channels::EmotionMapper fuzzy_emotion_mapper();

/// What the face shows for displayed intensities, as the fuzzy system selects it (thesis §6.5):
/// "happiness 1.00 + surprise 0.56" in Blend mode, "sadness 0.93" in Single mode, "neutral" when
/// every intensity is below 0.03. Used for the key-moment captions and summary.json.
std::string expression_text(const std::array<double, 6>& shown);

/// Frame index shown for a key moment: round((time_map.seconds(minute) + delay)·fps), clamped to
/// [0, frames − 1].
std::size_t key_moment_frame(const TimeMap& time_map, double minute, double delay, double fps, std::size_t frames);

/// Goals from the events (an event whose outcome is in match.goal_outcomes, scored by the team whose
/// side appears as an argument of its action) with the running score.
std::vector<Goal> find_goals(const MatchScript& match);

/// Runs everything. Throws InvalidInput for bad options or inputs, FormatError for a script that
/// does not fit the domain, Error if espeak-ng or the sink fails.
ObieResult run_obie(const MatchScript& match, const parlee::AgentConfig& agent, const facemesh::Face& face,
                    const ObieOptions& options, const ProgressCallback& progress = {}, FrameSink* sink = nullptr,
                    const std::string& match_file = "<match>");

// ---- outputs ------------------------------------------------------------------------------------

/// The emotion chart of the run (fear, happiness, surprise, sadness over match minutes, Figs.
/// 7.4–7.8) with the goals marked.
core::Image emotion_chart(const ObieResult& result);
/// The key-moment frames side by side, each captioned with its minute, label and strongest emotion.
core::Image key_moment_sheet(const ObieResult& result);
/// Timeline NDJSON: parlee's timeline line of every record plus "agent" and "anim_time" (seconds).
std::string format_timeline(const ObieResult& result);
/// `emoface.obie.summary` 1.0 JSON: match, agent, goals, peaks, utterances, key moments, frames,
/// durations, per-stage timings (`timings` = false leaves them out, for byte-comparable files).
std::string format_summary(const ObieResult& result, const MatchScript& match, bool timings = true);

}  // namespace emoface::obie
