// VulkanGraph construction: compile with the device's real memory requirements and queue families,
// create the transient resources inside their aliasing heaps, and translate every barrier and
// rendering info to Vulkan structures once, so executing a frame only records and submits.
#include "executable_graph.hpp"

#include "translate.hpp"

#include <fgb/core/align.hpp>
#include <fgb/core/error.hpp>
#include <fgb/graph/compiler.hpp>

#include <algorithm>
#include <queue>
#include <string>
#include <string_view>
#include <unordered_map>

namespace fgb::vulkan {
namespace {

rhi::TextureDesc textureDesc(std::string_view name, const graph::TextureDesc& t, rhi::TextureUsage usage) {
  return {std::string(name), t.format, t.extent, t.mipLevels, t.layers, t.samples, usage};
}

rhi::BufferDesc bufferDesc(std::string_view name, const graph::BufferDesc& b, rhi::BufferUsage usage) {
  return {std::string(name), b.size, usage, rhi::MemoryUsage::DeviceLocal};
}

// Per resource, the union of `usageFor(access)` over every use the graph declares of it.
template <typename Usage>
std::vector<Usage> usagesOf(const graph::FrameGraph& graph, Usage (*usageFor)(graph::Access)) {
  std::vector<Usage> usage(graph.resources().size(), 0);
  for (uint32_t n = 0; n < graph.nodes().size(); ++n) {
    for (const graph::ResourceAccess& use : graph.accesses(n)) usage[use.resource] |= usageFor(use.access);
  }
  return usage;
}

}  // namespace

VulkanGraph::VulkanGraph(VulkanDevice& device, graph::FrameGraph&& graph, const rhi::GraphOptions& options)
    : device_(device), id_(device.registerGraph(this)), options_(options), declaration_(std::move(graph)),
      commandBuffer_(device) {
  try {
    mapQueues(options.queues, options.separateQueues);
    compiled_ = graph::compile(declaration_, compileOptions());
    jobs_ = declaration_.takeJobs();
    recordingKeys_ = declaration_.takeRecordingKeys();
    createResources();
    translateBarriers();
    translateRendering();
    orderSubmits();
    createSpin();
    createSyncAndSlots();
    createScopedSets();
    hashStaticKeys();
  } catch (...) {
    release();  // the destructor will not run
    throw;
  }
}

VulkanGraph::~VulkanGraph() {
  waitForAll();
  release();
}

// Gives back what the graph registered and created: its registration, its transients and their heaps.
void VulkanGraph::release() {
  device_.unregisterGraph(id_);
  for (uint32_t r = 0; r < ownsResource_.size(); ++r) {
    if (!ownsResource_[r]) continue;
    if (buffers_[r].valid()) device_.destroyBuffer(buffers_[r]);
    if (textures_[r].valid()) device_.destroyTexture(textures_[r]);
  }
  for (const auto& heap : heaps_) device_.memory().free(heap);
}

void VulkanGraph::mapQueues(uint32_t requested, bool separate) {
  const auto& deviceQueues = device_.queues();
  const auto& ofClass = device_.queueOfClass();
  // Requested queue r serves class r (the last one also the classes beyond it) on the device queue
  // of that class. Requests that land on one device queue merge (unless kept apart): one queue
  // needs no semaphores, and its barriers are planned as one queue's.
  const uint32_t wanted = requested == 0 ? graph::kQueueClassCount : std::min(requested, graph::kQueueClassCount);
  std::vector<uint32_t> requestOf;  // per logical queue: the request it serves first
  deviceQueueOf_.clear();
  for (uint32_t c = 0; c < graph::kQueueClassCount; ++c) {
    const uint32_t request = std::min(c, wanted - 1);
    const uint32_t deviceQueue = ofClass[request];
    uint32_t logical = 0;
    while (logical < deviceQueueOf_.size() &&
           (separate ? requestOf[logical] != request : deviceQueueOf_[logical] != deviceQueue)) {
      ++logical;
    }
    if (logical == deviceQueueOf_.size()) {
      deviceQueueOf_.push_back(deviceQueue);
      requestOf.push_back(request);
    }
    logicalOfClass_[c] = logical;
  }
  logicalQueues_ = static_cast<uint32_t>(deviceQueueOf_.size());
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device_.physical(), &properties);
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device_.physical(), &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(device_.physical(), &familyCount, families.data());
  timestampMask_.resize(logicalQueues_);
  for (uint32_t q = 0; q < logicalQueues_; ++q) {
    const uint32_t bits = families[deviceQueues[deviceQueueOf_[q]].family].timestampValidBits;
    timestampMask_[q] = bits == 0 ? 0 : bits >= 64 ? ~0ull : (1ull << bits) - 1;
  }
}

