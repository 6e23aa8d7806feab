// The crowd (issue #9 §2): several mind-map characters, one motion graph, muscle faces side by side.
#include "emoface/mindmotion/crowd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/mindmap/chart.hpp"
#include "emoface/mindmap/io.hpp"

namespace mo = emoface::mindmotion;
namespace mg = emoface::motiongraph;
namespace mm = emoface::mindmap;
namespace fm = emoface::facemesh;
namespace core = emoface::core;

namespace {

// A small graph through the crowd's own default-graph function (fewer sequences than the default).
const mg::MotionGraph& small_graph() {
  static const mg::MotionGraph graph = [] {
    mg::SyntheticOptions o;
    o.seed = 5;
    o.sequences_per_label = 2;
    o.subjects = 3;
    o.min_frames = 6;
    o.max_frames = 12;
    return mo::default_motion_graph(o);
  }();
  return graph;
}

struct Face {
  std::unique_ptr<emoface::muscles::FaceSolver> solver;
  std::unique_ptr<emoface::bridge::LandmarkFitter> fitter;
};
const Face& default_face() {
  static const Face face = [] {
    auto f = fm::make_generic_face();
    Face out;
    out.solver = std::make_unique<emoface::muscles::FaceSolver>(std::move(f.mesh), std::move(f.rig));
    out.fitter = std::make_unique<emoface::bridge::LandmarkFitter>(*out.solver);
    return out;
  }();
  return face;
}
std::vector<mo::CrowdRig> rigs() { return {{default_face().solver.get(), default_face().fitter.get()}}; }

// Characters with the emotion nodes happiness, anger, fear; `bang` and `joke` weights differ.
mm::MindMap character(const std::string& name, double bang_anger, double bang_fear, double joke_happiness,
                      double personality_anger) {
  char buf[4096];
  std::snprintf(buf, sizeof buf, R"({"format": "emoface.mindmap", "version": "1.0", "character": "%s",
    "emotions": ["happiness", "anger", "fear"],
    "actions": [{"name": "bang", "receive": true}, {"name": "joke", "receive": true},
                {"name": "laugh", "perform": true, "label": "happiness"},
                {"name": "rage", "perform": true, "label": "anger"},
                {"name": "cower", "perform": true, "label": "fear"}],
    "stimulus_edges": [{"stimulus": "bang", "emotion": "anger", "weight": %g},
                       {"stimulus": "bang", "emotion": "fear", "weight": %g},
                       {"stimulus": "joke", "emotion": "happiness", "weight": %g}],
    "response_edges": [{"emotion": "happiness", "action": "laugh", "weight": 0.6},
                       {"emotion": "anger", "action": "rage", "weight": 0.7},
                       {"emotion": "fear", "action": "cower", "weight": 0.7}],
    "traits": {"starting_mood": [0.2, %g, 0.1], "personality": [0.2, %g, 0.1],
               "lambda": 0.0, "alpha": 0.9, "beta": 0.9, "decay": {"duration": 3.0, "curve": "linear"}}})",
                name.c_str(), bang_anger, bang_fear, joke_happiness, personality_anger, personality_anger);
  return mm::parse_mind_map(buf, name + ".json");
}

// A character whose emotion node no stimulus reaches, whose mood is zero throughout and who never acts.
mm::MindMap zen() {
  return mm::parse_mind_map(R"({"format": "emoface.mindmap", "version": "1.0", "character": "zen",
    "emotions": ["calm"], "actions": [],
    "traits": {"starting_mood": [0], "personality": [0], "lambda": 0, "alpha": 0.5, "beta": 0.5,
               "decay": {"duration": 2.0, "curve": "linear"}}})");
}

std::vector<mm::MindMap> trio() {
  return {character("hot", 1.0, 0.1, 0.3, 0.4), character("tim", 0.0, 1.0, 0.4, 0.0), zen()};
}

std::vector<mm::Event> events() {
  return mm::parse_events(
      "{\"time\": 0.5, \"to\": \"*\", \"stimulus\": \"bang\", \"weights\": {\"fear\": 0.9}}\n"
      "{\"time\": 2.0, \"to\": \"*\", \"stimulus\": \"joke\", \"weights\": {\"happiness\": 0.8}}\n");
}

