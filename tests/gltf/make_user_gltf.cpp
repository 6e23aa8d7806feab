// Writes a user's character glTF (tests/common/user_gltf.hpp) from the built-in face's mesh, for
// tests/gltf/check_gltf.sh: retarget --mode transfer rigs it, faceanim --gltf adds our targets.
// Usage: make_user_gltf OUT.gltf|OUT.glb
#include <cstdio>

#include "emoface/facemesh/default_face.hpp"
#include "user_gltf.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_user_gltf OUT.gltf|OUT.glb\n");
    return 1;
  }
  const auto face = emoface::facemesh::make_default_face();
  if (!emoface::testing::write_user_gltf(argv[1], face.mesh)) {
    std::fprintf(stderr, "make_user_gltf: cannot write %s\n", argv[1]);
    return 2;
  }
  return 0;
}
