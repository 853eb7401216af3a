// Helpers for the shader tests: temporary directories and file writing.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace wb::shader::test {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("wb_shader_test_" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(path);
    path = fs::canonical(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::permissions(path, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path, ec);
  }
  fs::path operator/(const std::string& s) const { return path / s; }
};

inline void writeFile(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

inline std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline fs::path dataDir() {
  return fs::path(WB_SOURCE_DIR) / "tests/shader/data";
}

// A tiny compute shader that includes "inc.glsl" (which defines VALUE).
inline const char* kComputeMain = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "inc.glsl"
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) buffer Out { uint v[]; } outBuf;
void main() { outBuf.v[0] = VALUE; }
)";

}  // namespace wb::shader::test
