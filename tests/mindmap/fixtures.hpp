#pragma once
// Tiny mind maps built in code for the mindmap tests.
#include "emoface/mindmap/mind_map.hpp"

namespace emoface::mindmap::test {

/// alice: emotions {happiness, sadness}; stimuli gift (→ happiness 0.8), insult (→ sadness 0.6);
/// performing smile (happiness), laugh (happiness), sigh (sadness), wave (happiness, chained after
/// smile); smile → wave chain; representatives happiness → smile, sadness → sigh.
/// Traits: starting mood {0.2, 0.4}, personality {0.1, 0.3}, λ 0, α 0.5, β 0.5, linear decay over 4 s.
inline MindMap make_alice() {
  MindMap m;
  m.character = "alice";
  m.emotions = {"happiness", "sadness"};
  m.actions = {{"gift", true, false, ""},         {"insult", true, false, ""},
               {"smile", false, true, "happiness"}, {"laugh", false, true, "happiness"},
               {"sigh", false, true, "sadness"},    {"wave", false, true, "happiness"}};
  m.stimulus_edges = {{0, 0, 0.8}, {1, 1, 0.6}};
  m.response_edges = {{0, 2, 0.3}, {0, 3, 0.9}, {1, 4, 0.5}};
  m.chain_edges = {{2, 5}};
  m.representative = {2, 4};
  m.traits.starting_mood = {0.2, 0.4};
  m.traits.personality = {0.1, 0.3};
  m.traits.lambda = 0.0;
  m.traits.alpha = 0.5;
  m.traits.beta = 0.5;
  m.traits.decay_duration = 4.0;
  m.traits.decay_curve = DecayCurve::Linear;
  return m;
}

/// bob: emotions {anger, sadness}; stimulus insult (→ anger 0.9, sadness 0.3); performing frown
/// (anger). Personality {0.5, 0.2}, starting mood = personality.
inline MindMap make_bob() {
  MindMap m;
  m.character = "bob";
  m.emotions = {"anger", "sadness"};
  m.actions = {{"insult", true, true, "anger"}, {"frown", false, true, "anger"}};
  m.stimulus_edges = {{0, 0, 0.9}, {0, 1, 0.3}};
  m.response_edges = {{0, 1, 0.6}};
  m.traits.starting_mood = {0.5, 0.2};
  m.traits.personality = {0.5, 0.2};
  m.traits.alpha = 0.7;
  m.traits.beta = 0.6;
  m.traits.decay_duration = 3.0;
  m.traits.decay_curve = DecayCurve::Sigmoid;
  return m;
}

}  // namespace emoface::mindmap::test
