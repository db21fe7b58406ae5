#version 450 core
// The boxes only count the samples that pass the depth test (occlusion_culling.cpp).
void main() {}
