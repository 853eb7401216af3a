// Where the workbench finds its own files (shaders/, assets/, shader_cache/) and ../shared.
#pragma once
#include <filesystem>

namespace wb {

// The project root: the folder above the running binary (build/workbench -> .) when it holds shaders/,
// else WB_ROOT from the environment, else the source folder the binary was configured from.
std::filesystem::path projectRoot();
std::filesystem::path shaderDir();       // projectRoot()/shaders
std::filesystem::path assetDir();        // projectRoot()/assets
std::filesystem::path shaderCacheDir();  // WB_SHADER_CACHE_DIR, else projectRoot()/shader_cache
std::filesystem::path sharedDir();       // WB_SHARED_DIR, else projectRoot()/../shared (third-party assets)
std::filesystem::path defaultScenePath();

}  // namespace wb
