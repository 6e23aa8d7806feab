#pragma once
// A region motion graph as a Graphviz DOT graph (issue 19, item 4): nodes coloured by their labels
// (grey = several), peak nodes as double circles naming their peak labels and neutral-to-peak
// length, the source (averaged neutral) as a box; edges with their eq. (1) weights on request. Big
// graphs are cut to the nodes within `depth` edges of the source. Render with core::render_dot or
// `dot -Tsvg`.
#include <cstddef>
#include <string>

#include "emoface/motiongraph/graph.hpp"

namespace emoface::motiongraph {

struct GraphDotOptions {
  std::size_t depth =
      0;  ///< only nodes within this many edges of the source (either direction); 0 = all
  bool edge_weights = false;  ///< label edges with their eq. (1) similarity
};

/// Label colours of the DOT pictures (and their legend), index = Label.
std::string label_colour(Label label);

std::string region_graph_dot(const RegionGraph& region, const GraphDotOptions& options = {});

}  // namespace emoface::motiongraph
