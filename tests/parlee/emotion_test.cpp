#include "emoface/parlee/emotion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

using namespace emoface::parlee;
using emoface::InvalidInput;

TEST(Emotion, NamesRoundTrip) {
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    const auto e = static_cast<Emotion>(i);
    EXPECT_EQ(emotion_from_string(to_string(e)), e);
  }
  for (std::size_t i = 0; i < kTraitCount; ++i) {
    const auto t = static_cast<Trait>(i);
    EXPECT_EQ(trait_from_string(to_string(t)), t);
  }
  EXPECT_EQ(to_string(Trait::PerceivingLevel), "perceiving_level");
  EXPECT_EQ(to_string(Trait::FeelingFocus), "feeling_focus");
  EXPECT_EQ(decay_model_from_string(to_string(DecayModel::Product)), DecayModel::Product);
  EXPECT_THROW(emotion_from_string("glee"), InvalidInput);
  EXPECT_THROW(trait_from_string("courage"), InvalidInput);
  EXPECT_THROW(decay_model_from_string("linear"), InvalidInput);
  EXPECT_EQ(valence(Emotion::Gloating), Valence::Positive);
  EXPECT_EQ(valence(Emotion::Shame), Valence::Negative);
  EXPECT_EQ(valence(Emotion::Surprise), Valence::Neutral);
}

TEST(Personality, FormulasAsPowers) {
  Personality p;  // neutral: every modifier is the identity except feelingFocus (×0.5)
  EXPECT_DOUBLE_EQ(perceive_probability(p, 0.25), 0.25);
  EXPECT_DOUBLE_EQ(reason_impact(p, -0.25), -0.25);
  EXPECT_DOUBLE_EQ(reason_impact(p, 0.25), 0.25);
  EXPECT_DOUBLE_EQ(feel_impulse(p, 0.25), 0.25);
  p[Trait::PerceivingFocus] = 1.0;  // realistic: P^1.5
  EXPECT_NEAR(perceive_probability(p, 0.25), 0.125, 1e-15);
  p[Trait::ReasoningFocus] = 0.0;  // pessimistic: negative impact ^0.5, positive ^1.5
  EXPECT_NEAR(reason_impact(p, -0.25), -0.5, 1e-15);
  EXPECT_NEAR(reason_impact(p, 0.25), 0.125, 1e-15);
  p[Trait::ReasoningFocus] = 1.0;  // optimistic
  EXPECT_NEAR(reason_impact(p, -0.25), -0.125, 1e-15);
  EXPECT_NEAR(reason_impact(p, 0.25), 0.5, 1e-15);
  p[Trait::FeelingLevel] = 1.0;  // sensitive: impulse^0.5
  EXPECT_NEAR(feel_impulse(p, 0.25), 0.5, 1e-15);
  p[Trait::FeelingLevel] = 0.0;  // emotionless: impulse^1.5
  EXPECT_NEAR(feel_impulse(p, 0.25), 0.125, 1e-15);
  EXPECT_EQ(feel_impulse(p, 0.0), 0.0);
  p[Trait::FeelingFocus] = 0.8;
  EXPECT_DOUBLE_EQ(desire_other_factor(p), 0.8);
  p.values[3] = 1.5;
  EXPECT_THROW(p.validate(), InvalidInput);
  p.values[3] = std::nan("");
  EXPECT_THROW(p.validate(), InvalidInput);
}

TEST(Emotion, DecayMultipliers) {
  EmotionParams params = EmotionParams::defaults();
  params.decay.fill(0.81);
  Personality p;
  EXPECT_NEAR(decay_multipliers(params, p)[0], 0.81, 1e-15);
  p[Trait::FeelingLevel] = 1.0;  // more sensitive → slower decay
  EXPECT_NEAR(decay_multipliers(params, p)[0], 0.9, 1e-15);
  p[Trait::FeelingLevel] = 0.0;
  EXPECT_NEAR(decay_multipliers(params, p)[0], 0.729, 1e-15);
  params.decay_model = DecayModel::Product;  // §5.6.3 as printed: decay · feelingLevel
  p[Trait::FeelingLevel] = 0.5;
  EXPECT_NEAR(decay_multipliers(params, p)[0], 0.405, 1e-15);
}

