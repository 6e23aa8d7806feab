#pragma once
// emoface::runtime::Character — one animated character for a game engine or any real-time host,
// updated frame by frame (issue 16). It owns
//   an emotion source: direct emotion input, a ParleE agent (thesis ch. 5), a mind map (paper
//   §6) or a mind map with a motion graph (issue 19 item 5: the mood's actions played as
//   synthesized motion by mindmotion::LiveCharacter instead of fuzzy displays), the fuzzy mapper
//   (thesis ch. 6: ESV → FMCV → 35 face parameters), the channels of thesis
//   ch. 4 in streaming form (runtime/streaming.hpp): emotion displays (channel 4), speech visemes
//   (channel 2), blinks (1), gaze (5) and head (6) noise, mixed with a bounded look-ahead (a fixed
//   output latency ≤ 0.3 s), optionally a face (any rig: the default face or a rig file, e.g. one
//   fitted by `retarget`) for deformed vertices on request.
//
//   runtime::Character c(runtime::parse_character_config(json_text));
//   c.push_event(R"({"emotions": {"happiness": 0.9}})");
//   c.speak("Hello there!");
//   for (;;) { c.update(1.0 / 60); use(c.parameters()); }   // 42 values,
//   muscles::parameter_names()
//
// Time: update(dt) advances the input clock by dt seconds; the outputs (emotions(), parameters(),
// vertices()) are those of output_time() = the last internal frame mixed, `latency()` seconds
// behind the input clock. Events and speech act at the input clock. Emotion decay is per second,
// ParleE's own (parlee::decayed, §5.6.3): a thesis per-step factor Φ applies over Δt seconds as
// Φ^(Δt/step_seconds), slower at low intensity (EmotionParams::low_intensity_rate), step_seconds
// being the length of one thesis step (one match minute in ch. 7 = 1 s of animation by default;
// it overrides the agent's emotions.step_seconds and time_unit_seconds: agent event times are
// input-clock seconds / step_seconds); with events step_seconds apart it is exactly the agent's
// per-minute update (tested). Determinism: the same config (seed), events and update steps give
// bit-identical outputs; snapshot() captures the whole state as JSON and restore_character()
// continues bit-identically (tested). Not thread-safe: one thread per Character (different
// Characters are independent).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/channels/dominance.hpp"
#include "emoface/channels/generators.hpp"
#include "emoface/channels/mixer.hpp"
#include "emoface/channels/speech.hpp"
#include "emoface/facemesh/mesh.hpp"
#include "emoface/mindmap/mind_map.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/parlee/agent.hpp"

