#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/mindmotion/muscle_tracks.hpp"
#include "emoface/core/csv.hpp"

#include <algorithm>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/synthetic.hpp"

namespace mo = emoface::mindmotion;
namespace mg = emoface::motiongraph;
namespace mm = emoface::mindmap;

namespace {

// A small motion graph from the synthetic CK+-like database, built once.
const mg::MotionGraph& small_graph() {
  static const mg::MotionGraph graph = [] {
    mg::SyntheticOptions o;
    o.seed = 3;
    o.sequences_per_label = 2;
    o.subjects = 3;
    o.min_frames = 6;
    o.max_frames = 12;
    const auto db = mg::generate_synthetic_database(mg::ParametricLandmarkModel(), o);
    return mg::build_graph(mg::preprocess(db, mg::default_layout()));
  }();
  return graph;
}

mm::TriggeredAction act(double t, const char* action, const char* label, mm::Cause cause,
                        const char* who = "ana") {
  return {t, who, action, label, "happiness", 0.5, cause, "gift", 0};
}

}  // namespace

TEST(Behaviour, GraphLabelsAreThePeaks) {
  const auto labels = mo::graph_labels(small_graph());
  for (const char* l : {"happiness", "sadness", "disgust", "surprise", "anger", "fear", "contempt"})
    EXPECT_NE(std::find(labels.begin(), labels.end(), l), labels.end()) << l;
}

TEST(Behaviour, SegmentsCoverTheTimelineWithIdleBetweenActions) {
  const std::vector<mm::TriggeredAction> actions = {
      act(1.0, "smile", "happiness", mm::Cause::Stimulus), act(1.0, "x", "anger", mm::Cause::Stimulus, "ben"),
      act(1.5, "gasp", "surprise", mm::Cause::Chain), act(5.0, "pout", "sadness", mm::Cause::Decay)};
  const auto m = mo::synthesize_behaviour(small_graph(), actions, "ana", 0, 8.0);
  ASSERT_GE(m.segments.size(), 5u);  // idle, smile, gasp, (idle), pout, idle
  const auto cut = mo::synthesize_behaviour(small_graph(), actions, "ana", 0, 1.2);  // actions after 1.2 s ignored
  ASSERT_GE(cut.segments.size(), 2u);  // idle, smile (then idle if the smile ends before 1.2 s)
  EXPECT_EQ(cut.segments[1].action, "smile");
  for (std::size_t i = 2; i < cut.segments.size(); ++i) EXPECT_EQ(cut.segments[i].kind, mo::SegmentKind::Idle);
  EXPECT_EQ(m.segments.front().kind, mo::SegmentKind::Idle);
  EXPECT_EQ(m.segments.front().label, "neutral");
  EXPECT_EQ(m.segments[1].action, "smile");
  EXPECT_NEAR(m.segments[1].start, 1.0, 1.0 / m.frame_rate + 1e-9);
  std::size_t next = 0;
  for (const auto& s : m.segments) {
    EXPECT_EQ(s.first_frame, next);
    EXPECT_GT(s.frame_count, 0u);
    EXPECT_GE(s.start + 1e-9, s.requested_time - 1.0 / m.frame_rate);
    EXPECT_NE(s.action, "x");  // ben's action is not ana's
    next += s.frame_count;
  }
  EXPECT_EQ(next, m.frames.size());
  EXPECT_GE(static_cast<double>(m.frames.size()) / m.frame_rate, 8.0 - 0.5);
  EXPECT_EQ(m.segments.back().kind, mo::SegmentKind::Idle);
  bool hint = false;
  for (const auto& s : m.segments) hint = hint || (s.kind == mo::SegmentKind::Hint && s.action == "pout");
  EXPECT_TRUE(hint);
  const auto db = mo::to_database(small_graph(), m);
  EXPECT_NO_THROW(mg::validate(db, 1));
  EXPECT_EQ(db.sequences.size(), m.segments.size());
  EXPECT_EQ(mo::segments_csv(m).substr(emoface::core::csv_stamp().size(), 20), "kind,action,label,re");
}

TEST(Behaviour, HintsUseOnlyTheInitialNodesAndAreDroppedWhenBusy) {
  const auto full = mo::synthesize_behaviour(small_graph(), {act(0.0, "a", "fear", mm::Cause::Stimulus)}, "ana", 0, 0.0);
  mo::BehaviourMotionOptions o;
  o.hint_path_fraction = 0.3;
  const auto hint = mo::synthesize_behaviour(small_graph(), {act(0.0, "a", "fear", mm::Cause::Decay)}, "ana", 0, 0.0, o);
  ASSERT_EQ(full.segments.size(), 1u);
  ASSERT_EQ(hint.segments.size(), 1u);
  EXPECT_EQ(hint.segments[0].kind, mo::SegmentKind::Hint);
  // Paths of this small graph have 2–3 nodes, so a 0.3 prefix may keep all of them (motiongraph keeps
  // at least 2): never longer than the full synthesis; with fraction 1 exactly the full synthesis.
  EXPECT_LE(hint.segments[0].frame_count, full.segments[0].frame_count);
  o.hint_path_fraction = 1.0;
  const auto whole = mo::synthesize_behaviour(small_graph(), {act(0.0, "a", "fear", mm::Cause::Decay)}, "ana", 0, 0.0, o);
  ASSERT_EQ(whole.frames.size(), full.frames.size());
  for (std::size_t f = 0; f < whole.frames.size(); ++f) ASSERT_EQ(whole.frames[f], full.frames[f]);
  const auto busy = mo::synthesize_behaviour(
      small_graph(), {act(0.0, "a", "fear", mm::Cause::Stimulus), act(0.01, "b", "sadness", mm::Cause::Decay)},
      "ana", 0, 0.01);
  EXPECT_EQ(busy.dropped_hints, 1u);
  EXPECT_EQ(busy.segments.size(), 1u);
}

