#version 450 core
// The techniques' G-buffer channels (frame/gbuffer.cpp) as AOVs: sample 0, as aovs.frag's.
// Generated: the channels' samplers and outputs, and copyChannels().
#include "frame/samples.glsl"
#include "frame/channel_parts.glsl"
void main() {
  copyChannels(ivec2(gl_FragCoord.xy));
}
