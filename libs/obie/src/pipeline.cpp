#include "emoface/obie/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <thread>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/video.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/parlee/domain.hpp"

namespace emoface::obie {

namespace {

bool in(double x, double lo, double hi) { return std::isfinite(x) && x >= lo && x <= hi; }

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

constexpr std::array<const char*, 6> kEsvNames = {"sadness", "happiness", "anger", "fear", "disgust", "surprise"};

}  // namespace

void DisplayOptions::validate() const {
  if (!(in(onset, 0, 5) && onset > 0)) throw InvalidInput("display: onset must be in (0, 5] s");
  if (!(in(offset, 0, 5) && offset > 0)) throw InvalidInput("display: offset must be in (0, 5] s");
  if (!in(reaction_delay, 0, 5)) throw InvalidInput("display: reaction_delay must be in [0, 5] s");
  if (!(in(min_intensity, 0, 1) && min_intensity < 1)) throw InvalidInput("display: min_intensity must be in [0, 1)");
  if (!(in(merge_tolerance, 0, 1) && merge_tolerance < 1))
    throw InvalidInput("display: merge_tolerance must be in [0, 1)");
  if (!(in(reaction_rise, 0, 1) && reaction_rise > 0)) throw InvalidInput("display: reaction_rise must be in (0, 1]");
  if (!(in(reaction_hold, 0, 60) && reaction_hold > 0)) throw InvalidInput("display: reaction_hold must be in (0, 60] s");
  if (!in(background_scale, 0, 1)) throw InvalidInput("display: background_scale must be in [0, 1]");
  if (!in(reaction_gain, 1, 4)) throw InvalidInput("display: reaction_gain must be in [1, 4]");
  if (!in(smile_outranks_speech, 0, 2))
    throw InvalidInput("display: smile_outranks_speech must be in [0, 2]");
}

void ObieOptions::validate() const {
  if (!in(fps, 1, 120)) throw InvalidInput("obie: fps must be in [1, 120]");
  time.validate();
  display.validate();
  utterances.validate();
  voice.validate();
  solver.validate();
  if (width < 16 || width > 4096) throw InvalidInput("obie: width must be in [16, 4096] pixels");
  if (height < 16 || height > 4096) throw InvalidInput("obie: height must be in [16, 4096] pixels");
  if (!in(gltf_fps, 0, fps)) throw InvalidInput("obie: gltf_fps must be in [0, fps]");
  if (!in(key_moment_delay, 0, 30)) throw InvalidInput("obie: key_moment_delay must be in [0, 30] s");
  if (threads < 0 || threads > 64) throw InvalidInput("obie: threads must be in [0, 64]");
}

std::vector<parlee::StepRecord> run_match(const MatchScript& match, const parlee::AgentConfig& config,
                                          const std::string& match_file) {
  match.validate();
  config.validate();
  const parlee::Domain domain(parlee::read_domain_files(match.domain_paths()));
  // A match script is authored data: an event Obie's model does not allow is a located error here
  // (`parlee run` skips and reports such events instead, DisallowedEvent::Skip).
  parlee::AgentConfig strict = config;
  strict.on_disallowed = parlee::DisallowedEvent::Stop;
  parlee::Agent agent(domain, strict);
  std::vector<parlee::StepRecord> records{agent.initial_record()};
  const auto events = to_parlee_events(match);
  for (std::size_t i = 0; i < events.size(); ++i) {
    try {
      records.push_back(agent.step(events[i]));
    } catch (const InvalidInput& e) {
      SourceLocation where;
      where.file = match_file;
      where.json_pointer = "/events/" + std::to_string(i);
      throw FormatError(where, e.what());
    }
  }
  return records;
}

std::vector<channels::EmotionItem> emotion_displays(const std::vector<parlee::StepRecord>& records,
                                                    const std::vector<double>& step_seconds,
                                                    const DisplayOptions& options) {
  options.validate();
  if (records.size() != step_seconds.size())
    throw InvalidInput("emotion_displays: one animation time per timeline record is needed");
  for (std::size_t k = 1; k < step_seconds.size(); ++k)
    if (!(step_seconds[k] >= step_seconds[k - 1]) || !std::isfinite(step_seconds[k]))
      throw InvalidInput("emotion_displays: animation times must be finite and non-decreasing");
  // Steps at the same animation time (several events in one minute) collapse into the last of them.
  std::vector<std::size_t> steps;
  for (std::size_t k = 0; k < records.size(); ++k) {
    if (!steps.empty() && step_seconds[k] - step_seconds[steps.back()] < 1e-3) steps.back() = k;
    else steps.push_back(k);
  }
  // Change points: every step, plus the end of each reaction that ends before the next step.
  struct Point {
    double t;
    std::array<double, 6> esv;
  };
  std::vector<Point> points;
  // Reactions, per emotion: an emotion that rose at a step stays "fresh" for reaction_hold seconds;
  // while any emotion is fresh the fresh ones show ×gain and the rest ×background_scale. Emotions
  // that rose within reaction_hold of each other therefore show together (the blend of surprise at
  // the long free-kick and happiness at the goal half a minute later, Fig. 7.9).
  std::array<double, 6> fresh_until{};
  fresh_until.fill(-1e300);
  auto display = [&](double t, const std::array<double, 6>& esv) {
    bool any = false;
    for (double u : fresh_until) any = any || t < u;
    std::array<double, 6> shown = esv;
    if (any)
      for (std::size_t e = 0; e < 6; ++e)
        shown[e] = t < fresh_until[e] ? std::min(1.0, esv[e] * options.reaction_gain)
                                      : esv[e] * options.background_scale;
    return shown;
  };
  std::array<double, 6> prev{};
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::size_t k = steps[i];
    const double t = step_seconds[k] + options.reaction_delay;
    std::array<double, 6> esv{};
    for (std::size_t e = 0; e < 6; ++e) {
      esv[e] = std::clamp(records[k].shown[e], 0.0, 1.0);  // §5.6.5 revealingLevel applied
      if (options.reactions && i > 0 && esv[e] - prev[e] >= options.reaction_rise)
        fresh_until[e] = t + options.reaction_hold;
    }
    prev = esv;
    points.push_back({t, display(t, esv)});
    // windows that close before the next step are change points of their own
    const double next = i + 1 < steps.size() ? step_seconds[steps[i + 1]] + options.reaction_delay : 1e300;
    std::vector<double> ends;
    for (double u : fresh_until)
      if (u > t && u < next - 1e-3) ends.push_back(u);
    std::sort(ends.begin(), ends.end());
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
    for (double u : ends) points.push_back({u, display(u, esv)});
  }
  std::vector<channels::EmotionItem> out;
  bool open = false;  // the last item is still being held
  std::array<double, 6> held{};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double start = points[i].t;
    const double next = i + 1 < points.size() ? points[i + 1].t : start + std::max(2.0, options.onset);
    const std::array<double, 6>& esv = points[i].esv;
    double largest = 0.0;
    for (double v : esv) largest = std::max(largest, v);
    if (largest < options.min_intensity) {  // neutral: the held display ends (its offset runs from here)
      open = false;
      continue;
    }
    bool same = open;
    for (std::size_t e = 0; same && e < 6; ++e) same = std::abs(esv[e] - held[e]) < options.merge_tolerance;
    if (same) {  // extend the held display until the next point
      out.back().timing.end = next + options.offset;
      continue;
    }
    channels::EmotionItem item;
    item.intensities = esv;
    if (esv[1] >= options.smile_outranks_speech) item.priority = 1;  // §4.1, above speech (2)
    item.timing.start = start;
    item.timing.end = next + options.offset;
    item.timing.offset = options.offset;
    item.timing.onset = std::min(options.onset, next - start);  // Do + Dr <= Te − Ts (thesis §4.4)
    out.push_back(item);
    held = esv;
    open = true;
  }
  return out;
}