mo::CrowdOptions short_options(double fps = 10.0) {
  mo::CrowdOptions o;
  o.simulation.duration = 3.5;
  o.fps = fps;
  o.seed = 7;
  return o;
}

const mo::Crowd& trio_crowd() {
  static const mo::Crowd crowd = mo::animate_crowd(trio(), events(), small_graph(), rigs(), short_options());
  return crowd;
}

mo::CrowdRenderOptions tiny() {
  mo::CrowdRenderOptions r;
  r.face_width = 36;
  r.strip_height = 12;
  r.gap = 2;
  return r;
}

std::size_t count_colour(const core::Image& img, std::uint32_t c, int x0 = 0, int y0 = 0,
                         int x1 = -1, int y1 = -1) {
  if (x1 < 0) x1 = img.width;
  if (y1 < 0) y1 = img.height;
  std::size_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = &img.rgb[(static_cast<std::size_t>(y) * img.width + x) * 3];
      n += p[0] == (c >> 16 & 0xff) && p[1] == (c >> 8 & 0xff) && p[2] == (c & 0xff);
    }
  return n;
}

std::string tracks_csv(const mo::Crowd& c, std::size_t i) {
  return emoface::muscles::format_parameter_frames_csv(c.characters[i].tracks);
}

}  // namespace

TEST(Crowd, EveryCharacterHasTracksOfTheFrameCount) {
  const mo::Crowd& c = trio_crowd();
  ASSERT_EQ(c.characters.size(), 3u);
  EXPECT_EQ(c.fps, 10.0);
  EXPECT_EQ(c.frame_count(), 36u);  // 3.5 s at 10 fps: frames 0 … 35
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& ch = c.characters[i];
    EXPECT_EQ(ch.name, c.maps[i].character);
    ASSERT_EQ(ch.tracks.size(), c.frame_count()) << ch.name;
    EXPECT_EQ(c.simulation.mood[i].size(), c.frame_count() * c.maps[i].emotion_count());
    for (std::size_t k = 0; k < ch.tracks.size(); ++k) {
      EXPECT_DOUBLE_EQ(ch.tracks[k].time, static_cast<double>(k) / 10.0);
      ASSERT_EQ(ch.tracks[k].values.size(), emoface::muscles::kParameterCount);
      for (double v : ch.tracks[k].values) ASSERT_TRUE(v >= 0.0 && v <= 1.0);
    }
    EXPECT_GE(static_cast<double>(ch.motion.frames.size()) / ch.motion.frame_rate, 3.5 - 1e-9);
  }
  EXPECT_EQ(c.emotions, (std::vector<std::string>{"happiness", "anger", "fear", "calm"}));
}

TEST(Crowd, TracksAreTheFitResampledToTheOutputRate) {
  // Independently: synthesize and fit one character by hand, then compare with the crowd's tracks.
  for (double fps : {10.0, 20.0}) {
    const mo::Crowd c = mo::animate_crowd(trio(), events(), small_graph(), rigs(), short_options(fps));
    mo::BehaviourMotionOptions bo;
    bo.seed = 7;
    const auto motion =
        mo::synthesize_behaviour(small_graph(), c.simulation.actions, "tim", 1, c.simulation.duration + 1.0 / 30.0, bo);
    const auto fitted = mo::fit_muscle_tracks(*default_face().fitter, small_graph(), motion);
    ASSERT_EQ(small_graph().frame_rate, 30.0);
    const auto& tracks = c.characters[1].tracks;
    for (std::size_t k = 0; k < tracks.size(); ++k) {
      const double s = static_cast<double>(k) * 30.0 / fps;  // 3k or 1.5k
      const auto i = static_cast<std::size_t>(s);
      ASSERT_LT(i + (s == static_cast<double>(i) ? 0 : 1), fitted.size());
      for (std::size_t j = 0; j < emoface::muscles::kParameterCount; ++j) {
        const double expected = s == static_cast<double>(i)
                                    ? fitted[i].values[j]
                                    : 0.5 * (fitted[i].values[j] + fitted[i + 1].values[j]);
        ASSERT_NEAR(tracks[k].values[j], expected, 1e-12) << "fps " << fps << " frame " << k << " parameter " << j;
      }
    }
  }
}

