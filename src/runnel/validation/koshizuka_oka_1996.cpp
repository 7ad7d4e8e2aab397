// SPDX-License-Identifier: MIT
// Dam-break surge front, experiment of Koshizuka & Oka (1996), Nuclear Science and Engineering 123,
// 421–434, as transcribed for DualSPHysics' dam-break validation. The same values as
// data/reference/dambreak_koshizuka_oka_1996.csv (a test keeps the two equal); compiled in so the
// binary validates from any directory.
#include "runnel/validation/validation.hpp"

namespace runnel {

const std::vector<FrontSample>& koshizuka_oka_1996() {
  static const std::vector<FrontSample> data = {
      {0.28825, 1.128}, {0.59729, 1.244}, {0.83421, 1.464}, {1.00899, 1.695}, {1.15279, 1.903},
      {1.29653, 2.123}, {1.39877, 2.365}, {1.55289, 2.584}, {1.63448, 2.804}, {1.76846, 3.034},
      {1.86052, 3.219}, {1.99386, 3.462}, {2.09617, 3.704}, {2.19918, 3.900}, {2.35324, 4.132},
  };
  return data;
}

}  // namespace runnel
