#include "render/scene_renderer.h"

#include <algorithm>

namespace mostyle::render {

void SceneRenderer::draw(const Scene& scene, const OrbitCamera& camera, const glm::ivec2& size,
                         const SceneStyle& style) {
  ground_.draw(scene.skeletons, scene.ground_height, camera, size, style.ground);
  const float aspect = static_cast<float>(size.x) / static_cast<float>(std::max(size.y, 1));
  skeletons_.draw(scene.skeletons, camera.view(), camera.projection(aspect), style.lighting, style.skeleton);
}

}  // namespace mostyle::render