graph::CompileOptions VulkanGraph::compileOptions() {
  graph::CompileOptions options;
  options.queueCount = logicalQueues_;
  options.queueOfClass = logicalOfClass_;
  for (uint32_t q = 0; q < logicalQueues_; ++q) {
    options.familyOfQueue[q] = device_.queues()[deviceQueueOf_[q]].family;
  }
  options.buffersShareFamilies = true;  // VulkanDevice::bufferInfo
  options.cull = options_.cull;
  options.profile = options_.compileProfile;
  options.alias = options_.alias;

  // Real requirements of the resource as it will be created (usages gathered from the graph).
  auto textureUsage = std::make_shared<std::vector<rhi::TextureUsage>>(textureUsages());
  auto bufferUsage = std::make_shared<std::vector<rhi::BufferUsage>>(bufferUsages());
  auto indexOfFirstVersion = std::make_shared<std::unordered_map<uint32_t, uint32_t>>();
  const auto& resources = declaration_.resources();
  for (uint32_t r = 0; r < resources.size(); ++r) indexOfFirstVersion->emplace(resources[r].firstVersion, r);
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device_.physical(), &properties);
  const uint64_t granularity = properties.limits.bufferImageGranularity;
  const VkDevice device = device_.device();
  const VulkanDevice* owner = &device_;

  options.requirements = [=](const graph::ResourceDecl& decl, const graph::ResolvedResource& resolved) {
    const uint32_t r = indexOfFirstVersion->at(decl.firstVersion);
    auto requirements = vkStruct<VkMemoryRequirements2>(VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2);
    if (decl.kind == graph::ResourceKind::Texture) {
      const VkImageCreateInfo info = VulkanDevice::imageInfo(textureDesc(decl.name, resolved.texture, (*textureUsage)[r]));
      auto query = vkStruct<VkDeviceImageMemoryRequirements>(VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS);
      query.pCreateInfo = &info;
      vkGetDeviceImageMemoryRequirements(device, &query, &requirements);
    } else {
      const VkBufferCreateInfo info = owner->bufferInfo(bufferDesc(decl.name, resolved.buffer, (*bufferUsage)[r]));
      auto query = vkStruct<VkDeviceBufferMemoryRequirements>(VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS);
      query.pCreateInfo = &info;
      vkGetDeviceBufferMemoryRequirements(device, &query, &requirements);
    }
    const auto& m = requirements.memoryRequirements;
    // Heaps hold one kind only, but they sit next to other blocks' neighbours: keep granularity.
    return graph::MemoryRequirements{m.size, std::max<uint64_t>(m.alignment, granularity), m.memoryTypeBits};
  };
  return options;
}

std::vector<rhi::TextureUsage> VulkanGraph::textureUsages() const { return usagesOf(declaration_, textureUsageFor); }

std::vector<rhi::BufferUsage> VulkanGraph::bufferUsages() const { return usagesOf(declaration_, bufferUsageFor); }

