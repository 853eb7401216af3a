#version 460
#extension GL_EXT_ray_tracing : require
// The split's shadow launch skips closest-hit (shadow_split.rgen); its hit group still names this empty stage:
// lavapipe (Mesa 25.0) runs a pipeline whose only hit group has no stage at all wrong (some invocations of the
// launch never run).
void main() {}
