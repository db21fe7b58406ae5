// Generic widgets for parameter tables: the widget follows the parameter's type.
#include <imgui.h>

#include <cmath>

#include "panels.hpp"

namespace cutaway::view {

std::optional<ParameterValue> parameterWidget(const Parameter& p, const Scene& scene) {
  using Type = OptionSpec::Type;
  const ParameterValue value = p.value(scene);
  std::optional<ParameterValue> changed;
  ImGui::PushID(p.key.c_str());
  switch (p.type) {
    case Type::Bool: {
      bool v = std::get<bool>(value);
      if (ImGui::Checkbox(p.label.c_str(), &v)) changed = v;
      break;
    }
    case Type::Int: {
      int v = int(std::get<double>(value));
      const int hi = int(p.sliderMax.value_or(p.max));
      if (p.powerOfTwo) {  // the slider moves the exponent: every stop is a valid size
        int e = int(std::log2(v));
        const std::string shown = std::to_string(1 << e);
        if (ImGui::SliderInt(p.label.c_str(), &e, int(std::ceil(std::log2(p.min))),
                             int(std::floor(std::log2(hi))), shown.c_str(), ImGuiSliderFlags_AlwaysClamp))
          changed = double(1 << e);
      } else if (ImGui::SliderInt(p.label.c_str(), &v, int(p.min), hi, "%d", ImGuiSliderFlags_AlwaysClamp))
        changed = double(v);
      break;
    }
    case Type::Float: {
      float v = float(std::get<double>(value));
      const bool unbounded = p.max > 1e6 && !p.sliderMax;
      bool moved = false;
      if (unbounded) {
        const float speed = std::max(std::abs(v), 1.0f) * 0.01f;
        moved = ImGui::DragFloat(p.label.c_str(), &v, speed, float(p.min), float(p.max), "%.3g",
                                 ImGuiSliderFlags_AlwaysClamp);
      } else {
        const float hi = float(p.sliderMax.value_or(p.max));
        moved = ImGui::SliderFloat(p.label.c_str(), &v, float(p.min), hi, "%.3g",
                                   ImGuiSliderFlags_AlwaysClamp);
      }
      if (moved) changed = double(v);
      break;
    }
    case Type::Choice: {
      const std::string current = std::get<std::string>(value);
      if (ImGui::BeginCombo(p.label.c_str(), current.c_str())) {
        for (const auto& choice : p.choices)
          if (ImGui::Selectable(choice.c_str(), choice == current) && choice != current)
            changed = choice;
        ImGui::EndCombo();
      }
      break;
    }
    case Type::Color: {
      glm::vec3 v = std::get<glm::vec3>(value);
      if (ImGui::ColorEdit3(p.label.c_str(), &v[0], ImGuiColorEditFlags_Float)) changed = v;
      break;
    }
    case Type::Direction: {
      glm::vec3 v = std::get<glm::vec3>(value);
      if (ImGui::SliderFloat3(p.label.c_str(), &v[0], -1.0f, 1.0f, "%.2f") &&
          glm::length(v) > 1e-3f)
        changed = glm::normalize(v);
      break;
    }
    case Type::Vec3: {
      glm::vec3 v = std::get<glm::vec3>(value);
      const float speed = std::max(glm::length(v), 1.0f) * 0.01f;
      if (ImGui::DragFloat3(p.label.c_str(), &v[0], speed, float(p.min), float(p.max), "%.3g"))
        changed = v;
      break;
    }
    case Type::Text:  // patterns and names come from the scene file
      ImGui::LabelText(p.label.c_str(), "%s", std::get<std::string>(value).c_str());
      break;
  }
  if (!p.doc.empty() && ImGui::IsItemHovered())
    ImGui::SetTooltip("%s\n(%s)", p.doc.c_str(), p.key.c_str());
  ImGui::PopID();
  return changed;
}

void parameterTable(const std::vector<Parameter>& table, ViewerState& state) {
  for (const auto& p : table) {
    const bool applies = p.appliesTo(state.scene);
    ImGui::BeginDisabled(!applies);
    if (const auto value = parameterWidget(p, state.scene)) setParameter(state, p, *value);
    ImGui::EndDisabled();
  }
}

}  // namespace cutaway::view
