#include "eval/live_error.h"

#include <cmath>
#include <stdexcept>

#include "eval/metrics.h"

namespace wb::eval {
namespace {

bool isPowerOfTwo(uint32_t n) {
  return n != 0 && (n & (n - 1)) == 0;
}

std::string sizeText(uint32_t w, uint32_t h) {
  return std::to_string(w) + "x" + std::to_string(h);
}

}  // namespace

bool LiveError::loadReference(const std::string& path) {
  try {
    setReference(readExr(path), path);
    return true;
  } catch (const std::exception& e) {
    error_ = e.what();
    return false;
  }
}

void LiveError::setReference(ImageRGBA reference, std::string name) {
  reference_ = std::move(reference);
  referenceName_ = std::move(name);
  error_.clear();
  restart();
}

void LiveError::clearReference() {
  reference_.reset();
  referenceName_.clear();
  error_.clear();
  restart();
}

void LiveError::restart() {
  history_.clear();
  snapshot_ = ImageRGBA{};
  snapshotSamples_ = 0;
  lastSamples_ = 0;
  lastSeconds_ = -1e9;
}

bool LiveError::wants(uint32_t samples, double seconds) const {
  if (samples == 0 || samples == lastSamples_) return false;
  if (isPowerOfTwo(samples)) return true;
  return reference_ && seconds - lastSeconds_ >= referenceEverySeconds;
}

uint32_t LiveError::nextCheckpoint(uint32_t samples, double seconds) const {
  if (wants(samples + 1, seconds)) return samples + 1;
  uint32_t p = 1;
  while (p <= samples && p < (1u << 31)) p <<= 1;
  return p;
}

bool LiveError::fits(uint32_t width, uint32_t height) const {
  const ImageRGBA& ref = *reference_;
  if (ref.width == width && ref.height == height) return true;
  return width > 0 && height > 0 && ref.width % width == 0 && ref.height % height == 0 &&
         ref.width / width == ref.height / height;
}

bool LiveError::checkSize(uint32_t width, uint32_t height) {
  if (!reference_) return false;
  if (fits(width, height)) return true;
  const ImageRGBA& ref = *reference_;
  error_ = "reference " + sizeText(ref.width, ref.height) + " does not match the trace size " +
           sizeText(width, height) + " (nor an integer multiple of it): set the trace size with " +
           "--size WxH --scale 1, or render the reference at that size";
  return false;
}

std::optional<ImageRGBA> LiveError::referenceFor(const ImageRGBA& image) {
  if (!checkSize(image.width, image.height)) return std::nullopt;
  const ImageRGBA& ref = *reference_;
  if (ref.width == image.width && ref.height == image.height) return ref;
  return downsampleTo(ref, image.width, image.height);
}

void LiveError::add(const ImageRGBA& image, uint32_t samples, double seconds) {
  if (!history_.empty() && (image.width != snapshot_.width || image.height != snapshot_.height)) restart();
  if (samples < lastSamples_) restart();
  lastSamples_ = samples;
  lastSeconds_ = seconds;
  LiveErrorPoint p;
  p.samples = samples;
  p.seconds = seconds;
  bool have = false;
  if (reference_) {
    if (auto ref = referenceFor(image)) {
      error_.clear();
      p.rmse = rmse(image, *ref);
      p.relMse = relMse(image, *ref, 0.01);
      have = true;
    }
  } else if (snapshotSamples_ > 0 && snapshotSamples_ * 2 == samples && snapshot_.width == image.width &&
             snapshot_.height == image.height) {
    // Noise estimate from the half snapshot (see the header).
    p.rmse = rmse(image, snapshot_);
    p.relMse = relMse(snapshot_, image, 0.01);
    p.estimated = true;
    have = true;
  }
  if (isPowerOfTwo(samples)) {
    snapshot_ = image;
    snapshotSamples_ = samples;
  }
  if (have) history_.push_back(p);
}

std::optional<LiveErrorPoint> LiveError::latest() const {
  if (history_.empty()) return std::nullopt;
  return history_.back();
}

}  // namespace wb::eval
