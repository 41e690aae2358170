#include <gtest/gtest.h>

#include <fgb/core/error.hpp>
#include <fgb/harness/sweep/sweep.hpp>
#include <fgb/harness/sweep_report/sweep_report.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "test_util.hpp"

namespace fgb::harness {
namespace {

TEST(SweepGrid, ParsesAxes) {
  const SweepAxis axis = parseVary("lighting.max_per_cluster=4,64");
  EXPECT_EQ(axis.key, "lighting.max_per_cluster");
  EXPECT_EQ(axis.values, (std::vector<std::string>{"4", "64"}));
  EXPECT_EQ(parseVary("size=640x360,1280x720").values.size(), 2u);
}

TEST(SweepGrid, BadAxesAreInputErrorsNamingTheOption) {
  for (const char* bad :
       {"msaa", "=1,2", "msaa=", "msaa=1,,4", "msaa=1,1", "msaa=3", "width=0", "size=640", "size=0x10", "height=abc"}) {
    try {
      parseVary(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--vary ") + bad), std::string::npos) << e.what();
    }
  }
}

TEST(SweepGrid, FullGridFirstAxisSlowest) {
  render::WorkloadConfig base;
  base.scenePath = "s.json";
  base.knobs = {{"post.exposure", "0.5"}};
  const auto grid = expandGrid(base, {parseVary("msaa=1,4"), parseVary("bloom.mips=2,4,6")});
  ASSERT_EQ(grid.size(), 6u);
  EXPECT_EQ(grid[0].label, "msaa=1 bloom.mips=2");
  EXPECT_EQ(grid[1].label, "msaa=1 bloom.mips=4");
  EXPECT_EQ(grid[5].label, "msaa=4 bloom.mips=6");
  EXPECT_EQ(grid[5].workload.msaa, 4u);
  EXPECT_EQ(grid[5].workload.knobs.at("bloom.mips"), "6");
  EXPECT_EQ(grid[5].workload.knobs.at("post.exposure"), "0.5");  // --set knobs kept
  const auto sized = expandGrid(base, {parseVary("size=320x180,64x32")});
  EXPECT_EQ(sized[1].workload.width, 64u);
  EXPECT_EQ(sized[1].workload.height, 32u);
}

TEST(SweepGrid, BadGridsAreInputErrors) {
  const render::WorkloadConfig base;
  EXPECT_THROW(expandGrid(base, {}), InputError);
  EXPECT_THROW(expandGrid(base, {parseVary("msaa=1,4"), parseVary("msaa=2")}), InputError);
  EXPECT_THROW(expandGrid(base, {parseVary("size=64x32"), parseVary("width=32,64")}), InputError);
  // 2^9 = 512 combinations: more than a sweep accepts.
  std::vector<SweepAxis> axes;
  for (char c = 'a'; c < 'a' + 9; ++c) axes.push_back(parseVary(std::string("k.") + c + "=0,1"));
  EXPECT_THROW(expandGrid(base, axes), InputError);
}

// A registry shaped like the real one (fgbench's knobs carry these roles).
KnobRegistry roleRegistry() {
  using enum ReferenceRole;
  KnobRegistry registry;
  registry.add({{"render.ssaa", KnobType::Integer, 1, 8, false, false, {}, "renderer", "", Approximation, "4"},
                {"lighting.mode",
                 KnobType::Word,
                 0,
                 0,
                 false,
                 false,
                 {"clustered", "all"},
                 "renderer",
                 "",
                 Approximation,
                 "all"},
                {"lighting.max_per_cluster",
                 KnobType::Integer,
                 1,
                 1024,
                 false,
                 false,
                 {},
                 "renderer",
                 "",
                 Approximation,
                 "1024"},
                {"render.path",
                 KnobType::Word,
                 0,
                 0,
                 false,
                 false,
                 {"forward", "visbuffer"},
                 "renderer",
                 "",
                 CostOnly,
                 "forward"},
                {"render.depth_prepass", KnobType::Flag, 0, 0, false, false, {}, "renderer", "", CostOnly, ""},
                {"bloom.mips", KnobType::Integer, 1, 10, false, false, {}, "renderer", "", Look, ""},
                {"post.exposure", KnobType::Number, 0, 100, true, false, {}, "scene", "", Look, ""},
                {"camera.fov", KnobType::Number, 0, 179, true, true, {}, "scene", "", Content, ""}});
  return registry;
}

TEST(SweepGrid, ReferenceSetsApproximationsExactKeepsTheLookAndPinsCostOnlyKnobs) {
  const KnobRegistry registry = roleRegistry();
  render::WorkloadConfig base;
  base.width = 320;
  base.knobs = {{"bloom.mips", "6"}, {"post.exposure", "0.7"}, {"camera.fov", "50"}, {"render.depth_prepass", "1"}};
  ReferenceRules rules{&registry, 4, 8, base.knobs};
  const auto grid = expandGrid(base, {parseVary("msaa=1,4"), parseVary("lighting.max_per_cluster=4,64"),
                                      parseVary("render.path=forward,visbuffer")});
  const render::WorkloadConfig ra = referenceOf(grid.front(), rules);
  EXPECT_EQ(ra.msaa, 8u);
  EXPECT_TRUE(ra.clampMsaaToPath);
  EXPECT_EQ(ra.width, 320u);
  EXPECT_EQ(ra.knobs.at("render.ssaa"), "4");
  EXPECT_EQ(ra.knobs.at("lighting.mode"), "all");              // approximation: exact
  EXPECT_EQ(ra.knobs.at("lighting.max_per_cluster"), "1024");  // approximation: exact
  EXPECT_EQ(ra.knobs.at("bloom.mips"), "6");                   // look: the scene's own, not the widest
  EXPECT_EQ(ra.knobs.at("post.exposure"), "0.7");              // look: copied
  EXPECT_EQ(ra.knobs.at("camera.fov"), "50");                  // content: copied
  EXPECT_EQ(ra.knobs.at("render.path"), "forward");            // cost only: pinned
  EXPECT_EQ(ra.knobs.count("render.depth_prepass"), 0u);       // cost only, no pinned value: dropped
  for (const auto& c : grid) EXPECT_EQ(referenceOf(c, rules).knobs, ra.knobs) << c.label;  // one reference
  // The convergence step is the same reference one SSAA step down.
  const auto step = convergenceStepOf(ra);
  ASSERT_TRUE(step);
  EXPECT_EQ(step->knobs.at("render.ssaa"), "3");
  render::WorkloadConfig single = ra;
  single.knobs.insert_or_assign("render.ssaa", std::string("1"));
  EXPECT_FALSE(convergenceStepOf(single));
  // Bias renders: only where a varied cost-only knob differs from the pinned value.
  EXPECT_FALSE(biasRenderOf(grid[0], ra, rules));  // render.path=forward
  const auto bias = biasRenderOf(grid[1], ra, rules);
  ASSERT_TRUE(bias);
  EXPECT_EQ(bias->knobs.at("render.path"), "visbuffer");
  EXPECT_EQ(bias->knobs.at("render.ssaa"), "4");
  EXPECT_EQ(biasLabelOf(grid[1], rules), "render.path=visbuffer");
  EXPECT_TRUE(variedLookKeys(grid, rules).empty());
}

TEST(SweepGrid, AVariedLookKnobIsJudgedAgainstTheScenesOwnValue) {
  const KnobRegistry registry = roleRegistry();
  render::WorkloadConfig base;
  ReferenceRules rules{&registry, 4, 8, {}};
  const auto grid = expandGrid(base, {parseVary("bloom.mips=2,10"), parseVary("camera.fov=40,60")});
  // No --set bloom.mips: the scene's own value, so the knob is dropped from the reference.
  EXPECT_EQ(referenceOf(grid[0], rules).knobs.count("bloom.mips"), 0u);
  EXPECT_EQ(referenceOf(grid[0], rules).knobs, referenceOf(grid[2], rules).knobs);
  // A varied content knob: each value its own reference.
  EXPECT_EQ(referenceOf(grid[0], rules).knobs.at("camera.fov"), "40");
  EXPECT_NE(referenceOf(grid[0], rules).knobs, referenceOf(grid[1], rules).knobs);
  EXPECT_EQ(variedLookKeys(grid, rules), (std::vector<std::string>{"bloom.mips"}));
  // The sweep's base value (a sweep file's or --set value) counts as the scene's look.
  rules.baseKnobs = {{"bloom.mips", "4"}};
  EXPECT_EQ(referenceOf(grid[0], rules).knobs.at("bloom.mips"), "4");
  // A key the registry lacks cannot be classified.
  const auto unknown = expandGrid(base, {parseVary("k.unknown=1,2")});
  EXPECT_THROW(referenceOf(unknown[0], rules), std::logic_error);
}

TEST(SweepGrid, SweepFileRoundTripAndErrors) {
  const auto dir = std::filesystem::temp_directory_path() / "fgb-sweep-file-test";
  std::filesystem::create_directories(dir);
  const auto good = dir / "good.json";
  std::ofstream(good) << R"({"schema": 1, "description": "d", "vary": [{"key": "msaa", "values": [1, 4]},
                          {"key": "render.path", "values": ["forward"]}], "set": {"bloom.mips": 3}, "width": 64})";
  const SweepFile file = loadSweepFile(good);
  ASSERT_EQ(file.axes.size(), 2u);
  EXPECT_EQ(file.axes[0].values, (std::vector<std::string>{"1", "4"}));
  EXPECT_EQ(file.knobs.at("bloom.mips"), "3");
  EXPECT_EQ(file.width, 64u);
  const auto bad = dir / "bad.json";
  std::ofstream(bad) << R"({"schema": 1, "vary": [{"key": "msaa", "values": [3]}]})";
  try {
    loadSweepFile(bad);
    ADD_FAILURE() << "msaa=3 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

// A workload whose frame time grows with MSAA and whose image approaches the reference's (msaa 8,
// value 0.5) except for msaa 2, which is both slower than msaa 1 and further off: dominated.
class GridWorkload : public render::Workload {
 public:
  using ValueOf = std::function<float(const render::WorkloadConfig&)>;
  explicit GridWorkload(const render::WorkloadConfig& c, std::vector<std::string>& log, ValueOf valueOf = {})
      : config_(c), log_(log), valueOf_(std::move(valueOf)) {
    device_.name = "fake";
    device_.type = "cpu";
  }
  const render::DeviceDescription& device() const override { return device_; }
  render::FrameTiming renderFrame() override {
    log_.push_back(std::to_string(config_.msaa));
    render::FrameTiming t;
    const double jitter = 0.01 * static_cast<double>(frame_++ % 7);
    t.passes.push_back({"Draw", "graphics", false, config_.msaa + jitter, 0.0});
    t.gpuFrameMs = config_.msaa + jitter;
    return t;
  }
  std::vector<render::FrameTiming> finish() override { return {}; }
  render::ImageRGBA32F readHdr() override { return image(value() * 4.0f); }
  render::ImageRGBA32F readDisplay() override { return image(value()); }
  std::string graphviz(render::GraphDetail) const override { return ""; }
  std::map<std::string, double> stats() const override { return {{"msaa", config_.msaa}}; }
  uint64_t validationMessages() const override { return 0; }

 private:
  float value() const {
    if (valueOf_) return valueOf_(config_);
    switch (config_.msaa) {
      case 1:
        return 0.40f;
      case 2:
        return 0.30f;
      case 4:
        return 0.49f;
      default:
        return 0.50f;
    }
  }
  static render::ImageRGBA32F image(float v) {
    render::ImageRGBA32F img{32, 16, {}};
    img.pixels.assign(32 * 16 * 4, v);
    for (std::size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
    return img;
  }
  render::WorkloadConfig config_;
  render::DeviceDescription device_;
  std::vector<std::string>& log_;
  ValueOf valueOf_;
  uint32_t frame_ = 0;
};

SweepPlan gridPlan() {
  render::WorkloadConfig base;
  base.scenePath = "grid.json";
  SweepPlan plan;
  plan.scene = base.scenePath;
  plan.configurations = expandGrid(base, {parseVary("msaa=1,2,4")});
  plan.warmup = 3;
  plan.frames = 24;
  plan.roundFrames = 8;
  plan.rewarmFrames = 0;
  return plan;
}

TEST(Sweep, MeasuresInterleavedRoundsAndFindsTheFront) {
  std::vector<std::string> log;
  std::vector<render::WorkloadConfig> opened;
  const WorkloadOpener open = [&](const render::WorkloadConfig& c) {
    opened.push_back(c);
    return std::make_unique<GridWorkload>(c, log);
  };
  const SweepResult result = runSweep(open, gridPlan());
  // Three configurations, then one reference rendered twice, then once one SSAA step down.
  ASSERT_EQ(opened.size(), 6u);
  EXPECT_EQ(opened[3].msaa, 8u);
  EXPECT_EQ(opened[3].knobs.at("render.ssaa"), "4");
  EXPECT_EQ(opened[5].knobs.at("render.ssaa"), "3");
  ASSERT_TRUE(result.references[0].convergence);
  EXPECT_EQ(result.references[0].convergence->label, "render.ssaa=3");
  ASSERT_EQ(result.references.size(), 1u);
  EXPECT_TRUE(result.references[0].identical);
  EXPECT_EQ(result.errorFloor, 0.0);
  EXPECT_EQ(result.rounds, 3u);  // 24 frames in rounds of 8
  // Rounds interleave: the log after warm-up holds 3 rounds x 3 blocks of 8 frames of one config.
  const std::size_t warm = 3 * 3 + 3 * 2;  // 3 warm-up frames per config, 2 image frames per reference render
  ASSERT_EQ(log.size(), warm + 3 * 24);
  for (int round = 0; round < 3; ++round) {
    std::vector<std::string> blocks;
    for (int b = 0; b < 3; ++b) blocks.push_back(log[warm + (round * 3 + b) * 8]);
    std::sort(blocks.begin(), blocks.end());
    EXPECT_EQ(blocks, (std::vector<std::string>{"1", "2", "4"})) << "round " << round;
  }
  const auto& c = result.configurations;
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].run.frameGpuMs.size(), 24u);
  EXPECT_GT(c[1].display.flip->mean, c[0].display.flip->mean);
  EXPECT_GT(c[0].display.flip->mean, c[2].display.flip->mean);
  EXPECT_TRUE(c[0].onFront);   // fastest
  EXPECT_FALSE(c[1].onFront);  // slower and worse than msaa 1
  EXPECT_EQ(c[1].dominatedBy, (std::vector<std::size_t>{0}));
  EXPECT_TRUE(c[2].onFront);  // most accurate
  EXPECT_EQ(frontByTime(result), (std::vector<std::size_t>{0, 2}));
}

TEST(Sweep, OrderOfEachRoundFollowsTheSeed) {
  auto firstBlocks = [](uint64_t seed) {
    std::vector<std::string> log;
    const WorkloadOpener open = [&](const render::WorkloadConfig& c) { return std::make_unique<GridWorkload>(c, log); };
    SweepPlan plan = gridPlan();
    plan.seed = seed;
    runSweep(open, plan);
    std::string order;
    for (std::size_t i = 15; i < log.size(); i += 8) order += log[i];
    return order;
  };
  EXPECT_EQ(firstBlocks(7), firstBlocks(7));
  bool someDiffer = false;
  for (uint64_t seed = 1; seed < 6 && !someDiffer; ++seed) someDiffer = firstBlocks(seed) != firstBlocks(seed + 10);
  EXPECT_TRUE(someDiffer);
}

TEST(Sweep, OutputsCarryTheFrontAndInlineEverything) {
  std::vector<std::string> log;
  const WorkloadOpener open = [&](const render::WorkloadConfig& c) { return std::make_unique<GridWorkload>(c, log); };
  SweepResult result = runSweep(open, gridPlan());
  result.axes = {parseVary("msaa=1,2,4")};
  const nlohmann::json j = sweepJson(result);
  EXPECT_EQ(j["schema"], kSweepSchema);
  EXPECT_EQ(j["front"], (nlohmann::json{"msaa=1", "msaa=4"}));
  EXPECT_EQ(j["configurations"][1]["dominated_by"], (nlohmann::json{"msaa=1"}));
  EXPECT_EQ(j["configurations"][0]["frame_gpu_ms"]["n"], 24);
  EXPECT_TRUE(j["references"][0]["repeat_identical"].get<bool>());
  const std::string csv = sweepCsv(result);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  const std::string html = sweepHtml(result);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  // 1 reference + 3 frames + 3 heat maps, all inline.
  std::size_t images = 0;
  for (auto at = html.find("data:image/png;base64,"); at != std::string::npos;
       at = html.find("data:image/png;base64,", at + 1))
    ++images;
  EXPECT_EQ(images, 7u);
  EXPECT_NE(timeErrorSvg(result).find("polyline"), std::string::npos);
  EXPECT_NE(sweepTable(result).find("* msaa=1"), std::string::npos);
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(Sweep, AccountsForItsWallTimeByPhaseAndConfiguration) {
  std::vector<std::string> log;
  const WorkloadOpener open = [&](const render::WorkloadConfig& c) { return std::make_unique<GridWorkload>(c, log); };
  testing::ScratchDir dir;
  SweepResult result = runSweep(open, gridPlan());
  writeSweepOutputs(dir.path(), result);
  ASSERT_EQ(result.references.size(), 1u);
  EXPECT_EQ(result.references[0].renders.size(), 2u);  // the reference and its repeat (noise floor)
  for (const auto& c : result.configurations) {
    EXPECT_EQ(c.wall.visits, 3u) << c.configuration.label;  // 24 frames in rounds of 8
    EXPECT_EQ(c.wall.rewarmFrames, 0u);
    EXPECT_EQ(c.wall.warmupFrames, 3u);
    EXPECT_GE(c.wall.measureMs, 0.0);
  }
  EXPECT_GT(result.overhead.reportMs, 0.0);
  const nlohmann::json j = nlohmann::json::parse(readText(dir / "sweep.json"));
  for (const char* phase : {"open", "references", "warmup", "measure", "close", "metrics", "report", "total"}) {
    EXPECT_TRUE(j["wall_ms"].contains(phase)) << phase;
  }
  EXPECT_GT(j["wall_ms"]["report"].get<double>(), 0.0);
  EXPECT_EQ(j["configurations"][0]["wall_ms"]["measured_frames"], 24);
  EXPECT_EQ(j["configurations"][0]["wall_ms"]["visits"], 3);
  EXPECT_EQ(j["references"][0]["renders_ms"].size(), 2u);
  const std::string summary = sweepWallSummary(result);
  EXPECT_NE(summary.find("references"), std::string::npos);
  EXPECT_NE(summary.find("msaa=4: open"), std::string::npos);
  EXPECT_NE(summary.find("24 measured + 0 re-warm frames in 3 visit(s)"), std::string::npos);
}

// On a CPU device with trimOnCpu a sweep renders only the frames its statistics use: warm-up up to
// the compared frame, no re-warm frame per visit, and a visit ends once the configuration is stable.
TEST(Sweep, OnACpuDeviceRendersNoFrameBeyondNeed) {
  auto framesRendered = [](bool trim, SweepResult& result) {
    std::vector<std::string> log;
    const WorkloadOpener open = [&](const render::WorkloadConfig& c) { return std::make_unique<GridWorkload>(c, log); };
    SweepPlan plan = gridPlan();
    plan.warmup = 8;
    plan.rewarmFrames = 1;
    plan.roundFrames = 16;
    plan.untilStable = StabilityRule{0.5, 12, 16};  // wide: stable as soon as it has 12 frames
    plan.trimOnCpu = trim;
    plan.trimWarmupOnCpu = trim;
    plan.cpuStableCheckFrames = 4;
    result = runSweep(open, plan);
    return log.size();
  };
  SweepResult trimmed, full;
  const std::size_t trimmedFrames = framesRendered(true, trimmed), fullFrames = framesRendered(false, full);
  const std::size_t referenceFrames = 3 * 2;  // two renders and the convergence step, 2 frames each
  // Trimmed: 2 warm-up frames (the compared frame is the second) and 12 measured, checked every 4.
  EXPECT_EQ(trimmed.warmupFrames, 2u);
  EXPECT_EQ(trimmed.rewarmFrames, 0u);
  EXPECT_EQ(trimmed.stableCheckFrames, 4u);
  EXPECT_EQ(trimmedFrames, referenceFrames + 3 * (2 + 12));
  // Untrimmed: 8 warm-up frames, 1 re-warm and a whole round of 16 frames each.
  EXPECT_EQ(fullFrames, referenceFrames + 3 * (8 + 1 + 16));
  for (const auto& c : trimmed.configurations) {
    EXPECT_EQ(c.run.frameGpuMs.size(), 12u) << c.configuration.label;
    EXPECT_TRUE(c.stable);
  }
  // The same front either way.
  EXPECT_EQ(frontByTime(trimmed), frontByTime(full));
}

// A converging renderer: the image approaches 0.5 with more SSAA (SSAA 3 is 0.01 short of SSAA 4:
// the reference's convergence gap), and the visibility-buffer path is 0.08 off at any sampling (its
// bias).
float convergingValue(const render::WorkloadConfig& c) {
  const int ssaa = c.knobs.count("render.ssaa") ? std::stoi(c.knobs.at("render.ssaa")) : 1;
  const bool visbuffer = c.knobs.count("render.path") && c.knobs.at("render.path") == "visbuffer";
  const float sampled = ssaa >= 4 ? 0.5f : (ssaa == 3 ? 0.49f : 0.40f);
  return sampled + (visbuffer ? 0.08f : 0.0f);
}

TEST(Sweep, ChecksTheReferencesConvergenceAndEachPathsBias) {
  const KnobRegistry registry = roleRegistry();
  std::vector<std::string> log;
  std::vector<render::WorkloadConfig> opened;
  const WorkloadOpener open = [&](const render::WorkloadConfig& c) {
    opened.push_back(c);
    return std::make_unique<GridWorkload>(c, log, convergingValue);
  };
  render::WorkloadConfig base;
  base.scenePath = "grid.json";
  SweepPlan plan;
  plan.scene = base.scenePath;
  plan.configurations = expandGrid(base, {parseVary("render.path=forward,visbuffer"), parseVary("render.ssaa=1,3")});
  plan.referenceRules = {&registry, 4, 8, {}};
  plan.warmup = 2;
  plan.frames = 8;
  plan.roundFrames = 8;
  SweepResult result = runSweep(open, plan);
  result.axes = {parseVary("render.path=forward,visbuffer"), parseVary("render.ssaa=1,3")};
  // One reference (path and SSAA share it): two renders, the convergence step, one bias render.
  ASSERT_EQ(result.references.size(), 1u);
  const ReferenceOutcome& ref = result.references[0];
  ASSERT_EQ(opened.size(), 4u + 4u);
  ASSERT_TRUE(ref.convergence);
  EXPECT_GT(ref.convergenceGap(), 0.0);
  ASSERT_EQ(ref.biases.size(), 1u);
  EXPECT_EQ(ref.biases[0].label, "render.path=visbuffer");
  EXPECT_TRUE(ref.biases[0].workload.clampMsaaToPath);
  EXPECT_GT(ref.biases[0].gap(), ref.convergenceGap());
  // forward ssaa=3 renders exactly the convergence step: within the gap, so unresolved; forward
  // ssaa=1 is far off; the visbuffer configurations carry the path's bias.
  const auto& c = result.configurations;
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[1].configuration.label, "render.path=forward render.ssaa=3");
  EXPECT_TRUE(c[1].unresolved);
  EXPECT_FALSE(c[0].unresolved);
  EXPECT_FALSE(c[0].bias);
  ASSERT_TRUE(c[2].bias);
  EXPECT_EQ(*c[2].bias, 0u);
  const nlohmann::json j = sweepJson(result);
  EXPECT_TRUE(j["configurations"][1]["unresolved"].get<bool>());
  EXPECT_EQ(j["configurations"][2]["bias"]["label"], "render.path=visbuffer");
  EXPECT_EQ(j["references"][0]["convergence"]["label"], "render.ssaa=3");
  EXPECT_EQ(j["method"]["roles"]["render.path"], "cost-only");
  EXPECT_EQ(j["method"]["roles"]["render.ssaa"], "approximation");
  const std::string html = sweepHtml(result);
  EXPECT_NE(html.find("unresolved-band"), std::string::npos);
  EXPECT_NE(html.find("bias of render.path=visbuffer"), std::string::npos);
  EXPECT_NE(sweepTable(result).find("unresolved"), std::string::npos);
}

TEST(Sweep, AVariedLookKnobsColumnIsTheChangeFromTheScenesLook) {
  const KnobRegistry registry = roleRegistry();
  std::vector<std::string> log;
  const WorkloadOpener open = [&](const render::WorkloadConfig& c) { return std::make_unique<GridWorkload>(c, log); };
  SweepPlan plan = gridPlan();
  plan.configurations = expandGrid(render::WorkloadConfig{}, {parseVary("bloom.mips=2,6")});
  plan.referenceRules = {&registry, 4, 8, {}};
  SweepResult result = runSweep(open, plan);
  result.axes = {parseVary("bloom.mips=2,6")};
  EXPECT_EQ(result.lookKeys, (std::vector<std::string>{"bloom.mips"}));
  EXPECT_EQ(errorColumnName(result), "LDR-FLIP change from the scene's look");
  EXPECT_NE(sweepMarkdown(result).find("change from the scene's look"), std::string::npos);
  EXPECT_EQ(sweepJson(result)["method"]["roles"]["bloom.mips"], "look");
}

TEST(SweepPath, TimesAreMidpointsOfEqualSpans) {
  EXPECT_EQ(spreadPathTimes(34.0, 4), (std::vector<double>{4.25, 12.75, 21.25, 29.75}));
  EXPECT_EQ(spreadPathTimes(1.0, 3), (std::vector<double>{0.167, 0.5, 0.833}));  // to the millisecond
  EXPECT_TRUE(spreadPathTimes(34.0, 0).empty());
  EXPECT_TRUE(spreadPathTimes(0.0, 4).empty());
  EXPECT_EQ(atPathTime({}, 12.75).knobs.at("camera.time"), "12.75");
}

// Along a camera path each configuration is judged at every path time against its reference at
// the same time: the image's value depends on camera.time, so a frame compared with another
// time's reference would be off. msaa 8 renders what its reference (msaa 8, SSAA 4) renders: no
// error at any time; msaa 1 drifts further from it the later the time.
TEST(SweepPath, JudgesEachPathTimeAgainstItsOwnReference) {
  std::vector<std::string> log;
  std::vector<render::WorkloadConfig> opened;
  const auto valueAt = [](const render::WorkloadConfig& c) {
    const auto time = c.knobs.find("camera.time");
    const float t = time == c.knobs.end() ? 0.0f : std::stof(time->second);
    return 0.2f + 0.05f * t + (c.msaa == 1 ? 0.02f * t : 0.0f);
  };
  const WorkloadOpener open = [&](const render::WorkloadConfig& c) {
    opened.push_back(c);
    return std::make_unique<GridWorkload>(c, log, valueAt);
  };
  SweepPlan plan = gridPlan();
  plan.configurations = expandGrid(render::WorkloadConfig{}, {parseVary("msaa=1,8")});
  plan.pathTimes = {1.0, 3.0, 5.0};
  SweepResult result = runSweep(open, plan);
  result.axes = {parseVary("msaa=1,8")};
  std::size_t atTimes = 0;
  for (const auto& c : opened) atTimes += c.knobs.count("camera.time");
  EXPECT_EQ(atTimes, 3u * (1 + 2));  // the reference and both configurations at each time
  const auto& exact = result.configurations[1];
  ASSERT_EQ(exact.pathErrors.size(), 3u);
  EXPECT_EQ(exact.pathErrorWorst(), 0.0);
  const auto& coarse = result.configurations[0];
  ASSERT_EQ(coarse.pathErrors.size(), 3u);
  EXPECT_EQ(coarse.pathErrors[2].timeS, 5.0);
  EXPECT_GT(displayError(coarse.pathErrors[0].display), 0.0);
  EXPECT_GT(displayError(coarse.pathErrors[2].display), displayError(coarse.pathErrors[1].display));
  EXPECT_EQ(coarse.pathErrorWorstTime(), 5.0);
  EXPECT_DOUBLE_EQ(coarse.pathErrorMean(),
                   (displayError(coarse.pathErrors[0].display) + displayError(coarse.pathErrors[1].display) +
                    displayError(coarse.pathErrors[2].display)) /
                       3.0);
  EXPECT_DOUBLE_EQ(sweepError(coarse), coarse.pathErrorMean());  // the front judges the mean
  const nlohmann::json j = sweepJson(result);
  EXPECT_EQ(j["method"]["path_times_s"], (std::vector<double>{1.0, 3.0, 5.0}));
  EXPECT_DOUBLE_EQ(j["configurations"][0]["path_error"]["ldr_flip_worst"].get<double>(), coarse.pathErrorWorst());
  EXPECT_EQ(j["configurations"][0]["path_error"]["times"].size(), 3u);
  EXPECT_NE(sweepMarkdown(result).find("## Along the camera path"), std::string::npos);
  EXPECT_NE(sweepTable(result).find("msaa=1: LDR-FLIP mean"), std::string::npos);
  EXPECT_NE(sweepCsv(result).find("path_ldr_flip_mean,path_ldr_flip_worst\n"), std::string::npos);
}
}  // namespace
}  // namespace fgb::harness