std::string expression_text(const std::array<double, 6>& shown) {
  static const fuzzyexpr::Engine engine(fuzzyexpr::default_rule_base());
  fuzzyexpr::Esv esv{};
  double largest = 0.0;
  for (std::size_t k = 0; k < 6; ++k) {
    esv[k] = std::clamp(shown[k], 0.0, 1.0);
    largest = std::max(largest, esv[k]);
  }
  if (largest < 0.03) return "neutral";
  const fuzzyexpr::Selection sel = engine.select(esv);
  auto part = [&](fuzzyexpr::Emotion e) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%s %.2f", std::string(fuzzyexpr::to_string(e)).c_str(),
                  esv[static_cast<std::size_t>(e)]);
    return std::string(buf);
  };
  if (sel.mode == fuzzyexpr::ExpressionMode::Blend && sel.pair_has_rules &&
      esv[static_cast<std::size_t>(sel.second)] > 0.0)
    return part(sel.first) + " + " + part(sel.second);
  return part(sel.first);
}

channels::EmotionMapper fuzzy_emotion_mapper() {
  // The one mapper (issue 18): fuzzyexpr's ESV → side parameters, named by channels.
  return channels::side_parameter_mapper(fuzzyexpr::side_parameter_function());
}

std::size_t key_moment_frame(const TimeMap& time_map, double minute, double delay, double fps, std::size_t frames) {
  if (frames == 0) return 0;
  const double t = time_map.seconds(minute) + delay;
  const auto f = static_cast<double>(std::llround(t * fps));
  return static_cast<std::size_t>(std::clamp(f, 0.0, static_cast<double>(frames - 1)));
}

