// Level summary: counting and formatting for `lantern info`.
#include "engine/scene/level_summary.h"

#include <fmt/format.h>

#include <algorithm>

namespace lantern {

LevelSummary summarize(const Level& level) {
  LevelSummary s;
  s.name = level.name;
  s.source = level.source.string();
  s.instances = level.instances.size();
  s.meshes = level.meshes.size();
  for (const Instance& inst : level.instances) {
    const std::uint64_t tris = level.meshes[inst.mesh].triangle_count();
    s.triangles += tris;
    if (level.materials[inst.material].emissive()) s.emissive_triangles += tris;
    if (inst.behaviour) ++s.behaviours;
  }
  for (const Light& l : level.lights) {
    if (l.type == LightType::Point) ++s.point_lights;
    if (l.type == LightType::Spot) ++s.spot_lights;
    if (l.type == LightType::Directional) ++s.directional_lights;
    if (l.behaviour) ++s.behaviours;
  }
  s.volumes = level.volumes.size();
  for (const Volume& v : level.volumes)
    if (v.behaviour) ++s.behaviours;
  s.entities = s.instances + level.lights.size() + level.volumes.size() + 1;
  s.environment_map = level.environment.has_value();
  s.camera_path = level.camera_path;
  for (const CameraPath& p : level.paths)
    s.paths.push_back({p.name, p.duration(), p.keys.size(), p.loop});
  return s;
}

nlohmann::json to_json(const LevelSummary& s) {
  nlohmann::json paths = nlohmann::json::array();
  for (const auto& p : s.paths)
    paths.push_back(
        {{"name", p.name}, {"duration", p.duration}, {"keys", p.keys}, {"loop", p.loop}});
  nlohmann::json j = {
      {"level", s.name},
      {"source", s.source},
      {"entities", s.entities},
      {"instances", s.instances},
      {"meshes", s.meshes},
      {"triangles", s.triangles},
      {"emissive_triangles", s.emissive_triangles},
      {"lights",
       {{"point", s.point_lights},
        {"spot", s.spot_lights},
        {"directional", s.directional_lights},
        {"total", s.point_lights + s.spot_lights + s.directional_lights}}},
      {"volumes", s.volumes},
      {"behaviours", s.behaviours},
      {"environment_map", s.environment_map},
      {"camera_path", s.camera_path},
      {"paths", paths},
  };
  nlohmann::json enabled = nlohmann::json::object();
  for (const auto& [section, value] : s.enabled) enabled[section] = value;
  j["enabled"] = enabled;
  return j;
}

std::string to_text(const LevelSummary& s) {
  std::string out = fmt::format("level {} ({})\n", s.name, s.source);
  out += fmt::format("  entities            {}\n", s.entities);
  out += fmt::format("  instances           {}\n", s.instances);
  out += fmt::format("  meshes              {}\n", s.meshes);
  out += fmt::format("  triangles           {}\n", s.triangles);
  out += fmt::format("  emissive triangles  {}\n", s.emissive_triangles);
  out += fmt::format("  lights              {} point, {} spot, {} directional\n", s.point_lights,
                     s.spot_lights, s.directional_lights);
  out += fmt::format("  volumes             {}\n", s.volumes);
  out += fmt::format("  behaviours          {}\n", s.behaviours);
  out += fmt::format("  environment map     {}\n", s.environment_map ? "yes" : "no");
  out += fmt::format("  camera              {}\n",
                     s.camera_path.empty() ? "static" : "follows path '" + s.camera_path + "'");
  out += fmt::format("  paths               {}\n", s.paths.size());
  for (const auto& p : s.paths)
    out += fmt::format("    {:<18}{:.2f} s, {} keys{}\n", p.name, p.duration, p.keys,
                       p.loop ? ", loops" : "");
  if (!s.enabled.empty()) out += "enabled for this level\n";
  auto text = [](const nlohmann::json& v) {
    return v.is_string() ? v.get<std::string>() : v.dump();
  };
  for (const auto& [section, value] : s.enabled) {
    out += fmt::format("  {}\n", section);
    if (value.is_object()) {
      // Values in one column per section, a space after the longest key at least.
      std::size_t width = 16;
      for (const auto& [key, field] : value.items()) width = std::max(width, key.size() + 1);
      for (const auto& [key, field] : value.items()) {
        if (field.is_array() && !field.empty() && field.front().is_object()) {  // one per line
          out += fmt::format("    {}\n", key);
          for (const auto& item : field) out += fmt::format("      {}\n", text(item));
        } else {
          out += fmt::format("    {:<{}}{}\n", key, width, text(field));
        }
      }
    } else if (value.is_array()) {
      for (const auto& item : value) out += fmt::format("    {}\n", text(item));
    } else {
      out += fmt::format("    {}\n", text(value));
    }
  }
  return out;
}

}  // namespace lantern
