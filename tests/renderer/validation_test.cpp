// Every scene the renderer draws quickly runs clean under the Vulkan validation layers, with
// synchronization validation on (WorkloadConfig::validation enables both): zero messages. The
// RHI gives each node a descriptor set exposing only the resources outside the graph (read-only)
// and the ones the node declared, so the layers see exactly the declared accesses.
#include <fgb/renderer/scene_workload.hpp>

#include <gtest/gtest.h>

#include <ostream>
#include <utility>
#include <string>

namespace fgb::render {
namespace {

struct ValidatedScene {
  std::string path;  // absolute
  uint32_t frames;
};

void PrintTo(const ValidatedScene& scene, std::ostream* out) { *out << scene.path; }

class SceneValidation : public ::testing::TestWithParam<ValidatedScene> {};

TEST_P(SceneValidation, RunsCleanUnderSynchronizationValidation) {
  WorkloadConfig config;
  config.scenePath = GetParam().path;
  config.device = "lavapipe";
  config.validation = true;
  config.width = 160;
  config.height = 90;
  auto workload = openSceneWorkload(config);
  // More than the frames in flight: the second use of every per-frame resource is checked too.
  for (uint32_t i = 0; i < GetParam().frames; ++i) workload->renderFrame();
  workload->finish();
  EXPECT_EQ(workload->validationMessages(), 0u);
}

const std::string kRepo = FGB_SCENES_DIR;
const std::string kOurs = FGB_RENDERER_TEST_SCENES;

INSTANTIATE_TEST_SUITE_P(Scenes, SceneValidation,
                         ::testing::Values(ValidatedScene{kRepo + "/empty.json", 3},
                                           ValidatedScene{kRepo + "/no-lights.json", 3},
                                           ValidatedScene{kRepo + "/lights-only.json", 3},
                                           ValidatedScene{kRepo + "/particles-only.json", 4},
                                           ValidatedScene{kRepo + "/bloom.json", 3},
                                           ValidatedScene{kRepo + "/transparency-only.json", 3},
                                           ValidatedScene{kRepo + "/alpha-mask.json", 3},
                                           ValidatedScene{kOurs + "/atrium-small.json", 3},
                                           ValidatedScene{kOurs + "/showcase-small.json", 3}),
                         [](const ::testing::TestParamInfo<ValidatedScene>& param) {
                           std::string name = param.param.path.substr(param.param.path.rfind('/') + 1);
                           name = name.substr(0, name.find('.'));
                           for (char& c : name) c = (c == '-') ? '_' : c;
                           return name;
                         });

// The particle and transparent passes' fragment shaders read storage buffers (the opaque depth on
// the visibility-buffer path) through the read-only binding their vertex shaders use, so every
// buffer those passes read is declared for both stages. At this size with auto exposure the
// transient "luminance partials" reuses memory that "Particle Render" read: with its reads
// declared for the vertex stage only, the WAR barrier before the reuse missed the fragment stage.
TEST(SceneValidation, AutoExposureAtriumRunsCleanOnEveryRenderPath) {
  for (const char* path : {"forward", "visbuffer", "meshlet"}) {
    WorkloadConfig config;
    config.scenePath = kRepo + "/atrium.json";
    config.device = "lavapipe";
    config.validation = true;
    config.width = 320;
    config.height = 180;
    config.knobs = {{"post.exposure", "auto"}, {"render.path", path}};
    auto workload = openSceneWorkload(config);
    for (uint32_t i = 0; i < 3; ++i) workload->renderFrame();
    workload->finish();
    EXPECT_EQ(workload->validationMessages(), 0u) << path;
  }
}

// lavapipe supports 1 and 4 samples: 2 is clamped down to 1, 8 down to 4, and both run clean.
uint32_t msaaSamplesOf(const Workload& workload) {
  const graph::FrameGraph* graph = frameGraphOf(workload);
  if (graph == nullptr) return 0;
  for (const auto& resource : graph->resources())
    if (resource.name == "hdr msaa") return resource.texture.samples;
  return 1;
}

TEST(SceneValidation, UnsupportedMsaaIsClampedDownAndRunsClean) {
  for (const auto& [requested, expected] : {std::pair{2u, 1u}, std::pair{8u, 4u}}) {
    WorkloadConfig config;
    config.scenePath = kRepo + "/no-lights.json";
    config.device = "lavapipe";
    config.validation = true;
    config.width = 160;
    config.height = 90;
    config.msaa = requested;
    auto workload = openSceneWorkload(config);
    workload->renderFrame();
    workload->finish();
    EXPECT_EQ(msaaSamplesOf(*workload), expected) << "--msaa " << requested;
    EXPECT_EQ(workload->validationMessages(), 0u) << "--msaa " << requested;
  }
}

}  // namespace
}  // namespace fgb::render
