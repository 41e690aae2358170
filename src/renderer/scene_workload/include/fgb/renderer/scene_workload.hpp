// The Workload for scene JSON files: loads the scene, uploads it, builds the frame graph from the
// render features and renders it. openWorkload() dispatches every non-"builtin:" scene here.
#pragma once

#include <fgb/renderer/workload.hpp>

#include <memory>

namespace fgb::render {

// Throws fgb::InputError (bad scene/option), fgb::DeviceError (no device, GPU failure).
std::unique_ptr<Workload> openSceneWorkload(const WorkloadConfig& config);

}  // namespace fgb::render