void VulkanGraph::createResources() {
  const auto& decls = declaration_.resources();
  const auto& plan = compiled_.aliasing;
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device_.physical(), &properties);
  for (const auto& heap : plan.heaps) {
    const VkMemoryRequirements requirements{alignUp(heap.size, properties.limits.bufferImageGranularity),
                                            heap.alignment, heap.memoryTypeBits};
    const Tiling tiling = heap.kind == graph::ResourceKind::Buffer ? Tiling::Linear : Tiling::Optimal;
    heaps_.push_back(device_.memory().allocate(requirements, rhi::MemoryUsage::DeviceLocal, tiling,
                                               "graph '" + options_.name + "' aliasing heap"));
  }
  const auto textureUsage = textureUsages();
  const auto bufferUsage = bufferUsages();
  buffers_.assign(decls.size(), {});
  textures_.assign(decls.size(), {});
  ownsResource_.assign(decls.size(), false);
  // Transients are private to this graph: only nodes that declare them see their descriptors.
  struct PrivateCreation {
    Descriptors& descriptors;
    explicit PrivateCreation(Descriptors& d) : descriptors(d) { descriptors.setCreatingPrivate(true); }
    ~PrivateCreation() { descriptors.setCreatingPrivate(false); }
    PrivateCreation(const PrivateCreation&) = delete;
    PrivateCreation& operator=(const PrivateCreation&) = delete;
  } privateCreation(device_.descriptors());
  for (uint32_t r = 0; r < decls.size(); ++r) {
    const auto& decl = decls[r];
    const bool texture = decl.kind == graph::ResourceKind::Texture;
    if (decl.imported) {
      if (texture) textures_[r] = rhi::externalTexture(decl.external);
      else buffers_[r] = rhi::externalBuffer(decl.external);
      if (!(texture ? textures_[r].valid() : buffers_[r].valid())) {
        throw InputError("graph '" + options_.name + "': imported " + (texture ? "texture '" : "buffer '") +
                         std::string(decl.name) + "' does not name an RHI " + (texture ? "texture" : "buffer") +
                         " (use rhi::external)");
      }
      continue;
    }
    if (!compiled_.resourceAlive[r]) continue;  // culled: never created
    const graph::Placement& placement = plan.placements[r];
    Allocation at{};
    const Allocation* where = nullptr;
    if (placement.heap != graph::kInvalidIndex) {
      at = heaps_[placement.heap];
      at.offset += placement.offset;
      at.size = placement.size;
      if (at.mapped) at.mapped += placement.offset;
      where = &at;
    }
    const std::string name = options_.name + "/" + std::string(decl.name);
    if (texture) {
      textures_[r] = device_.createTextureIn(textureDesc(name, compiled_.resources[r].texture, textureUsage[r]), where);
    } else {
      buffers_[r] = device_.createBufferIn(bufferDesc(name, compiled_.resources[r].buffer, bufferUsage[r]), where);
    }
    ownsResource_[r] = true;
  }
}

