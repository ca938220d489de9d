// Instance creation: layer/extension discovery, validation features, debug messenger.
#include "runtime/core/instance.h"

#include <fmt/format.h>

#include <cstring>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool has_layer(const char* name) {
  std::uint32_t count = 0;
  VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  for (const auto& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

bool has_extension(const char* layer, const char* name) {
  std::uint32_t count = 0;
  VK_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  VK_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()));
  for (const auto& extension : extensions)
    if (std::strcmp(extension.extensionName, name) == 0) return true;
  return false;
}

}  // namespace

Instance::Instance(ValidationRequest request, std::span<const char* const> extra) {
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  if (request.validation) {
    if (has_layer(kValidationLayer)) {
      layers.push_back(kValidationLayer);
      validation_enabled_ = true;
    } else {
      log::warn(
          "Vulkan validation was requested but {} is not installed (Debian package "
          "vulkan-validationlayers): validation unavailable, errors will not be caught",
          kValidationLayer);
    }
  }
  debug_utils_ =
      has_extension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) ||
      (validation_enabled_ && has_extension(kValidationLayer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME));
  if (debug_utils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (validation_enabled_ && !debug_utils_) {
    log::warn("VK_EXT_debug_utils is unavailable: validation messages cannot be counted");
    validation_enabled_ = false;
  }
  // The portability extension lets the loader list non-conformant (e.g. MoltenVK) devices too.
  const bool portability = has_extension(nullptr, VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
  if (portability) extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);

  for (const char* name : extra) {
    if (!has_extension(nullptr, name))
      throw RuntimeError(fmt::format("Vulkan instance extension {} is not available", name));
    extensions.push_back(name);
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "lantern";
  app.pEngineName = "lantern";
  app.apiVersion = VK_API_VERSION_1_3;  // the highest we use; devices may still be 1.2

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  if (portability) info.flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;

  // Chained messenger info: also catches messages from vkCreateInstance/vkDestroyInstance.
  VkDebugUtilsMessengerCreateInfoEXT messenger_info = messenger_create_info(counters_.get());
  const VkValidationFeatureEnableEXT sync_feature =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  if (validation_enabled_) {
    info.pNext = &messenger_info;
    if (request.synchronization) {
      features.enabledValidationFeatureCount = 1;
      features.pEnabledValidationFeatures = &sync_feature;
      messenger_info.pNext = &features;
      sync_validation_enabled_ = true;
    }
  }
  VK_CHECK(vkCreateInstance(&info, nullptr, &instance_));

  if (validation_enabled_) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    messenger_info.pNext = nullptr;
    VK_CHECK(create(instance_, &messenger_info, nullptr, &messenger_));
  }
}

Instance::~Instance() {
  if (messenger_ != VK_NULL_HANDLE) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

}  // namespace lantern::runtime
