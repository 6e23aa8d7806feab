// Throughput of the motiongraph numeric work on the default synthetic database (70 sequences,
// 7 labels, 20 subjects, 10–30 frames, 68 landmarks). Run:
//   cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DEMOFACE_BUILD_BENCH=ON
//   cmake --build build-bench --target motiongraph_bench -j2
//   build-bench/tests/bench/motiongraph_bench
#include <benchmark/benchmark.h>

#include "emoface/motiongraph/capture.hpp"
#include "emoface/motiongraph/curves.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/synthesis.hpp"
#include "emoface/motiongraph/synthetic.hpp"

namespace mg = emoface::motiongraph;

namespace {
const mg::Database& database() {
  static const mg::Database db = mg::generate_synthetic_database(mg::ParametricLandmarkModel());
  return db;
}
const mg::PreparedDatabase& prepared() {
  static const mg::PreparedDatabase p = mg::preprocess(database(), mg::default_layout());
  return p;
}
const mg::MotionGraph& graph() {
  static const mg::MotionGraph g = mg::build_graph(prepared());
  return g;
}
}  // namespace

static void BM_GenerateSyntheticDatabase(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(mg::generate_synthetic_database(mg::ParametricLandmarkModel()));
}
BENCHMARK(BM_GenerateSyntheticDatabase)->Unit(benchmark::kMillisecond);

static void BM_Preprocess(benchmark::State& state) {
  mg::PreprocessOptions o;
  o.clean = state.range(0) != 0;
  mg::PreprocessReport rep;
  for (auto _ : state)
    benchmark::DoNotOptimize(mg::preprocess(database(), mg::default_layout(), o, &rep));
  // fit quality of the cleaning, to compare solvers on the same data
  state.counters["fits"] = static_cast<double>(rep.sigmoid_fits);
  state.counters["not_converged"] = static_cast<double>(rep.sigmoid_not_converged);
  state.counters["mean_fit_rms"] = rep.mean_fit_rms;
}
BENCHMARK(BM_Preprocess)->Arg(0)->Arg(1)->ArgName("clean")->Unit(benchmark::kMillisecond);

// One cleaning fit (§4) on its own: a noisy 2-column sigmoid of 25 samples, LM on all 6 parameters
// with slope and midpoint boxed (core::solve_bounded_lm + Ceres Jets; before: ceres::Solve), and
// the variable-projection solver on the same data for comparison.
static void BM_FitSigmoid(benchmark::State& state) {
  mg::SigmoidCurve truth;
  truth.slope = 0.6;
  truth.midpoint = 11.0;
  truth.offset = Eigen::Vector2d(0.0, 5.0);
  truth.amplitude = Eigen::Vector2d(3.0, -7.0);
  Eigen::VectorXd t(25);
  for (int i = 0; i < 25; ++i) t[i] = i;
  Eigen::MatrixXd y = truth.evaluate(t);
  for (int i = 0; i < 25; ++i) y(i, 1) += (i % 3 - 1) * 0.4;
  mg::SigmoidFitOptions o;
  o.solver = state.range(0) ? mg::SigmoidSolver::VariableProjection : mg::SigmoidSolver::Ceres;
  mg::SigmoidFitReport rep;
  for (auto _ : state) benchmark::DoNotOptimize(mg::fit_sigmoid(y, o, &rep).slope);
  state.counters["iterations"] = rep.iterations;
  state.counters["final_cost"] = rep.final_cost;
}
BENCHMARK(BM_FitSigmoid)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("variable_projection")
    ->Unit(benchmark::kMicrosecond);

// Graph creation (§4.1) from the prepared database; argument = threshold in 1/100 px per landmark.
static void BM_BuildGraph(benchmark::State& state) {
  mg::GraphOptions o;
  o.sample_threshold = o.merge_threshold = static_cast<double>(state.range(0)) / 100.0;
  const mg::PreparedDatabase& data = prepared();  // prepared once, outside the timing
  double compression = 0.0;
  for (auto _ : state) compression = mg::build_graph(data, o).compression_ratio();
  state.counters["compression_%"] = 100.0 * compression;
  state.counters["samples"] = static_cast<double>(prepared().samples.size());
}
BENCHMARK(BM_BuildGraph)->Arg(16)->Arg(40)->Arg(63)->Unit(benchmark::kMillisecond);

// One synthesized transition for all regions (Dijkstra + §5 steps 1–4); argument 1 = with the
// sigmoid smoothing of step 4, 0 = Savitzky–Golay only.
static void BM_SynthesizeTransition(benchmark::State& state) {
  mg::SynthesisOptions o;
  o.smoothing.sigmoid = state.range(0) != 0;
  const mg::Label labels[] = {mg::Label::Happiness, mg::Label::Fear, mg::Label::Surprise, mg::Label::Anger};
  mg::SynthesisState s = mg::initial_state(graph());
  std::size_t i = 0, frames = 0;
  for (auto _ : state) {
    frames += mg::synthesize(graph(), s, labels[i++ % 4], o).size();
  }
  state.counters["frames/transition"] = static_cast<double>(frames) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_SynthesizeTransition)->Arg(0)->Arg(1)->ArgName("sigmoid")->Unit(benchmark::kMicrosecond);

static void BM_Idle4s(benchmark::State& state) {
  mg::SynthesisState s = mg::initial_state(graph());
  mg::synthesize(graph(), s, mg::Label::Happiness);
  for (auto _ : state) {
    mg::SynthesisState t = s;
    benchmark::DoNotOptimize(mg::idle(graph(), t, mg::Label::Happiness));
  }
}
BENCHMARK(BM_Idle4s)->Unit(benchmark::kMicrosecond);

static void BM_SimilarityEq1(benchmark::State& state) {
  const Eigen::RowVectorXd a = Eigen::RowVectorXd::Random(20), b = Eigen::RowVectorXd::Random(20);
  const Eigen::RowVectorXd va = Eigen::RowVectorXd::Random(20), vb = Eigen::RowVectorXd::Random(20);
  mg::SimilarityOptions o;
  for (auto _ : state) benchmark::DoNotOptimize(mg::similarity(a.data(), va.data(), b.data(), vb.data(), 10, 2, o));
}
BENCHMARK(BM_SimilarityEq1);

// Captures (issue 19): the 20 generated long takes of the default synthetic database (parametric
// model), ~4 800 frames. Baseline: the OpenFace writer and reader on the same takes; then cleaning +
// stabilisation + trimming + labels (capture_database).
static const std::vector<mg::TrackedFrames>& capture_takes() {
  static const std::vector<mg::TrackedFrames> t = mg::generate_capture_takes(mg::ParametricLandmarkModel(), {});
  return t;
}
static void BM_CaptureReadOpenFace(benchmark::State& state) {
  std::vector<std::string> texts;
  for (const auto& t : capture_takes()) texts.push_back(mg::openface_csv(t));
  mg::OpenFaceReadOptions o;
  o.label_column = "label";
  for (auto _ : state)
    for (const auto& text : texts) benchmark::DoNotOptimize(mg::parse_openface_csv(text, "take.csv", o));
}
BENCHMARK(BM_CaptureReadOpenFace)->Unit(benchmark::kMillisecond);
static void BM_CaptureDatabase(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(mg::capture_database(capture_takes()));
}
BENCHMARK(BM_CaptureDatabase)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