void VulkanGraph::translateBarriers() {
  const auto& barriers = compiled_.barriers;
  const auto familyOf = [&](uint32_t logical) { return device_.queues()[deviceQueueOf_[logical]].family; };
  std::vector<int32_t> imageSlot(barriers.size(), -1);
  std::vector<int32_t> bufferSlot(barriers.size(), -1);
  imageBarriers_.clear();
  bufferBarriers_.clear();
  for (uint32_t i = 0; i < barriers.size(); ++i) {
    const graph::Barrier& b = barriers[i];
    const bool texture = textures_[b.resource].valid();
    const bool sameFamily = familyOf(b.srcQueue) == familyOf(b.dstQueue);
    // Same family (e.g. every logical queue on lavapipe's one queue): no ownership transfer; the
    // release half is dropped and the acquire half does the layout change after the semaphore.
    if (b.kind == graph::Barrier::Kind::Release && sameFamily) continue;
    if (options_.testDropSameLayoutBarriers && b.kind == graph::Barrier::Kind::Transition &&
        (!texture || b.oldLayout == b.newLayout)) {
      continue;
    }
    VkPipelineStageFlags2 srcStages = toVkStages(b.srcStages);
    VkAccessFlags2 srcAccess = toVkAccess(b.srcAccess);
    VkPipelineStageFlags2 dstStages = toVkStages(b.dstStages);
    VkAccessFlags2 dstAccess = toVkAccess(b.dstAccess);
    uint32_t srcFamily = VK_QUEUE_FAMILY_IGNORED;
    uint32_t dstFamily = VK_QUEUE_FAMILY_IGNORED;
    if (b.kind != graph::Barrier::Kind::Transition && !sameFamily) {
      srcFamily = familyOf(b.srcQueue);
      dstFamily = familyOf(b.dstQueue);
    }
    // The half of an ownership transfer recorded on the other queue has no scope here.
    if (b.kind == graph::Barrier::Kind::Release && !sameFamily) dstStages = dstAccess = 0;
    if (b.kind == graph::Barrier::Kind::Acquire) srcStages = srcAccess = 0;
    // A barrier names only accesses its queue can make: an import's final state may list every
    // later read (index, vertex, shader), but on a transfer queue ALL_COMMANDS covers transfers
    // only. Later readers on other queues are ordered by the semaphore, whose signal makes every
    // write available, and by their own queue's barriers.
    const VkQueueFlags recordedOn =
        device_.queues()[deviceQueueOf_[b.kind == graph::Barrier::Kind::Acquire ? b.dstQueue : b.srcQueue]].flags;
    srcAccess &= supportedAccess(recordedOn);
    dstAccess &= supportedAccess(recordedOn);
    if (texture) {
      const TextureRecord& record = device_.texture(textures_[b.resource]);
      auto barrier = vkStruct<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2);
      barrier.srcStageMask = srcStages;
      barrier.srcAccessMask = srcAccess;
      barrier.dstStageMask = dstStages;
      barrier.dstAccessMask = dstAccess;
      barrier.oldLayout = toVk(b.oldLayout);
      barrier.newLayout = toVk(b.newLayout);
      barrier.srcQueueFamilyIndex = srcFamily;
      barrier.dstQueueFamilyIndex = dstFamily;
      barrier.image = record.image.get();
      barrier.subresourceRange = {record.aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
      imageSlot[i] = static_cast<int32_t>(imageBarriers_.size());
      imageBarriers_.push_back(barrier);
    } else {
      auto barrier = vkStruct<VkBufferMemoryBarrier2>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2);
      barrier.srcStageMask = srcStages;
      barrier.srcAccessMask = srcAccess;
      barrier.dstStageMask = dstStages;
      barrier.dstAccessMask = dstAccess;
      barrier.srcQueueFamilyIndex = srcFamily;
      barrier.dstQueueFamilyIndex = dstFamily;
      barrier.buffer = device_.buffer(buffers_[b.resource]).buffer.get();
      barrier.size = VK_WHOLE_SIZE;
      bufferSlot[i] = static_cast<int32_t>(bufferBarriers_.size());
      bufferBarriers_.push_back(barrier);
    }
  }

  // Each step's before/after range becomes a list of references to the translated barriers.
  const auto references = [&](graph::BarrierRange range) {
    const BarrierList list{static_cast<uint32_t>(barrierRefs_.size()), 0};
    for (uint32_t i = range.first; i < range.first + range.count; ++i) {
      if (imageSlot[i] < 0 && bufferSlot[i] < 0) continue;
      const graph::Barrier& b = barriers[i];
      BarrierRef ref;
      ref.resource = b.resource;
      ref.image = imageSlot[i] >= 0;
      ref.index = static_cast<uint32_t>(ref.image ? imageSlot[i] : bufferSlot[i]);
      ref.heap = compiled_.aliasing.placements[b.resource].heap;
      // Only same-queue, same-layout barriers of graph-owned memory may be skipped (see
      // queueBarriers): layout changes and ownership transfers must happen either way.
      ref.elidable = ref.heap != graph::kInvalidIndex && b.kind == graph::Barrier::Kind::Transition &&
                     (!ref.image || b.oldLayout == b.newLayout);
      barrierRefs_.push_back(ref);
    }
    return BarrierList{list.first, static_cast<uint32_t>(barrierRefs_.size()) - list.first};
  };
  barrierRefs_.clear();
  steps_.resize(compiled_.steps.size());
  for (uint32_t s = 0; s < compiled_.steps.size(); ++s) {
    const graph::Step& step = compiled_.steps[s];
    steps_[s].node = step.node;
    steps_[s].type = declaration_.nodes()[step.node].type;
    steps_[s].logicalQueue = compiled_.nodes[step.node].queue;
    steps_[s].before = references(step.before);
    steps_[s].after = references(step.after);
  }
  listTouchedHeaps();
  pendingBarriers_.resize(declaration_.resources().size());
  heapTouched_.assign(compiled_.aliasing.heaps.size(), 0);
}