TEST(Crowd, DifferentPersonalitiesReactDifferentlyToTheSameStimuli) {
  const mo::Crowd& c = trio_crowd();
  auto first_action = [&](const std::string& who) {
    for (const auto& a : c.simulation.actions)
      if (a.character == who && a.stimulus == "bang") return a.label;
    return std::string();
  };
  EXPECT_EQ(first_action("hot"), "anger");
  EXPECT_EQ(first_action("tim"), "fear");
  // Issue 19: the faces differ, not only the action names. Distinctness = mean per-frame parameter
  // distance (face_distance). Baseline: twins (the same mind map under two names) differ only by the
  // seeded variation and idle motion; different personalities must differ clearly more.
  const auto d = mo::face_distances(c);
  mo::CrowdOptions o = short_options();
  const mo::Crowd twins = mo::animate_crowd({trio()[0], character("hot2", 1.0, 0.1, 0.3, 0.4)}, events(),
                                            small_graph(), rigs(), o);
  const double baseline = mo::face_distance(twins, 0, 1);
  EXPECT_GT(baseline, 0.05);  // variation is on: even twins do not move alike
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = a + 1; b < 3; ++b) {
      EXPECT_GT(d[a][b], 0.8) << c.maps[a].character << " vs " << c.maps[b].character;
      EXPECT_GT(d[a][b], 1.5 * baseline) << c.maps[a].character << " vs " << c.maps[b].character;
    }
}

TEST(Crowd, FaceDistanceIsTheMeanPerFrameParameterDistance) {
  // Hand-computed: frame 0 differs by (0.3, 0.4) in two parameters → 0.5; frame 1 by 0; mean 0.25.
  mo::Crowd c;
  c.characters.resize(3);
  for (auto& ch : c.characters) ch.tracks.assign(2, {0.0, std::vector<double>(emoface::muscles::kParameterCount, 0.0)});
  c.characters[1].tracks[0].values[0] = 0.3;
  c.characters[1].tracks[0].values[5] = 0.4;
  EXPECT_NEAR(mo::face_distance(c, 0, 1), 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(mo::face_distance(c, 0, 2), 0.0);
  const auto d = mo::face_distances(c);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NEAR(d[1][0], 0.25, 1e-12);
  EXPECT_NEAR(d[1][2], 0.25, 1e-12);
  EXPECT_EQ(d[2][2], 0.0);
  EXPECT_THROW(mo::face_distance(c, 0, 3), emoface::InvalidInput);
}

TEST(Crowd, KeyMomentsOnePerStimulusTimeAtTheReactionPeak) {
  const mo::Crowd& c = trio_crowd();
  ASSERT_EQ(c.key_moments.size(), 2u);
  EXPECT_EQ(c.key_moments[0].stimuli, std::vector<std::string>{"bang"});
  EXPECT_EQ(c.key_moments[1].time, 2.0);
  for (const auto& km : c.key_moments) {
    ASSERT_EQ(km.frames.size(), 3u);
    for (std::size_t f : km.frames) {
      EXPECT_LT(f, c.frame_count());
      EXPECT_GE(static_cast<double>(f) / c.fps, km.time - 1e-9);
    }
  }
  // hot's bang reaction: the last frame of its first action segment after 0.5 s.
  for (const auto& s : c.characters[0].motion.segments)
    if (s.kind == mo::SegmentKind::Action) {
      const double end = static_cast<double>(s.first_frame + s.frame_count - 1) / 30.0;
      EXPECT_EQ(c.key_moments[0].frames[0], static_cast<std::size_t>(std::floor(end * 10.0 + 1e-9)));
      break;
    }
  // zen never reacts: the middle of the window [0.5, 2.0).
  EXPECT_EQ(c.key_moments[0].frames[2], 12u);
  const std::string stamped = mo::key_moments_csv(c);
  ASSERT_EQ(stamped.rfind(emoface::core::csv_stamp(), 0), 0u);
  const std::string csv = stamped.substr(emoface::core::csv_stamp().size());
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "time,stimuli,hot_frame,tim_frame,zen_frame,hot_time,tim_time,zen_time");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
}

