// SPIR-V binary reflection: one pass collects names, decorations, types, constants and variables;
// a second step resolves descriptor variables into bindings.
#include "runtime/gpu/spirv_reflect.h"

#include <fmt/format.h>
#include <spirv/unified1/spirv.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <tuple>
#include <unordered_map>

#include "engine/core/error.h"

namespace lantern::runtime {
namespace {

struct Id {
  SpvOp op = SpvOpNop;                  // the defining instruction
  std::vector<std::uint32_t> operands;  // words after the result id (types) or after result type
  std::uint32_t type = 0;               // result type (constants, variables)
  std::string name;
  std::optional<std::uint32_t> set, binding, spec_id, builtin, array_stride;
  bool block = false, buffer_block = false;
  std::unordered_map<std::uint32_t, std::uint32_t> member_offsets;
  std::unordered_map<std::uint32_t, std::string> member_names;
};

std::string read_string(std::span<const std::uint32_t> words) {
  std::string s;
  for (std::uint32_t w : words) {
    for (int b = 0; b < 4; ++b) {
      const char c = static_cast<char>((w >> (8 * b)) & 0xff);
      if (c == '\0') return s;
      s.push_back(c);
    }
  }
  return s;
}

VkFormat format_of(std::uint32_t spv_format) {
  switch (spv_format) {
    case SpvImageFormatRgba32f:
      return VK_FORMAT_R32G32B32A32_SFLOAT;
    case SpvImageFormatRgba16f:
      return VK_FORMAT_R16G16B16A16_SFLOAT;
    case SpvImageFormatR32f:
      return VK_FORMAT_R32_SFLOAT;
    case SpvImageFormatRgba8:
      return VK_FORMAT_R8G8B8A8_UNORM;
    case SpvImageFormatRg32f:
      return VK_FORMAT_R32G32_SFLOAT;
    case SpvImageFormatRg16f:
      return VK_FORMAT_R16G16_SFLOAT;
    case SpvImageFormatR11fG11fB10f:
      return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
    case SpvImageFormatR16f:
      return VK_FORMAT_R16_SFLOAT;
    case SpvImageFormatRgba32ui:
      return VK_FORMAT_R32G32B32A32_UINT;
    case SpvImageFormatRg32ui:
      return VK_FORMAT_R32G32_UINT;
    case SpvImageFormatR32ui:
      return VK_FORMAT_R32_UINT;
    default:
      return VK_FORMAT_UNDEFINED;
  }
}

VkShaderStageFlagBits stage_of(std::uint32_t model) {
  switch (model) {
    case SpvExecutionModelVertex:
      return VK_SHADER_STAGE_VERTEX_BIT;
    case SpvExecutionModelFragment:
      return VK_SHADER_STAGE_FRAGMENT_BIT;
    case SpvExecutionModelGLCompute:
      return VK_SHADER_STAGE_COMPUTE_BIT;
    case SpvExecutionModelRayGenerationKHR:
      return VK_SHADER_STAGE_RAYGEN_BIT_KHR;
    case SpvExecutionModelMissKHR:
      return VK_SHADER_STAGE_MISS_BIT_KHR;
    case SpvExecutionModelClosestHitKHR:
      return VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR;
    case SpvExecutionModelAnyHitKHR:
      return VK_SHADER_STAGE_ANY_HIT_BIT_KHR;
    default:
      return VK_SHADER_STAGE_ALL;
  }
}

class Parser {
 public:
  Parser(std::span<const std::uint32_t> words, std::string_view what)
      : words_(words), what_(what) {}

  ShaderReflection run() {
    if (words_.size() < 5 || words_[0] != SpvMagicNumber)
      fail("not a SPIR-V module (bad magic number)");
    ids_.resize(words_[3]);  // id bound
    referenced_.assign(words_[3], false);
    for (std::size_t at = 5; at < words_.size();) {
      const std::uint32_t count = words_[at] >> 16;
      if (count == 0 || at + count > words_.size())
        fail(fmt::format("truncated instruction at word {}", at));
      instruction(static_cast<SpvOp>(words_[at] & 0xffff), words_.subspan(at + 1, count - 1));
      at += count;
    }
    resolve();
    return std::move(out_);
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw RuntimeError(fmt::format("SPIR-V reflection of {}: {}", what_, why));
  }
  Id& id(std::uint32_t i) {
    if (i >= ids_.size()) fail(fmt::format("id {} out of bound {}", i, ids_.size()));
    return ids_[i];
  }