namespace emoface::runtime {

enum class SourceKind { Direct, Parlee, MindMap, MindMotion };
/// "direct", "parlee", "mindmap", "mindmotion"
std::string_view to_string(SourceKind kind) noexcept;
SourceKind source_kind_from_string(std::string_view name);  ///< throws InvalidInput

/// The MindMotion source (a live mind-map character, mindmotion::LiveCharacter): the map's mood
/// chooses actions whose expression labels are synthesized by a motion graph, frame by frame.
struct MotionSourceOptions {
  /// A weight-space ARKit-52 graph (parameters through the exact ARKit mapping) or a 2D landmark
  /// graph of iBUG-68 ids (parameters by the landmark fit on the character's face, or on the
  /// default face without one). Shared: characters may use one graph.
  std::shared_ptr<const motiongraph::MotionGraph> graph;
  /// The file `graph` was read from; "" = set in code (format_character_config writes it inline).
  std::string graph_file;
  bool variation = true;             ///< §5.1 variation (duration, node replacement, peak choice)
  double hint_path_fraction = 0.35;  ///< mood-decay hints play this leading part, (0, 1]
  void validate() const;             ///< throws InvalidInput naming the field (source.graph...)
};

/// How emotions become emotion displays (channel 4): the displayed ESV follows the felt one; a new
/// display (held until the next takes over, §4.5.2 concatenation) starts when an entry has moved by
/// more than `tolerance` since the last display.
struct DisplayOptions {
  double onset = 0.4;       ///< Do, s, (0, 5]
  double offset = 0.8;      ///< Dr, s, (0, 5]
  double tolerance = 0.02;  ///< [0, 1)
  void validate() const;
};

struct CharacterOptions {
  double fps = 60.0;  ///< internal frame rate, [10, 1000]
  double lookahead =
      0.3;  ///< mixer look-ahead = output latency, s, [0, 0.3] (rounded up to frames)
  std::uint64_t seed = 1;  ///< blinks, gaze and head noise (and the agent's own seed stays its own)
  DisplayOptions display;
  bool blinks = true;
  bool gaze_noise = true;
  bool head_noise = true;
  channels::BlinkOptions blink;
  channels::NoiseOptions gaze = channels::default_gaze_noise();
  channels::NoiseOptions head = channels::default_head_noise();
  double chunk_seconds = 10.0;  ///< blinks/noise are generated this far ahead, s, [1, 600]
  channels::MixOptions mix;
  channels::CoarticulationOptions coarticulation;
  double silence_pad = 0.2;        ///< silence viseme before and after each utterance, s, (0, 2]
  channels::SpeechOptions speech;  ///< the espeak-ng program (speak(text) without a synthesizer)
  /// Seconds per thesis step for the per-step decay constants (ParleE), (0, 3600]: the agent's
  /// emotions.step_seconds and time_unit_seconds are set to it (agent event times are input-clock
  /// seconds / step_seconds, thesis steps).
  double step_seconds = 1.0;
  /// Direct source: fraction of each emotion left after one second, (0, 1] (1 = held until
  /// changed).
  double direct_decay_per_second = 1.0;
  void validate() const;  ///< throws InvalidInput naming the field
};

struct CharacterConfig {
  SourceKind source = SourceKind::Direct;
  std::string domain_text;     ///< Parlee: domain (thesis or PPDDL text)
  parlee::AgentConfig agent;   ///< Parlee
  mindmap::MindMap map;        ///< MindMap, MindMotion: the character's map
  MotionSourceOptions motion;  ///< MindMotion
  CharacterOptions options;
  /// Face for vertices(): "" = none, "default" = the built-in default face (the rigged MakeHuman
  /// head), "generic" = the procedural generic face, otherwise a rig file path.
  std::string face;
  void validate() const;
};

/// Outcome of push_event: applied, or reported and skipped (the character is unchanged).
struct EventResult {
  bool applied = false;
  std::string message;  ///< why it was skipped; empty when applied
};

class Character {
 public:
  explicit Character(CharacterConfig config);
  ~Character();
  Character(Character&&) noexcept;
  Character& operator=(Character&&) noexcept;
  Character(const Character&) = delete;
  Character& operator=(const Character&) = delete;

  /// One event as JSON: {"emotions": {"happiness": 0.9, ...}} (direct source: sets the named
  /// emotions; "replace": true zeroes the others), {"action": "(shot oteam)", "outcome": "goal",
  /// "feedback": 0.5} (ParleE), {"stimulus": "gift", "source": "", "weights": {"happiness": 0.8}}
  /// (mind map). Malformed JSON, a kind the source does not take, or an event the model does not
  /// allow (not applicable, unknown stimulus) is reported and skipped, never fatal.
  EventResult push_event(std::string_view event_json);
  EventResult push_emotions(const std::array<double, 6>& esv, bool replace = true);  ///< ESV order
  EventResult push_parlee_event(const parlee::Event& event);  ///< event.time is ignored
  EventResult push_stimulus(const mindmap::Event& event);     ///< event.time is ignored

  /// Speaks `text` with the synthesizer (default: the espeak-ng program with options.speech, run in
  /// this thread, tens of ms). Starts at the input clock or when the previous utterance ends.
  /// Returns the utterance and writes its start time (input clock, s) to `start`: play its samples
  /// then + latency() on the host's audio clock. Throws InvalidInput/IoError from the synthesizer.
  channels::Utterance speak(std::string_view text, double* start = nullptr);
  /// Speaks an utterance with its own timing (e.g. external timings, channels/timing_io.hpp).
  double speak(const channels::Utterance& utterance);
  void set_synthesizer(std::shared_ptr<const channels::SpeechSynthesizer> synthesizer);