// Per step, the heaps holding graph-owned resources the node uses (each once).
void VulkanGraph::listTouchedHeaps() {
  stepHeaps_.clear();
  std::vector<uint32_t> seenInStep(compiled_.aliasing.heaps.size(), graph::kInvalidIndex);
  for (uint32_t s = 0; s < steps_.size(); ++s) {
    steps_[s].firstHeap = static_cast<uint32_t>(stepHeaps_.size());
    for (const graph::ResourceAccess& use : declaration_.accesses(steps_[s].node)) {
      const uint32_t heap = compiled_.aliasing.placements[use.resource].heap;
      if (heap == graph::kInvalidIndex || seenInStep[heap] == s) continue;
      seenInStep[heap] = s;
      stepHeaps_.push_back(heap);
    }
    steps_[s].heapCount = static_cast<uint32_t>(stepHeaps_.size()) - steps_[s].firstHeap;
  }
}

void VulkanGraph::translateRendering() {
  // Count first: attachments_ must not reallocate once steps point into it.
  size_t count = 0;
  for (uint32_t n = 0; n < declaration_.nodes().size(); ++n) {
    count += declaration_.attachments(n).color.size() + 2;
  }
  attachments_.clear();
  attachments_.reserve(count);
  for (auto& step : steps_) {
    if (declaration_.nodes()[step.node].type != graph::NodeType::Graphics) continue;
    const graph::NodeAttachments& declared = declaration_.attachments(step.node);
    const size_t first = attachments_.size();
    graph::Extent extent{0, 0, 1};
    for (const auto& color : declared.color) {
      const TextureRecord& target = device_.texture(textureOf(color.target));
      auto info = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
      info.imageView = target.view.get();
      info.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      info.loadOp = toVk(color.load);
      info.storeOp = toVk(color.store);
      std::copy(color.clear.color.begin(), color.clear.color.end(), info.clearValue.color.float32);
      if (color.resolveTarget.valid()) {
        const TextureRecord& resolve = device_.texture(textureOf(color.resolveTarget));
        const bool integer = target.desc.format == graph::Format::R32Uint;
        info.resolveMode = integer ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT : VK_RESOLVE_MODE_AVERAGE_BIT;
        info.resolveImageView = resolve.view.get();
        info.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      }
      if (extent.width == 0) extent = target.desc.extent;
      attachments_.push_back(info);
    }
    step.renderingInfo.colorAttachmentCount = static_cast<uint32_t>(attachments_.size() - first);
    step.renderingInfo.pColorAttachments = step.renderingInfo.colorAttachmentCount ? &attachments_[first] : nullptr;
    const graph::DepthAttachment& depth = declared.depth;
    if (depth.target.valid()) {
      const TextureRecord& target = device_.texture(textureOf(depth.target));
      auto info = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
      info.imageView = target.view.get();
      info.imageLayout = depth.readOnly ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                        : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
      info.loadOp = toVk(depth.load);
      info.storeOp = toVk(depth.store);
      info.clearValue.depthStencil = {depth.clear.depth, depth.clear.stencil};
      attachments_.push_back(info);
      step.renderingInfo.pDepthAttachment = &attachments_.back();
      if (graph::hasStencil(target.desc.format)) step.renderingInfo.pStencilAttachment = &attachments_.back();
      if (extent.width == 0) extent = target.desc.extent;
    }
    // A graphics node without attachments records outside a rendering scope (e.g. copies on the
    // graphics queue); draws need attachments.
    if (extent.width == 0) continue;
    step.rendering = true;
    step.extent = extent;
    step.renderingInfo.renderArea = {{0, 0}, {extent.width, extent.height}};
    step.renderingInfo.layerCount = 1;
  }
}

