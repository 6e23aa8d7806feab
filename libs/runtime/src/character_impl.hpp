#pragma once
// Private: the state of a runtime::Character (character.cpp runs it, io.cpp snapshots it).
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "emoface/bridge/landmark_fit.hpp"
#include "emoface/channels/dominance.hpp"
#include "emoface/channels/speech.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "emoface/mindmotion/live.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/parlee/agent.hpp"
#include "emoface/runtime/character.hpp"
#include "emoface/runtime/streaming.hpp"

namespace emoface::runtime {

namespace ch = emoface::channels;

struct Character::Impl {
  CharacterConfig config;
  std::size_t lookahead = 0;
  // emotion source
  std::unique_ptr<parlee::Domain> domain;
  std::unique_ptr<parlee::Agent> agent;
  std::vector<parlee::Event> parlee_log;
  parlee::EmotionVector occ_last{};
  parlee::EmotionVector phi{};
  double t_last = 0.0;
  std::unique_ptr<mindmap::World> world;
  std::vector<mindmap::Event> mind_log;
  std::array<std::optional<std::size_t>, 6> mood_node;
  std::array<double, 6> direct{};
  double direct_time = 0.0;
  // mapping and display
  fuzzyexpr::Engine engine;
  bool shown_any = false;
  std::array<double, 6> shown{};
  // channels
  StreamingChannel emotion, blinks, gaze, head;
  std::uint64_t chunks = 0;
  ch::VisemeSet visemes = ch::default_viseme_set();
  std::vector<std::string> lip_params;
  struct Utt {
    double start = 0, end = 0;  // of the padded segments
    std::vector<ch::LipSegment> segs;
    std::unique_ptr<ch::Coarticulation> co;
    std::vector<int> col;  // lip_params index → co parameter (-1: absent)
  };
  std::vector<Utt> utts;
  std::shared_ptr<const ch::SpeechSynthesizer> synth;
  // mixing
  StreamingMixer mixer;
  std::array<std::vector<double>, ch::kChannelCount> raw;
  double time = 0.0;
  std::vector<std::array<double, 6>> esv_ring;
  std::array<double, 6> esv_out{};
  std::vector<double> params_out;
  // engine outputs (faceweights), built on first use
  std::unique_ptr<faceweights::Mapper> arkit, facs;
  std::vector<double> arkit_out, facs_out;
  std::size_t arkit_frame = std::numeric_limits<std::size_t>::max();
  std::size_t facs_frame = std::numeric_limits<std::size_t>::max();
  // face
  std::unique_ptr<muscles::FaceSolver> solver;
  muscles::Deformation deformation;
  muscles::DeformWorkspace workspace;
  std::size_t deformed_frame = std::numeric_limits<std::size_t>::max();
  // MindMotion: the live character and its fitter (declared after the face they may fit on)
  std::unique_ptr<muscles::FaceSolver> fit_solver;  // default face, when the character has none
  std::unique_ptr<bridge::LandmarkFitter> fitter;
  std::unique_ptr<mindmotion::LiveCharacter> live;
  std::vector<std::size_t> live_cols;  // emotion-channel parameter i → index in live->parameters()
  std::vector<double> live_prev,
      live_cur;                  // display values of the previous and current graph frame
  std::uint64_t live_frame = 0;  // live->frames() when live_cur was taken (0: none)

  explicit Impl(CharacterConfig c);
  void make_live();
  void advance_live(double t);
  void make_agent();
  void build_utt(Utt& u) const;
  std::array<double, 6> esv_at(double t);
  void generate_chunks(double t);
  void raw_frame();
  EventResult emotions_event(const std::array<double, 6>& e, const std::array<bool, 6>& given,
                             bool replace);
  EventResult parlee_event(parlee::Event e, bool log);
  EventResult mind_event(mindmap::Event e, bool log);
};

}  // namespace emoface::runtime
