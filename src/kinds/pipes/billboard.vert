#version 450 core
// Konev18 §5: the node buffer; the geometry shader builds the quads.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in float aArc;
layout(location = 2) in int aPipe;
out vec3 gPosition;
out float gArc;
flat out int gPipe;
void main() {
  gPosition = aPosition;
  gArc = aArc;
  gPipe = aPipe;
}
