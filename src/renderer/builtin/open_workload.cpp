// openWorkload(): a small dispatcher from the scene path to the workload that renders it.
#include <fgb/core/error.hpp>
#include <fgb/renderer/workload.hpp>

#include "proof_workload.hpp"

#if FGB_HAVE_SCENE_WORKLOAD
#include <fgb/renderer/scene_workload.hpp>

#include "features/context/render_settings.hpp"
#endif

namespace fgb::render {

std::unique_ptr<Workload> openWorkload(const WorkloadConfig& config) {
  if (config.scenePath == "builtin:proof") return openProofWorkload(config);
  if (config.scenePath.starts_with("builtin:")) {
    throw InputError("unknown built-in scene '" + config.scenePath + "' (known: builtin:proof)");
  }
#if FGB_HAVE_SCENE_WORKLOAD
  return openSceneWorkload(config);
#else
  throw InputError(config.scenePath + ": scene files are not supported by this build (only builtin:proof)");
#endif
}

std::vector<KnobSpec> rendererKnobSpecs() {
#if FGB_HAVE_SCENE_WORKLOAD
  return features::rendererKnobSpecs();
#else
  return {};  // builtin:proof has no knobs
#endif
}

}  // namespace fgb::render
