// Obie's pipeline without the encoder: the stages before rendering on the §7.4 match, deformation of
// the tracks' frames, and rendering one frame (docs/obie.md, "Performance").
//   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DEMOFACE_BUILD_BENCH=ON
//   cmake --build build --target obie_bench -j2
//   build/tests/bench/obie_bench --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/obie/pipeline.hpp"
#include "emoface/parlee/io.hpp"

namespace {

namespace ob = emoface::obie;
namespace fm = emoface::facemesh;
namespace mu = emoface::muscles;

const std::string kSrc = EMOFACE_SOURCE_DIR;

struct Fixture {
  ob::MatchScript match = ob::read_match_file(kSrc + "/data/obie/match_7_4.json");
  emoface::parlee::AgentConfig agent = emoface::parlee::read_agent_file(kSrc + "/data/parlee/agents/neutral.json");
  fm::Face face = fm::make_generic_face();
  ob::ObieOptions options() const {
    ob::ObieOptions o;
    o.speech = false;  // espeak-ng is measured by channels_bench; its timing varies within a process
    o.render_frames = false;
    o.gltf_fps = 0;
    o.threads = 1;
    return o;
  }
};
const Fixture& fixture() {
  static const Fixture f;
  return f;
}

// parlee over the 91 events of §7.4 (planner + appraisal per event).
void BM_Emotions(benchmark::State& state) {
  const auto& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(ob::run_match(f.match, f.agent));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(f.match.events.size()));
}
BENCHMARK(BM_Emotions)->Unit(benchmark::kMillisecond);

// Everything before the frames: emotions, displays, channels and mixing into 2,388 frames of 40
// parameters (speech off), plus the 4 key-moment frames (deformed and rendered 320×384).
void BM_TracksNoSpeech(benchmark::State& state) {
  const auto& f = fixture();
  const auto o = f.options();
  std::size_t frames = 0;
  for (auto _ : state) {
    const auto r = ob::run_obie(f.match, f.agent, f.face, o);
    frames = r.frames;
    benchmark::DoNotOptimize(r.head.tracks.values.data());
  }
  state.counters["frames"] = static_cast<double>(frames);
}
BENCHMARK(BM_TracksNoSpeech)->Unit(benchmark::kMillisecond);

// Tracks → parameter vector → deformed mesh, one frame per iteration, cycling through the match.
void BM_DeformFrame(benchmark::State& state) {
  const auto& f = fixture();
  static const auto r = ob::run_obie(f.match, f.agent, f.face, f.options());
  const auto& tracks = r.head.tracks;
  const mu::FaceSolver solver(f.face.mesh, f.face.rig);
  std::vector<std::size_t> column(mu::kParameterCount);
  for (std::size_t c = 0; c < tracks.names.size(); ++c) column[mu::parameter_index(tracks.names[c])] = c;
  std::vector<double> values(mu::kParameterCount);
  mu::Deformation d;
  std::size_t frame = 0;
  for (auto _ : state) {
    for (std::size_t p = 0; p < values.size(); ++p) values[p] = tracks.at(frame, column[p]);
    solver.deform(values, d);
    benchmark::DoNotOptimize(d.vertices.data());
    frame = (frame + 37) % tracks.frames();
  }
  state.SetItemsProcessed(state.iterations());  // items/s = frames per second
}
BENCHMARK(BM_DeformFrame)->Unit(benchmark::kMicrosecond);

// One 320×384 frame of the rasteriser (the default video size).
void BM_RenderFrame(benchmark::State& state) {
  const auto& f = fixture();
  const auto colors = fm::material_colors(f.face.rig, f.face.mesh);
  fm::RenderOptions ro;
  ro.width = static_cast<int>(state.range(0));
  ro.height = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(fm::render(f.face.mesh, colors, {}, ro).rgb.data());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RenderFrame)->Args({320, 384})->Args({160, 192})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