  /// Advances the input clock by dt seconds (finite, >= 0, <= 3600) and mixes every frame due.
  void update(double dt);

  double input_time() const noexcept;
  double output_time()
      const noexcept;               ///< time of the current outputs, s (0 before the first frame)
  double latency() const noexcept;  ///< lookahead frames / fps, s
  /// Basic emotions at output_time(), ESV order (sadness happiness anger fear disgust surprise).
  const std::array<double, 6>& emotions() const noexcept;
  /// The face parameters at output_time(), muscles::parameter_names() order (42 entries).
  const std::vector<double>& parameters() const noexcept;
  static const std::vector<std::string>& parameter_names();
  /// The 52 ARKit blend-shape weights at output_time() (faceweights' built-in "arkit" set, in the
  /// order of arkit_names()), computed on request and cached per frame.
  const std::vector<double>& arkit();
  static const std::vector<std::string>& arkit_names();
  /// FACS action-unit intensities at output_time() (faceweights' built-in "facs" set, in the order
  /// of facs_names()), computed on request and cached per frame.
  const std::vector<double>& facs();
  static std::vector<std::string> facs_names();
  /// ParleE: the 21 OCC intensities at the input clock (decayed); other sources: empty.
  std::vector<double> occ_emotions() const;

  bool has_face() const noexcept;
  /// The deformed face at output_time() (#V by 3, m), computed on request and cached per frame.
  /// Throws InvalidInput if the character has no face.
  const facemesh::Vertices& vertices();
  const facemesh::Mesh& mesh() const;  ///< neutral mesh (faces, UVs); throws without a face

  /// The whole state as an "emoface.character_state" JSON document (config included). Throws
  /// InvalidInput for the mindmotion source (its motion player's state is not serialisable yet).
  std::string snapshot() const;
  const CharacterConfig& config() const noexcept;

  struct Impl;

 private:
  explicit Character(std::unique_ptr<Impl> impl);
  friend Character restore_character(std::string_view snapshot_json, const std::string& file);
  std::unique_ptr<Impl> impl_;
};

/// A Character from snapshot() output; continuing it gives bit-identical outputs to the original.
/// Throws FormatError (file + JSON pointer) for a malformed or foreign document.
Character restore_character(std::string_view snapshot_json, const std::string& file = "<snapshot>");

/// Reads an "emoface.character" config (docs/runtime.md): {"format": "emoface.character",
/// "version": "1.0", "source": {"kind": "direct"} | {"kind": "parlee", "domain": TEXT |
/// "domain_file": PATH, "agent": {...} | "agent_file": PATH} | {"kind": "mindmap", "map": {...} |
/// "map_file": PATH} | {"kind": "mindmotion", "map" | "map_file", "graph": {...} | "graph_file":
/// PATH, "variation": BOOL, "hint_path_fraction": X}, "face": "default" | PATH, "fps", "lookahead",
/// "seed", "display": {...}, "blinks", "gaze_noise", "head_noise", "step_seconds",
/// "direct_decay_per_second", "speech":
/// {"voice", "rate", "pitch", "program"}, "mix": {"dmin_plus", "dmin_minus"}}. Relative paths are
/// resolved against `base_dir`. Throws FormatError naming the field.
CharacterConfig parse_character_config(std::string_view json_text,
                                       const std::string& file = "<config>",
                                       const std::string& base_dir = "");
CharacterConfig read_character_config(const std::string& path);
/// The config as JSON (inline domain/agent/map), parse_character_config gives it back.
std::string format_character_config(const CharacterConfig& config);

/// A mindmotion config from files: the motion graph (motiongraph::read_graph) and the mind map
/// (mindmap::read_mind_map); every other field from `base`, whose source must be the default
/// (direct). Throws IoError/FormatError naming the file, InvalidInput for a source in `base` or a
/// graph that does not fit the map (CharacterConfig::validate()).
CharacterConfig mindmotion_config(const std::string& graph_file, const std::string& map_file,
                                  CharacterConfig base = {});

}  // namespace emoface::runtime
