// Writes a user's character glTF (tests/common/user_gltf.hpp) from the built-in face's mesh, for
// tests/gltf/check_gltf.sh: retarget --mode transfer rigs it, faceanim --gltf adds our targets.
// Usage: make_user_gltf OUT.gltf|OUT.glb [--sparse]   (--sparse: their target as a sparse accessor)
#include <cstdio>
#include <cstring>

#include "emoface/facemesh/default_face.hpp"
#include "user_gltf.hpp"

int main(int argc, char** argv) {
  const bool sparse = argc == 3 && std::strcmp(argv[2], "--sparse") == 0;
  if (argc != 2 && !sparse) {
    std::fprintf(stderr, "usage: make_user_gltf OUT.gltf|OUT.glb [--sparse]\n");
    return 1;
  }
  const auto face = emoface::facemesh::make_default_face();
  if (!emoface::testing::write_user_gltf(argv[1], face.mesh, sparse)) {
    std::fprintf(stderr, "make_user_gltf: cannot write %s\n", argv[1]);
    return 2;
  }
  return 0;
}
