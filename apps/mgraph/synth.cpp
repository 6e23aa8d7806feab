// mgraph synth and idle: animations from a motion graph, written with their pictures or weights.
#include <iostream>

#include "commands.hpp"
#include "emoface/bridge/weight_space.hpp"
#include "emoface/cli/cli.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/motiongraph/batch.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "emoface/muscles/io.hpp"

namespace emoface::mgraph {

using namespace motiongraph;

namespace {

// The sequences as a database of the graph's reduced landmarks, its pictures and the weight
// outputs: every output computed and staged, then all committed (core::OutputBundle).
int write_animation(const Args& a, const MotionGraph& g, const std::vector<Sequence>& seqs) {
  const bool weights = is_weight_space(g.dimensions);
  const AnimationPictures pics{a.sheet, a.plot,       a.frames_dir,  a.video,        a.columns,
                               a.every, a.cell_width, a.video_width, a.video_height, a.fps};
  if (weights && pics.any())
    throw cli::UsageError(
        "--video, --sheet, --plot and --frames-dir draw landmarks: not for a "
        "weight graph (use --params and faceanim)");
  if (!weights && !(a.livelink_out.empty() && a.params_out.empty()))
    throw cli::UsageError(
        "--livelink and --params need a weight graph (mgraph generate --space arkit)");
  std::vector<Pose> all;
  for (const Sequence& s : seqs) all.insert(all.end(), s.frames.begin(), s.frames.end());
  core::OutputBundle bundle;
  // Weight graphs: Live Link Face CSV, face parameters through the exact ARKit mapping (bridge).
  if (!a.livelink_out.empty())
    bundle.add(a.livelink_out,
               bridge::live_link_csv(bridge::weight_take(g, all, "synth"), g.frame_rate));
  if (!a.params_out.empty()) {
    bridge::WeightDriveReport rep;
    bundle.add(a.params_out,
               muscles::format_parameter_frames_csv(bridge::weight_parameters(g, all, &rep)));
    std::cerr << "mgraph: " << rep.frames << " frames of face parameters, largest weight error "
              << rep.max_weight_error << "\n";
  }
  stage_database(bundle, a.out, animation_database(g, seqs));
  stage_animation_pictures(bundle, g, all, pics);
  bundle.commit();
  return cli::kExitOk;
}

}  // namespace

int synth(const Args& a) {
  const MotionGraph g = read_graph(a.graph);
  if (!a.requests.empty() && !a.labels.empty())
    throw cli::UsageError("give --labels or --requests, not both");
  if (a.requests.empty() && a.labels.empty()) throw cli::UsageError("give --labels or --requests");
  ChainOptions o = chain_options_for(g);
  o.synthesis.vary_duration = a.vary;
  o.synthesis.replace_probability = a.replace;
  o.synthesis.path_fraction = a.hint;
  o.synthesis.smoothing.sigmoid = !a.no_sigmoid;
  o.idle_after = a.idle_after;
  if (a.requests.empty())
    return write_animation(a, g, synthesize_chain(g, a.labels, a.seed, "", o));
  // Batch (motiongraph/batch.hpp): request r uses the seed stream r, and a shard takes its
  // contiguous block of the requests (bad ones count), so shard outputs concatenate to one run.
  const std::vector<RequestRecord> records = read_requests_csv(a.requests);
  ReadReport report;
  const std::vector<Sequence> seqs = synthesize_requests(
      g, records, cli::parse_shard(a.shard).block(records.size()), a.seed, o, on_error(a), &report);
  print_skipped(report, "request(s)");
  if (seqs.empty()) throw InvalidInput("no request produced an animation (shard " + a.shard + ")");
  return write_animation(a, g, seqs);
}

int idle(const Args& a) {
  const MotionGraph g = read_graph(a.graph);
  const Label label = label_from_string(a.idle_label);
  SynthesisState state = initial_state(g);
  const bool weights = is_weight_space(g.dimensions);
  SynthesisOptions so = weights ? weight_synthesis_options() : SynthesisOptions{};
  so.seed = a.seed;
  std::vector<Sequence> seqs;
  if (label != Label::Neutral)
    seqs.push_back({"onset_" + a.idle_label, "", label, synthesize(g, state, label, so)});
  IdleOptions o = weights ? weight_idle_options() : IdleOptions{};
  o.duration = a.duration;
  o.hop_interval = a.hop_interval;
  o.dwell = a.dwell;
  o.seed = a.seed;
  seqs.push_back({"idle_" + a.idle_label, "", label, motiongraph::idle(g, state, label, o)});
  return write_animation(a, g, seqs);
}

}  // namespace emoface::mgraph
