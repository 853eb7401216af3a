// Where the workbench finds its own files (shaders/, assets/, shader_cache/) and ../shared.
#pragma once
#include <filesystem>

namespace wb {

// The project root: WB_ROOT from the environment when it is set, else the folder above the running binary
// (build/workbench -> .) that holds shaders/ and assets/, else the source folder the binary was configured
// from. A WB_ROOT without shaders/ and assets/ throws std::invalid_argument naming WB_ROOT.
std::filesystem::path projectRoot();
std::filesystem::path shaderDir();       // projectRoot()/shaders
std::filesystem::path assetDir();        // projectRoot()/assets
std::filesystem::path shaderCacheDir();  // WB_SHADER_CACHE_DIR, else projectRoot()/shader_cache
std::filesystem::path sharedDir();       // WB_SHARED_DIR, else projectRoot()/../shared (third-party assets)
std::filesystem::path defaultScenePath();

}  // namespace wb
