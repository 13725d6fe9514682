// Embedded explicit Runge-Kutta pairs with a continuous extension (dense output), as plain data:
// the stepper (sim/ode/rk_stepper.h) knows nothing about a particular method and the methods
// know nothing about metronomes.
//
//   stages k_j = f(t0 + c_j h, y0 + h sum_{l<j} a_jl k_l),  j = 0 .. stages-1
//   y1       = y0 + h sum_j b_j k_j
//   error    = h sum_j e_j k_j                       (e = b - b-hat, the embedded pair)
//   y(t0 + th h) = y0 + h sum_j k_j sum_q p_jq th^(q+1),   j = 0 .. dense_stages-1
// With `fsal`, the last of `stages` is f(t1, y1): it is the next step's k_0 and costs nothing
// after a step that is kept. Stages `stages .. dense_stages-1` are evaluated only for a step
// whose interior is interpolated.
#pragma once

#include <string>
#include <vector>

namespace metrosync::ode {

struct RkTableau {
  std::string name;
  int order = 0;        // order of y1
  int error_order = 0;  // order of the embedded solution (step control exponent 1/(error_order+1))
  int stages = 0;       // per kept step, including the FSAL stage
  bool fsal = false;
  int dense_stages = 0;                // >= stages
  int dense_degree = 0;                // the interpolant is a polynomial of this degree in th
  double pi_beta = 0.0;                // PI step-size control: weight of the previous error
  std::vector<double> c;               // (dense_stages)
  std::vector<std::vector<double>> a;  // (dense_stages x dense_stages), lower triangular
  std::vector<double> b;               // (stages)
  std::vector<double> e;               // (stages)
  std::vector<std::vector<double>> p;  // (dense_stages x dense_degree)
};

// The methods, by the names simulation.integrator accepts (the slow flow uses dopri5):
//   dopri5    Dormand-Prince 5(4), 7 stages (FSAL), 4th-order interpolant without extra stages
//   verner65  Verner's "efficient" 6(5), 9 stages (FSAL), 6th-order interpolant (+3 stages)
//   verner76  Verner's "efficient" 7(6), 10 stages + FSAL, 7th-order interpolant (+5 stages)
// Throws std::invalid_argument for any other name.
const RkTableau& rkTableau(const std::string& name);

}  // namespace metrosync::ode

// The direct engine's names from before the toolkit was shared with the slow flow.
namespace metrosync::direct {
using ode::RkTableau;
using ode::rkTableau;
}  // namespace metrosync::direct
