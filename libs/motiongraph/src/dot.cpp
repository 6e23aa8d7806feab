#include "emoface/motiongraph/dot.hpp"

#include <cstdio>
#include <deque>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/core/graphviz.hpp"

namespace emoface::motiongraph {

std::string label_colour(Label label) {
  // neutral, happiness, sadness, disgust, surprise, anger, fear, contempt
  static const char* colours[] = {"#bbbbbb", "#1f77b4", "#ff7f0e", "#8c564b",
                                  "#d62728", "#2ca02c", "#9467bd", "#e377c2"};
  return colours[static_cast<int>(label)];
}

std::string region_graph_dot(const RegionGraph& region, const GraphDotOptions& options) {
  const std::size_t n = region.nodes.size();
  if (region.neutral_node >= n)
    throw InvalidInput("region_graph_dot: the graph has no source node");
  // Nodes kept: breadth-first from the source over edges in either direction.
  std::vector<std::size_t> dist(n, n + 1);
  const auto adj = region.adjacency(true);
  std::deque<std::size_t> queue{region.neutral_node};
  dist[region.neutral_node] = 0;
  while (!queue.empty()) {
    const std::size_t u = queue.front();
    queue.pop_front();
    for (const auto& [v, w] : adj[u])
      if (dist[v] > dist[u] + 1) dist[v] = dist[u] + 1, queue.push_back(v);
  }
  auto kept = [&](std::size_t i) { return options.depth == 0 || dist[i] <= options.depth; };
  using core::dot_quote;
  std::string out = "digraph " + dot_quote("motion graph " + region.name) + " {\n";
  out += "  graph [rankdir=LR, fontname=\"Helvetica\", label=" +
         dot_quote("region " + region.name + ": " + std::to_string(n) + " nodes, " +
                   std::to_string(region.edges.size()) + " edges" +
                   (options.depth ? " (within " + std::to_string(options.depth) + " of the source)"
                                  : "")) +
         "];\n  node [fontname=\"Helvetica\", fontsize=9, style=filled];\n  edge [fontsize=8, "
         "color=\"#888888\"];\n";
  char buf[64];
  for (std::size_t i = 0; i < n; ++i) {
    if (!kept(i)) continue;
    const Node& node = region.nodes[i];
    const std::string id = "n" + std::to_string(i);
    if (i == region.neutral_node) {
      out += "  " + id + " [shape=box, fillcolor=\"#dddddd\", label=" +
             dot_quote("source\n(neutral, " + std::to_string(node.frame_count) + " frames)") +
             "];\n";
      continue;
    }
    const std::string fill =
        node.labels.size() == 1 ? label_colour(node.labels[0]) : std::string("#cccccc");
    if (node.is_peak()) {
      std::string label;
      for (Label l : node.peak_labels) label += (label.empty() ? "" : "+") + to_string(l);
      std::snprintf(buf, sizeof buf, "\n%.0f±%.0f f", node.peak_length_mean, node.peak_length_std);
      out += "  " + id + " [shape=doublecircle, fillcolor=\"" + label_colour(node.peak_labels[0]) +
             "\", fontcolor=white, label=" + dot_quote(label + buf) + "];\n";
    } else {
      std::string initials;
      for (Label l : node.labels) initials += to_string(l).substr(0, 2);
      out += "  " + id + " [shape=circle, fillcolor=\"" + fill +
             "80\", label=" + dot_quote(initials) + "];\n";
    }
  }
  for (const Edge& e : region.edges) {
    if (!kept(e.from) || !kept(e.to)) continue;
    out += "  n" + std::to_string(e.from) + " -> n" + std::to_string(e.to);
    if (options.edge_weights) {
      std::snprintf(buf, sizeof buf, "%.2f", e.weight);
      out += std::string(" [label=") + dot_quote(buf) + "]";
    }
    out += ";\n";
  }
  return out + "}\n";
}

}  // namespace emoface::motiongraph
