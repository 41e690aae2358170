#include <algorithm>
#include <array>
#include <cmath>
#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/passes/pass_capture.hpp>
#include <set>

namespace fgb::harness {
namespace {

using render::CaptureContent;

// The counts that stand for nodes which write only buffers, and the node each one describes: the
// one home of that attribution. A key the run does not have (another render path) is skipped.
struct StatOwner {
  const char* key;
  const char* label;
  const char* pass;
};
constexpr std::array kStatOwners{
    StatOwner{"instances_visible", "visible instances", "Mesh Frustum Cull"},
    StatOwner{"triangles_visible", "visible triangles", "Mesh Frustum Cull"},
    StatOwner{"draws_issued", "draws issued", "Mesh Frustum Cull"},
    StatOwner{"lights_per_cluster_avg", "lights per cluster (mean)", "Clustered Light Cull"},
    StatOwner{"lights_per_cluster_max", "lights per cluster (max)", "Clustered Light Cull"},
    StatOwner{"clusters_overflowed", "overflowing clusters", "Clustered Light Cull"},
    StatOwner{"vis_clusters_visible", "visible clusters", "Cluster Cull"},
    StatOwner{"vis_triangles_small", "small triangles", "Triangle Filter"},
    StatOwner{"vis_triangles_large", "large triangles", "Triangle Filter"},
    StatOwner{"vis_raster_tile_jobs", "raster tile jobs", "Triangle Filter"},
    StatOwner{"vis_large_overflow", "large-triangle overflow", "Triangle Filter"},
};

bool hasNode(const std::vector<render::PassNode>& nodes, const std::string& name) {
  return std::any_of(nodes.begin(), nodes.end(), [&](const auto& node) { return node.name == name; });
}

// File names keep node names readable; only characters that file systems or shells trip over go.
std::string fileStem(std::string name) {
  for (char& c : name)
    if (c == '/' || c == '\\' || c == ':' || c == '*' || c == '?' || c == '"' || c == '<' || c == '>' || c == '|')
      c = '_';
  return name;
}

// A hue per draw index, for looking at the visibility words.
Image falseColour(const Image& visibility) {
  Image out = makeImage(visibility.width, visibility.height, Encoding::Srgb);
  for (std::size_t i = 0; i < visibility.pixelCount(); ++i) {
    out.rgba[i * 4 + 3] = 1.0f;
    if (visibility.rgba[i * 4] == 0.0f) continue;  // no depth key: nothing drawn
    const auto id = uint32_t(visibility.rgba[i * 4 + 1]) * 2654435761u;
    for (int c = 0; c < 3; ++c) out.rgba[i * 4 + c] = 0.25f + 0.75f * float((id >> (8 * c)) & 0xffu) / 255.0f;
  }
  return out;
}

int channelsOf(CaptureContent content) {
  return content == CaptureContent::Depth ? 1 : content == CaptureContent::Visibility ? 3 : 4;
}

CaptureContent contentOf(const std::string& name, const std::filesystem::path& file) {
  if (name == "color") return CaptureContent::Color;
  if (name == "depth") return CaptureContent::Depth;
  if (name == "visibility") return CaptureContent::Visibility;
  throw InputError(file.string() + ": unknown image content '" + name + "'");
}

// Images an earlier capture or bless left in `dir` that this set does not have (a node renamed or
// gone): removed, so the folder holds exactly what its passes.json lists.
void removeStaleImages(const std::filesystem::path& dir, const PassCaptureSet& set) {
  std::set<std::string> kept;
  for (const CapturedImage& image : set.images) {
    kept.insert(image.file);
    kept.insert(std::filesystem::path(image.file).stem().string() + ".png");
  }
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string extension = entry.path().extension().string();
    if ((extension == ".exr" || extension == ".png") && !kept.count(entry.path().filename().string()))
      std::filesystem::remove(entry.path(), ec);
  }
}

}  // namespace

std::string contentName(CaptureContent content) {
  switch (content) {
    case CaptureContent::Depth:
      return "depth";
    case CaptureContent::Visibility:
      return "visibility";
    default:
      return "color";
  }
}

PassCaptureSet makeCaptureSet(std::vector<render::PassCapture> captures, std::vector<render::PassNode> nodes,
                              const std::map<std::string, double>& runStats) {
  PassCaptureSet set;
  std::map<std::string, int> imagesPerPass;
  for (const auto& capture : captures) ++imagesPerPass[capture.pass];
  for (auto& capture : captures) {
    CapturedImage image{capture.pass, capture.resource, capture.content, {}, {}};
    const bool several = imagesPerPass[capture.pass] > 1;
    image.file = fileStem(several ? capture.pass + "-" + capture.resource : capture.pass) + ".exr";
    const Image decoded = fromRendered(capture.image);
    // Colour is stored as half floats: compare what the file holds. Depth and ids stay exact.
    image.image = capture.content == CaptureContent::Color ? quantizeToHalf(decoded) : decoded;
    // What the file gives back: a depth file has R only (G = B = 0), no file has alpha but colour.
    for (std::size_t i = 0; capture.content != CaptureContent::Color && i < image.image.pixelCount(); ++i) {
      if (capture.content == CaptureContent::Depth) image.image.rgba[i * 4 + 1] = image.image.rgba[i * 4 + 2] = 0.0f;
      image.image.rgba[i * 4 + 3] = 1.0f;
    }
    set.images.push_back(std::move(image));
  }
  for (const StatOwner& owner : kStatOwners) {
    const auto found = runStats.find(owner.key);
    if (found != runStats.end() && hasNode(nodes, owner.pass))
      set.stats.push_back({owner.key, owner.label, owner.pass, found->second});
  }
  set.nodes = std::move(nodes);
  return set;
}

