// Internal: the reader behind read_json_level, split over json_level.cpp (document, assets,
// camera, environment, settings) and json_level_entities.cpp (materials, behaviours, primitives,
// lights, paths). Generators receive it to share named materials and behaviours.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "engine/level/json_object.h"
#include "engine/level/level_builder.h"

namespace lantern {

class JsonLevelReader {
 public:
  JsonLevelReader(const std::filesystem::path& file, Level& level, LoadDiagnostics& diagnostics)
      : file_(file), builder_(level, diagnostics) {}

  void read(const nlohmann::json& document);

  // Section readers (json_level_entities.cpp).
  void read_materials(JsonObject& section);
  void read_behaviours(JsonObject& section);
  void read_primitive(JsonObject& object);
  void read_light(JsonObject& object);
  void read_paths(JsonObject& section);
  void read_volume(JsonObject& object);  // json_level_volumes.cpp

  // Shared pieces.
  Transform read_transform(JsonObject& object);
  Material read_material(JsonObject& object);
  std::uint32_t material_ref(JsonObject& owner, std::string_view key);  // name or inline object
  std::optional<Behaviour> behaviour_ref(JsonObject& owner);  // "behaviour": name or object
  std::filesystem::path existing_file(JsonObject& owner,
                                      std::string_view key);  // relative to the level

  const std::filesystem::path& file() const { return file_; }
  LevelBuilder& builder() { return builder_; }
  Level& level() { return builder_.level(); }

 private:
  void read_assets(const nlohmann::json& section, const std::string& pointer);
  void read_camera(JsonObject& object);
  void read_environment(JsonObject& object);
  void read_settings(const nlohmann::json& value, const std::string& prefix,
                     const std::string& pointer);
  void read_generators(const nlohmann::json& section, const std::string& pointer);
  Behaviour read_behaviour(JsonObject& object);
  void check_follow_paths();

  const std::filesystem::path& file_;
  LevelBuilder builder_;
  std::map<std::string, std::uint32_t, std::less<>> materials_;
  std::map<std::string, Behaviour, std::less<>> behaviours_;
  std::optional<Camera> asset_camera_;
  std::string camera_pointer_;
};

}  // namespace lantern