TEST(Crowd, FrameIsTheGridLayout) {
  const mo::Crowd& c = trio_crowd();
  const mo::CrowdRenderer r(c, rigs(), tiny());
  EXPECT_EQ(r.columns(), 3);
  EXPECT_EQ(r.rows(), 1);
  EXPECT_EQ(r.cell_width(), 36);
  EXPECT_EQ(r.cell_height(), 36 * 7 / 6 + 12);  // 42 + 12
  const core::Image f = r.frame(5);
  EXPECT_EQ(f.width, 3 * 36 + 4 * 2);
  EXPECT_EQ(f.height, 54 + 2 * 2);
  EXPECT_EQ(f.rgb.size(), static_cast<std::size_t>(f.width) * f.height * 3);
  // The cell of character 1 sits at (gap + cell + gap, gap).
  const core::Image cell = r.cell(1, 5);
  for (int y = 0; y < cell.height; ++y)
    ASSERT_EQ(0, std::memcmp(&cell.rgb[static_cast<std::size_t>(y) * cell.width * 3],
                             &f.rgb[(static_cast<std::size_t>(2 + y) * f.width + 2 + 36 + 2) * 3], 36 * 3));
  auto o = tiny();
  o.columns = 2;
  const mo::CrowdRenderer g(c, rigs(), o);
  EXPECT_EQ(g.columns(), 2);
  EXPECT_EQ(g.rows(), 2);
  EXPECT_EQ(g.frame(0).height, 2 * 54 + 3 * 2);
  const core::Image sheet = r.key_moment_sheet();
  EXPECT_EQ(sheet.width, f.width);
  EXPECT_EQ(sheet.height, 2 * f.height + 2);  // two moments, a 2-pixel rule between
}

TEST(Crowd, MoreThanFourCharactersMakeAGrid) {
  std::vector<mm::MindMap> maps;
  for (int i = 0; i < 5; ++i) maps.push_back(character("c" + std::to_string(i), 0.2 * i, 1.0 - 0.2 * i, 0.5, 0.1));
  auto o = short_options();
  o.simulation.duration = 1.0;
  const mo::Crowd c = mo::animate_crowd(maps, events(), small_graph(), rigs(), o);
  const mo::CrowdRenderer r(c, rigs(), tiny());
  EXPECT_EQ(r.columns(), 3);  // ⌈√5⌉
  EXPECT_EQ(r.rows(), 2);
  const core::Image f = r.frame(c.frame_count() - 1);
  EXPECT_EQ(f.width, 3 * 36 + 4 * 2);
  EXPECT_EQ(f.height, 2 * 54 + 3 * 2);
  // The sixth cell is empty: white.
  EXPECT_EQ(count_colour(f, 0xffffff, 2 + 2 * 38, 2 + 56, 2 + 2 * 38 + 36, 2 + 56 + 54), 36u * 54u);
}

TEST(Crowd, MoodStripBarsFollowTheMood) {
  const std::vector<std::uint32_t> colours = {0x1f77b4, 0xff7f0e, 0x2ca02c};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // 60 × 20, three slots of 20 px: frame columns 3…16 (bar 4…15: 12 px), frame rows 2 and 17, bar
  // rows inside: 14 px; a value v fills round(14·v) rows.
  const core::Image zero = mo::mood_strip({0.0, 0.0, 0.0}, colours, 60, 20);
  ASSERT_EQ(zero.width, 60);
  ASSERT_EQ(zero.height, 20);
  for (auto c : colours) EXPECT_EQ(count_colour(zero, c), 0u);  // empty bars
  EXPECT_GT(count_colour(zero, 0xc8c8c8), 0u);                  // but their frames
  const core::Image mixed = mo::mood_strip({1.0, 0.5, nan}, colours, 60, 20);
  EXPECT_EQ(count_colour(mixed, colours[0]), 14u * 12u);
  EXPECT_EQ(count_colour(mixed, colours[1]), 7u * 12u);
  EXPECT_EQ(count_colour(mixed, colours[1], 20, 0, 40, 10), 0u);  // bars grow from the bottom
  EXPECT_EQ(count_colour(mixed, 0xffffff, 40, 0, 60, 20), 20u * 20u);  // NaN: the slot stays blank
  EXPECT_EQ(count_colour(mo::mood_strip({2.0, -1.0, 0.0}, colours, 60, 20), colours[0]), 14u * 12u);  // clamped
  EXPECT_EQ(count_colour(mo::mood_strip({0.25, 0.0, 0.0}, colours, 60, 20), colours[0]), 4u * 12u);  // round(3.5)
  EXPECT_THROW(mo::mood_strip({0.5}, colours, 60, 20), emoface::InvalidInput);
  EXPECT_THROW(mo::mood_strip({0.5, 0.5, 0.5}, colours, 9, 20), emoface::InvalidInput);  // 3 px per bar
  EXPECT_THROW(mo::mood_strip({0.5, 0.5, 0.5}, colours, 60, 4), emoface::InvalidInput);
}

