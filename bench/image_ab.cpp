// image_ab: the A/B image verdict (src/eval/ab.h, the one the workbench gives after an edit) of two sets of
// EXR renders, for comparing two binaries: image_ab OLD_0.exr NEW_0.exr [OLD_1.exr NEW_1.exr ...], pair k
// rendered by both with the same seed. Prints one JSON line: verdict, RMSE, relative MSE, largest
// differences, the fraction of pixels changed, and whether the mean moved beyond its noise. Exit status 2 on
// bad input.
#include <cstdio>
#include <exception>
#include <vector>

#include "eval/ab.h"
#include "eval/image.h"

int main(int argc, char** argv) {
  if (argc < 3 || (argc - 1) % 2 != 0) {
    std::fprintf(stderr, "usage: image_ab OLD_0.exr NEW_0.exr [OLD_1.exr NEW_1.exr ...]\n");
    return 2;
  }
  try {
    std::vector<wb::eval::ImageRGBA> oldRuns, newRuns;
    for (int i = 1; i + 1 < argc; i += 2) {
      oldRuns.push_back(wb::eval::readExr(argv[i]));
      newRuns.push_back(wb::eval::readExr(argv[i + 1]));
    }
    const auto c = wb::eval::compareImages(oldRuns, newRuns);
    std::printf(
        "{\"verdict\": \"%s\", \"runs\": %zu, \"rmse\": %.6g, \"rel_mse\": %.6g, \"max_abs_diff\": %.6g, "
        "\"max_rel_diff\": %.6g, \"changed_pixel_fraction\": %.6g, \"mean_shift_significant\": %s, "
        "\"mean_shift_p\": %.3g}\n",
        wb::eval::imageVerdictName(c.verdict), oldRuns.size(), c.rmse, c.relMse, c.maxAbsDiff, c.maxRelDiff,
        c.changedPixelFraction, c.meanShiftSignificant ? "true" : "false", c.meanShiftPValue);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "image_ab: %s\n", e.what());
    return 2;
  }
  return 0;
}