std::vector<Goal> find_goals(const MatchScript& match) {
  std::vector<Goal> goals;
  int for_score = 0, against_score = 0;
  auto has_side = [](const std::string& action, const std::string& side) {
    // arguments are the whitespace/paren-separated tokens after the operator name
    std::string token;
    bool first = true;
    for (char c : action + " ") {
      if (c == '(' || c == ')' || c == ' ' || c == '\t') {
        if (!token.empty()) {
          if (!first && token == side) return true;
          first = false;
          token.clear();
        }
      } else {
        token += c;
      }
    }
    return false;
  };
  for (const auto& e : match.events) {
    if (std::find(match.goal_outcomes.begin(), match.goal_outcomes.end(), e.outcome) == match.goal_outcomes.end())
      continue;
    Goal g;
    g.minute = e.minute;
    if (has_side(e.action, match.for_team.side)) {
      ++for_score;
      g.side = match.for_team.side;
      g.team = match.for_team.name;
    } else if (has_side(e.action, match.against_team.side)) {
      ++against_score;
      g.side = match.against_team.side;
      g.team = match.against_team.name;
    } else {
      continue;
    }
    g.for_score = for_score;
    g.against_score = against_score;
    goals.push_back(g);
  }
  return goals;
}

// ---- video sink ---------------------------------------------------------------------------------

struct VideoSink::Impl {
  std::unique_ptr<core::VideoWriter> writer;
};

VideoSink::VideoSink(std::string video_path, std::string wav_path, std::string ffmpeg)
    : video_path_(std::move(video_path)), wav_path_(std::move(wav_path)), ffmpeg_(std::move(ffmpeg)),
      impl_(std::make_unique<Impl>()) {
  if (video_path_.empty() || wav_path_.empty()) throw InvalidInput("VideoSink: video and WAV paths are required");
}

VideoSink::~VideoSink() = default;

void VideoSink::begin(const ObieResult& result, int width, int height, double fps) {
  channels::write_wav(wav_path_, result.head.audio, result.head.sample_rate);
  core::VideoOptions vo;
  vo.width = width;
  vo.height = height;
  vo.fps = fps;
  vo.audio_path = wav_path_;
  vo.shortest = false;  // audio and video have the same length by construction
  vo.ffmpeg = ffmpeg_;
  impl_->writer = std::make_unique<core::VideoWriter>(video_path_, vo);
}

void VideoSink::frame(const core::Image& image) {
  if (!impl_->writer) throw Error("VideoSink: frame() before begin()");
  impl_->writer->add_frame(image);
}

void VideoSink::finish() {
  if (!impl_->writer) throw Error("VideoSink: finish() before begin()");
  impl_->writer->finish();
}

// ---- the pipeline -------------------------------------------------------------------------------