TEST(Behaviour, DeterministicPerSeedAndBadInputThrows) {
  const std::vector<mm::TriggeredAction> actions = {act(0.5, "smile", "happiness", mm::Cause::Stimulus)};
  mo::BehaviourMotionOptions o;
  o.synthesis.vary_duration = true;
  o.synthesis.replace_probability = 0.3;
  const auto a = mo::synthesize_behaviour(small_graph(), actions, "ana", 0, 3.0, o);
  const auto b = mo::synthesize_behaviour(small_graph(), actions, "ana", 0, 3.0, o);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t f = 0; f < a.frames.size(); ++f) ASSERT_EQ(a.frames[f], b.frames[f]);
  EXPECT_THROW(mo::synthesize_behaviour(small_graph(), {act(0, "s", "joy", mm::Cause::Stimulus)}, "ana", 0, 1.0),
               emoface::InvalidInput);
  o.hint_path_fraction = 0.0;
  EXPECT_THROW(mo::synthesize_behaviour(small_graph(), actions, "ana", 0, 1.0, o), emoface::InvalidInput);
  EXPECT_THROW(mo::synthesize_behaviour(small_graph(), actions, "ana", 0, -1.0), emoface::InvalidInput);
  for (auto k : {mo::SegmentKind::Action, mo::SegmentKind::Hint, mo::SegmentKind::Idle, mo::SegmentKind::Rest})
    EXPECT_EQ(mo::segment_kind_from_string(mo::to_string(k)), k);
  EXPECT_EQ(mo::segment_kind_from_string("resting"), std::nullopt);
  o = {};
  o.return_after = -1.0;
  EXPECT_THROW(mo::synthesize_behaviour(small_graph(), actions, "ana", 0, 1.0, o), emoface::InvalidInput);
}

// Issue 19: variation (§5.1) is on by default, so the same label differs between characters.
TEST(Behaviour, VariationIsOnByDefaultAndCanBeSwitchedOff) {
  const mo::BehaviourMotionOptions defaults;
  EXPECT_TRUE(defaults.synthesis.vary_duration);
  EXPECT_DOUBLE_EQ(defaults.synthesis.replace_probability, 0.3);
  EXPECT_TRUE(defaults.synthesis.vary_peak);
  // The same action at t = 0 (no idle before it) for characters 0 and 1 of the world.
  auto face = [&](std::size_t index, const mo::BehaviourMotionOptions& o) {
    return mo::synthesize_behaviour(small_graph(), {act(0.0, "a", "fear", mm::Cause::Stimulus, "x")}, "x", index,
                                    0.0, o);
  };
  mo::BehaviourMotionOptions off;
  off.synthesis = mg::SynthesisOptions{};
  const auto a0 = face(0, off), a1 = face(1, off);
  ASSERT_EQ(a0.frames.size(), a1.frames.size());
  for (std::size_t f = 0; f < a0.frames.size(); ++f) ASSERT_EQ(a0.frames[f], a1.frames[f]);  // identical
  int differing = 0;
  for (std::size_t index = 1; index < 6; ++index) {
    const auto v0 = face(0, defaults), v = face(index, defaults);
    bool same = v0.frames.size() == v.frames.size();
    for (std::size_t f = 0; same && f < v.frames.size(); ++f) same = v0.frames[f] == v.frames[f];
    differing += same ? 0 : 1;
  }
  EXPECT_GE(differing, 4);  // per-character seeds give different faces for the same label
}

