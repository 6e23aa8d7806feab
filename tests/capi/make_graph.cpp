// Writes a small weight-space ARKit-52 motion graph from emoface's own face (the graph of
// tests/runtime/mindmotion_source_test.cpp) for the C and Python tests of the mindmotion source.
// Usage: capi_make_graph OUT.json
#include <cstdio>
#include <exception>

#include "emoface/bridge/face_landmark_model.hpp"
#include "emoface/bridge/weight_space.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/weights.hpp"

int main(int argc, char** argv) {
  namespace mg = emoface::motiongraph;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.json\n", argv[0]);
    return 2;
  }
  try {
    const emoface::bridge::FaceLandmarkModel face;
    emoface::bridge::WeightDatabaseOptions o;
    o.database.sequences_per_label = 2;
    o.database.subjects = 4;
    o.database.min_frames = 8;
    o.database.max_frames = 16;
    mg::write_graph(
        argv[1], mg::build_graph(mg::preprocess(emoface::bridge::generate_weight_database(face, o),
                                                emoface::bridge::arkit_layout(),
                                                mg::weight_preprocess_options()),
                                 mg::weight_graph_options()));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "capi_make_graph: %s\n", e.what());
    return 1;
  }
  return 0;
}
