// The sampler types of the frame's per-sample targets (TargetDesc::samples ≥ 1): multisample
// textures from 2 samples up, plain 2-D textures at 1 (SINGLE_SAMPLE, set by
// frame/samples.hpp). texelFetch's third argument is then the level: sample 0 is level 0;
// sizeMS(s) is textureSize's answer for either.
#ifdef SINGLE_SAMPLE
#define SAMPLER_MS sampler2D
#define ISAMPLER_MS isampler2D
#define USAMPLER_MS usampler2D
#define sizeMS(s) textureSize(s, 0)
#else
#define SAMPLER_MS sampler2DMS
#define ISAMPLER_MS isampler2DMS
#define USAMPLER_MS usampler2DMS
#define sizeMS(s) textureSize(s)
#endif
