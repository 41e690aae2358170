// Graphviz output. Nodes are boxes coloured by type (graphics/compute/transfer), resources are
// ellipses (imported: double border); edges follow resource versions. Culled nodes are dashed and
// carry the reason. The full detail adds resource parameters, use kinds, queues, submits,
// aliasing slots and each step's barriers, named in words (fgb/graph/barrier_names.hpp).
#include <fgb/graph/barrier_names.hpp>
#include <fgb/graph/dot.hpp>
#include <sstream>
#include <string>

namespace fgb::graph {
namespace {

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out;
}

// By NodeType (FrameGraph::addNode accepts no other value).
constexpr std::string_view kFillColours[] = {"#f4a261", "#8ecae6", "#b5e48c"};

std::string describeResource(const ResourceDecl& decl, const CompiledGraph& compiled, uint32_t r) {
  std::ostringstream s;
  const ResolvedResource& res = compiled.resources[r];
  if (decl.kind == ResourceKind::Texture) {
    s << toString(res.texture.format) << "\\n" << res.texture.extent.width << "x" << res.texture.extent.height;
    if (res.texture.samples > 1) s << " x" << res.texture.samples << " MSAA";
    if (res.texture.mipLevels > 1) s << " mips " << res.texture.mipLevels;
  } else {
    s << res.buffer.size << " bytes";
  }
  if (decl.imported) {
    s << "\\nimported";
  } else if (r < compiled.aliasing.placements.size() && compiled.aliasing.placements[r].heap != kInvalidIndex) {
    const Placement& p = compiled.aliasing.placements[r];
    s << "\\nheap " << p.heap << " @" << p.offset << " +" << p.size;
  }
  if (r < compiled.lifetimes.size() && compiled.lifetimes[r].used()) {
    s << "\\nlife " << compiled.lifetimes[r].first << ".." << compiled.lifetimes[r].last;
  }
  return s.str();
}

std::string nodeLabel(const FrameGraph& graph, const CompiledGraph& compiled, const CullDiagnostics& cullReasons,
                      uint32_t n, DotDetail detail) {
  const NodeDecl& node = graph.nodes()[n];
  const NodeInfo& info = compiled.nodes[n];
  std::ostringstream s;
  s << escape(node.name);
  if (info.culled) {
    s << "\\nculled: " << escape(cullReasons.describe(n));
    return s.str();
  }
  if (detail == DotDetail::Brief) return s.str();
  s << "\\n" << toString(node.type) << " on queue " << info.queue;
  s << ", level " << info.level << ", submit " << info.submit;
  auto listBarriers = [&](std::string_view when, BarrierRange range) {
    for (uint32_t i = range.first; i < range.first + range.count; ++i) {
      const ResourceDecl& resource = graph.resources()[compiled.barriers[i].resource];
      const bool texture = resource.kind == ResourceKind::Texture;
      s << "\\n" << when << ": " << escape(describeBarrier(compiled.barriers[i], resource.name, texture));
    }
  };
  listBarriers("before", compiled.steps[info.step].before);
  listBarriers("after", compiled.steps[info.step].after);
  return s.str();
}

void writeNodes(std::ostringstream& s, const FrameGraph& graph, const CompiledGraph& compiled, DotDetail detail) {
  // One index for the whole dump: cullDiagnostic() per culled node would rescan the graph for each.
  const CullDiagnostics cullReasons(graph, compiled);
  for (uint32_t n = 0; n < graph.nodes().size(); ++n) {
    const NodeDecl& node = graph.nodes()[n];
    const bool culled = compiled.nodes[n].culled;
    s << "  n" << n << " [shape=box, style=\"" << (culled ? "dashed" : "filled,rounded") << "\", fillcolor=\""
      << kFillColours[static_cast<size_t>(node.type)] << "\", label=\""
      << nodeLabel(graph, compiled, cullReasons, n, detail) << "\"];\n";
  }
}

void writeResources(std::ostringstream& s, const FrameGraph& graph, const CompiledGraph& compiled, DotDetail detail) {
  for (uint32_t r = 0; r < graph.resources().size(); ++r) {
    const ResourceDecl& decl = graph.resources()[r];
    s << "  r" << r << " [shape=ellipse, " << (decl.imported ? "peripheries=2, " : "")
      << (r < compiled.resourceAlive.size() && compiled.resourceAlive[r] ? "" : "style=dashed, ") << "label=\""
      << escape(decl.name);
    if (detail == DotDetail::Full) s << "\\n" << describeResource(decl, compiled, r);
    s << "\"];\n";
  }
}

void writeUses(std::ostringstream& s, const FrameGraph& graph, DotDetail detail) {
  for (uint32_t n = 0; n < graph.nodes().size(); ++n) {
    for (const ResourceAccess& use : graph.accesses(n)) {
      const std::string label = detail == DotDetail::Full ? std::string(toString(use.access)) : std::string();
      if (use.readVersion != kInvalidIndex) {
        s << "  r" << use.resource << " -> n" << n << " [label=\"" << label << " v" << use.readVersion << "\"];\n";
      }
      if (use.writeVersion != kInvalidIndex) {
        s << "  n" << n << " -> r" << use.resource << " [color=\"#c0392b\", label=\"" << label << " v"
          << use.writeVersion << "\"];\n";
      }
    }
  }
}

void writeSubmits(std::ostringstream& s, const CompiledGraph& compiled) {
  for (uint32_t i = 0; i < compiled.submits.size(); ++i) {
    const Submit& submit = compiled.submits[i];
    s << "  subgraph cluster_submit" << i << " {\n    label=\"queue " << submit.queue << " submit "
      << submit.signalValue;
    for (const SemaphoreWait& w : submit.waits) s << "\\nwaits q" << w.queue << " >= " << w.value;
    s << "\\nsignals " << submit.signalValue << "\"; style=dotted;\n";
    for (uint32_t k = 0; k < submit.stepCount; ++k) s << "    n" << compiled.steps[submit.firstStep + k].node << ";\n";
    s << "  }\n";
  }
  for (const Edge& e : compiled.syncEdges) {
    s << "  n" << e.from << " -> n" << e.to << " [style=bold, color=\"#6a4c93\", constraint=false, label=\"G*\"];\n";
  }
}

}  // namespace

std::string toDot(const FrameGraph& graph, const CompiledGraph& compiled, DotDetail detail) {
  std::ostringstream s;
  s << "digraph framegraph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n"
       "  edge [fontname=\"Helvetica\", fontsize=8];\n";
  if (detail == DotDetail::Full) {
    s << "  label=\"transient memory: " << compiled.aliasing.peakBytesAliased << " bytes aliased, "
      << compiled.aliasing.peakBytesUnaliased << " unaliased\";\n";
  }
  writeNodes(s, graph, compiled, detail);
  writeResources(s, graph, compiled, detail);
  writeUses(s, graph, detail);
  if (detail == DotDetail::Full) writeSubmits(s, compiled);
  s << "}\n";
  return s.str();
}

}  // namespace fgb::graph
