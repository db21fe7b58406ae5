// A volume's lines as SVG, for illustrators' drawing programs (Burns11 §2.4.2.2's styles).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cutaway/core/atomic_file.hpp"
#include "cutaway/styles/volume_lines.hpp"

namespace cutaway {

namespace {

std::string rgb(glm::vec3 c) {
  const glm::ivec3 v = glm::ivec3(glm::round(glm::clamp(c, 0.0f, 1.0f) * 255.0f));
  char s[8];
  std::snprintf(s, sizeof s, "#%02x%02x%02x", v.r, v.g, v.b);
  return s;
}

// A halo ends where its line ends (butt caps): it breaks the lines that cross behind it, not
// the next run of its own curve.
void polyline(std::ostream& out, const DrawnVolumeLine& line, glm::vec3 color, float width,
              float opacity, const char* role, const char* cap) {
  out << "<polyline class='" << role << " " << volumeLineKindName(line.kind)
      << "' fill='none' stroke='" << rgb(color) << "' stroke-width='" << width
      << "' stroke-linecap='" << cap << "' stroke-linejoin='round'";
  if (opacity < 1.0f) out << " stroke-opacity='" << opacity << "'";
  out << " points='";
  // Hundredths of a pixel.
  const auto at = [](float v) { return std::round(v * 100.0f) / 100.0f; };
  for (std::size_t i = 0; i < line.points.size(); ++i)
    out << (i ? " " : "") << at(line.points[i].x) << "," << at(line.points[i].y);
  out << "'/>\n";
}

}  // namespace

std::string volumeLineSvg(const VolumeLineDrawing& drawing) {
  std::vector<const DrawnVolumeLine*> order;
  for (const DrawnVolumeLine& l : drawing.lines) order.push_back(&l);
  std::stable_sort(
      order.begin(), order.end(),
      [](const DrawnVolumeLine* a, const DrawnVolumeLine* b) { return a->depth > b->depth; });
  std::ostringstream out;
  out.precision(6);
  out << "<?xml version='1.0' encoding='UTF-8'?>\n"
      << "<svg xmlns='http://www.w3.org/2000/svg' width='" << drawing.width << "' height='"
      << drawing.height << "' viewBox='0 0 " << drawing.width << " " << drawing.height << "'>\n";
  for (const DrawnVolumeLine* l : order) {
    if (l->halo > 0.0f && !l->hidden)
      polyline(out, *l, l->haloColor, l->width + 2.0f * l->halo, 1.0f, "halo", "butt");
    polyline(out, *l, l->color, l->width, l->opacity, l->hidden ? "line hidden" : "line", "round");
  }
  out << "</svg>\n";
  return out.str();
}

void writeVolumeLineSvg(const std::string& path, const VolumeLineDrawing& drawing) {
  const std::string text = volumeLineSvg(drawing);
  writeFileAtomically(path, [&](std::ostream& os) { os << text; });
}

}  // namespace cutaway
