// The seed's Table 1: the four laboratory shear creep tests of a weak
// structural plane (normal and shear stress) with their fitted Burgers
// parameters. Reference data for the verification tests, benchmarks and
// examples, kept in one place. Units as in the seed: stresses in MPa, E1 and E2
// per unit joint area in MPa/mm, eta1 and eta2 in MPa*h/mm.
#pragma once

#include <array>

namespace rheodda::laws {

struct SeedTable1Row {
  double sigma, tau;  ///< normal and shear stress of the test [MPa]
  double E1, E2;      ///< Burgers stiffnesses [MPa/mm]
  double eta1, eta2;  ///< Burgers viscosities [MPa*h/mm]
};

inline constexpr std::array<SeedTable1Row, 4> kSeedTable1{{
    {1.408, 0.232, 26.87, 192.43, 34807.72, 2141.23},
    {1.156, 0.424, 40.13, 249.33, 101760.29, 3236.41},
    {0.942, 0.439, 29.45, 260.76, 52869.39, 3771.63},
    {0.751, 0.512, 33.65, 305.53, 23051.02, 5736.91},
}};

}  // namespace rheodda::laws
