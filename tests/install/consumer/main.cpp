#include <cstdio>

#include "emoface/core/version.hpp"
#include "emoface/fuzzyexpr/engine.hpp"

int main() {
  namespace fx = emoface::fuzzyexpr;
  const fx::Engine engine;
  fx::Esv esv{};
  esv[fx::index(fx::Emotion::Happiness)] = 1.0;
  const fx::Fmcv f = engine.convert(esv);
  std::printf("%s: happiness 1.0 -> zygomatic_major %.3f\n", emoface::kGenerator,
              f[fx::index(fx::Muscle::ZygomaticMajor)]);
  return f[fx::index(fx::Muscle::ZygomaticMajor)] == 1.0 ? 0 : 1;
}
