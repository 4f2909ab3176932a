#include "render/scene.h"

namespace alignset::render {

Scene::Scene(std::string name, int width, int height, std::vector<PixelIntegrand> pixels, PixelDomain domain)
    : name_(std::move(name)), width_(width), height_(height), pixels_(std::move(pixels)), domain_(domain) {}

std::vector<double> Scene::Reference() const {
  std::vector<double> image(pixels_.size());
  for (size_t i = 0; i < pixels_.size(); ++i) image[i] = pixels_[i].Exact();
  return image;
}

std::vector<PixelClass> Scene::Classes() const {
  std::vector<PixelClass> c(pixels_.size());
  for (size_t i = 0; i < pixels_.size(); ++i) c[i] = pixels_[i].Classify();
  return c;
}

std::vector<std::string> SceneNames() { return {"antialias", "shadow"}; }

StatusOr<Scene> MakeScene(const std::string& name, int width, int height, uint64_t seed) {
  if (width < 1 || height < 1 || width > 4096 || height > 4096) {
    return Status::InvalidArgument("scene size must be in [1, 4096] x [1, 4096], got " +
                                   std::to_string(width) + "x" + std::to_string(height));
  }
  if (name == "antialias") return MakeAntialiasScene(width, height, seed);
  if (name == "shadow") return MakeShadowScene(width, height, seed);
  return Status::InvalidArgument("unknown scene '" + name + "' (known: antialias, shadow)");
}

}  // namespace alignset::render
