// SPDX-License-Identifier: MIT
// Dam-break fronts beside the target reading (koshizuka_oka_1996.cpp), as printed in their
// dimensionless form, T = t·sqrt(2g/a) and Z = x/a (a the column's width), and transcribed for
// PySPH's dam-break example. The same values as data/reference/dambreak_other_readings.csv (a test
// keeps the two equal). runnel's t* is t·sqrt(g/a) = T/√2.
#include <cmath>

#include "runnel/validation/validation.hpp"

namespace runnel {
namespace {

struct Printed {
  double T, Z;
};

FrontReading reading(std::string name, std::string source, std::initializer_list<Printed> printed) {
  FrontReading r{std::move(name), std::move(source), {}};
  for (const Printed& p : printed) r.samples.push_back({p.T / std::sqrt(2.0), p.Z});
  return r;
}

}  // namespace

const std::vector<FrontReading>& dambreak_other_readings() {
  static const std::vector<FrontReading> readings = {
      reading("koshizuka_oka_pysph", "Koshizuka & Oka 1996, as read for PySPH's dam-break example",
              {{0.381, 1.111},
               {0.769, 1.252},
               {1.153, 1.505},
               {1.537, 1.892},
               {1.935, 2.241},
               {2.323, 2.615},
               {2.719, 3.003},
               {3.096, 3.624}}),
      reading("martin_moyce_a1.125", "Martin & Moyce 1952, Figure 3, n^2 = 2, a = 1.125 in",
              {{0.849, 1.245},
               {1.212, 1.443},
               {1.602, 1.884},
               {2.283, 2.689},
               {2.950, 3.728},
               {3.598, 4.528},
               {3.905, 4.999},
               {4.592, 5.841},
               {4.961, 6.271},
               {5.316, 6.717}}),
      reading("martin_moyce_a2.25", "Martin & Moyce 1952, Figure 3, n^2 = 2, a = 2.25 in",
              {{0.832, 1.217},
               {1.219, 1.474},
               {1.997, 2.292},
               {2.547, 2.995},
               {3.345, 4.134},
               {4.034, 4.944},
               {4.418, 5.881},
               {5.091, 6.980},
               {5.685, 7.945},
               {6.306, 8.966},
               {6.822, 9.986},
               {7.439, 10.963},
               {8.031, 11.977},
               {8.633, 13.005},
               {9.237, 13.970}}),
  };
  return readings;
}

}  // namespace runnel