void writeCaptureSet(const std::filesystem::path& dir, const PassCaptureSet& set, const CaptureExtras& extras) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot create the capture folder (" + ec.message() + ")");
  nlohmann::json images = nlohmann::json::array();
  for (const CapturedImage& image : set.images) {
    if (image.content == CaptureContent::Color) {
      writeExr(dir / image.file, image.image);
    } else {
      writeExrFloat(dir / image.file, image.image, channelsOf(image.content));
    }
    if (image.content == CaptureContent::Visibility)
      writePng(dir / (std::filesystem::path(image.file).stem().string() + ".png"), falseColour(image.image));
    nlohmann::json entry{{"pass", image.pass}, {"resource", image.resource}, {"content", contentName(image.content)},
                         {"file", image.file}, {"width", image.image.width}, {"height", image.image.height}};
    if (const auto extra = extras.images.find(image.file); extra != extras.images.end()) entry.update(extra->second);
    images.push_back(std::move(entry));
  }
  nlohmann::json nodes = nlohmann::json::array();
  for (const render::PassNode& node : set.nodes) {
    nlohmann::json inputs = nlohmann::json::array();
    for (const uint32_t input : node.inputs) inputs.push_back(set.nodes.at(input).name);
    nodes.push_back({{"name", node.name}, {"inputs", inputs}});
  }
  nlohmann::json stats = nlohmann::json::object();
  for (const PassStat& stat : set.stats) {
    stats[stat.key] = {{"value", stat.value}, {"label", stat.label}, {"pass", stat.pass}};
    if (const auto tolerance = extras.statTolerances.find(stat.key); tolerance != extras.statTolerances.end())
      stats[stat.key]["tolerance"] = tolerance->second;
  }
  nlohmann::json index{{"schema", 1}, {"nodes", nodes}, {"images", images}};
  if (!extras.made.is_null()) index["made"] = extras.made;
  // The images first, then the files that refer to them.
  writeFileAtomic(dir / "stats.json", dumpJson(stats));
  writeFileAtomic(dir / "passes.json", dumpJson(index));
  removeStaleImages(dir, set);
}

LoadedCaptureSet readCaptureSet(const std::filesystem::path& dir) {
  LoadedCaptureSet loaded;
  const std::filesystem::path index = dir / "passes.json";
  loaded.document = readJsonFile(index);
  const nlohmann::json& doc = loaded.document;
  try {
    std::map<std::string, uint32_t> indexOf;
    for (const auto& node : doc.at("nodes")) indexOf[node.at("name").get<std::string>()] = uint32_t(indexOf.size());
    for (const auto& node : doc.at("nodes")) {
      render::PassNode pass{node.at("name").get<std::string>(), {}};
      for (const auto& input : node.at("inputs")) pass.inputs.push_back(indexOf.at(input.get<std::string>()));
      loaded.set.nodes.push_back(std::move(pass));
    }
    for (const auto& entry : doc.at("images")) {
      CapturedImage image{entry.at("pass").get<std::string>(),
                          entry.at("resource").get<std::string>(),
                          contentOf(entry.at("content").get<std::string>(), index),
                          entry.at("file").get<std::string>(),
                          {}};
      image.image = readExr(dir / image.file);
      loaded.set.images.push_back(std::move(image));
    }
    const nlohmann::json stats = readJsonFile(dir / "stats.json");
    for (const auto& [key, stat] : stats.items())
      loaded.set.stats.push_back({key, stat.at("label").get<std::string>(), stat.at("pass").get<std::string>(),
                                  stat.at("value").get<double>(), stat.value("tolerance", 0.0)});
  } catch (const nlohmann::json::exception& e) {
    throw InputError(index.string() + ": malformed (" + e.what() + ")");
  } catch (const std::out_of_range&) {
    throw InputError(index.string() + ": an input names no node of the file");
  }
  return loaded;
}

std::vector<std::string> parseCaptureList(const std::string& value) {
  std::vector<std::string> names;
  if (value == "passes") return names;
  std::size_t start = 0;
  while (start <= value.size()) {
    const std::size_t comma = std::min(value.find(',', start), value.size());
    std::string name = value.substr(start, comma - start);
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    if (name.empty()) throw InputError("--capture " + value + ": an empty node name (give 'passes' or NODE,NODE,...)");
    names.push_back(std::move(name));
    start = comma + 1;
  }
  return names;
}

}  // namespace fgb::harness
