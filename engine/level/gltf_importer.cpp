// glTF -> Level conversion. Images are not decoded (a no-op image loader keeps only references and
// embedded bytes); the runtime reads pixels later with OpenImageIO.
#include "engine/level/gltf_importer.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <map>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/gltf_accessor.h"
#include "engine/scene/finite.h"

namespace lantern {
namespace {

// Keeps the encoded bytes of embedded images and nothing of external ones (their path is kept).
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->uri.empty()) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

struct Importer {
  const std::filesystem::path& file;
  const tinygltf::Model& model;
  Level& level;
  LoadDiagnostics& diagnostics;
  GltfAccessorReader accessors{model, file.string()};
  std::size_t material_base = 0;
  std::size_t image_base = 0;
  std::optional<std::uint32_t> default_material;
  std::size_t blend_materials = 0;  // alphaMode BLEND, rendered as MASK (one warning per file)
  std::map<std::pair<int, int>, std::uint32_t>
      mesh_of_primitive;              // (mesh, primitive) -> level mesh
  std::vector<glm::mat4> node_world;  // filled while traversing
  std::vector<int> node_parent;
  std::vector<std::vector<std::size_t>> node_instances;  // level instances made from each node

  [[noreturn]] void fail(const std::string& place, const std::string& message) const {
    throw InputError(fmt::format("{}: {}: {}", file.string(), place, message));
  }

  glm::vec3 vec3_of(const std::vector<double>& v, glm::vec3 fallback) const {
    return v.size() == 3 ? glm::vec3(static_cast<float>(v[0]), static_cast<float>(v[1]),
                                     static_cast<float>(v[2]))
                         : fallback;
  }

  void import_images() {
    image_base = level.images.size();
    for (std::size_t i = 0; i < model.images.size(); ++i) {
      const tinygltf::Image& img = model.images[i];
      ImageRef ref;
      ref.name = img.name;
      ref.mime_type = img.mimeType;
      if (!img.uri.empty()) {
        ref.path = std::filesystem::absolute(file.parent_path() / img.uri);
        if (!std::filesystem::exists(ref.path))
          fail(fmt::format("image {} '{}'", i, img.name),
               fmt::format("referenced file {} does not exist", ref.path.string()));
      } else {
        ref.embedded = img.image;
      }
      level.images.push_back(std::move(ref));
    }
  }

  TextureSampler sampler(int index, const std::string& place) const {
    TextureSampler out;
    if (index < 0) return out;
    if (static_cast<std::size_t>(index) >= model.samplers.size())
      fail(place, fmt::format("sampler {} does not exist", index));
    const tinygltf::Sampler& s = model.samplers[static_cast<std::size_t>(index)];
    auto wrap = [&](int mode) {
      switch (mode) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
        case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::Repeat;
        default: fail(place, fmt::format("sampler {} has unknown wrap mode {}", index, mode));
      }
    };
    out.wrap_s = wrap(s.wrapS);
    out.wrap_t = wrap(s.wrapT);
    out.mag_linear = s.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST;
    switch (s.minFilter) {
      case TINYGLTF_TEXTURE_FILTER_NEAREST: out = {out.wrap_s, out.wrap_t, out.mag_linear, false, false, false}; break;
      case TINYGLTF_TEXTURE_FILTER_LINEAR: out.mipmaps = false; break;
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: out.min_linear = false; out.mip_linear = false; break;
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: out.mip_linear = false; break;
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: out.min_linear = false; break;
      default: break;  // LINEAR_MIPMAP_LINEAR or unset
    }
    return out;
  }