void VulkanGraph::orderSubmits() {
  // Several logical queues may share one device queue (lavapipe has one). Submitting a batch that
  // waits for a later batch of the same VkQueue would deadlock, so order the submits
  // topologically: a submit goes after every submit it waits for and after its queue predecessor.
  const auto& submits = compiled_.submits;
  const auto count = static_cast<uint32_t>(submits.size());
  std::vector<std::vector<uint32_t>> successors(count);
  std::vector<uint32_t> pending(count, 0);
  std::vector<std::vector<uint32_t>> byQueue(logicalQueues_);
  for (uint32_t s = 0; s < count; ++s) byQueue[submits[s].queue].push_back(s);
  for (auto& list : byQueue) {
    std::sort(list.begin(), list.end(), [&](uint32_t a, uint32_t b) { return submits[a].signalValue < submits[b].signalValue; });
    for (size_t i = 1; i < list.size(); ++i) {
      successors[list[i - 1]].push_back(list[i]);
      ++pending[list[i]];
    }
  }
  for (uint32_t s = 0; s < count; ++s) {
    for (const auto& wait : submits[s].waits) {
      const auto& list = byQueue.at(wait.queue);
      const auto producer = std::find_if(list.begin(), list.end(),
                                         [&](uint32_t t) { return submits[t].signalValue >= wait.value; });
      if (producer == list.end()) {
        throw DeviceError("graph '" + options_.name + "': a submit waits for a value no submit signals");
      }
      successors[*producer].push_back(s);
      ++pending[s];
    }
  }
  // Ready submits by position of their first step in the topological order.
  const auto key = [&](uint32_t s) { return compiled_.nodes[compiled_.steps[submits[s].firstStep].node].orderIndex; };
  const auto later = [&](uint32_t a, uint32_t b) { return key(a) > key(b); };
  std::priority_queue<uint32_t, std::vector<uint32_t>, decltype(later)> ready(later);
  for (uint32_t s = 0; s < count; ++s) {
    if (pending[s] == 0) ready.push(s);
  }
  submitOrder_.clear();
  while (!ready.empty()) {
    const uint32_t s = ready.top();
    ready.pop();
    submitOrder_.push_back(s);
    for (uint32_t next : successors[s]) {
      if (--pending[next] == 0) ready.push(next);
    }
  }
  if (submitOrder_.size() != count) throw DeviceError("graph '" + options_.name + "': submits wait in a cycle");
}

