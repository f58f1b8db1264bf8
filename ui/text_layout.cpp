// Text that fits the space it is given: shortened with "..." and shown whole in a tooltip.
#include <string>

#include "ui/panels.h"

namespace kdswap {

std::string fitText(const std::string& text, float width) {
  if (ImGui::CalcTextSize(text.c_str()).x <= width) return text;
  const char* dots = "...";
  const float dotsWidth = ImGui::CalcTextSize(dots).x;
  // Drop whole UTF-8 characters from the end until the rest and the dots fit.
  std::size_t keep = text.size();
  while (keep > 0) {
    do --keep;
    while (keep > 0 && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80);
    if (ImGui::CalcTextSize(text.data(), text.data() + keep).x + dotsWidth <= width) break;
  }
  return text.substr(0, keep) + dots;
}

void textFitted(const std::string& text, bool disabled) {
  const std::string shown = fitText(text, ImGui::GetContentRegionAvail().x);
  if (disabled) ImGui::TextDisabled("%s", shown.c_str());
  else ImGui::TextUnformatted(shown.c_str());
  if (shown != text && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text.c_str());
}

void sameLineIfFits(float width) {
  ImGui::SameLine();
  if (ImGui::GetContentRegionAvail().x < width) ImGui::NewLine();
}

float buttonWidth(const char* label) {
  return ImGui::CalcTextSize(label, nullptr, true).x + 2 * ImGui::GetStyle().FramePadding.x;
}

float labelledWidth(float item, const char* label) {
  const float text = ImGui::CalcTextSize(label, nullptr, true).x;
  return text > 0 ? item + ImGui::GetStyle().ItemInnerSpacing.x + text : item;
}

}  // namespace kdswap
