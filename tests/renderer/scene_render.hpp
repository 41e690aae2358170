// Shared by the scene-workload tests (scene_workload_test.cpp, visbuffer_test.cpp,
// stability_test.cpp): rendering a small scene on lavapipe, reading back what the tests compare,
// and finding nodes in the frame graph it compiled.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fgb/graph/frame_graph.hpp>
#include <fgb/renderer/scene_workload.hpp>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace fgb::render::scene_test {

inline const std::string kScenes = FGB_RENDERER_TEST_SCENES;  // small scenes of these tests
inline const std::string kRepositoryScenes = FGB_SCENES_DIR;  // scenes/ (owned by the scene side)

struct Rendered {
  std::unique_ptr<Workload> workload;
  std::vector<PassTiming> passes;  // of the last frame
};

// Validation is off by default (it is slow); FGB_RENDERER_TEST_VALIDATION=1 turns it on for every
// test. validation_test.cpp checks every quick scene under synchronization validation.
inline WorkloadConfig lavapipeConfig(const std::string& scene, std::map<std::string, std::string> knobs,
                                     bool validation = false) {
  WorkloadConfig config;
  config.scenePath = scene.starts_with("/") ? scene : kScenes + "/" + scene;  // absolute or ours
  config.device = "lavapipe";
  config.validation = validation || std::getenv("FGB_RENDERER_TEST_VALIDATION") != nullptr;
  config.knobs = std::move(knobs);
  return config;
}

inline WorkloadConfig sized(WorkloadConfig config, uint32_t width, uint32_t height, uint32_t msaa) {
  config.width = width;
  config.height = height;
  config.msaa = msaa;
  return config;
}

inline Rendered render(const WorkloadConfig& config, uint32_t frames) {
  Rendered result{openSceneWorkload(config), {}};
  for (uint32_t i = 0; i < frames; ++i) result.workload->renderFrame();
  const auto rest = result.workload->finish();
  if (!rest.empty()) result.passes = rest.back().passes;
  return result;
}

inline Rendered render(const std::string& scene, std::map<std::string, std::string> knobs = {}, uint32_t frames = 2,
                       bool validation = false) {
  return render(lavapipeConfig(scene, std::move(knobs), validation), frames);
}

inline std::set<std::string> aliveNames(const std::vector<PassTiming>& passes) {
  std::set<std::string> names;
  for (const auto& pass : passes)
    if (!pass.culled) names.insert(pass.name);
  return names;
}

// Mean of the RGB channels.
inline double meanOf(const ImageRGBA32F& image) {
  double sum = 0.0;
  for (size_t i = 0; i < image.pixels.size(); i += 4)
    sum += image.pixels[i] + image.pixels[i + 1] + image.pixels[i + 2];
  return sum / double(image.pixels.size() / 4 * 3);
}

// Pixels (of all four channels) where a and b differ by more than `relative` of the larger value
// (and more than `absolute`).
inline size_t differingValues(const ImageRGBA32F& a, const ImageRGBA32F& b, float relative, float absolute) {
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const float tolerance = std::max(absolute, relative * std::max(std::abs(a.pixels[i]), std::abs(b.pixels[i])));
    differing += !(std::abs(a.pixels[i] - b.pixels[i]) <= tolerance);
  }
  return differing;
}

// A rendering's results, read before the next workload opens (each test holds one device at a time).
struct Images {
  std::set<std::string> passes;  // alive passes
  ImageRGBA32F hdr;
  ImageRGBA32F display;
  uint64_t validationMessages = 0;
  std::map<std::string, double> stats;
};

inline Images imagesOf(const Rendered& r) {
  return {aliveNames(r.passes), r.workload->readHdr(), r.workload->readDisplay(), r.workload->validationMessages(),
          r.workload->stats()};
}

inline Images renderImages(const WorkloadConfig& config, uint32_t frames) {
  return imagesOf(render(config, frames));
}

// The index of the frame graph's node `name` (std::runtime_error if there is none).
inline uint32_t nodeIndex(const graph::FrameGraph& graph, const std::string& name) {
  const auto& nodes = graph.nodes();
  const auto node = std::find_if(nodes.begin(), nodes.end(), [&](const auto& n) { return n.name == name; });
  if (node == nodes.end()) throw std::runtime_error("no node " + name);
  return uint32_t(node - nodes.begin());
}

}  // namespace fgb::render::scene_test
