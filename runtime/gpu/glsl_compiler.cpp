// glslang library front end: preamble defines, an #include resolver and SPIR-V generation.
#include "runtime/gpu/glsl_compiler.h"

#include <fmt/format.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include "engine/core/error.h"

namespace lantern::runtime {
namespace {

std::optional<std::string> read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

EShLanguage language_of(VkShaderStageFlagBits stage) {
  switch (stage) {
    case VK_SHADER_STAGE_VERTEX_BIT:
      return EShLangVertex;
    case VK_SHADER_STAGE_FRAGMENT_BIT:
      return EShLangFragment;
    case VK_SHADER_STAGE_COMPUTE_BIT:
      return EShLangCompute;
    case VK_SHADER_STAGE_RAYGEN_BIT_KHR:
      return EShLangRayGen;
    case VK_SHADER_STAGE_MISS_BIT_KHR:
      return EShLangMiss;
    case VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR:
      return EShLangClosestHit;
    case VK_SHADER_STAGE_ANY_HIT_BIT_KHR:
      return EShLangAnyHit;
    default:
      throw InputError(fmt::format("compile_glsl: unsupported shader stage {:#x}",
                                   static_cast<unsigned>(stage)));
  }
}

// Resolves `#include "x"` relative to the including file, then against the include dirs
// (the same rule as glslangValidator -I).
class Includer final : public glslang::TShader::Includer {
 public:
  explicit Includer(std::vector<std::filesystem::path> dirs) : dirs_(std::move(dirs)) {}

  IncludeResult* includeLocal(const char* header, const char* includer, size_t depth) override {
    const auto local = std::filesystem::path(includer).parent_path() / header;
    if (auto* result = open(local)) return result;
    return includeSystem(header, includer, depth);
  }
  IncludeResult* includeSystem(const char* header, const char*, size_t) override {
    for (const auto& dir : dirs_)
      if (auto* result = open(dir / header)) return result;
    return nullptr;
  }
  void releaseInclude(IncludeResult* result) override {
    if (result != nullptr) {
      delete static_cast<std::string*>(result->userData);
      delete result;
    }
  }

 private:
  IncludeResult* open(const std::filesystem::path& path) {
    auto text = read_text(path);
    if (!text) return nullptr;
    auto* data = new std::string(std::move(*text));
    return new IncludeResult(path.lexically_normal().string(), data->data(), data->size(), data);
  }
  std::vector<std::filesystem::path> dirs_;
};

void initialize_glslang_once() {
  static std::once_flag once;
  std::call_once(once,
                 [] { glslang::InitializeProcess(); });  // finalized at process exit by the OS
}

}  // namespace

VkShaderStageFlagBits stage_from_extension(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".comp") return VK_SHADER_STAGE_COMPUTE_BIT;
  if (ext == ".vert") return VK_SHADER_STAGE_VERTEX_BIT;
  if (ext == ".frag") return VK_SHADER_STAGE_FRAGMENT_BIT;
  if (ext == ".rgen") return VK_SHADER_STAGE_RAYGEN_BIT_KHR;
  if (ext == ".rmiss") return VK_SHADER_STAGE_MISS_BIT_KHR;
  if (ext == ".rchit") return VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR;
  if (ext == ".rahit") return VK_SHADER_STAGE_ANY_HIT_BIT_KHR;
  throw InputError(fmt::format("{}: unknown shader stage for extension '{}'", path.string(), ext));
}

GlslResult compile_glsl(const std::filesystem::path& path, VkShaderStageFlagBits stage,
                        std::span<const std::string> defines,
                        std::span<const std::filesystem::path> include_dirs) {
  initialize_glslang_once();
  if (stage == VkShaderStageFlagBits{}) stage = stage_from_extension(path);
  const EShLanguage language = language_of(stage);
  const auto source = read_text(path);
  if (!source) throw InputError(fmt::format("compile_glsl: cannot read {}", path.string()));

  std::string preamble;
  for (const auto& define : defines) {
    const auto eq = define.find('=');
    preamble += eq == std::string::npos
                    ? fmt::format("#define {} 1\n", define)
                    : fmt::format("#define {} {}\n", define.substr(0, eq), define.substr(eq + 1));
  }
  std::vector<std::filesystem::path> dirs(include_dirs.begin(), include_dirs.end());
  // The build's own include path (cmake/LanternShaders.cmake): shaders/, then the NanoVDB
  // headers (PNanoVDB.h, which the volume lookup benchmark's kernel includes).
  if (dirs.empty()) {
#ifdef LANTERN_SOURCE_DIR
    dirs.emplace_back(std::filesystem::path(LANTERN_SOURCE_DIR) / "shaders");
#endif
#ifdef LANTERN_NANOVDB_INCLUDE_DIR
    dirs.emplace_back(LANTERN_NANOVDB_INCLUDE_DIR);
#endif
  }

  const std::string name = path.string();
  const char* text = source->c_str();
  const char* names = name.c_str();
  const int length = static_cast<int>(source->size());
  glslang::TShader shader(language);
  shader.setStringsWithLengthsAndNames(&text, &length, &names, 1);
  shader.setPreamble(preamble.c_str());
  shader.setEntryPoint("main");
  shader.setEnvInput(glslang::EShSourceGlsl, language, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  Includer includer(std::move(dirs));

  GlslResult result;
  if (!shader.parse(GetDefaultResources(), 100, false, messages, includer)) {
    result.log = fmt::format("{}{}", shader.getInfoLog(), shader.getInfoDebugLog());
    return result;
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    result.log =
        fmt::format("{}: link failed: {}{}", name, program.getInfoLog(), program.getInfoDebugLog());
    return result;
  }
  glslang::SpvOptions options;
  options.validate = false;  // spirv-val is run separately where wanted
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*program.getIntermediate(language), result.spirv, &logger, &options);
  result.log = shader.getInfoLog() + logger.getAllMessages();
  return result;
}

}  // namespace lantern::runtime