TEST(Crowd, TheStripUnderEachFaceShowsThatCharactersMood) {
  const mo::Crowd& c = trio_crowd();
  const mo::CrowdRenderer r(c, rigs(), tiny());
  const int face_h = 42;
  for (std::size_t k : {std::size_t{0}, std::size_t{8}, c.frame_count() - 1}) {
    const core::Image zen_cell = r.cell(2, k);
    for (std::size_t e = 0; e < c.emotions.size(); ++e)  // zen's mood is 0: no bar in any colour
      EXPECT_EQ(count_colour(zen_cell, mm::emotion_colour(e), 0, face_h, 36, zen_cell.height), 0u) << k;
    const core::Image hot_cell =
        r.cell(0, k);  // hot's anger (slot 1) is never below its personality 0.4
    EXPECT_GT(count_colour(hot_cell, mm::emotion_colour(1), 0, face_h, 36, hot_cell.height), 0u) << k;
    EXPECT_EQ(c.strip_values(2, k)[3], 0.0);
    EXPECT_TRUE(std::isnan(c.strip_values(2, k)[0]));
  }
  // The strip drawn in a cell is mood_strip of the character's values at that frame.
  const core::Image cell = r.cell(1, 9);
  const core::Image strip = mo::mood_strip(
      c.strip_values(1, 9),
      {mm::emotion_colour(0), mm::emotion_colour(1), mm::emotion_colour(2), mm::emotion_colour(3)},
      36, 12);
  EXPECT_EQ(0, std::memcmp(&cell.rgb[static_cast<std::size_t>(face_h) * 36 * 3], strip.rgb.data(), strip.rgb.size()));
  EXPECT_THROW(c.strip_values(3, 0), emoface::InvalidInput);
  EXPECT_THROW(c.strip_values(0, c.frame_count()), emoface::InvalidInput);
}

TEST(Crowd, DeterministicWithASeed) {
  const mo::Crowd a = mo::animate_crowd(trio(), events(), small_graph(), rigs(), short_options());
  const mo::Crowd& b = trio_crowd();
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(tracks_csv(a, i), tracks_csv(b, i));
  EXPECT_EQ(mo::key_moments_csv(a), mo::key_moments_csv(b));
  const mo::CrowdRenderer ra(a, rigs(), tiny()), rb(b, rigs(), tiny());
  for (std::size_t k : {std::size_t{3}, std::size_t{20}}) EXPECT_EQ(ra.frame(k).rgb, rb.frame(k).rgb);
  // The number of render threads does not change a pixel.
  auto one = tiny(), three = tiny();
  one.threads = 1;
  three.threads = 3;
  EXPECT_EQ(mo::CrowdRenderer(b, rigs(), one).frame(20).rgb, mo::CrowdRenderer(b, rigs(), three).frame(20).rgb);
  // One rig per character (here all the default face): each character uses its own, same pictures.
  const std::vector<mo::CrowdRig> own = {rigs()[0], rigs()[0], rigs()[0]};
  const mo::Crowd e = mo::animate_crowd(trio(), events(), small_graph(), own, short_options());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(e.characters[i].rig, i);
    EXPECT_EQ(b.characters[i].rig, 0u);
    EXPECT_EQ(tracks_csv(e, i), tracks_csv(b, i));
  }
  EXPECT_EQ(mo::CrowdRenderer(e, own, tiny()).frame(20).rgb, rb.frame(20).rgb);
  // Another seed changes the idle movements.
  auto o = short_options();
  o.seed = 8;
  const mo::Crowd d = mo::animate_crowd(trio(), events(), small_graph(), rigs(), o);
  EXPECT_NE(tracks_csv(d, 0), tracks_csv(b, 0));
}

