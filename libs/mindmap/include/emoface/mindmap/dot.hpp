#pragma once
// A mind map as a Graphviz DOT graph (issue 19, item 4; the paper's "visual authoring" of mind
// maps, §6 and Fig. 2): the character in the centre, its emotion nodes (filled in the mood-chart
// colours, with the current mood when given), the stimuli it receives and the actions it performs,
// stimulus and response edges labelled with their weights, chained actions dashed, representative
// (decay) actions dotted. Render with core::render_dot or `dot -Tsvg`.
#include <string>
#include <vector>

#include "emoface/mindmap/mind_map.hpp"
#include "emoface/mindmap/simulation.hpp"

namespace emoface::mindmap {

struct MindMapDotOptions {
  /// Current mood per emotion node (empty = none): shown under each emotion name, and the node's
  /// border width grows with it. Must have one value per emotion node, each in [0, 1].
  std::vector<double> mood;
  bool weights = true;  ///< label stimulus and response edges with their weights
  void validate(const MindMap& map) const;  ///< throws InvalidInput
};

std::string mind_map_dot(const MindMap& map, const MindMapDotOptions& options = {});

/// The mood of `character` (index into result.characters) at the last sample at or before `time`
/// seconds (the first sample for earlier times). Throws InvalidInput for a bad index or no samples.
std::vector<double> mood_at(const SimulationResult& result, std::size_t character, double time);

/// The mind map of `character` (one of `maps`) as DOT (mindmap dot): with `events`, as it stands
/// at `time` seconds after them (map_at: learnt stimuli, changed context) with its simulated mood
/// then (`simulation`'s duration replaced by `time`); without events and `time` >= 0, with its
/// starting mood; otherwise without a mood. InvalidInput naming the character if no map is its,
/// or if events are given with a negative time.
std::string mind_map_dot_at(const std::vector<MindMap>& maps, const std::string& character,
                            const std::vector<Event>* events, double time,
                            SimulationOptions simulation = {});

}  // namespace emoface::mindmap