void VulkanGraph::createSyncAndSlots() {
  const VkDevice device = device_.device();
  uint32_t maxSubmits = 0;
  for (uint32_t n : compiled_.submitsPerQueue) maxSubmits = std::max(maxSubmits, n);
  valuesPerExecution_ = maxSubmits + 1;
  for (uint32_t q = 0; q < logicalQueues_; ++q) {
    auto type = vkStruct<VkSemaphoreTypeCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO);
    type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    auto info = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    info.pNext = &type;
    VkSemaphore semaphore = VK_NULL_HANDLE;
    check(vkCreateSemaphore(device, &info, nullptr, &semaphore), "vkCreateSemaphore (timeline)");
    timelines_.emplace_back(device, semaphore, vkDestroySemaphore);
    device_.setName(VK_OBJECT_TYPE_SEMAPHORE, reinterpret_cast<uint64_t>(semaphore),
                    options_.name + " timeline q" + std::to_string(q));
  }
  slots_.resize(std::max(1u, device_.framesInFlight_));
  for (auto& slot : slots_) {
    for (uint32_t q = 0; q < logicalQueues_; ++q) {
      auto info = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
      // Buffers are kept across executions and recorded again one by one (begin resets one).
      info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
      info.queueFamilyIndex = device_.queues()[deviceQueueOf_[q]].family;
      VkCommandPool pool = VK_NULL_HANDLE;
      check(vkCreateCommandPool(device, &info, nullptr, &pool), "vkCreateCommandPool");
      slot.pools.emplace_back(device, pool, vkDestroyCommandPool);
    }
    slot.commandBuffers.resize(steps_.size());
    slot.recorded.assign(steps_.size(), 0);
    slot.started.assign(steps_.size(), 0);
    slot.keys.assign(steps_.size(), 0);
    slot.reusable.assign(steps_.size(), 0);
    for (uint32_t s = 0; s < steps_.size(); ++s) {
      auto info = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
      info.commandPool = slot.pools[steps_[s].logicalQueue].get();
      info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      info.commandBufferCount = 1;
      check(vkAllocateCommandBuffers(device, &info, &slot.commandBuffers[s]), "vkAllocateCommandBuffers");
    }
    if (options_.timestamps && !steps_.empty()) {
      auto info = vkStruct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
      info.queryType = VK_QUERY_TYPE_TIMESTAMP;
      info.queryCount = queryCount_ = static_cast<uint32_t>(steps_.size() * 2 + (spin_ ? 1 : 0));
      VkQueryPool pool = VK_NULL_HANDLE;
      check(vkCreateQueryPool(device, &info, nullptr, &pool), "vkCreateQueryPool");
      slot.queries = Owned<VkQueryPool>(device, pool, vkDestroyQueryPool);
      vkResetQueryPool(device, pool, 0, info.queryCount);
    }
  }
}

// What the compiled graph fixes about each step's recording, hashed once: its node, the physical
// resources it uses (transients and imports alike), its render extent and whether it closes its
// submit. (Keys are compared within one compiled graph only, so this guards nothing today; it
// keeps the key complete should kept buffers ever outlive a recompile.)
void VulkanGraph::hashStaticKeys() {
  for (const auto& submit : compiled_.submits) {
    if (submit.stepCount > 0) steps_[submit.firstStep + submit.stepCount - 1].lastOfSubmit = true;
  }
  const auto mix = graph::hashCombine;
  for (Step& step : steps_) {
    uint64_t key = mix(step.node, step.lastOfSubmit);
    key = mix(mix(key, step.extent.width), step.extent.height);
    for (const graph::ResourceAccess& use : declaration_.accesses(step.node)) {
      key = mix(mix(key, buffers_[use.resource].index), textures_[use.resource].index);
      key = mix(key, static_cast<uint64_t>(use.access));
    }
    step.staticKey = key;
  }
}