// Issue 19: faces rest. They move at rest before the first stimulus, return to neutral through the
// graph source `return_after` seconds after their last animation, and `neutral` is a label.
TEST(Behaviour, FacesIdleAtRestAndReturnToNeutral) {
  const auto labels = mo::graph_labels(small_graph());
  EXPECT_EQ(labels.front(), "neutral");
  const std::vector<mm::TriggeredAction> actions = {act(1.0, "smile", "happiness", mm::Cause::Stimulus)};
  const auto m = mo::synthesize_behaviour(small_graph(), actions, "ana", 0, 8.0);
  // Before the stimulus: idle at rest, and not frozen.
  ASSERT_EQ(m.segments.front().kind, mo::SegmentKind::Idle);
  double moved = 0.0;
  for (std::size_t f = 0; f < m.segments.front().frame_count; ++f)
    moved = std::max(moved, (m.frames[f] - m.frames[0]).cwiseAbs().maxCoeff());
  EXPECT_GT(moved, 0.05);
  // After the smile: 2 s of idle around happiness, then the return, then rest until the end.
  std::vector<mo::SegmentKind> kinds;
  for (const auto& s : m.segments) kinds.push_back(s.kind);
  const std::vector<mo::SegmentKind> expected = {mo::SegmentKind::Idle, mo::SegmentKind::Action,
                                                 mo::SegmentKind::Idle, mo::SegmentKind::Rest,
                                                 mo::SegmentKind::Idle};
  ASSERT_EQ(kinds, expected);
  const auto& smile = m.segments[1];
  const auto& rest = m.segments[3];
  EXPECT_EQ(rest.label, "neutral");
  EXPECT_NEAR(rest.start, smile.start + static_cast<double>(smile.frame_count) / m.frame_rate + 2.0,
              1.0 / m.frame_rate + 1e-9);
  EXPECT_EQ(m.segments[4].label, "neutral");
  // At the end of the return the face is back at the averaged neutral (within the smoothing of the
  // last frames), while the smile's peak was far from it.
  const std::size_t back = rest.first_frame + rest.frame_count - 1;
  const std::size_t peak = smile.first_frame + smile.frame_count - 1;
  double at_rest = 0.0, at_peak = 0.0;
  for (Eigen::Index l = 0; l < m.frames[0].rows(); ++l) {
    at_rest = std::max(at_rest, (m.frames[back].row(l) - m.frames[0].row(l)).norm());
    at_peak = std::max(at_peak, (m.frames[peak].row(l) - m.frames[0].row(l)).norm());
  }
  EXPECT_GT(at_peak, 5.0);
  EXPECT_LT(at_rest, 1.0 + 2.0 * moved);
  // return_after = 0 keeps the old behaviour: the face holds its expression.
  mo::BehaviourMotionOptions hold;
  hold.return_after = 0.0;
  const auto h = mo::synthesize_behaviour(small_graph(), actions, "ana", 0, 8.0, hold);
  for (const auto& s : h.segments) EXPECT_NE(s.kind, mo::SegmentKind::Rest);
  // A return that does not fit before the next action is not started (the action is not delayed).
  const auto tight = mo::synthesize_behaviour(
      small_graph(), {actions[0], act(1.0 + 2.6, "gasp", "surprise", mm::Cause::Stimulus)}, "ana", 0, 6.0);
  for (const auto& s : tight.segments)
    if (s.action == "gasp") EXPECT_NEAR(s.start, 3.6, 1.0 / tight.frame_rate + 1e-9);
  // `neutral` actions synthesize the return too.
  const auto calm = mo::synthesize_behaviour(
      small_graph(), {actions[0], act(2.0, "calm", "neutral", mm::Cause::Stimulus)}, "ana", 0, 3.0);
  const auto it = std::find_if(calm.segments.begin(), calm.segments.end(),
                               [](const mo::Segment& x) { return x.action == "calm"; });
  ASSERT_NE(it, calm.segments.end());
  EXPECT_EQ(it->kind, mo::SegmentKind::Action);
  EXPECT_EQ(it->label, "neutral");
  EXPECT_GT(it->frame_count, 3u);
}

TEST(MuscleTracks, NeutralPoseAndDisplacementsInFaceUnits) {
  const Eigen::MatrixXd neutral = mo::graph_neutral_ibug68(small_graph());
  ASSERT_EQ(neutral.rows(), 68);
  EXPECT_TRUE(neutral.row(36).allFinite());
  EXPECT_TRUE(neutral.row(45).allFinite());
  // A motion that is the neutral pose everywhere has zero displacement on every observed landmark.
  mo::CharacterMotion still;
  still.frame_rate = 30.0;
  mg::Pose pose(static_cast<Eigen::Index>(small_graph().landmark_ids().size()), 2);
  const auto ids = small_graph().landmark_ids();
  for (std::size_t i = 0; i < ids.size(); ++i) pose.row(static_cast<Eigen::Index>(i)) = neutral.row(ids[i]);
  still.frames = {pose, pose};
  Eigen::MatrixXd face = Eigen::MatrixXd::Zero(68, 3);
  face.row(36) << -0.04, 0.0, 0.0;
  face.row(45) << 0.04, 0.0, 0.0;
  const auto d = mo::face_displacements(small_graph(), still, face);
  ASSERT_EQ(d.size(), 2u);
  for (std::size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(d[0].row(ids[i]).norm(), 0.0);
  // One pixel to the right of the neutral pose = (eye-corner distance in m / in px) metres.
  still.frames[1](0, 0) += 1.0;
  const double scale = 0.08 / (neutral.row(45) - neutral.row(36)).norm();
  EXPECT_NEAR(mo::face_displacements(small_graph(), still, face)[1](ids[0], 0), scale, 1e-15);
}