  // Marks the pointer operands of instructions in function bodies: a variable is statically used
  // when some instruction loads, stores, indexes, queries or atomically accesses it or passes it
  // to a function.
  void note_references(SpvOp op, std::span<const std::uint32_t> w) {
    auto mark = [&](std::size_t i) {
      if (i < w.size() && w[i] < referenced_.size()) referenced_[w[i]] = true;
    };
    switch (op) {
      case SpvOpLoad:
      case SpvOpAccessChain:
      case SpvOpInBoundsAccessChain:
      case SpvOpPtrAccessChain:
      case SpvOpArrayLength:
      case SpvOpImageTexelPointer:
      case SpvOpCopyObject:
        mark(2);
        break;
      case SpvOpStore:
      case SpvOpAtomicStore:
        mark(0);
        break;
      case SpvOpCopyMemory:
      case SpvOpCopyMemorySized:
        mark(0);
        mark(1);
        break;
      case SpvOpFunctionCall:
        for (std::size_t i = 3; i < w.size(); ++i) mark(i);
        break;
      default:
        if ((op >= SpvOpAtomicLoad && op <= SpvOpAtomicXor) || op == SpvOpAtomicFAddEXT ||
            op == SpvOpAtomicFMinEXT || op == SpvOpAtomicFMaxEXT)
          mark(2);
        break;
    }
  }

  void instruction(SpvOp op, std::span<const std::uint32_t> w) {
    if (in_function_) note_references(op, w);
    switch (op) {
      case SpvOpFunction:
        in_function_ = true;
        break;
      case SpvOpFunctionEnd:
        in_function_ = false;
        break;
      case SpvOpEntryPoint:
        out_.stage = stage_of(w[0]);
        out_.entry_point = read_string(w.subspan(2));
        break;
      case SpvOpExecutionMode:
        if (w[1] == SpvExecutionModeLocalSize) out_.local_size = {w[2], w[3], w[4]};
        break;
      case SpvOpExecutionModeId:
        if (w[1] == SpvExecutionModeLocalSizeId) local_size_ids_ = {w[2], w[3], w[4]};
        break;
      case SpvOpName:
        id(w[0]).name = read_string(w.subspan(1));
        break;
      case SpvOpDecorate:
        decorate(id(w[0]), w[1], w.size() > 2 ? w[2] : 0);
        break;
      case SpvOpMemberDecorate:
        if (w[2] == SpvDecorationOffset) id(w[0]).member_offsets[w[1]] = w[3];
        break;
      case SpvOpMemberName:
        id(w[0]).member_names[w[1]] = read_string(w.subspan(2));
        break;
      case SpvOpTypeVoid:
      case SpvOpTypeBool:
      case SpvOpTypeInt:
      case SpvOpTypeFloat:
      case SpvOpTypeVector:
      case SpvOpTypeMatrix:
      case SpvOpTypeImage:
      case SpvOpTypeSampler:
      case SpvOpTypeSampledImage:
      case SpvOpTypeArray:
      case SpvOpTypeRuntimeArray:
      case SpvOpTypeStruct:
      case SpvOpTypePointer:
      case SpvOpTypeAccelerationStructureKHR: {
        Id& t = id(w[0]);
        t.op = op;
        t.operands.assign(w.begin() + 1, w.end());
        break;
      }
      case SpvOpConstant:
      case SpvOpSpecConstant:
      case SpvOpConstantComposite:
      case SpvOpSpecConstantComposite:
      case SpvOpSpecConstantTrue:
      case SpvOpSpecConstantFalse:
      case SpvOpConstantTrue:
      case SpvOpConstantFalse:
      case SpvOpVariable: {
        Id& c = id(w[1]);
        c.op = op;
        c.type = w[0];
        c.operands.assign(w.begin() + 2, w.end());
        if (op == SpvOpVariable) variables_.push_back(w[1]);
        if (op == SpvOpSpecConstant || op == SpvOpSpecConstantTrue || op == SpvOpSpecConstantFalse)
          spec_constants_.push_back(w[1]);
        break;
      }
      default:
        break;
    }
  }

  static void decorate(Id& target, std::uint32_t decoration, std::uint32_t value) {
    switch (decoration) {
      case SpvDecorationDescriptorSet:
        target.set = value;
        break;
      case SpvDecorationBinding:
        target.binding = value;
        break;
      case SpvDecorationSpecId:
        target.spec_id = value;
        break;
      case SpvDecorationBuiltIn:
        target.builtin = value;
        break;
      case SpvDecorationArrayStride:
        target.array_stride = value;
        break;
      case SpvDecorationBlock:
        target.block = true;
        break;
      case SpvDecorationBufferBlock:
        target.buffer_block = true;
        break;
      default:
        break;
    }
  }

  std::uint32_t constant_value(std::uint32_t c) {
    const Id& k = id(c);
    if (k.op == SpvOpSpecConstantTrue || k.op == SpvOpConstantTrue) return 1;
    if (k.op == SpvOpSpecConstantFalse || k.op == SpvOpConstantFalse) return 0;
    if ((k.op == SpvOpConstant || k.op == SpvOpSpecConstant) && !k.operands.empty())
      return k.operands[0];
    fail(fmt::format("id {} is not a scalar constant", c));
  }

