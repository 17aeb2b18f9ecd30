#include "contact/unbuilt_models.h"

#include <functional>
#include <map>

namespace contactlab {
namespace {

std::map<std::string, std::string, std::less<>>& Unbuilt() {
  static std::map<std::string, std::string, std::less<>> unbuilt;
  return unbuilt;
}

}  // namespace

void RegisterUnbuiltContactModel(std::string name, std::string reason) { Unbuilt()[std::move(name)] = std::move(reason); }

std::optional<std::string> UnbuiltContactModelReason(std::string_view name) {
  const auto it = Unbuilt().find(name);
  if (it == Unbuilt().end()) return std::nullopt;
  return it->second;
}

}  // namespace contactlab
