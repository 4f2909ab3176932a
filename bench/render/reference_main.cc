// Writes a scene's exact image and its pixel classes as .npy files.
//   render_reference SCENE W H SEED OUT_PREFIX
#include <cstdio>
#include <cstdlib>

#include <alignset/npy.h>

#include "render/scene.h"

int main(int argc, char** argv) {
  using namespace alignset::render;
  if (argc != 6) {
    std::fprintf(stderr, "usage: render_reference SCENE W H SEED OUT_PREFIX\n");
    return 2;
  }
  auto scene = MakeScene(argv[1], std::atoi(argv[2]), std::atoi(argv[3]), std::strtoull(argv[4], nullptr, 10));
  if (!scene.ok()) {
    std::fprintf(stderr, "render_reference: %s\n", scene.status().message().c_str());
    return 2;
  }
  const std::vector<size_t> shape = {size_t(scene->height()), size_t(scene->width())};
  std::vector<double> classes;
  for (PixelClass c : scene->Classes()) classes.push_back(static_cast<double>(c));
  const std::string prefix = argv[5];
  if (!alignset::WriteNpy(prefix + "_reference.npy", shape, scene->Reference()).ok() ||
      !alignset::WriteNpy(prefix + "_classes.npy", shape, classes).ok()) {
    std::fprintf(stderr, "render_reference: cannot write %s_*.npy\n", prefix.c_str());
    return 1;
  }
  return 0;
}
