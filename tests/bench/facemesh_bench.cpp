// The software rasteriser (facemesh::render) on the default face: the cost behind every video the apps
// make (docs/facemesh.md, "Performance"). Reproduce: build/tests/bench/facemesh_bench --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/render.hpp"

namespace {

namespace fm = emoface::facemesh;
namespace core = emoface::core;

const fm::Face& face() {
  static const fm::Face f = fm::make_generic_face();
  return f;
}

void BM_Render(benchmark::State& state) {
  const auto& f = face();
  const auto colors = fm::material_colors(f.rig, f.mesh);
  fm::RenderOptions ro;
  ro.width = static_cast<int>(state.range(0));
  ro.height = static_cast<int>(state.range(1));
  ro.view = state.range(2) ? fm::View::ThreeQuarter : fm::View::Front;
  for (auto _ : state) benchmark::DoNotOptimize(fm::render(f.mesh, colors, {}, ro).rgb.data());
  state.SetItemsProcessed(state.iterations());
  state.counters["pixels"] = static_cast<double>(ro.width) * ro.height;
}
BENCHMARK(BM_Render)
    ->Args({160, 192, 0})
    ->Args({320, 384, 0})
    ->Args({480, 560, 0})
    ->Args({480, 560, 1})
    ->Unit(benchmark::kMillisecond);

// What the apps draw since issue 14: the default face's surface paint (brows, hairline) on top,
// with the default normal smoothing; BM_Render above is without paint (and smoothing is on there
// too).
void BM_RenderPainted(benchmark::State& state) {
  const auto& f = face();
  const auto colors = fm::material_colors(f.rig, f.mesh);
  const fm::Paint* paint = fm::paint_for(f.rig);
  fm::RenderOptions ro;
  ro.width = static_cast<int>(state.range(0));
  ro.height = static_cast<int>(state.range(1));
  ro.normal_smoothing = static_cast<int>(state.range(2));
  for (auto _ : state)
    benchmark::DoNotOptimize(fm::render(f.mesh, colors, {}, ro, paint).rgb.data());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RenderPainted)
    ->Args({320, 384, 1})
    ->Args({480, 560, 1})
    ->Args({480, 560, 0})
    ->Unit(benchmark::kMillisecond);

// The optional light terms (issue 14, session 6) on the default face at 480×560, painted, against
// the plain render in the same run (args: shadow, occlusion; 0, 0 = the baseline).
void BM_RenderShadowOcclusion(benchmark::State& state) {
  static const fm::Face f = fm::make_default_face();
  const auto colors = fm::material_colors(f.rig, f.mesh);
  fm::RenderOptions ro;
  ro.shadow = static_cast<double>(state.range(0));
  ro.occlusion = static_cast<double>(state.range(1));
  for (auto _ : state)
    benchmark::DoNotOptimize(fm::render(f.mesh, colors, {}, ro, fm::paint_for(f.rig)).rgb.data());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RenderShadowOcclusion)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond);

void BM_EncodePng(benchmark::State& state) {
  const auto& f = face();
  fm::RenderOptions ro;
  ro.width = 480;
  ro.height = 560;
  const core::Image image = fm::render(f.mesh, fm::material_colors(f.rig, f.mesh), {}, ro);
  for (auto _ : state) benchmark::DoNotOptimize(core::encode_png(image).data());
}
BENCHMARK(BM_EncodePng)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