  TextureRef texture(int texture_index, int texcoord, const tinygltf::ExtensionMap& extensions,
                     const std::string& place) const {
    if (texture_index < 0) return {};
    if (static_cast<std::size_t>(texture_index) >= model.textures.size())
      fail(place, fmt::format("texture {} does not exist", texture_index));
    const tinygltf::Texture& tex = model.textures[static_cast<std::size_t>(texture_index)];
    const int source = tex.source;
    if (source < 0 && tex.extensions.count("KHR_texture_basisu") != 0)
      fail(place, fmt::format("texture {} has only a KHR_texture_basisu (KTX2) source, which "
                              "OpenImageIO cannot decode here; give it a PNG or JPEG `source` "
                              "as a fallback",
                              texture_index));
    if (source < 0 || static_cast<std::size_t>(source) >= model.images.size())
      fail(place, fmt::format("texture {} has no valid image source ({})", texture_index, source));
    if (texcoord < 0 || texcoord > 1)
      fail(place, fmt::format("texture {} uses TEXCOORD_{} (sets 0 and 1 are supported)",
                              texture_index, texcoord));
    TextureRef ref;
    ref.image = static_cast<std::int32_t>(image_base + static_cast<std::size_t>(source));
    ref.texcoord = static_cast<std::uint32_t>(texcoord);
    ref.sampler = sampler(tex.sampler, fmt::format("{} texture {}", place, texture_index));
    if (auto it = extensions.find("KHR_texture_transform"); it != extensions.end()) {
      const tinygltf::Value& t = it->second;
      auto vec2_of = [&](const char* key, glm::vec2 fallback) {
        if (!t.Has(key)) return fallback;
        const tinygltf::Value& v = t.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2)
          fail(place, fmt::format("KHR_texture_transform {} is not two numbers", key));
        return glm::vec2(static_cast<float>(v.Get(0).GetNumberAsDouble()),
                         static_cast<float>(v.Get(1).GetNumberAsDouble()));
      };
      ref.offset = vec2_of("offset", ref.offset);
      ref.scale = vec2_of("scale", ref.scale);
      if (t.Has("rotation"))
        ref.rotation = static_cast<float>(t.Get("rotation").GetNumberAsDouble());
      if (t.Has("texCoord")) {
        const int set = t.Get("texCoord").GetNumberAsInt();
        if (set < 0 || set > 1)
          fail(place, fmt::format("KHR_texture_transform texCoord {} (sets 0 and 1 are supported)",
                                  set));
        ref.texcoord = static_cast<std::uint32_t>(set);
      }
      if (!all_finite(ref.offset) || !all_finite(ref.scale) || !std::isfinite(ref.rotation))
        fail(place, "KHR_texture_transform is not finite");
    }
    return ref;
  }

  void import_materials() {
    material_base = level.materials.size();
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
      const tinygltf::Material& src = model.materials[i];
      const std::string place = fmt::format("material {} '{}'", i, src.name);
      const auto& pbr = src.pbrMetallicRoughness;
      Material m;
      m.name = src.name;
      if (pbr.baseColorFactor.size() == 4)
        m.base_color = glm::vec4(
            static_cast<float>(pbr.baseColorFactor[0]), static_cast<float>(pbr.baseColorFactor[1]),
            static_cast<float>(pbr.baseColorFactor[2]), static_cast<float>(pbr.baseColorFactor[3]));
      m.metallic = static_cast<float>(pbr.metallicFactor);
      m.roughness = static_cast<float>(pbr.roughnessFactor);
      m.emissive_factor = vec3_of(src.emissiveFactor, glm::vec3(0.0f));
      m.double_sided = src.doubleSided;
      if (auto it = src.extensions.find("KHR_materials_emissive_strength");
          it != src.extensions.end() && it->second.Has("emissiveStrength"))
        m.emissive_strength =
            static_cast<float>(it->second.Get("emissiveStrength").GetNumberAsDouble());
      if (auto it = src.extensions.find("KHR_materials_specular"); it != src.extensions.end()) {
        if (it->second.Has("specularFactor"))
          m.specular_factor =
              static_cast<float>(it->second.Get("specularFactor").GetNumberAsDouble());
        if (it->second.Has("specularColorFactor")) {
          const tinygltf::Value& c = it->second.Get("specularColorFactor");
          if (c.IsArray() && c.ArrayLen() == 3)
            for (int k = 0; k < 3; ++k)
              m.specular_color[k] = static_cast<float>(c.Get(k).GetNumberAsDouble());
        }
      }
      if (glm::any(glm::lessThan(m.emissive_factor, glm::vec3(0.0f))) || m.emissive_strength < 0.0f)
        fail(place, "negative emission (emissiveFactor × emissiveStrength must be ≥ 0)");
      if (!std::isfinite(m.emissive_strength) || !all_finite(m.emissive_factor))
        fail(place, "emission is not finite");
      m.base_color_texture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                     pbr.baseColorTexture.extensions, place);
      m.metallic_roughness_texture =
          texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                  pbr.metallicRoughnessTexture.extensions, place);
      m.normal_texture = texture(src.normalTexture.index, src.normalTexture.texCoord,
                                 src.normalTexture.extensions, place);
      m.normal_scale = static_cast<float>(src.normalTexture.scale);
      m.emissive_texture = texture(src.emissiveTexture.index, src.emissiveTexture.texCoord,
                                   src.emissiveTexture.extensions, place);
      if (src.alphaMode == "MASK") {
        m.alpha_mode = AlphaMode::Mask;
      } else if (src.alphaMode == "BLEND") {
        m.alpha_mode = AlphaMode::Blend;
        ++blend_materials;
      } else if (!src.alphaMode.empty() && src.alphaMode != "OPAQUE") {
        fail(place, fmt::format("unknown alphaMode '{}'", src.alphaMode));
      }
      m.alpha_cutoff = m.alpha_mode == AlphaMode::Mask ? static_cast<float>(src.alphaCutoff) : 0.5f;
      if (!std::isfinite(m.alpha_cutoff) || !std::isfinite(m.normal_scale))
        fail(place, "alphaCutoff or normalTexture.scale is not finite");
      level.materials.push_back(std::move(m));
    }
  }

  std::uint32_t material_index(int gltf_material) {
    if (gltf_material >= 0) {
      if (static_cast<std::size_t>(gltf_material) >= model.materials.size())
        throw InputError(
            fmt::format("{}: material {} does not exist", file.string(), gltf_material));
      return static_cast<std::uint32_t>(material_base + static_cast<std::size_t>(gltf_material));
    }
    if (!default_material) {  // glTF's default material
      default_material = static_cast<std::uint32_t>(level.materials.size());
      Material m;
      m.name = "gltf_default";
      level.materials.push_back(m);
    }
    return *default_material;
  }

  const Material* gltf_material(int index) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model.materials.size()) return nullptr;
    return &level.materials[material_base + static_cast<std::size_t>(index)];
  }
  // Whether a texture of glTF material `index` samples texcoord set `set`.
  bool samples_set(int index, std::uint32_t set) const {
    const Material* m = gltf_material(index);
    if (m == nullptr) return false;
    for (const TextureRef* t : {&m->base_color_texture, &m->metallic_roughness_texture,
                                &m->normal_texture, &m->emissive_texture})
      if (t->present() && t->texcoord == set) return true;
    return false;
  }

  std::uint32_t level_mesh(int mesh_index, int primitive_index) {
    if (auto it = mesh_of_primitive.find({mesh_index, primitive_index});
        it != mesh_of_primitive.end())
      return it->second;
    const tinygltf::Mesh& src = model.meshes[static_cast<std::size_t>(mesh_index)];
    const tinygltf::Primitive& prim = src.primitives[static_cast<std::size_t>(primitive_index)];
    const std::string place = fmt::format("{}: mesh {} '{}' primitive {}", file.string(),
                                          mesh_index, src.name, primitive_index);
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
      throw InputError(
          fmt::format("{}: primitive mode {} is not supported (triangles only)", place, prim.mode));
    auto attribute = [&](const char* name) {
      auto it = prim.attributes.find(name);
      return it == prim.attributes.end() ? -1 : it->second;
    };
    const int pos = attribute("POSITION");
    if (pos < 0) throw InputError(fmt::format("{}: has no POSITION attribute", place));
    Mesh mesh;
    mesh.name = src.name;
    mesh.positions = accessors.vec3s(pos);
    if (int a = attribute("NORMAL"); a >= 0) mesh.normals = accessors.vec3s(a);
    // TEXCOORD_0 whenever the primitive has it; TEXCOORD_1 when a texture samples it. A set a
    // texture samples must exist.
    for (std::uint32_t set : {0u, 1u}) {
      const std::string uv_name = fmt::format("TEXCOORD_{}", set);
      const int a = attribute(uv_name.c_str());
      const bool sampled = samples_set(prim.material, set);
      if (a >= 0 && (set == 0 || sampled)) {
        (set == 0 ? mesh.uvs : mesh.uvs1) = accessors.vec2s(a, true);
      } else if (a < 0 && sampled) {
        throw InputError(fmt::format(
            "{}: material {} samples {}, which the primitive does not have", place,
            prim.material, uv_name));
      }
    }
    if (int a = attribute("TANGENT"); a >= 0) mesh.tangents = accessors.vec4s(a);
    if (prim.indices >= 0) {
      mesh.indices = accessors.indices(prim.indices);
    } else {
      mesh.indices.resize(mesh.positions.size());
      for (std::size_t i = 0; i < mesh.indices.size(); ++i)
        mesh.indices[i] = static_cast<std::uint32_t>(i);
    }
    finalize_mesh(mesh, fmt::format("{} (POSITION accessor {})", place, pos), diagnostics);
    const auto index = static_cast<std::uint32_t>(level.meshes.size());
    level.meshes.push_back(std::move(mesh));
    mesh_of_primitive[{mesh_index, primitive_index}] = index;
    return index;
  }

  glm::mat4 local_matrix(const tinygltf::Node& node) const {
    if (node.matrix.size() == 16) {
      glm::mat4 m;
      for (int i = 0; i < 16; ++i)
        glm::value_ptr(m)[i] = static_cast<float>(node.matrix[static_cast<std::size_t>(i)]);
      return m;
    }
    return local_transform(node).matrix();
  }

  static Transform local_transform(const tinygltf::Node& node) {
    Transform t;
    if (node.translation.size() == 3)
      t.translation = glm::vec3(static_cast<float>(node.translation[0]),
                                static_cast<float>(node.translation[1]),
                                static_cast<float>(node.translation[2]));
    if (node.rotation.size() == 4)
      t.rotation =
          glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                    static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
    if (node.scale.size() == 3)
      t.scale = glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                          static_cast<float>(node.scale[2]));
    return t;
  }

  // Depth-first, parents before children, children in file order. An explicit stack, not
  // recursion: the hierarchy depth comes from the file and must not bound the call stack.
  void visit(int root, const glm::mat4& placement) {
    struct Pending {
      int index;
      int parent_index;
      glm::mat4 parent_world;
    };
    std::vector<Pending> stack{{root, -1, placement}};
    while (!stack.empty()) {
      const Pending p = stack.back();
      stack.pop_back();
      const glm::mat4 world = visit_node(p.index, p.parent_world, p.parent_index);
      const std::vector<int>& children = model.nodes[static_cast<std::size_t>(p.index)].children;
      for (auto it = children.rbegin(); it != children.rend(); ++it)
        stack.push_back({*it, p.index, world});
    }
  }

  // One node: its world matrix (returned), instances and light.
  glm::mat4 visit_node(int index, const glm::mat4& parent, int parent_index) {
    const std::string place = fmt::format("node {}", index);
    if (index < 0 || static_cast<std::size_t>(index) >= model.nodes.size())
      fail(place, "does not exist");
    // glTF node hierarchies are disjoint trees: a node reached twice is a cycle or a node with
    // two parents (a DAG, whose traversal would be exponential in its depth).
    if (node_parent[static_cast<std::size_t>(index)] != kUnvisited)
      fail(place, "is reached twice (node hierarchy has a cycle or a node with two parents)");
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(index)];
    const glm::mat4 world = parent * local_matrix(node);
    if (!all_finite(world[0]) || !all_finite(world[1]) || !all_finite(world[2]) ||
        !all_finite(world[3]))
      fail(fmt::format("node {} '{}'", index, node.name), "transform is not finite");
    node_world[static_cast<std::size_t>(index)] = world;
    node_parent[static_cast<std::size_t>(index)] = parent_index;
    if (node.mesh >= 0) {
      if (static_cast<std::size_t>(node.mesh) >= model.meshes.size())
        fail(fmt::format("node {} '{}'", index, node.name),
             fmt::format("mesh {} does not exist", node.mesh));
      const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
      for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        Instance inst;
        inst.name = node.name.empty() ? mesh.name : node.name;
        inst.mesh = level_mesh(node.mesh, static_cast<int>(p));
        inst.material = material_index(mesh.primitives[p].material);
        inst.world = world;
        inst.transform = Transform::from_matrix(world);
        node_instances[static_cast<std::size_t>(index)].push_back(level.instances.size());
        level.instances.push_back(std::move(inst));
      }
    }
    if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end())
      add_light(index, it->second, world);
    return world;
  }

  void add_light(int node_index, const tinygltf::Value& ext, const glm::mat4& world) {
    const std::string node_place = fmt::format("node {}", node_index);
    if (!ext.Has("light") || !ext.Get("light").IsNumber())
      fail(node_place, "KHR_lights_punctual extension has no light index");
    const int li = ext.Get("light").GetNumberAsInt();
    if (li < 0 || static_cast<std::size_t>(li) >= model.lights.size())
      fail(node_place, fmt::format("KHR_lights_punctual light {} does not exist", li));
    const tinygltf::Light& src = model.lights[static_cast<std::size_t>(li)];
    const std::string place =
        fmt::format("KHR_lights_punctual light {} '{}' (node {})", li, src.name, node_index);
    Light l;
    l.name = src.name;
    if (src.type == "point")
      l.type = LightType::Point;
    else if (src.type == "spot")
      l.type = LightType::Spot;
    else if (src.type == "directional")
      l.type = LightType::Directional;
    else
      fail(place, fmt::format("unknown light type '{}'", src.type));
    l.color = vec3_of(src.color, glm::vec3(1.0f));
    l.intensity = static_cast<float>(src.intensity);
    l.range = static_cast<float>(src.range);
    if (!all_finite(l.color) || !std::isfinite(l.intensity) || !std::isfinite(l.range))
      fail(place, "color, intensity or range is not finite");
    if (glm::any(glm::lessThan(l.color, glm::vec3(0.0f))) || l.intensity < 0.0f)
      fail(place, fmt::format("negative color or intensity ({})", l.intensity));
    if (l.range < 0.0f) fail(place, "negative range");
    if (l.type == LightType::Spot) {
      l.inner_cone = static_cast<float>(src.spot.innerConeAngle);
      l.outer_cone = static_cast<float>(src.spot.outerConeAngle);
      if (!(l.inner_cone >= 0.0f && l.inner_cone < l.outer_cone &&
            l.outer_cone <= glm::half_pi<float>() + 1e-6f))
        fail(place, fmt::format("spot cone angles need 0 <= inner ({}) < outer ({}) <= pi/2",
                                l.inner_cone, l.outer_cone));
    }
    const Transform t = Transform::from_matrix(world);
    l.position = t.translation;
    l.rotation = t.rotation;
    level.lights.push_back(std::move(l));
  }

  std::optional<Camera> camera(int& camera_node) const {
    camera_node = -1;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (model.nodes[i].camera >= 0 && node_parent[i] != kUnvisited) {
        camera_node = static_cast<int>(i);
        break;
      }
    if (camera_node < 0) return std::nullopt;
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(camera_node)];
    const std::string place = fmt::format("node {} '{}'", camera_node, node.name);
    if (static_cast<std::size_t>(node.camera) >= model.cameras.size())
      fail(place, fmt::format("camera {} does not exist", node.camera));
    const tinygltf::Camera& src = model.cameras[static_cast<std::size_t>(node.camera)];
    if (src.type != "perspective")
      fail(fmt::format("camera {} '{}'", node.camera, src.name),
           fmt::format("camera type '{}' is not supported (perspective only)", src.type));
    Camera c;
    c.yfov = static_cast<float>(src.perspective.yfov);
    c.aspect = static_cast<float>(src.perspective.aspectRatio);
    c.znear = static_cast<float>(src.perspective.znear);
    c.zfar = static_cast<float>(src.perspective.zfar);
    if (!(c.yfov > 0.0f && c.yfov < glm::pi<float>()) || !(c.znear > 0.0f) || c.aspect < 0.0f ||
        (c.zfar != 0.0f && c.zfar <= c.znear))
      fail(fmt::format("camera {} '{}'", node.camera, src.name),
           fmt::format("invalid perspective (yfov {}, aspect {}, znear {}, zfar {})", c.yfov,
                       c.aspect, c.znear, c.zfar));
    const Transform t = Transform::from_matrix(node_world[static_cast<std::size_t>(camera_node)]);
    c.position = t.translation;
    c.orientation = t.rotation;
    return c;
  }

  // Samples one channel (translation VEC3 or rotation VEC4) at time t.
  glm::vec4 sample(const tinygltf::AnimationSampler& s, const std::vector<float>& times,
                   const std::vector<glm::vec4>& values, bool rotation, float t) const {
    const bool cubic = s.interpolation == "CUBICSPLINE";
    auto value = [&](std::size_t k) { return values[cubic ? 3 * k + 1 : k]; };
    if (t <= times.front()) return value(0);
    if (t >= times.back()) return value(times.size() - 1);
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) -
        1;
    if (s.interpolation == "STEP") return value(k);
    const float u = (t - times[k]) / (times[k + 1] - times[k]);
    if (!rotation) return glm::mix(value(k), value(k + 1), u);
    const glm::vec4 a = value(k), b = value(k + 1);
    const glm::quat qa(a.w, a.x, a.y, a.z), qb(b.w, b.x, b.y, b.z);
    const glm::quat q = glm::slerp(qa, glm::dot(qa, qb) < 0.0f ? -qb : qb, u);
    return {q.x, q.y, q.z, q.w};
  }

  // The first animation that moves `node_index` (translation and/or rotation), sampled at the
  // union of its key times into world-space keys: parent world (at rest) × animated local. The
  // path is named after the animation (possibly empty). Other channels (scale, weights) are
  // skipped.
  std::optional<CameraPath> node_path(int node_index, const glm::mat4& placement) const {
    for (std::size_t ai = 0; ai < model.animations.size(); ++ai) {
      const tinygltf::Animation& anim = model.animations[ai];
      struct Channel {
        const tinygltf::AnimationSampler* sampler;
        std::vector<float> times;
        std::vector<glm::vec4> values;
        bool rotation;
      };
      std::vector<Channel> channels;
      std::vector<float> all_times;
      for (std::size_t ci = 0; ci < anim.channels.size(); ++ci) {
        const tinygltf::AnimationChannel& ch = anim.channels[ci];
        if (ch.target_node != node_index) continue;
        if (ch.target_path != "translation" && ch.target_path != "rotation") continue;
        const std::string place = fmt::format("animation {} '{}' channel {}", ai, anim.name, ci);
        if (ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size())
          fail(place, fmt::format("sampler {} does not exist", ch.sampler));
        const tinygltf::AnimationSampler& s = anim.samplers[static_cast<std::size_t>(ch.sampler)];
        Channel c{&s, accessors.scalars(s.input), {}, ch.target_path == "rotation"};
        if (c.rotation) {
          c.values = accessors.vec4s(s.output, true);
        } else {
          for (const glm::vec3& v : accessors.vec3s(s.output)) c.values.emplace_back(v, 0.0f);
        }
        const std::size_t per_key = s.interpolation == "CUBICSPLINE" ? 3 : 1;
        if (c.times.empty() || c.values.size() != c.times.size() * per_key)
          fail(place, fmt::format("{} key times but {} values", c.times.size(), c.values.size()));
        for (std::size_t k = 0; k < c.times.size(); ++k)
          if (!std::isfinite(c.times[k]) || (k > 0 && !(c.times[k] > c.times[k - 1])))
            fail(place,
                 fmt::format("key time {} ({}) is not finite and increasing (input accessor {})", k,
                             c.times[k], s.input));
        for (const glm::vec4& v : c.values)
          if (!all_finite(v))
            fail(place, fmt::format("non-finite value (output accessor {})", s.output));
        all_times.insert(all_times.end(), c.times.begin(), c.times.end());
        channels.push_back(std::move(c));
      }
      if (channels.empty()) continue;
      std::sort(all_times.begin(), all_times.end());
      all_times.erase(std::unique(all_times.begin(), all_times.end()), all_times.end());
      const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_index)];
      const int parent = node_parent[static_cast<std::size_t>(node_index)];
      const glm::mat4 parent_world =
          parent >= 0 ? node_world[static_cast<std::size_t>(parent)] : placement;
      CameraPath path;
      path.name = anim.name;
      for (float t : all_times) {
        Transform local = local_transform(node);
        for (const Channel& c : channels) {
          const glm::vec4 v = sample(*c.sampler, c.times, c.values, c.rotation, t);
          if (c.rotation)
            local.rotation = glm::normalize(glm::quat(v.w, v.x, v.y, v.z));
          else
            local.translation = glm::vec3(v);
        }
        const Transform world = Transform::from_matrix(parent_world * local.matrix());
        path.keys.push_back({t, world.translation, world.rotation, std::nullopt});
      }
      if (std::string problem = path.problem(); !problem.empty())
        fail(fmt::format("animation {} '{}' of node {} '{}'", ai, anim.name, node_index, node.name),
             problem);
      return path;
    }
    return std::nullopt;
  }

  std::optional<CameraPath> camera_path(int camera_node, const glm::mat4& placement) const {
    std::optional<CameraPath> path = node_path(camera_node, placement);
    if (path && path->name.empty()) path->name = "camera";
    return path;
  }

  // "<file stem>/<node name or index>", suffixed "#2", "#3"... if the level already has it.
  std::string unique_path_name(int node_index) const {
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_index)];
    const std::string base = fmt::format(
        "{}/{}", file.stem().string(), node.name.empty() ? std::to_string(node_index) : node.name);
    std::string name = base;
    for (int k = 2; level.find_path(name); ++k) name = fmt::format("{}#{}", base, k);
    return name;
  }

  // Every animated mesh node gets a path of its own, followed (speed 1, looping) by each
  // instance made from it; follow_path sets translation and rotation, the node's scale stays.
  void animate_mesh_nodes(const glm::mat4& placement) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
      if (node_instances[i].empty()) continue;
      std::optional<CameraPath> path = node_path(static_cast<int>(i), placement);
      if (!path) continue;
      path->name = unique_path_name(static_cast<int>(i));
      const FollowPathBehaviour follow{path->name, 1.0f, true};
      for (std::size_t k : node_instances[i]) level.instances[k].behaviour = follow;
      level.paths.push_back(std::move(*path));
    }
  }

  static constexpr int kUnvisited = -2;
};

}  // namespace

