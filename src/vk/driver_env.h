// Environment variables the workbench sets for the Vulkan drivers unless the user set them (an empty value
// counts as unset: a parent process hands its children the choice back that way). Drivers read them
// once, when they load, so this runs before the process's first instance (every Context calls it; the first
// call decides, later ones return what it did).
//
// - LP_NATIVE_VECTOR_WIDTH=128: llvmpipe (lavapipe) compiles shaders 4 lanes wide instead of its 8-lane AVX2
//   default. Measured on this project's 2-core VM (docs/bench/lavapipe_vector_width.md): the path tracer's
//   pipeline JITs in ~40% less time and edits reach the screen 25-35% sooner, while the trace rate and every
//   image stay the same (rays diverge too much for 8 lanes to pay); the window's raster work (panel, display
//   pass) takes ~20% longer. GPU drivers ignore it. Left alone when the user set a MESA_SHADER_CACHE_DIR of
//   their own (see below).
// - MESA_SHADER_CACHE_DIR=<cacheDir>/mesa/lp<width> (the user's width or ours): Mesa's shader disk
//   cache under the workbench's shader cache. One folder per width because llvmpipe's cache key leaves the
//   width out: code compiled 8 lanes wide, loaded by a process running 4 lanes wide, writes past the end of
//   the driver's vertex buffers (heap corruption in the window's hybrid mode with Mesa 25.0.7; a cache the
//   user shares with programs of Mesa's default width would do the same, hence the rule above).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace wb::vk {

// Applies the defaults above (cacheDir: the workbench's shader cache, e.g. shaderCacheDir()). Returns
// "NAME=value" for each variable it set.
std::vector<std::string> applyDriverDefaults(const std::filesystem::path& cacheDir);

}  // namespace wb::vk
