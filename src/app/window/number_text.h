// Numbers as the window prints them: rates in the Stats panel, the heat legends' scales.
#pragma once
#include <string>

namespace wb::app {

// "12.3 M" style numbers: k, M and G with fixed decimals, whole numbers below a thousand.
std::string humanCount(double v);
// A legend's number: as humanCount from a thousand up ("20.6 k"), else at most 3 significant digits
// ("0.0123", "4.5").
std::string legendNumber(double v);

}  // namespace wb::app
