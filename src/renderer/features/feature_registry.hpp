// The feature registry: every render feature a render path (context/render_path.hpp) can name,
// with its factory, its options, where in the frame it goes and what it needs from the features
// before it and provides to those after it. scene_workload/render_paths.cpp checks a path against
// it and composes the path's features from it. Adding a feature = a folder under features/ and one
// entry in featureKinds() (feature_registry.cpp).
#pragma once

#include "context/render_feature.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace fgb::features {

// Where a feature's nodes go in the frame. A path lists its features in this order (those of one
// phase in any order): colour passes before the MSAA resolve, which comes before the SSAA resolve,
// bloom, exposure (which reads this frame's pre-exposure after bloom) and tone mapping.
enum class FeaturePhase : uint8_t { Lighting, Opaque, SceneColour, MsaaResolve, SsaaResolve, Bloom, Exposure, ToneMapping };
[[nodiscard]] const char* phaseName(FeaturePhase phase);  // "scene colour", ...
[[nodiscard]] std::string phaseOrder();                   // "lighting, opaque, ..., tone mapping"

// One option of a feature: its name, its default value (whose JSON type is the option's type) and
// what it does.
struct FeatureOption {
  std::string name;
  nlohmann::json defaultValue;
  std::string help;
};

// Products: what features hand on to each other (through the blackboard and FrameTargets), by name.
// A path is checked so that every feature finds what it needs before it (or in itself), and the
// frame gets the opaque scene (once) and the display image:
//   clusters             the cooked clusters are on the GPU (the path's "upload": {"clusters": true})
//   light_lists          per-cluster light lists (clustered_lighting; optional for the shading passes)
//   opaque_scene         the opaque and alpha-masked scene is drawn (every path needs it, from one feature)
//   depth_attachment     its depth is in the depth attachment ("depth_test": "attachment" reads it)
//   opaque_depth_buffer  its depth is in a buffer ("depth_test": "opaque_depth_buffer" reads it)
//   hdr                  the scene's single-sample HDR image (after the MSAA resolve)
//   output_hdr           the HDR image at the output size (after the SSAA resolve)
//   bloom                the bloom texture tone mapping adds
//   display              the tone-mapped display image (every path needs it)
struct FeatureContract {
  std::vector<std::string> needs;
  std::vector<std::string> provides;
};
// Who provides a product, in words, for messages: "visbuffer", "meshes with \"opaque\": true", ...
[[nodiscard]] std::string providersOf(std::string_view product);
// The product the path's depth test reads.
[[nodiscard]] const char* depthProductOf(DepthTest test);

struct FeatureKind {
  std::string name;  // as a path names it: "meshes", "visbuffer", ...
  FeaturePhase phase = FeaturePhase::SceneColour;
  std::string help;
  std::vector<FeatureOption> options;
  uint32_t maxMsaa = 8;           // the most MSAA samples it draws with (the path's max_msaa is at most this)
  bool computeWritesHdr = false;  // a compute node of it writes the HDR image (storage usage)
  // What it needs and provides with these options (defaults filled in) on this path.
  std::function<FeatureContract(const nlohmann::json& options, const RenderPath& path)> contract;
  // The feature, not yet initialised (FeatureInit brings the device, scene, settings and path).
  std::function<std::unique_ptr<IRenderFeature>(const nlohmann::json& options)> create;
};

// Every feature, in phase order.
[[nodiscard]] const std::vector<FeatureKind>& featureKinds();
// The kind named `name`; nullptr when there is none.
[[nodiscard]] const FeatureKind* findFeatureKind(std::string_view name);
// "bloom, clustered_lighting, ...": every kind's name, sorted.
[[nodiscard]] std::string knownFeatureNames();

}  // namespace fgb::features
