// Konev18 §6.1–6.2: the proxy geometry's tests, mirrored by proxyTriangle / proxyQuad in
// src/geometry/pipe_network.cpp. Pass 1 draws the cut surface, pass 2 marks the inside.
const int kProxyDiscard = 0, kProxyCutSurface = 1, kProxyMarkInside = 2;

// Eqs. 12–14 on an end triangle: d from (0.5, 0.5); the outer wall at d_out = 0.5, the inner
// at d_in = 0.5 r_in / r_out (the texture scale 0.5/r_out applies to both radii).
int proxyTriangle(int pass, vec2 uv, float innerR, float outerR) {
  float d = length(vec2(0.5) - uv);  // eq. 12
  float dIn = 0.5 * innerR / outerR, dOut = 0.5;
  if (pass == 1) return d > dIn && d < dOut ? kProxyCutSurface : kProxyDiscard;  // eq. 13
  return d < dIn ? kProxyMarkInside : kProxyDiscard;                              // eq. 14
}

// Eqs. 15–16 on a quad along the cut: v across the full diameter, so each wall takes
// t = (r_out − r_in) / (2 r_out) of it.
int proxyQuad(int pass, float v, float innerR, float outerR) {
  float t = 0.5 * (outerR - innerR) / outerR;
  if (pass == 1) return v > 1.0 - t || v < t ? kProxyCutSurface : kProxyDiscard;  // eq. 16
  return v > t && v < 1.0 - t ? kProxyMarkInside : kProxyDiscard;                // eq. 15
}
