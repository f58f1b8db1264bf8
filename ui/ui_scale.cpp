#include "ui/ui_scale.h"

namespace kdswap {
namespace {
float gUiScale = 1.0f;  // written once before the UI thread draws, read only by it
}  // namespace

void setUiScale(float scale) { gUiScale = scale; }
float uiScale() { return gUiScale; }

}  // namespace kdswap