// Issue 17 item 3: decay per second (§5.6.3 at the thesis' step of one match minute, §7.4).
TEST(Emotion, DecayPerSecondEqualsPerStepAtOneStep) {
  EXPECT_EQ(kThesisStepSeconds, 60.0);
  EmotionParams params = EmotionParams::defaults();
  EXPECT_EQ(params.step_seconds, 60.0);
  params.low_intensity_rate = 1.0;  // every intensity alike: the per-step law
  const EmotionVector phi = decay_multipliers(params, Personality{});
  EmotionVector e{};
  for (std::size_t i = 0; i < kEmotionCount; ++i) e[i] = 0.05 + 0.045 * static_cast<double>(i);
  const EmotionVector one = decayed(e, params, phi, 60.0);
  for (std::size_t i = 0; i < kEmotionCount; ++i) EXPECT_EQ(one[i], phi[i] * e[i]) << i;
  // per second: d^(Δt/step); joy 0.9 per minute over 90 s = 0.9^1.5 = 0.853815…
  EXPECT_NEAR(decayed(e, params, phi, 90.0)[0], e[0] * 0.85381496824546, 1e-14);
  // k = −ln Φ / 60 s: joy 0.0017560 /s, surprise −ln 0.3 / 60 = 0.0200662 /s
  const EmotionVector k = decay_rates(params, phi);
  EXPECT_NEAR(k[index(Emotion::Joy)], 0.10536051565782628 / 60.0, 1e-15);
  EXPECT_NEAR(k[index(Emotion::Surprise)], 1.2039728043259361 / 60.0, 1e-15);
  // nothing decays in no time
  EXPECT_EQ(decayed(e, params, phi, 0.0), e);
}

TEST(Emotion, TwoHalfStepsMakeOneStep) {
  for (double r : {1.0, 0.5, 0.2, 0.0}) {
    EmotionParams params = EmotionParams::defaults();
    params.low_intensity_rate = r;
    params.omega[index(Emotion::Joy)] = 2.0;
    const EmotionVector phi = decay_multipliers(params, Personality{});
    EmotionVector e{};
    for (std::size_t i = 0; i < kEmotionCount; ++i) e[i] = 0.9 - 0.04 * static_cast<double>(i);
    const EmotionVector whole = decayed(e, params, phi, 60.0);
    const EmotionVector halves = decayed(decayed(e, params, phi, 30.0), params, phi, 30.0);
    const EmotionVector thirds =
        decayed(decayed(decayed(e, params, phi, 20.0), params, phi, 25.0), params, phi, 15.0);
    for (std::size_t i = 0; i < kEmotionCount; ++i) {
      EXPECT_NEAR(halves[i], whole[i], 1e-15) << "r " << r << " emotion " << i;
      EXPECT_NEAR(thirds[i], whole[i], 1e-15) << "r " << r << " emotion " << i;
      EXPECT_LT(whole[i], e[i]);
    }
  }
}

TEST(Emotion, LowIntensityDecaysSlowerByHand) {
  // §5.6.3 "emotions decay slower when their intensity levels are lower": rate k·(r + (1−r)·E/ω).
  EmotionParams params = EmotionParams::defaults();
  EXPECT_EQ(params.low_intensity_rate, 0.5);
  params.decay.fill(0.9);
  const EmotionVector phi = decay_multipliers(params, Personality{});  // 0.9 (neutral)
  EmotionVector e{};
  e[0] = 0.8;
  e[1] = 0.05;
  // r = 1/2, ω = 1, one step: e^(−aΔt) = √0.9, b/a = 1, so E' = E·√d / (1 + E·(1 − √d))
  const EmotionVector one = decayed(e, params, phi, 60.0);
  EXPECT_NEAR(one[0], 0.7290179989462238, 1e-14);    // 0.8·0.948683/(1 + 0.8·0.051317)
  EXPECT_NEAR(one[1], 0.047312768141469654, 1e-15);  // 0.05·0.948683/(1 + 0.05·0.051317)
  EXPECT_GT(one[1] / e[1], one[0] / e[0]);           // the mood keeps more of itself
  EXPECT_GT(one[0], 0.9 * e[0]);                     // never faster than Φ per step
  // r = 0: dE/dt = −k·E²/ω, E' = E / (1 + k·E·Δt) = 0.8 / (1 − 0.8·ln 0.9)
  params.low_intensity_rate = 0.0;
  EXPECT_NEAR(decayed(e, params, phi, 60.0)[0], 0.7378110756861236, 1e-14);
  // the instantaneous rate over a short time: (E − E')/(E·Δt) → k·(r + (1 − r)·E/ω)
  params.low_intensity_rate = 0.25;
  params.omega[0] = 2.0;
  const double k = -std::log(0.9) / 60.0, dt = 1e-3;
  const double rate = (e[0] - decayed(e, params, phi, dt)[0]) / (e[0] * dt);
  EXPECT_NEAR(rate, k * (0.25 + 0.75 * 0.8 / 2.0), 1e-9);
}