TEST(Crowd, BadOptionsAndInputsAreClearErrors) {
  auto expect_error = [](auto&& f, const std::string& needle) {
    try {
      f();
      ADD_FAILURE() << "no error, expected one mentioning " << needle;
    } catch (const emoface::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  const auto g = [&](std::vector<mm::MindMap> maps, std::vector<mo::CrowdRig> r, mo::CrowdOptions o) {
    return [=] { mo::animate_crowd(maps, events(), small_graph(), r, o); };
  };
  auto o = short_options();
  o.fps = -1.0;
  expect_error(g(trio(), rigs(), o), "fps");
  o.fps = 300.0;
  expect_error(g(trio(), rigs(), o), "fps");
  o = short_options();
  o.key_window = 0.0;
  expect_error(g(trio(), rigs(), o), "key_window");
  o = short_options();
  o.simulation.tie_tolerance = 2.0;
  expect_error(g(trio(), rigs(), o), "tie");
  expect_error(g({zen()}, rigs(), short_options()), "at least 2");
  std::vector<mm::MindMap> many;
  for (int i = 0; i < 17; ++i) many.push_back(character("m" + std::to_string(i), 0.5, 0.5, 0.5, 0.1));
  expect_error(g(many, rigs(), short_options()), "at most 16");
  expect_error(g(trio(), {rigs()[0], rigs()[0]}, short_options()), "one per character");
  expect_error(g(trio(), {{nullptr, default_face().fitter.get()}}, short_options()), "null");
  expect_error(g({character("a", 1, 0, 0, 0), character("a", 0, 1, 0, 0)}, rigs(), short_options()), "duplicate character");
  // An event for a character that is not in the crowd names its line.
  expect_error(
      [] {
        mo::animate_crowd(trio(), mm::parse_events("{\"time\": 1, \"to\": \"nobody\", \"stimulus\": \"bang\"}\n"),
                          small_graph(), rigs(), short_options());
      },
      "nobody");
  // A label the graph cannot synthesize.
  mg::MotionGraph no_fear = small_graph();
  for (auto& region : no_fear.regions)
    for (auto& node : region.nodes)
      node.peak_labels.erase(std::remove(node.peak_labels.begin(), node.peak_labels.end(), mg::Label::Fear),
                             node.peak_labels.end());
  expect_error([&] { mo::animate_crowd(trio(), events(), no_fear, rigs(), short_options()); }, "fear");
  // Renderer options and misuse.
  const mo::Crowd& c = trio_crowd();
  for (auto bad : {&mo::CrowdRenderOptions::face_width, &mo::CrowdRenderOptions::strip_height,
                   &mo::CrowdRenderOptions::columns, &mo::CrowdRenderOptions::gap, &mo::CrowdRenderOptions::threads}) {
    auto r = tiny();
    r.*bad = 5000;
    EXPECT_THROW(mo::CrowdRenderer(c, rigs(), r), emoface::InvalidInput);
  }
  auto r = tiny();
  r.zoom = 0.0;
  expect_error([&] { mo::CrowdRenderer(c, rigs(), r); }, "zoom");
  r = tiny();
  r.face_width = 32;
  r.face_height = 10;
  expect_error([&] { mo::CrowdRenderer(c, rigs(), r); }, "face_height");
  const mo::CrowdRenderer renderer(c, rigs(), tiny());
  expect_error([&] { renderer.compose({0, 0}); }, "one frame per character");
  expect_error([&] { renderer.compose({0, 0, c.frame_count()}); }, "out of range");
  expect_error([&] { renderer.cell(0, c.frame_count()); }, "out of range");
  expect_error([&] { mo::CrowdRenderer(c, {rigs()[0], rigs()[0]}, tiny()); }, "one per character");
  mo::Crowd broken = c;
  broken.characters[1].tracks.pop_back();
  expect_error([&] { mo::CrowdRenderer(broken, rigs(), tiny()); }, "tracks");
  mo::Crowd none = c;
  none.key_moments.clear();
  expect_error([&] { mo::CrowdRenderer(none, rigs(), tiny()).key_moment_sheet(); }, "key moments");
}

namespace {

TEST(CrowdFaces, RigSpecsAssignFacesPerCharacter) {
  namespace fs = std::filesystem;
  const auto maps = trio();
  const mo::CrowdFaces shared(maps, {});
  ASSERT_EQ(shared.rigs().size(), 1u);  // everyone the built-in face, one solver
  EXPECT_NE(shared.rigs()[0].solver, nullptr);
  EXPECT_NE(shared.rigs()[0].fitter, nullptr);
  const std::string dir = ::testing::TempDir() + "emoface_crowd_faces";
  fs::remove_all(dir);
  fs::create_directories(dir);
  emoface::facemesh::save_face(dir + "/face.rig", emoface::facemesh::make_generic_face());
  const mo::CrowdFaces one(maps, {"tim=" + dir + "/face.rig"});
  ASSERT_EQ(one.rigs().size(), 3u);  // per character, map order: hot, tim, zen
  EXPECT_EQ(one.rigs()[0].solver, one.rigs()[2].solver);  // hot and zen share the default face
  EXPECT_NE(one.rigs()[0].solver, one.rigs()[1].solver);
  EXPECT_EQ(mo::CrowdFaces(maps, {dir + "/face.rig"}).rigs().size(), 1u);  // one file for everyone
  EXPECT_THROW(mo::CrowdFaces(maps, {dir + "/face.rig", dir + "/face.rig"}), emoface::InvalidInput);
  EXPECT_ANY_THROW(mo::CrowdFaces(maps, {dir + "/missing.rig"}));
  fs::remove_all(dir);
}

}  // namespace

// Issue 19 item 4: labelled strips (emotion names under the bars), names on the faces, key-moment
// headers; small pictures keep no text.
TEST(Crowd, StripsAndCellsCarryLabels) {
  const std::vector<std::uint32_t> colours = {0x1f77b4, 0xff7f0e, 0x2ca02c};
  const std::vector<std::string> names = {"happiness", "sadness", "anger"};
  auto ink = [](const core::Image& im, int x0, int y0, int x1, int y1) {
    return count_colour(im, 0x3c3c3c, x0, y0, x1, y1);
  };
  // 90 × 40, three slots of 30 px: bars in the top 32 rows (frame rows 3 and 28), labels below
  const core::Image s = mo::mood_strip({1.0, 0.5, 0.0}, colours, 90, 40, names);
  EXPECT_EQ(ink(s, 0, 0, 90, 32), 0u);
  for (int i = 0; i < 3; ++i) EXPECT_GT(ink(s, 30 * i, 33, 30 * i + 30, 38), 5u) << i;
  // bar of 1.0 fills the inside of its frame: 32 − 2·3 − 2 = 24 rows (rows 4…27), 30 − 2·5 − 2 = 18
  // columns
  EXPECT_EQ(count_colour(s, colours[0]), 24u * 18u);
  // without labels, or on a strip under 24 pixels, no text and the old layout
  EXPECT_EQ(ink(mo::mood_strip({1.0, 0.5, 0.0}, colours, 90, 40), 0, 0, 90, 40), 0u);
  EXPECT_EQ(mo::mood_strip({1.0, 0.5, 0.0}, colours, 90, 20, names).rgb,
            mo::mood_strip({1.0, 0.5, 0.0}, colours, 90, 20).rgb);
  EXPECT_THROW(mo::mood_strip({1.0, 0.5, 0.0}, colours, 90, 40, {"a"}), emoface::InvalidInput);
  // a cell 80 px wide names its character in the top-left corner (scale 1, ink 40,40,40)
  const mo::Crowd& c = trio_crowd();
  auto o = tiny();
  o.face_width = 80;
  o.strip_height = 30;
  const mo::CrowdRenderer r(c, rigs(), o);
  const core::Image cell = r.cell(0, 3);
  const int name_w = 4 * static_cast<int>(c.characters[0].name.size());
  EXPECT_GT(count_colour(cell, 0x282828, 3, 3, 3 + name_w, 8), 3u);
  EXPECT_EQ(count_colour(cell, 0x282828, 0, 0, 4 + name_w, 10) +
                count_colour(cell, 0xffffff, 0, 0, 4 + name_w, 10),
            static_cast<std::size_t>((4 + name_w) * 10));  // ink on its white label
  EXPECT_GT(count_colour(cell, 0x3c3c3c, 0, cell.height - 8, cell.width, cell.height), 5u);
  // the tiny renderer (36 px faces, 12 px strips) draws no text
  const mo::CrowdRenderer t(c, rigs(), tiny());
  EXPECT_EQ(count_colour(t.cell(0, 3), 0x282828), 0u);
}
