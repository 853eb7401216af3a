// The running error of a progressive render, for the live panel: against a loaded reference image when there
// is one, otherwise an estimate of the noise from the render itself.
//
// The estimate needs no second moments from the GPU: the running mean I_n after n samples and the snapshot
// I_{n/2} taken at n/2 samples differ by (J - I_{n/2}) / 2, where J is the mean of the second, independent
// half of the samples. Its variance is (s^2/(n/2) + s^2/(n/2)) / 4 = s^2 / n: exactly the variance of I_n. So
// mean((I_n - I_{n/2})^2) is an unbiased estimate of the noise part of I_n's MSE (bias is invisible to it;
// with Sobol samples, which are not independent, it is an indicator rather than an estimate).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "eval/image.h"

namespace wb::eval {

struct LiveErrorPoint {
  uint32_t samples = 0;
  double seconds = 0;  // since the accumulation restarted
  double rmse = 0;
  double relMse = 0;       // eps 0.01, the reference (or the current image, for the estimate) below
  bool estimated = false;  // true: the half-snapshot noise estimate (no reference)
};

class LiveError {
 public:
  // Loads an EXR reference; returns false and keeps the reason (error()) when it cannot be read.
  bool loadReference(const std::string& path);
  void setReference(ImageRGBA reference, std::string name);
  void clearReference();
  bool hasReference() const { return reference_.has_value(); }
  const std::string& referenceName() const { return referenceName_; }
  const std::string& error() const { return error_; }  // why the last reference or comparison failed

  // Whether the reference can score an image of this size (the same, or an integer multiple of it); when it
  // cannot, error() says why at once instead of at the next point.
  bool checkSize(uint32_t width, uint32_t height);

  // The accumulation restarted (drops the history and the snapshots).
  void restart();
  // Whether a readback at this sample count would add a point: at 1, 2, 4, 8, ... samples and, with a
  // reference, also every `referenceEverySeconds` of accumulation.
  bool wants(uint32_t samples, double seconds) const;
  // The sample count of the next point after `samples` (so a progressive renderer can stop there).
  uint32_t nextCheckpoint(uint32_t samples, double seconds) const;
  // Adds the point for the current accumulation (same size as the last ones; a size change restarts).
  void add(const ImageRGBA& image, uint32_t samples, double seconds);

  const std::vector<LiveErrorPoint>& history() const { return history_; }
  std::optional<LiveErrorPoint> latest() const;

  double referenceEverySeconds = 2.0;

 private:
  std::optional<ImageRGBA> referenceFor(const ImageRGBA& image);
  bool fits(uint32_t width, uint32_t height) const;

  std::optional<ImageRGBA> reference_;
  std::string referenceName_;
  std::string error_;
  std::vector<LiveErrorPoint> history_;
  ImageRGBA snapshot_;  // the accumulation at the last power-of-two sample count
  uint32_t snapshotSamples_ = 0;
  uint32_t lastSamples_ = 0;
  double lastSeconds_ = -1e9;
};

}  // namespace wb::eval