  // Byte size of a type in a Block/push-constant layout (explicit offsets and strides).
  std::uint32_t type_size(std::uint32_t t) {
    const Id& type = id(t);
    switch (type.op) {
      case SpvOpTypeBool:
        return 4;
      case SpvOpTypeInt:
      case SpvOpTypeFloat:
        return type.operands[0] / 8;
      case SpvOpTypeVector:
        return type_size(type.operands[0]) * type.operands[1];
      case SpvOpTypeMatrix:
        return type_size(type.operands[0]) * type.operands[1];
      case SpvOpTypeArray:
        return constant_value(type.operands[1]) *
               type.array_stride.value_or(type_size(type.operands[0]));
      case SpvOpTypeStruct: {
        std::uint32_t size = 0;
        for (std::uint32_t m = 0; m < type.operands.size(); ++m) {
          const auto offset = type.member_offsets.find(m);
          const std::uint32_t start = offset != type.member_offsets.end() ? offset->second : size;
          size = std::max(size, start + type_size(type.operands[m]));
        }
        return size;
      }
      default:
        return 0;  // runtime arrays and opaque types have no static size
    }
  }

  void resolve_local_size_from(const std::array<std::uint32_t, 3>& components) {
    for (int axis = 0; axis < 3; ++axis) {
      const Id& c = id(components[static_cast<std::size_t>(axis)]);
      out_.local_size[static_cast<std::size_t>(axis)] =
          constant_value(components[static_cast<std::size_t>(axis)]);
      if (c.spec_id)
        out_.local_size_spec_id[static_cast<std::size_t>(axis)] = static_cast<int>(*c.spec_id);
    }
  }

  void resolve() {
    // Workgroup size: LocalSizeId operands, or a constant decorated BuiltIn WorkgroupSize
    // (glslang emits one for local_size_x_id); both override the LocalSize literal.
    if (local_size_ids_) resolve_local_size_from(*local_size_ids_);
    for (std::uint32_t i = 0; i < ids_.size(); ++i) {
      const Id& c = ids_[i];
      if (c.builtin == SpvBuiltInWorkgroupSize &&
          (c.op == SpvOpSpecConstantComposite || c.op == SpvOpConstantComposite) &&
          c.operands.size() == 3)
        resolve_local_size_from({c.operands[0], c.operands[1], c.operands[2]});
    }
    for (std::uint32_t c : spec_constants_) {
      const Id& k = id(c);
      if (!k.spec_id) continue;
      out_.spec_constants.push_back({k.name, *k.spec_id, constant_value(c)});
    }
    for (std::uint32_t v : variables_) variable(v);
    std::sort(out_.bindings.begin(), out_.bindings.end(), [](const auto& a, const auto& b) {
      return std::tie(a.set, a.binding) < std::tie(b.set, b.binding);
    });
    resolve_structs();
  }

  void resolve_structs() {
    // The stride of the arrays of each element type (one pass, not one per struct).
    std::unordered_map<std::uint32_t, std::uint32_t> stride_of_element;
    for (const Id& a : ids_) {
      if ((a.op == SpvOpTypeArray || a.op == SpvOpTypeRuntimeArray) && !a.operands.empty() &&
          a.array_stride)
        stride_of_element[a.operands[0]] = *a.array_stride;
    }
    for (std::uint32_t i = 0; i < ids_.size(); ++i) {
      const Id& t = ids_[i];
      if (t.op != SpvOpTypeStruct || t.name.empty()) continue;
      StructLayout s;
      s.name = t.name;
      const std::size_t n = t.operands.size();
      s.member_names.assign(n, "");
      s.member_offsets.assign(n, -1);
      for (const auto& [m, name] : t.member_names)
        if (m < n) s.member_names[m] = name;
      for (const auto& [m, offset] : t.member_offsets)
        if (m < n) s.member_offsets[m] = offset;
      if (const auto stride = stride_of_element.find(i); stride != stride_of_element.end())
        s.array_stride = stride->second;
      auto same = std::find_if(out_.structs.begin(), out_.structs.end(),
                               [&](const StructLayout& o) { return o.name == s.name; });
      const auto decorated = [](const StructLayout& l) {
        return std::any_of(l.member_offsets.begin(), l.member_offsets.end(),
                           [](std::int64_t o) { return o >= 0; });
      };
      if (same == out_.structs.end())
        out_.structs.push_back(std::move(s));
      else if (decorated(s) && !decorated(*same))
        *same = std::move(s);
    }
  }

