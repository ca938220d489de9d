// Forward declarations of the runtime's classes, for headers that only name them by reference or
// pointer (the way <iosfwd> serves the standard streams).
#pragma once

namespace lantern::runtime {
class Bindings;
class Buffer;
class ComputePipeline;
class Device;
class GpuTimer;
class GraphicsPipeline;
class Image;
class Pipeline;
class ShaderLibrary;
namespace graph {
class GraphExecutor;
class PassBuilder;
class PassContext;
class RenderGraph;
}  // namespace graph
}  // namespace lantern::runtime
