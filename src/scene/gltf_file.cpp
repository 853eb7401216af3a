#include "scene/gltf_file.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#include "common/file_io.h"
#include "common/image_decode.h"

#include "scene/load_context.h"
#include "scene/scene.h"

namespace wb::scene {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;        // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;       // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;        // "BIN\0"
constexpr size_t kMaxFileSize = size_t{2} << 30;  // 2 GiB: glTF's own limit for GLB

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& reason) {
  throw SceneError(path.filename().string() + ": " + oneLine(reason));
}

uint32_t readU32(const std::vector<unsigned char>& data, size_t offset) {
  uint32_t value = 0;
  std::memcpy(&value, data.data() + offset, 4);
  return value;
}

std::vector<unsigned char> readWholeFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "file not found (" + path.string() + ")");
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory, not a glTF file");
  std::string why;
  const auto text = readRegularFile(path, &why, kMaxFileSize);  // never blocks on a named pipe
  if (!text) fail(path, "cannot read the file: " + why);
  if (text->empty()) fail(path, "file is empty");
  return std::vector<unsigned char>(text->begin(), text->end());
}

// tinygltf 2.7 trusts the GLB header more than it should; check every length against the file size first.
void validateGlbContainer(const std::filesystem::path& path, const std::vector<unsigned char>& data) {
  if (data.size() < 20) fail(path, "GLB file shorter than its 12-byte header plus a chunk header");
  const uint32_t version = readU32(data, 4);
  const uint32_t length = readU32(data, 8);
  if (version != 2) fail(path, "unsupported GLB container version " + std::to_string(version));
  if (length > data.size()) {
    fail(path,
         "GLB header length " + std::to_string(length) + " exceeds file size " + std::to_string(data.size()));
  }
  size_t offset = 12;
  int chunkIndex = 0;
  while (offset + 8 <= length) {
    const uint64_t chunkLength = readU32(data, offset);
    const uint32_t chunkType = readU32(data, offset + 4);
    if (chunkLength == 0) {
      fail(path, "zero-sized GLB chunk " + std::to_string(chunkIndex) +
                     (chunkType == kChunkBin    ? " (BIN)"
                      : chunkType == kChunkJson ? " (JSON)"
                                                : ""));
    }
    if (offset + 8 + chunkLength > length) {
      fail(path, "GLB chunk " + std::to_string(chunkIndex) + " (" + std::to_string(chunkLength) +
                     " bytes) runs past the end of the file");
    }
    if (chunkIndex == 0 && chunkType != kChunkJson) fail(path, "first GLB chunk is not JSON");
    if (chunkIndex == 1 && chunkType != kChunkBin) fail(path, "second GLB chunk is not BIN");
    offset += 8 + static_cast<size_t>(chunkLength);
    ++chunkIndex;
  }
  if (chunkIndex == 0) fail(path, "GLB file has no JSON chunk");
}

// Image callback for tinygltf: decode anything stb understands to RGBA8; leave the rest empty with a warning.
// `user` is the model being parsed: tinygltf 2.7 passes an image's bufferView to this callback without
// checking it against its buffer, so the callback checks the range before anything reads it.
bool decodeImageRgba8(tinygltf::Image* image, const int imageIndex, std::string* err, std::string* warn,
                      int /*reqWidth*/, int /*reqHeight*/, const unsigned char* bytes, int size, void* user) {
  if (image->bufferView >= 0 && user) {
    const auto* model = static_cast<const tinygltf::Model*>(user);
    const auto& views = model->bufferViews;
    const size_t viewIndex = static_cast<size_t>(image->bufferView);
    const bool viewOk = viewIndex < views.size() && views[viewIndex].buffer >= 0 &&
                        static_cast<size_t>(views[viewIndex].buffer) < model->buffers.size();
    const size_t available =
        viewOk ? model->buffers[static_cast<size_t>(views[viewIndex].buffer)].data.size() : 0;
    if (!viewOk || views[viewIndex].byteOffset > available ||
        views[viewIndex].byteLength > available - views[viewIndex].byteOffset) {
      if (err) {
        *err += "image " + std::to_string(imageIndex) + ": bufferView " + std::to_string(image->bufferView) +
                " runs past the end of its buffer (" + std::to_string(available) + " bytes)";
      }
      return false;
    }
  }
  image->width = image->height = 0;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.clear();
  // Bounded decoding (common/image_decode.h): dimensions checked before any pixel is decoded, and Radiance
  // HDR bytes never reach stb_image (which can loop forever on a truncated one).
  std::string reason = "no image data";
  if (bytes && size > 0) {
    try {
      Rgba8Image decoded = decodeRgba8(bytes, static_cast<size_t>(size));
      image->width = int(decoded.width);
      image->height = int(decoded.height);
      image->image = std::move(decoded.rgba);
      return true;
    } catch (const ImageDecodeError& e) {
      reason = e.what();
    }
  }
  if (warn) {
    *warn += "image " + std::to_string(imageIndex) + " ('" + image->name + image->uri + "', " +
             (image->mimeType.empty() ? std::string("unknown type") : image->mimeType) +
             ") could not be decoded: " + reason + "\n";
  }
  return true;
}

// File reads for tinygltf (external .bin buffers and image files): regular files only, never blocking on a
// named pipe, at most 2 GiB.
bool readReferencedFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::string why;
  const auto data = readRegularFile(path, &why, kMaxFileSize);
  if (!data) {
    if (err) *err += "cannot read '" + path + "': " + why + "\n";
    return false;
  }
  out->assign(data->begin(), data->end());
  return true;
}

}  // namespace

tinygltf::Model parseGltfFile(const std::filesystem::path& path, std::vector<std::string>& warnings) {
  const std::vector<unsigned char> data = readWholeFile(path);
  const bool isGlb = data.size() >= 4 && readU32(data, 0) == kGlbMagic;
  if (isGlb) validateGlbContainer(path, data);
  if (data.size() > static_cast<size_t>(std::numeric_limits<unsigned int>::max()))
    fail(path, "file too large");

  tinygltf::TinyGLTF parser;
  tinygltf::Model model;
  parser.SetImageLoader(decodeImageRgba8, &model);
  parser.SetFsCallbacks({&tinygltf::FileExists, &tinygltf::ExpandFilePath, &readReferencedFile,
                         &tinygltf::WriteWholeFile, nullptr});
  std::string err, warn;
  const std::filesystem::path parent = path.parent_path();
  const std::string baseDir = parent.empty() ? std::string(".") : parent.string();
  bool ok = false;
  try {
    if (isGlb) {
      ok = parser.LoadBinaryFromMemory(&model, &err, &warn, data.data(),
                                       static_cast<unsigned int>(data.size()), baseDir);
    } else {
      if (data[0] != '{' && data[0] != ' ' && data[0] != '\n' && data[0] != '\r' && data[0] != '\t' &&
          data[0] != 0xEF) {
        fail(path, "not a glTF file (neither JSON nor GLB)");
      }
      ok = parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data.data()),
                                      static_cast<unsigned int>(data.size()), baseDir);
    }
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {  // e.g. bad_alloc for absurd sizes inside tinygltf
    fail(path, std::string("tinygltf failed: ") + e.what());
  }
  if (!ok) fail(path, err.empty() ? std::string("tinygltf could not parse the file") : err);
  std::string line;
  for (char c : warn) {
    if (c == '\n') {
      if (!line.empty()) warnings.push_back(line);
      line.clear();
    } else if (c != '\r') {
      line += c;
    }
  }
  if (!line.empty()) warnings.push_back(line);
  return model;
}

}  // namespace wb::scene