  void variable(std::uint32_t v) {
    const Id& var = id(v);
    const std::uint32_t storage = var.operands.empty() ? 0 : var.operands[0];
    const Id& pointer = id(var.type);
    if (pointer.op != SpvOpTypePointer) return;
    std::uint32_t type_id = pointer.operands[1];
    if (storage == SpvStorageClassPushConstant) {
      out_.push_constant_bytes = std::max(out_.push_constant_bytes, type_size(type_id));
      return;
    }
    if (storage != SpvStorageClassUniform && storage != SpvStorageClassUniformConstant &&
        storage != SpvStorageClassStorageBuffer)
      return;
    if (!var.binding) return;

    DescriptorBinding b;
    b.set = var.set.value_or(0);
    b.binding = *var.binding;
    b.stages = static_cast<VkShaderStageFlags>(out_.stage);
    const Id* type = &id(type_id);
    if (type->op == SpvOpTypeArray) {
      b.count = constant_value(type->operands[1]);
      type_id = type->operands[0];
    } else if (type->op == SpvOpTypeRuntimeArray) {
      b.count = 0;
      type_id = type->operands[0];
    }
    type = &id(type_id);
    b.name = !var.name.empty() ? var.name : type->name;
    switch (type->op) {
      case SpvOpTypeStruct:
        b.type = storage == SpvStorageClassStorageBuffer || type->buffer_block
                     ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                     : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        break;
      case SpvOpTypeImage: {
        const bool storage_image = type->operands[5] == 2;
        b.image_format = format_of(type->operands[6]);
        if (type->operands[1] == SpvDimBuffer)
          b.type = storage_image ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER
                                 : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        else if (type->operands[1] == SpvDimSubpassData)
          b.type = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
        else
          b.type =
              storage_image ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        break;
      }
      case SpvOpTypeSampledImage:
        b.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        break;
      case SpvOpTypeSampler:
        b.type = VK_DESCRIPTOR_TYPE_SAMPLER;
        break;
      case SpvOpTypeAccelerationStructureKHR:
        b.type = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
        break;
      default:
        fail(fmt::format("binding '{}' (set {}, binding {}) has an unsupported type", b.name, b.set,
                         b.binding));
    }
    (referenced_[v] ? out_.bindings : out_.unused_bindings).push_back(std::move(b));
  }

  std::span<const std::uint32_t> words_;
  std::string_view what_;
  std::vector<Id> ids_;
  std::vector<std::uint32_t> variables_;
  std::vector<bool> referenced_;  // per id: used by an instruction in a function body
  bool in_function_ = false;
  std::vector<std::uint32_t> spec_constants_;
  std::optional<std::array<std::uint32_t, 3>> local_size_ids_;
  ShaderReflection out_;
};

}  // namespace

const DescriptorBinding* ShaderReflection::find_binding(std::string_view name) const {
  for (const auto& b : bindings)
    if (b.name == name) return &b;
  return nullptr;
}

const SpecConstant* ShaderReflection::find_spec_constant(std::string_view name) const {
  for (const auto& s : spec_constants)
    if (s.name == name) return &s;
  return nullptr;
}

const StructLayout* ShaderReflection::find_struct(std::string_view name) const {
  for (const auto& s : structs)
    if (s.name == name) return &s;
  return nullptr;
}

ShaderReflection reflect_spirv(std::span<const std::uint32_t> words, std::string_view what) {
  return Parser(words, what).run();
}

std::vector<DescriptorBinding> merge_bindings(std::span<const ShaderReflection* const> stages,
                                              std::string_view what) {
  std::vector<DescriptorBinding> merged;
  for (const ShaderReflection* stage : stages) {
    for (const auto& b : stage->bindings) {
      auto same = std::find_if(merged.begin(), merged.end(), [&](const auto& m) {
        return m.set == b.set && m.binding == b.binding;
      });
      if (same == merged.end()) {
        merged.push_back(b);
      } else if (same->type != b.type || same->count != b.count) {
        throw RuntimeError(
            fmt::format("{}: set {} binding {} is '{}' ({}) in one stage and '{}' ({}) in another",
                        what, b.set, b.binding, same->name, descriptor_type_name(same->type),
                        b.name, descriptor_type_name(b.type)));
      } else {
        same->stages |= b.stages;
      }
    }
  }
  std::sort(merged.begin(), merged.end(), [](const auto& a, const auto& b) {
    return std::tie(a.set, a.binding) < std::tie(b.set, b.binding);
  });
  return merged;
}

const char* descriptor_type_name(VkDescriptorType type) {
  switch (type) {
    case VK_DESCRIPTOR_TYPE_SAMPLER:
      return "sampler";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
      return "combined image sampler";
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
      return "sampled image";
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
      return "storage image";
    case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
      return "uniform texel buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
      return "storage texel buffer";
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
      return "uniform buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
      return "storage buffer";
    case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT:
      return "input attachment";
    case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR:
      return "acceleration structure";
    default:
      return "unknown descriptor";
  }
}

}  // namespace lantern::runtime
