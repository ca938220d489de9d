// JSON levels: materials, behaviours, primitives, lights and paths.
#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/level/json_level_reader.h"
#include "engine/level/primitives.h"

namespace lantern {
namespace {

// Largest emissive quad grid one primitive may make (2 triangles per quad).
constexpr std::uint64_t kMaxGridQuads = std::uint64_t{1} << 22;

glm::quat direction_to_rotation(const glm::vec3& direction) {
  return look_at_orientation(glm::vec3(0.0f), glm::normalize(direction));
}

}  // namespace

Transform JsonLevelReader::read_transform(JsonObject& o) {
  Transform t;
  t.translation = o.vec3("translation", t.translation);
  if (o.has("rotation") && o.has("rotation_deg"))
    o.fail("give either 'rotation' or 'rotation_deg', not both");
  t.rotation = o.quat("rotation", t.rotation);
  if (o.has("rotation_deg"))
    t.rotation = glm::quat(glm::radians(o.vec3("rotation_deg")));  // XYZ Euler
  if (o.has("scale")) {
    if (o.raw("scale").is_number())
      t.scale = glm::vec3(o.number("scale"));
    else
      t.scale = o.vec3("scale");
    if (glm::any(glm::equal(t.scale, glm::vec3(0.0f)))) o.fail("scale", "scale must not be zero");
  }
  return t;
}

Material JsonLevelReader::read_material(JsonObject& o) {
  Material m;
  m.metallic = 0.0f;  // JSON materials default to a rough dielectric (glTF defaults to metal)
  m.roughness = 0.5f;
  if (o.has("base_color")) {
    const nlohmann::json& v = o.raw("base_color");
    if (v.is_array() && v.size() == 3)
      m.base_color = glm::vec4(o.vec3("base_color"), 1.0f);
    else
      m.base_color = o.vec4("base_color", m.base_color);
  }
  m.metallic = o.number("metallic", m.metallic);
  m.roughness = o.number("roughness", m.roughness);
  m.emissive_factor = o.vec3("emissive", m.emissive_factor);
  m.emissive_strength = o.number("emissive_strength", m.emissive_strength);
  m.specular_factor = o.number("specular", m.specular_factor);
  m.specular_color = o.vec3("specular_color", m.specular_color);
  m.double_sided = o.boolean("double_sided", false);
  if (glm::any(glm::lessThan(m.emissive_factor, glm::vec3(0.0f))) || m.emissive_strength < 0.0f)
    o.fail("negative radiance (emissive × emissive_strength must be >= 0)");
  if (glm::any(glm::lessThan(glm::vec3(m.base_color), glm::vec3(0.0f))) || m.metallic < 0.0f ||
      m.metallic > 1.0f || m.roughness < 0.0f || m.roughness > 1.0f || m.specular_factor < 0.0f)
    o.fail("base_color, specular must be >= 0; metallic and roughness in [0, 1]");
  auto texture = [&](std::string_view key, TextureRef& slot) {
    if (!o.has(key)) return;
    ImageRef img;
    img.path = existing_file(o, key);
    img.name = img.path.filename().string();
    level().images.push_back(std::move(img));
    slot.image = static_cast<std::int32_t>(level().images.size() - 1);
  };
  texture("base_color_texture", m.base_color_texture);
  texture("metallic_roughness_texture", m.metallic_roughness_texture);
  texture("normal_texture", m.normal_texture);
  texture("emissive_texture", m.emissive_texture);
  o.finish();
  return m;
}

void JsonLevelReader::read_materials(JsonObject& section) {
  for (const std::string& name : section.keys()) {
    JsonObject o = section.object(name);
    Material m = read_material(o);
    m.name = name;
    materials_[name] = builder_.add_material(std::move(m));
  }
}

std::uint32_t JsonLevelReader::material_ref(JsonObject& owner, std::string_view key) {
  if (!owner.has(key)) {  // a plain light-grey dielectric, made once
    auto it = materials_.find("__default");
    if (it != materials_.end()) return it->second;
    Material m;
    m.name = "default";
    m.base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
    m.metallic = 0.0f;
    m.roughness = 0.5f;
    return materials_["__default"] = builder_.add_material(m);
  }
  const nlohmann::json& v = owner.raw(key);
  if (v.is_string()) {
    auto it = materials_.find(v.get<std::string>());
    if (it == materials_.end())
      owner.fail(key, fmt::format("no material named '{}' in 'materials'", v.get<std::string>()));
    return it->second;
  }
  JsonObject o = owner.object(key);
  return builder_.add_material(read_material(o));
}

Behaviour JsonLevelReader::read_behaviour(JsonObject& o) {
  const std::string type = o.string("type");
  Behaviour out;
  if (type == "rotate") {
    RotateBehaviour b;
    b.axis = o.vec3("axis", b.axis);
    if (glm::length(b.axis) < 1e-6f) o.fail("axis", "axis has zero length");
    b.axis = glm::normalize(b.axis);
    b.speed = glm::radians(o.number("speed_deg", glm::degrees(b.speed)));
    out = b;
  } else if (type == "orbit") {
    OrbitBehaviour b;
    b.center = o.vec3("center", b.center);
    b.radius = o.number("radius", b.radius);
    b.speed = glm::radians(o.number("speed_deg", glm::degrees(b.speed)));
    b.axis = o.vec3("axis", b.axis);
    b.phase = glm::radians(o.number("phase_deg", 0.0f));
    if (glm::length(b.axis) < 1e-6f) o.fail("axis", "axis has zero length");
    b.axis = glm::normalize(b.axis);
    if (b.radius < 0.0f) o.fail("radius", "must be >= 0");
    out = b;
  } else if (type == "flicker") {
    FlickerBehaviour b;
    b.min = o.number("min", b.min);
    b.max = o.number("max", b.max);
    b.rate = o.number("rate", b.rate);
    b.seed = static_cast<std::uint32_t>(o.integer("seed", 0, 0, 0xFFFFFFFFll));
    if (b.min < 0.0f || b.max < b.min) o.fail("need 0 <= min <= max");
    if (b.rate <= 0.0f) o.fail("rate", "must be > 0");
    out = b;
  } else if (type == "follow_path") {
    FollowPathBehaviour b;
    b.path = o.string("path");
    b.speed = o.number("speed", b.speed);
    b.loop = o.boolean("loop", b.loop);
    if (!level().find_path(b.path))
      o.fail("path", fmt::format("no path named '{}' in 'paths'", b.path));
    out = b;
  } else {
    o.fail("type",
           fmt::format("unknown behaviour type '{}' (rotate, orbit, flicker, follow_path)", type));
  }
  o.finish();
  return out;
}

void JsonLevelReader::read_behaviours(JsonObject& section) {
  for (const std::string& name : section.keys()) {
    JsonObject o = section.object(name);
    behaviours_[name] = read_behaviour(o);
  }
}

std::optional<Behaviour> JsonLevelReader::behaviour_ref(JsonObject& owner) {
  if (!owner.has("behaviour")) return std::nullopt;
  const nlohmann::json& v = owner.raw("behaviour");
  if (v.is_string()) {
    auto it = behaviours_.find(v.get<std::string>());
    if (it == behaviours_.end())
      owner.fail("behaviour",
                 fmt::format("no behaviour named '{}' in 'behaviours'", v.get<std::string>()));
    return it->second;
  }
  JsonObject o = owner.object("behaviour");
  return read_behaviour(o);
}

void JsonLevelReader::read_primitive(JsonObject& o) {
  const std::string type = o.string("type");
  const std::string name = o.string("name", type);
  const std::string where = fmt::format("{}: {}", file_.string(), o.pointer());
  if (type == "emissive_quad_grid") {
    EmissiveQuadGrid g;
    g.origin = o.vec3("origin", g.origin);
    g.u = o.vec3("u", g.u);
    g.v = o.vec3("v", g.v);
    if (glm::length(glm::cross(g.u, g.v)) < 1e-9f)
      o.fail("u and v must be non-zero and not parallel");
    const nlohmann::json& counts = o.raw("counts");
    if (!counts.is_array() || counts.size() != 2 || !counts[0].is_number_integer() ||
        !counts[1].is_number_integer() || counts[0].get<std::int64_t>() < 1 ||
        counts[1].get<std::int64_t>() < 1)
      o.fail("counts",
             fmt::format("expected [nx, ny], two positive integers, got {}", counts.dump()));
    const auto nx = counts[0].get<std::uint64_t>(), ny = counts[1].get<std::uint64_t>();
    if (nx > kMaxGridQuads || ny > kMaxGridQuads || nx * ny > kMaxGridQuads)
      o.fail("counts",
             fmt::format("{} x {} = {} quads exceeds the limit of {} quads per grid", nx, ny,
                         static_cast<double>(nx) * static_cast<double>(ny), kMaxGridQuads));
    g.nx = static_cast<std::uint32_t>(nx);
    g.ny = static_cast<std::uint32_t>(ny);
    g.size = o.vec2("size", g.size);
    if (g.size.x <= 0.0f || g.size.y <= 0.0f) o.fail("size", "quad size must be > 0");
    g.color = o.vec3("color", g.color);
    if (glm::any(glm::lessThan(g.color, glm::vec3(0.0f))))
      o.fail("color", "negative radiance colour");
    JsonObject r = o.object("radiance");
    g.radiance_min = r.number("min");
    g.radiance_max = r.number("max", g.radiance_min);
    g.pattern = r.string("pattern", g.pattern);
    g.levels = static_cast<std::uint32_t>(r.integer("levels", g.levels, 1, 4096));
    g.seed = static_cast<std::uint32_t>(r.integer("seed", g.seed, 0, 0xFFFFFFFFll));
    if (g.radiance_min < 0.0f) r.fail("min", fmt::format("negative radiance {}", g.radiance_min));
    if (g.radiance_max < g.radiance_min) r.fail("max", "must be >= min");
    if (g.pattern != "uniform" && g.pattern != "linear" && g.pattern != "log" &&
        g.pattern != "checker" && g.pattern != "random")
      r.fail("pattern", fmt::format("unknown pattern '{}' (uniform, linear, log, checker, random)",
                                    g.pattern));
    r.finish();
    Material base = level().materials[material_ref(o, "material")];
    const Transform t = read_transform(o);
    std::optional<Behaviour> behaviour = behaviour_ref(o);
    o.finish();
    for (EmissiveQuadBin& bin : make_emissive_quad_grid(g)) {
      Material m = base;
      m.name = fmt::format("{}_L{:.4g}", name, bin.radiance);
      m.emissive_factor = g.color;
      m.emissive_strength = bin.radiance;
      const std::uint32_t mat = builder_.add_material(m);
      const std::uint32_t mesh = builder_.add_mesh(std::move(bin.mesh), where);
      builder_.add_instance(name, mesh, mat, t, behaviour);
    }
    return;
  }
  Mesh mesh;
  if (type == "plane") {
    const glm::vec2 size = o.vec2("size", glm::vec2(1.0f));
    if (size.x <= 0.0f || size.y <= 0.0f) o.fail("size", "must be > 0");
    mesh = make_plane(size);
  } else if (type == "box") {
    const glm::vec3 size = o.vec3("size", glm::vec3(1.0f));
    if (glm::any(glm::lessThanEqual(size, glm::vec3(0.0f)))) o.fail("size", "must be > 0");
    mesh = make_box(size, o.boolean("inward", false));
  } else if (type == "sphere") {
    const float radius = o.number("radius", 1.0f);
    if (radius <= 0.0f) o.fail("radius", "must be > 0");
    const std::string kind = o.string("mesh", "ico");
    if (kind == "ico") {
      mesh =
          make_ico_sphere(radius, static_cast<std::uint32_t>(o.integer("subdivisions", 3, 0, 8)));
    } else if (kind == "uv") {
      mesh = make_uv_sphere(radius, static_cast<std::uint32_t>(o.integer("segments", 32, 3, 4096)),
                            static_cast<std::uint32_t>(o.integer("rings", 16, 2, 4096)));
    } else {
      o.fail("mesh", fmt::format("unknown sphere mesh '{}' (ico, uv)", kind));
    }
  } else {
    o.fail(
        "type",
        fmt::format("unknown primitive type '{}' (plane, box, sphere, emissive_quad_grid)", type));
  }
  mesh.name = name;
  const std::uint32_t mat = material_ref(o, "material");
  const Transform t = read_transform(o);
  std::optional<Behaviour> behaviour = behaviour_ref(o);
  o.finish();
  const std::uint32_t m = builder_.add_mesh(std::move(mesh), where);
  builder_.add_instance(name, m, mat, t, behaviour);
}

void JsonLevelReader::read_light(JsonObject& o) {
  Light l;
  const std::string type = o.string("type");
  if (type == "point")
    l.type = LightType::Point;
  else if (type == "spot")
    l.type = LightType::Spot;
  else if (type == "directional")
    l.type = LightType::Directional;
  else
    o.fail("type", fmt::format("unknown light type '{}' (point, spot, directional)", type));
  l.name = o.string("name", type);
  l.color = o.vec3("color", l.color);
  l.intensity = o.number("intensity");
  l.range = o.number("range", 0.0f);
  if (glm::any(glm::lessThan(l.color, glm::vec3(0.0f)))) o.fail("color", "negative light colour");
  if (l.intensity < 0.0f) o.fail("intensity", fmt::format("negative intensity {}", l.intensity));
  if (l.range < 0.0f) o.fail("range", "must be >= 0 (0 = no range, inverse square)");
  if (l.type != LightType::Directional) l.position = o.vec3("position");
  const int ways = int(o.has("direction")) + int(o.has("target")) + int(o.has("rotation"));
  if (ways > 1) o.fail("give one of 'direction', 'target', 'rotation'");
  if (l.type != LightType::Point && ways == 0)
    o.fail("direction", "is required for spot and directional lights");
  if (o.has("direction")) {
    const glm::vec3 d = o.vec3("direction");
    if (glm::length(d) < 1e-6f) o.fail("direction", "has zero length");
    l.rotation = direction_to_rotation(d);
  } else if (o.has("target")) {
    const glm::vec3 target = o.vec3("target");
    if (glm::length(target - l.position) < 1e-6f) o.fail("target", "equals the light position");
    l.rotation = direction_to_rotation(target - l.position);
  } else {
    l.rotation = o.quat("rotation", l.rotation);
  }
  if (l.type == LightType::Spot) {
    l.inner_cone = glm::radians(o.number("inner_cone_deg", 0.0f));
    l.outer_cone = glm::radians(o.number("outer_cone_deg", 45.0f));
    if (!(l.inner_cone >= 0.0f && l.inner_cone < l.outer_cone &&
          l.outer_cone <= glm::half_pi<float>() + 1e-6f))
      o.fail("need 0 <= inner_cone_deg < outer_cone_deg <= 90");
  }
  l.behaviour = behaviour_ref(o);
  o.finish();
  builder_.add_light(std::move(l));
}

void JsonLevelReader::read_paths(JsonObject& section) {
  for (const std::string& name : section.keys()) {
    JsonObject p = section.object(name);
    CameraPath path;
    path.name = name;
    path.loop = p.boolean("loop", false);
    const std::string keys_ptr = p.pointer("keys");
    const nlohmann::json& keys = expect_array(p.raw("keys"), keys_ptr, file_);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      JsonObject k(keys[i], fmt::format("{}/{}", keys_ptr, i), file_);
      PathKey key;
      key.time = k.number("time");
      key.position = k.vec3("position");
      if (k.has("target") && k.has("rotation"))
        k.fail("give either 'target' or 'rotation', not both");
      if (k.has("target")) {
        const glm::vec3 target = k.vec3("target");
        if (glm::length(target - key.position) < 1e-6f) k.fail("target", "equals the position");
        key.orientation = look_at_orientation(key.position, target);
      } else {
        key.orientation = k.quat("rotation", key.orientation);
      }
      if (k.has("yfov_deg")) key.yfov = glm::radians(k.number("yfov_deg"));
      k.finish();
      path.keys.push_back(key);
    }
    p.finish();
    if (std::string problem = path.problem(); !problem.empty()) p.fail(problem);
    level().paths.push_back(std::move(path));
  }
}

}  // namespace lantern