ObieResult run_obie(const MatchScript& match, const parlee::AgentConfig& agent, const facemesh::Face& face,
                    const ObieOptions& options, const ProgressCallback& progress, FrameSink* sink,
                    const std::string& match_file) {
  options.validate();
  match.validate();
  auto report = [&](std::string_view stage, std::size_t done, std::size_t total) {
    if (progress) progress(Progress{stage, done, total});
  };
  ObieResult r;
  r.agent_name = agent.name;

  // 1. events → emotions (parlee)
  Stopwatch watch;
  report("emotions", 0, match.events.size());
  r.timeline = run_match(match, agent, match_file);
  report("emotions", match.events.size(), match.events.size());
  r.timings.push_back({"emotions (parlee)", watch.seconds()});

  // 2. match minutes → animation seconds
  watch = Stopwatch();
  std::vector<double> minutes;
  for (const auto& e : match.events) minutes.push_back(e.minute);
  r.time_map = TimeMap(minutes, match.duration, options.time);
  for (const auto& rec : r.timeline) r.step_seconds.push_back(r.time_map.seconds(rec.time));

  // 3. utterances (seeded choice; durations measured by synthesis so they never overlap)
  std::map<std::string, double> spoken;
  const SpeechDuration duration = [&](const std::string& text) {
    auto it = spoken.find(text);
    if (it == spoken.end()) it = spoken.emplace(text, channels::synthesize(text, options.voice).duration()).first;
    return it->second * 1.15 + 0.2;  // espeak-ng timing varies by a few percent within a process
  };
  if (options.speech) r.utterances = choose_utterances(r.timeline, r.step_seconds, options.utterances, options.seed, duration);
  r.timings.push_back({"utterances", watch.seconds()});

  // 4. emotion displays + speech → channels → tracks and audio (thesis ch. 4, ch. 6)
  watch = Stopwatch();
  r.script.file = match_file;
  r.script.emotions = emotion_displays(r.timeline, r.step_seconds, options.display);
  for (const auto& u : r.utterances) {
    channels::SpeechItem s;
    s.time = u.time;
    s.text = u.text;
    r.script.speech.push_back(std::move(s));
  }
  channels::TalkingHeadOptions th;
  th.speech = options.voice;
  th.timeline.blinks = options.blinks;
  th.timeline.gaze_noise = options.gaze_noise;
  th.timeline.head_noise = options.head_noise;
  th.render.fps = options.fps;
  th.render.duration = r.time_map.duration();
  th.seed = options.seed;
  r.head = channels::run_talking_head(r.script, channels::default_viseme_set(), channels::default_conflict_table(),
                                      fuzzy_emotion_mapper(), th);
  r.frames = r.head.tracks.frames();
  r.timings.push_back({"speech + channels", watch.seconds()});

  // 5. tracks → parameter vectors → deformed meshes → frames
  watch = Stopwatch();
  const channels::Tracks& tracks = r.head.tracks;
  std::vector<std::size_t> column_of(muscles::kParameterCount, SIZE_MAX);
  for (std::size_t c = 0; c < tracks.names.size(); ++c) column_of[muscles::parameter_index(tracks.names[c])] = c;
  const muscles::FaceSolver solver(face.mesh, face.rig, options.solver);
  const auto colors = facemesh::material_colors(face.rig, face.mesh);
  const facemesh::Paint* paint =
      facemesh::paint_for(face.rig);  // brows/hairline of the built-in face
  facemesh::RenderOptions ro;
  ro.view = options.view;
  ro.width = options.width;
  ro.height = options.height;
  r.timings.push_back({"solver setup", watch.seconds()});

  watch = Stopwatch();
  const std::size_t frames = r.frames;
  std::vector<char> want_gltf(frames, 0), want_key(frames, 0);
  if (options.gltf_fps > 0) {
    const double step = options.fps / options.gltf_fps;
    std::size_t last = SIZE_MAX;
    for (std::size_t j = 0;; ++j) {
      const auto f = static_cast<std::size_t>(std::llround(static_cast<double>(j) * step));
      if (f >= frames) break;
      if (f != last) want_gltf[f] = 1;
      last = f;
    }
  }
  for (const auto& km : match.key_moments) {
    KeyMomentFrame kf;
    kf.moment = km;
    kf.frame = key_moment_frame(r.time_map, km.minute, options.key_moment_delay, options.fps, frames);
    kf.time = tracks.time(kf.frame);
    for (const auto& rec : r.timeline)
      if (rec.time <= km.minute) kf.esv = rec.basic;
    for (const auto& item : r.script.emotions)
      if (item.timing.start <= kf.time) kf.shown = item.intensities;
    want_key[kf.frame] = 1;
    r.key_frames.push_back(std::move(kf));
  }
  if (!options.render_frames) sink = nullptr;  // nothing to stream
  const bool render_all = sink != nullptr;
  if (sink) sink->begin(r, options.width, options.height, options.fps);

  unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                         : std::min(8u, std::max(1u, std::thread::hardware_concurrency()));
  struct Work {
    std::vector<double> values;
    muscles::Deformation def;
    facemesh::Mesh mesh;
  };
  std::vector<Work> work(threads);
  for (auto& w : work) {
    w.values.assign(muscles::kParameterCount, 0.0);
    w.mesh.faces = face.mesh.faces;
  }
  const std::size_t batch = std::max<std::size_t>(threads * 4, 8);
  std::vector<core::Image> images(batch);
  std::vector<facemesh::Vertices> verts(batch);
  std::vector<char> done(batch);
  std::map<std::size_t, core::Image> key_images;
  auto process = [&](Work& w, std::size_t f, std::size_t slot) {
    const bool need_render = render_all || want_key[f];
    const bool need_mesh = need_render || want_gltf[f];
    done[slot] = 0;
    if (!need_mesh) return;
    for (std::size_t p = 0; p < muscles::kParameterCount; ++p) {
      double v = column_of[p] == SIZE_MAX ? 0.0 : tracks.at(f, column_of[p]);
      if (muscles::is_level_parameter(p)) v = std::clamp(v, 0.0, 1.0);  // contractions; mixing keeps them in range
      w.values[p] = v;
    }
    solver.deform(w.values, w.def);
    if (!w.def.vertices.allFinite()) throw NumericalError("obie: non-finite vertex at frame " + std::to_string(f));
    if (want_gltf[f]) verts[slot] = w.def.vertices;
    if (need_render) {
      w.mesh.vertices = w.def.vertices;
      images[slot] = facemesh::render(w.mesh, colors, w.def.crease, ro, paint);
    }
    done[slot] = 1;
  };
  for (std::size_t b0 = 0; b0 < frames; b0 += batch) {
    const std::size_t n = std::min(batch, frames - b0);
    if (threads == 1) {
      for (std::size_t i = 0; i < n; ++i) process(work[0], b0 + i, i);
    } else {
      std::vector<std::thread> pool;
      std::vector<std::exception_ptr> errors(threads);
      for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
          try {
            for (std::size_t i = t; i < n; i += threads) process(work[t], b0 + i, i);
          } catch (...) {
            errors[t] = std::current_exception();
          }
        });
      for (auto& th_ : pool) th_.join();
      for (auto& e : errors)
        if (e) std::rethrow_exception(e);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t f = b0 + i;
      if (want_gltf[f]) {
        r.gltf_frames.push_back(std::move(verts[i]));
        r.gltf_times.push_back(tracks.time(f));
      }
      if (want_key[f]) key_images[f] = images[i];
      if (render_all) {
        sink->frame(images[i]);
        ++r.frames_rendered;
      }
    }
    report("frames", b0 + n, frames);
  }
  for (auto& kf : r.key_frames) kf.image = key_images.at(kf.frame);
  r.timings.push_back({"deform + render frames", watch.seconds()});
  if (sink) {
    watch = Stopwatch();
    sink->finish();
    r.timings.push_back({"video finish (ffmpeg)", watch.seconds()});
  }

  // 6. summary facts
  r.goals = find_goals(match);
  for (std::size_t e = 0; e < 6; ++e) {
    r.peaks[e].emotion = kEsvNames[e];
    for (const auto& rec : r.timeline)
      if (rec.basic[e] > r.peaks[e].value + 1e-12) {
        r.peaks[e].value = rec.basic[e];
        r.peaks[e].minute = rec.time;
      }
  }
  return r;
}

}  // namespace emoface::obie
