// Renderer settings: the run's size and MSAA plus the renderer-owned `--set` knobs. Post-processing
// parameters (exposure, bloom) are scene settings (post.* knobs, applied by the scene loader).
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace fgb::features {

enum class DebugView : uint8_t { None, LightComplexity };

// render.path: which features draw the opaque scene. Forward (the thesis' renderer) rasterises it
// in "Mesh Render"; VisBuffer culls clusters and triangles, rasterises ids in compute and shades
// from the visibility buffer (features/visbuffer).
enum class RenderPath : uint8_t { Forward, VisBuffer };

struct RenderSettings {
  uint32_t width = 640;
  uint32_t height = 360;
  uint32_t msaa = 1;
  RenderPath renderPath = RenderPath::Forward;  // render.path = forward | visbuffer
  bool depthPrepass = false;          // render.depth_prepass
  DebugView debugView = DebugView::None;  // debug.view = none | light-complexity
  uint32_t clusterSlices = 24;        // lighting.slices
  uint32_t maxLightsPerCluster = 128; // lighting.max_per_cluster (overflow guard)
  uint32_t bloomMips = 6;             // bloom.mips
  uint32_t particleSeedOffset = 0;    // particles.seed (added to every emitter's seed)
};

// Keys of the renderer knobs, for the CLI's unknown-key check.
bool isRendererKnob(const std::string& key);

// Applies the renderer-owned knobs; other keys are ignored (they belong to the scene or harness).
// Throws fgb::InputError "--set key=value: expected ..." for malformed values.
void applyRendererKnobs(RenderSettings& settings, const std::map<std::string, std::string>& knobs);

}  // namespace fgb::features