TEST(Emotion, DecayEdgesAndBadInput) {
  EmotionParams params = EmotionParams::defaults();
  EmotionVector phi{}, e{};
  phi.fill(0.5);
  phi[0] = 0.0;  // no persistence: gone after any time
  phi[1] = 1.0;  // no decay
  e.fill(0.7);
  const EmotionVector d = decayed(e, params, phi, 1.0);
  EXPECT_EQ(d[0], 0.0);
  EXPECT_EQ(d[1], 0.7);
  EXPECT_EQ(decay_rates(params, phi)[1], 0.0);
  EXPECT_TRUE(std::isinf(decay_rates(params, phi)[0]));
  EXPECT_NEAR(decayed(e, params, phi, 1e7)[2], 0.0, 1e-12);  // a long time: nothing left
  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(decayed(e, params, phi, bad), InvalidInput) << bad;
  params.step_seconds = 0.0;
  EXPECT_THROW(params.validate(), InvalidInput);
  params.step_seconds = std::nan("");
  EXPECT_THROW(params.validate(), InvalidInput);
  params = EmotionParams::defaults();
  params.low_intensity_rate = 1.5;
  EXPECT_THROW(params.validate(), InvalidInput);
}

TEST(Emotion, UpdateDecayedMatchesPerStepUpdate) {
  EmotionParams params = EmotionParams::defaults();
  EmotionVector e{}, impulse{}, mult{};
  mult.fill(0.9);
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    e[i] = 0.03 * static_cast<double>(i);
    impulse[i] = i % 3 == 0 ? 0.2 : 0.0;
  }
  EmotionVector a = e, b = e, psi{};
  for (std::size_t i = 0; i < kEmotionCount; ++i) psi[i] = 0.9 * e[i];
  update_emotions(a, impulse, params, params.alpha, mult);
  update_decayed_emotions(b, psi, impulse, params, params.alpha);
  EXPECT_EQ(a, b);
}

TEST(Emotion, UpdateHandComputed) {
  EmotionParams params;
  params.alpha.fill(0.1);
  params.omega.fill(1.0);
  params.decay.fill(0.9);
  params.effect[index(Emotion::Joy)][index(Emotion::Distress)] = 0.3;
  params.effect[index(Emotion::Distress)][index(Emotion::Joy)] = 0.3;
  params.validate();
  EmotionVector e{}, impulse{}, mult{};
  mult.fill(0.9);
  e[index(Emotion::Joy)] = 0.5;
  e[index(Emotion::Distress)] = 0.2;
  e[index(Emotion::Fear)] = 0.05;  // below α: decays, damps nothing
  impulse[index(Emotion::Distress)] = 0.4;
  impulse[index(Emotion::Joy)] = 0.1;
  update_emotions(e, impulse, params, params.alpha, mult);
  // E_distress = 0.9·0.2 + 0.4·(1 − 0.5/1·0.3) = 0.52 ; E_joy = 0.9·0.5 + 0.1·(1 − 0.2·0.3) = 0.544
  EXPECT_NEAR(e[index(Emotion::Distress)], 0.52, 1e-15);
  EXPECT_NEAR(e[index(Emotion::Joy)], 0.544, 1e-15);
  EXPECT_NEAR(e[index(Emotion::Fear)], 0.045, 1e-15);
  // saturation at ω
  impulse = {};
  impulse[index(Emotion::Fear)] = 5.0;
  update_emotions(e, impulse, params, params.alpha, mult);
  EXPECT_EQ(e[index(Emotion::Fear)], 1.0);
  const auto act = active(e, params.alpha);
  EXPECT_TRUE(act[index(Emotion::Fear)]);
  EXPECT_FALSE(act[index(Emotion::Anger)]);
}

