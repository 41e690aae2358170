// Cold vs warm scene loads through fgb::scene::loadScene.
//   Cold: the cache directory is emptied before every iteration, so each load imports or
//         generates, cooks and stores.
//   Warm: the entry exists; each load reads it, verifies the checksum and decodes it.
// Run: build/bench/bench_scene_load [--benchmark_filter=Atrium]
#include <fgb/import/model_importer.hpp>
#include <fgb/scene/load.hpp>
#include <fgb/scene/stats.hpp>

#include <benchmark/benchmark.h>

#include <filesystem>
#include <stdexcept>

#include <unistd.h>

namespace {

const std::filesystem::path kSceneDir = std::filesystem::path(FGBENCH_SOURCE_DIR) / "scenes";

std::filesystem::path cacheDir(const char* tag) {
  return std::filesystem::temp_directory_path() / ("fgb-bench-scene-" + std::to_string(::getpid()) + "-" + tag);
}

void reportScene(benchmark::State& state, const fgb::scene::LoadedScene& loaded) {
  const auto s = fgb::scene::stats(loaded.scene);
  state.counters["triangles"] = double(s.triangles);
  state.counters["instances"] = double(s.instances);
  double produce = 0, cook = 0, read = 0;
  for (const auto& part : loaded.parts) {
    produce += part.produceMs;
    cook += part.cookMs;
    read += part.readMs;
  }
  state.counters["produce_ms"] = produce;
  state.counters["cook_ms"] = cook;
  state.counters["read_ms"] = read;
}

void loadCold(benchmark::State& state, const std::string& scene) {
  fgb::import::enableModelImport();
  const auto dir = cacheDir("cold");
  fgb::scene::LoadedScene last;
  for (auto _ : state) {
    state.PauseTiming();
    std::filesystem::remove_all(dir);
    state.ResumeTiming();
    last = fgb::scene::loadScene(kSceneDir / scene, {dir, true, {}});
    if (last.parts.empty() || last.parts[0].cache != "miss") throw std::runtime_error("cold load hit the cache");
  }
  reportScene(state, last);
  std::filesystem::remove_all(dir);
}

void loadWarm(benchmark::State& state, const std::string& scene) {
  fgb::import::enableModelImport();
  const auto dir = cacheDir("warm");
  std::filesystem::remove_all(dir);
  fgb::scene::loadScene(kSceneDir / scene, {dir, true, {}});  // fill the cache
  fgb::scene::LoadedScene last;
  for (auto _ : state) {
    last = fgb::scene::loadScene(kSceneDir / scene, {dir, true, {}});
    if (last.parts.empty() || last.parts[0].cache != "hit") throw std::runtime_error("warm load missed the cache");
  }
  reportScene(state, last);
  std::filesystem::remove_all(dir);
}

void BM_AtriumCold(benchmark::State& state) { loadCold(state, "atrium.json"); }
void BM_AtriumWarm(benchmark::State& state) { loadWarm(state, "atrium.json"); }
void BM_ModelDuckCold(benchmark::State& state) { loadCold(state, "model-collada-duck.json"); }
void BM_ModelDuckWarm(benchmark::State& state) { loadWarm(state, "model-collada-duck.json"); }
void BM_ModelEngineCold(benchmark::State& state) { loadCold(state, "model-glb-engine.json"); }
void BM_ModelEngineWarm(benchmark::State& state) { loadWarm(state, "model-glb-engine.json"); }

}  // namespace

BENCHMARK(BM_AtriumCold)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_AtriumWarm)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_ModelDuckCold)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ModelDuckWarm)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ModelEngineCold)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ModelEngineWarm)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
