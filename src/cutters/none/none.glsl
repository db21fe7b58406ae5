// No cutter: every fragment is kept.
const int kKeep = 0, kDiscard = 1, kCutSurface = 2;
int cutFragment(bool frontFacing, out vec3 cutPosition, out vec3 cutNormal) {
  cutPosition = vec3(0.0);
  cutNormal = vec3(0.0);
  return kKeep;
}