TEST(Emotion, EffectMatrixConstraint) {
  EmotionParams p = EmotionParams::defaults();
  EXPECT_NO_THROW(p.validate());
  p.effect[index(Emotion::Joy)][index(Emotion::Fear)] = 0.6;
  p.effect[index(Emotion::Hope)][index(Emotion::Fear)] = 0.5;  // column fear sums to 1.1 (with 0 else)
  try {
    p.validate();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("column fear"), std::string::npos);
  }
  p = EmotionParams::defaults();
  p.effect[0][1] = -0.1;
  EXPECT_THROW(p.validate(), InvalidInput);
  p = EmotionParams::defaults();
  p.alpha[2] = 2.0;
  EXPECT_THROW(p.validate(), InvalidInput);
  p = EmotionParams::defaults();
  p.omega[2] = 0.0;
  EXPECT_THROW(p.validate(), InvalidInput);
  p = EmotionParams::defaults();
  p.decay[2] = 1.1;
  EXPECT_THROW(p.validate(), InvalidInput);
}

TEST(Emotion, UpdateStaysWithinBoundsProperty) {
  emoface::core::Rng rng(42, 0);
  for (int trial = 0; trial < 500; ++trial) {
    EmotionParams p;
    for (std::size_t i = 0; i < kEmotionCount; ++i) {
      p.omega[i] = rng.uniform(0.2, 2.0);
      p.alpha[i] = rng.uniform(0.0, p.omega[i]);
      p.decay[i] = rng.uniform();
      // random column with sum ≤ 1
      double budget = rng.uniform();
      for (std::size_t j = 0; j < kEmotionCount; ++j) {
        const double v = rng.uniform() < 0.3 ? rng.uniform(0.0, budget) : 0.0;
        p.effect[j][i] = v;
        budget -= v;
      }
    }
    ASSERT_NO_THROW(p.validate());
    Personality pers;
    pers[Trait::FeelingLevel] = rng.uniform();
    const auto mult = decay_multipliers(p, pers);
    EmotionVector e{};
    for (std::size_t i = 0; i < kEmotionCount; ++i) e[i] = rng.uniform(0.0, p.omega[i]);
    for (int step = 0; step < 20; ++step) {
      EmotionVector impulse{};
      for (auto& v : impulse) v = rng.uniform() < 0.5 ? rng.uniform(0.0, 3.0) : 0.0;
      const EmotionVector before = e;
      update_emotions(e, impulse, p, p.alpha, mult);
      for (std::size_t i = 0; i < kEmotionCount; ++i) {
        ASSERT_GE(e[i], 0.0);
        ASSERT_LE(e[i], p.omega[i]);
        ASSERT_LE(e[i], mult[i] * before[i] + impulse[i] + 1e-12);  // §5.6.4 upper bound
      }
    }
  }
}

