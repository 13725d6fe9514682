// What a friction law gives the slow flow (models/slow_flow.h): the platform's averaged response
// to a sinusoidal drive of amplitude A (contact/averaged_response.h), or why it has none. A law
// answers with one of three values (LawKind::slowResponse, in scaled units):
//   refused(why)     no averaged response derived: the slow flow refuses the law, saying `why`
//   constant(beta)   beta independent of the drive (viscous, none, fixed)
//   dryFriction(mu)  Coulomb's eq. d2 at s = A / mu with its regimes (stuck s <= 1, stick-slip,
//                    slip beyond s_b); at mu = 0 the free platform's constant (1/2, 0), its
//                    borders |Z| = mu and s_b mu still there (a continuation in mu reaches 0)
// The slow flow and the continuation ask the value (available, regimes, borders), never the law.
#pragma once

#include <string>

#include "contact/averaged_response.h"

namespace metrosync {

class SlowResponse {
 public:
  static SlowResponse refused(std::string why);
  static SlowResponse constant(AveragedResponse beta);
  static SlowResponse dryFriction(double mu);
  // A refused response of a dry law that keeps its borders at coefficient mu (the continuation
  // keeps the same borders on both sides of a parameter value where the response is refused).
  static SlowResponse refusedDry(double mu, std::string why);

  // The law has an averaged response (else the slow flow refuses it: why()).
  bool available() const { return why_.empty(); }
  const std::string& why() const { return why_; }
  // The response switches regime with the drive (Coulomb's stuck / stick-slip / slip, mu > 0).
  bool hasRegimes() const { return dry_ && mu_ > 0.0; }
  // The regimes' borders |Z| = mu and |Z| = s_b mu exist (a dry law, mu >= 0).
  bool hasBorders() const { return dry_; }
  // The drive |Z| at s = 1 (a dry law's mu; 0 otherwise).
  double mu() const { return mu_; }

  // The response at drive amplitude A >= 0; throws std::invalid_argument when !available().
  AveragedResponse at(double A) const;

 private:
  std::string why_;            // non-empty: refused
  bool dry_ = false;           // Coulomb's regimes and borders
  double mu_ = 0.0;            // dry_: the scaled coefficient
  AveragedResponse constant_;  // !dry_, or dry_ at mu = 0
};

}  // namespace metrosync