// debug.slow_pass: the step of the node named options_.slowNode gets a spin at its end.
void VulkanGraph::createSpin() {
  if (options_.slowNode.empty() || options_.slowFraction <= 0.0) return;
  for (uint32_t s = 0; s < steps_.size(); ++s) {
    if (declaration_.nodes()[steps_[s].node].name == options_.slowNode) slowStep_ = s;
  }
  if (slowStep_ == graph::kInvalidIndex) {
    throw InputError("slow pass '" + options_.slowNode + "': no node of that name runs in graph '" + options_.name +
                     "'");
  }
  if ((device_.queues()[deviceQueueOf_[steps_[slowStep_].logicalQueue]].flags & VK_QUEUE_COMPUTE_BIT) == 0) {
    throw InputError("slow pass '" + options_.slowNode +
                     "': it runs on a queue without compute work (a transfer queue)");
  }
  spin_ = std::make_unique<SpinWork>(device_, options_.slowFraction);
}

rhi::BufferId VulkanGraph::bufferOf(graph::BufferHandle handle) const {
  return buffers_.at(declaration_.resourceOf(handle));
}

rhi::TextureId VulkanGraph::textureOf(graph::TextureHandle handle) const {
  return textures_.at(declaration_.resourceOf(handle));
}

// One scoped descriptor set per step (see descriptors.hpp): resources outside the graph stay
// visible read-only; of the graph's own resources, a node sees only those it declared, writable
// only where it declared a write.
// They exist for the validation layer's sake (a GPU runs the same shaders either way), so they are
// built only when validation is on: without it every node binds the shared set and a graph costs
// no descriptor memory per node.
void VulkanGraph::createScopedSets() {
  if (!device_.validationEnabled() || !device_.descriptors().bindless() || steps_.empty()) return;
  const auto& decls = declaration_.resources();
  std::vector<bool> graphBuffers(kMaxStorageBuffers, false);
  std::vector<bool> graphSampled(kMaxSampledTextures, false);
  const auto mark = [](std::vector<bool>& slots, uint32_t slot) {
    if (slot != rhi::kInvalidId) slots[slot] = true;
  };
  for (uint32_t r = 0; r < decls.size(); ++r) {
    if (buffers_[r].valid()) mark(graphBuffers, device_.buffer(buffers_[r]).storageIndex);
    if (textures_[r].valid()) mark(graphSampled, device_.texture(textures_[r]).sampledIndex);
  }
  scopedSets_ = std::make_unique<ScopedSets>(device_.descriptors(), static_cast<uint32_t>(steps_.size()));
  for (uint32_t s = 0; s < steps_.size(); ++s) {
    DescriptorScope scope;
    scope.graphBuffers = &graphBuffers;
    scope.graphSampled = &graphSampled;
    const auto add = [](std::vector<uint32_t>& list, uint32_t slot) {
      if (slot != rhi::kInvalidId) list.push_back(slot);
    };
    for (const graph::ResourceAccess& use : declaration_.accesses(steps_[s].node)) {
      const bool sampledStorage = use.access == graph::Access::StorageSampledWrite;
      const bool storage = use.access == graph::Access::StorageRead || use.access == graph::Access::StorageWrite ||
                           use.access == graph::Access::StorageReadWrite || sampledStorage;
      if (buffers_[use.resource].valid()) {
        // Only what shaders access: a buffer the node reads as indirect arguments, vertices or a
        // copy source is not in its shaders' tables (the layer would count a shader read of it).
        if (!storage && use.access != graph::Access::Uniform) continue;
        const bool writes = graph::isWriteAccess(use.access);
        add(writes ? scope.writtenBuffers : scope.readBuffers, device_.buffer(buffers_[use.resource]).storageIndex);
      } else if (textures_[use.resource].valid()) {
        const TextureRecord& record = device_.texture(textures_[use.resource]);
        if (use.access == graph::Access::Sampled) add(scope.sampled, record.sampledIndex);
        if (sampledStorage) add(scope.sampled, record.sampledGeneralIndex);
        if (storage)
          add(storageTextureBinding(record.desc.format) == Binding::Int64StorageTextures ? scope.int64StorageTextures
                                                                                         : scope.storageTextures,
              record.storageIndex);
      }
    }
    scopedSets_->fill(s, scope);
  }
}

}  // namespace fgb::vulkan