TEST(Motivation, ShiftsActivationThresholds) {
  EmotionParams p = EmotionParams::defaults();
  MotivationOptions o;
  MotivationalState m;
  const auto base = motivated_alpha(p, m, o);
  for (std::size_t i = 0; i < kEmotionCount; ++i) EXPECT_DOUBLE_EQ(base[i], p.alpha[i]);
  m.fatigue = 1.0;  // tired: negative emotions activate more easily, positive less
  auto a = motivated_alpha(p, m, o);
  EXPECT_NEAR(a[index(Emotion::Anger)], 0.05, 1e-15);
  EXPECT_NEAR(a[index(Emotion::Joy)], 0.15, 1e-15);
  EXPECT_NEAR(a[index(Emotion::Surprise)], 0.1, 1e-15);
  m = {};
  m.pain = 1.0;  // pain lowers the fear threshold only
  a = motivated_alpha(p, m, o);
  EXPECT_NEAR(a[index(Emotion::Fear)], 0.05, 1e-15);
  EXPECT_NEAR(a[index(Emotion::Distress)], 0.1, 1e-15);
  m = {};
  m.hunger = 1.0;
  m.thirst = 1.0;  // hunger and thirst raise every threshold
  a = motivated_alpha(p, m, o);
  for (std::size_t i = 0; i < kEmotionCount; ++i) EXPECT_NEAR(a[i], 0.15, 1e-15);
  o.hunger_gain = 4.0;
  o.thirst_gain = 4.0;
  p.alpha.fill(0.3);
  a = motivated_alpha(p, m, o);
  for (std::size_t i = 0; i < kEmotionCount; ++i) EXPECT_EQ(a[i], 1.0);  // clamped at ω
  MotivationalState s;
  for (int k = 0; k < 150; ++k) update_motivation(s, BodyEvent::Action, MotivationOptions{});
  EXPECT_EQ(s.hunger, 1.0);
  EXPECT_EQ(s.fatigue, 1.0);
  update_motivation(s, BodyEvent::Eat);
  EXPECT_EQ(s.hunger, 0.0);
  EXPECT_EQ(s.thirst, 1.0);
  update_motivation(s, BodyEvent::Hit);
  EXPECT_NEAR(s.pain, 0.2, 1e-15);
  update_motivation(s, BodyEvent::Rest);
  EXPECT_EQ(s.fatigue, 0.0);
  EXPECT_EQ(s.pain, 0.0);
  s.pain = 2.0;
  EXPECT_THROW(s.validate(), InvalidInput);
  o.pain_gain = -1;
  EXPECT_THROW(o.validate(), InvalidInput);
}

TEST(Emotion, BasicEmotionMapping) {
  EmotionParams p = EmotionParams::defaults();  // α 0.1, ω 1
  EmotionVector e{};
  EXPECT_EQ(basic_emotions(e, p), (std::array<double, 6>{}));
  e[index(Emotion::Distress)] = 0.55;     // (0.55 − 0.1)/0.9 = 0.5 → sadness
  e[index(Emotion::Joy)] = 0.05;          // a mood: below α, does not show
  e[index(Emotion::Gratitude)] = 1.0;     // 0.8 → happiness
  e[index(Emotion::Reproach)] = 1.0;      // anger 0.7, disgust 0.5
  e[index(Emotion::Fear)] = 0.325;        // 0.25
  e[index(Emotion::Surprise)] = 1.0;
  const auto b = basic_emotions(e, p);
  EXPECT_NEAR(b[0], 0.5, 1e-15);
  EXPECT_NEAR(b[1], 0.8, 1e-15);
  EXPECT_NEAR(b[2], 0.7, 1e-15);
  EXPECT_NEAR(b[3], 0.25, 1e-15);
  EXPECT_NEAR(b[4], 0.5, 1e-15);
  EXPECT_NEAR(b[5], 1.0, 1e-15);
  EXPECT_EQ(kBasicEmotionNames[0], "sadness");
  EXPECT_EQ(kBasicEmotionNames[5], "surprise");
}

// §5.6.5 revealingLevel in the display component: shown = felt^(1.5 − revealingLevel), by hand.
TEST(Display, RevealingLevelByHand) {
  const std::array<double, 6> felt{0.25, 0.0, 1.0, 0.64, 0.5, 0.01};
  Personality p;
  EXPECT_EQ(revealed_emotions(felt, p), felt);  // neutral 0.5: what is felt shows
  p[Trait::RevealingLevel] = 1.0;               // open: felt^0.5
  auto s = revealed_emotions(felt, p);
  EXPECT_NEAR(s[0], 0.5, 1e-12);
  EXPECT_EQ(s[1], 0.0);
  EXPECT_EQ(s[2], 1.0);
  EXPECT_NEAR(s[3], 0.8, 1e-12);
  EXPECT_NEAR(s[5], 0.1, 1e-12);
  p[Trait::RevealingLevel] = 0.0;  // secretive: felt^1.5
  s = revealed_emotions(felt, p);
  EXPECT_NEAR(s[0], 0.125, 1e-12);
  EXPECT_NEAR(s[3], 0.512, 1e-12);
  EXPECT_NEAR(s[5], 0.001, 1e-12);
  EXPECT_THROW(revealed_emotions({0.1, 1.5, 0, 0, 0, 0}, p), emoface::InvalidInput);
  EXPECT_THROW(revealed_emotions({std::nan(""), 0, 0, 0, 0, 0}, p), emoface::InvalidInput);
}
