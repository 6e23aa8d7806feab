// The live motion API (issue 19 item 5): prepared-ahead transitions, idle when done, interrupts
// that continue from the current frame without a jump.
#include "emoface/motiongraph/player.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"
#include "fixtures.hpp"

namespace mg = emoface::motiongraph;

namespace {
const mg::MotionGraph& graph() {
  static const mg::MotionGraph g = mg::build_graph(mg::test::small_prepared());
  return g;
}
double step(const mg::Pose& a, const mg::Pose& b) { return (a - b).rowwise().norm().maxCoeff(); }
// The largest per-frame landmark step of a plain chained synthesis: what "no jump" is measured by.
double largest_plain_step() {
  mg::SynthesisState s = mg::initial_state(graph());
  double m = 0.0;
  for (mg::Label l :
       {mg::Label::Happiness, mg::Label::Surprise, mg::Label::Fear, mg::Label::Neutral}) {
    const auto f = mg::synthesize(graph(), s, l);
    for (std::size_t i = 1; i < f.size(); ++i) m = std::max(m, step(f[i], f[i - 1]));
  }
  return m;
}
}  // namespace

TEST(MotionPlayer, StartsAtRestAndIdlesWithoutRequests) {
  mg::MotionPlayer p(graph());
  EXPECT_EQ(p.label(), mg::Label::Neutral);
  EXPECT_EQ(p.current().rows(), static_cast<Eigen::Index>(graph().landmark_ids().size()));
  const mg::Pose start = p.current();
  double drift = 0.0;
  for (int i = 0; i < 200; ++i) drift = std::max(drift, step(p.next_frame(), start));
  EXPECT_EQ(p.frames_played(), 200u);
  EXPECT_EQ(p.label(), mg::Label::Neutral);
  EXPECT_GE(p.prepared_parts(), 1u);  // the next idle stretch is always ready
  EXPECT_LT(drift, 3.0);              // rest motion stays small (px)
}

TEST(MotionPlayer, QueuedTransitionIsPreparedAheadAndMatchesSynthesis) {
  mg::PlayerOptions o;
  o.synthesis.seed = 5;
  mg::MotionPlayer p(graph(), o);
  const std::size_t before = p.prepared_frames();
  p.queue(mg::Label::Happiness);
  // Prepared at once: the frames are there before the first one is played.
  EXPECT_GT(p.prepared_frames(), before);
  // The first part is the (at most one frame long) start; then the happiness transition, which
  // ends at a happiness peak like mg::synthesize from rest.
  mg::SynthesisState s = mg::initial_state(graph());
  mg::SynthesisOptions so;
  so.seed = emoface::core::derive_seed(5, 0);
  const auto ref = mg::synthesize(graph(), s, mg::Label::Happiness, so);
  std::vector<mg::Pose> got;
  for (std::size_t i = 0; i < ref.size() - 1; ++i) got.push_back(p.next_frame());
  EXPECT_EQ(p.label(), mg::Label::Happiness);
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT(step(got[i], ref[i + 1]), 1e-9) << i;
  // Then it idles under happiness without a jump.
  const mg::Pose last = p.current();
  EXPECT_LE(step(p.next_frame(), last), largest_plain_step());
  // Unknown peaks are refused and change nothing.
  mg::MotionGraph no_contempt = graph();
  for (auto& r : no_contempt.regions)
    for (auto& n : r.nodes)
      n.peak_labels.erase(
          std::remove(n.peak_labels.begin(), n.peak_labels.end(), mg::Label::Contempt),
          n.peak_labels.end());
  mg::MotionPlayer q(no_contempt);
  const std::size_t n = q.prepared_frames();
  EXPECT_THROW(q.queue(mg::Label::Contempt), emoface::InvalidInput);
  EXPECT_THROW(q.interrupt(mg::Label::Contempt), emoface::InvalidInput);
  EXPECT_EQ(q.prepared_frames(), n);
}

TEST(MotionPlayer, InterruptContinuesFromTheCurrentFrameWithoutAJump) {
  const double plain = largest_plain_step();
  for (int at : {3, 9, 17}) {
    mg::MotionPlayer p(graph());
    p.queue(mg::Label::Surprise);
    for (int i = 0; i < at; ++i) p.next_frame();
    ASSERT_EQ(p.label(), mg::Label::Surprise);
    const mg::Pose before = p.current();
    p.interrupt(mg::Label::Happiness);
    EXPECT_EQ(p.label(), mg::Label::Happiness);
    EXPECT_EQ(p.current(), before);  // nothing changes until the next frame
    // The first new frame is one ordinary step away (the offset fades over the transition) ...
    const mg::Pose first = p.next_frame();
    EXPECT_LE(step(first, before), plain) << "interrupt at frame " << at;
    // ... and every later step stays ordinary: the faded offset adds offset/(n − 1) per frame, a
    // few per cent of the largest plain step (25 % allowed).
    mg::Pose prev = first;
    double worst = 0.0;
    for (int i = 0; i < 60; ++i) {
      const mg::Pose& f = p.next_frame();
      worst = std::max(worst, step(f, prev));
      prev = f;
    }
    EXPECT_LE(worst, 1.25 * plain) << "interrupt at frame " << at;
  }
  // Without the continuation the same interrupt would jump: the surprise pose (jaw open) is far
  // from the start of a plain happiness transition from the nearest nodes.
  mg::MotionPlayer p(graph());
  p.queue(mg::Label::Surprise);
  for (int i = 0; i < 17; ++i) p.next_frame();
  mg::SynthesisState s = mg::initial_state(graph());
  const auto rest_to_happy = mg::synthesize(graph(), s, mg::Label::Happiness);
  EXPECT_GT(step(p.current(), rest_to_happy.front()), plain);
}

TEST(MotionPlayer, InterruptDropsTheQueueAndHoldModeHolds) {
  mg::PlayerOptions o;
  o.idle_when_done = false;
  o.idle.duration = 0.5;
  mg::MotionPlayer p(graph(), o);
  p.queue(mg::Label::Fear);
  p.queue(mg::Label::Sadness);
  EXPECT_EQ(p.prepared_parts(), 2u);
  p.next_frame();
  p.interrupt(mg::Label::Anger);
  EXPECT_EQ(p.prepared_parts(), 1u);  // the stretch after anger, prepared ahead
  mg::Pose last;
  std::size_t frames = 0;
  while (p.label() == mg::Label::Anger && frames < 500) {
    last = p.next_frame();
    ++frames;
  }
  // Anger plays, then the pose holds (hold mode: the held frames equal the last anger frame).
  mg::MotionPlayer q(graph(), o);
  q.interrupt(mg::Label::Anger);
  mg::Pose prev = q.next_frame();
  bool held = false;
  for (int i = 0; i < 200 && !held; ++i) {
    const mg::Pose f = q.next_frame();
    held = step(f, prev) == 0.0;
    prev = f;
  }
  EXPECT_TRUE(held);
  // Same calls, same seeds → same frames.
  mg::MotionPlayer a(graph()), b(graph());
  a.queue(mg::Label::Disgust);
  b.queue(mg::Label::Disgust);
  for (int i = 0; i < 40; ++i) EXPECT_EQ(a.next_frame(), b.next_frame());
}

TEST(MotionPlayer, RefusesAMalformedGraph) {
  mg::MotionGraph bad = graph();
  bad.dimensions = 3;  // node sizes are for 2D
  EXPECT_THROW(mg::MotionPlayer{bad}, emoface::InvalidInput);
  mg::MotionGraph empty = graph();
  empty.regions.clear();
  EXPECT_THROW(mg::MotionPlayer{empty}, emoface::InvalidInput);
}