GltfImport import_gltf(const std::filesystem::path& file, const glm::mat4& placement, Level& level,
                       LoadDiagnostics& diagnostics) {
  if (!std::filesystem::is_regular_file(file))
    throw InputError(fmt::format("{}: glTF file not found", file.string()));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const std::string ext = file.extension().string();
  const bool ok = (ext == ".glb" || ext == ".GLB")
                      ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                      : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
  if (!ok || !err.empty()) {
    std::string what = err.empty() ? warn : err;
    while (!what.empty() && (what.back() == '\n' || what.back() == ' ')) what.pop_back();
    std::replace(what.begin(), what.end(), '\n', ';');
    throw InputError(fmt::format("{}: malformed glTF: {}", file.string(), what));
  }
  if (!warn.empty()) log::debug("{}: tinygltf: {}", file.string(), warn);

  Importer im{file, model, level, diagnostics};
  im.node_world.assign(model.nodes.size(), glm::mat4(1.0f));
  im.node_parent.assign(model.nodes.size(), Importer::kUnvisited);
  im.node_instances.assign(model.nodes.size(), {});
  im.import_images();
  im.import_materials();
  if (im.blend_materials > 0)
    log::warn("{}: {} material(s) with alphaMode BLEND rendered as MASK at cutoff 0.5",
              file.string(), im.blend_materials);

  GltfImport result;
  result.first_instance = level.instances.size();
  result.first_light = level.lights.size();
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(scene) >= model.scenes.size())
      throw InputError(fmt::format("{}: default scene {} does not exist", file.string(), scene));
    roots = model.scenes[static_cast<std::size_t>(scene)].nodes;
  } else {  // no scene: every node that is nobody's child is a root
    std::vector<bool> is_child(model.nodes.size(), false);
    for (const auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && static_cast<std::size_t>(c) < is_child.size())
          is_child[static_cast<std::size_t>(c)] = true;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
  }
  for (int r : roots) im.visit(r, placement);

  int camera_node = -1;
  result.camera = im.camera(camera_node);
  if (camera_node >= 0) result.camera_path = im.camera_path(camera_node, placement);
  im.animate_mesh_nodes(placement);
  std::size_t scale_channels = 0;
  for (const tinygltf::Animation& anim : model.animations)
    for (const tinygltf::AnimationChannel& ch : anim.channels)
      scale_channels += ch.target_path == "scale" ? 1 : 0;
  if (scale_channels > 0)
    log::warn("{}: {} scale animation channel(s) ignored (node animations move and turn only)",
              file.string(), scale_channels);
  return result;
}

}  // namespace lantern
