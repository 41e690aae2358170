// The Workload for scene JSON files: loads the scene, uploads it, builds the frame graph from the
// render features and renders it. openWorkload() dispatches every non-"builtin:" scene here.
#pragma once

#include <fgb/graph/frame_graph.hpp>
#include <fgb/renderer/workload.hpp>

#include <memory>

namespace fgb::render {

// Throws fgb::InputError (bad scene/option), fgb::DeviceError (no device, GPU failure).
std::unique_ptr<Workload> openSceneWorkload(const WorkloadConfig& config);

// The frame graph a scene workload declared (jobs moved out), e.g. to compile it again with other
// queue families in tests; null if `workload` is not a scene workload.
const graph::FrameGraph* frameGraphOf(const Workload& workload);

}  // namespace fgb::render
